//! Snapshots: a scene's complete state as bytes, restored bit for bit.
//!
//! Layout (little-endian): magic `FLOESNAP`, format version (u32), the scene
//! as JSON (u64 length + bytes), the run statistics, the halt (if any, as JSON),
//! then the backend's own state. Restoring rebuilds the scene from its JSON and
//! loads the state into a fresh backend, so stepping on from a restored
//! snapshot gives exactly the same numbers as stepping on from the original.

/// Magic bytes at the start of a snapshot.
pub const MAGIC: &[u8; 8] = b"FLOESNAP";
/// Format version this build writes and reads.
pub const VERSION: u32 = 1;

/// Why a snapshot could not be restored.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SnapshotError {
    /// The bytes are not a snapshot, or are damaged or cut short.
    #[error("snapshot is malformed: {0}")]
    Malformed(String),
    /// Written by another format version.
    #[error("snapshot format version {0} is not supported (this build reads version {VERSION})")]
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
