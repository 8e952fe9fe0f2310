//! Helpers shared by the integration tests: a small deterministic generator and
//! random frames.

#![allow(dead_code)]

use floe_proto::{Bounds, ChannelInfo, ChannelKind, Frame, FrameInput, GridInfo, ValuesRef};

/// xorshift64*: deterministic, seeded, good enough to vary test inputs.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform in `lo..=hi`.
    pub fn int(&mut self, lo: u64, hi: u64) -> u64 {
        lo + self.next_u64() % (hi - lo + 1)
    }

    pub fn chance(&mut self, p: f32) -> bool {
        self.unit() < p
    }
}

/// Particle data owned by a test, lent to the encoder as a [`FrameInput`].
#[derive(Debug, Clone, Default)]
pub struct Particles {
    pub positions: Vec<[f32; 3]>,
    pub set: u8,
    pub grid: Option<GridInfo>,
    pub velocities: Option<Vec<[f32; 3]>>,
    pub densities: Option<Vec<f32>>,
    pub pressures: Option<Vec<f32>>,
    pub temperatures: Option<Vec<f32>>,
    pub materials: Option<Vec<u8>>,
    /// A per-scene channel: its tag, components and values.
    pub extra: Option<(ChannelKind, u8, Vec<f32>)>,
    /// Stable ids, ascending (a set whose particles are born and die).
    pub ids: Option<Vec<u32>>,
}

impl Particles {
    pub fn input(&self) -> FrameInput<'_> {
        let mut channels = Vec::new();
        if let Some(v) = &self.velocities {
            channels.push((ChannelKind::VELOCITY, ValuesRef::Float { components: 3, data: v.as_flattened() }));
        }
        for (kind, v) in [
            (ChannelKind::DENSITY, &self.densities),
            (ChannelKind::PRESSURE, &self.pressures),
            (ChannelKind::TEMPERATURE, &self.temperatures),
        ] {
            if let Some(v) = v {
                channels.push((kind, ValuesRef::Float { components: 1, data: v }));
            }
        }
        if let Some(v) = &self.materials {
            channels.push((ChannelKind::MATERIAL, ValuesRef::Exact(v)));
        }
        if let Some((kind, components, v)) = &self.extra {
            channels.push((*kind, ValuesRef::Float { components: *components, data: v }));
        }
        FrameInput { positions: &self.positions, grid: self.grid, set: self.set, channels, ids: self.ids.as_deref() }
    }

    /// `n` particles inside `bounds`, with each other channel present with probability `p`.
    pub fn random(rng: &mut Rng, n: usize, bounds: &Bounds, p: f32) -> Self {
        let positions = (0..n).map(|_| std::array::from_fn(|k| rng.range(bounds.min[k], bounds.max[k]))).collect();
        let mut out = Particles { positions, ..Default::default() };
        if rng.chance(p) {
            out.velocities = Some((0..n).map(|_| std::array::from_fn(|_| rng.range(-4.0, 4.0))).collect());
        }
        if rng.chance(p) {
            out.densities = Some((0..n).map(|_| rng.range(950.0, 1100.0)).collect());
        }
        if rng.chance(p) {
            out.pressures = Some((0..n).map(|_| rng.range(-2e3, 3e4)).collect());
        }
        if rng.chance(p) {
            out.temperatures = Some((0..n).map(|_| rng.range(250.0, 380.0)).collect());
        }
        if rng.chance(p) {
            out.materials = Some((0..n).map(|_| rng.int(0, 3) as u8).collect());
        }
        if rng.chance(p) {
            out.extra = Some((ChannelKind(64), 2, (0..2 * n).map(|_| rng.range(-5.0, 5.0)).collect()));
        }
        out
    }

    /// Moves every particle by up to `step` (m) per axis, staying inside `bounds`, and
    /// perturbs the other channels a little.
    /// Moves every particle by its velocity over `dt` (s), clamped to `bounds`.
    pub fn drift(&mut self, bounds: &Bounds, dt: f32) {
        let v = self.velocities.as_ref().expect("drift needs velocities");
        for (p, v) in self.positions.iter_mut().zip(v) {
            for k in 0..3 {
                p[k] = (p[k] + v[k] * dt).clamp(bounds.min[k], bounds.max[k]);
            }
        }
    }

    pub fn advance(&mut self, rng: &mut Rng, bounds: &Bounds, step: f32) {
        for p in &mut self.positions {
            for (k, x) in p.iter_mut().enumerate() {
                *x = (*x + rng.range(-step, step)).clamp(bounds.min[k], bounds.max[k]);
            }
        }
        if let Some(v) = &mut self.velocities {
            v.iter_mut().flatten().for_each(|x| *x += rng.range(-0.1, 0.1));
        }
        let extra = self.extra.as_mut().map(|(_, _, v)| v);
        for s in [&mut self.densities, &mut self.pressures, &mut self.temperatures].into_iter().flatten().chain(extra) {
            s.iter_mut().for_each(|x| *x *= rng.range(0.99, 1.01));
        }
        if let Some(ph) = &mut self.materials {
            ph.iter_mut().filter(|_| rng.chance(0.01)).for_each(|x| *x = x.wrapping_add(1));
        }
    }
}

/// A random box between -10 and 10 m with sides of 0.01 to 5 m.
pub fn random_bounds(rng: &mut Rng) -> Bounds {
    let min: [f32; 3] = std::array::from_fn(|_| rng.range(-10.0, 10.0));
    Bounds { min, max: std::array::from_fn(|k| min[k] + rng.range(0.01, 5.0)) }
}

/// The largest error a channel's values may have: the stated maximum error plus f32
/// rounding of a few ulps of the range's magnitude.
pub fn tolerance(info: &ChannelInfo, component: usize) -> f32 {
    let r = info.ranges[component];
    r.max_error + 4.0 * f32::EPSILON * r.min.abs().max(r.max.abs())
}

/// The channel-table entry of `tag` in `frame`.
pub fn channel(frame: &Frame, tag: u8) -> &ChannelInfo {
    frame.header.channels.iter().find(|c| c.tag == tag).expect("channel present")
}
