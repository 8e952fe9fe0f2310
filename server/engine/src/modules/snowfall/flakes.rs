//! A flake's life on the CPU, the GPU's oracle (`snowfall/fall.wgsl` mirrors it
//! line for line): born at the emission height, moved by the snow thesis's
//! `V_n = V_(n-1) + K W + a n + r(n)`, `S_n = S_(n-1) + V_n dt` (eqs. 2.5-2.6) with
//! drag, and landed on the objects, the snow already there or the ground.
//!
//! **The motion.** The thesis adds the wind `K W`, gravity and a random flutter
//! `r(n)` to the velocity each step, with no drag, so a flake would fall ever
//! faster. Floe adds linear drag towards the air's velocity with the relaxation
//! time `tau = v_t / |g|`, which makes `v_t` the terminal speed in still air and
//! `W` the flake's horizontal speed in wind (the thesis's `K` is then `1 / tau`),
//! and integrates it exactly over the step: `v = u + (v - u) e^(-dt / tau) + r dt`,
//! `u = (W, -v_t)` (stable at any step), then `x += v dt`.

use super::SnowfallConsts;
use crate::math::Vec3;

/// Airborne.
pub const AIRBORNE: f32 = 1.0;
/// Landed (its snow is in a cell's count).
pub const LANDED: f32 = 2.0;
/// Left the area, or still airborne at the oldest age a flake may have.
pub const LEFT: f32 = 3.0;

/// Index of the tally's counters.
pub mod tally {
    /// Flakes emitted since the scene started.
    pub const EMITTED: usize = 0;
    /// Number of the first flake born this step.
    pub const FIRST: usize = 1;
    /// Flakes born this step.
    pub const BORN: usize = 2;
    /// Flakes that left.
    pub const LEFT: usize = 3;
}

/// Index of the timer's values.
pub mod timer {
    /// The fraction of a flake owed to the next step.
    pub const CARRY: usize = 0;
    /// Time since the scene started (s), for the gusts.
    pub const CLOCK: usize = 1;
}

/// Chris Wellons' lowbias32 integer hash.
pub fn hash(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^ (x >> 16)
}

/// A uniform number in [0, 1) from a hash (24 bits: exact in f32).
pub fn unit(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The emission of a step: `(first, born)` flake numbers, with the tally and
/// timer advanced by a step of `dt` (s).
pub fn emit(c: &SnowfallConsts, tally: &mut [u32], timer: &mut [f32], dt: f32) {
    let owed = c.rate * dt;
    let carry = timer[timer::CARRY] + owed;
    let born = carry.floor();
    timer[timer::CARRY] = carry - born;
    timer[timer::CLOCK] += dt;
    tally[tally::FIRST] = tally[tally::EMITTED];
    tally[tally::BORN] = born as u32;
    tally[tally::EMITTED] = tally[tally::EMITTED].wrapping_add(born as u32);
}

/// The wind at `clock` (s): `[x, z]` (m/s).
pub fn wind(c: &SnowfallConsts, clock: f32) -> [f32; 2] {
    let gust = 1.0 + c.gusts * (c.gust_omega * clock).sin();
    [c.wind[0] * gust, c.wind[1] * gust]
}

/// The turbulence at `(x, z)` (m) and `clock` (s): `[x, z]` (m/s) to add to the
/// wind. Value noise: random values in [-1, 1] on the lattice of `scale` metres
/// and `period` seconds (hashed from the lattice point's integer coordinates, so
/// both backends draw the same), blended trilinearly with smoothstep weights.
pub fn turbulence(c: &SnowfallConsts, x: f32, z: f32, clock: f32) -> [f32; 2] {
    let [amplitude, per_metre, per_second] = c.turbulence;
    if amplitude == 0.0 {
        return [0.0, 0.0];
    }
    let p = [x * per_metre, z * per_metre, clock * per_second];
    let lattice = p.map(f32::floor);
    let s: Vec<f32> = (0..3).map(|a| p[a] - lattice[a]).map(|f| f * f * (3.0 - 2.0 * f)).collect();
    let base = lattice.map(|l| l as i32 as u32);
    let mut out = [0.0f32; 2];
    for corner in 0..8u32 {
        let o = [corner & 1, (corner >> 1) & 1, (corner >> 2) & 1];
        let w = (0..3).map(|a| if o[a] == 1 { s[a] } else { 1.0 - s[a] }).product::<f32>();
        let h = hash(base[0].wrapping_add(o[0]) ^ hash(base[1].wrapping_add(o[1]) ^ hash(base[2].wrapping_add(o[2]))));
        out[0] += w * (2.0 * unit(h) - 1.0);
        out[1] += w * (2.0 * unit(hash(h)) - 1.0);
    }
    out.map(|v| amplitude * v)
}

/// Where flake number `id` is born (m): the `id`th point of Roberts' R2 sequence
/// over the area (`frac(id a1)`, `frac(id a2)`, `a` from the plastic number, in
/// 32-bit fixed point so both backends compute it exactly), which covers the area
/// far more evenly than independent draws: the flux on open ground is the emitted
/// one within a fraction of a percent.
pub fn birth(c: &SnowfallConsts, id: u32) -> Vec3 {
    let hx = id.wrapping_mul(0xc13f_a9a9);
    let hz = id.wrapping_mul(0x91e1_0da5);
    let x = c.emit_min[0] + unit(hx) * (c.emit_max[0] - c.emit_min[0]);
    let z = c.emit_min[1] + unit(hz) * (c.emit_max[1] - c.emit_min[1]);
    Vec3::new(x, c.height, z)
}

/// Whether `x` lies over the rectangle `[min, max]` (`[x, z]`, m).
pub fn over(min: [f32; 2], max: [f32; 2], x: Vec3) -> bool {
    x.x >= min[0] && x.x <= max[0] && x.z >= min[1] && x.z <= max[1]
}

/// The flutter of a flake at `x` of age `age` this step (m/s^2): seeded by its
/// state, so both backends draw the same.
pub fn flutter(c: &SnowfallConsts, x: Vec3, age: f32) -> Vec3 {
    let h0 = hash(x.x.to_bits() ^ hash(x.z.to_bits() ^ hash(age.to_bits())));
    let (h1, h2) = (hash(h0), hash(h0 ^ 0x9e37_79b9));
    let r = |h: u32| c.flutter * (2.0 * unit(h) - 1.0);
    Vec3::new(r(h0), r(h1), r(h2))
}

/// The centre `(x, z)` (m) of cell `k`.
pub fn centre(c: &SnowfallConsts, k: usize) -> (f32, f32) {
    let (i, j) = (k % c.nx as usize, k / c.nx as usize);
    (c.origin[0] + (i as f32 + 0.5) * c.cell, c.origin[1] + (j as f32 + 0.5) * c.cell)
}

/// The cell of the snow grid over `(x, z)`, clamped to the grid.
pub fn cell(c: &SnowfallConsts, x: f32, z: f32) -> usize {
    let i = ((x - c.origin[0]) / c.cell).floor().clamp(0.0, (c.nx - 1) as f32) as usize;
    let k = ((z - c.origin[1]) / c.cell).floor().clamp(0.0, (c.nz - 1) as f32) as usize;
    k * c.nx as usize + i
}

/// The top (m), its snow `snow` (m) included, of the first object a flake that
/// moved from height `from` (m) to `x` landed on: it is in the object, or it
/// crossed the object's top (snow included) over the object this step, so that it
/// cannot pass through a roof thinner than a step's fall.
pub fn object_top(c: &SnowfallConsts, from: f32, x: Vec3, snow: f32) -> Option<f32> {
    c.objects.iter().find_map(|o| {
        let [a, b] = *o;
        let over = if a[3] == 0.0 {
            x.x >= a[0] && x.x <= b[0] && x.z >= a[2] && x.z <= b[2]
        } else {
            let (dx, dz) = (x.x - a[0], x.z - a[2]);
            dx * dx + dz * dz <= b[0] * b[0]
        };
        let top = b[1] + snow;
        let inside = x.y >= a[1] && x.y <= top;
        let crossed = from > top && x.y <= top;
        (over && (inside || crossed)).then_some(top)
    })
}

/// The top (m), its snow `snow` (m) included, of a mesh's column over the cell
/// (`column`: bottom, top; [`super::columns`]) if a flake that moved from height
/// `from` to `y` landed on it, by [`object_top`]'s rule.
pub fn column_top(column: [f32; 2], from: f32, y: f32, snow: f32) -> Option<f32> {
    let top = column[1] + snow;
    let inside = y >= column[0] && y <= top;
    let crossed = from > top && y <= top;
    (column[1] >= column[0] && (inside || crossed)).then_some(top)
}
