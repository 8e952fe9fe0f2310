//! `floe bench --view`: what a region of interest saves a stream of a large scene. A
//! dam-break column of `--particles` particles (its first step's state, with
//! velocities), encoded whole and through views holding a share of it: a box (the
//! column's first slices along x), a budget alone, and a camera with a budget. Each
//! row's encode time includes the view's cull and thinning (the server's work per
//! frame before it encodes), single thread, best of [`PASSES`] passes.

use crate::service::view::{BoxRequest, CameraRequest, ViewRequest};
use anyhow::Context;
use floe_engine::Simulation;
use floe_engine::modules::fluid::presets::DAM_BREAK_A;
use floe_engine::scene::load;
use floe_proto::{ChannelKind, Encoder, EncoderConfig, FrameInput, Mode, Particles};
use std::time::{Duration, Instant};

/// Timing passes; the fastest counts.
const PASSES: usize = 3;

/// One row: the view, what it sends, and its cost.
struct Row {
    label: String,
    particles: usize,
    bytes: usize,
    /// Cull, pick and encode.
    encode: Duration,
    /// Of which the cull and thinning.
    cull: Duration,
}

/// Prints the table for a dam break of about `particles` particles, the views
/// holding `share` (0 to 1) of them.
pub fn view_bench(particles: usize, share: f64) -> anyhow::Result<()> {
    anyhow::ensure!(share > 0.0 && share < 1.0, "the share must be between 0 and 1");
    let spacing = format!("particle_spacing={}", DAM_BREAK_A / (particles as f32).cbrt().round());
    let t0 = Instant::now();
    let mut sim = Simulation::new_cpu(load::from_preset("dam_break", &[spacing])?)?;
    sim.step().context("the first step")?;
    let p = sim.read(&["velocity"]);
    let n = p.positions.len();
    eprintln!("dam break, {n} particles, built and stepped once in {:.1} s", t0.elapsed().as_secs_f64());
    let [lo, hi] = extent(&p);
    // A box: the slices x <= x_share holding `share` of the particles.
    let mut xs: Vec<f32> = p.positions.iter().map(|x| x[0]).collect();
    let k = ((n as f64 * share) as usize).clamp(1, n - 1);
    let (_, &mut cut, _) = xs.select_nth_unstable_by(k, f32::total_cmp);
    let boxed = BoxRequest {
        min: lo.map(|v| f64::from(v) - 1.0),
        max: [f64::from(cut) - 1e-6, f64::from(hi[1]) + 1.0, f64::from(hi[2]) + 1.0],
    };
    let budget = Some(k as u64);
    // A camera in front of the column, looking at its middle from two column widths.
    let centre = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])].map(f64::from);
    let back = 2.0 * f64::from(hi[0] - lo[0]);
    let camera = CameraRequest {
        position: [centre[0], centre[1], centre[2] + back],
        direction: [0.0, 0.0, -1.0],
        fov_deg: Some(90.0),
        far: None,
    };
    let views = [
        (format!("box, x below {cut:.3} m"), ViewRequest { bounds: Some(boxed), ..ViewRequest::default() }),
        (format!("budget {k}"), ViewRequest { budget, ..ViewRequest::default() }),
        (format!("camera, budget {k}"), ViewRequest { camera: Some(camera), budget, ..ViewRequest::default() }),
    ];
    let share_pct = 100.0 * k as f64 / n as f64;
    println!(
        "dam break, {n} particles with velocities, its first step; views holding {share_pct:.1} %; one thread, best of {PASSES} passes; encode time includes the view's cull"
    );
    println!(
        "| mode | view | particles sent | bytes/frame | encode ms | of which cull ms | bytes: whole / view | encode: whole / view |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|");
    for mode in [Mode::Unordered, Mode::IdentityOrdered] {
        let whole = measure("whole scene".into(), mode, &p, None)?;
        print_row(mode, &whole, &whole);
        for (label, request) in &views {
            let view = request.check().map_err(|e| anyhow::anyhow!("{e}"))?;
            let row = measure(label.clone(), mode, &p, Some(&view))?;
            print_row(mode, &row, &whole);
        }
    }
    Ok(())
}

/// The smallest box holding every particle of `p`.
fn extent(p: &Particles) -> [[f32; 3]; 2] {
    p.positions.iter().fold([[f32::MAX; 3], [f32::MIN; 3]], |[lo, hi], x| {
        [std::array::from_fn(|k| lo[k].min(x[k])), std::array::from_fn(|k| hi[k].max(x[k]))]
    })
}

/// Culls (with `view`) and encodes `p` [`PASSES`] times with fresh encoders (each frame
/// a keyframe, as a stream's first); the fastest pass.
fn measure(label: String, mode: Mode, p: &Particles, view: Option<&crate::service::view::View>) -> anyhow::Result<Row> {
    let [lo, hi] = extent(p);
    let bounds = floe_proto::Bounds { min: lo, max: hi }.with_margin(0.05);
    let mut best: Option<Row> = None;
    let mut out = Vec::new();
    for _ in 0..PASSES {
        let mut encoder = Encoder::new(EncoderConfig::new(mode, 1, bounds))?;
        let t0 = Instant::now();
        let kept = view.map(|v| v.select(p));
        let cull = t0.elapsed();
        let picked = kept.map(|k| p.pick(&k));
        let sent = picked.as_ref().unwrap_or(p);
        let velocity = sent.channel("velocity").context("velocities read")?.as_ref();
        let ids = sent.ids.as_deref().filter(|_| mode == Mode::IdentityOrdered);
        let channels = vec![(ChannelKind::named("velocity").context("the velocity channel")?, velocity)];
        let input = FrameInput { positions: &sent.positions, grid: None, set: 0, channels, ids };
        encoder.encode_into(1, 0.0, &input, &mut out)?;
        let encode = t0.elapsed();
        let row = Row { label: label.clone(), particles: sent.positions.len(), bytes: out.len(), encode, cull };
        if best.as_ref().is_none_or(|b| row.encode < b.encode) {
            best = Some(row);
        }
    }
    Ok(best.expect("at least one pass"))
}

fn print_row(mode: Mode, row: &Row, whole: &Row) {
    let mode = match mode {
        Mode::Unordered => "unordered",
        _ => "identity",
    };
    let (ms, cull) = (row.encode.as_secs_f64() * 1e3, row.cull.as_secs_f64() * 1e3);
    println!(
        "| {mode} | {} | {} | {} | {ms:.1} | {cull:.1} | {:.1} | {:.1} |",
        row.label,
        row.particles,
        row.bytes,
        whole.bytes as f64 / row.bytes as f64,
        whole.encode.as_secs_f64() / row.encode.as_secs_f64()
    );
}
