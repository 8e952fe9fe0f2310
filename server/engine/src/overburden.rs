//! The pressure of a fluid at rest from the weight of the fluid above each
//! particle: the state a scheme starts a scene in, so that a fluid at rest does not
//! fall onto its own compression and ring (WCSPH's integrated density, DFSPH's
//! stiffness).

use crate::attrs::{Column, PARTICLES};
use crate::math::{Real, Vec3};
use crate::model::ModelBuilder;

/// The hydrostatic pressure (Pa) on each particle from the weight of the fluid above
/// it: particles in columns `d` wide along gravity `g`, each carrying
/// `|g| (rho0_i d / 2 + sum of rho0_j d above it)`, its own half layer and the whole
/// layers above. A block at rest gets `rho0 |g| depth`, and a layer under another
/// carries the other's weight as well. Gravity along a periodic axis has no "above":
/// [`at_rest`] starts such scenes at zero pressure.
pub fn overburden(x: &[Vec3], rho0: &[Real], g: Vec3, d: Real) -> Vec<Real> {
    let (g_len, down) = (g.length(), g.normalize_or_zero());
    let mut out = vec![0.0; x.len()];
    if g_len == 0.0 {
        return out;
    }
    let (e1, e2) = down.any_orthonormal_pair();
    let mut columns: std::collections::HashMap<(i64, i64), Vec<usize>> = Default::default();
    for (i, x) in x.iter().enumerate() {
        let key = ((x.dot(e1) / d).floor() as i64, (x.dot(e2) / d).floor() as i64);
        columns.entry(key).or_default().push(i);
    }
    for mut column in columns.into_values() {
        column.sort_by(|&a, &b| x[a].dot(down).total_cmp(&x[b].dot(down)));
        let mut above = 0.0;
        for i in column {
            out[i] = g_len * (above + 0.5 * rho0[i] * d);
            above += rho0[i] * d;
        }
    }
    out
}

/// Each particle's pressure at rest and material, for the scene being built.
#[derive(Debug)]
pub struct AtRest {
    /// [`overburden`] with each particle's rest density (Pa); zero everywhere where
    /// gravity acts along a periodic axis.
    pub pressure: Vec<Real>,
    /// Each particle's material.
    pub material: Vec<u32>,
}

/// The pressure at rest of the particles declared so far ([`AtRest`]).
pub fn at_rest(b: &ModelBuilder) -> AtRest {
    let rest: Vec<Real> = b.materials().iter().map(|m| m.rest_density).collect();
    let g: Vec3 = b.scene.gravity.into();
    let material = match b.column("material") {
        Some(Column::U32(mat)) => mat.clone(),
        _ => vec![0; b.count(PARTICLES)],
    };
    let Some(Column::Vec3(x)) = b.column("x") else { panic!("the core declares positions first") };
    let rho0: Vec<Real> = material.iter().map(|&m| rest[m as usize]).collect();
    let along_periodic = b.scene.periodic_axes().iter().zip(g.to_array()).any(|(&p, g)| p && g != 0.0);
    let pressure = if along_periodic { vec![0.0; x.len()] } else { overburden(x, &rho0, g, b.scene.particle_spacing) };
    AtRest { pressure, material }
}
