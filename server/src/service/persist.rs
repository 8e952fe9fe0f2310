//! What makes scenes survive the process: bringing every scene back at start-up
//! (paused, at its newest checkpoint that verifies), checkpoints while scenes run,
//! re-reading the directory when `floe admin` changed it, and the shutdown that
//! checkpoints everything.

use super::{Options, Registry, State, unavailable};
use crate::cluster::Member;
use crate::store::Store;
use crate::store::checkpoint::{Checkpoints, Meta};
use crate::store::cluster::Lease;
use crate::store::db::SceneRow;
use floe_engine::Simulation;
use floe_engine::scene::tunable;
use floe_engine::scene::{Scene, load};
use floe_engine::simulation::BackendFactory;
use serde_json::Value;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

/// The database row of a new scene.
pub(super) fn row(id: u64, owner: &str, sim: &Simulation, particles: u64, lease: Option<Lease>) -> SceneRow {
    let spec = serde_json::to_string(sim.scene()).expect("scenes serialise");
    SceneRow {
        id,
        owner: owner.into(),
        name: sim.scene().name.clone(),
        tunables: tunables_json(&spec),
        spec,
        state: "paused".into(),
        real_time_factor: 0.0,
        particles,
        lease,
        generation: 0,
    }
}

/// A JSON pointer for a tunable path (`fluids[0].xsph` -> `/fluids/0/xsph`).
fn pointer(path: &str) -> String {
    path.split(['.', '[']).map(|p| format!("/{}", p.trim_end_matches(']'))).collect()
}

/// The concrete paths of tunable `path` in `scene` (`fluids[*].xsph`: one per fluid).
fn concrete(path: &str, scene: &Value) -> Vec<String> {
    match path.split_once("[*]") {
        None => vec![path.to_owned()],
        Some((head, tail)) => {
            let n = scene.pointer(&pointer(head)).and_then(Value::as_array).map_or(0, Vec::len);
            (0..n).flat_map(|i| concrete(&format!("{head}[{i}]{tail}"), scene)).collect()
        }
    }
}

/// The tunable settings of a scene (as JSON text) as a JSON object, path -> value:
/// those of the core and of the scene's modules.
pub(super) fn tunables_json(scene_json: &str) -> String {
    let value: Value = serde_json::from_str(scene_json).expect("a serialised scene");
    let scene = load::from_value(value.clone()).expect("a serialised scene is valid");
    let map: serde_json::Map<String, Value> = floe_engine::module::tunables(&scene)
        .iter()
        .flat_map(|t| concrete(t.path, &value))
        .filter_map(|path| value.pointer(&pointer(&path)).map(|v| (path, v.clone())))
        .collect();
    Value::Object(map).to_string()
}

/// The overrides that set every tunable field recorded in `tunables`.
fn tunable_overrides(tunables: &str) -> Result<Vec<String>, String> {
    let map: serde_json::Map<String, Value> =
        serde_json::from_str(tunables).map_err(|e| format!("recorded settings: {e}"))?;
    Ok(map.iter().map(|(path, value)| format!("{path}={value}")).collect())
}

/// Where a recovered scene came from.
#[derive(Debug)]
pub(super) enum Recovered {
    /// Its newest checkpoint that verified.
    Checkpoint(Meta),
    /// Rebuilt at t = 0 from its recorded scene (no checkpoint verified).
    Spec,
}

impl std::fmt::Display for Recovered {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Recovered::Checkpoint(m) => {
                write!(f, "at step {} (t = {:.6} s) from checkpoint {}", m.step, m.time, m.sequence)
            }
            Recovered::Spec => write!(f, "at t = 0, rebuilt from its recorded settings (no checkpoint verified)"),
        }
    }
}

/// The scene a database row describes, with its recorded live settings.
fn recorded_scene(row: &SceneRow) -> Result<Scene, String> {
    let mut value: Value = serde_json::from_str(&row.spec).map_err(|e| format!("recorded scene: {e}"))?;
    load::apply_overrides(&mut value, &tunable_overrides(&row.tunables)?).map_err(|e| e.to_string())?;
    load::from_value(value).map_err(|e| format!("recorded scene: {e}"))
}

/// Brings one scene back: from its newest checkpoint that verifies (checksum, then
/// a restore of the snapshot it holds, of this very scene), with the live settings
/// recorded since; else rebuilt from its recorded scene at t = 0. Each checkpoint
/// passed over is logged with the reason.
pub(super) fn recover(
    row: &SceneRow,
    checkpoints: &Checkpoints,
    backend: &BackendFactory,
) -> Result<(Simulation, Recovered), String> {
    let scene = recorded_scene(row)?;
    let overrides = tunable_overrides(&row.tunables)?;
    for (_, path) in checkpoints.files(row.id) {
        let attempt = Checkpoints::read(&path).map_err(|e| e.to_string()).and_then(|(meta, payload)| {
            if meta.scene != row.id {
                return Err(format!("{}: a checkpoint of scene {}", path.display(), meta.scene));
            }
            // The checkpoint's scene, with the live settings recorded since, must be the
            // recorded scene: checked before anything is built.
            let at_checkpoint = Simulation::snapshot_scene(&payload).map_err(|e| format!("{}: {e}", path.display()))?;
            let tuned = tunable::apply(&at_checkpoint, &overrides).map_err(|e| format!("{}: {e}", path.display()))?;
            if tuned != scene {
                return Err(format!("{}: a checkpoint of another scene", path.display()));
            }
            let mut sim = Simulation::restore_on(&payload, backend).map_err(|e| format!("{}: {e}", path.display()))?;
            if at_checkpoint != scene {
                sim.set_parameters(&overrides).map_err(|e| format!("{}: {e}", path.display()))?;
            }
            Ok((sim, meta))
        });
        match attempt {
            Ok((sim, meta)) => return Ok((sim, Recovered::Checkpoint(meta))),
            Err(reason) => tracing::warn!(scene = row.id, "checkpoint passed over: {reason}"),
        }
    }
    let sim = Simulation::new(scene, backend).map_err(|e| e.to_string())?;
    Ok((sim, Recovered::Spec))
}

impl Registry {
    /// A registry over `store`: every scene recorded there comes back, paused, at its
    /// newest checkpoint that verifies (in a cluster, every scene placed on this
    /// worker); checkpoint directories of scenes no longer recorded (a crash
    /// mid-delete) are removed.
    pub async fn open(
        options: Options,
        backend: Arc<BackendFactory>,
        store: Store,
        member: Option<Member>,
    ) -> anyhow::Result<Arc<Self>> {
        let rows = store.db.scenes().await?;
        let next = store.db.next_scene_id().await?;
        let held = match &member {
            Some(m) => store.db.scenes_held(&m.lease()).await?,
            None => rows.clone(),
        };
        let registry = Self::with_store(options, backend, Some(store), member);
        let store = registry.store.as_ref().expect("just given");
        registry.reload_directory(store).await.map_err(|e| anyhow::anyhow!("{e}"))?;
        registry.next_id.store(next.max(rows.last().map_or(1, |r| r.id + 1)), Ordering::Relaxed);
        let lease = registry.lease();
        for row in &held {
            let (r, checkpoints, backend) = (row.clone(), store.checkpoints.clone(), registry.backend.clone());
            let recovered =
                tokio::task::spawn_blocking(move || recover(&r, &checkpoints, &*backend)).await.expect("recovery task");
            match recovered {
                Ok((sim, from)) => {
                    tracing::info!(scene = row.id, owner = %row.owner, "scene restored paused {from} (was {})", row.state);
                    registry.insert(row.id, row.owner.clone(), sim);
                    if row.state != "paused" {
                        store.db.update_state(row.id, lease.as_ref(), "paused", 0.0).await?;
                    }
                }
                Err(e) => tracing::error!(scene = row.id, "scene could not be brought back, kept in the database: {e}"),
            }
        }
        for orphan in store.checkpoints.scenes().into_iter().filter(|id| !rows.iter().any(|r| r.id == *id)) {
            tracing::info!(scene = orphan, "removing checkpoints of a deleted scene");
            store.checkpoints.remove(orphan)?;
        }
        Ok(Arc::new(registry))
    }

    /// Until `stop` resolves, once a second: re-reads the directory if `floe admin`
    /// changed it, and checkpoints every scene that has run for the checkpoint
    /// interval since its last checkpoint.
    pub async fn maintain(self: Arc<Self>, stop: impl std::future::Future<Output = ()>) {
        let Some(store) = &self.store else { return stop.await };
        let mut tick = tokio::time::interval(Duration::from_secs(1));
        tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
        let mut last = Instant::now();
        tokio::pin!(stop);
        loop {
            tokio::select! {
                _ = tick.tick() => {}
                () = &mut stop => break,
            }
            let elapsed = std::mem::replace(&mut last, Instant::now()).elapsed();
            if self.member.is_some()
                && let Err(e) = self.cluster_tick(store).await
            {
                tracing::warn!("cluster: {e}");
            }
            match store.db.directory_version().await {
                Ok(v) if v != self.access.directory().version => {
                    if self.reload_directory(store).await.is_ok() {
                        tracing::info!("users, tokens, quotas or share links changed; re-read");
                    }
                }
                Ok(_) => {}
                Err(e) => tracing::warn!("{}", unavailable(e)),
            }
            for id in self.due_for_checkpoint(elapsed) {
                let _ = self.write_checkpoint(id).await;
            }
        }
    }

    /// Adds `elapsed` to the running time of every running scene; those that reach
    /// the checkpoint interval, and those stepped by calls whose callers left before
    /// their answers (an answered step call checkpoints itself).
    fn due_for_checkpoint(&self, elapsed: Duration) -> Vec<u64> {
        let scenes = self.scenes.0.read().expect("lock");
        scenes
            .iter()
            .filter_map(|(&id, e)| {
                // A checkpoint in progress holds the lock and resets the time anyway.
                let mut since = e.checkpoint.try_lock().ok()?;
                if e.handle.shared.status().state == State::Running {
                    since.running += elapsed;
                }
                (since.running >= self.options.checkpoint_every || since.stepped).then_some(id)
            })
            .collect()
    }

    /// Server shutdown: checkpoints every scene (when a store keeps them), then stops
    /// every worker, which ends their frame and event streams and WebSockets.
    pub async fn shutdown(&self) {
        let ids: Vec<u64> = self.scenes.0.read().expect("lock").keys().copied().collect();
        if self.store.is_some() {
            for &id in &ids {
                match self.write_checkpoint(id).await {
                    Ok(m) => tracing::info!(scene = id, "checkpoint at step {} on shutdown", m.step),
                    Err(e) => tracing::error!(scene = id, "no checkpoint on shutdown: {e}"),
                }
            }
        }
        let entries: Vec<_> = std::mem::take(&mut *self.scenes.0.write().expect("lock")).into_values().collect();
        tokio::task::spawn_blocking(move || entries.iter().for_each(|e| e.handle.delete()))
            .await
            .expect("scene stop task");
        if let Some(store) = &self.store {
            store.db.close().await;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tunables_round_trip_through_overrides() {
        let scene = floe_engine::scene::presets::get("dam_break").unwrap();
        let changed =
            floe_engine::scene::tunable::apply(&scene, &["gravity=[0,-1,0]".into(), "fluids[0].xsph=0.2".into()])
                .unwrap();
        let json = tunables_json(&serde_json::to_string(&changed).unwrap());
        let value: Value = serde_json::from_str(&json).unwrap();
        assert_eq!(value["gravity"], serde_json::json!([0.0, -1.0, 0.0]));
        // One value per tunable: the scene has one fluid.
        assert_eq!(value.as_object().unwrap().len(), floe_engine::module::tunables(&scene).len());
        let back = floe_engine::scene::tunable::apply(&scene, &tunable_overrides(&json).unwrap()).unwrap();
        assert_eq!(back, changed);
        assert_eq!(pointer("fluids[0].viscosity"), "/fluids/0/viscosity");
        let two = serde_json::json!({ "fluids": [{}, {}] });
        assert_eq!(concrete("fluids[*].xsph", &two), ["fluids[0].xsph", "fluids[1].xsph"]);
    }
}
