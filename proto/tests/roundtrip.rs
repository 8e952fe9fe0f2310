//! decode(encode(x)) equals x within each channel's stated maximum error, over many
//! random frames of both modes.

mod common;

use common::{Particles, Rng, channel, random_bounds, tolerance};
use floe_proto::quantize::Quantizer;
use floe_proto::{
    ChannelKind, Decoder, Encoder, EncoderConfig, Frame, FrameInput, Limits, Mode, Predictor, Values, ValuesRef,
};

fn random_config(rng: &mut Rng, mode: Mode) -> EncoderConfig {
    let mut c = EncoderConfig::new(mode, rng.next_u64(), random_bounds(rng));
    c.position_bits = rng.int(8, 16) as u8;
    c.channel_bits = [ChannelKind::VELOCITY, ChannelKind::DENSITY, ChannelKind::PRESSURE, ChannelKind(64)]
        .into_iter()
        .map(|k| (k, rng.int(1, 16) as u8))
        .collect();
    c.keyframe_interval = rng.int(1, 6) as u32;
    c
}

fn random_count(rng: &mut Rng) -> usize {
    match rng.int(0, 9) {
        0 => rng.int(0, 2) as usize,
        _ => rng.int(3, 2000) as usize,
    }
}

/// Checks every channel of `frame` against `p`; `map[i]` is the input index of decoded
/// particle `i`: exact channels equal, float channels within their stated error.
fn assert_frame_matches(frame: &Frame, p: &Particles, map: &[usize]) {
    let input = p.input();
    assert_eq!(frame.positions.len(), p.positions.len(), "particle count");
    let info = channel(frame, ChannelKind::POSITION.tag());
    for (i, got) in frame.positions.iter().enumerate() {
        for (k, x) in got.iter().enumerate() {
            let err = (x - p.positions[map[i]][k]).abs();
            assert!(err <= tolerance(info, k), "position of particle {i}, component {k}: error {err}");
        }
    }
    assert_eq!(frame.channels.len(), input.channels.len(), "channels present");
    for (kind, want) in &input.channels {
        let got = frame.channel(*kind).unwrap_or_else(|| panic!("{kind} missing"));
        match (want, got) {
            (ValuesRef::Exact(w), Values::Exact(g)) => {
                assert!(g.iter().enumerate().all(|(i, &x)| x == w[map[i]]), "{kind} is exact");
            }
            (ValuesRef::Float { components, data }, Values::Float { components: c, data: g }) => {
                assert_eq!(components, c, "{kind} components");
                let (info, c) = (channel(frame, kind.tag()), usize::from(*c));
                for (i, values) in g.chunks_exact(c).enumerate() {
                    for (k, &x) in values.iter().enumerate() {
                        let err = (x - data[map[i] * c + k]).abs();
                        assert!(err <= tolerance(info, k), "{kind} particle {i} component {k}: error {err}");
                    }
                }
            }
            _ => panic!("{kind}: decoded as another form"),
        }
    }
}

#[test]
fn identity_ordered_streams_round_trip_within_max_error() {
    for seed in 0..60 {
        let mut rng = Rng::new(seed);
        let config = random_config(&mut rng, Mode::IdentityOrdered);
        let bounds = config.bounds;
        let interval = config.keyframe_interval as u64;
        let mut encoder = Encoder::new(config.clone()).unwrap();
        let mut decoder = Decoder::new(Limits::default());
        let mut p = {
            let n = random_count(&mut rng);
            Particles::random(&mut rng, n, &bounds, 0.6)
        };
        let identity: Vec<usize> = (0..p.positions.len()).collect();
        let motion = rng.range(0.0, 0.05);
        for f in 0..8u64 {
            let bytes = encoder.encode(100 + f, f as f64 / 60.0, &p.input()).unwrap();
            let frame = decoder.decode(&bytes).unwrap_or_else(|e| panic!("seed {seed} frame {f}: {e}"));
            let h = &frame.header;
            assert_eq!((h.sequence, h.step, h.time), (f, 100 + f, f as f64 / 60.0));
            assert_eq!(h.scene_id, config.scene_id);
            assert_eq!(h.keyframe, f % interval == 0, "seed {seed} frame {f}: keyframe every {interval}");
            assert_eq!(h.frame_len as usize, bytes.len());
            assert_frame_matches(&frame, &p, &identity);
            p.advance(&mut rng, &bounds, motion);
        }
    }
}

/// Frames of particles moving at constant velocity, taken at unequal intervals (as a
/// subscriber that skips frames receives them): the linear predictor's fitted gain follows the
/// ratio of the intervals, so every delta frame after the first stays as small as one of
/// equally spaced frames.
#[test]
fn unequally_spaced_frames_extrapolate_with_the_interval_ratio() {
    let mut rng = Rng::new(7);
    let bounds = floe_proto::Bounds { min: [0.0; 3], max: [2.0, 1.0, 0.5] };
    let inner = floe_proto::Bounds { min: [0.5, 0.3, 0.15], max: [1.5, 0.7, 0.35] };
    let mut p = Particles::random(&mut rng, 5_000, &inner, 0.0);
    p.velocities = Some((0..5_000).map(|_| std::array::from_fn(|_| rng.range(-1.0, 1.0))).collect());
    let mut encoder = Encoder::new(EncoderConfig::new(Mode::IdentityOrdered, 1, bounds)).unwrap();
    let mut decoder = Decoder::new(Limits::default());
    let identity: Vec<usize> = (0..p.positions.len()).collect();
    let (mut time, mut since) = (0.0, 0.0);
    // Intervals in 1/60 s: the fourth frame comes three intervals after the third, the
    // fifth half an interval after that.
    for (f, interval) in [1.0, 1.0, 3.0, 0.5, 0.0].into_iter().enumerate() {
        let bytes = encoder.encode(f as u64, time, &FrameInput { positions: &p.positions, ..Default::default() });
        let bytes = bytes.unwrap();
        let frame = decoder.decode(&bytes).unwrap();
        assert_frame_matches(&frame, &Particles { positions: p.positions.clone(), ..Default::default() }, &identity);
        if f >= 2 {
            assert_eq!(frame.header.channels[0].predictor, Predictor::Linear);
            // About 1,100 codes of motion per axis per interval; what is left to store is
            // rounding, a few bits per axis.
            let per_particle = bytes.len() as f64 / p.positions.len() as f64;
            assert!(
                per_particle < 1.2,
                "frame {f} ({since} intervals after the last): {per_particle:.2} bytes/particle"
            );
        }
        since = interval;
        let dt = interval / 60.0;
        p.drift(&bounds, dt as f32);
        time += dt;
    }
}

#[test]
fn unordered_frames_round_trip_within_max_error() {
    for seed in 100..180 {
        let mut rng = Rng::new(seed);
        let mut config = random_config(&mut rng, Mode::Unordered);
        // The particle index travels in the temperature channel (16 bits over [0, n - 1],
        // so it rounds back exactly) to match decoded particles with their inputs.
        config.channel_bits.push((ChannelKind::TEMPERATURE, 16));
        let bounds = config.bounds;
        let mut encoder = Encoder::new(config).unwrap();
        let mut decoder = Decoder::new(Limits::default());
        let mut p = {
            let n = random_count(&mut rng);
            Particles::random(&mut rng, n, &bounds, 0.6)
        };
        let index: Vec<f32> = (0..p.positions.len()).map(|i| i as f32).collect();
        for f in 0..3 {
            p.temperatures = Some(index.clone());
            let bytes = encoder.encode(f, 0.5, &p.input()).unwrap();
            let frame = decoder.decode(&bytes).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
            assert!(frame.header.keyframe);
            let temperatures = frame.channel(ChannelKind::TEMPERATURE).and_then(Values::as_scalars).unwrap();
            let map: Vec<usize> = temperatures.iter().map(|&t| t.round() as usize).collect();
            let mut seen = vec![false; map.len()];
            for &i in &map {
                assert!(!std::mem::replace(&mut seen[i], true), "seed {seed}: particle {i} twice");
            }
            assert_frame_matches(&frame, &p, &map);
            p.advance(&mut rng, &bounds, 0.1);
        }
    }
}

#[test]
fn unordered_positions_are_the_quantised_inputs_in_another_order() {
    for seed in 200..230 {
        let mut rng = Rng::new(seed);
        let config = random_config(&mut rng, Mode::Unordered);
        let p = {
            let n = random_count(&mut rng);
            Particles::random(&mut rng, n, &config.bounds, 0.0)
        };
        let bytes = Encoder::new(config.clone()).unwrap().encode(0, 0.0, &p.input()).unwrap();
        let frame = Decoder::new(Limits::default()).decode(&bytes).unwrap();
        let q: [Quantizer; 3] = config.position_quantizers();
        let key = |v: &[f32; 3]| v.map(f32::to_bits);
        let mut want: Vec<[u32; 3]> = p
            .positions
            .iter()
            .map(|v| {
                key(&std::array::from_fn(|k| {
                    let mut code = Vec::new();
                    q[k].encode_into(std::iter::once(v[k]), &mut code);
                    q[k].decode(code[0])
                }))
            })
            .collect();
        let mut got: Vec<[u32; 3]> = frame.positions.iter().map(key).collect();
        want.sort_unstable();
        got.sort_unstable();
        assert_eq!(got, want, "seed {seed}");
    }
}

#[test]
fn stated_errors_are_half_a_step() {
    let mut rng = Rng::new(7);
    let config = random_config(&mut rng, Mode::Unordered);
    let p = Particles::random(&mut rng, 500, &config.bounds, 1.0);
    let bytes = Encoder::new(config.clone()).unwrap().encode(0, 0.0, &p.input()).unwrap();
    let frame = Decoder::new(Limits::default()).decode(&bytes).unwrap();
    let pos = &frame.header.channels[0];
    assert_eq!(pos.bits, config.position_bits);
    // One step for every axis, the longest axis's (up to the rounding of `min + span`).
    let span = (0..3).map(|k| config.bounds.max[k] - config.bounds.min[k]).fold(0.0, f32::max);
    let half_step = span / ((1u32 << config.position_bits) - 1) as f32 / 2.0;
    for k in 0..3 {
        assert_eq!(pos.ranges[k].min, config.bounds.min[k]);
        assert!((pos.ranges[k].max_error - half_step).abs() <= half_step * 1e-5, "axis {k}");
    }
    let phase = channel(&frame, ChannelKind::MATERIAL.tag());
    assert_eq!((phase.bits, phase.ranges[0].max_error), (8, 0.0));
}
