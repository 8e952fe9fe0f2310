//! The `floe` command's entry point, shared by every binary that runs it.

use crate::cli::LogFormat;
use clap::Parser;
use std::io::IsTerminal;

/// `floe`'s whole life: parses the command line, sets up logging and carries the
/// command out; a binary that adds modules registers them, then calls this
/// (`tests/examples/floe_traced.rs`).
pub fn main() -> std::process::ExitCode {
    quiet_mesa_device_select();
    let cli = crate::cli::Cli::parse();
    // Fuzzing creates and deletes scenes by the thousand: only warnings by default.
    let level = if matches!(cli.command, crate::cli::Command::Fuzz(_)) { "warn" } else { "info" };
    let logs = tracing_subscriber::fmt()
        .with_env_filter(tracing_subscriber::EnvFilter::try_from_env("FLOE_LOG").unwrap_or_else(|_| level.into()))
        .with_writer(std::io::stderr);
    match cli.log_format {
        // Colour on a terminal only: a log file or journal gets plain text.
        LogFormat::Text => logs.with_ansi(std::io::stderr().is_terminal()).init(),
        // One object per line, the event's fields at the top level, for log collectors.
        LogFormat::Json => logs.json().flatten_event(true).with_current_span(false).init(),
    }
    match crate::execute(cli) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::FAILURE
        }
    }
}

/// Mesa's Vulkan device-select layer connects to a Wayland display to rank the
/// GPUs and prints "error: XDG_RUNTIME_DIR is invalid" on a server without one.
/// Floe ranks adapters itself (`floe_gpu::context`), so the layer is switched off
/// unless the user set `NODEVICE_SELECT` one way or the other.
#[allow(unsafe_code)]
fn quiet_mesa_device_select() {
    if std::env::var_os("NODEVICE_SELECT").is_none() {
        // SAFETY: the first thing `main` does, before any other thread exists, so
        // nothing reads the environment while it changes.
        unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    }
}
