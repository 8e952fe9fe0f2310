//! Identity-ordered frame size against the time between frames: how much a frame costs
//! depends on how far the particles move between frames, which a live stream sets by the
//! solver's speed and the subscriber's frame rate.
//!
//! A viewer at 30 frames/s receives a frame every `steps/s / 30` steps: every step on a
//! machine that steps slower than that (this one, at 100k particles), tens of steps on a
//! fast GPU. A recording played back in real time at 60 frames/s is the other end: 1/60 s of
//! simulated time between frames, a hundred steps or more.

use super::tank;
use floe_engine::Simulation;
use floe_proto::{Encoder, EncoderConfig, FrameInput, Mode};

/// How far apart the frames of one row are.
#[derive(Debug, Clone, Copy)]
enum Interval {
    Steps(u64),
    Seconds(f64),
    /// 1/60 s and 1/30 s in turn: a 60 frames/s subscriber that misses every other frame.
    Skipping,
}

impl Interval {
    fn label(self) -> String {
        match self {
            Interval::Steps(1) => "every step".into(),
            Interval::Steps(n) => format!("every {n} steps"),
            Interval::Seconds(s) => format!("1/{:.0} s", 1.0 / s),
            Interval::Skipping => "1/60 s and 1/30 s in turn".into(),
        }
    }
}

/// The rows, from a live stream on a slow machine to real-time playback at 30 frames/s.
const INTERVALS: [Interval; 8] = [
    Interval::Steps(1),
    Interval::Steps(4),
    Interval::Steps(16),
    Interval::Steps(32),
    Interval::Seconds(1.0 / 120.0),
    Interval::Seconds(1.0 / 60.0),
    Interval::Seconds(1.0 / 30.0),
    Interval::Skipping,
];

/// Keyframe interval of the amortised column: the encoder's default.
const KEYFRAME_INTERVAL: f64 = 30.0;

/// Restores `start` (a snapshot) for each row, takes `frames` frames that far apart and
/// prints a markdown table of identity-ordered 16-bit position frame sizes.
pub fn by_interval(start: &[u8], frames: usize) -> anyhow::Result<()> {
    println!();
    println!("identity-ordered 16-bit positions by time between frames, {frames} frames from the same state:");
    println!(
        "| frames | simulated ms between frames | RMS motion per frame (mm) | keyframe | first delta (base) | \
         later deltas (linear) | keyframe every 30 |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for interval in INTERVALS {
        eprintln!("frames {}: simulating {frames} frames", interval.label());
        let mut sim = Simulation::restore(start)?;
        let t0 = sim.time();
        let mut positions = vec![sim.read(&[]).positions];
        while positions.len() < frames {
            match interval {
                Interval::Steps(n) => {
                    for _ in 0..n {
                        sim.step()?;
                    }
                }
                Interval::Seconds(s) => advance(&mut sim, s)?,
                Interval::Skipping => {
                    advance(&mut sim, if positions.len() % 2 == 1 { 1.0 / 60.0 } else { 1.0 / 30.0 })?
                }
            }
            positions.push(sim.read(&[]).positions);
        }
        let ms = (sim.time() - t0) / (frames - 1) as f64 * 1e3;
        let sizes = frame_sizes(&positions)?;
        let n = positions[0].len() as f64;
        let per = |bytes: f64| bytes / n;
        let (key, first) = (per(sizes[0]), per(sizes[1]));
        let later = per(sizes[2..].iter().sum::<f64>() / (sizes.len() - 2) as f64);
        let amortised = (key + first + (KEYFRAME_INTERVAL - 2.0) * later) / KEYFRAME_INTERVAL;
        println!(
            "| {} | {ms:.2} | {:.3} | {key:.2} | {first:.2} | {later:.2} | {amortised:.2} |",
            interval.label(),
            rms_motion(&positions) * 1e3
        );
    }
    Ok(())
}

/// Steps `sim` until `seconds` of simulated time have passed.
fn advance(sim: &mut Simulation, seconds: f64) -> anyhow::Result<()> {
    let next = sim.time() + seconds;
    while sim.time() < next {
        sim.step()?;
    }
    Ok(())
}

/// Bytes of each frame of one identity-ordered stream (a keyframe, then delta frames).
fn frame_sizes(positions: &[Vec<[f32; 3]>]) -> anyhow::Result<Vec<f64>> {
    let mut config = EncoderConfig::new(Mode::IdentityOrdered, 1, tank());
    config.keyframe_interval = u32::MAX;
    let mut encoder = Encoder::new(config)?;
    let mut out = Vec::new();
    let mut sizes = Vec::with_capacity(positions.len());
    for (i, p) in positions.iter().enumerate() {
        encoder.encode_into(i as u64, i as f64, &FrameInput::positions(p), &mut out)?;
        sizes.push(out.len() as f64);
    }
    Ok(sizes)
}

/// Root mean square distance (m) a particle moves from one frame to the next.
fn rms_motion(positions: &[Vec<[f32; 3]>]) -> f64 {
    let mut sum = 0.0;
    let mut count = 0usize;
    for pair in positions.windows(2) {
        for (a, b) in pair[0].iter().zip(&pair[1]) {
            sum += (0..3).map(|k| f64::from(b[k] - a[k]).powi(2)).sum::<f64>();
        }
        count += pair[0].len();
    }
    (sum / count as f64).sqrt()
}
