//! `floe`: parse the command line, set up logging, hand over to [`floe_server::execute`]
//! (all in [`floe_server::entry::main`]).

fn main() -> std::process::ExitCode {
    floe_server::entry::main()
}
