//! The `floe` command's entry point, shared by every binary that runs it.

use crate::cli::LogFormat;
use clap::Parser;
use std::io::IsTerminal;

/// `floe`'s whole life: parses the command line, sets up logging and carries the
/// command out; a binary that adds modules registers them, then calls this
/// (`tests/examples/floe_traced.rs`).
pub fn main() -> std::process::ExitCode {
    quiet_mesa_device_select();
    quiet_closed_pipe();
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

/// Output into a pipe whose reader has gone (`floe presets | head -1`) ends the
/// command quietly with status 0, as Unix tools end (ripgrep's status, so a
/// `set -o pipefail` script does not fail on it), rather than with a panic and its
/// backtrace: Rust ignores SIGPIPE, so `println!` panics on the write that fails.
/// The hook turns exactly that panic into the exit; every other panic is reported
/// as before.
fn quiet_closed_pipe() {
    let report = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let payload = info.payload();
        let message = payload.downcast_ref::<String>().map(String::as_str).or(payload.downcast_ref::<&str>().copied());
        if message.is_some_and(closed_pipe) {
            std::process::exit(0);
        }
        report(info)
    }));
}

/// Whether a panic's message is the standard library's for printing into a
/// closed pipe ("failed printing to stdout: Broken pipe (os error 32)").
fn closed_pipe(message: &str) -> bool {
    (message.starts_with("failed printing to stdout") || message.starts_with("failed printing to stderr"))
        && message.contains("Broken pipe")
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

#[cfg(test)]
mod tests {
    #[test]
    fn only_printing_into_a_closed_pipe_is_quiet() {
        assert!(super::closed_pipe("failed printing to stdout: Broken pipe (os error 32)"));
        assert!(super::closed_pipe("failed printing to stderr: Broken pipe (os error 32)"));
        assert!(!super::closed_pipe("failed printing to stdout: No space left on device (os error 28)"));
        assert!(!super::closed_pipe("index out of bounds: Broken pipe"));
    }
}
