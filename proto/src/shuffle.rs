//! Byte planes and zigzag residuals: the transforms that turn codes into bytes a fast
//! compressor shrinks well.
//!
//! Byte shuffling stores byte 0 of every value, then byte 1 of every value, and so on
//! (little-endian byte order within a value). Small residuals then leave whole planes
//! of zeros or near-zeros, which compress to almost nothing, while the noisy low bytes
//! sit together instead of breaking up the runs.

/// Bytes needed to hold `max` (at least 1).
pub(crate) fn width_of(max: u64) -> usize {
    (64 - max.leading_zeros() as usize).div_ceil(8).max(1)
}

/// Writes `width` planes of `values`' bytes into `out`, resized to `values.len() * width`.
pub(crate) fn split_planes<T: Copy + Into<u64>>(values: &[T], width: usize, out: &mut Vec<u8>) {
    let n = values.len();
    out.clear();
    out.resize(n * width, 0);
    for (k, plane) in out.chunks_exact_mut(n.max(1)).enumerate().take(width) {
        let shift = 8 * k;
        for (o, &v) in plane.iter_mut().zip(values) {
            *o = (v.into() >> shift) as u8;
        }
    }
}

/// Rebuilds 16-bit values from `width` (1 or 2) planes of `out.len()` bytes each.
pub(crate) fn join_planes_u16(planes: &[u8], width: usize, out: &mut [u16]) {
    let n = out.len();
    let low = &planes[..n];
    if width == 1 {
        for (o, &b) in out.iter_mut().zip(low) {
            *o = u16::from(b);
        }
    } else {
        let high = &planes[n..2 * n];
        for ((o, &l), &h) in out.iter_mut().zip(low).zip(high) {
            *o = u16::from_le_bytes([l, h]);
        }
    }
}

/// Rebuilds values of up to 8 bytes from `width` planes of `out.len()` bytes each.
pub(crate) fn join_planes_u64(planes: &[u8], width: usize, out: &mut [u64]) {
    let n = out.len();
    out.fill(0);
    for (k, plane) in planes.chunks_exact(n.max(1)).enumerate().take(width) {
        let shift = 8 * k;
        for (o, &b) in out.iter_mut().zip(plane) {
            *o |= u64::from(b) << shift;
        }
    }
}

/// `(now - prev) mod 2^bits` read as a signed `bits`-bit number and zigzag-encoded
/// (`0, -1, 1, -2, ...` to `0, 1, 2, 3, ...`), so it stays within `bits` bits and small
/// changes either way give small values.
#[inline]
pub(crate) fn zigzag_residual(now: u16, prev: u16, bits: u8) -> u16 {
    let shift = 32 - u32::from(bits);
    let d = u32::from(now).wrapping_sub(u32::from(prev));
    let s = ((d << shift) as i32) >> shift;
    ((s << 1) ^ (s >> 31)) as u16
}

/// Inverse of [`zigzag_residual`]: the code `prev + residual` modulo `2^bits`.
#[inline]
pub(crate) fn apply_residual(residual: u16, prev: u16, bits: u8) -> u16 {
    let z = u32::from(residual);
    let s = (z >> 1) ^ (z & 1).wrapping_neg();
    let mask = (1u32 << bits) - 1;
    (u32::from(prev).wrapping_add(s) & mask) as u16
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn residuals_invert_for_every_pair_of_8_bit_codes() {
        for bits in [1u8, 3, 8] {
            let top = (1u16 << bits) - 1;
            for a in 0..=top {
                for b in 0..=top {
                    let r = zigzag_residual(a, b, bits);
                    assert!(r <= top, "residual {r} of {a}-{b} exceeds {bits} bits");
                    assert_eq!(apply_residual(r, b, bits), a);
                }
            }
        }
        assert_eq!(zigzag_residual(5, 5, 16), 0);
        assert_eq!(zigzag_residual(4, 5, 16), 1);
        assert_eq!(zigzag_residual(6, 5, 16), 2);
        assert_eq!(zigzag_residual(0, 65535, 16), 2, "wraps the short way round");
        assert_eq!(apply_residual(u16::MAX, 0, 16), 32768);
    }

    #[test]
    fn planes_round_trip() {
        let v: Vec<u64> = (0..1000u64).map(|i| i * 0x0123_4567_89ab).collect();
        let w = width_of(*v.iter().max().unwrap());
        assert_eq!(w, 7);
        let mut planes = Vec::new();
        split_planes(&v, w, &mut planes);
        let mut back = vec![0; v.len()];
        join_planes_u64(&planes, w, &mut back);
        assert_eq!(back, v);

        let v16: Vec<u16> = (0..300u16).map(|i| i * 211).collect();
        split_planes(&v16, 2, &mut planes);
        assert_eq!(planes[300], v16[0].to_le_bytes()[1]);
        let mut back16 = vec![0; v16.len()];
        join_planes_u16(&planes, 2, &mut back16);
        assert_eq!(back16, v16);
    }

    #[test]
    fn widths() {
        assert_eq!(width_of(0), 1);
        assert_eq!(width_of(255), 1);
        assert_eq!(width_of(256), 2);
        assert_eq!(width_of(u64::MAX), 8);
    }
}
