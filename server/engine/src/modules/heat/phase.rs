//! Melting and freezing by enthalpy (Floe's model, docs/ice.md; the enthalpy
//! method of phase change, e.g. Voller & Prakash 1987, on SPH particles).
//!
//! A fluid with `melting` is the solid phase of a substance (ice); the module
//! declares its melt as a phase of it ([`crate::model::ModelBuilder::phase`]) like
//! the fluid named `into` (water): the melt keeps the solid's particle mass, so
//! mass is conserved exactly, and takes the rest density, viscosity, conductivity
//! and heat capacity of `into`. Each particle of either phase carries a specific
//! enthalpy `H` (J/kg) relative to the solid at the melting point `T_m`:
//!
//! - `H < 0`: solid, `T = T_m + H / c_s`, liquid fraction `beta = 0`;
//! - `0 <= H <= L`: melting, `T = T_m`, `beta = H / L`;
//! - `H > L`: liquid, `T = T_m + (H - L) / c_l`, `beta = 1`.
//!
//! The conduction pass gives `dT/dt` with the capacity `c` of the particle's
//! material, so `dH = c dT/dt dt` is the heat per kilogram it took in whatever its
//! phase (summed with Kahan's compensation, as the temperature is). A particle
//! becomes the melt once `H >= L` (fully melted) and the solid again once `H <= 0`
//! (fully frozen); in between it keeps the phase it had, so a melting particle is
//! still solid (an elastic body's member) and a freezing one still liquid. `beta`
//! is the core's quantity [`crate::quantities::LIQUID_FRACTION`]: the solid module
//! blends a melting particle's updates by it (the first thesis's eqs. 2.39-2.40).
//! Heat conducts with each material's own conductivity and capacity, so the total
//! heat `sum m (c_s T_m + H)` (and `sum m c T` for particles that never change
//! phase) changes only through walls and sources.
//!
//! Here too: the `melting` entries' check ([`validate`]), the melt's declaration
//! ([`declare`]), the state and passes a scene that melts adds ([`build`]).

use super::HeatConsts;
use super::passes::compensated_add;
use crate::attrs::Column;
use crate::attrs::{AttrSpec, Elem, PARTICLES, Role};
use crate::cpu::{CpuCx, CpuPass};
use crate::materials::Material;
use crate::math::Real;
use crate::model::{BuildError, ModelBuilder};
use crate::plan::{PassSpec, Stage};
use crate::scene::Scene;
use crate::scene::validate::Checker;
use rayon::prelude::*;

/// A substance's phase change, as each of its two materials sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhaseChange {
    /// Melting point T_m (K).
    pub melting_point: Real,
    /// Specific latent heat L (J/kg).
    pub latent: Real,
    /// The solid's heat capacity c_s (J/(kg K)).
    pub solid_capacity: Real,
    /// The melt's heat capacity c_l (J/(kg K)).
    pub liquid_capacity: Real,
    /// The solid's material index.
    pub solid: u32,
    /// The melt's material index.
    pub liquid: u32,
}

impl PhaseChange {
    /// The enthalpy (J/kg, relative to the solid at `T_m`) of a particle at `t`
    /// (K) with liquid fraction `beta`.
    pub fn enthalpy(&self, t: Real, beta: Real) -> Real {
        if t < self.melting_point {
            self.solid_capacity * (t - self.melting_point)
        } else if t > self.melting_point {
            self.latent + self.liquid_capacity * (t - self.melting_point)
        } else {
            beta * self.latent
        }
    }

    /// The enthalpy of a particle of the solid starting at `t`: below the melting
    /// point the solid's, above it the melt's (it melts in its first step).
    pub fn initial(&self, t: Real) -> Real {
        self.enthalpy(t, 0.0)
    }

    /// The temperature (K) at enthalpy `h` (melting.wgsl computes the same).
    pub fn temperature(&self, h: Real) -> Real {
        if h < 0.0 {
            self.melting_point + h / self.solid_capacity
        } else if h > self.latent {
            self.melting_point + (h - self.latent) / self.liquid_capacity
        } else {
            self.melting_point
        }
    }

    /// The liquid fraction at enthalpy `h`.
    pub fn fraction(&self, h: Real) -> Real {
        (h / self.latent).clamp(0.0, 1.0)
    }

    /// The material of a particle of `material` at enthalpy `h`: the melt once
    /// fully melted, the solid once fully frozen, else as it was.
    pub fn material(&self, h: Real, material: u32) -> u32 {
        if h >= self.latent {
            self.liquid
        } else if h <= 0.0 {
            self.solid
        } else {
            material
        }
    }

    /// The heat (J/kg) of a particle at enthalpy `h` counted from 0 K along the
    /// solid's capacity: `c_s T_m + H`.
    pub fn heat(&self, h: Real) -> f64 {
        f64::from(self.solid_capacity) * f64::from(self.melting_point) + f64::from(h)
    }
}

/// A per-particle f32 attribute of the module.
const fn attr(name: &'static str, unit: &'static str, role: Role, about: &'static str) -> AttrSpec {
    AttrSpec { name, elem: Elem::F32, unit, role, added_later: false, space: PARTICLES, module: "heat", about }
}

/// Specific enthalpy (J/kg), the state of particles that change phase.
pub static ENTHALPY: AttrSpec = attr(
    "enthalpy",
    "J/kg",
    Role::State,
    "Specific enthalpy relative to the solid at its melting point (particles that melt or freeze).",
);

/// The rounding lost from the enthalpy's last increments (J/kg).
pub static ENTHALPY_CARRY: AttrSpec = attr(
    "enthalpy_carry",
    "J/kg",
    Role::State,
    "Rounding lost from the enthalpy's last increments, subtracted from the next.",
);

/// The part of `dT/dt` from held walls and sources (K/s), where a fluid melts and
/// heat enters from outside.
pub static HEAT_INPUT: AttrSpec = attr(
    "heat_input",
    "K/s",
    Role::Derived,
    "The part of the temperature's rate from walls held at a temperature and from sources.",
);

/// The heat each particle took in from walls and sources since the start (J/kg).
pub static HEAT_IN: AttrSpec = attr(
    "heat_in",
    "J/kg",
    Role::State,
    "Heat taken in from walls held at a temperature and from sources since the start, per kilogram.",
);

/// The rounding lost from `heat_in`'s last increments (J/kg).
pub static HEAT_IN_CARRY: AttrSpec = attr(
    "heat_in_carry",
    "J/kg",
    Role::State,
    "Rounding lost from heat_in's last increments, subtracted from the next.",
);

/// `heat_in += c heat_input dt`, compensated: what a wall or a source gave each
/// particle, summed apart from conduction between particles, so the energy
/// balance (heat in = sensible + latent heat stored) is a check of the phase
/// change's bookkeeping and of the conduction's antisymmetry, not an identity.
pub static INPUT: PassSpec = PassSpec {
    name: "heat.input",
    module: "heat",
    stage: Stage::Kick,
    reads: &["heat_input", "material"],
    writes: &[],
    accumulates: &["heat_in", "heat_in_carry"],
    tolerance: 1e-5,
};

/// The integration of scenes where a fluid melts: the temperature of the other
/// particles, the enthalpy, temperature, liquid fraction and phase of those that
/// melt or freeze.
pub static MELT: PassSpec = PassSpec {
    name: "heat.melt",
    module: "heat",
    stage: Stage::Kick,
    reads: &["heat_rate"],
    writes: &["liquid_fraction"],
    accumulates: &["temperature", "temperature_carry", "enthalpy", "enthalpy_carry", "material"],
    tolerance: 1e-5,
};

/// The phase of each material (`None` where it never changes phase), from the
/// scene's `melting` entries and the materials table (solid and melt both get it).
pub fn phases(heat: &super::spec::Heat, materials: &[Material], capacity: &[Real]) -> Vec<Option<PhaseChange>> {
    let mut out = vec![None; materials.len()];
    for (i, f) in heat.fluids.iter().enumerate() {
        let Some(m) = &f.melting else { continue };
        let Some(liquid) = materials.iter().position(|x| x.name == melt_name(&materials[i].name)) else { continue };
        let phase = PhaseChange {
            melting_point: m.temperature,
            latent: m.latent_heat,
            solid_capacity: capacity[i],
            liquid_capacity: capacity[liquid],
            solid: i as u32,
            liquid: liquid as u32,
        };
        (out[i], out[liquid]) = (Some(phase), Some(phase));
    }
    out
}

/// The name of the melt of the fluid `solid`.
pub fn melt_name(solid: &str) -> String {
    format!("{solid}_melt")
}

/// Declares the melt of each fluid that melts, a phase of it like its `into`.
pub fn declare(scene: &Scene, b: &mut ModelBuilder) -> Result<(), BuildError> {
    let Some(heat) = scene.section::<super::spec::Heat>(super::SECTION) else { return Ok(()) };
    for (i, f) in heat.fluids.iter().enumerate() {
        let Some(m) = &f.melting else { continue };
        let names: Vec<String> = b.materials().iter().map(|m| m.name.clone()).collect();
        let Some(like) = names.iter().position(|n| *n == m.into) else {
            return Err(BuildError::Setting(format!(
                "heat.fluids[{i}].melting.into: no fluid named {:?} (the scene's: {names:?})",
                m.into
            )));
        };
        let rho = b.materials()[like].rest_density;
        b.phase(i as u32, like as u32, &melt_name(&names[i]), rho);
    }
    Ok(())
}

/// Each `melting.into` names another fluid of the scene, one that does not melt
/// itself (its melt would have two phase changes).
pub fn validate(scene: &Scene, heat: &super::spec::Heat, c: &mut Checker) {
    /// What this check reads of a fluid (the fluid module's section, as data).
    #[derive(serde::Deserialize)]
    struct Named {
        name: String,
    }
    let names: Vec<String> =
        scene.section::<Vec<Named>>("fluids").unwrap_or_default().into_iter().map(|f| f.name).collect();
    for (i, m) in heat.fluids.iter().enumerate().filter_map(|(i, f)| f.melting.as_ref().map(|m| (i, m))) {
        let path = format!("heat.fluids[{i}].melting.into");
        match names.iter().position(|n| *n == m.into) {
            None => c.fail(&path, format!("no fluid named {:?} (the scene's: {names:?})", m.into)),
            Some(j) if j == i => c.fail(&path, "must name another fluid than the one that melts".into()),
            Some(j) if heat.fluids.get(j).is_some_and(|f| f.melting.is_some()) => {
                c.fail(&path, format!("names {:?}, which melts itself", m.into))
            }
            Some(_) => {}
        }
    }
}

/// The state of particles that melt or freeze: each one's enthalpy from its
/// starting temperature, its liquid fraction, and the integration that changes
/// their phase.
pub fn build(b: &mut ModelBuilder, consts: &HeatConsts, t: &[Real]) {
    let material = match b.column("material") {
        Some(Column::U32(m)) => m.clone(),
        _ => unreachable!("a fluid that melts and its melt are two materials"),
    };
    let h: Vec<Real> =
        t.iter().zip(&material).map(|(&t, &m)| consts.phases[m as usize].map_or(0.0, |p| p.initial(t))).collect();
    let beta =
        h.iter().zip(&material).map(|(&h, &m)| consts.phases[m as usize].map_or(0.0, |p| p.fraction(h))).collect();
    b.attr(&ENTHALPY, Column::F32(h));
    b.zeros(&ENTHALPY_CARRY);
    b.attr(&crate::quantities::LIQUID_FRACTION, Column::F32(beta));
    b.pass(&MELT);
    b.channel(super::LIQUID_FRACTION_CHANNEL);
    if consts.takes_input() {
        b.zeros(&HEAT_INPUT);
        b.zeros(&HEAT_IN);
        b.zeros(&HEAT_IN_CARRY);
        b.pass(&INPUT);
    }
}

/// The integration on the CPU.
#[derive(Debug)]
pub struct Melt;

impl CpuPass for Melt {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let dt = cx.dt;
        let hc: &HeatConsts = cx.model.consts();
        let a = &mut *cx.attrs;
        let handles = (
            a.handle::<Real>("temperature"),
            a.handle::<Real>("temperature_carry"),
            a.handle::<Real>(ENTHALPY.name),
            a.handle::<Real>(ENTHALPY_CARRY.name),
            a.handle::<Real>(crate::quantities::LIQUID_FRACTION.name),
            a.handle::<u32>("material"),
        );
        let (mut t, mut tc, mut h, mut hcarry, mut beta, mut material) = (
            a.take(handles.0),
            a.take(handles.1),
            a.take(handles.2),
            a.take(handles.3),
            a.take(handles.4),
            a.take(handles.5),
        );
        let rate = a.get(a.handle::<Real>("heat_rate"));
        let each = t
            .par_iter_mut()
            .zip(tc.par_iter_mut())
            .zip(h.par_iter_mut())
            .zip(hcarry.par_iter_mut())
            .zip(beta.par_iter_mut())
            .zip(material.par_iter_mut())
            .zip(rate.par_iter())
            .with_min_len(4096);
        each.for_each(|((((((t, tc), h), hcarry), beta), m), &r)| {
            let own = *m as usize;
            match hc.phases[own] {
                None => (*t, *tc) = compensated_add(*t, *tc, dt * r),
                Some(p) => {
                    (*h, *hcarry) = compensated_add(*h, *hcarry, dt * r * hc.capacity[own]);
                    *t = p.temperature(*h);
                    *beta = p.fraction(*h);
                    *m = p.material(*h, *m);
                }
            }
        });
        let a = &mut *cx.attrs;
        a.put(handles.0, t);
        a.put(handles.1, tc);
        a.put(handles.2, h);
        a.put(handles.3, hcarry);
        a.put(handles.4, beta);
        a.put(handles.5, material);
    }
}

/// The heat taken in from outside, on the CPU.
#[derive(Debug)]
pub struct Input;

impl CpuPass for Input {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let dt = cx.dt;
        let hc: &HeatConsts = cx.model.consts();
        let a = &mut *cx.attrs;
        let (hi, hc_) = (a.handle::<Real>(HEAT_IN.name), a.handle::<Real>(HEAT_IN_CARRY.name));
        let (mut sum, mut carry) = (a.take(hi), a.take(hc_));
        let input = a.get(a.handle::<Real>(HEAT_INPUT.name));
        let material = a.get(a.handle::<u32>("material"));
        let each = sum.par_iter_mut().zip(carry.par_iter_mut()).zip(input.par_iter().zip(material)).with_min_len(4096);
        each.for_each(|((s, c), (&q, &m))| (*s, *c) = compensated_add(*s, *c, dt * q * hc.capacity[m as usize]));
        a.put(hi, sum);
        a.put(hc_, carry);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ICE: PhaseChange = PhaseChange {
        melting_point: 273.15,
        latent: 3.34e5,
        solid_capacity: 2100.0,
        liquid_capacity: 4186.0,
        solid: 0,
        liquid: 2,
    };

    #[test]
    fn enthalpy_and_temperature_agree_across_the_phases() {
        for t in [250.0, 273.0, 273.15, 274.0, 300.0] {
            let h = ICE.enthalpy(t, 0.0);
            assert!((ICE.temperature(h) - t).abs() < 1e-3, "{t}: {h} gives {}", ICE.temperature(h));
        }
        assert_eq!(ICE.enthalpy(273.15, 0.25), 0.25 * 3.34e5);
        assert_eq!(ICE.temperature(1e5), 273.15);
        assert_eq!(ICE.fraction(ICE.latent * 0.5), 0.5);
        assert_eq!(ICE.fraction(-10.0), 0.0);
        assert_eq!(ICE.fraction(1e6), 1.0);
    }

    #[test]
    fn a_bad_melting_entry_is_named() {
        let errors = |o: &[&str]| {
            let o: Vec<String> = o.iter().map(|s| s.to_string()).collect();
            crate::scene::load::from_preset("ice_cube_in_glass", &o).unwrap_err().to_string()
        };
        assert_eq!(
            errors(&["heat.fluids[1].melting.into=\"lava\""]),
            "heat.fluids[1].melting.into: no fluid named \"lava\" (the scene's: [\"water\", \"ice\"])"
        );
        assert_eq!(
            errors(&["heat.fluids[1].melting.into=\"ice\""]),
            "heat.fluids[1].melting.into: must name another fluid than the one that melts"
        );
        assert_eq!(
            errors(&["heat.fluids[1].melting.latent_heat=-1"]),
            "heat.fluids[1].melting.latent_heat: must be between 1 and 100000000, got -1"
        );
        // Oriented particles melt too (solid/tests.rs).
        let oriented = crate::scene::load::from_preset("ice_cube_in_glass", &["solid.oriented={}".into()]).unwrap();
        crate::model::Model::build(&oriented).unwrap();
    }

    #[test]
    fn a_particle_changes_phase_only_when_fully_melted_or_frozen() {
        assert_eq!(ICE.material(-1.0, 2), 0, "frozen melt is ice");
        assert_eq!(ICE.material(0.5 * ICE.latent, 0), 0, "half-melted ice is still ice");
        assert_eq!(ICE.material(0.5 * ICE.latent, 2), 2, "half-frozen melt is still melt");
        assert_eq!(ICE.material(ICE.latent, 0), 2, "fully melted ice is melt");
    }
}
