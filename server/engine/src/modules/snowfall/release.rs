//! The release of the snow cover on the slopes as SPH particles of a fluid (with
//! the `snow` module, avalanche snow): snowfall, then an avalanche, in one scene.
//!
//! **Mass.** The cover is counted in flakes; a particle of the fluid is a whole
//! number `q` of them, so a release conserves mass exactly, in integers: a cell
//! of `n` flakes gives `n / q` particles (integer division) and keeps the
//! remainder, less than one particle's snow. The cover's density is the
//! particles' on their lattice (`m / d^3`, `m` the fluid's particle mass, `d` the
//! particle spacing), so each flake is `V` cubic metres of snow and
//! `q = round(d^3 / V)`: the cover's density is that rounded by at most
//! `1 / (2 q)`, and a scene whose flakes carry more than a particle's snow
//! (`q < 1`) is refused.
//!
//! **Where.** The cells of the ground (not objects' tops) whose slope, from the
//! ground's heights under the cells' centres (as the coverage's inclination), is
//! at least `min_slope`. A cell's
//! particles stand in columns `cell / round(cell / d)` apart, stacked from the
//! ground up in layers as thick as their snow, at rest.
//!
//! **When.** After the first step that ends at or after `at` (a live setting:
//! a client releases now by setting it to the scene's time), once per value. The
//! cover's state records the `at` last released and the flakes released in all,
//! so the flakes' accounting stays exact: emitted = airborne + landed + left +
//! released. Flakes that fall afterwards land on the cover the release left,
//! not on the released snow.

use super::{BED, GROUND_COUNT, SnowfallConsts, spec};
use crate::attrs::{AttrSpec, Column, Elem, PARTICLES, Role};
use crate::backend::Backend;
use crate::math::{Real, Vec3};
use crate::model::{BuildError, ModelBuilder};
use crate::population::{Births, Emitter};

/// The release's space (one element).
pub const SPACE: &str = "snow_release";

/// Flakes released in all.
pub static RELEASED: AttrSpec = AttrSpec {
    name: "snow_released",
    elem: Elem::U32,
    unit: "",
    role: Role::State,
    added_later: false,
    space: SPACE,
    module: "snowfall",
    about: "Flakes' worth of snow released as particles, in all.",
};

/// The `at` (s) of the last release (-1: none yet).
pub static LAST: AttrSpec = AttrSpec {
    name: "snow_release_at",
    elem: Elem::F32,
    unit: "s",
    role: Role::State,
    added_later: false,
    space: SPACE,
    module: "snowfall",
    about: "Scene time the last release was set for (-1: none).",
};

/// What the release needs, fixed when the scene is built but for `at`.
#[derive(Debug, Clone, PartialEq)]
pub struct ReleaseConsts {
    /// When (s), if set.
    pub at: Option<f32>,
    /// The fluid's material index.
    pub material: u32,
    /// Flakes per particle (`q`).
    pub flakes_per_particle: u32,
    /// A particle's mass (kg).
    pub particle_mass: Real,
    /// The cells released, by index.
    pub cells: Vec<u32>,
    /// Columns of particles along each edge of a cell.
    pub per_side: u32,
    /// Thickness of a layer of particles (m).
    pub layer: Real,
}

impl ReleaseConsts {
    /// A flake's mass (kg).
    pub fn flake_mass(&self) -> f64 {
        f64::from(self.particle_mass) / f64::from(self.flakes_per_particle)
    }
}

/// Declares the release of scene section `r` over the grid of `c` with the
/// ground's heights `bed` (m per cell): its state, its room and its emitter.
pub fn build(
    r: &spec::Release,
    c: &SnowfallConsts,
    bed: &[f32],
    b: &mut ModelBuilder,
) -> Result<ReleaseConsts, BuildError> {
    let names: Vec<&str> = b.materials().iter().map(|m| m.name.as_str()).collect();
    let Some(material) = names.iter().position(|&n| n == r.fluid) else {
        return Err(BuildError::Setting(format!(
            "snowfall.release.fluid: no fluid named {:?} (the scene's: {names:?})",
            r.fluid
        )));
    };
    let d = b.scene.particle_spacing;
    let mass = b.materials()[material].mass;
    let flake_volume = c.depth_per_flake * c.cell * c.cell;
    let q = (d.powi(3) / flake_volume).round();
    if q < 1.0 {
        return Err(BuildError::Setting(format!(
            "snowfall.release: a flake carries {flake_volume:.3e} m^3 of snow, more than a particle's {:.3e} m^3; \
             lower depth_per_hour or raise the intensity",
            d.powi(3)
        )));
    }
    let per_side = (c.cell / d).round().max(1.0) as u32;
    let column = c.cell / per_side as f32;
    b.space(SPACE, 1);
    b.zeros(&RELEASED);
    b.attr(&LAST, Column::F32(vec![-1.0]));
    b.reserve(r.particles as usize);
    b.emitter(Emitter { name: "snowfall.release", emit: release });
    Ok(ReleaseConsts {
        at: r.at,
        material: material as u32,
        flakes_per_particle: q as u32,
        particle_mass: mass,
        cells: steep(c, bed, r.min_slope),
        per_side,
        layer: q * flake_volume / (column * column),
    })
}

/// The cells whose ground is at least `min_slope` degrees steep (the
/// inclination the coverage takes, [`super::coverage::inclination`]).
fn steep(c: &SnowfallConsts, bed: &[f32], min_slope: f32) -> Vec<u32> {
    let limit = min_slope.to_radians().cos();
    (0..bed.len()).filter(|&k| super::coverage::inclination(c, bed, k) <= limit).map(|k| k as u32).collect()
}

/// The emitter: the cover's particles after the step that reaches `at`.
fn release(b: &mut dyn Backend, _: u64, time: f64, _: Real) -> Result<Births, String> {
    let c = b.model().consts::<SnowfallConsts>();
    let r = c.release.as_ref().expect("the emitter is declared with the release");
    let Some(at) = r.at.filter(|&at| time >= f64::from(at)) else { return Ok(Births::default()) };
    let mut cols = b.download(&[LAST.name, GROUND_COUNT.name, BED.name, RELEASED.name]).into_iter();
    let mut next = || cols.next().expect("four columns");
    let (Column::F32(last), Column::U32(mut counts), Column::F32(bed), Column::U32(released)) =
        (next(), next(), next(), next())
    else {
        panic!("the release's columns")
    };
    if last[0] == at {
        return Ok(Births::default());
    }
    let (births, flakes) = particles(c, r, &mut counts, &bed);
    let (n, capacity) = (b.particle_count(), b.model().particle_capacity());
    if n + births.len() > capacity {
        return Err(format!(
            "snowfall.release: the cover makes {} particles, with {n} there is room for {} \
             (raise snowfall.release.particles)",
            births.len(),
            capacity - n
        ));
    }
    let Some(total) = u32::try_from(flakes).ok().and_then(|f| released[0].checked_add(f)) else {
        return Err("snowfall.release: more than 2^32 flakes released".into());
    };
    b.upload(GROUND_COUNT.name, Column::U32(counts));
    b.upload(RELEASED.name, Column::U32(vec![total]));
    b.upload(LAST.name, Column::F32(vec![at]));
    Ok(births)
}

/// The particles of the released cells, taken from `counts`, and the flakes they hold.
fn particles(c: &SnowfallConsts, r: &ReleaseConsts, counts: &mut [u32], bed: &[f32]) -> (Births, u64) {
    let q = r.flakes_per_particle;
    let side = r.per_side as usize;
    let column = c.cell / r.per_side as f32;
    let mut births = Births::default();
    let mut flakes = 0u64;
    for &cell in &r.cells {
        let cell = cell as usize;
        let k = counts[cell] / q;
        counts[cell] -= k * q;
        flakes += u64::from(k * q);
        let (i, j) = ((cell % c.nx as usize) as f32, (cell / c.nx as usize) as f32);
        for p in 0..k as usize {
            let (col, layer) = (p % (side * side), p / (side * side));
            let x = c.origin[0] + i * c.cell + ((col % side) as f32 + 0.5) * column;
            let z = c.origin[1] + j * c.cell + ((col / side) as f32 + 0.5) * column;
            births.x.push(Vec3::new(x, bed[cell] + (layer as f32 + 0.5) * r.layer, z));
        }
    }
    births.v = vec![Vec3::ZERO; births.len()];
    births.material = vec![r.material; births.len()];
    (births, flakes)
}

/// The particles' count of the space: none of it is allocated without a release.
pub fn count(r: &spec::Release) -> [(&'static str, u64); 2] {
    [(SPACE, 1), (PARTICLES, u64::from(r.particles))]
}
