//! Frame codec benchmark: bytes per particle and single-thread encode/decode throughput of
//! `floe-proto` on dam-break frames taken 1/60 s of simulated time apart.
//!
//! Frames start once the column has collapsed into a running surge (t = 0.25 s), so the
//! motion between frames is that of the flow rather than of water still at rest. A second
//! table ([`intervals`]) gives identity-ordered sizes against the time between frames.

mod intervals;
mod view;

pub use view::view_bench;

use anyhow::Context;
use floe_engine::Simulation;
use floe_engine::modules::fluid::presets::DAM_BREAK_A;
use floe_engine::scene::load;
use floe_proto::{Bounds, Decoder, Encoder, EncoderConfig, FrameInput, Limits, Mode};
use std::time::{Duration, Instant};

/// Default size: a 48 x 96 x 24 column, 110,592 particles.
pub const DEFAULT_PARTICLES: usize = 110_592;
/// Default number of frames.
pub const DEFAULT_FRAMES: usize = 8;
/// Simulated time (s) before the first frame.
const WARM_UP: f64 = 0.25;
/// Simulated time (s) between frames: a 60 Hz stream.
const FRAME_INTERVAL: f64 = 1.0 / 60.0;
/// Timing passes over the frames; the fastest counts, as the least disturbed by the machine.
const PASSES: usize = 5;

/// The dam-break tank (4a x 2.4a x a/2 for a = 0.5 m) with a 5 cm margin for splashes.
pub(super) fn tank() -> Bounds {
    let a = DAM_BREAK_A;
    Bounds { min: [0.0; 3], max: [4.0 * a, 2.4 * a, 0.5 * a] }.with_margin(0.05)
}

/// One benchmark row: how to encode, and which frames count.
struct Case {
    label: &'static str,
    mode: Mode,
    bits: u8,
    /// Identity-ordered: keyframe interval (1 = keyframes only).
    keyframe_interval: u32,
    /// Whether the first frame (a keyframe) is left out of the figures.
    skip_first: bool,
}

/// Measured figures of one case.
struct Row {
    bytes: usize,
    particles: usize,
    encode: Duration,
    decode: Duration,
    max_error_um: [f32; 3],
}

/// Simulates the dam break with about `particles` particles, takes `frames` frames and
/// prints a markdown table of the codec's size and speed in each mode.
pub fn codec_bench(particles: usize, frames: usize) -> anyhow::Result<()> {
    anyhow::ensure!(frames >= 2, "at least 2 frames are needed (a keyframe and a delta frame)");
    let spacing = format!("particle_spacing={}", DAM_BREAK_A / (particles as f32).cbrt().round());
    let mut sim = Simulation::new_cpu(load::from_preset("dam_break", &[spacing])?)?;
    let n = sim.particle_count();
    eprintln!("dam break, {n} particles: simulating to t = {WARM_UP} s, then {frames} frames 1/60 s apart");
    while sim.time() < WARM_UP {
        sim.step().context("warm-up")?;
    }
    let start = sim.snapshot();
    let mut positions = Vec::with_capacity(frames);
    let mut times = Vec::with_capacity(frames);
    for _ in 0..frames {
        let next = sim.time() + FRAME_INTERVAL;
        while sim.time() < next {
            sim.step().context("simulating frames")?;
        }
        positions.push(sim.read(&[]).positions);
        times.push((sim.steps(), sim.time()));
    }

    let all_deltas = u32::try_from(frames).unwrap_or(u32::MAX);
    let mut cases: Vec<Case> = [16, 14, 12, 10]
        .map(|bits| Case { label: "unordered", mode: Mode::Unordered, bits, keyframe_interval: 1, skip_first: false })
        .into();
    for bits in [16, 12] {
        let (label, mode) = ("identity, delta frames", Mode::IdentityOrdered);
        cases.push(Case { label, mode, bits, keyframe_interval: all_deltas, skip_first: true });
        cases.push(Case { label: "identity, keyframes", mode, bits, keyframe_interval: 1, skip_first: false });
    }

    println!(
        "dam break, {n} particles, {frames} frames 1/60 s apart from t = {WARM_UP} s; single thread, best of {PASSES} passes"
    );
    println!("| mode | bits | bytes/particle | encode M particles/s | decode M particles/s | max error x/y/z (µm) |");
    println!("|---|---:|---:|---:|---:|---:|");
    for case in &cases {
        let row = measure(case, &positions, &times)?;
        let per = |d: Duration| row.particles as f64 / d.as_secs_f64() / 1e6;
        let bpp = row.bytes as f64 / row.particles as f64;
        let [ex, ey, ez] = row.max_error_um;
        println!(
            "| {} | {} | {bpp:.2} | {:.0} | {:.0} | {ex:.1} / {ey:.1} / {ez:.1} |",
            case.label,
            case.bits,
            per(row.encode),
            per(row.decode)
        );
    }
    intervals::by_interval(&start, frames)
}

/// Encodes and decodes every frame `PASSES` times with a fresh encoder and decoder per pass.
fn measure(case: &Case, positions: &[Vec<[f32; 3]>], times: &[(u64, f64)]) -> anyhow::Result<Row> {
    let mut config = EncoderConfig::new(case.mode, 1, tank());
    config.position_bits = case.bits;
    config.keyframe_interval = case.keyframe_interval;
    let first = usize::from(case.skip_first);
    let mut best: Option<Row> = None;
    let mut out = Vec::new();
    for _ in 0..PASSES {
        let mut encoder = Encoder::new(config.clone())?;
        let mut decoder = Decoder::new(Limits::default());
        let mut row =
            Row { bytes: 0, particles: 0, encode: Duration::ZERO, decode: Duration::ZERO, max_error_um: [0.0; 3] };
        for (i, (p, &(step, time))) in positions.iter().zip(times).enumerate() {
            let t0 = Instant::now();
            encoder.encode_into(step, time, &FrameInput::positions(p), &mut out)?;
            let t1 = Instant::now();
            let frame = decoder.decode(&out)?;
            let t2 = Instant::now();
            anyhow::ensure!(
                frame.positions.len() == p.len(),
                "decoded {} of {} particles",
                frame.positions.len(),
                p.len()
            );
            if i >= first {
                row.bytes += out.len();
                row.particles += p.len();
                row.encode += t1 - t0;
                row.decode += t2 - t1;
                for (k, r) in frame.header.channels[0].ranges.iter().enumerate() {
                    row.max_error_um[k] = r.max_error * 1e6;
                }
            }
        }
        best = Some(match best {
            Some(b) => Row { encode: b.encode.min(row.encode), decode: b.decode.min(row.decode), ..row },
            None => row,
        });
    }
    best.context("no passes")
}
