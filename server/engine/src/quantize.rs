//! Positions on the frame codec's grid: `2^bits - 1` equal steps per axis over
//! `[min, max]` (floe-proto's `Quantizer`, one per axis, with the same formulas
//! and f32 rounding), so a backend can quantise where the state lives — a GPU
//! then copies back 6 bytes per particle instead of 16 — and hand over values
//! that quantise again to exactly the same codes.

/// A quantisation grid for positions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PositionGrid {
    /// Value of code 0 per axis (m).
    pub min: [f32; 3],
    /// Value of the largest code per axis (m).
    pub max: [f32; 3],
    /// Bits per code (1 to 16).
    pub bits: u8,
}

impl PositionGrid {
    /// The largest code, `2^bits - 1`.
    pub fn top(&self) -> u32 {
        (1u32 << self.bits) - 1
    }

    /// Codes per metre on `axis` (0 for an empty range).
    pub fn scale(&self, axis: usize) -> f32 {
        let span = self.max[axis] - self.min[axis];
        if span > 0.0 { self.top() as f32 / span } else { 0.0 }
    }

    /// The code of `v` on `axis`: rounded to nearest, clamped to `0..=top`, NaN to 0.
    pub fn code(&self, v: f32, axis: usize) -> u16 {
        let top = self.top() as f32;
        let x = (v - self.min[axis]) * self.scale(axis) + 0.5;
        // `as u16` saturates negatives to 0 and turns NaN into 0.
        if x >= top { top as u16 } else { x as u16 }
    }

    /// The value of `code` on `axis`.
    pub fn value(&self, code: u16, axis: usize) -> f32 {
        let step = (self.max[axis] - self.min[axis]) / self.top() as f32;
        self.min[axis] + f32::from(code) * step
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_values_quantise_to_their_own_codes() {
        let g = PositionGrid { min: [-0.3, 0.0, 0.1], max: [1.7, 2.0, 2.1], bits: 16 };
        for code in (0..=u16::MAX).step_by(7) {
            for k in 0..3 {
                assert_eq!(g.code(g.value(code, k), k), code);
            }
        }
        assert_eq!(g.code(f32::NAN, 0), 0);
        assert_eq!(g.code(-5.0, 1), 0);
        assert_eq!(g.code(5.0, 2), u16::MAX);
        let x = g.value(g.code(0.123_456, 0), 0);
        assert!((x - 0.123_456).abs() <= 0.5 * 2.0 / 65535.0 + 1e-6);
    }
}
