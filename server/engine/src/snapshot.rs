//! Snapshots: a scene's complete state as bytes, restored bit for bit.
//!
//! Layout of version 2 (little-endian; "bytes" is a u64 length and the bytes):
//! magic `FLOESNAP`, format version (u32), then as bytes the scene (JSON), the run
//! statistics (JSON), the halt (JSON, `null` if none) and the clock (JSON); then a
//! u32 section count and per section: the attribute's name (bytes), its element
//! type (u8: 0 f32, 1 u32, 2 vec3, 3 vec4, 4 symmetric tensor), its element count
//! (u64) and its values (bytes: 32-bit words, element by element). There is one
//! section per state attribute of the scene (`crate::attrs::Role::State`), in
//! slot order; the loader matches them by name and names any that are missing,
//! unexpected or of the wrong type or length.
//!
//! Restoring rebuilds the scene from its JSON and uploads the sections into a fresh
//! backend, so stepping on from a restored snapshot gives exactly the same numbers
//! as stepping on from the original, on either backend. Version 1 snapshots (the
//! fluid's positions, velocities, accelerations and ids in fixed order) still load.

use crate::attrs::{Column, Elem, Role};
use crate::backend::Section;
use crate::clock::{ClockState, MeasuresState};
use crate::model::Model;

/// Magic bytes at the start of a snapshot.
pub const MAGIC: &[u8; 8] = b"FLOESNAP";
/// Format version this build writes.
pub const VERSION: u32 = 2;

/// The parts of a snapshot.
#[derive(Debug, Clone, PartialEq)]
pub struct Parts {
    /// The scene, as JSON.
    pub scene: String,
    /// The run statistics, as JSON.
    pub stats: String,
    /// The halt, as JSON.
    pub halt: String,
    /// The clock.
    pub clock: ClockState,
    /// Every state attribute.
    pub sections: Vec<Section>,
}

/// Writes a version-2 snapshot.
pub fn write(p: &Parts) -> Vec<u8> {
    let mut w = Writer(Vec::new());
    w.0.extend_from_slice(MAGIC);
    w.u32(VERSION);
    w.bytes(p.scene.as_bytes());
    w.bytes(p.stats.as_bytes());
    w.bytes(p.halt.as_bytes());
    w.bytes(serde_json::to_string(&p.clock).expect("clocks serialise").as_bytes());
    w.u32(p.sections.len() as u32);
    for s in &p.sections {
        w.bytes(s.name.as_bytes());
        w.0.push(s.column.elem().tag());
        w.u64(s.column.len() as u64);
        let words = s.column.words();
        w.u64(4 * words.len() as u64);
        for x in words {
            w.u32(x);
        }
    }
    w.0
}

/// Reads a snapshot of either version into its parts.
pub fn read(bytes: &[u8]) -> Result<Parts, SnapshotError> {
    let bad = |m: String| SnapshotError::Malformed(m);
    if bytes.len() < MAGIC.len() || &bytes[..MAGIC.len()] != MAGIC {
        return Err(bad("it does not start with FLOESNAP".into()));
    }
    let mut r = Reader::new(&bytes[MAGIC.len()..]);
    let parts = match r.u32("version")? {
        1 => read_v1(&mut r)?,
        2 => {
            let text = |r: &mut Reader<'_>, what: &str| -> Result<String, SnapshotError> {
                String::from_utf8(r.bytes(what)?.to_vec()).map_err(|_| bad(format!("{what}: not UTF-8")))
            };
            let (scene, stats, halt) = (text(&mut r, "scene")?, text(&mut r, "statistics")?, text(&mut r, "halt")?);
            let clock = serde_json::from_str(&text(&mut r, "clock")?).map_err(|e| bad(format!("clock: {e}")))?;
            let count = r.u32("section count")?;
            let mut sections = Vec::new();
            for i in 0..count {
                let name = text(&mut r, "section name")?;
                let tag = r.bytes_fixed(1, "section type")?[0];
                let elem = Elem::ALL
                    .into_iter()
                    .find(|e| e.tag() == tag)
                    .ok_or_else(|| bad(format!("section {i} ({name}): unknown element type {tag}")))?;
                let n = r.u64("section length")?;
                let raw = r.bytes(&name)?;
                if raw.len() as u64 != n.saturating_mul(4 * elem.components() as u64) {
                    return Err(bad(format!("section {name}: {} bytes for {n} elements", raw.len())));
                }
                let words: Vec<u32> =
                    raw.chunks_exact(4).map(|c| u32::from_le_bytes(c.try_into().expect("4 bytes"))).collect();
                let column = Column::from_words(elem, &words).ok_or_else(|| bad(format!("section {name}")))?;
                sections.push(Section { name, column });
            }
            Parts { scene, stats, halt, clock, sections }
        }
        v => return Err(SnapshotError::UnsupportedVersion(v)),
    };
    r.finish()?;
    Ok(parts)
}

/// Version 1: the scene, six statistics and two sums as f64, the halt, then the
/// clock and the fluid's positions, velocities, accelerations and ids.
fn read_v1(r: &mut Reader<'_>) -> Result<Parts, SnapshotError> {
    let bad = |m: String| SnapshotError::Malformed(m);
    let scene = String::from_utf8(r.bytes("scene")?.to_vec()).map_err(|_| bad("scene: not UTF-8".into()))?;
    let mut f = [0.0; 8];
    for v in &mut f {
        *v = r.f64("statistics")?;
    }
    let stats = serde_json::json!({
        "stats": {"dt_min": f[0], "dt_mean": f[1], "dt_max": f[2], "max_density_deviation": f[3],
                  "mean_density_deviation": f[4], "max_speed": f[5]},
        "dt_sum": f[6], "compression_sum": f[7],
    })
    .to_string();
    let halt = String::from_utf8(r.bytes("halt")?.to_vec()).map_err(|_| bad("halt: not UTF-8".into()))?;
    let time = r.f64("time")?;
    let steps = r.u64("steps")?;
    let (remaining, substeps) = (r.f32("time step control")?, r.u64("time step control")?);
    let n = usize::try_from(r.u64("particle count")?).map_err(|_| bad("particle count".into()))?;
    let vecs =
        |v: Vec<f32>| Column::Vec3(v.chunks_exact(3).map(|c| crate::math::Vec3::new(c[0], c[1], c[2])).collect());
    let x = vecs(r.f32s(3 * n, "positions")?);
    let v = vecs(r.f32s(3 * n, "velocities")?);
    let a = vecs(r.f32s(3 * n, "accelerations")?);
    let ids = Column::U32(r.f32s(n, "ids")?.into_iter().map(f32::to_bits).collect());
    let measures = match r.u32("measures flag")? {
        0 => None,
        1 => Some(MeasuresState {
            max_speed2: (r.u32("measures")?, r.u32("measures")?),
            max_accel2: r.u32("measures")?,
            max_compression: (r.u32("measures")?, r.u32("measures")?),
            sum_compression: r.u64("measures")?,
        }),
        f => return Err(bad(format!("measures flag {f}"))),
    };
    let clock = ClockState { time: time.to_bits(), steps, remaining: remaining.to_bits(), substeps, measures };
    let sections = [("x", x), ("v", v), ("a", a), ("id", ids)]
        .into_iter()
        .map(|(name, column)| Section { name: name.into(), column })
        .collect();
    Ok(Parts { scene, stats, halt, clock, sections })
}

/// Checks that `sections` are exactly the state attributes of `model` (those of
/// [`crate::attrs::AttrSpec::added_later`] may be missing), each with its type and element count, and that
/// the ids are a permutation.
pub fn check_sections(model: &Model, sections: &[Section]) -> Result<(), SnapshotError> {
    let bad = |m: String| Err(SnapshotError::Malformed(m));
    let wanted: Vec<_> = model.layout.specs().filter(|s| s.role == Role::State).collect();
    let saved_ids = sections.iter().find_map(|s| match (s.name.as_str(), &s.column) {
        ("id", Column::U32(ids)) => Some(ids),
        _ => None,
    });
    // Where particles are born and die, the saved scene holds as many as its ids
    // (within its capacity), each below its next id.
    let particles = match (&model.population, saved_ids) {
        (Some(p), Some(ids)) => {
            let next = sections.iter().find_map(|s| match (s.name.as_str(), &s.column) {
                ("next_id", Column::U32(v)) => v.first().copied(),
                _ => None,
            });
            let Some(next) = next else { return bad("no section for the scene's next particle id".into()) };
            if ids.len() > p.capacity {
                return bad(format!("{} particles, the scene holds at most {}", ids.len(), p.capacity));
            }
            let mut sorted = ids.clone();
            sorted.sort_unstable();
            if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
                return bad(format!("particle id {} twice", w[0]));
            }
            if sorted.last().is_some_and(|&last| last >= next) {
                return bad(format!("particle id {} not below the next id {next}", sorted[sorted.len() - 1]));
            }
            ids.len()
        }
        _ => model.particle_count(),
    };
    for spec in &wanted {
        let Some(s) = sections.iter().find(|s| s.name == spec.name) else {
            if spec.added_later {
                continue;
            }
            return bad(format!("no section for attribute {} ({})", spec.name, spec.module));
        };
        let n = if spec.space == crate::attrs::PARTICLES { particles } else { model.layout.count(spec.space) };
        if s.column.elem() != spec.elem || s.column.len() != n {
            return bad(format!(
                "section {}: {} values of {:?}, the scene has {n} of {:?}",
                spec.name,
                s.column.len(),
                s.column.elem(),
                spec.elem
            ));
        }
    }
    if let Some(s) = sections.iter().find(|s| !wanted.iter().any(|w| w.name == s.name)) {
        return bad(format!("section {} belongs to no state attribute of this scene", s.name));
    }
    if let (None, Some(ids)) = (&model.population, saved_ids) {
        let mut seen = vec![false; ids.len()];
        for &i in ids {
            if i as usize >= ids.len() || std::mem::replace(&mut seen[i as usize], true) {
                return bad(format!("particle ids are not a permutation (id {i})"));
            }
        }
    }
    Ok(())
}

/// Why a snapshot could not be restored.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SnapshotError {
    /// The bytes are not a snapshot, or are damaged or cut short.
    #[error("snapshot is malformed: {0}")]
    Malformed(String),
    /// Written by another format version.
    #[error("snapshot format version {0} is not supported (this build reads versions 1 and {VERSION})")]
    UnsupportedVersion(u32),
}

/// Appends values to a snapshot.
#[derive(Debug, Default)]
pub struct Writer(pub Vec<u8>);

impl Writer {
    /// A u32.
    pub fn u32(&mut self, v: u32) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    /// A u64.
    pub fn u64(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    /// An f32, bit for bit.
    pub fn f32(&mut self, v: f32) {
        self.u32(v.to_bits());
    }
    /// An f64, bit for bit.
    pub fn f64(&mut self, v: f64) {
        self.u64(v.to_bits());
    }
    /// Length-prefixed bytes.
    pub fn bytes(&mut self, b: &[u8]) {
        self.u64(b.len() as u64);
        self.0.extend_from_slice(b);
    }
    /// A slice of f32 values, length-prefixed.
    pub fn f32s(&mut self, v: impl ExactSizeIterator<Item = f32>) {
        self.u64(v.len() as u64);
        for x in v {
            self.f32(x);
        }
    }
}

/// Reads values back, checking every length against what is left.
#[derive(Debug)]
pub struct Reader<'a> {
    data: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    /// A reader over `data`.
    pub fn new(data: &'a [u8]) -> Self {
        Self { data, at: 0 }
    }

    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], SnapshotError> {
        if self.data.len() - self.at < n {
            return Err(SnapshotError::Malformed(format!("cut short while reading {what}")));
        }
        let s = &self.data[self.at..self.at + n];
        self.at += n;
        Ok(s)
    }

    /// A u32.
    pub fn u32(&mut self, what: &str) -> Result<u32, SnapshotError> {
        Ok(u32::from_le_bytes(self.take(4, what)?.try_into().expect("4 bytes")))
    }
    /// A u64.
    pub fn u64(&mut self, what: &str) -> Result<u64, SnapshotError> {
        Ok(u64::from_le_bytes(self.take(8, what)?.try_into().expect("8 bytes")))
    }
    /// An f32.
    pub fn f32(&mut self, what: &str) -> Result<f32, SnapshotError> {
        Ok(f32::from_bits(self.u32(what)?))
    }
    /// An f64.
    pub fn f64(&mut self, what: &str) -> Result<f64, SnapshotError> {
        Ok(f64::from_bits(self.u64(what)?))
    }
    /// Exactly `n` bytes.
    pub fn bytes_fixed(&mut self, n: usize, what: &str) -> Result<&'a [u8], SnapshotError> {
        self.take(n, what)
    }
    /// Length-prefixed bytes.
    pub fn bytes(&mut self, what: &str) -> Result<&'a [u8], SnapshotError> {
        let n = self.u64(what)?;
        let n = usize::try_from(n).map_err(|_| SnapshotError::Malformed(format!("{what}: length {n}")))?;
        self.take(n, what)
    }
    /// `expected` f32 values, length-prefixed.
    pub fn f32s(&mut self, expected: usize, what: &str) -> Result<Vec<f32>, SnapshotError> {
        let n = self.u64(what)?;
        if n != expected as u64 {
            return Err(SnapshotError::Malformed(format!("{what}: {n} values, expected {expected}")));
        }
        let raw = self.take(4 * expected, what)?;
        Ok(raw.chunks_exact(4).map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes"))).collect())
    }
    /// Checks that everything was read.
    pub fn finish(&self) -> Result<(), SnapshotError> {
        if self.at == self.data.len() {
            Ok(())
        } else {
            Err(SnapshotError::Malformed(format!("{} bytes left over", self.data.len() - self.at)))
        }
    }
}
