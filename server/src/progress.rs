//! Progress display for long runs: a redrawn bar on a terminal, a plain line
//! every 10 % otherwise (logs and CI).

use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

/// Reports progress towards a simulated end time.
#[derive(Debug)]
pub struct Progress {
    end: f64,
    start: Instant,
    last_draw: Instant,
    tty: bool,
    quiet: bool,
    next_decile: u32,
}

impl Progress {
    /// Progress towards `end` simulated seconds.
    pub fn new(end: f64, quiet: bool) -> Self {
        let now = Instant::now();
        Self { end, start: now, last_draw: now, tty: std::io::stderr().is_terminal(), quiet, next_decile: 1 }
    }

    /// Updates the display (cheap when nothing is due).
    pub fn update(&mut self, t: f64, steps: u64, dt: f32, particles: usize) {
        if self.quiet {
            return;
        }
        let frac = (t / self.end).clamp(0.0, 1.0);
        let now = Instant::now();
        let due_tty = self.tty && now - self.last_draw > Duration::from_millis(100);
        let due_line = !self.tty && frac * 10.0 >= self.next_decile as f64;
        if !(due_tty || due_line) {
            return;
        }
        self.last_draw = now;
        let wall = (now - self.start).as_secs_f64();
        let rate = particles as f64 * steps as f64 / wall.max(1e-9);
        let eta = if frac > 0.0 { wall * (1.0 - frac) / frac } else { 0.0 };
        let text = format!(
            "t = {t:.4}/{:.4} s  step {steps}  dt {dt:.2e} s  {:.2} M particle-steps/s  wall {wall:.1} s  eta {eta:.0} s",
            self.end,
            rate / 1e6
        );
        let mut err = std::io::stderr().lock();
        if self.tty {
            let filled = (frac * 30.0) as usize;
            let _ = write!(
                err,
                "\r[{}{}] {:>3.0}%  {text}\x1b[K",
                "#".repeat(filled),
                " ".repeat(30 - filled),
                frac * 100.0
            );
            let _ = err.flush();
        } else {
            self.next_decile = (frac * 10.0) as u32 + 1;
            let _ = writeln!(err, "{:>3.0}%  {text}", frac * 100.0);
        }
    }

    /// Ends the bar's line on a terminal.
    pub fn finish(&self) {
        if self.tty && !self.quiet {
            eprintln!();
        }
    }
}
