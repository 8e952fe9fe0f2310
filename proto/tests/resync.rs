//! Identity-ordered streams: keyframe interval, forced keyframes, and a decoder that
//! misses a frame asking for a keyframe instead of decoding garbage.

mod common;

use common::{Particles, Rng};
use floe_proto::{Bounds, DecodeError, Decoder, Encoder, EncoderConfig, Limits, Mode, Predictor, read_header};

const BOUNDS: Bounds = Bounds { min: [0.0; 3], max: [2.0, 1.0, 0.5] };

fn stream(interval: u32, frames: usize, seed: u64) -> (Encoder, Vec<Vec<u8>>) {
    let mut config = EncoderConfig::new(Mode::IdentityOrdered, 42, BOUNDS);
    config.keyframe_interval = interval;
    let mut encoder = Encoder::new(config).unwrap();
    let mut rng = Rng::new(seed);
    let mut p = Particles::random(&mut rng, 300, &BOUNDS, 1.0);
    let mut out = Vec::new();
    for f in 0..frames {
        out.push(encoder.encode(f as u64, f as f64 * 0.01, &p.input()).unwrap());
        p.advance(&mut rng, &BOUNDS, 0.002);
    }
    (encoder, out)
}

#[test]
fn keyframes_come_at_the_interval_and_deltas_predict_from_the_frame_before() {
    let (_, frames) = stream(4, 10, 1);
    let mut decoder = Decoder::new(Limits::default());
    for (f, bytes) in frames.iter().enumerate() {
        let h = decoder.decode(bytes).unwrap().header;
        assert_eq!(h.keyframe, f % 4 == 0, "frame {f}");
        let want_base = if h.keyframe { f as u64 } else { f as u64 - 1 };
        assert_eq!(h.base_sequence, want_base);
        let positions = if h.keyframe {
            Predictor::Previous
        } else if f % 4 == 1 {
            Predictor::Base
        } else {
            Predictor::Linear
        };
        assert_eq!(h.channels[0].predictor, positions, "frame {f}");
        assert_eq!(decoder.held_sequence(), Some(f as u64));
    }
    let positions_len = |f: usize| read_header(&frames[f], &Limits::default()).unwrap().channels[0].payload_len;
    assert!(positions_len(5) < positions_len(4), "small motion makes delta positions smaller than a keyframe's");
}

#[test]
fn a_missed_frame_needs_a_keyframe_and_the_next_keyframe_resyncs() {
    let (_, frames) = stream(5, 11, 2);
    let mut decoder = Decoder::new(Limits::default());
    for bytes in &frames[..3] {
        decoder.decode(bytes).unwrap();
    }
    // Frame 3 is lost: 4 predicts from 3, which this decoder never saw.
    let err = decoder.decode(&frames[4]).unwrap_err();
    assert_eq!(err, DecodeError::NeedKeyframe { sequence: 4, base: 3, held: Some(2) });
    assert_eq!(decoder.held_sequence(), Some(2), "a refused frame leaves the state alone");
    let frame = decoder.decode(&frames[5]).unwrap();
    assert!(frame.header.keyframe);
    for bytes in &frames[6..] {
        decoder.decode(bytes).unwrap();
    }
    assert_eq!(decoder.last_sequence(), Some(10));
}

#[test]
fn a_new_subscriber_gets_a_forced_keyframe() {
    let (mut encoder, frames) = stream(30, 4, 3);
    let mut late = Decoder::new(Limits::default());
    let err = late.decode(&frames[3]).unwrap_err();
    assert_eq!(err, DecodeError::NeedKeyframe { sequence: 3, base: 2, held: None });

    encoder.force_keyframe();
    let mut rng = Rng::new(9);
    let p = Particles::random(&mut rng, 300, &BOUNDS, 1.0);
    let key = encoder.encode(4, 0.04, &p.input()).unwrap();
    let next = encoder.encode(5, 0.05, &p.input()).unwrap();
    assert!(late.decode(&key).unwrap().header.keyframe);
    let frame = late.decode(&next).unwrap();
    assert!(!frame.header.keyframe, "forcing lasts one frame");
    assert_eq!(frame.header.sequence, 5);
}

#[test]
fn a_delta_frame_of_another_scene_needs_a_keyframe() {
    let (_, ours) = stream(30, 2, 4);
    let mut config = EncoderConfig::new(Mode::IdentityOrdered, 43, BOUNDS);
    config.keyframe_interval = 30;
    let mut other = Encoder::new(config).unwrap();
    let mut rng = Rng::new(4);
    let p = Particles::random(&mut rng, 300, &BOUNDS, 1.0);
    other.encode(0, 0.0, &p.input()).unwrap();
    let theirs = other.encode(1, 0.01, &p.input()).unwrap();

    let mut decoder = Decoder::new(Limits::default());
    decoder.decode(&ours[0]).unwrap();
    assert!(matches!(decoder.decode(&theirs), Err(DecodeError::NeedKeyframe { base: 0, .. })));
    decoder.decode(&ours[1]).unwrap();
}

#[test]
fn a_change_of_particle_count_starts_with_a_keyframe() {
    let config = EncoderConfig::new(Mode::IdentityOrdered, 1, BOUNDS);
    let mut encoder = Encoder::new(config).unwrap();
    let mut rng = Rng::new(5);
    let a = Particles::random(&mut rng, 100, &BOUNDS, 0.0);
    let b = Particles::random(&mut rng, 120, &BOUNDS, 0.0);
    let mut decoder = Decoder::new(Limits::default());
    assert!(decoder.decode(&encoder.encode(0, 0.0, &a.input()).unwrap()).unwrap().header.keyframe);
    assert!(!decoder.decode(&encoder.encode(1, 0.1, &a.input()).unwrap()).unwrap().header.keyframe);
    let frame = decoder.decode(&encoder.encode(2, 0.2, &b.input()).unwrap()).unwrap();
    assert!(frame.header.keyframe);
    assert_eq!(frame.positions.len(), 120);
}

#[test]
fn unordered_frames_decode_on_their_own() {
    let config = EncoderConfig::new(Mode::Unordered, 1, BOUNDS);
    let mut encoder = Encoder::new(config).unwrap();
    let mut rng = Rng::new(6);
    let p = Particles::random(&mut rng, 200, &BOUNDS, 1.0);
    let frames: Vec<Vec<u8>> = (0..3).map(|f| encoder.encode(f, 0.0, &p.input()).unwrap()).collect();
    let frame = Decoder::new(Limits::default()).decode(&frames[2]).unwrap();
    assert!(frame.header.keyframe);
    assert_eq!((frame.header.sequence, frame.header.base_sequence), (2, 2));
}
