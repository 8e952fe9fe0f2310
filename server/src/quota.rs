//! Per-user quotas: server-wide defaults (`floe serve --quota NAME=VALUE`) with
//! per-user overrides (`floe admin quota set`). A request over a quota is refused
//! with RESOURCE_EXHAUSTED / 429 naming the quota and its value, before anything is
//! allocated. The request rate is a GCRA limiter per user (the governor crate); the
//! other quotas are counted from the scenes and streams the user has.

use crate::metrics::Metrics;
use crate::service::ServiceError;
use governor::{DefaultDirectRateLimiter, Quota as Rate, RateLimiter};
use std::collections::HashMap;
use std::num::NonZeroU32;
use std::sync::{Arc, Mutex};

/// A quota.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Limit {
    /// Fluid particles in one scene.
    ParticlesPerScene,
    /// Scenes running continuously at once.
    RunningScenes,
    /// Fluid particles in all running scenes together.
    RunningParticles,
    /// Frame and event streams (WebSockets included) open at once.
    OpenStreams,
    /// Calls per second (a burst of one second's worth is allowed).
    RequestsPerSecond,
}

impl Limit {
    /// Every quota.
    pub const ALL: [Limit; 5] = [
        Limit::ParticlesPerScene,
        Limit::RunningScenes,
        Limit::RunningParticles,
        Limit::OpenStreams,
        Limit::RequestsPerSecond,
    ];

    /// The name used on the command line, in the database and in messages.
    pub fn name(self) -> &'static str {
        match self {
            Limit::ParticlesPerScene => "particles_per_scene",
            Limit::RunningScenes => "running_scenes",
            Limit::RunningParticles => "running_particles",
            Limit::OpenStreams => "open_streams",
            Limit::RequestsPerSecond => "requests_per_second",
        }
    }

    /// The quota of this name.
    pub fn from_name(name: &str) -> Option<Limit> {
        Limit::ALL.into_iter().find(|l| l.name() == name)
    }

    /// The server-wide default.
    pub fn default_value(self) -> u64 {
        match self {
            Limit::ParticlesPerScene => crate::service::DEFAULT_MAX_PARTICLES,
            Limit::RunningScenes => 8,
            Limit::RunningParticles => 16_000_000,
            Limit::OpenStreams => 64,
            Limit::RequestsPerSecond => 200,
        }
    }

    fn index(self) -> usize {
        Limit::ALL.iter().position(|&l| l == self).expect("listed")
    }
}

/// A value for every quota.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct QuotaSet([u64; 5]);

impl Default for QuotaSet {
    fn default() -> Self {
        Self(Limit::ALL.map(Limit::default_value))
    }
}

impl QuotaSet {
    /// The value of `limit`.
    pub fn get(&self, limit: Limit) -> u64 {
        self.0[limit.index()]
    }

    /// Sets `limit`.
    pub fn set(&mut self, limit: Limit, value: u64) {
        self.0[limit.index()] = value;
    }

    /// Applies `name=value` (as given to `--quota`).
    pub fn assign(&mut self, text: &str) -> Result<(), String> {
        let (limit, value) = parse_assignment(text)?;
        self.set(limit, value);
        Ok(())
    }
}

/// The quota called `name`, or a message listing the quotas.
pub fn limit_named(name: &str) -> Result<Limit, String> {
    Limit::from_name(name).ok_or_else(|| {
        format!("unknown quota '{}'; quotas are {}", crate::echo::cap(name), Limit::ALL.map(Limit::name).join(", "))
    })
}

/// `value` if `limit` can take it.
pub fn check_value(limit: Limit, value: u64) -> Result<u64, String> {
    let max = match limit {
        Limit::RequestsPerSecond => u64::from(u32::MAX),
        _ => i64::MAX as u64,
    };
    if (1..=max).contains(&value) {
        Ok(value)
    } else {
        Err(format!("{}: must be between 1 and {max}, got {value}", limit.name()))
    }
}

/// Reads `name=value`, naming what is wrong.
pub fn parse_assignment(text: &str) -> Result<(Limit, u64), String> {
    let (name, value) = text.split_once('=').ok_or_else(|| {
        format!("'{}': expected NAME=VALUE ({})", crate::echo::cap(text), Limit::ALL.map(Limit::name).join(", "))
    })?;
    let limit = limit_named(name.trim())?;
    let value: u64 = value.trim().parse().map_err(|_| {
        format!("{}: must be a whole number >= 1, got '{}'", limit.name(), crate::echo::cap(value.trim()))
    })?;
    Ok((limit, check_value(limit, value)?))
}

/// The quotas being enforced, per account (a user; a share link's viewers count
/// against the scene's owner).
#[derive(Debug)]
pub struct Quotas {
    defaults: QuotaSet,
    limiters: Mutex<HashMap<String, (u64, Arc<DefaultDirectRateLimiter>)>>,
    streams: Mutex<HashMap<String, u64>>,
    metrics: Arc<Metrics>,
}

/// An open stream, counted against its account until dropped.
#[derive(Debug)]
pub struct StreamPermit {
    quotas: Arc<Quotas>,
    account: String,
}

impl Drop for StreamPermit {
    fn drop(&mut self) {
        let mut streams = self.quotas.streams.lock().expect("lock");
        if let Some(n) = streams.get_mut(&self.account) {
            *n -= 1;
            if *n == 0 {
                streams.remove(&self.account);
            }
        }
    }
}

impl Quotas {
    /// Quotas with these server-wide defaults.
    pub fn new(defaults: QuotaSet, metrics: Arc<Metrics>) -> Self {
        Self { defaults, limiters: Mutex::default(), streams: Mutex::default(), metrics }
    }

    /// The server-wide defaults.
    pub fn defaults(&self) -> QuotaSet {
        self.defaults
    }

    /// The refusal of a request over `limit` (counted in the metrics).
    pub fn refuse(&self, limit: Limit, value: u64, detail: String) -> ServiceError {
        self.metrics.quota_refused(limit.name());
        ServiceError::ResourceExhausted(format!("quota {} = {value} reached: {detail}", limit.name()))
    }

    /// Takes one call from `account`'s request rate, or refuses it.
    pub fn admit(&self, account: &str, set: &QuotaSet) -> Result<(), ServiceError> {
        let rate = set.get(Limit::RequestsPerSecond);
        let limiter = {
            let mut limiters = self.limiters.lock().expect("lock");
            let entry = limiters.entry(account.to_owned()).or_insert_with(|| (rate, limiter(rate)));
            if entry.0 != rate {
                *entry = (rate, limiter(rate));
            }
            entry.1.clone()
        };
        limiter.check().map_err(|_| {
            self.refuse(Limit::RequestsPerSecond, rate, format!("{account} sends more than {rate} requests per second"))
        })
    }

    /// Opens a stream for `account`, or refuses it.
    pub fn open_stream(self: &Arc<Self>, account: &str, set: &QuotaSet) -> Result<StreamPermit, ServiceError> {
        let limit = set.get(Limit::OpenStreams);
        let mut streams = self.streams.lock().expect("lock");
        let open = streams.entry(account.to_owned()).or_insert(0);
        if *open >= limit {
            let n = *open;
            drop(streams);
            return Err(self.refuse(
                Limit::OpenStreams,
                limit,
                format!("{account} has {n} streams open; close one first"),
            ));
        }
        *open += 1;
        Ok(StreamPermit { quotas: self.clone(), account: account.to_owned() })
    }

    /// Streams `account` has open.
    pub fn streams_of(&self, account: &str) -> u64 {
        self.streams.lock().expect("lock").get(account).copied().unwrap_or(0)
    }
}

fn limiter(per_second: u64) -> Arc<DefaultDirectRateLimiter> {
    let n = NonZeroU32::new(u32::try_from(per_second).unwrap_or(u32::MAX)).unwrap_or(NonZeroU32::MIN);
    Arc::new(RateLimiter::direct(Rate::per_second(n)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug)]
    struct NoScenes;
    impl crate::metrics::SceneSamples for NoScenes {
        fn samples(&self) -> Vec<crate::metrics::SceneSample> {
            Vec::new()
        }
    }

    fn quotas() -> Arc<Quotas> {
        Arc::new(Quotas::new(QuotaSet::default(), Arc::new(Metrics::new(Arc::new(NoScenes)))))
    }

    #[test]
    fn assignments_name_what_is_wrong() {
        let mut q = QuotaSet::default();
        q.assign("running_scenes=2").unwrap();
        assert_eq!(q.get(Limit::RunningScenes), 2);
        assert!(
            q.assign("running=2").unwrap_err().starts_with("unknown quota 'running'; quotas are particles_per_scene")
        );
        assert_eq!(
            q.assign("open_streams=0").unwrap_err(),
            format!("open_streams: must be between 1 and {}, got 0", i64::MAX)
        );
        assert_eq!(q.assign("open_streams=x").unwrap_err(), "open_streams: must be a whole number >= 1, got 'x'");
        assert!(q.assign("open_streams").unwrap_err().contains("expected NAME=VALUE"));
    }

    #[test]
    fn streams_are_counted_until_dropped() {
        let q = quotas();
        let mut set = QuotaSet::default();
        set.set(Limit::OpenStreams, 2);
        let a = q.open_stream("alice", &set).unwrap();
        let _b = q.open_stream("alice", &set).unwrap();
        let e = q.open_stream("alice", &set).unwrap_err().to_string();
        assert_eq!(e, "quota open_streams = 2 reached: alice has 2 streams open; close one first");
        q.open_stream("bob", &set).expect("bob has his own count");
        drop(a);
        assert_eq!(q.streams_of("alice"), 1);
        q.open_stream("alice", &set).expect("room again");
    }

    #[test]
    fn the_request_rate_is_limited_per_account() {
        let q = quotas();
        let mut set = QuotaSet::default();
        set.set(Limit::RequestsPerSecond, 5);
        let admitted = (0..20).filter(|_| q.admit("alice", &set).is_ok()).count();
        // A burst of one second's worth, give or take one cell replenished meanwhile.
        assert!((5..=6).contains(&admitted), "{admitted}");
        assert!(q.admit("bob", &set).is_ok());
        let e = q.admit("alice", &set).unwrap_err().to_string();
        assert_eq!(e, "quota requests_per_second = 5 reached: alice sends more than 5 requests per second");
    }
}
