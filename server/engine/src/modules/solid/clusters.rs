//! The clusters of shape matching (the first thesis's eq. 2.10): one per particle
//! of an elastic fluid, its neighbours of the same material within the cluster
//! radius at rest, itself included; the rest offsets `x0 - x0_cm` of each
//! membership. Found on a grid of cells one radius wide.

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

/// The clusters of the particles `ids` (at `x`, of material `material`) within
/// `radius` (m) of each other and of one material; each cluster's rest offsets sum
/// to zero to the rounding of the offsets themselves.
pub fn build(ids: &[u32], x: &[Vec3], material: &[u32], radius: f32) -> Clusters {
    let key = |p: Vec3| (p / radius).floor().as_ivec3();
    let mut grid: HashMap<glam::IVec3, Vec<u32>> = HashMap::new();
    for &id in ids {
        grid.entry(key(x[id as usize])).or_default().push(id);
    }
    let r2 = radius * radius;
    let mut lists = Vec::with_capacity(ids.len());
    let mut rest = Vec::new();
    for &id in ids {
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
