//! Presets sized to the machine: a preset created without a resolution (from the
//! viewer, or any client that names no `particle_spacing`) starts at the finest
//! spacing this server's backend steps at least [`TARGET_RTF`] times real time, so
//! a viewer of the bunny or the avalanche watches it move, and a GPU gets the fine
//! version (`floe serve --preset-size auto`, the default; `full` keeps every
//! preset's own resolution). The choice is measured, not guessed: a few short runs
//! of the scene itself, a second or two in all, kept for the server's lifetime per
//! preset and overrides. The scene's info carries what was chosen and the full
//! size ([`Sizing`]), and the viewer offers the full size in one click.
//!
//! `floe serve` sizes its default scene, the dam break, the same way.

use floe_engine::Simulation;
use floe_engine::scene::load;
use floe_engine::simulation::BackendFactory;
use std::time::{Duration, Instant};

/// The real-time factor a preset aims at when stepped alone: twice the 0.5 a
/// viewer should see, leaving half the machine to the browser and the server.
pub const TARGET_RTF: f64 = 1.0;

/// Resolutions tried, finest first, as the spacing's divisor of the preset's own
/// times 28: the dam break's column width in spacings (28 is the preset's 21,952
/// particles, 10 is 1,000, still enough for the surge and the splash on the far
/// wall, so its column stays a whole number of spacings); a preset at 10 has
/// (10/28)^3, a twenty-second, of its particles.
const WIDTHS: &[u32] = &[28, 24, 20, 16, 14, 12, 10];

/// Wall time one measurement steps for, after a first step that is not timed (a GPU
/// compiles its kernels then).
const MEASURE: Duration = Duration::from_millis(250);

/// How many steps a measurement takes at least, whatever the wall time (a scene
/// whose first steps each take longer than [`MEASURE`]).
const MIN_STEPS: u64 = 2;

/// The resolution chosen for a preset, and why: what a scene's info says.
#[derive(Debug, Clone, PartialEq)]
pub struct Sizing {
    /// The chosen particle spacing (m).
    pub spacing: f32,
    /// Particles at that spacing.
    pub particles: usize,
    /// The real-time factor measured at that spacing, stepped alone.
    pub rtf: f64,
    /// The preset's own spacing (m): its full size.
    pub full_spacing: f32,
    /// Particles at the full size.
    pub full_particles: u64,
}

impl Sizing {
    /// Whether the chosen size is the preset's own.
    pub fn is_full(&self) -> bool {
        self.spacing == self.full_spacing
    }
}

/// The override that sets the spacing of width `width` on a preset of spacing
/// `full` (m).
fn spacing(full: f32, width: u32) -> f32 {
    if width == WIDTHS[0] { full } else { full * WIDTHS[0] as f32 / width as f32 }
}

/// Steps `preset` with `overrides` at spacing `s` for [`MEASURE`] and returns its
/// particles and simulated seconds per wall second.
fn measure(preset: &str, overrides: &[String], s: f32, factory: &BackendFactory) -> anyhow::Result<(usize, f64)> {
    let mut o = overrides.to_vec();
    o.push(format!("particle_spacing={s}"));
    let scene = load::from_preset(preset, &o)?;
    let mut sim = Simulation::new(scene, factory)?;
    sim.step().map_err(|h| anyhow::anyhow!("{h}"))?;
    let (t0, start, s0) = (sim.time(), Instant::now(), sim.steps());
    while start.elapsed() < MEASURE || sim.steps() - s0 < MIN_STEPS {
        sim.step().map_err(|h| anyhow::anyhow!("{h}"))?;
    }
    Ok((sim.particle_count(), (sim.time() - t0) / start.elapsed().as_secs_f64()))
}

/// The index of the first (finest) width at most `width`, past `after`.
fn next_index(after: usize, width: f64) -> usize {
    (after + 1..WIDTHS.len()).find(|&j| f64::from(WIDTHS[j]) <= width).unwrap_or(WIDTHS.len() - 1)
}

/// Sizes `preset` with `overrides` (which set no `particle_spacing`) for the
/// backend `factory` makes: measures the full size; while too slow, predicts the
/// width that would reach the target (the real-time factor goes about as the
/// spacing to the fourth power: particles as its cube, the stable time step as the
/// spacing) and measures that, coarser each time, down to the coarsest. A size that
/// does not build or halts is passed over for the next coarser one.
pub fn size(preset: &str, overrides: &[String], factory: &BackendFactory) -> anyhow::Result<Sizing> {
    let scene = load::from_preset(preset, overrides)?;
    let full = scene.particle_spacing;
    // Built, not counted on the lattice: a mesh body or a terrain keeps a part of its block.
    let full_particles = floe_engine::model::Model::build(&scene)?.particle_count() as u64;
    let mut best: Option<Sizing> = None;
    let mut i = 0;
    loop {
        let s = spacing(full, WIDTHS[i]);
        let predicted = match measure(preset, overrides, s, factory) {
            Ok((particles, rtf)) => {
                tracing::debug!(preset, particles, rtf, "preset size measured");
                let sizing = Sizing { spacing: s, particles, rtf, full_spacing: full, full_particles };
                if rtf >= TARGET_RTF || i == WIDTHS.len() - 1 {
                    return Ok(sizing);
                }
                if best.as_ref().is_none_or(|b| rtf > b.rtf) {
                    best = Some(sizing);
                }
                f64::from(WIDTHS[i]) * (rtf / TARGET_RTF).powf(0.25)
            }
            Err(e) => {
                tracing::debug!(preset, spacing = s, "preset size passed over: {e}");
                if i == WIDTHS.len() - 1 {
                    return best.ok_or(e);
                }
                f64::from(WIDTHS[i])
            }
        };
        i = next_index(i, predicted);
    }
}

/// Whether overrides set the spacing themselves.
pub fn sets_spacing(overrides: &[String]) -> bool {
    overrides.iter().any(|o| o.trim_start().starts_with("particle_spacing"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_prediction_moves_coarser_and_stops_at_the_coarsest() {
        assert_eq!(WIDTHS[next_index(0, 27.0)], 24);
        assert_eq!(WIDTHS[next_index(0, 13.0)], 12);
        assert_eq!(WIDTHS[next_index(2, 30.0)], 16, "never back to a finer width");
        assert_eq!(WIDTHS[next_index(0, 3.0)], 10);
    }

    #[test]
    fn the_dam_break_keeps_whole_spacings_across_its_column() {
        let a = floe_engine::modules::fluid::presets::DAM_BREAK_A;
        for &w in WIDTHS {
            let s = spacing(a / 28.0, w);
            assert!(((a / s) - w as f32).abs() < 1e-4, "width {w}: {} spacings", a / s);
        }
    }

    #[test]
    fn the_choice_is_measured_and_states_its_size() {
        // The CPU backend in a test build: whatever it measures, the choice is one of
        // the widths, reaches the target unless it is the coarsest, and states its size
        // and the full one.
        let c = size("dam_break", &[], &floe_engine::simulation::cpu_backend).unwrap();
        let a = floe_engine::modules::fluid::presets::DAM_BREAK_A;
        let width = (a / c.spacing).round() as u32;
        assert!(WIDTHS.contains(&width), "{c:?}");
        assert_eq!(c.particles as u32, width * 2 * width * (width / 2));
        assert!(c.rtf >= TARGET_RTF || width == 10, "{c:?}");
        assert_eq!((c.full_spacing, c.full_particles), (a / 28.0, 21_952));
        assert!(!sets_spacing(&["solver.method=\"wcsph\"".into()]) && sets_spacing(&["particle_spacing=0.1".into()]));
    }
}
