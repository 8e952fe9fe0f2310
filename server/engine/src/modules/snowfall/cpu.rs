//! The snowfall's CPU passes, the GPU's oracle (`server/gpu/src/modules/snowfall/`):
//! the step's births counted, the flakes moved and landed, the surface refreshed.

use super::{BED, FLAKE_AGE, FLAKE_V, FLAKE_X, GROUND_COUNT, SURFACE, SnowfallConsts, TALLY, TIMER, TOP_COUNT, flakes};
use crate::cpu::{CpuCx, CpuPass};
use crate::math::Vec3;
use rayon::prelude::*;

/// Counts the step's births.
#[derive(Debug)]
pub struct Emit;

impl CpuPass for Emit {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let c = cx.model.consts::<SnowfallConsts>();
        let (t, m) = (cx.attrs.handle::<u32>(TALLY.name), cx.attrs.handle::<f32>(TIMER.name));
        let (mut tally, mut timer) = (cx.attrs.take(t), cx.attrs.take(m));
        flakes::emit(c, &mut tally, &mut timer, cx.dt);
        cx.attrs.put(t, tally);
        cx.attrs.put(m, timer);
    }
}

/// Moves, lands and bears the flakes: chunks of slots in parallel, each flake
/// touching only its slot, the landings then counted in slot order (whole counts,
/// as the GPU's atomics: the same whatever the order).
#[derive(Debug)]
pub struct Fall;

/// Slots a thread moves at a time.
const CHUNK: usize = 1 << 14;

/// What became of a flake this step.
enum Fate {
    /// Born, in the air, or landed before.
    Nothing,
    /// Left.
    Left,
    /// Landed on the ground of a cell.
    Ground(usize),
    /// Landed on an object's top over a cell.
    Top(usize),
}

/// What a step needs to move a flake.
struct Sky<'a> {
    c: &'a SnowfallConsts,
    dt: f32,
    target: Vec3,
    clock: f32,
    decay: f32,
    first: u32,
    born: u32,
    surface: &'a [[f32; 4]],
}

impl Sky<'_> {
    /// Flake slot `i` (`x`, `v`, `age` its values) through the step.
    fn advance(&self, i: u32, x: &mut Vec3, v: &mut [f32; 4], age: &mut f32) -> Fate {
        let (c, dt, n) = (self.c, self.dt, self.c.capacity);
        let d = (i + n - self.first % n) % n;
        if d < self.born {
            *x = flakes::birth(c, self.first.wrapping_add(d));
            *v = [self.target.x, self.target.y, self.target.z, flakes::AIRBORNE];
            *age = 0.0;
            return Fate::Nothing;
        }
        if v[3] != flakes::AIRBORNE {
            return Fate::Nothing;
        }
        *age += dt;
        let r = flakes::flutter(c, *x, *age);
        let [tx, tz] = flakes::turbulence(c, x.x, x.z, self.clock);
        let target = self.target + Vec3::new(tx, 0.0, tz);
        let vel = target + (Vec3::new(v[0], v[1], v[2]) - target) * self.decay + r * dt;
        let p = *x + vel * dt;
        let (mut state, mut at, mut fate) = (flakes::AIRBORNE, p, Fate::Nothing);
        if !flakes::over(c.area_min, c.area_max, p) {
            // Upwind of the area, on its way in, or gone.
            if !flakes::over(c.emit_min, c.emit_max, p) || p.y <= c.floor || *age > c.max_age {
                (state, fate) = (flakes::LEFT, Fate::Left);
            }
        } else {
            let k = flakes::cell(c, p.x, p.z);
            let cover = self.surface[k];
            let top = flakes::object_top(c, x.y, p, cover[1])
                .or_else(|| flakes::column_top([cover[2], cover[3]], x.y, p.y, cover[1]));
            if let Some(y) = top {
                (state, fate) = (flakes::LANDED, Fate::Top(k));
                at.y = y;
            } else if p.y <= cover[0] {
                (state, fate) = (flakes::LANDED, Fate::Ground(k));
                at.y = cover[0];
            } else if *age > c.max_age {
                (state, fate) = (flakes::LEFT, Fate::Left);
            }
        }
        *x = at;
        *v = [vel.x, vel.y, vel.z, state];
        fate
    }
}

impl CpuPass for Fall {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let c = cx.model.consts::<SnowfallConsts>();
        let a = &mut *cx.attrs;
        let (hx, hv, hage) =
            (a.handle::<Vec3>(FLAKE_X.name), a.handle::<[f32; 4]>(FLAKE_V.name), a.handle::<f32>(FLAKE_AGE.name));
        let (ht, hg, ho) =
            (a.handle::<u32>(TALLY.name), a.handle::<u32>(GROUND_COUNT.name), a.handle::<u32>(TOP_COUNT.name));
        let (mut x, mut v, mut age) = (a.take(hx), a.take(hv), a.take(hage));
        let (mut tally, mut ground, mut top) = (a.take(ht), a.take(hg), a.take(ho));
        let clock = a.get(a.handle::<f32>(TIMER.name))[flakes::timer::CLOCK];
        let w = flakes::wind(c, clock);
        let sky = Sky {
            c,
            dt: cx.dt,
            target: Vec3::new(w[0], -c.terminal_speed, w[1]),
            clock,
            decay: (-cx.dt / c.tau).exp(),
            first: tally[flakes::tally::FIRST],
            born: tally[flakes::tally::BORN],
            surface: a.get(a.handle::<[f32; 4]>(SURFACE.name)),
        };
        let fates: Vec<Vec<Fate>> = x
            .par_chunks_mut(CHUNK)
            .zip(v.par_chunks_mut(CHUNK))
            .zip(age.par_chunks_mut(CHUNK))
            .enumerate()
            .map(|(chunk, ((x, v), age))| {
                let base = (chunk * CHUNK) as u32;
                let mut out = Vec::new();
                for (s, ((x, v), age)) in x.iter_mut().zip(v.iter_mut()).zip(age.iter_mut()).enumerate() {
                    match sky.advance(base + s as u32, x, v, age) {
                        Fate::Nothing => {}
                        fate => out.push(fate),
                    }
                }
                out
            })
            .collect();
        for fate in fates.into_iter().flatten() {
            match fate {
                Fate::Left => tally[flakes::tally::LEFT] += 1,
                Fate::Ground(k) => ground[k] += 1,
                Fate::Top(k) => top[k] += 1,
                Fate::Nothing => {}
            }
        }
        let a = &mut *cx.attrs;
        a.put(hx, x);
        a.put(hv, v);
        a.put(hage, age);
        a.put(ht, tally);
        a.put(hg, ground);
        a.put(ho, top);
    }
}

/// `snow_surface = (bed + ground_count d, top_count d, column bottom, column top)`,
/// `d` the depth per flake.
#[derive(Debug)]
pub struct Surface;

impl CpuPass for Surface {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let per = cx.model.consts::<SnowfallConsts>().depth_per_flake;
        let a = &mut *cx.attrs;
        let h = a.handle::<[f32; 4]>(SURFACE.name);
        let mut surface = a.take(h);
        let (bed, ground, top, columns) = (
            a.get(a.handle::<f32>(BED.name)),
            a.get(a.handle::<u32>(GROUND_COUNT.name)),
            a.get(a.handle::<u32>(TOP_COUNT.name)),
            a.get(a.handle::<[f32; 4]>(super::columns::COLUMNS.name)),
        );
        for (k, s) in surface.iter_mut().enumerate() {
            *s = [bed[k] + ground[k] as f32 * per, top[k] as f32 * per, columns[k][0], columns[k][1]];
        }
        a.put(h, surface);
    }
}
