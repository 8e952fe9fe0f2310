//! Unordered frames: particles sorted by the Morton key of their quantised position.
//!
//! Sorting makes the positions a sorted set of keys, whose differences are small
//! (their size is set by the volume per particle, not the scene), and brings
//! neighbours together so every other channel predicts each particle from the one
//! before it. The order of the particles is given up, which viewers do not need.

use crate::codes::ChannelCodes;
use crate::error::DecodeError;
use crate::morton;
use crate::quantize::Quantizer;
use crate::reader::Reader;
use crate::stream;

/// Scratch buffers reused from frame to frame.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    pub(crate) keys: Vec<u64>,
    pub(crate) ids: Vec<u32>,
    spare_keys: Vec<u64>,
    spare_ids: Vec<u32>,
}

/// Appends the positions stream of `positions` (sorted Morton-key differences). With
/// `carry_ids`, leaves in `s.ids` the particle at each sorted place, so the other channels
/// can follow the same order.
pub(crate) fn write_positions(out: &mut Vec<u8>, positions: &ChannelCodes, carry_ids: bool, s: &mut Scratch) {
    let [x, y, z] = [&positions.codes[0], &positions.codes[1], &positions.codes[2]];
    s.keys.clear();
    s.keys.extend(x.iter().zip(y).zip(z).map(|((&a, &b), &c)| morton::encode([a, b, c])));
    let key_bits = 3 * u32::from(positions.bits());
    if carry_ids {
        s.ids.clear();
        // The encoder has checked that the particle count fits in u32.
        s.ids.extend(0..s.keys.len() as u32);
        morton::sort(&mut s.keys, Some(&mut s.ids), key_bits, &mut s.spare_keys, &mut s.spare_ids);
    } else {
        morton::sort(&mut s.keys, None, key_bits, &mut s.spare_keys, &mut s.spare_ids);
    }
    let mut prev = 0;
    for k in &mut s.keys {
        let d = *k - prev;
        prev = *k;
        *k = d;
    }
    stream::write(out, &s.keys);
}

/// Reads the positions stream of `n` particles quantised by `q` (one per axis) and
/// de-quantises it.
pub(crate) fn read_positions(
    r: &mut Reader<'_>,
    n: usize,
    q: &[Quantizer],
    keys: &mut Vec<u64>,
) -> Result<Vec<[f32; 3]>, DecodeError> {
    let key_bits = 3 * u32::from(q[0].bits);
    stream::read(r, n, key_bits, keys)?;
    let mut key = 0u64;
    for k in keys.iter_mut() {
        key = key
            .checked_add(*k)
            .filter(|&k| k >> key_bits == 0)
            .ok_or_else(|| DecodeError::malformed(format!("Morton key differences sum past {key_bits} bits")))?;
        *k = key;
    }
    let steps = [q[0].step(), q[1].step(), q[2].step()];
    let mins = [q[0].min, q[1].min, q[2].min];
    Ok(keys
        .iter()
        .map(|&k| {
            let [a, b, c] = morton::decode(k);
            [mins[0] + f32::from(a) * steps[0], mins[1] + f32::from(b) * steps[1], mins[2] + f32::from(c) * steps[2]]
        })
        .collect())
}
