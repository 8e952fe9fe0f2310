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

use crate::error::DecodeError;
use crate::reader::Reader;

/// Values per block: each block's parameter costs 6 bits, 0.05 bits per value.
pub const BLOCK: usize = 128;
/// Block parameter meaning "all 128 values are 0".
pub const ZERO_BLOCK: u32 = 63;
/// Quotients from this on are escaped: the value is stored in full, `w` bits.
pub const ESCAPE: u32 = 16;
const PARAMETER_BITS: u32 = 6;

/// Appends bits least significant first; at most 32 bits per call.
#[derive(Debug)]
struct BitWriter<'a> {
    out: &'a mut Vec<u8>,
    acc: u64,
    filled: u32,
}

impl BitWriter<'_> {
    #[inline]
    fn put(&mut self, bits: u64, count: u32) {
        debug_assert!(count <= 32 && bits >> count == 0);
        self.acc |= bits << self.filled;
        self.filled += count;
        if self.filled >= 32 {
            self.out.extend_from_slice(&(self.acc as u32).to_le_bytes());
            self.acc >>= 32;
            self.filled -= 32;
        }
    }

    /// Up to 64 bits.
    #[inline]
    fn put_wide(&mut self, bits: u64, count: u32) {
        if count > 32 {
            self.put(bits & 0xffff_ffff, 32);
            self.put(bits >> 32, count - 32);
        } else {
            self.put(bits, count);
        }
    }

    fn finish(self) {
        let bytes = self.filled.div_ceil(8) as usize;
        self.out.extend_from_slice(&self.acc.to_le_bytes()[..bytes]);
    }
}

/// Bits of `max` (0 for 0).
pub(crate) fn width_of(max: u64) -> u32 {
    64 - max.leading_zeros()
}

/// The parameter that codes `block` (not all zero) in about the fewest bits: of the one its
/// mean suggests (a Rice code's best `k` is about `log2` of the mean) and its two neighbours,
/// the one with the fewest bits not counting escapes, which the best parameter makes rare.
fn best_parameter(block: &[u64], sum: u64, width: u32) -> u32 {
    let guess = width_of(sum / block.len() as u64).min(width);
    let k = [guess.saturating_sub(1), guess, (guess + 1).min(width)];
    let mut quotients = [0u64; 3];
    for &v in block {
        for (q, &k) in quotients.iter_mut().zip(&k) {
            *q += v >> k;
        }
    }
    let cost = |i: usize| quotients[i] + block.len() as u64 * u64::from(k[i]);
    (0..3).min_by_key(|&i| (cost(i), k[i])).map_or(guess, |i| k[i])
}

/// Appends a stream of `values` to `out`.
pub(crate) fn write(out: &mut Vec<u8>, values: &[u64]) {
    let width = width_of(values.iter().fold(0, |a, &v| a | v));
    out.push(width as u8);
    let len_at = out.len();
    out.extend_from_slice(&[0; 4]);
    let mut w = BitWriter { out, acc: 0, filled: 0 };
    for block in values.chunks(BLOCK) {
        // Values are below 2^48, so 128 of them sum below 2^55.
        let sum: u64 = block.iter().sum();
        if sum == 0 {
            w.put(u64::from(ZERO_BLOCK), PARAMETER_BITS);
            continue;
        }
        let k = best_parameter(block, sum, width);
        w.put(u64::from(k), PARAMETER_BITS);
        let low = (1u64 << k) - 1;
        for &v in block {
            let q = v >> k;
            if q < u64::from(ESCAPE) {
                // The unary quotient and the low bits in one call when they fit.
                let unary = q as u32 + 1;
                if unary + k <= 32 {
                    w.put(1 << q | (v & low) << unary, unary + k);
                } else {
                    w.put(1 << q, unary);
                    w.put_wide(v & low, k);
                }
            } else {
                w.put(0, ESCAPE);
                w.put_wide(v, width);
            }
        }
    }
    w.finish();
    // The encoder has checked that the frame, and so this stream, fits in u32.
    let len = (out.len() - len_at - 4) as u32;
    out[len_at..len_at + 4].copy_from_slice(&len.to_le_bytes());
}

/// Reads bits least significant first from a byte slice; reads past its end see zeros.
#[derive(Debug)]
struct BitReader<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl BitReader<'_> {
    /// The next 56 bits or more, from bit `pos` up.
    #[inline]
    fn peek(&self) -> u64 {
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

    /// `count` bits (at most 56).
    #[inline]
    fn read(&mut self, count: u32) -> u64 {
        let v = self.peek() & ((1u64 << count) - 1);
        self.pos += count as usize;
        v
    }
}

/// Reads a stream of `n` values of at most `max_width` bits into `values` (cleared first).
///
/// Allocation is bounded twice: by `n` (which the caller has checked against its limit)
/// and by the bytes actually present, since every block takes at least 6 bits.
pub(crate) fn read(r: &mut Reader<'_>, n: usize, max_width: u32, values: &mut Vec<u64>) -> Result<(), DecodeError> {
    let width = u32::from(r.u8()?);
    if width > max_width {
        return Err(DecodeError::malformed(format!("stream width {width} bits (at most {max_width} allowed)")));
    }
    let len = r.u32()? as usize;
    let bytes = r.take(len)?;
    let available = 8 * len as u64;
    if n.div_ceil(BLOCK) as u64 * u64::from(PARAMETER_BITS) > available {
        return Err(DecodeError::malformed(format!("{len} bytes cannot hold {n} values")));
    }
    values.clear();
    values.reserve(n);
    let mut bits = BitReader { bytes, pos: 0 };
    let mut left = n;
    while left > 0 {
        let count = left.min(BLOCK);
        left -= count;
        let k = bits.read(PARAMETER_BITS) as u32;
        if k == ZERO_BLOCK {
            values.extend(std::iter::repeat_n(0, count));
            continue;
        }
        if k > width {
            return Err(DecodeError::malformed(format!("block parameter {k} exceeds the stream width {width}")));
        }
        let mut any = 0;
        for _ in 0..count {
            let window = bits.peek();
            let q = window.trailing_zeros().min(ESCAPE);
            let v = if q < ESCAPE && q + k < 56 {
                // The quotient and the low bits from the same 56-bit window.
                bits.pos += (q + 1 + k) as usize;
                u64::from(q) << k | (window >> (q + 1)) & ((1u64 << k) - 1)
            } else if q < ESCAPE {
                bits.pos += q as usize + 1;
                u64::from(q) << k | bits.read(k)
            } else {
                bits.pos += ESCAPE as usize;
                bits.read(width)
            };
            any |= v;
            values.push(v);
        }
        if width_of(any) > width {
            return Err(DecodeError::malformed(format!("a value exceeds the stream width {width}")));
        }
        if bits.pos as u64 > available {
            return Err(DecodeError::malformed(format!("the values run past the stream's {len} bytes")));
        }
    }
    if bits.pos.div_ceil(8) != len {
        return Err(DecodeError::malformed(format!("the values take {} bits of the stream's {len} bytes", bits.pos)));
    }
    if !bits.pos.is_multiple_of(8) && bytes[len - 1] >> (bits.pos % 8) != 0 {
        return Err(DecodeError::malformed("padding bits after the last value are not zero"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip(values: &[u64], max_width: u32) -> Vec<u8> {
        let mut out = Vec::new();
        write(&mut out, values);
        let mut back = Vec::new();
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
        let decode = |bytes: &[u8], max_width| read(&mut Reader::new(bytes, "stream"), 500, max_width, &mut Vec::new());
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
        let mut values = Vec::new();
        let err = read(&mut Reader::new(&bytes, "stream"), 1 << 30, 16, &mut values).unwrap_err();
        assert!(matches!(err, DecodeError::Malformed { .. }), "{err}");
        assert_eq!(values.capacity(), 0);
    }
}
