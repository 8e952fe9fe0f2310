//! Bit-level reading and writing of streams ([`crate::stream`]): bits packed from the least
//! significant bit of each byte up.
//!
//! Both sides move a whole 64-bit word per call, so a value costs one load or one store
//! whatever its length, with no branch on where byte boundaries fall; the price is that one
//! call handles at most [`WINDOW`] bits (a word less the 7 bits of a partial byte).

/// Most bits one [`BitWriter::put`] writes or one [`BitReader::window`] is sure to hold.
pub(crate) const WINDOW: u32 = 56;

/// Appends bits, least significant first, to a byte vector passed to each call (a slice
/// of it for [`BitWriter::put`], which lets the compiler keep the slice in registers).
#[derive(Debug)]
pub(crate) struct BitWriter {
    /// Where the byte holding `acc`'s first bit goes.
    at: usize,
    /// Bits not yet in whole bytes (fewer than 8 between calls).
    acc: u64,
    filled: u32,
}

impl BitWriter {
    /// Writes after the end of `out`.
    pub(crate) fn new(out: &[u8]) -> Self {
        Self { at: out.len(), acc: 0, filled: 0 }
    }

    /// Makes room in `out` for `bits` more bits: every call writes a whole word past `at`,
    /// so the vector is kept long enough for that, and trimmed by [`BitWriter::finish`].
    pub(crate) fn reserve(&self, out: &mut Vec<u8>, bits: usize) {
        let needed = self.at + (self.filled as usize + bits) / 8 + 8;
        if out.len() < needed {
            out.resize(needed, 0);
        }
    }

    /// Appends the low `count` bits of `bits` (at most [`WINDOW`]; none set above `count`),
    /// within room made by [`BitWriter::reserve`].
    #[inline(always)]
    pub(crate) fn put(&mut self, out: &mut [u8], bits: u64, count: u32) {
        debug_assert!(count <= WINDOW && bits >> count == 0);
        self.acc |= bits << self.filled;
        self.filled += count;
        // Store the whole word, keep its complete bytes: the same work for any `count`.
        out[self.at..self.at + 8].copy_from_slice(&self.acc.to_le_bytes());
        let whole = self.filled / 8;
        self.at += whole as usize;
        self.acc >>= 8 * whole;
        self.filled %= 8;
    }

    /// Appends the low `count` bits of `bits`, up to 64.
    #[inline]
    pub(crate) fn put_wide(&mut self, out: &mut [u8], bits: u64, count: u32) {
        if count > WINDOW {
            self.put(out, bits & 0xffff_ffff, 32);
            self.put(out, bits >> 32, count - 32);
        } else {
            self.put(out, bits, count);
        }
    }

    /// Ends `out` at the last partial byte, its unused high bits zero.
    pub(crate) fn finish(self, out: &mut Vec<u8>) {
        out.truncate(self.at + usize::from(self.filled > 0));
    }
}

/// Reads bits, least significant first, from a byte slice; reads past its end see zeros.
#[derive(Debug, Default)]
pub(crate) struct BitReader<'a> {
    bytes: &'a [u8],
    /// The next bit to read.
    pub(crate) pos: usize,
}

impl<'a> BitReader<'a> {
    pub(crate) fn new(bytes: &'a [u8]) -> Self {
        Self { bytes, pos: 0 }
    }

    /// The bits from `pos` up, at least [`WINDOW`] of them (more past the end, all zero).
    #[inline(always)]
    pub(crate) fn window(&self) -> u64 {
        let at = self.pos / 8;
        let word = match self.bytes.get(at..).and_then(<[u8]>::first_chunk::<8>) {
            Some(w) => u64::from_le_bytes(*w),
            None => {
                let mut w = [0; 8];
                let tail = self.bytes.get(at..).unwrap_or(&[]);
                w[..tail.len()].copy_from_slice(tail);
                u64::from_le_bytes(w)
            }
        };
        word >> (self.pos % 8)
    }

    /// The next `count` bits (at most [`WINDOW`]).
    #[inline]
    pub(crate) fn read(&mut self, count: u32) -> u64 {
        let v = self.window() & ((1u64 << count) - 1);
        self.pos += count as usize;
        v
    }

    /// The next `count` bits, up to 64.
    #[inline]
    pub(crate) fn read_wide(&mut self, count: u32) -> u64 {
        if count > WINDOW {
            let low = self.read(32);
            low | self.read(count - 32) << 32
        } else {
            self.read(count)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_of_every_length_round_trip() {
        let fields: Vec<(u64, u32)> =
            (0..=64).map(|count| (0x9e37_79b9_7f4a_7c15_u64.checked_shr(64 - count).unwrap_or(0), count)).collect();
        let mut out = Vec::new();
        let mut w = BitWriter::new(&out);
        w.reserve(&mut out, 64 * 65);
        for &(bits, count) in &fields {
            w.put_wide(&mut out, bits, count);
        }
        w.finish(&mut out);
        let total: u32 = fields.iter().map(|f| f.1).sum();
        assert_eq!(out.len(), total.div_ceil(8) as usize);
        let mut r = BitReader::new(&out);
        for &(bits, count) in &fields {
            assert_eq!(r.read_wide(count), bits, "{count} bits");
        }
        assert_eq!(r.window(), 0, "zeros past the end");
    }
}
