//! Morton (Z-order) codes and the radix sort that orders particles by them.
//!
//! Interleaving the bits of the three quantised coordinates (x in bit 0, y in bit 1,
//! z in bit 2 of each triple) gives a key whose order keeps nearby particles nearby,
//! so the differences between sorted keys are small and their high bytes mostly zero.

/// Spreads the low 16 bits of `v` to every third bit (the classic magic-number spread).
#[inline]
fn spread(v: u16) -> u64 {
    let mut x = u64::from(v);
    x = (x | x << 16) & 0x001f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

/// Gathers every third bit of `x` (from bit 0) into 16 bits.
#[inline]
fn gather(x: u64) -> u16 {
    let mut x = x & 0x1249_2492_4924_9249;
    x = (x | x >> 2) & 0x10c3_0c30_c30c_30c3;
    x = (x | x >> 4) & 0x100f_00f0_0f00_f00f;
    x = (x | x >> 8) & 0x001f_0000_ff00_00ff;
    x = (x | x >> 16) & 0x001f_0000_0000_ffff;
    x as u16
}

/// The Morton key of one quantised position.
#[inline]
pub(crate) fn encode(q: [u16; 3]) -> u64 {
    spread(q[0]) | spread(q[1]) << 1 | spread(q[2]) << 2
}

/// The quantised position of a Morton key.
#[inline]
pub(crate) fn decode(key: u64) -> [u16; 3] {
    [gather(key), gather(key >> 1), gather(key >> 2)]
}

/// Bits per radix digit: 4096 counters fit in L1 and four passes cover 48-bit keys.
const DIGIT_BITS: u32 = 12;
const BUCKETS: usize = 1 << DIGIT_BITS;

/// Sorts `keys` (below `2^key_bits`) ascending, applying the same permutation to `ids`
/// when given (same length). Stable LSD radix sort; passes whose digit is the same for
/// every key are skipped. `spare_keys`/`spare_ids` are scratch reused across calls.
pub(crate) fn sort(
    keys: &mut Vec<u64>,
    mut ids: Option<&mut Vec<u32>>,
    key_bits: u32,
    spare_keys: &mut Vec<u64>,
    spare_ids: &mut Vec<u32>,
) {
    let n = keys.len();
    let passes = key_bits.div_ceil(DIGIT_BITS) as usize;
    let mut counts = vec![[0u32; BUCKETS]; passes];
    for &k in keys.iter() {
        for (p, c) in counts.iter_mut().enumerate() {
            c[((k >> (p as u32 * DIGIT_BITS)) as usize) & (BUCKETS - 1)] += 1;
        }
    }
    spare_keys.clear();
    spare_keys.resize(n, 0);
    if ids.is_some() {
        spare_ids.clear();
        spare_ids.resize(n, 0);
    }
    for (p, c) in counts.iter_mut().enumerate() {
        if c.iter().any(|&x| x as usize == n) {
            continue;
        }
        let mut sum = 0;
        for x in c.iter_mut() {
            let here = *x;
            *x = sum;
            sum += here;
        }
        let shift = p as u32 * DIGIT_BITS;
        match ids.as_deref_mut() {
            Some(ids) => {
                for (&k, &id) in keys.iter().zip(ids.iter()) {
                    let slot = &mut c[((k >> shift) as usize) & (BUCKETS - 1)];
                    spare_keys[*slot as usize] = k;
                    spare_ids[*slot as usize] = id;
                    *slot += 1;
                }
                std::mem::swap(ids, spare_ids);
            }
            None => {
                for &k in keys.iter() {
                    let slot = &mut c[((k >> shift) as usize) & (BUCKETS - 1)];
                    spare_keys[*slot as usize] = k;
                    *slot += 1;
                }
            }
        }
        std::mem::swap(keys, spare_keys);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_interleave_and_invert() {
        assert_eq!(encode([1, 0, 0]), 1);
        assert_eq!(encode([0, 1, 0]), 2);
        assert_eq!(encode([0, 0, 1]), 4);
        assert_eq!(encode([u16::MAX; 3]), (1 << 48) - 1);
        let mut s = 0x9e37_79b9_7f4a_7c15_u64;
        for _ in 0..10_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let q = [s as u16, (s >> 16) as u16, (s >> 32) as u16];
            assert_eq!(decode(encode(q)), q);
        }
    }

    #[test]
    fn sort_orders_keys_and_carries_ids() {
        let mut keys: Vec<u64> = (0..5000u64).map(|i| i.wrapping_mul(0x5851_f42d_4c95_7f2d) >> 16).collect();
        let original = keys.clone();
        let mut ids: Vec<u32> = (0..5000).collect();
        let (mut sk, mut si) = (Vec::new(), Vec::new());
        sort(&mut keys, Some(&mut ids), 48, &mut sk, &mut si);
        assert!(keys.windows(2).all(|w| w[0] <= w[1]));
        for (k, &id) in keys.iter().zip(&ids) {
            assert_eq!(*k, original[id as usize]);
        }
        let mut alone = original.clone();
        sort(&mut alone, None, 48, &mut sk, &mut si);
        assert_eq!(alone, keys);
    }
}
