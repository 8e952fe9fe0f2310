//! Quantities modules share through the core: the one way modules couple. A
//! module never calls another or reads its section; it claims a quantity the core
//! declares here ([`crate::module::ModuleDef::claims`]), per material, and the core
//! resolves the claims of a scene's modules before any module builds: who writes
//! the quantity, who scales it, what is refused (naming both settings). A module
//! then asks the resolution ([`Resolution::role`]) what it does, whichever modules
//! it shares the scene with and whatever order they were listed or built in.
//!
//! | quantity | attribute | unit | combine |
//! |---|---|---|---|
//! | [`VISCOSITY`] | `mu` | Pa s | set once: one module per scene writes it per particle |
//! | [`VISCOSITY_FACTOR`] | `viscosity_shift` | 1 | multiply: modules scale what the setter writes |
//! | [`LIQUID_FRACTION`] | `liquid_fraction` | 1 | set by the module that changes a solid's phase (heat's melting); read by those that blend by it (the solid module) |
//!
//! The viscosity's force (explicit or implicit, [`crate::viscosity`]) is the core's:
//! it acts on `mu` whoever wrote it, integrated as the setting module chose.

use crate::attrs::AttrSpec;
use crate::scene::Scene;
use crate::scene::validate::Checker;
use crate::viscosity::{self, Integration};

/// A quantity of the core that modules may write or read.
#[derive(Debug)]
pub struct Quantity {
    /// What it is, for messages.
    pub about: &'static str,
    /// The attribute holding it (allocated by the core when a module claims it).
    pub attr: &'static AttrSpec,
}

/// Dynamic viscosity per particle (Pa s).
pub static VISCOSITY: Quantity = Quantity { about: "viscosity", attr: &viscosity::MU };

/// A factor on the viscosity a module sets (1).
pub static VISCOSITY_FACTOR: Quantity = Quantity { about: "viscosity factor", attr: &viscosity::FACTOR };

/// The liquid fraction of each particle that melts or freezes: 0 solid, 1
/// liquid, in between while it melts or freezes; 0 for materials that never
/// change phase (so an elastic body that does not melt stays elastic). The heat module allocates and writes it in scenes where a
/// fluid melts (`heat.fluids[i].melting`); the solid module, built after it,
/// blends its particles' solid and fluid updates by it where the scene has it.
pub static LIQUID_FRACTION: AttrSpec = AttrSpec {
    name: "liquid_fraction",
    elem: crate::attrs::Elem::F32,
    unit: "1",
    role: crate::attrs::Role::State,
    added_later: false,
    space: crate::attrs::PARTICLES,
    module: "core",
    about: "Liquid fraction beta: 0 solid, 1 liquid.",
};

/// What a module does with the viscosity of one material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Write {
    /// Writes `mu` for the material's particles from their state (a rheology),
    /// integrated as `how` says; `scalable` if it multiplies in the factor.
    Sets {
        /// The force's integration.
        how: Integration,
        /// Whether the module's pass applies [`VISCOSITY_FACTOR`].
        scalable: bool,
    },
    /// Gives the material its viscosity by a force of its own (the fluid module's
    /// model): a module whose law would set `mu` for the material is refused.
    Own,
    /// Sets `mu` where no module of the scene sets it (integrated as `how` says),
    /// and otherwise scales the setter's through [`VISCOSITY_FACTOR`].
    SetsOrScales {
        /// The force's integration, where it sets.
        how: Integration,
    },
}

/// A module's claim on the viscosity of one material.
#[derive(Debug, Clone, PartialEq)]
pub struct Claim {
    /// The material (the fluids' order).
    pub material: usize,
    /// The scene setting that makes the claim (`snow.fluids[0].model`), for messages.
    pub path: String,
    /// What the module does.
    pub write: Write,
    /// What the setting must become where another claim excludes it
    /// (`must be {"model": "none"}`), shown after its path.
    pub fix: &'static str,
}

/// What a module does with the viscosity in one scene, once resolved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Writes `mu`.
    Sets,
    /// Writes the factor the setter multiplies `mu` by.
    Scales,
}

/// The resolved claims of a scene's modules.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Resolution {
    /// Each claiming module's role, by module id.
    roles: Vec<(&'static str, Role)>,
    /// How the per-particle viscosity's force is integrated, if a module sets it.
    integration: Option<Integration>,
}

impl Resolution {
    /// What module `id` does with the viscosity, if it claimed any.
    pub fn role(&self, id: &str) -> Option<Role> {
        self.roles.iter().find(|(m, _)| *m == id).map(|&(_, r)| r)
    }

    /// Whether some module scales the viscosity (the setter then reads the factor).
    pub fn scaled(&self) -> bool {
        self.roles.iter().any(|&(_, r)| r == Role::Scales)
    }

    /// The integration of the per-particle viscosity, if a module sets it.
    pub fn integration(&self) -> Option<Integration> {
        self.integration
    }
}

/// The claims of `scene`'s modules, each with its module's id, in registry order.
fn claims(scene: &Scene) -> Vec<(&'static str, Claim)> {
    crate::module::of(scene).into_iter().flat_map(|m| (m.claims)(scene).into_iter().map(move |c| (m.id, c))).collect()
}

/// Resolves the claims of `scene`'s modules, reporting conflicts to `c` (each at the
/// setting that must change, naming the other).
pub fn check(scene: &Scene, c: &mut Checker) -> Resolution {
    resolve(&claims(scene), c)
}

/// Resolves `scene`'s claims (validated before: conflicts are not reported).
pub fn resolution(scene: &Scene) -> Resolution {
    check(scene, &mut Checker::default())
}

fn resolve(claims: &[(&'static str, Claim)], c: &mut Checker) -> Resolution {
    let setters: Vec<&(&str, Claim)> = claims.iter().filter(|(_, k)| matches!(k.write, Write::Sets { .. })).collect();
    let mut out = Resolution::default();
    if let Some((first, claim)) = setters.first() {
        if let Some((second, other)) = setters.iter().find(|(m, _)| m != first) {
            c.fail(&other.path, format!("{second} cannot set the {} {first} sets ({})", VISCOSITY.about, claim.path));
        }
        if let Write::Sets { how, .. } = claim.write {
            out.integration = Some(how);
        }
        out.roles.push((first, Role::Sets));
    }
    let rheology = !setters.is_empty();
    for (module, claim) in claims {
        let Write::SetsOrScales { how } = claim.write else { continue };
        let role = if rheology { Role::Scales } else { Role::Sets };
        if role == Role::Sets && out.integration.is_none() {
            out.integration = Some(how);
        }
        if !out.roles.iter().any(|(m, _)| m == module) {
            out.roles.push((module, role));
        }
        let verb = if role == Role::Sets { "sets" } else { "scales" };
        // The other claims on this material that cannot take this one's role.
        for (_, other) in claims.iter().filter(|(m, o)| m != module && o.material == claim.material) {
            let excluded = match other.write {
                Write::Own => role == Role::Sets,
                Write::Sets { scalable, .. } => !scalable,
                Write::SetsOrScales { .. } => false,
            };
            if excluded {
                c.fail(&other.path, format!("{}: {} {verb} this fluid's {}", other.fix, claim.path, VISCOSITY.about));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viscosity::{ViscousSolver, WallShear};

    const HOW: Integration = Integration { solver: ViscousSolver::Explicit, walls: WallShear::NoSlip };

    fn claim(material: usize, path: &str, write: Write) -> Claim {
        Claim { material, path: path.into(), write, fix: "must change" }
    }

    fn errors(claims: &[(&'static str, Claim)]) -> (Resolution, Vec<String>) {
        let mut c = Checker::default();
        let r = resolve(claims, &mut c);
        (r, c.into_errors())
    }

    #[test]
    fn a_law_sets_alone_and_scales_a_rheology() {
        let law = ("heat", claim(0, "heat.fluids[0].viscosity", Write::SetsOrScales { how: HOW }));
        let (alone, e) = errors(std::slice::from_ref(&law));
        assert!(e.is_empty(), "{e:?}");
        assert_eq!(alone.role("heat"), Some(Role::Sets));
        assert!(!alone.scaled());
        let rheology = ("snow", claim(0, "snow.fluids[0]", Write::Sets { how: HOW, scalable: true }));
        // Whichever order the claims come in, the rheology sets and the law scales.
        for claims in [vec![law.clone(), rheology.clone()], vec![rheology.clone(), law.clone()]] {
            let (both, e) = errors(&claims);
            assert!(e.is_empty(), "{e:?}");
            assert_eq!((both.role("snow"), both.role("heat")), (Some(Role::Sets), Some(Role::Scales)));
            assert!(both.scaled());
        }
    }

    #[test]
    fn conflicts_are_named_at_the_setting_that_must_change() {
        let law = ("heat", claim(0, "heat.fluids[0].viscosity", Write::SetsOrScales { how: HOW }));
        let own = ("fluid", claim(0, "fluids[0].viscosity", Write::Own));
        let (_, e) = errors(&[own.clone(), law.clone()]);
        assert_eq!(e, ["fluids[0].viscosity: must change: heat.fluids[0].viscosity sets this fluid's viscosity"]);
        let fixed = ("snow", claim(0, "snow.fluids[0].model", Write::Sets { how: HOW, scalable: false }));
        let (_, e) = errors(&[own, fixed, law]);
        assert_eq!(e, ["snow.fluids[0].model: must change: heat.fluids[0].viscosity scales this fluid's viscosity"]);
        let a = ("snow", claim(0, "snow.fluids[0]", Write::Sets { how: HOW, scalable: true }));
        let b = ("ice", claim(1, "ice.fluids[1]", Write::Sets { how: HOW, scalable: true }));
        let (_, e) = errors(&[a, b]);
        assert_eq!(e, ["ice.fluids[1]: ice cannot set the viscosity snow sets (snow.fluids[0])"]);
    }
}
