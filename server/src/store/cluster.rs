//! The database's cluster rows: workers with their epochs and heartbeats, and each
//! scene's placement (the worker and epoch holding it). Every statement is portable
//! SQL, so the rules are tested on SQLite as well as PostgreSQL, though a cluster
//! runs on PostgreSQL only (its workers are on several machines).
//!
//! Fencing: a worker's epoch is new at each start and unique over the cluster. A
//! scene is held by `(worker, epoch)`, and every write for it names both, so a
//! worker whose scenes were moved while it was silent (stopped, cut off) writes
//! nothing for them: its writes match no row. Its heartbeat matches no row either
//! once others have declared it gone, which is how it learns.

use super::Database;
use super::db::{DbError, SCENE_COLUMNS, SceneRow, id, now, scene_row};
use crate::cluster::placement::{self, Candidate};
use sqlx::Row;

/// What a worker holds a scene by: its name and its epoch.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Lease {
    /// Worker name.
    pub worker: String,
    /// The worker's epoch when it took the scene.
    pub epoch: i64,
}

/// What a worker says about itself when it joins.
#[derive(Debug, Clone, PartialEq)]
pub struct WorkerInfo {
    /// Worker name (`--worker`).
    pub name: String,
    /// Where its gRPC is reached.
    pub grpc: String,
    /// Where its HTTP is reached.
    pub http: String,
    /// `gpu` or `cpu`.
    pub backend: String,
    /// Its `--max-scenes`.
    pub max_scenes: u64,
    /// Its `--max-particles`, a budget over all its scenes.
    pub max_particles: u64,
}

/// A worker as recorded, with what it holds.
#[derive(Debug, Clone, PartialEq)]
pub struct WorkerRow {
    /// What it said when it joined.
    pub info: WorkerInfo,
    /// Its epoch now.
    pub epoch: i64,
    /// Heartbeats so far this epoch.
    pub beats: i64,
    /// Taking no new scenes, handing its own to others.
    pub draining: bool,
    /// Scenes it holds.
    pub scenes: u64,
    /// Particles over those scenes.
    pub particles: u64,
    /// Placements on it whose scenes have no row yet: how many, and their particles.
    pub reserved: (u64, u64),
    /// Its scenes' figures as of its last heartbeat (JSON, what it published).
    pub live: String,
}

impl WorkerRow {
    /// The worker as placement sees it: the room reserved for scenes on their way
    /// counts as taken.
    pub fn candidate(&self) -> Candidate {
        Candidate {
            name: self.info.name.clone(),
            backend: self.info.backend.clone(),
            max_scenes: self.info.max_scenes,
            max_particles: self.info.max_particles,
            scenes: self.scenes + self.reserved.0,
            particles: self.particles + self.reserved.1,
            draining: self.draining,
        }
    }

    /// Its lease on scenes.
    pub fn lease(&self) -> Lease {
        Lease { worker: self.info.name.clone(), epoch: self.epoch }
    }
}

/// A scene moved off a silent or draining worker.
#[derive(Debug, Clone, PartialEq)]
pub struct Moved {
    /// Scene id.
    pub scene: u64,
    /// Where it went.
    pub to: Lease,
}

/// Every worker with its scenes and the room reserved on it, in one statement: a
/// scene's row replaces its reservation in one transaction, so reading both at once
/// counts it exactly once.
const WORKERS: &str = "SELECT w.name, w.epoch, w.grpc, w.http, w.backend, w.max_scenes, w.max_particles, w.beats, \
     w.draining, w.live, COUNT(s.id) AS scenes, CAST(COALESCE(SUM(s.particles), 0) AS BIGINT) AS particles, \
     (SELECT COUNT(r.id) FROM reservations r WHERE r.worker = w.name AND r.epoch = w.epoch \
      AND w.beats < r.until_beats) AS reserved_scenes, \
     (SELECT CAST(COALESCE(SUM(r.particles), 0) AS BIGINT) FROM reservations r WHERE r.worker = w.name \
      AND r.epoch = w.epoch AND w.beats < r.until_beats) AS reserved_particles \
     FROM workers w LEFT JOIN scenes s ON s.worker = w.name AND s.epoch = w.epoch \
     GROUP BY w.name, w.epoch, w.grpc, w.http, w.backend, w.max_scenes, w.max_particles, w.beats, w.draining, w.live \
     ORDER BY w.name";

/// How many of its own heartbeats (about a second each) a worker's reservation
/// lasts if its scene never arrives: long enough to build a large scene.
pub const RESERVED_BEATS: i64 = 30;

fn worker_row(r: &sqlx::any::AnyRow) -> Result<WorkerRow, sqlx::Error> {
    Ok(WorkerRow {
        info: WorkerInfo {
            name: r.try_get("name")?,
            grpc: r.try_get("grpc")?,
            http: r.try_get("http")?,
            backend: r.try_get("backend")?,
            max_scenes: r.try_get::<i64, _>("max_scenes")? as u64,
            max_particles: r.try_get::<i64, _>("max_particles")? as u64,
        },
        epoch: r.try_get("epoch")?,
        beats: r.try_get("beats")?,
        draining: r.try_get::<i64, _>("draining")? != 0,
        scenes: r.try_get::<i64, _>("scenes")? as u64,
        particles: r.try_get::<i64, _>("particles")? as u64,
        reserved: (r.try_get::<i64, _>("reserved_scenes")? as u64, r.try_get::<i64, _>("reserved_particles")? as u64),
        live: r.try_get("live")?,
    })
}

/// Every worker up, with the room reserved on it, on one connection (a pool's or
/// a placement's transaction).
async fn workers_on(c: &mut sqlx::AnyConnection) -> Result<Vec<WorkerRow>, DbError> {
    let rows = sqlx::query(WORKERS).fetch_all(&mut *c).await?;
    Ok(rows.iter().map(worker_row).collect::<Result<_, _>>()?)
}

/// Takes the next value of the counter `name` in `meta` (epochs, scene ids,
/// reservations): its row stays locked until the transaction ends, so whoever takes
/// it next waits.
async fn take(c: &mut sqlx::AnyConnection, name: &str) -> Result<i64, DbError> {
    sqlx::query("UPDATE meta SET value = value + 1 WHERE name = $1").bind(name).execute(&mut *c).await?;
    let row = sqlx::query("SELECT value - 1 AS taken FROM meta WHERE name = $1").bind(name).fetch_one(&mut *c).await?;
    Ok(row.try_get("taken")?)
}

/// Where [`Database::place`] put a new scene.
#[derive(Debug, Clone, PartialEq)]
pub enum Placement {
    /// On this worker, whose room is reserved until the scene's row is inserted.
    On(String),
    /// No worker can take it now; each one's reason.
    Refused(String),
    /// No worker of the cluster runs the backend it asks for; the backends they run.
    Unserved(String),
}

fn size(v: u64) -> i64 {
    i64::try_from(v).unwrap_or(i64::MAX)
}

impl Database {
    /// Joins the cluster as `info.name` with a new epoch, which it returns. The scenes
    /// recorded on a previous process of the same name become this one's (that
    /// process is gone: a name is one process, `floe serve` takes a lock on it).
    pub async fn register_worker(&self, info: &WorkerInfo) -> Result<Lease, DbError> {
        let mut tx = self.pool.begin().await?;
        let epoch = take(&mut tx, "next_epoch").await?;
        sqlx::query(
            "INSERT INTO workers (name, epoch, grpc, http, backend, max_scenes, max_particles, beats, draining, \
             started_at) VALUES ($1, $2, $3, $4, $5, $6, $7, 0, 0, $8) \
             ON CONFLICT (name) DO UPDATE SET epoch = excluded.epoch, grpc = excluded.grpc, http = excluded.http, \
             backend = excluded.backend, max_scenes = excluded.max_scenes, max_particles = excluded.max_particles, \
             beats = 0, draining = 0, started_at = excluded.started_at",
        )
        .bind(&info.name)
        .bind(epoch)
        .bind(&info.grpc)
        .bind(&info.http)
        .bind(&info.backend)
        .bind(size(info.max_scenes))
        .bind(size(info.max_particles))
        .bind(now())
        .execute(&mut *tx)
        .await?;
        sqlx::query("UPDATE scenes SET epoch = $1, generation = generation + 1 WHERE worker = $2")
            .bind(epoch)
            .bind(&info.name)
            .execute(&mut *tx)
            .await?;
        tx.commit().await?;
        Ok(Lease { worker: info.name.clone(), epoch })
    }

    /// One heartbeat of `lease`'s worker, publishing its scenes' figures `live`
    /// (JSON): `Some(draining)` while the cluster still counts it, `None` once it was
    /// declared gone (its scenes are others' now).
    pub async fn heartbeat(&self, lease: &Lease, live: &str) -> Result<Option<bool>, DbError> {
        let done = sqlx::query("UPDATE workers SET beats = beats + 1, live = $3 WHERE name = $1 AND epoch = $2")
            .bind(&lease.worker)
            .bind(lease.epoch)
            .bind(live)
            .execute(&self.pool)
            .await?;
        if done.rows_affected() == 0 {
            return Ok(None);
        }
        let row = sqlx::query("SELECT draining FROM workers WHERE name = $1 AND epoch = $2")
            .bind(&lease.worker)
            .bind(lease.epoch)
            .fetch_optional(&self.pool)
            .await?;
        Ok(row.map(|r| r.try_get::<i64, _>("draining")).transpose()?.map(|d| d != 0))
    }

    /// Every worker up, by name, with the scenes and particles it holds and the room
    /// reserved on it.
    pub async fn workers(&self) -> Result<Vec<WorkerRow>, DbError> {
        workers_on(&mut *self.pool.acquire().await?).await
    }

    /// Places a new scene of `particles` by [`placement::choose`], counting the room
    /// reserved for scenes on their way, and reserves its room on the chosen worker
    /// until its row is inserted ([`Database::insert_scene`]) or for
    /// [`RESERVED_BEATS`] of that worker's heartbeats. Placements take turns (each
    /// first updates one row of `meta`), so simultaneous ones see each other.
    ///
    /// With `named` (a creation that followed a placement to that worker), that
    /// worker takes it when a reservation of this size waits there, or it has room;
    /// otherwise placement chooses among all.
    pub async fn place(
        &self,
        particles: u64,
        named: Option<&str>,
        backend: Option<&str>,
    ) -> Result<Placement, DbError> {
        let mut tx = self.pool.begin().await?;
        let reservation = take(&mut tx, "next_reservation").await?;
        sqlx::query(
            "DELETE FROM reservations WHERE NOT EXISTS (SELECT 1 FROM workers w WHERE w.name = reservations.worker \
             AND w.epoch = reservations.epoch AND w.beats < reservations.until_beats)",
        )
        .execute(&mut *tx)
        .await?;
        let workers = workers_on(&mut tx).await?;
        let named = named.and_then(|n| workers.iter().find(|w| w.info.name == n));
        if let Some(w) = named {
            let waiting =
                sqlx::query("SELECT id FROM reservations WHERE worker = $1 AND epoch = $2 AND particles = $3")
                    .bind(&w.info.name)
                    .bind(w.epoch)
                    .bind(size(particles))
                    .fetch_optional(&mut *tx)
                    .await?;
            if waiting.is_some() && backend.is_none_or(|b| b == w.info.backend) {
                tx.commit().await?;
                return Ok(Placement::On(w.info.name.clone()));
            }
        }
        if let Some(b) = backend
            && !workers.is_empty()
            && workers.iter().all(|w| w.info.backend != b)
        {
            let runs: std::collections::BTreeSet<&str> = workers.iter().map(|w| w.info.backend.as_str()).collect();
            return Ok(Placement::Unserved(runs.into_iter().collect::<Vec<_>>().join(", ")));
        }
        let candidates: Vec<Candidate> = workers.iter().map(WorkerRow::candidate).collect();
        let fits = |w: &WorkerRow| placement::choose(&[w.candidate()], particles, backend).is_ok();
        let chosen = match (named, placement::choose(&candidates, particles, backend)) {
            (Some(w), _) if fits(w) => w,
            (_, Ok(c)) => workers.iter().find(|w| w.info.name == c.name).expect("chosen among them"),
            (_, Err(why)) => return Ok(Placement::Refused(why)),
        };
        sqlx::query("INSERT INTO reservations (id, worker, epoch, particles, until_beats) VALUES ($1, $2, $3, $4, $5)")
            .bind(reservation)
            .bind(&chosen.info.name)
            .bind(chosen.epoch)
            .bind(size(particles))
            .bind(chosen.beats + RESERVED_BEATS)
            .execute(&mut *tx)
            .await?;
        tx.commit().await?;
        Ok(Placement::On(chosen.info.name.clone()))
    }

    /// Marks a worker draining (or not): it takes no new scenes and hands its own to
    /// others. False when no worker has that name.
    pub async fn set_draining(&self, worker: &str, draining: bool) -> Result<bool, DbError> {
        let done = sqlx::query("UPDATE workers SET draining = $1 WHERE name = $2")
            .bind(i64::from(draining))
            .bind(worker)
            .execute(&self.pool)
            .await?;
        Ok(done.rows_affected() > 0)
    }

    /// Takes the next scene id (ids are never reused, over the whole cluster).
    pub async fn take_scene_id(&self) -> Result<u64, DbError> {
        let mut tx = self.pool.begin().await?;
        let id = take(&mut tx, "next_scene_id").await?;
        tx.commit().await?;
        Ok(id as u64)
    }

    /// The scenes `lease` holds, by id.
    pub async fn scenes_held(&self, lease: &Lease) -> Result<Vec<SceneRow>, DbError> {
        let rows =
            sqlx::query(&format!("SELECT {SCENE_COLUMNS} FROM scenes WHERE worker = $1 AND epoch = $2 ORDER BY id"))
                .bind(&lease.worker)
                .bind(lease.epoch)
                .fetch_all(&self.pool)
                .await?;
        Ok(rows.iter().map(scene_row).collect::<Result<_, _>>()?)
    }

    /// One scene's row, if it exists.
    pub async fn scene(&self, scene: u64) -> Result<Option<SceneRow>, DbError> {
        let row = sqlx::query(&format!("SELECT {SCENE_COLUMNS} FROM scenes WHERE id = $1"))
            .bind(id(scene))
            .fetch_optional(&self.pool)
            .await?;
        Ok(row.as_ref().map(scene_row).transpose()?)
    }

    /// Scenes and particles `owner` runs over the whole cluster.
    pub async fn running_of(&self, owner: &str) -> Result<(u64, u64), DbError> {
        let row = sqlx::query(
            "SELECT COUNT(id) AS scenes, CAST(COALESCE(SUM(particles), 0) AS BIGINT) AS particles FROM scenes \
             WHERE owner = $1 AND state = 'running'",
        )
        .bind(owner)
        .fetch_one(&self.pool)
        .await?;
        Ok((row.try_get::<i64, _>("scenes")? as u64, row.try_get::<i64, _>("particles")? as u64))
    }

    /// Scenes `owner` has over the whole cluster.
    pub async fn scenes_of(&self, owner: &str) -> Result<u64, DbError> {
        let row = sqlx::query("SELECT COUNT(id) AS scenes FROM scenes WHERE owner = $1")
            .bind(owner)
            .fetch_one(&self.pool)
            .await?;
        Ok(row.try_get::<i64, _>("scenes")? as u64)
    }

    /// Declares the worker `gone` (as of its epoch) out of the cluster: its scenes are
    /// left without a worker, for [`Database::place_orphans`]. False if the worker has
    /// a newer epoch since (it restarted) or another worker evicted it first: the
    /// delete of its row decides.
    pub async fn evict(&self, gone: &Lease) -> Result<bool, DbError> {
        let deleted = sqlx::query("DELETE FROM workers WHERE name = $1 AND epoch = $2")
            .bind(&gone.worker)
            .bind(gone.epoch)
            .execute(&self.pool)
            .await?;
        Ok(deleted.rows_affected() > 0)
    }

    /// Moves `scene` from `from` (a draining worker) to a worker placement picks,
    /// paused; `None` when no other worker can take it or `from` no longer holds it.
    pub async fn hand_over(&self, from: &Lease, scene: u64, particles: u64) -> Result<Option<Lease>, DbError> {
        let workers = self.workers().await?;
        let others: Vec<Candidate> =
            workers.iter().filter(|w| w.info.name != from.worker).map(WorkerRow::candidate).collect();
        let Ok(to) = placement::choose(&others, particles, None) else { return Ok(None) };
        let to = workers.iter().find(|w| w.info.name == to.name).expect("chosen among them").lease();
        let done = sqlx::query(
            "UPDATE scenes SET worker = $1, epoch = $2, state = 'paused', real_time_factor = 0, \
             generation = generation + 1 \
             WHERE id = $3 AND worker = $4 AND epoch = $5",
        )
        .bind(&to.worker)
        .bind(to.epoch)
        .bind(id(scene))
        .bind(&from.worker)
        .bind(from.epoch)
        .execute(&self.pool)
        .await?;
        Ok((done.rows_affected() > 0).then_some(to))
    }

    /// Places every scene whose worker is no longer up (evicted, or a single server's
    /// scene in a database turned cluster) on a worker that is, one at a time so
    /// each placement sees the ones before it.
    pub async fn place_orphans(&self) -> Result<Vec<Moved>, DbError> {
        let rows = sqlx::query(&format!(
            "SELECT {SCENE_COLUMNS} FROM scenes s WHERE NOT EXISTS \
             (SELECT 1 FROM workers w WHERE w.name = s.worker AND w.epoch = s.epoch) ORDER BY id"
        ))
        .fetch_all(&self.pool)
        .await?;
        let orphans: Vec<SceneRow> = rows.iter().map(scene_row).collect::<Result<_, _>>()?;
        let mut moved = Vec::new();
        for scene in orphans {
            let workers = self.workers().await?;
            let candidates: Vec<Candidate> = workers.iter().map(WorkerRow::candidate).collect();
            let to = match placement::choose(&candidates, scene.particles, None) {
                Ok(c) => workers.iter().find(|w| w.info.name == c.name).expect("chosen among them").lease(),
                Err(why) => {
                    tracing::warn!(scene = scene.id, "scene waits for a worker: {why}");
                    continue;
                }
            };
            let done = sqlx::query(
                "UPDATE scenes SET worker = $1, epoch = $2, state = 'paused', real_time_factor = 0, \
             generation = generation + 1 \
                 WHERE id = $3 AND worker IS NOT DISTINCT FROM $4 AND epoch = $5",
            )
            .bind(&to.worker)
            .bind(to.epoch)
            .bind(id(scene.id))
            .bind(scene.lease.as_ref().map(|l| l.worker.clone()))
            .bind(scene.lease.as_ref().map_or(0, |l| l.epoch))
            .execute(&self.pool)
            .await?;
            if done.rows_affected() > 0 {
                moved.push(Moved { scene: scene.id, to });
            }
        }
        Ok(moved)
    }
}

#[cfg(test)]
mod tests;
