//! The clusters of shape matching (the first thesis's eq. 2.10): one per centre
//! (every particle of an elastic fluid, or the centres [`centres`] samples), its
//! neighbours of the same material within the cluster radius at rest, itself
//! included; the rest offsets `x0 - x0_cm` of each membership. Found on a grid of
//! cells one radius wide.

use crate::math::Vec3;
use std::collections::HashMap;

/// The members (particle ids) of each cluster, and each membership's rest offset
/// from its cluster's centre, in the map's membership order (cluster by cluster).
#[derive(Debug)]
pub struct Clusters {
    /// Members of each cluster, by particle id.
    pub lists: Vec<Vec<u32>>,
    /// Rest offsets, one per membership.
    pub rest: Vec<Vec3>,
}

/// The clusters centred on the particles `centres`, each of the particles `ids`
/// (at `x`, of material `material`) within `radius` (m) of its centre and of its
/// material; each cluster's rest offsets sum to zero to the rounding of the offsets
/// themselves.
pub fn build(centres: &[u32], ids: &[u32], x: &[Vec3], material: &[u32], radius: f32) -> Clusters {
    let key = |p: Vec3| (p / radius).floor().as_ivec3();
    let mut grid: HashMap<glam::IVec3, Vec<u32>> = HashMap::new();
    for &id in ids {
        grid.entry(key(x[id as usize])).or_default().push(id);
    }
    let r2 = radius * radius;
    let mut lists = Vec::with_capacity(centres.len());
    let mut rest = Vec::new();
    for &id in centres {
        let (p, m) = (x[id as usize], material[id as usize]);
        let c = key(p);
        let mut members: Vec<u32> = Vec::new();
        for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let Some(cell) = grid.get(&(c + glam::IVec3::new(dx, dy, dz))) else { continue };
                    members.extend(
                        cell.iter().filter(|&&j| material[j as usize] == m && x[j as usize].distance_squared(p) <= r2),
                    );
                }
            }
        }
        members.sort_unstable();
        // In f64 and about the cluster's own particle: offsets summed from f32
        // positions about an f32 centre would share that centre's rounding and
        // sum to n times it, a push the matching would give every step.
        let offset = |j: u32| (x[j as usize] - p).as_dvec3();
        let centre = members.iter().map(|&j| offset(j)).sum::<glam::DVec3>() / members.len() as f64;
        rest.extend(members.iter().map(|&j| (offset(j) - centre).as_vec3()));
        lists.push(members);
    }
    Clusters { lists, rest }
}

/// Cluster centres among the particles `ids` (at `x`, of material `material`) by
/// Poisson-disk sampling (the first thesis's section 2.3.4): no two centres of one
/// material closer than `distance` (m), and every particle closer than `distance` to
/// a centre of its material (a maximal sample: a particle is left out only for a
/// centre within `distance`). The candidates are taken in an order scrambled from
/// their ids, so the sample does not follow the lattice's rows, and the same ids
/// give the same centres. Returned in ascending id order.
pub fn centres(ids: &[u32], x: &[Vec3], material: &[u32], distance: f32) -> Vec<u32> {
    let key = |id: u32| {
        let c = (x[id as usize] / distance).floor().as_ivec3();
        (material[id as usize], c)
    };
    let mut order = ids.to_vec();
    order.sort_unstable_by_key(|&id| (scramble(id), id));
    let mut taken: HashMap<(u32, glam::IVec3), Vec<u32>> = HashMap::new();
    let d2 = distance * distance;
    let mut out = Vec::new();
    for id in order {
        let (m, c) = key(id);
        let p = x[id as usize];
        let near = (-1..=1).any(|dz| {
            (-1..=1).any(|dy| {
                (-1..=1).any(|dx| {
                    taken
                        .get(&(m, c + glam::IVec3::new(dx, dy, dz)))
                        .is_some_and(|cell| cell.iter().any(|&j| x[j as usize].distance_squared(p) < d2))
                })
            })
        });
        if !near {
            taken.entry((m, c)).or_default().push(id);
            out.push(id);
        }
    }
    out.sort_unstable();
    out
}

/// A bijective scramble of a 32-bit id (the finaliser of MurmurHash3).
fn scramble(id: u32) -> u32 {
    let mut h = id;
    h ^= h >> 16;
    h = h.wrapping_mul(0x85eb_ca6b);
    h ^= h >> 13;
    h = h.wrapping_mul(0xc2b2_ae35);
    h ^ (h >> 16)
}

/// A colour per cluster such that no two clusters of a colour share a member
/// (greedy, in cluster order: each takes the smallest colour none of the clusters
/// sharing a member with it has), and the number of colours. The Gauss-Seidel
/// solver sweeps the colours in turn.
pub fn colours(lists: &[Vec<u32>]) -> (Vec<u32>, u32) {
    let ids = lists.iter().flatten().map(|&m| m as usize + 1).max().unwrap_or(0);
    let mut of_member: Vec<Vec<u32>> = vec![Vec::new(); ids];
    for (s, members) in lists.iter().enumerate() {
        for &m in members {
            of_member[m as usize].push(s as u32);
        }
    }
    let mut colour = vec![u32::MAX; lists.len()];
    let mut taken: Vec<bool> = Vec::new();
    let mut count = 0;
    for (s, members) in lists.iter().enumerate() {
        taken.clear();
        taken.resize(count as usize + 1, false);
        for &m in members {
            for &other in &of_member[m as usize] {
                let c = colour[other as usize];
                if c != u32::MAX {
                    taken[c as usize] = true;
                }
            }
        }
        let c = taken.iter().position(|&t| !t).expect("one colour more than used is free") as u32;
        colour[s] = c;
        count = count.max(c + 1);
    }
    (colour, count)
}
