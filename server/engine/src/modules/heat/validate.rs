//! The `heat` section's checks: each names the setting it rejects and why.

use super::{MAX_BOXES, SECTION, phase, spec, viscosity};
use crate::scene::Scene;
use crate::scene::validate::Checker;

/// Checks a scene's `heat` section, where it has one.
pub(super) fn validate(scene: &Scene, c: &mut Checker) {
    let Some(heat) = scene.section::<spec::Heat>(SECTION) else { return };
    let fluids = crate::module::materials(scene);
    if heat.fluids.len() != fluids {
        c.fail("heat.fluids", format!("must hold one entry per fluid ({fluids}), got {}", heat.fluids.len()));
    }
    let [lo, hi] = heat.range;
    c.positive("heat.range[0]", lo);
    if c.finite("heat.range[1]", hi) && hi <= lo {
        c.fail("heat.range[1]", format!("must exceed range[0] = {lo}, got {hi}"));
    }
    let temperature = |c: &mut Checker, path: &str, t: f32| {
        if c.finite(path, t) && !(lo..=hi).contains(&t) {
            c.fail(path, format!("must lie within heat.range [{lo}, {hi}] K, got {t}"));
        }
    };
    temperature(c, "heat.reference_temperature", heat.reference_temperature);
    if let Some(g) = &heat.buoyancy_gravity {
        c.vector("heat.buoyancy_gravity", g);
    }
    for (i, f) in heat.fluids.iter().enumerate() {
        let p = format!("heat.fluids[{i}]");
        c.within(&format!("{p}.conductivity"), f.conductivity, 0.0, 1e6);
        c.positive(&format!("{p}.heat_capacity"), f.heat_capacity);
        c.within(&format!("{p}.expansion"), f.expansion, -0.1, 0.1);
        temperature(c, &format!("{p}.temperature"), f.temperature);
        if let Some(law) = &f.viscosity {
            validate_law(c, &format!("{p}.viscosity"), law);
        }
        if let Some(m) = &f.melting {
            temperature(c, &format!("{p}.melting.temperature"), m.temperature);
            c.within(&format!("{p}.melting.latent_heat"), m.latent_heat, 1.0, 1e8);
        }
    }
    phase::validate(scene, &heat, c);
    c.positive("heat.max_viscosity", heat.max_viscosity);
    crate::viscosity::validate_solver(c, "heat.viscous_solver", heat.viscous_solver);
    for (name, boxes) in [("regions", &heat.regions), ("walls", &heat.walls)] {
        for (i, b) in boxes.iter().enumerate() {
            let p = format!("heat.{name}[{i}]");
            c.ordered_box(&p, b.min, b.max);
            temperature(c, &format!("{p}.temperature"), b.temperature);
        }
    }
    for (i, s) in heat.sources.iter().enumerate() {
        c.ordered_box(&format!("heat.sources[{i}]"), s.min, s.max);
        c.finite(&format!("heat.sources[{i}].power"), s.power);
    }
    for (i, f) in heat.fluxes.iter().enumerate() {
        c.ordered_box(&format!("heat.fluxes[{i}]"), f.min, f.max);
        c.finite(&format!("heat.fluxes[{i}].flux"), f.flux);
    }
    let sources = heat.sources.len() + heat.fluxes.len();
    for (name, count) in [("walls", heat.walls.len()), ("sources", sources)] {
        if count > MAX_BOXES {
            let what = if name == "sources" { "sources and fluxes together" } else { "boxes" };
            c.fail(&format!("heat.{name}"), format!("at most {MAX_BOXES} {what}, got {count}"));
        }
    }
}

/// A temperature law's parameters: positive viscosities and temperatures, a table's
/// temperatures rising.
fn validate_law(c: &mut Checker, p: &str, law: &spec::ViscosityLaw) {
    match law {
        spec::ViscosityLaw::Exponential { mu_ref, t_ref, b } => {
            c.positive(&format!("{p}.mu_ref"), *mu_ref);
            c.positive(&format!("{p}.t_ref"), *t_ref);
            c.within(&format!("{p}.b"), *b, -1.0, 1.0);
        }
        spec::ViscosityLaw::Arrhenius { mu_ref, t_ref, activation_temperature } => {
            c.positive(&format!("{p}.mu_ref"), *mu_ref);
            c.positive(&format!("{p}.t_ref"), *t_ref);
            c.within(&format!("{p}.activation_temperature"), *activation_temperature, -1e5, 1e5);
        }
        spec::ViscosityLaw::Table { points } => {
            if !(2..=viscosity::MAX_POINTS).contains(&points.len()) {
                let n = viscosity::MAX_POINTS;
                c.fail(&format!("{p}.points"), format!("must hold 2 to {n} points, got {}", points.len()));
            }
            for (k, &[t, mu]) in points.iter().enumerate() {
                c.positive(&format!("{p}.points[{k}][0]"), t);
                c.non_negative(&format!("{p}.points[{k}][1]"), mu);
                if k > 0 && t.is_finite() && t <= points[k - 1][0] {
                    c.fail(
                        &format!("{p}.points[{k}][0]"),
                        format!("must exceed the previous point's {}, got {t}", points[k - 1][0]),
                    );
                }
            }
        }
    }
}
