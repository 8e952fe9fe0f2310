//! Streams: how a channel's payload stores its values.
//!
//! A channel's payload is one stream per component, or a single stream of Morton-key
//! differences for unordered positions ([`crate::header::Predictor::Morton`]). A stream
//! holds `n` unsigned values (`n` = the particle count), Rice-coded in blocks:
//!
//! | offset | size | type | field |
//! |---:|---:|---|---|
//! | 0 | 1 | u8 | width `w`: bits of the largest value (0 to 16, or 0 to 48 for Morton differences) |
//! | 1 | 4 | u32 | length `len` of the coded blocks in bytes |
//! | 5 | len | bits | the blocks, bits packed from the least significant bit of each byte up |
//!
//! Values are coded in blocks of [`BLOCK`] (the last block may be shorter). A block starts
//! with a 6-bit parameter `k`; [`ZERO_BLOCK`] (63) means every value of the block is 0 and
//! nothing else of the block is stored; otherwise `k <= w`, and each value `v` follows:
//!
//! - if `q = v >> k` is below [`ESCAPE`] (16): `q` zero bits, a one bit, then the low `k`
//!   bits of `v` (a Rice code);
//! - otherwise [`ESCAPE`] zero bits and then `v` in `w` bits.
//!
//! Multi-bit fields are written least significant bit first. `len` is exactly the bytes
//! the bits need, and the bits after the last value (up to 7) are zero.
//!
//! Why: residuals and Morton differences are roughly geometrically distributed with a scale
//! that changes along the stream (a splash next to water at rest). A Rice code whose
//! parameter follows each block's scale stays within a few percent of the values' order-0
//! entropy and adapts to the local scale, where byte planes with LZ4 stayed 0.3 to 0.7 bytes
//! per particle above it (`proto/README.md`); the escape bounds the cost of outliers.

use crate::bits::{BitReader, BitWriter, WINDOW};
use crate::error::DecodeError;
use crate::reader::Reader;

/// Values per block: each block's parameter costs 6 bits, 0.05 bits per value.
pub const BLOCK: usize = 128;
/// Block parameter meaning "all 128 values are 0".
pub const ZERO_BLOCK: u32 = 63;
/// Quotients from this on are escaped: the value is stored in full, `w` bits.
pub const ESCAPE: u32 = 16;
const PARAMETER_BITS: u32 = 6;

/// What a stream holds: 16-bit codes and residuals, or 48-bit Morton-key differences.
pub(crate) trait Value: Copy + Default + Into<u64> {
    /// The value of at most the type's bits (callers check the width first).
    fn truncate(v: u64) -> Self;
}

impl Value for u16 {
    #[inline(always)]
    fn truncate(v: u64) -> Self {
        v as u16
    }
}

impl Value for u64 {
    #[inline(always)]
    fn truncate(v: u64) -> Self {
        v
    }
}

/// Bits of `max` (0 for 0).
pub(crate) fn width_of(max: u64) -> u32 {
    64 - max.leading_zeros()
}

/// Whether a value of a `width`-bit stream, Rice-coded or escaped, always fits in one
/// [`WINDOW`]: then the coding loops need no second read or write per value.
fn fits_window(width: u32) -> bool {
    ESCAPE + width <= WINDOW
}

/// The parameter that codes `block` (not all zero) in about the fewest bits: of the one its
/// mean suggests (a Rice code's best `k` is about `log2` of the mean) and its two neighbours,
/// the one with the fewest bits not counting escapes, which the best parameter makes rare.
fn best_parameter<T: Value>(block: &[T], sum: u64, width: u32) -> u32 {
    let guess = width_of(sum / block.len() as u64).min(width);
    let k = [guess.saturating_sub(1), guess, (guess + 1).min(width)];
    let mut quotients = [0u64; 3];
    for &v in block {
        for (q, &k) in quotients.iter_mut().zip(&k) {
            *q += v.into() >> k;
        }
    }
    let cost = |i: usize| quotients[i] + block.len() as u64 * u64::from(k[i]);
    (0..3).min_by_key(|&i| (cost(i), k[i])).map_or(guess, |i| k[i])
}

/// Appends a stream of `values` to `out`.
pub(crate) fn write<T: Value>(out: &mut Vec<u8>, values: &[T]) {
    write_each([out], [values]);
}

/// Appends `S` streams, of `values[0]` to `values[S - 1]` (all of the same length), to
/// `bufs[0]`; the other vectors of `bufs` (cleared first) hold streams 1 to `S - 1` while
/// they are written.
///
/// The streams are written side by side, a value of each in turn, for the reason
/// [`read_each`] reads them so: each value's position in its stream waits on the length of
/// the one before it, and independent streams overlap those waits.
pub(crate) fn write_each<T: Value, const S: usize>(mut bufs: [&mut Vec<u8>; S], values: [&[T]; S]) {
    let n = values.first().map_or(0, |v| v.len());
    let widths = values.map(|v| width_of(v.iter().fold(0, |a, &x| a | x.into())));
    let mut len_at = [0; S];
    let mut writers: [BitWriter; S] = std::array::from_fn(|s| {
        let out = &mut *bufs[s];
        if s > 0 {
            out.clear();
        }
        out.push(widths[s] as u8);
        len_at[s] = out.len();
        out.extend_from_slice(&[0; 4]);
        BitWriter::new(out)
    });
    let narrow = widths.iter().all(|&w| fits_window(w));
    let mut start = 0;
    while start < n {
        let end = n.min(start + BLOCK);
        let mut ks = [ZERO_BLOCK; S];
        for s in 0..S {
            let block = &values[s][start..end];
            // Values are below 2^48, so 128 of them sum below 2^55.
            let sum: u64 = block.iter().map(|&v| v.into()).sum();
            let (w, out) = (&mut writers[s], &mut *bufs[s]);
            w.reserve(out, PARAMETER_BITS as usize + block.len() * (ESCAPE + widths[s]) as usize);
            if sum != 0 {
                ks[s] = best_parameter(block, sum, widths[s]);
            }
            w.put(out, u64::from(ks[s]), PARAMETER_BITS);
        }
        let blocks = values.map(|v| &v[start..end]);
        if narrow {
            write_blocks::<T, S, false>(&mut writers, &mut bufs, blocks, ks, widths);
        } else {
            write_blocks::<T, S, true>(&mut writers, &mut bufs, blocks, ks, widths);
        }
        start = end;
    }
    for ((w, out), at) in writers.into_iter().zip(bufs.iter_mut()).zip(len_at) {
        w.finish(out);
        // The encoder has checked that the frame, and so this stream, fits in u32.
        let len = (out.len() - at - 4) as u32;
        out[at..at + 4].copy_from_slice(&len.to_le_bytes());
    }
    if let Some((first, rest)) = bufs.split_first_mut() {
        for stream in rest {
            first.extend_from_slice(stream);
        }
    }
}

/// Writes one block of each stream, with parameters `ks` (a stream whose parameter is
/// [`ZERO_BLOCK`] writes nothing); `WIDE` when a value may not fit in one [`WINDOW`]
/// (`!fits_window(width)`), so the narrow loop has no branch for it.
#[inline(always)]
#[allow(clippy::needless_range_loop, reason = "value `i` of every stream in turn")]
fn write_blocks<T: Value, const S: usize, const WIDE: bool>(
    writers: &mut [BitWriter; S],
    bufs: &mut [&mut Vec<u8>; S],
    blocks: [&[T]; S],
    ks: [u32; S],
    widths: [u32; S],
) {
    let outs = bufs.each_mut().map(|b| b.as_mut_slice());
    let lows = ks.map(|k| (1u64 << k.min(48)) - 1);
    let count = blocks.first().map_or(0, |b| b.len());
    for i in 0..count {
        for s in 0..S {
            let (k, w, out) = (ks[s], &mut writers[s], &mut *outs[s]);
            if k == ZERO_BLOCK {
                continue;
            }
            let v: u64 = blocks[s][i].into();
            let q = (v >> k) as u32;
            if q < ESCAPE {
                if WIDE && q + 1 + k > WINDOW {
                    w.put(out, 1 << q, q + 1);
                    w.put(out, v & lows[s], k);
                } else {
                    // The unary quotient, its closing one bit and the low bits in one call.
                    w.put(out, ((v & lows[s]) << 1 | 1) << q, q + 1 + k);
                }
            } else if WIDE {
                w.put(out, 0, ESCAPE);
                w.put_wide(out, v, widths[s]);
            } else {
                w.put(out, v << ESCAPE, ESCAPE + widths[s]);
            }
        }
    }
}

/// Reads a stream of `n` values of at most `max_width` bits into `values`.
/// `max_width` is at most the bits of `T`.
pub(crate) fn read<T: Value>(
    r: &mut Reader<'_>,
    n: usize,
    max_width: u32,
    values: &mut Vec<T>,
) -> Result<(), DecodeError> {
    read_each(r, n, max_width, [values])
}

/// Reads `S` consecutive streams of `n` values each, of at most `max_width` bits (at most
/// the bits of `T`), into `values` (one vector per stream, resized to `n`).
///
/// The streams are decoded side by side, a value of each in turn: a Rice decoder waits on
/// every value's length before it can find the next one, and interleaving independent
/// streams lets the processor overlap those waits (the three axes of a channel decode
/// about twice as fast as one after the other).
///
/// Allocation is bounded twice: by `n` (which the caller has checked against its limit)
/// and by the bytes actually present, since every block takes at least 6 bits.
pub(crate) fn read_each<T: Value, const S: usize>(
    r: &mut Reader<'_>,
    n: usize,
    max_width: u32,
    mut values: [&mut Vec<T>; S],
) -> Result<(), DecodeError> {
    let mut streams: [Coded<'_>; S] = std::array::from_fn(|_| Coded::default());
    for s in &mut streams {
        *s = Coded::open(r, n, max_width)?;
    }
    for v in &mut values {
        // Every value is written below, zero blocks included, so old contents may stay.
        v.resize(n, T::default());
    }
    if streams.iter().all(|s| fits_window(s.width)) {
        read_blocks::<T, S, false>(&mut streams, &mut values)?;
    } else {
        read_blocks::<T, S, true>(&mut streams, &mut values)?;
    }
    streams.iter().try_for_each(Coded::finish)
}

/// The blocks of `streams`, a value of each in turn. `WIDE` as for [`write_block`].
fn read_blocks<T: Value, const S: usize, const WIDE: bool>(
    streams: &mut [Coded<'_>; S],
    values: &mut [&mut Vec<T>; S],
) -> Result<(), DecodeError> {
    let n = values.first().map_or(0, |v| v.len());
    let mut start = 0;
    while start < n {
        let end = n.min(start + BLOCK);
        for s in streams.iter_mut() {
            s.start_block()?;
        }
        let mut any = [0u64; S];
        for i in start..end {
            for ((s, v), any) in streams.iter_mut().zip(values.iter_mut()).zip(&mut any) {
                let x = s.value::<WIDE>();
                *any |= x;
                v[i] = T::truncate(x);
            }
        }
        for (s, any) in streams.iter().zip(any) {
            s.end_block(any)?;
        }
        start = end;
    }
    Ok(())
}

/// One stream being read: its header's fields, its blocks' bits, and the current block's
/// parameter.
#[derive(Debug, Default)]
struct Coded<'a> {
    width: u32,
    len: usize,
    bits: BitReader<'a>,
    /// The current block's parameter, [`ZERO_BLOCK`] included.
    k: u32,
    /// `2^k - 1`, the mask of a value's low bits.
    low: u64,
}

impl<'a> Coded<'a> {
    /// Reads the stream's header and takes its bytes, checking they could hold `n` values.
    fn open(r: &mut Reader<'a>, n: usize, max_width: u32) -> Result<Self, DecodeError> {
        let width = u32::from(r.u8()?);
        if width > max_width {
            return Err(DecodeError::malformed(format!("stream width {width} bits (at most {max_width} allowed)")));
        }
        let len = r.u32()? as usize;
        let bytes = r.take(len)?;
        if n.div_ceil(BLOCK) as u64 * u64::from(PARAMETER_BITS) > 8 * len as u64 {
            return Err(DecodeError::malformed(format!("{len} bytes cannot hold {n} values")));
        }
        Ok(Self { width, len, bits: BitReader::new(bytes), k: 0, low: 0 })
    }

    /// Reads and checks the next block's parameter.
    fn start_block(&mut self) -> Result<(), DecodeError> {
        let k = self.bits.read(PARAMETER_BITS) as u32;
        if k != ZERO_BLOCK && k > self.width {
            let width = self.width;
            return Err(DecodeError::malformed(format!("block parameter {k} exceeds the stream width {width}")));
        }
        self.k = k;
        self.low = (1u64 << k.min(self.width)) - 1;
        Ok(())
    }

    /// The next value of the current block.
    #[inline(always)]
    fn value<const WIDE: bool>(&mut self) -> u64 {
        let (k, bits) = (self.k, &mut self.bits);
        if k == ZERO_BLOCK {
            return 0;
        }
        let window = bits.window();
        // The unary quotient's length; 64 for an all-zero window, an escape like any q >= 16.
        let q = window.trailing_zeros();
        if q < ESCAPE {
            if WIDE && q + 1 + k > WINDOW {
                bits.pos += q as usize + 1;
                u64::from(q) << k | bits.read(k)
            } else {
                bits.pos += (q + 1 + k) as usize;
                u64::from(q) << k | (window >> (q + 1)) & self.low
            }
        } else if WIDE {
            bits.pos += ESCAPE as usize;
            bits.read_wide(self.width)
        } else {
            bits.pos += (ESCAPE + self.width) as usize;
            (window >> ESCAPE) & ((1u64 << self.width) - 1)
        }
    }

    /// Checks a finished block: `any`, the bitwise or of its values, within the width, and
    /// the bits read within the stream.
    fn end_block(&self, any: u64) -> Result<(), DecodeError> {
        if width_of(any) > self.width {
            return Err(DecodeError::malformed(format!("a value exceeds the stream width {}", self.width)));
        }
        if self.bits.pos as u64 > 8 * self.len as u64 {
            return Err(DecodeError::malformed(format!("the values run past the stream's {} bytes", self.len)));
        }
        Ok(())
    }

    /// Checks that the values took exactly the stream's bytes, with zero padding bits.
    fn finish(&self) -> Result<(), DecodeError> {
        let (pos, len) = (self.bits.pos, self.len);
        if pos.div_ceil(8) != len {
            return Err(DecodeError::malformed(format!("the values take {pos} bits of the stream's {len} bytes")));
        }
        if !pos.is_multiple_of(8) && self.bits.window() != 0 {
            return Err(DecodeError::malformed("padding bits after the last value are not zero"));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip(values: &[u64], max_width: u32) -> Vec<u8> {
        let mut out = Vec::new();
        write(&mut out, values);
        let mut back: Vec<u64> = Vec::new();
        let mut r = Reader::new(&out, "stream");
        read(&mut r, values.len(), max_width, &mut back).unwrap();
        assert_eq!(r.remaining(), 0);
        assert_eq!(back, values);
        out
    }

    #[test]
    fn streams_round_trip_at_every_scale() {
        let mut s = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        for width in [1, 5, 16, 48] {
            // Mostly small values with rare outliers, which take the escape.
            let values: Vec<u64> =
                (0..1000).map(|i| if i % 97 == 0 { next() >> (64 - width) } else { next() % 7 }).collect();
            round_trip(&values, 48);
        }
        round_trip(&[], 16);
        round_trip(&[u64::from(u16::MAX); 300], 16);
        round_trip(&[(1 << 48) - 1, 0, 1], 48);
    }

    #[test]
    fn streams_side_by_side_match_streams_one_after_the_other() {
        // Different widths (one past a window), zero blocks in one stream only, and escapes.
        let a: Vec<u64> = (0..700u64).map(|i| if i < 300 { 0 } else { i % 13 }).collect();
        let b: Vec<u64> = (0..700u64).map(|i| if i % 50 == 0 { (1 << 47) + i } else { i * 31 }).collect();
        let c: Vec<u64> = (0..700u64).map(|i| (i * 2_654_435_761) % 65_536).collect();
        let mut one_by_one = Vec::new();
        for v in [&a, &b, &c] {
            write(&mut one_by_one, v);
        }
        let (mut out, mut y, mut z) = (Vec::new(), vec![9], Vec::new());
        write_each([&mut out, &mut y, &mut z], [&a, &b, &c]);
        assert_eq!(out, one_by_one);
        let mut back: [Vec<u64>; 3] = Default::default();
        let [x, y, z] = &mut back;
        let mut r = Reader::new(&out, "streams");
        read_each(&mut r, 700, 48, [x, y, z]).unwrap();
        assert_eq!(r.remaining(), 0);
        assert_eq!(back, [a, b, c]);
    }

    #[test]
    fn zero_blocks_cost_six_bits() {
        let out = round_trip(&[0; 1000], 16);
        assert_eq!(out.len(), 5 + (8 * 6usize).div_ceil(8), "eight zero blocks");
        assert_eq!(out[0], 0, "width 0");
    }

    #[test]
    fn small_values_take_few_bits() {
        let values: Vec<u64> = (0..12_800u64).map(|i| (i * 2_654_435_761) % 8).collect();
        let out = round_trip(&values, 16);
        assert!(out.len() < 12_800 * 4 / 8 + 200, "about 4 bits per value 0 to 7: {} bytes", out.len());
    }

    #[test]
    fn damaged_streams_are_refused() {
        let values: Vec<u64> = (0..500u64).map(|i| i % 37).collect();
        let mut good = Vec::new();
        write(&mut good, &values);
        let decode =
            |bytes: &[u8], max_width| read(&mut Reader::new(bytes, "stream"), 500, max_width, &mut Vec::<u16>::new());
        assert!(decode(&good, 16).is_ok());
        assert!(decode(&good, 5).is_err(), "width 6 over a maximum of 5");
        let mut longer = good.clone();
        longer[1] += 1;
        longer.push(0);
        assert!(decode(&longer, 16).is_err(), "a byte more than the values take");
        let mut padded = good.clone();
        *padded.last_mut().unwrap() |= 0x80;
        assert!(decode(&padded, 16).is_err(), "padding bits set");
        let mut parameter = good.clone();
        parameter[5] = (parameter[5] & !63) | 20;
        assert!(decode(&parameter, 16).is_err(), "parameter above the width");
    }

    #[test]
    fn an_implausible_length_is_refused_before_allocating() {
        let mut bytes = vec![16];
        bytes.extend_from_slice(&4u32.to_le_bytes());
        bytes.extend_from_slice(&[0; 4]);
        let mut values: Vec<u16> = Vec::new();
        let err = read(&mut Reader::new(&bytes, "stream"), 1 << 30, 16, &mut values).unwrap_err();
        assert!(matches!(err, DecodeError::Malformed { .. }), "{err}");
        assert_eq!(values.capacity(), 0);
    }
}
