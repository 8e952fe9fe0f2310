//! `floectl`: drive a Floe server from the command line ([`floe_client::cli`]).

use clap::Parser;
use floe_client::cli::{Cli, error_chain, execute};

#[tokio::main(flavor = "current_thread")]
async fn main() -> std::process::ExitCode {
    match execute(Cli::parse()).await {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", error_chain(&e));
            std::process::ExitCode::FAILURE
        }
    }
}
