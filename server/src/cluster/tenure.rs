//! How long this process may go on stepping its scenes without hearing from the
//! database: a worker that was stopped (SIGSTOP, a frozen VM) or cut off past its
//! lease may have lost its scenes to others, so its scene threads stop stepping
//! when the tenure runs out, before anything tells them, and resume only once a
//! heartbeat says the worker still holds them.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// A deadline on a monotonic clock, moved on by each heartbeat.
#[derive(Debug)]
pub struct Tenure {
    origin: Instant,
    /// Milliseconds after `origin` until which this process holds its scenes.
    until_ms: AtomicU64,
}

impl Tenure {
    /// A tenure that never ends: a single server holds its scenes alone.
    pub fn forever() -> Self {
        Self { origin: Instant::now(), until_ms: AtomicU64::new(u64::MAX) }
    }

    /// A tenure that has ended (until the first heartbeat).
    pub fn ended() -> Self {
        Self { origin: Instant::now(), until_ms: AtomicU64::new(0) }
    }

    /// Whether the scenes may be stepped and written now.
    pub fn holds(&self) -> bool {
        (self.origin.elapsed().as_millis() as u64) < self.until_ms.load(Ordering::Acquire)
    }

    /// Holds until `sent + span`, where `sent` is when the heartbeat that allows it
    /// was sent (not answered: the others' clocks started no later than that).
    pub fn extend(&self, sent: Instant, span: Duration) {
        let until = (sent.saturating_duration_since(self.origin) + span).as_millis() as u64;
        self.until_ms.store(until, Ordering::Release);
    }

    /// Ends it now (the worker learnt that it lost its scenes).
    pub fn end(&self) {
        self.until_ms.store(0, Ordering::Release);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tenure_ends_after_its_span() {
        assert!(Tenure::forever().holds());
        let t = Tenure::ended();
        assert!(!t.holds());
        t.extend(Instant::now(), Duration::from_millis(60));
        assert!(t.holds());
        std::thread::sleep(Duration::from_millis(80));
        assert!(!t.holds(), "a tenure not extended ends");
        t.extend(Instant::now(), Duration::from_secs(5));
        t.end();
        assert!(!t.holds());
    }
}
