//! The database: users, token hashes, quota overrides, scenes and share links, on
//! SQLite (a file in the data directory, the default) or PostgreSQL (`--database
//! postgres://...`). One code path for both: sqlx's `Any` driver with queries bound
//! at run time and portable SQL; versioned migrations (`migrations/`) run at start-up.

use sqlx::any::{AnyPoolOptions, AnyRow};
use sqlx::error::BoxDynError;
use sqlx::migrate::{Migration, MigrationSource, MigrationType, Migrator};
use sqlx::{AnyPool, Row};
use std::borrow::Cow;
use std::future::Future;
use std::pin::Pin;
use std::time::{SystemTime, UNIX_EPOCH};

pub use super::cluster::Lease;

/// The migrations, in order; a released one is never edited (its checksum is
/// recorded in the database), a change of schema is a new file.
const MIGRATIONS: &[(i64, &str, &str)] = &[
    (1, "lab", include_str!("migrations/0001_lab.sql")),
    (2, "cluster", include_str!("migrations/0002_cluster.sql")),
    (3, "cluster_live", include_str!("migrations/0003_cluster_live.sql")),
];

/// The migrations built into this binary.
#[derive(Debug)]
struct Embedded;

impl MigrationSource<'static> for Embedded {
    fn resolve(self) -> Pin<Box<dyn Future<Output = Result<Vec<Migration>, BoxDynError>> + Send>> {
        Box::pin(async {
            Ok(MIGRATIONS
                .iter()
                .map(|&(version, name, sql)| {
                    Migration::new(version, Cow::Borrowed(name), MigrationType::Simple, Cow::Borrowed(sql), false)
                })
                .collect())
        })
    }
}

/// Why a database call failed.
#[derive(Debug, thiserror::Error)]
pub enum DbError {
    /// The database refused or could not be reached.
    #[error("database: {0}")]
    Sql(#[from] sqlx::Error),
    /// A migration failed or the database's schema is newer than this build.
    #[error("database migration: {0}")]
    Migrate(#[from] sqlx::migrate::MigrateError),
    /// A user of that name exists already.
    #[error("user '{0}' exists already")]
    UserExists(String),
    /// No user has that name.
    #[error("no user named '{0}'")]
    NoUser(String),
    /// The worker no longer holds the scene (it moved to another worker).
    #[error("scene {0} is no longer held by this worker")]
    Fenced(u64),
}

/// A user as stored.
#[derive(Debug, Clone, PartialEq)]
pub struct UserRow {
    /// Login name.
    pub name: String,
    /// May call admin-only endpoints and sees every scene.
    pub admin: bool,
}

/// A scene as stored (its particle state is in checkpoint files).
#[derive(Debug, Clone, PartialEq)]
pub struct SceneRow {
    /// Scene id.
    pub id: u64,
    /// The user who created it.
    pub owner: String,
    /// Scene name.
    pub name: String,
    /// The resolved scene at creation (JSON).
    pub spec: String,
    /// The tunable settings now: a JSON object of path -> value.
    pub tunables: String,
    /// `paused`, `running` or `halted` when last recorded.
    pub state: String,
    /// The real-time factor of the last run.
    pub real_time_factor: f64,
    /// Particles (placement and the cluster's running quotas count them).
    pub particles: u64,
    /// The worker holding it in a cluster; `None` on a single server.
    pub lease: Option<Lease>,
    /// How many times it moved between workers (its checkpoints' generation).
    pub generation: u64,
}

/// Everything the server keeps in memory to authenticate and apply quotas, read at once.
#[derive(Debug, Clone, Default)]
pub struct DirectoryRows {
    /// [`Database::directory_version`] when read.
    pub version: i64,
    /// Users.
    pub users: Vec<UserRow>,
    /// (token hash, user).
    pub tokens: Vec<(String, String)>,
    /// (user, quota name, value).
    pub quotas: Vec<(String, String, i64)>,
    /// (share hash, scene id).
    pub shares: Vec<(String, u64)>,
}

/// A connection pool with the schema migrated.
#[derive(Debug, Clone)]
pub struct Database {
    pub(super) pool: AnyPool,
}

pub(super) fn now() -> i64 {
    SystemTime::now().duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs() as i64)
}

/// Scene ids are u64 in the API and BIGINT (i64) in SQL; ids stay far below 2^63.
pub(super) fn id(v: u64) -> i64 {
    i64::try_from(v).expect("scene ids stay below 2^63")
}

impl Database {
    /// Connects to `url` (`sqlite://PATH?mode=rwc` or `postgres://...`) and brings its
    /// schema up to date.
    pub async fn open(url: &str) -> Result<Self, DbError> {
        sqlx::any::install_default_drivers();
        let sqlite = url.starts_with("sqlite:");
        let pool = AnyPoolOptions::new()
            // SQLite serialises writers anyway; one connection avoids busy waits.
            .max_connections(if sqlite { 1 } else { 8 })
            // A PostgreSQL server that went away fails a call within seconds, so the
            // maintenance loop (heartbeats) comes round and retries, instead of one
            // call waiting out the default 30 s while the server is back.
            .acquire_timeout(std::time::Duration::from_secs(if sqlite { 30 } else { 3 }))
            .after_connect(move |conn, _| {
                Box::pin(async move {
                    if sqlite {
                        // Durable after each commit, and readable by `floe admin` while
                        // the server writes.
                        sqlx::query("PRAGMA journal_mode = WAL").execute(&mut *conn).await?;
                        sqlx::query("PRAGMA synchronous = FULL").execute(&mut *conn).await?;
                        sqlx::query("PRAGMA busy_timeout = 10000").execute(&mut *conn).await?;
                    }
                    Ok(())
                })
            })
            .connect(url)
            .await?;
        Migrator::new(Embedded).await?.run(&pool).await?;
        Ok(Self { pool })
    }

    /// Closes every connection.
    pub async fn close(&self) {
        self.pool.close().await;
    }

    async fn bump_directory(&self) -> Result<(), DbError> {
        sqlx::query("UPDATE meta SET value = value + 1 WHERE name = 'directory_version'").execute(&self.pool).await?;
        Ok(())
    }

    /// Adds a user.
    pub async fn add_user(&self, name: &str, admin: bool) -> Result<(), DbError> {
        let exists =
            sqlx::query("SELECT name FROM users WHERE name = $1").bind(name).fetch_optional(&self.pool).await?;
        if exists.is_some() {
            return Err(DbError::UserExists(name.into()));
        }
        sqlx::query("INSERT INTO users (name, admin, created_at) VALUES ($1, $2, $3)")
            .bind(name)
            .bind(i64::from(admin))
            .bind(now())
            .execute(&self.pool)
            .await?;
        self.bump_directory().await
    }

    /// Removes a user with their tokens and quota overrides (their scenes stay, for
    /// an admin to delete or keep).
    pub async fn remove_user(&self, name: &str) -> Result<(), DbError> {
        let mut tx = self.pool.begin().await?;
        sqlx::query("DELETE FROM tokens WHERE user_name = $1").bind(name).execute(&mut *tx).await?;
        sqlx::query("DELETE FROM quotas WHERE user_name = $1").bind(name).execute(&mut *tx).await?;
        let gone = sqlx::query("DELETE FROM users WHERE name = $1").bind(name).execute(&mut *tx).await?;
        if gone.rows_affected() == 0 {
            return Err(DbError::NoUser(name.into()));
        }
        tx.commit().await?;
        self.bump_directory().await
    }

    /// Every user, by name.
    pub async fn users(&self) -> Result<Vec<UserRow>, DbError> {
        let rows = sqlx::query("SELECT name, admin FROM users ORDER BY name").fetch_all(&self.pool).await?;
        rows.iter().map(user_row).collect()
    }

    /// Replaces every token of `user` by one with this hash (none: revokes them all).
    pub async fn replace_tokens(&self, user: &str, hash: Option<&str>) -> Result<(), DbError> {
        let mut tx = self.pool.begin().await?;
        let known = sqlx::query("SELECT name FROM users WHERE name = $1").bind(user).fetch_optional(&mut *tx).await?;
        if known.is_none() {
            return Err(DbError::NoUser(user.into()));
        }
        sqlx::query("DELETE FROM tokens WHERE user_name = $1").bind(user).execute(&mut *tx).await?;
        if let Some(hash) = hash {
            sqlx::query("INSERT INTO tokens (hash, user_name, created_at) VALUES ($1, $2, $3)")
                .bind(hash)
                .bind(user)
                .bind(now())
                .execute(&mut *tx)
                .await?;
        }
        tx.commit().await?;
        self.bump_directory().await
    }

    /// Sets (`Some`) or removes (`None`) a user's override of one quota.
    pub async fn set_quota(&self, user: &str, quota: &str, value: Option<i64>) -> Result<(), DbError> {
        let known = sqlx::query("SELECT name FROM users WHERE name = $1").bind(user).fetch_optional(&self.pool).await?;
        if known.is_none() {
            return Err(DbError::NoUser(user.into()));
        }
        match value {
            Some(v) => {
                sqlx::query(
                    "INSERT INTO quotas (user_name, quota, value) VALUES ($1, $2, $3) \
                     ON CONFLICT (user_name, quota) DO UPDATE SET value = excluded.value",
                )
                .bind(user)
                .bind(quota)
                .bind(v)
                .execute(&self.pool)
                .await?
            }
            None => {
                sqlx::query("DELETE FROM quotas WHERE user_name = $1 AND quota = $2")
                    .bind(user)
                    .bind(quota)
                    .execute(&self.pool)
                    .await?
            }
        };
        self.bump_directory().await
    }

    /// The version of users, tokens, quotas and shares: it changes with each of them.
    pub async fn directory_version(&self) -> Result<i64, DbError> {
        let row = sqlx::query("SELECT value FROM meta WHERE name = 'directory_version'").fetch_one(&self.pool).await?;
        Ok(row.try_get("value")?)
    }

    /// Users, tokens, quotas and shares, as of one version.
    pub async fn directory(&self) -> Result<DirectoryRows, DbError> {
        let mut tx = self.pool.begin().await?;
        let version: i64 = sqlx::query("SELECT value FROM meta WHERE name = 'directory_version'")
            .fetch_one(&mut *tx)
            .await?
            .try_get("value")?;
        let users = sqlx::query("SELECT name, admin FROM users").fetch_all(&mut *tx).await?;
        let tokens = sqlx::query("SELECT hash, user_name FROM tokens").fetch_all(&mut *tx).await?;
        let quotas = sqlx::query("SELECT user_name, quota, value FROM quotas").fetch_all(&mut *tx).await?;
        let shares = sqlx::query("SELECT hash, scene_id FROM shares").fetch_all(&mut *tx).await?;
        tx.commit().await?;
        Ok(DirectoryRows {
            version,
            users: users.iter().map(user_row).collect::<Result<_, _>>()?,
            tokens: tokens
                .iter()
                .map(|r| Ok((r.try_get("hash")?, r.try_get("user_name")?)))
                .collect::<Result<_, sqlx::Error>>()?,
            quotas: quotas
                .iter()
                .map(|r| Ok((r.try_get("user_name")?, r.try_get("quota")?, r.try_get("value")?)))
                .collect::<Result<_, sqlx::Error>>()?,
            shares: shares
                .iter()
                .map(|r| Ok((r.try_get("hash")?, r.try_get::<i64, _>("scene_id")? as u64)))
                .collect::<Result<_, sqlx::Error>>()?,
        })
    }

    /// The id the next scene gets: above every id ever given.
    pub async fn next_scene_id(&self) -> Result<u64, DbError> {
        let row = sqlx::query("SELECT value FROM meta WHERE name = 'next_scene_id'").fetch_one(&self.pool).await?;
        Ok(row.try_get::<i64, _>("value")? as u64)
    }

    /// Records a new scene (and that its id is taken).
    pub async fn insert_scene(&self, s: &SceneRow) -> Result<(), DbError> {
        let mut tx = self.pool.begin().await?;
        sqlx::query(
            "INSERT INTO scenes (id, owner, name, spec, tunables, state, real_time_factor, created_at, updated_at, \
             particles, worker, epoch) VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $8, $9, $10, $11)",
        )
        .bind(id(s.id))
        .bind(&s.owner)
        .bind(&s.name)
        .bind(&s.spec)
        .bind(&s.tunables)
        .bind(&s.state)
        .bind(s.real_time_factor)
        .bind(now())
        .bind(id(s.particles))
        .bind(s.lease.as_ref().map(|l| l.worker.clone()))
        .bind(s.lease.as_ref().map_or(0, |l| l.epoch))
        .execute(&mut *tx)
        .await?;
        sqlx::query("UPDATE meta SET value = $1 WHERE name = 'next_scene_id' AND value < $1")
            .bind(id(s.id + 1))
            .execute(&mut *tx)
            .await?;
        if let Some(lease) = &s.lease {
            // The room its placement reserved is the scene's own now.
            sqlx::query(
                "DELETE FROM reservations WHERE id = (SELECT MIN(id) FROM reservations WHERE worker = $1 \
                 AND epoch = $2 AND particles = $3)",
            )
            .bind(&lease.worker)
            .bind(lease.epoch)
            .bind(id(s.particles))
            .execute(&mut *tx)
            .await?;
        }
        tx.commit().await?;
        Ok(())
    }

    /// The placement generation of `scene` (its checkpoints carry it) while `lease`
    /// holds it; `None` once it moved or is gone. Asked before each checkpoint.
    pub async fn generation(&self, scene: u64, lease: Option<&Lease>) -> Result<Option<u64>, DbError> {
        let sql = format!("SELECT generation FROM scenes WHERE {}", held_at(1));
        let row = bind_held(sqlx::query(&sql), scene, lease).fetch_optional(&self.pool).await?;
        Ok(row.map(|r| r.try_get::<i64, _>("generation")).transpose()?.map(|g| g as u64))
    }

    /// Records a scene's live settings; with a lease, only while it holds the scene.
    pub async fn update_tunables(&self, scene: u64, lease: Option<&Lease>, tunables: &str) -> Result<(), DbError> {
        let sql = format!("UPDATE scenes SET tunables = $1, updated_at = $2 WHERE {}", held_at(3));
        let query = sqlx::query(&sql).bind(tunables).bind(now());
        let done = bind_held(query, scene, lease).execute(&self.pool).await?;
        held(scene, lease, done.rows_affected())
    }

    /// Records a scene's run state; with a lease, only while it holds the scene.
    pub async fn update_state(
        &self,
        scene: u64,
        lease: Option<&Lease>,
        state: &str,
        real_time_factor: f64,
    ) -> Result<(), DbError> {
        let sql = format!("UPDATE scenes SET state = $1, real_time_factor = $2, updated_at = $3 WHERE {}", held_at(4));
        let query = sqlx::query(&sql).bind(state).bind(real_time_factor).bind(now());
        let done = bind_held(query, scene, lease).execute(&self.pool).await?;
        held(scene, lease, done.rows_affected())
    }

    /// Forgets a scene and its share links; with a lease, only while it holds the scene.
    pub async fn delete_scene(&self, scene: u64, lease: Option<&Lease>) -> Result<(), DbError> {
        let mut tx = self.pool.begin().await?;
        let shares = sqlx::query("DELETE FROM shares WHERE scene_id = $1").bind(id(scene)).execute(&mut *tx).await?;
        let sql = format!("DELETE FROM scenes WHERE {}", held_at(1));
        let gone = bind_held(sqlx::query(&sql), scene, lease).execute(&mut *tx).await?;
        // A fenced delete returns before the commit: the share links stay too.
        held(scene, lease, gone.rows_affected())?;
        tx.commit().await?;
        if shares.rows_affected() > 0 {
            self.bump_directory().await?;
        }
        Ok(())
    }

    /// Every scene, by id.
    pub async fn scenes(&self) -> Result<Vec<SceneRow>, DbError> {
        let rows =
            sqlx::query(&format!("SELECT {SCENE_COLUMNS} FROM scenes ORDER BY id")).fetch_all(&self.pool).await?;
        rows.iter().map(scene_row).collect::<Result<_, sqlx::Error>>().map_err(DbError::from)
    }

    /// Adds a share link of `scene` with this token hash.
    pub async fn add_share(&self, scene: u64, hash: &str) -> Result<(), DbError> {
        sqlx::query("INSERT INTO shares (hash, scene_id, created_at) VALUES ($1, $2, $3)")
            .bind(hash)
            .bind(id(scene))
            .bind(now())
            .execute(&self.pool)
            .await?;
        self.bump_directory().await
    }

    /// Revokes the share links of `scene` whose hash starts with `prefix` (a share's
    /// id, hex digits only); returns how many.
    pub async fn remove_shares(&self, scene: u64, prefix: &str) -> Result<u64, DbError> {
        debug_assert!(prefix.bytes().all(|b| b.is_ascii_hexdigit()), "a share id is hex");
        let removed = sqlx::query("DELETE FROM shares WHERE scene_id = $1 AND hash LIKE $2")
            .bind(id(scene))
            .bind(format!("{prefix}%"))
            .execute(&self.pool)
            .await?
            .rows_affected();
        if removed > 0 {
            self.bump_directory().await?;
        }
        Ok(removed)
    }
}

/// The columns [`scene_row`] reads.
pub(super) const SCENE_COLUMNS: &str =
    "id, owner, name, spec, tunables, state, real_time_factor, particles, worker, epoch, generation";

/// A scene row read with [`SCENE_COLUMNS`].
pub(super) fn scene_row(r: &AnyRow) -> Result<SceneRow, sqlx::Error> {
    let worker: Option<String> = r.try_get("worker")?;
    Ok(SceneRow {
        id: r.try_get::<i64, _>("id")? as u64,
        owner: r.try_get("owner")?,
        name: r.try_get("name")?,
        spec: r.try_get("spec")?,
        tunables: r.try_get("tunables")?,
        state: r.try_get("state")?,
        real_time_factor: r.try_get("real_time_factor")?,
        particles: r.try_get::<i64, _>("particles")? as u64,
        lease: worker.map(|worker| Ok::<_, sqlx::Error>(Lease { worker, epoch: r.try_get("epoch")? })).transpose()?,
        generation: r.try_get::<i64, _>("generation")? as u64,
    })
}

/// The condition of a write for a scene that holds, with a lease, only while that
/// lease holds the scene: parameters `$n` (scene id), `$n+1` (worker, NULL without
/// a lease) and `$n+2` (epoch), bound by [`bind_held`].
fn held_at(n: usize) -> String {
    format!("id = ${n} AND (${w} IS NULL OR (worker = ${w} AND epoch = ${e}))", w = n + 1, e = n + 2)
}

/// Binds [`held_at`]'s parameters.
fn bind_held<'q>(
    query: sqlx::query::Query<'q, sqlx::Any, sqlx::any::AnyArguments<'q>>,
    scene: u64,
    lease: Option<&Lease>,
) -> sqlx::query::Query<'q, sqlx::Any, sqlx::any::AnyArguments<'q>> {
    query.bind(id(scene)).bind(lease.map(|l| l.worker.clone())).bind(lease.map_or(0, |l| l.epoch))
}

/// A fenced write's outcome: with a lease, nothing written means the scene moved.
fn held(scene: u64, lease: Option<&Lease>, rows: u64) -> Result<(), DbError> {
    if lease.is_some() && rows == 0 { Err(DbError::Fenced(scene)) } else { Ok(()) }
}

fn user_row(r: &AnyRow) -> Result<UserRow, DbError> {
    Ok(UserRow { name: r.try_get("name")?, admin: r.try_get::<i64, _>("admin")? != 0 })
}
