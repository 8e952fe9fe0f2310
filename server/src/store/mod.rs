//! What survives a restart: a data directory holding the database (SQLite by
//! default, or a PostgreSQL URL) and the checkpoint files beside it.
//!
//! ```text
//! DATA_DIR/
//!   floe.db, floe.db-wal, floe.db-shm   (SQLite; absent with --database postgres://...)
//!   checkpoints/<scene id>/checkpoint-<generation>-<sequence>.bin
//!   lock                                 (held by the serving process)
//!   lock-<worker>                        (in a cluster: held by each worker)
//! ```
//!
//! - [`db`]: users, token hashes, quotas, scenes and share links.
//! - [`checkpoint`]: checkpoint files, written atomically, checked by checksum.
//! - [`cluster`]: a cluster's workers, leases and placements, fenced by epoch.

pub mod checkpoint;
pub mod cluster;
pub mod db;

pub use checkpoint::Checkpoints;
pub use db::Database;
use std::path::{Path, PathBuf};

/// Where the data lives, from the command line.
#[derive(Debug, Clone)]
pub struct Location {
    /// The data directory (created if missing).
    pub data_dir: PathBuf,
    /// A database URL; `None` is `DATA_DIR/floe.db` (SQLite).
    pub database: Option<String>,
}

impl Location {
    /// The database URL.
    pub fn database_url(&self) -> String {
        match &self.database {
            Some(url) => url.clone(),
            None => sqlite_url(&self.data_dir.join("floe.db")),
        }
    }

    /// The database URL with any password replaced by `***`, for logs.
    pub fn database_display(&self) -> String {
        let url = self.database_url();
        match (url.find("://"), url.rfind('@')) {
            (Some(s), Some(at)) if at > s => match url[s + 3..at].find(':') {
                Some(colon) => format!("{}:***{}", &url[..s + 3 + colon], &url[at..]),
                None => url,
            },
            _ => url,
        }
    }

    /// Creates the data directory and opens the database (for `floe admin`, which may
    /// run beside a serving process).
    pub async fn open_database(&self) -> anyhow::Result<Database> {
        std::fs::create_dir_all(&self.data_dir)
            .map_err(|e| anyhow::anyhow!("cannot create the data directory {}: {e}", self.data_dir.display()))?;
        Database::open(&self.database_url()).await.map_err(|e| anyhow::anyhow!("{e} ({})", self.database_display()))
    }
}

/// A file URL for SQLite: the path with `%`, `?` and `#` escaped, created if missing.
fn sqlite_url(path: &Path) -> String {
    let mut escaped = String::new();
    for c in path.to_string_lossy().chars() {
        match c {
            '%' => escaped.push_str("%25"),
            '?' => escaped.push_str("%3F"),
            '#' => escaped.push_str("%23"),
            c => escaped.push(c),
        }
    }
    format!("sqlite://{escaped}?mode=rwc")
}

/// The database and checkpoints of a serving process, which holds the data
/// directory's lock: two servers on one directory would overwrite each other's
/// checkpoints. A cluster's workers share the directory, each holding its own
/// name's lock, and write only the checkpoints of the scenes they hold.
#[derive(Debug)]
pub struct Store {
    /// The database.
    pub db: Database,
    /// The checkpoint files.
    pub checkpoints: Checkpoints,
    _lock: std::fs::File,
}

impl Store {
    /// Opens (creating) the data directory and the database, and takes the lock: the
    /// directory's, or in a cluster (`worker`), that worker name's.
    pub async fn open(location: &Location, worker: Option<&str>) -> anyhow::Result<Self> {
        let db = location.open_database().await?;
        let lock_path = match worker {
            Some(name) => location.data_dir.join(format!("lock-{name}")),
            None => location.data_dir.join("lock"),
        };
        let lock = std::fs::OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&lock_path)
            .map_err(|e| anyhow::anyhow!("cannot open {}: {e}", lock_path.display()))?;
        if lock.try_lock().is_err() {
            match worker {
                Some(name) => anyhow::bail!(
                    "worker {name} is already running on {}; give each worker its own --worker name",
                    location.data_dir.display()
                ),
                None => anyhow::bail!(
                    "the data directory {} is in use by another floe serve; give each server its own --data-dir",
                    location.data_dir.display()
                ),
            }
        }
        let checkpoints = Checkpoints::open(location.data_dir.join("checkpoints"))?;
        // In a shared directory another worker may be mid-write: a temporary file left
        // by a crash is overwritten by the next checkpoint of its scene instead.
        if worker.is_none() {
            checkpoints.remove_partial_writes();
        }
        Ok(Self { db, checkpoints, _lock: lock })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn urls() {
        let l = Location { data_dir: "/var/lib/floe 1#".into(), database: None };
        assert_eq!(l.database_url(), "sqlite:///var/lib/floe 1%23/floe.db?mode=rwc");
        let l = Location { data_dir: "d".into(), database: Some("postgres://floe:secret@db:5432/floe".into()) };
        assert_eq!(l.database_display(), "postgres://floe:***@db:5432/floe");
    }
}
