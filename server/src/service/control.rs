//! The calls with consequences beyond the scene's worker: running (quotas),
//! pausing, resetting and restoring (a checkpoint follows), live settings (kept in
//! the database), checkpoints on request, share links, and the admin's view of users.
//! Calls without such consequences (step, stats, snapshot) go to the scene's
//! [`SceneHandle`] directly, after [`Registry::get`].

use super::{Need, Registry, ServiceError, State, Status, persist, unavailable};
use crate::auth::{Caller, token};
use crate::quota::{Limit, QuotaSet};
use crate::store::Store;
use crate::store::checkpoint::Meta;
use std::time::Instant;

/// A user as an admin (or the user) sees them.
#[derive(Debug, Clone, PartialEq)]
pub struct UserView {
    /// Login name.
    pub name: String,
    /// Admin or not.
    pub admin: bool,
    /// The quotas in force (defaults with overrides).
    pub quotas: QuotaSet,
    /// Which quotas are the user's own overrides.
    pub overridden: Vec<Limit>,
    /// Scenes owned.
    pub scenes: u64,
    /// Scenes running.
    pub running_scenes: u64,
    /// Particles in running scenes.
    pub running_particles: u64,
    /// Streams open.
    pub open_streams: u64,
}

impl Registry {
    fn store(&self) -> Result<&Store, ServiceError> {
        self.store.as_ref().ok_or_else(|| {
            ServiceError::FailedPrecondition("this server keeps no data directory (scenes live in memory only)".into())
        })
    }

    /// Runs a scene continuously at `real_time_factor` (0: as fast as possible), if its
    /// owner's running-scene and running-particle quotas allow one more.
    pub async fn run(&self, caller: &Caller, id: u64, real_time_factor: f64) -> Result<Status, ServiceError> {
        let handle = self.get(caller, id, Need::Steer)?;
        self.tenured()?;
        let owner = handle.shared.owner.clone();
        let _gate = self.run_gate.lock().await;
        if handle.shared.status().state != State::Running {
            let quotas = self.quotas_of(&owner);
            let (running, particles) = match (&self.member, &self.store) {
                // Over the whole cluster: every worker records its runs in the database.
                (Some(_), Some(store)) => store.db.running_of(&owner).await.map_err(unavailable)?,
                _ => self.running_of(&owner),
            };
            let (max_scenes, max_particles) = (quotas.get(Limit::RunningScenes), quotas.get(Limit::RunningParticles));
            if running >= max_scenes {
                let detail = format!("{owner} runs {running} scenes; pause one first");
                return Err(self.quotas.refuse(Limit::RunningScenes, max_scenes, detail));
            }
            let more = handle.shared.particles as u64;
            if particles + more > max_particles {
                let detail = format!("{owner}'s running scenes have {particles} particles and this one {more}");
                return Err(self.quotas.refuse(Limit::RunningParticles, max_particles, detail));
            }
        }
        let status = handle.run(real_time_factor).await?;
        self.record_state(id, "running", real_time_factor).await;
        Ok(status)
    }

    /// Scenes and particles `owner` has running.
    fn running_of(&self, owner: &str) -> (u64, u64) {
        let scenes = self.scenes.0.read().expect("lock");
        scenes
            .values()
            .map(|e| &e.handle.shared)
            .filter(|s| s.owner == owner && s.status().state == State::Running)
            .fold((0, 0), |(n, p), s| (n + 1, p + s.particles as u64))
    }

    async fn record_state(&self, id: u64, state: &str, real_time_factor: f64) {
        if let Some(store) = &self.store
            && let Err(e) = store.db.update_state(id, self.lease().as_ref(), state, real_time_factor).await
        {
            tracing::warn!(scene = id, "run state not recorded: {e}");
        }
    }

    /// Pauses a scene after its current step, and checkpoints it.
    pub async fn pause(&self, caller: &Caller, id: u64) -> Result<Status, ServiceError> {
        let handle = self.get(caller, id, Need::Steer)?;
        let status = handle.pause().await?;
        self.record_state(id, "paused", 0.0).await;
        self.checkpoint_if_kept(id).await?;
        Ok(status)
    }

    /// Puts a paused or halted scene back at t = 0 with its current settings, and
    /// checkpoints it.
    pub async fn reset(&self, caller: &Caller, id: u64) -> Result<Status, ServiceError> {
        let status = self.get(caller, id, Need::Steer)?.reset().await?;
        self.checkpoint_if_kept(id).await?;
        Ok(status)
    }

    /// Replaces a paused scene's state with a snapshot of the same scene, and
    /// checkpoints it.
    pub async fn restore(&self, caller: &Caller, id: u64, state: Vec<u8>) -> Result<Status, ServiceError> {
        let status = self.get(caller, id, Need::Steer)?.restore(state).await?;
        self.checkpoint_if_kept(id).await?;
        Ok(status)
    }

    /// Steps a paused scene by hand ([`super::SceneHandle::step`]). A call that
    /// advanced it is checkpointed before its answer, every one: a crash after the
    /// answer loses nothing the caller was told (`floe bench --step-latency` measures
    /// what that costs a stepping script; docs/benchmarks.md).
    pub async fn step(&self, caller: &Caller, id: u64, steps: u64, until: Option<f64>) -> Result<Status, ServiceError> {
        let (handle, since) = self.entry(caller, id, Need::Steer, |e| (e.handle.clone(), e.checkpoint.clone()))?;
        self.tenured()?;
        let before = handle.shared.status().steps;
        let kept = self.store.is_some();
        // Marked before stepping: a caller who leaves mid-way drops this call, and the
        // maintenance loop still checkpoints what was stepped.
        let was = if kept { Some(std::mem::replace(&mut since.lock().await.stepped, true)) } else { None };
        let result = handle.step(steps, until).await;
        let advanced = handle.shared.status().steps != before;
        let Some(was) = was else { return Ok(result?) };
        since.lock().await.stepped = was || advanced;
        if advanced {
            self.write_checkpoint(id).await?;
        }
        Ok(result?)
    }

    /// Changes a scene's tunable settings and records them in the database.
    pub async fn set_parameters(
        &self,
        caller: &Caller,
        id: u64,
        overrides: Vec<String>,
    ) -> Result<Status, ServiceError> {
        let handle = self.get(caller, id, Need::Steer)?;
        let status = handle.set_parameters(overrides).await?;
        if let Some(store) = &self.store {
            let tunables = persist::tunables_json(&handle.shared.scene_json());
            store.db.update_tunables(id, self.lease().as_ref(), &tunables).await.map_err(|e| self.db_error(id, e))?;
        }
        Ok(status)
    }

    /// Checkpoints a scene now.
    pub async fn checkpoint(&self, caller: &Caller, id: u64) -> Result<Meta, ServiceError> {
        self.get(caller, id, Need::Steer)?;
        self.write_checkpoint(id).await
    }

    async fn checkpoint_if_kept(&self, id: u64) -> Result<(), ServiceError> {
        if self.store.is_some() {
            self.write_checkpoint(id).await?;
        }
        Ok(())
    }

    /// Takes scene `id`'s state from its worker and writes it as its newest checkpoint.
    pub(super) async fn write_checkpoint(&self, id: u64) -> Result<Meta, ServiceError> {
        let store = self.store()?;
        let (handle, lock) = {
            let scenes = self.scenes.0.read().expect("lock");
            // Dropped since the call found it: moved to another worker, or deleted.
            let e = scenes.get(&id).ok_or_else(|| self.not_here(&crate::auth::Caller::local(), id, Need::Watch))?;
            (e.handle.clone(), e.checkpoint.clone())
        };
        let mut since = lock.lock().await;
        let t0 = Instant::now();
        let saved = handle.save_at().await?;
        // A worker that may have lost the scene writes nothing for it: its tenure
        // must hold and the database must still place the scene here.
        let lease = self.lease();
        let generation = store.db.generation(id, lease.as_ref()).await.map_err(unavailable)?;
        let generation = match generation {
            Some(g) if self.tenure.holds() => g,
            // A single server's scene without a row is being deleted.
            _ if lease.is_none() => return Err(self.not_here(&crate::auth::Caller::local(), id, Need::Watch)),
            _ => return Err(self.db_error(id, crate::store::db::DbError::Fenced(id))),
        };
        let checkpoints = store.checkpoints.clone();
        let tenure = self.tenure.clone();
        let written = tokio::task::spawn_blocking(move || {
            checkpoints.write(id, generation, saved.step, saved.time, &saved.state, || tenure.holds())
        })
        .await
        .expect("checkpoint task");
        self.metrics.checkpointed(written.is_ok(), t0.elapsed().as_secs_f64());
        let meta = written.map_err(|e| {
            tracing::error!(scene = id, "checkpoint failed: {e}");
            ServiceError::Unavailable(format!("the checkpoint could not be written: {e}"))
        })?;
        *since = super::Since::default();
        tracing::debug!(scene = id, step = meta.step, sequence = meta.sequence, "checkpoint written");
        Ok(meta)
    }

    /// Creates a read-only share link of a scene: its token (shown once) and its id.
    pub async fn share(&self, caller: &Caller, id: u64) -> Result<(String, String), ServiceError> {
        self.get(caller, id, Need::Steer)?;
        let store = self.store()?;
        let link = token::generate(token::SHARE_PREFIX);
        let hash = token::hash(&link);
        store.db.add_share(id, &hash).await.map_err(unavailable)?;
        self.reload_directory(store).await?;
        Ok((link, hash[..token::SHARE_ID_LEN].to_owned()))
    }

    /// The ids of a scene's share links.
    pub fn shares(&self, caller: &Caller, id: u64) -> Result<Vec<String>, ServiceError> {
        self.get(caller, id, Need::Steer)?;
        Ok(self.access.directory().shares_of(id))
    }

    /// Revokes the share link `share` of a scene.
    pub async fn revoke_share(&self, caller: &Caller, id: u64, share: &str) -> Result<(), ServiceError> {
        self.get(caller, id, Need::Steer)?;
        let store = self.store()?;
        let missing = || ServiceError::Missing(format!("scene {id} has no share link '{}'", crate::echo::cap(share)));
        if share.len() != token::SHARE_ID_LEN || !share.bytes().all(|b| b.is_ascii_hexdigit()) {
            return Err(missing());
        }
        if store.db.remove_shares(id, &share.to_ascii_lowercase()).await.map_err(unavailable)? == 0 {
            return Err(missing());
        }
        self.reload_directory(store).await
    }

    /// Re-reads users, tokens, quotas and share links from the database.
    pub(super) async fn reload_directory(&self, store: &Store) -> Result<(), ServiceError> {
        let rows = store.db.directory().await.map_err(unavailable)?;
        self.access.set_directory(crate::auth::Directory::from_rows(rows));
        Ok(())
    }

    /// A user's quotas and what they use now.
    fn user_view(&self, name: &str, admin: bool, overridden: Vec<Limit>) -> UserView {
        let scenes = self.scenes.0.read().expect("lock").values().filter(|e| e.handle.shared.owner == name).count();
        let (running_scenes, running_particles) = self.running_of(name);
        UserView {
            name: name.into(),
            admin,
            quotas: self.quotas_of(name),
            overridden,
            scenes: scenes as u64,
            running_scenes,
            running_particles,
            open_streams: self.quotas.streams_of(name),
        }
    }

    /// The calling user, their quotas and usage.
    pub fn whoami(&self, caller: &Caller) -> Result<UserView, ServiceError> {
        match caller {
            Caller::User { name, admin } => {
                let overridden = self.access.directory().user(name).map(|u| u.overrides.iter().map(|o| o.0).collect());
                Ok(self.user_view(name, *admin, overridden.unwrap_or_default()))
            }
            Caller::Viewer { scene } => Err(ServiceError::PermissionDenied(format!(
                "this is a share link of scene {scene}, not a user's token"
            ))),
        }
    }

    /// Every user with quotas and usage (admins only).
    pub fn users(&self, caller: &Caller) -> Result<Vec<UserView>, ServiceError> {
        require_admin(caller)?;
        let directory = self.access.directory();
        let mut names: Vec<(String, bool, Vec<Limit>)> =
            directory.users().map(|(n, u)| (n.clone(), u.admin, u.overrides.iter().map(|o| o.0).collect())).collect();
        names.sort_by(|a, b| a.0.cmp(&b.0));
        Ok(names.into_iter().map(|(n, admin, o)| self.user_view(&n, admin, o)).collect())
    }

    /// Sets (`Some`) or removes (`None`) a user's override of `limit` (admins only).
    pub async fn set_quota(
        &self,
        caller: &Caller,
        user: &str,
        limit: Limit,
        value: Option<u64>,
    ) -> Result<UserView, ServiceError> {
        require_admin(caller)?;
        let store = self.store()?;
        let value = value.map(|v| i64::try_from(v).unwrap_or(i64::MAX));
        store.db.set_quota(user, limit.name(), value).await.map_err(|e| match e {
            crate::store::db::DbError::NoUser(_) => ServiceError::Missing(e.to_string()),
            e => unavailable(e),
        })?;
        self.reload_directory(store).await?;
        self.users(caller)?
            .into_iter()
            .find(|u| u.name == user)
            .ok_or_else(|| ServiceError::Missing(format!("no user named '{user}'")))
    }
}

/// Refuses a caller who is not an admin.
pub fn require_admin(caller: &Caller) -> Result<(), ServiceError> {
    if caller.is_admin() { Ok(()) } else { Err(ServiceError::PermissionDenied("only an admin may do this".into())) }
}
