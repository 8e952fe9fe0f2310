//! Zigzag residuals: what a prediction missed, as a small unsigned value whichever way it
//! missed, so the Rice-coded streams ([`crate::stream`]) store it in few bits.

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
}
