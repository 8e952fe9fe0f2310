//! A cluster worker's side of the registry: where new scenes go, taking up the
//! scenes placed on this worker (from their checkpoints on the shared directory),
//! dropping those that moved (writing nothing for them), handing every scene over
//! while draining, and knowing where the others' scenes are.

use super::{Need, Placed, Registry, ServiceError, State, persist, unavailable};
use crate::auth::Caller;
use crate::cluster::{Beat, Member};
use crate::metrics::{SceneSamples, WorkerSample};
use crate::store::Store;
use crate::store::cluster::{Lease, Placement};
use crate::store::db::DbError;

impl Registry {
    /// This worker's lease in a cluster; `None` on a single server.
    pub(super) fn lease(&self) -> Option<Lease> {
        self.member.as_ref().map(Member::lease)
    }

    /// Refuses to step or run while this cluster worker's tenure does not hold (it
    /// has not reached the database for half its lease: its scenes may be moving).
    pub(super) fn tenured(&self) -> Result<(), ServiceError> {
        if self.tenure.holds() {
            return Ok(());
        }
        Err(ServiceError::Unavailable(
            "this worker has not reached the cluster's database within half its lease, so it steps nothing; retry"
                .into(),
        ))
    }

    /// A database failure of a write for scene `id`: fenced (the scene moved while
    /// this worker was silent) or the database's own.
    pub(super) fn db_error(&self, id: u64, e: DbError) -> ServiceError {
        match e {
            DbError::Fenced(_) => {
                tracing::warn!(scene = id, "scene moved to another worker: this worker writes nothing more for it");
                ServiceError::Unavailable(format!("scene {id} moved to another worker; retry to reach it there"))
            }
            e => unavailable(e),
        }
    }

    /// The backend a new scene asks for, checked: `None` for any. A single server
    /// refuses one it does not run; a cluster's placement looks for a worker that does.
    pub(super) fn asked_backend<'a>(&self, asked: Option<&'a str>) -> Result<Option<&'a str>, ServiceError> {
        let Some(asked) = asked.filter(|b| !b.is_empty()) else { return Ok(None) };
        if !matches!(asked, "cpu" | "gpu") {
            return Err(ServiceError::InvalidArgument(format!(
                "backend: must be \"gpu\", \"cpu\" or empty (any), got {:?}",
                crate::echo::cap(asked)
            )));
        }
        let runs = self.options.backend;
        if self.member.is_none() && asked != runs {
            return Err(ServiceError::FailedPrecondition(format!(
                "backend: this server runs its scenes on the {runs} backend, not {asked}"
            )));
        }
        Ok(Some(asked))
    }

    /// In a cluster, whether a new scene of `particles` on `backend` is built here: yes when the
    /// request named this worker and room waits reserved for it or it has room, or
    /// placement picks it; else the worker placement picks (its room reserved), as
    /// [`ServiceError::Elsewhere`]. Always yes on a single server.
    pub(super) async fn place_here(
        &self,
        particles: u64,
        named: Option<&str>,
        backend: Option<&str>,
    ) -> Result<(), ServiceError> {
        let (Some(member), Some(store)) = (&self.member, &self.store) else { return Ok(()) };
        let me = &member.info.name;
        match store.db.place(particles, named.filter(|n| n == me), backend).await.map_err(unavailable)? {
            Placement::On(w) if &w == me => Ok(()),
            Placement::On(w) => Err(ServiceError::Elsewhere {
                message: format!("a new scene of {particles} particles goes to worker {w}"),
                worker: w,
            }),
            Placement::Refused(why) => Err(ServiceError::ResourceExhausted(format!("the cluster has no room: {why}"))),
            Placement::Unserved(runs) => Err(ServiceError::FailedPrecondition(format!(
                "backend: no worker of this cluster runs the {} backend (they run {runs})",
                backend.unwrap_or_default()
            ))),
        }
    }

    /// One cluster tick: the heartbeat (on losing the scenes, drops them all), the
    /// eviction of silent workers, taking up scenes placed here and dropping those
    /// that moved, handing scenes over while draining, and where the others' are.
    pub(super) async fn cluster_tick(&self, store: &Store) -> anyhow::Result<()> {
        let member = self.member.as_ref().expect("a cluster worker");
        let live = serde_json::to_string(&self.scenes.samples()).expect("scene figures serialize");
        let draining = match member.beat(&store.db, &live).await? {
            Beat::Member { draining } => draining,
            Beat::Rejoined => {
                self.locate(store, &member.lease()).await?;
                self.drop_scenes(&self.held_ids()).await;
                false
            }
        };
        member.evict_silent(&store.db).await?;
        let lease = member.lease();
        let rows = self.locate(store, &lease).await?;
        if draining {
            // What it holds now is read again at the next tick.
            self.hand_over_all(store).await;
            return Ok(());
        }
        // Dropped: scenes whose row names another holder. A scene without a row was
        // created here after the rows were read (a deleted one is gone already).
        let local = self.held_ids();
        let gone: Vec<u64> =
            rows.iter().filter(|r| local.contains(&r.id) && r.lease.as_ref() != Some(&lease)).map(|r| r.id).collect();
        self.drop_scenes(&gone).await;
        for row in rows.iter().filter(|r| r.lease.as_ref() == Some(&lease) && !local.contains(&r.id)) {
            self.take_up(store, row).await;
        }
        Ok(())
    }

    /// Records where every scene not held by `lease` is, before any is dropped: a
    /// call for a dropped scene then finds where it went, never "not found"; and what
    /// every worker published of its scenes, for lists and `/metrics`. Returns every
    /// scene's row.
    async fn locate(&self, store: &Store, lease: &Lease) -> anyhow::Result<Vec<crate::store::db::SceneRow>> {
        // Read before the scenes, so a scene created meanwhile is never taken as missing.
        let newest = store.db.next_scene_id().await?.saturating_sub(1);
        let rows = store.db.scenes().await?;
        let workers: Vec<WorkerSample> = store.db.workers().await?.iter().map(worker_sample).collect();
        let live = |id: u64, worker: &str| {
            let w = workers.iter().find(|w| w.name == worker)?;
            w.scenes.iter().find(|s| s.id == id).cloned()
        };
        self.newest_known.store(newest, std::sync::atomic::Ordering::Relaxed);
        *self.elsewhere.write().expect("lock") = rows
            .iter()
            .filter_map(|r| {
                let l = r.lease.as_ref().filter(|l| l.worker != lease.worker)?;
                let placed = Placed {
                    id: r.id,
                    worker: l.worker.clone(),
                    owner: r.owner.clone(),
                    name: r.name.clone(),
                    state: r.state.clone(),
                    particles: r.particles,
                    live: live(r.id, &l.worker),
                };
                Some((r.id, placed))
            })
            .collect();
        self.metrics.cluster().set(workers);
        Ok(rows)
    }

    fn held_ids(&self) -> Vec<u64> {
        self.scenes.0.read().expect("lock").keys().copied().collect()
    }

    /// Brings a scene placed here back from its newest checkpoint, paused, and
    /// checkpoints it at once in its new generation: from then on no file its
    /// previous worker may still name ranks above this worker's.
    async fn take_up(&self, store: &Store, row: &crate::store::db::SceneRow) {
        let (r, checkpoints, backend) = (row.clone(), store.checkpoints.clone(), self.backend.clone());
        let recovered = tokio::task::spawn_blocking(move || persist::recover(&r, &checkpoints, &*backend))
            .await
            .expect("recovery task");
        match recovered {
            Ok((sim, from)) => {
                tracing::info!(scene = row.id, owner = %row.owner, "scene taken up: {from}");
                self.insert(row.id, row.owner.clone(), sim);
                if let Err(e) = self.write_checkpoint(row.id).await {
                    tracing::warn!(scene = row.id, "the first checkpoint after taking the scene up failed: {e}");
                }
            }
            Err(e) => tracing::error!(scene = row.id, "scene placed here could not be brought back: {e}"),
        }
    }

    /// Stops the threads of scenes this worker no longer holds, writing nothing for
    /// them; their streams end, and their clients find them on their new worker.
    async fn drop_scenes(&self, ids: &[u64]) {
        let entries: Vec<_> = {
            let mut scenes = self.scenes.0.write().expect("lock");
            ids.iter().filter_map(|id| scenes.remove(id)).collect()
        };
        for e in &entries {
            tracing::warn!(scene = e.handle.shared.id, "scene dropped: another worker holds it now");
        }
        tokio::task::spawn_blocking(move || entries.iter().for_each(|e| e.handle.delete()))
            .await
            .expect("scene stop task");
    }

    /// Draining: pauses and checkpoints each scene, then moves it to the worker
    /// placement picks among the others; a scene no other worker has room for stays.
    async fn hand_over_all(&self, store: &Store) {
        let lease = self.lease().expect("a cluster worker");
        for id in self.held_ids() {
            let Some(handle) = self.scenes.0.read().expect("lock").get(&id).map(|e| e.handle.clone()) else { continue };
            if handle.shared.status().state == State::Running {
                let _ = handle.pause().await;
            }
            if let Err(e) = self.write_checkpoint(id).await {
                tracing::error!(scene = id, "not handed over, its checkpoint failed: {e}");
                continue;
            }
            match store.db.hand_over(&lease, id, handle.shared.particles as u64).await {
                Ok(Some(to)) => {
                    tracing::info!(scene = id, to = %to.worker, "scene handed over (draining)");
                    let placed = Placed {
                        id,
                        worker: to.worker,
                        owner: handle.shared.owner.clone(),
                        name: handle.shared.name.clone(),
                        state: "paused".into(),
                        particles: handle.shared.particles as u64,
                        live: None,
                    };
                    self.elsewhere.write().expect("lock").insert(id, placed);
                    self.drop_scenes(&[id]).await;
                }
                Ok(None) => tracing::warn!(scene = id, "draining: no other worker has room for this scene"),
                Err(e) => tracing::error!(scene = id, "draining: {e}"),
            }
        }
    }

    /// This worker's name in a cluster; empty on a single server.
    pub fn worker_name(&self) -> &str {
        self.member.as_ref().map_or("", |m| m.info.name.as_str())
    }

    /// The scenes of the cluster that `caller` may watch and other workers hold, as
    /// of the last tick, by id.
    pub fn placed_elsewhere(&self, caller: &Caller) -> Vec<Placed> {
        let map = self.elsewhere.read().expect("lock");
        map.values().filter(|p| Self::check(caller, p.id, &p.owner, Need::Watch).is_ok()).cloned().collect()
    }
}

/// A worker's row as `/metrics` shows it: what it published with its last heartbeat
/// (nothing, if that does not read: a worker of another version).
fn worker_sample(w: &crate::store::cluster::WorkerRow) -> WorkerSample {
    WorkerSample {
        name: w.info.name.clone(),
        draining: w.draining,
        max_particles: w.info.max_particles,
        scenes: serde_json::from_str(&w.live).unwrap_or_default(),
    }
}
