//! The scene `floe serve` starts with by default (`--scene auto`): the dam break at
//! the finest resolution this machine's backend steps at least [`TARGET_RTF`] times
//! real time, with whichever pressure solver gets there, so a new user sees the
//! column collapse within seconds of pressing Play on a laptop's CPU, and a GPU gets
//! the fine version. The choice is measured, not guessed: a few short runs of the
//! scene itself per scheme, a few seconds in all.

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

/// The pressure solvers tried (`solver.method`).
const SCHEMES: &[&str] = &["wcsph", "dfsph"];

/// Wall time one measurement steps for, after a first step that is not timed (a GPU
/// compiles its kernels then).
const MEASURE: Duration = Duration::from_millis(250);

/// The chosen resolution and scheme, and why.
#[derive(Debug, Clone)]
pub struct Choice {
    /// The overrides that size the preset and choose its scheme.
    pub overrides: Vec<String>,
    /// The scheme.
    pub scheme: &'static str,
    /// Fluid particles at that resolution.
    pub particles: usize,
    /// The real-time factor measured at that resolution.
    pub rtf: f64,
}

fn overrides(scheme: &str, width: u32) -> Vec<String> {
    vec![format!("particle_spacing={}", DAM_BREAK_A / width as f32), format!("solver.method={scheme}")]
}

/// Steps the dam break at `width` spacings per column width with `scheme` for
/// [`MEASURE`] and returns its particles and simulated seconds per wall second.
fn measure(scheme: &str, width: u32, factory: &BackendFactory) -> anyhow::Result<(usize, f64)> {
    let scene = load::from_preset("dam_break", &overrides(scheme, width))?;
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

/// The resolution for `scheme`: measures the finest; while too slow, predicts the
/// width that would reach the target (the real-time factor goes about as the spacing
/// to the fourth power: particles as its cube, the stable time step as the spacing)
/// and measures that, coarser each time, down to the coarsest.
fn search(scheme: &'static str, factory: &BackendFactory) -> anyhow::Result<Choice> {
    let mut i = 0;
    loop {
        let (particles, rtf) = measure(scheme, WIDTHS[i], factory)?;
        tracing::debug!(scheme, particles, rtf, "default scene measured");
        if rtf >= TARGET_RTF || i == WIDTHS.len() - 1 {
            return Ok(Choice { overrides: overrides(scheme, WIDTHS[i]), scheme, particles, rtf });
        }
        let predicted = f64::from(WIDTHS[i]) * (rtf / TARGET_RTF).powf(0.25);
        i = next_index(i, predicted);
    }
}

/// Whether `a` is the better default: it reaches the target with more particles (or
/// as many, faster), or neither reaches it and `a` is faster.
fn better(a: &Choice, b: &Choice) -> bool {
    match (a.rtf >= TARGET_RTF, b.rtf >= TARGET_RTF) {
        (true, false) => true,
        (false, true) => false,
        (true, true) => (a.particles, a.rtf) > (b.particles, b.rtf),
        (false, false) => a.rtf > b.rtf,
    }
}

/// Chooses the scheme and resolution. A scheme whose run halts is passed over
/// (logged); only if every one does is that an error.
pub fn choose(factory: &BackendFactory) -> anyhow::Result<Choice> {
    let mut best: Option<Choice> = None;
    let mut last_error = None;
    for &scheme in SCHEMES {
        match search(scheme, factory) {
            Ok(c) if best.as_ref().is_none_or(|b| better(&c, b)) => best = Some(c),
            Ok(_) => {}
            Err(e) => {
                tracing::warn!("default scene: {scheme} passed over: {e}");
                last_error = Some(e);
            }
        }
    }
    best.ok_or_else(|| last_error.expect("a scheme was tried"))
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

    fn choice(particles: usize, rtf: f64) -> Choice {
        Choice { overrides: Vec::new(), scheme: "wcsph", particles, rtf }
    }

    #[test]
    fn the_better_default_reaches_the_target_with_the_most_particles() {
        assert!(better(&choice(1000, 1.2), &choice(8000, 0.9)));
        assert!(better(&choice(8000, 1.1), &choice(1000, 3.0)));
        assert!(better(&choice(1000, 0.6), &choice(1000, 0.4)));
        assert!(!better(&choice(1000, 0.4), &choice(1000, 0.6)));
    }

    #[test]
    fn the_choice_is_measured_and_states_its_size() {
        // The CPU backend in a test build: whatever it measures, the choice is one of
        // the widths and schemes, reaches the target unless it is the coarsest, and
        // states its size.
        let c = choose(&floe_engine::simulation::cpu_backend).unwrap();
        let width = WIDTHS.iter().find(|&&w| overrides(c.scheme, w) == c.overrides).expect("one of the widths");
        assert_eq!(c.particles as u32, width * 2 * width * (width / 2));
        assert!(c.rtf >= TARGET_RTF || *width == 10, "{c:?}");
    }
}
