//! `floe plan`: what a scene is made of before it runs: its scheme and modules,
//! its materials, the attributes each index space holds (with their cost), the
//! passes of a step in order, and the channels frames can carry.

use floe_engine::attrs::{PARTICLES, Role};
use floe_engine::model::Model;
use floe_engine::scene::load;
use std::fmt::Write as _;

/// The plan of `source` (a preset or a file) with `overrides`, its terrain assets
/// read from `assets`, as text.
pub fn describe(source: &str, overrides: &[String], assets: Option<&std::path::Path>) -> anyhow::Result<String> {
    let scene = load::with_assets(load::resolve(source, overrides)?, assets)?;
    let model = Model::build(&scene)?;
    let mut out = String::new();
    let modules: Vec<&str> = model.modules.iter().map(|m| m.id).collect();
    writeln!(out, "scene {}: scheme {}, modules {}", scene.name, model.scheme.id, modules.join(", "))?;
    for (space, n) in &model.layout.spaces {
        writeln!(out, "space {space}: {n}")?;
    }
    writeln!(out, "\nmaterials")?;
    for (i, m) in model.materials.iter().enumerate() {
        writeln!(
            out,
            "  {i} {:<12} {:?}, rest density {} kg/m^3, particle mass {:.4e} kg",
            m.name, m.kind, m.rest_density, m.mass
        )?;
    }
    writeln!(out, "\nattributes (CPU bytes per element)")?;
    let mut per_particle = 0;
    for s in model.layout.specs() {
        let role = match s.role {
            Role::State => "state",
            Role::Derived => "derived",
            Role::Constant => "constant",
        };
        writeln!(
            out,
            "  {:<10} {:<8} {:>3} B  {:<8} {:<14} {}",
            s.name,
            s.space,
            s.elem.cpu_bytes(),
            role,
            s.unit,
            s.module
        )?;
        if s.space == PARTICLES {
            per_particle += s.elem.cpu_bytes();
        }
    }
    writeln!(out, "  {per_particle} bytes per particle in attributes (the CPU adds ~140 for neighbour lists)")?;
    writeln!(out, "\npasses")?;
    for line in model.plan.table().lines() {
        writeln!(out, "  {line}")?;
    }
    writeln!(out, "\nchannels")?;
    for c in &model.channels {
        writeln!(out, "  {:<12} {:<8} {} x {:<3} {}", c.name, c.unit, c.components, c.set, c.module)?;
    }
    Ok(out)
}
