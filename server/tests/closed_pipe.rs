//! `floe` printing into a pipe whose reader has gone (`floe schema | head -1`) ends
//! quietly with status 0, as Unix tools do: no panic, no backtrace.

use std::process::{Command, Stdio};

#[test]
fn printing_commands_end_quietly_when_the_reader_has_gone() {
    for args in [&["schema"][..], &["presets"], &["plan", "dam_break"]] {
        // The read end closed before the command starts: its first write fails.
        let (reader, writer) = std::io::pipe().expect("a pipe");
        drop(reader);
        let out = Command::new(env!("CARGO_BIN_EXE_floe"))
            .args(args)
            .env("RUST_BACKTRACE", "1")
            .stdin(Stdio::null())
            .stdout(writer)
            .stderr(Stdio::piped())
            .output()
            .expect("floe runs");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "floe {args:?}: {:?}\n{stderr}", out.status);
        assert!(!stderr.contains("panicked") && !stderr.contains("Broken pipe"), "floe {args:?}:\n{stderr}");
    }
}
