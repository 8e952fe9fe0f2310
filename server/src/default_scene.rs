//! The scene `floe serve` starts with by default (`--scene auto`): the dam break at
//! the finest resolution this machine's backend steps at least [`TARGET_RTF`] times
//! real time, so a new user sees the column collapse within seconds of pressing Play
//! on a laptop's CPU, and a GPU gets the fine version. The choice is measured, not
//! guessed: a few short runs of the scene itself, about a second in all.

use floe_engine::Simulation;
use floe_engine::modules::fluid::presets::DAM_BREAK_A;
use floe_engine::scene::load;
use floe_engine::simulation::BackendFactory;
use std::time::{Duration, Instant};

/// The real-time factor the scene aims at when stepped alone: twice the 0.5 a
/// viewer should see, leaving half the machine to the browser and the server.
pub const TARGET_RTF: f64 = 1.0;

/// Resolutions tried, finest first, as the column's width in particle spacings (the
/// preset's is 28: 21,952 particles; 10 is 1,000, still enough for the surge and
/// the splash on the far wall).
const WIDTHS: &[u32] = &[28, 24, 20, 16, 14, 12, 10];

/// Wall time one measurement steps for, after a first step that is not timed (a GPU
/// compiles its kernels then).
const MEASURE: Duration = Duration::from_millis(300);

/// The chosen resolution and why.
#[derive(Debug, Clone)]
pub struct Choice {
    /// The override that sizes the preset.
    pub overrides: Vec<String>,
    /// Fluid particles at that resolution.
    pub particles: usize,
    /// The real-time factor measured at that resolution.
    pub rtf: f64,
}

fn overrides(width: u32) -> Vec<String> {
    vec![format!("particle_spacing={}", DAM_BREAK_A / width as f32)]
}

/// Steps the dam break at `width` spacings per column width for [`MEASURE`] and
/// returns its particles and simulated seconds per wall second.
fn measure(width: u32, factory: &BackendFactory) -> anyhow::Result<(usize, f64)> {
    let scene = load::from_preset("dam_break", &overrides(width))?;
    let mut sim = Simulation::new(scene, factory)?;
    sim.step().map_err(|h| anyhow::anyhow!("{h}"))?;
    let (t0, start) = (sim.time(), Instant::now());
    while start.elapsed() < MEASURE {
        sim.step().map_err(|h| anyhow::anyhow!("{h}"))?;
    }
    Ok((sim.particle_count(), (sim.time() - t0) / start.elapsed().as_secs_f64()))
}

/// The index of the first (finest) width at most `width`, past `after`.
fn next_index(after: usize, width: f64) -> usize {
    (after + 1..WIDTHS.len()).find(|&j| f64::from(WIDTHS[j]) <= width).unwrap_or(WIDTHS.len() - 1)
}

/// Chooses the resolution: measures the finest; while too slow, predicts the width
/// that would reach the target (the real-time factor goes as the spacing to the
/// fourth power: particles as its cube, the stable time step as the spacing) and
/// measures that, coarser each time, down to the coarsest.
pub fn choose(factory: &BackendFactory) -> anyhow::Result<Choice> {
    let mut i = 0;
    loop {
        let (particles, rtf) = measure(WIDTHS[i], factory)?;
        tracing::debug!(particles, rtf, "default scene measured");
        if rtf >= TARGET_RTF || i == WIDTHS.len() - 1 {
            return Ok(Choice { overrides: overrides(WIDTHS[i]), particles, rtf });
        }
        let predicted = f64::from(WIDTHS[i]) * (rtf / TARGET_RTF).powf(0.25);
        i = next_index(i, predicted);
    }
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
    fn a_fast_backend_gets_the_full_preset_and_a_slow_one_a_coarser_scene() {
        // The CPU backend in a test build: whatever it measures, the choice is one of
        // the widths, reaches the target unless it is the coarsest, and states its size.
        let c = choose(&floe_engine::simulation::cpu_backend).unwrap();
        let width = WIDTHS.iter().find(|&&w| overrides(w) == c.overrides).expect("one of the widths");
        assert_eq!(c.particles as u32, width * 2 * width * (width / 2));
        assert!(c.rtf >= TARGET_RTF || *width == 10, "{c:?}");
    }
}
