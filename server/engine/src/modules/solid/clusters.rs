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
/// `radius` (m) of each other and of one material.
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
        let centre = members.iter().map(|&j| x[j as usize]).sum::<Vec3>() / members.len() as f32;
        rest.extend(members.iter().map(|&j| x[j as usize] - centre));
        lists.push(members);
    }
    Clusters { lists, rest }
}
