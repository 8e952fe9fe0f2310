//! Recordings: encoded frames in a file, as `floectl record` writes them.
//!
//! Layout: magic `FLOEREC1`, then per frame a little-endian u32 length and the
//! frame's bytes (the Floe frame format). Reading decodes with one decoder, so
//! identity-ordered delta frames replay correctly; a recording therefore starts
//! with the first frame of a stream (a keyframe), as `floectl record` does.

use floe_proto::{Decoder, Frame, Limits};
use std::io::{Read, Write};

/// Magic bytes of a recording.
pub const MAGIC: &[u8; 8] = b"FLOEREC1";

/// Writes frames to a recording.
#[derive(Debug)]
pub struct Recorder<W: Write> {
    out: W,
}

impl<W: Write> Recorder<W> {
    /// Starts a recording.
    pub fn new(mut out: W) -> std::io::Result<Self> {
        out.write_all(MAGIC)?;
        Ok(Self { out })
    }

    /// Appends one encoded frame.
    pub fn push(&mut self, frame: &[u8]) -> std::io::Result<()> {
        let len = u32::try_from(frame.len()).map_err(|_| std::io::Error::other("frame larger than 4 GiB"))?;
        self.out.write_all(&len.to_le_bytes())?;
        self.out.write_all(frame)
    }

    /// Flushes and returns the writer.
    pub fn finish(mut self) -> std::io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }
}

/// Reads every frame of a recording, decoded.
pub fn read(mut input: impl Read) -> anyhow::Result<Vec<Frame>> {
    let mut magic = [0u8; 8];
    input.read_exact(&mut magic)?;
    anyhow::ensure!(&magic == MAGIC, "not a Floe recording (no FLOEREC1 header)");
    let mut decoder = Decoder::new(Limits::default());
    let mut frames = Vec::new();
    let mut len = [0u8; 4];
    loop {
        match input.read_exact(&mut len) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => break,
            Err(e) => return Err(e.into()),
        }
        let len = u32::from_le_bytes(len) as usize;
        let limit = Limits::default().max_frame_bytes as usize;
        anyhow::ensure!(len <= limit, "frame {} declares {len} bytes, more than the limit of {limit}", frames.len());
        let mut bytes = vec![0u8; len];
        input.read_exact(&mut bytes)?;
        frames.push(decoder.decode(&bytes)?);
    }
    Ok(frames)
}
