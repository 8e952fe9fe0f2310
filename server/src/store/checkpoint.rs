//! Checkpoint files: a scene's snapshot (opaque bytes from the engine) behind a header
//! with a SHA-256 checksum, one directory per scene, the newest two kept.
//!
//! Layout (little-endian): magic `FLOECKPT`, file format version (u32), scene id,
//! checkpoint sequence, step (u64 each), simulated time (f64 bits), payload length
//! (u64), SHA-256 of everything before it and of the payload, then the payload.
//!
//! A checkpoint is written atomically: a temporary file is written and fsynced, renamed
//! over its final name, and the directory fsynced, so after a crash (kill -9, power
//! loss) a checkpoint file is either whole or absent. Damage found later (a bad disk, a
//! truncated copy) fails the checksum and the previous checkpoint is used.
//!
//! A file's name carries the scene's placement generation (the database counts the
//! scene's moves between cluster workers) before its sequence, and files rank by
//! both: a worker that lost a scene while stopped and names a file after it resumes
//! names one of an older generation, which never ranks above those of the scene's
//! new worker (which writes one as soon as it takes the scene up).

use sha2::{Digest, Sha256};
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

const MAGIC: &[u8; 8] = b"FLOECKPT";
const VERSION: u32 = 1;
/// Magic, version, scene, sequence, step, time, payload length.
const FIELDS: usize = 8 + 4 + 8 * 5;
const HEADER: usize = FIELDS + 32;
/// How many checkpoints of a scene are kept.
pub const KEPT: usize = 2;

/// What a checkpoint says about itself.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Meta {
    /// Scene id.
    pub scene: u64,
    /// Counts up by one per checkpoint of the scene.
    pub sequence: u64,
    /// Step it was taken at.
    pub step: u64,
    /// Simulated time (s).
    pub time: f64,
}

/// A checkpoint file that could not be used.
#[derive(Debug, thiserror::Error)]
pub enum CheckpointError {
    /// Reading or writing failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// Not written: the scene is no longer this worker's (its tenure lapsed).
    #[error("the checkpoint of scene {0} was withdrawn: this worker may no longer hold the scene")]
    Withdrawn(u64),
    /// The file is not a whole, undamaged checkpoint.
    #[error("{path}: {reason}")]
    Damaged {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
}

/// The checkpoint directory of a server.
#[derive(Debug, Clone)]
pub struct Checkpoints {
    root: PathBuf,
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> CheckpointError + '_ {
    move |source| CheckpointError::Io { path: path.into(), source }
}

/// The file's bytes for `payload`.
pub fn encode(meta: &Meta, payload: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER + payload.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    for v in [meta.scene, meta.sequence, meta.step, meta.time.to_bits(), payload.len() as u64] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    let sum = Sha256::new().chain_update(&out).chain_update(payload).finalize();
    out.extend_from_slice(&sum);
    out.extend_from_slice(payload);
    out
}

/// The header and payload of a checkpoint file's bytes, checked whole and undamaged.
pub fn decode(bytes: &[u8]) -> Result<(Meta, &[u8]), String> {
    if bytes.len() < HEADER {
        return Err(format!("cut short: {} bytes, a header alone is {HEADER}", bytes.len()));
    }
    if &bytes[..8] != MAGIC {
        return Err("not a checkpoint (no FLOECKPT magic)".into());
    }
    let u64_at = |k: usize| u64::from_le_bytes(bytes[12 + 8 * k..20 + 8 * k].try_into().expect("8 bytes"));
    let version = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
    if version != VERSION {
        return Err(format!("checkpoint format version {version}; this build reads {VERSION}"));
    }
    let meta = Meta { scene: u64_at(0), sequence: u64_at(1), step: u64_at(2), time: f64::from_bits(u64_at(3)) };
    let length = u64_at(4);
    let payload = &bytes[HEADER..];
    if payload.len() as u64 != length {
        return Err(format!("cut short or padded: the payload is {} bytes, the header says {length}", payload.len()));
    }
    let sum = Sha256::new().chain_update(&bytes[..FIELDS]).chain_update(payload).finalize();
    if sum.as_slice() != &bytes[FIELDS..HEADER] {
        return Err("checksum mismatch: the file is damaged".into());
    }
    Ok((meta, payload))
}

impl Checkpoints {
    /// Checkpoints under `root` (created if missing).
    pub fn open(root: PathBuf) -> Result<Self, CheckpointError> {
        fs::create_dir_all(&root).map_err(io(&root))?;
        Ok(Self { root })
    }

    fn dir(&self, scene: u64) -> PathBuf {
        self.root.join(scene.to_string())
    }

    /// The checkpoint files of `scene`, newest first, each with its rank: its
    /// placement generation and sequence (a name without a generation, as written
    /// before generations were, is of generation 0).
    pub fn files(&self, scene: u64) -> Vec<((u64, u64), PathBuf)> {
        let Ok(entries) = fs::read_dir(self.dir(scene)) else { return Vec::new() };
        let mut files: Vec<((u64, u64), PathBuf)> = entries
            .filter_map(|e| e.ok())
            .filter_map(|e| {
                let name = e.file_name().into_string().ok()?;
                let rank = name.strip_prefix("checkpoint-")?.strip_suffix(".bin")?;
                let rank = match rank.split_once('-') {
                    Some((generation, seq)) => (generation.parse().ok()?, seq.parse().ok()?),
                    None => (0, rank.parse().ok()?),
                };
                Some((rank, e.path()))
            })
            .collect();
        files.sort_by_key(|f| std::cmp::Reverse(f.0));
        files
    }

    /// Writes a checkpoint of `scene` in placement generation `generation`
    /// atomically and keeps only the newest [`KEPT`]. `held` is asked once more just
    /// before the file takes its name: false (a cluster worker's tenure lapsed while
    /// it wrote) removes it unnamed. Returns what was written.
    pub fn write(
        &self,
        scene: u64,
        generation: u64,
        step: u64,
        time: f64,
        payload: &[u8],
        held: impl Fn() -> bool,
    ) -> Result<Meta, CheckpointError> {
        let dir = self.dir(scene);
        fs::create_dir_all(&dir).map_err(io(&dir))?;
        let sequence = self.files(scene).iter().map(|f| f.0.1).max().map_or(1, |s| s + 1);
        let meta = Meta { scene, sequence, step, time };
        let path = dir.join(format!("checkpoint-{generation:06}-{sequence:010}.bin"));
        let temp = dir.join(format!("checkpoint-{generation:06}-{sequence:010}.tmp"));
        {
            let mut f = fs::File::create(&temp).map_err(io(&temp))?;
            f.write_all(&encode(&meta, payload)).map_err(io(&temp))?;
            f.sync_all().map_err(io(&temp))?;
        }
        if !held() {
            let _ = fs::remove_file(&temp);
            return Err(CheckpointError::Withdrawn(scene));
        }
        fs::rename(&temp, &path).map_err(io(&path))?;
        sync_dir(&dir)?;
        for (_, old) in self.files(scene).into_iter().skip(KEPT) {
            fs::remove_file(&old).map_err(io(&old))?;
        }
        Ok(meta)
    }

    /// Reads and checks one checkpoint file.
    pub fn read(path: &Path) -> Result<(Meta, Vec<u8>), CheckpointError> {
        let bytes = fs::read(path).map_err(io(path))?;
        let (meta, payload) =
            decode(&bytes).map_err(|reason| CheckpointError::Damaged { path: path.into(), reason })?;
        Ok((meta, payload.to_vec()))
    }

    /// Removes every checkpoint of `scene`.
    pub fn remove(&self, scene: u64) -> Result<(), CheckpointError> {
        let dir = self.dir(scene);
        match fs::remove_dir_all(&dir) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(io(&dir)(e)),
            _ => Ok(()),
        }
    }

    /// Scene ids that have a checkpoint directory.
    pub fn scenes(&self) -> Vec<u64> {
        let Ok(entries) = fs::read_dir(&self.root) else { return Vec::new() };
        entries.filter_map(|e| e.ok()?.file_name().into_string().ok()?.parse().ok()).collect()
    }

    /// Removes temporary files a crash left behind mid-write.
    pub fn remove_partial_writes(&self) {
        for scene in self.scenes() {
            let Ok(entries) = fs::read_dir(self.dir(scene)) else { continue };
            for e in entries.filter_map(|e| e.ok()) {
                if e.file_name().to_string_lossy().ends_with(".tmp") {
                    tracing::info!("removing {}, a checkpoint cut short by a crash", e.path().display());
                    let _ = fs::remove_file(e.path());
                }
            }
        }
    }
}

/// Makes a rename in `dir` durable.
fn sync_dir(dir: &Path) -> Result<(), CheckpointError> {
    fs::File::open(dir).and_then(|d| d.sync_all()).map_err(io(dir))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_damage_is_found() {
        let meta = Meta { scene: 7, sequence: 3, step: 120, time: 0.125 };
        let bytes = encode(&meta, b"state");
        assert_eq!(decode(&bytes).unwrap(), (meta, &b"state"[..]));
        for cut in [0, 10, HEADER - 1, bytes.len() - 1] {
            assert!(decode(&bytes[..cut]).is_err(), "cut at {cut}");
        }
        for at in [0, 9, 20, HEADER - 1, HEADER, bytes.len() - 1] {
            let mut bad = bytes.clone();
            bad[at] ^= 0x10;
            assert!(decode(&bad).is_err(), "flipped byte {at}");
        }
    }

    #[test]
    fn the_newest_two_are_kept() {
        let dir = tempfile::tempdir().unwrap();
        let c = Checkpoints::open(dir.path().to_path_buf()).unwrap();
        for step in [10, 20, 30] {
            c.write(4, 0, step, step as f64, &step.to_le_bytes(), || true).unwrap();
        }
        let files = c.files(4);
        assert_eq!(files.iter().map(|f| f.0).collect::<Vec<_>>(), [(0, 3), (0, 2)]);
        let (meta, payload) = Checkpoints::read(&files[0].1).unwrap();
        assert_eq!((meta.step, payload), (30, 30u64.to_le_bytes().to_vec()));
        let withdrawn = c.write(4, 0, 40, 40.0, b"late", || false).unwrap_err();
        assert!(matches!(withdrawn, CheckpointError::Withdrawn(4)), "{withdrawn}");
        let ranks = c.files(4).iter().map(|f| f.0).collect::<Vec<_>>();
        assert_eq!(ranks, [(0, 3), (0, 2)], "a withdrawn checkpoint leaves nothing");
        assert_eq!(std::fs::read_dir(c.dir(4)).unwrap().count(), 2, "nor a temporary file");
        c.remove(4).unwrap();
        assert!(c.files(4).is_empty());
    }

    /// A scene moved (generation 1) while its old worker was stopped: the old
    /// worker's file named after it resumes ranks below the new worker's and is the
    /// first removed; a name from before generations reads as generation 0.
    #[test]
    fn a_late_file_of_an_older_generation_never_ranks_first() {
        let dir = tempfile::tempdir().unwrap();
        let c = Checkpoints::open(dir.path().to_path_buf()).unwrap();
        std::fs::create_dir_all(c.dir(5)).unwrap();
        std::fs::write(
            c.dir(5).join("checkpoint-0000000001.bin"),
            encode(&Meta { scene: 5, sequence: 1, step: 10, time: 0.1 }, b"a"),
        )
        .unwrap();
        c.write(5, 1, 10, 0.1, b"taken up", || true).unwrap();
        c.write(5, 0, 12, 0.12, b"late", || true).unwrap();
        let files = c.files(5);
        assert_eq!(files.iter().map(|f| f.0).collect::<Vec<_>>(), [(1, 2), (0, 3)]);
        assert_eq!(Checkpoints::read(&files[0].1).unwrap().1, b"taken up");
        c.write(5, 1, 20, 0.2, b"on", || true).unwrap();
        assert_eq!(c.files(5).iter().map(|f| f.0).collect::<Vec<_>>(), [(1, 4), (1, 2)], "the late file went first");
    }
}
