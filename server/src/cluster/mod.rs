//! Several `floe serve --worker NAME` behind one address, sharing one PostgreSQL
//! database and one checkpoint directory.
//!
//! - [`placement`]: which worker a new or moved scene goes to.
//! - [`tenure`]: how long a worker may step its scenes without a heartbeat.
//! - [`Member`]: this worker's place in the cluster: its lease (name and epoch), its
//!   heartbeat, and who among the others has gone silent.
//!
//! The database rows and their fencing are `store::cluster`; the registry's side
//! (taking up scenes placed here, handing them over, refusing writes for scenes
//! that moved) is `service::membership`.

pub mod placement;
mod tenure;

use crate::store::Database;
use crate::store::cluster::{Lease, Moved, WorkerInfo};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, RwLock};
use std::time::{Duration, Instant};
pub use tenure::Tenure;

/// Default of [`Member::lease_time`] (s).
pub const DEFAULT_LEASE_SECONDS: u64 = 10;

/// The request header (gRPC metadata) naming the worker a call is for; the proxy
/// routes on it, and a worker's answer carries it to say where a scene is.
pub const WORKER_HEADER: &str = "floe-worker";

/// Whether `name` may name a worker: it goes into host names and URL paths.
pub fn valid_name(name: &str) -> bool {
    let b = name.as_bytes();
    !b.is_empty()
        && b.len() <= 63
        && (b[0].is_ascii_lowercase() || b[0].is_ascii_digit())
        && b.iter().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || *c == b'-')
}

/// What another worker was last seen doing.
#[derive(Debug, Clone, Copy)]
struct Heard {
    epoch: i64,
    beats: i64,
    /// When this worker first saw those beats (its own clock).
    since: Instant,
}

/// This worker's membership.
#[derive(Debug)]
pub struct Member {
    /// What it told the cluster about itself.
    pub info: WorkerInfo,
    /// A worker silent this long loses its scenes; this one stops stepping within half of it.
    pub lease_time: Duration,
    /// Its scene threads step while this holds.
    pub tenure: Arc<Tenure>,
    lease: RwLock<Lease>,
    heard: Mutex<HashMap<String, Heard>>,
    /// When this worker last looked at the others' heartbeats.
    watched: Mutex<Option<Instant>>,
}

/// What a heartbeat learnt.
#[derive(Debug, Clone, PartialEq)]
pub enum Beat {
    /// Still counted; draining or not.
    Member {
        /// Hand every scene to others.
        draining: bool,
    },
    /// Declared gone by the others: every scene it held is theirs now. It joined
    /// again with a new lease and holds nothing.
    Rejoined,
}

impl Member {
    /// Joins the cluster (a new epoch); the tenure starts with this first heartbeat.
    pub async fn join(db: &Database, info: WorkerInfo, lease_time: Duration) -> anyhow::Result<Self> {
        anyhow::ensure!(
            valid_name(&info.name),
            "--worker '{}': a worker name is 1 to 63 lower-case letters, digits and '-', starting with a letter or digit",
            crate::echo::cap(&info.name)
        );
        let sent = Instant::now();
        let lease = db.register_worker(&info).await?;
        let tenure = Arc::new(Tenure::ended());
        tenure.extend(sent, lease_time / 2);
        tracing::info!(worker = %info.name, epoch = lease.epoch, "joined the cluster");
        Ok(Self {
            info,
            lease_time,
            tenure,
            lease: RwLock::new(lease),
            heard: Mutex::new(HashMap::new()),
            watched: Mutex::new(None),
        })
    }

    /// The lease its scenes are held by now.
    pub fn lease(&self) -> Lease {
        self.lease.read().expect("lock").clone()
    }

    /// One heartbeat: extends the tenure while the cluster counts this worker; when
    /// it was declared gone, ends the tenure and joins again with a new lease (the
    /// caller drops every scene it held, writing nothing). `live` (JSON) is what
    /// its scenes are doing, for the others to show.
    pub async fn beat(&self, db: &Database, live: &str) -> anyhow::Result<Beat> {
        let sent = Instant::now();
        let lease = self.lease();
        match db.heartbeat(&lease, live).await? {
            Some(draining) => {
                self.tenure.extend(sent, self.lease_time / 2);
                Ok(Beat::Member { draining })
            }
            None => {
                self.tenure.end();
                tracing::warn!(
                    worker = %lease.worker,
                    epoch = lease.epoch,
                    "declared gone by the cluster (silent past the lease): dropping every scene, joining again"
                );
                // The tenure starts again at the next heartbeat, after the scenes
                // held before are dropped.
                let fresh = db.register_worker(&self.info).await?;
                *self.lease.write().expect("lock") = fresh;
                Ok(Beat::Rejoined)
            }
        }
    }

    /// Evicts every other worker whose heartbeats this one has seen stand still for
    /// the lease time, and places scenes left without a worker; the scenes moved.
    pub async fn evict_silent(&self, db: &Database) -> anyhow::Result<Vec<Moved>> {
        let now = Instant::now();
        let me = self.lease();
        let mut silent = Vec::new();
        {
            let workers = db.workers().await?;
            let mut heard = self.heard.lock().expect("lock");
            // Silence counts only while this worker was watching: after a gap (the
            // database was unreachable, this process was stopped) everyone starts
            // afresh, or all the others would look silent at once.
            let last = self.watched.lock().expect("lock").replace(now);
            if last.is_none_or(|t| now.duration_since(t) > self.lease_time / 2) {
                heard.clear();
            }
            heard.retain(|name, _| workers.iter().any(|w| &w.info.name == name));
            for w in workers.iter().filter(|w| w.info.name != me.worker) {
                let h =
                    heard.entry(w.info.name.clone()).or_insert(Heard { epoch: w.epoch, beats: w.beats, since: now });
                if h.epoch != w.epoch || h.beats != w.beats {
                    *h = Heard { epoch: w.epoch, beats: w.beats, since: now };
                } else if now.duration_since(h.since) >= self.lease_time {
                    silent.push(w.lease());
                }
            }
        }
        for gone in silent {
            if db.evict(&gone).await? {
                tracing::warn!(worker = %gone.worker, epoch = gone.epoch, "worker silent past the lease: evicted");
            }
        }
        let moved = db.place_orphans().await?;
        for m in &moved {
            tracing::info!(scene = m.scene, to = %m.to.worker, "scene placed on a worker");
        }
        Ok(moved)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn worker_names_fit_host_names_and_paths() {
        for ok in ["floe-0", "a", "gpu-node-3", "0x"] {
            assert!(valid_name(ok), "{ok}");
        }
        for bad in ["", "-a", "Floe", "a.b", "a/b", "a;b", "../x", &"a".repeat(64)] {
            assert!(!valid_name(bad), "{bad}");
        }
    }
}
