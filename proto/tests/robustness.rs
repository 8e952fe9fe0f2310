//! The decoder never panics: truncated frames, random bytes and corrupted fields all
//! give errors (or, for corrupted payload bytes, a frame of the declared size).

mod common;

use common::{Particles, Rng};
use floe_proto::header::{FIXED_HEADER_LEN, VERSION};
use floe_proto::{
    Bounds, ChannelKind, DecodeError, Decoder, Encoder, EncoderConfig, Frame, GridInfo, Limits, Mode, read_header,
};

const BOUNDS: Bounds = Bounds { min: [-1.0, 0.0, 0.0], max: [1.0, 1.0, 0.3] };

/// A frame and a decoder ready for it (holding its base frames if it is a delta frame).
struct Sample {
    name: &'static str,
    bytes: Vec<u8>,
    decoder: Decoder,
}

fn samples() -> Vec<Sample> {
    let mut rng = Rng::new(11);
    let mut out = Vec::new();
    let everything = Particles::random(&mut rng, 300, &BOUNDS, 1.0);
    let plain = Particles::random(&mut rng, 250, &BOUNDS, 0.0);
    for (name, p) in [("unordered, all channels", &everything), ("unordered, positions", &plain)] {
        let bytes = Encoder::new(EncoderConfig::new(Mode::Unordered, 5, BOUNDS)).unwrap().encode(1, 0.5, &p.input());
        out.push(Sample { name, bytes: bytes.unwrap(), decoder: Decoder::new(Limits::default()) });
    }
    let mut encoder = Encoder::new(EncoderConfig::new(Mode::IdentityOrdered, 6, BOUNDS)).unwrap();
    let mut decoder = Decoder::new(Limits::default());
    let mut p = everything.clone();
    for (f, name) in ["identity keyframe", "identity delta (base)", "identity delta (linear)"].into_iter().enumerate() {
        let bytes = encoder.encode(f as u64, f as f64, &p.input()).unwrap();
        out.push(Sample { name, bytes: bytes.clone(), decoder: decoder.clone() });
        decoder.decode(&bytes).unwrap();
        p.advance(&mut rng, &BOUNDS, 0.01);
    }
    let grid = GridInfo { origin: [0.0; 3], size: [1.0, 0.1, 1.0], dims: [10, 1, 12] };
    let mut g = Particles { grid: Some(grid), set: 3, ..Default::default() };
    g.temperatures = Some((0..120).map(|_| rng.range(250.0, 300.0)).collect());
    g.extra = Some((ChannelKind(64), 1, (0..120).map(|_| rng.range(0.0, 2.0)).collect()));
    let bytes = Encoder::new(EncoderConfig::new(Mode::Grid, 7, BOUNDS)).unwrap().encode(2, 1.5, &g.input()).unwrap();
    out.push(Sample { name: "grid", bytes, decoder: Decoder::new(Limits::default()) });
    out
}

/// Checks that a frame the decoder accepted is internally consistent.
fn assert_consistent(frame: &Frame, what: &str) {
    let n = frame.header.particle_count as usize;
    assert_eq!(frame.positions.len(), if frame.grid.is_some() { 0 } else { n }, "{what}");
    let lengths: Vec<usize> = frame.channels.iter().map(|(_, v)| v.len()).collect();
    assert!(lengths.iter().all(|&l| l == n), "{what}: channel lengths {lengths:?} for {n} particles");
}

#[test]
fn every_prefix_of_a_frame_is_incomplete() {
    for s in samples() {
        let mut decoder = s.decoder.clone();
        for len in 0..s.bytes.len() {
            match decoder.decode(&s.bytes[..len]) {
                Err(DecodeError::Incomplete { needed, available }) => {
                    assert_eq!(available, len);
                    assert!(needed > len && needed <= s.bytes.len(), "{}: prefix {len} needs {needed}", s.name);
                }
                other => panic!("{}: prefix of {len} bytes gave {other:?}", s.name),
            }
        }
        assert_consistent(&decoder.decode(&s.bytes).unwrap(), s.name);
    }
}

#[test]
fn random_bytes_are_refused() {
    let mut rng = Rng::new(12);
    let real = &samples()[0].bytes;
    let mut decoder = Decoder::new(Limits::default());
    for i in 0..20_000 {
        let len = rng.int(0, 600) as usize;
        let mut bytes: Vec<u8> = (0..len).map(|_| rng.next_u64() as u8).collect();
        if i % 2 == 1 {
            // A genuine fixed header, so the table and payload parsers see the noise.
            let keep = FIXED_HEADER_LEN.min(len);
            bytes[..keep].copy_from_slice(&real[..keep]);
            if len >= 12 {
                bytes[8..12].copy_from_slice(&(len as u32).to_le_bytes());
            }
        }
        assert!(decoder.decode(&bytes).is_err(), "{len} random bytes decoded");
    }
}

#[test]
fn corrupting_any_byte_never_panics() {
    for s in samples() {
        let mut accepted = 0;
        let header_len = read_header(&s.bytes, &Limits::default()).unwrap().encoded_len();
        for at in 0..s.bytes.len() {
            // Every field of the header and table gets four kinds of damage; payload
            // bytes, which only the plane decoder reads, get two.
            let masks: &[u8] = if at < header_len { &[0x01, 0x10, 0x80, 0xff] } else { &[0x01, 0xff] };
            for &mask in masks {
                let mut bytes = s.bytes.clone();
                bytes[at] ^= mask;
                if let Ok(frame) = s.decoder.clone().decode(&bytes) {
                    assert_consistent(&frame, s.name);
                    accepted += 1;
                }
            }
        }
        assert!(accepted < 2 * s.bytes.len(), "{}: some corruptions are caught", s.name);
    }
}

/// Offsets of interest in a frame: the fixed fields and channel 0's table entry.
const MODE: usize = 6;
const FLAGS: usize = 7;
const FRAME_LEN: usize = 8;
const COUNT: usize = 12;
const SEQUENCE: usize = 24;
const BASE: usize = 32;
const TIME: usize = 48;
const CHANNELS: usize = 56;
const TABLE: usize = 64;

/// The outcome without the decoded values, for failure messages.
fn brief(got: &Result<Frame, DecodeError>) -> String {
    match got {
        Ok(frame) => format!("a frame of {} particles", frame.positions.len()),
        Err(e) => format!("{e:?}"),
    }
}

fn frame_len(s: &Sample) -> u32 {
    s.bytes.len() as u32
}

fn count(s: &Sample) -> u32 {
    read_header(&s.bytes, &Limits::default()).unwrap().particle_count
}

fn put(bytes: &mut [u8], at: usize, value: &[u8]) {
    bytes[at..at + value.len()].copy_from_slice(value);
}

#[test]
fn corrupted_header_fields_are_refused() {
    let all = samples();
    type Edit = fn(&Sample, &mut Vec<u8>);
    let malformed: &[(&str, Edit)] = &[
        ("magic", |_, b| b[0] = b'X'),
        ("mode", |_, b| b[MODE] = 3),
        ("reserved flag", |_, b| b[FLAGS] |= 2),
        ("frame length short by one", |s, b| put(b, FRAME_LEN, &(frame_len(s) - 1).to_le_bytes())),
        ("frame length below the header", |_, b| put(b, FRAME_LEN, &10u32.to_le_bytes())),
        ("one particle more", |s, b| put(b, COUNT, &(count(s) + 1).to_le_bytes())),
        ("one particle fewer", |s, b| put(b, COUNT, &(count(s) - 1).to_le_bytes())),
        ("time NaN", |_, b| put(b, TIME, &f64::NAN.to_le_bytes())),
        ("no channels", |_, b| b[CHANNELS] = 0),
        ("17 channels", |_, b| b[CHANNELS] = 17),
        ("one channel more", |_, b| b[CHANNELS] += 1),
        ("reserved byte", |_, b| b[CHANNELS + 3] = 1),
        ("positions tagged as velocity", |_, b| b[TABLE] = 1),
        ("positions with 2 components", |_, b| b[TABLE + 1] = 2),
        ("positions with 5 components", |_, b| b[TABLE + 1] = 5),
        ("0 bits", |_, b| b[TABLE + 2] = 0),
        ("17 bits", |_, b| b[TABLE + 2] = 17),
        ("one bit fewer", |_, b| b[TABLE + 2] -= 1),
        ("unknown predictor", |_, b| b[TABLE + 3] = 9),
        ("payload one byte longer", |_, b| b[TABLE + 4] = b[TABLE + 4].wrapping_add(1)),
        ("range minimum NaN", |_, b| put(b, TABLE + 8, &f32::NAN.to_le_bytes())),
        ("range minimum above maximum", |_, b| put(b, TABLE + 8, &1e9f32.to_le_bytes())),
        ("range minimum moved", |_, b| put(b, TABLE + 8, &(-0.5f32).to_le_bytes())),
        ("stated error doubled", |_, b| {
            let e = f32::from_le_bytes(b[TABLE + 16..TABLE + 20].try_into().unwrap());
            put(b, TABLE + 16, &(2.0 * e).to_le_bytes());
        }),
    ];
    // A grid's extent carries no redundant error field (it is not quantised), so a moved
    // extent is a different grid, not a malformed one.
    let quantised_only = ["one bit fewer", "range minimum moved", "stated error doubled"];
    for s in &all {
        for (what, edit) in malformed {
            if s.name == "grid" && quantised_only.contains(what) {
                continue;
            }
            let mut bytes = s.bytes.clone();
            edit(s, &mut bytes);
            let got = s.decoder.clone().decode(&bytes);
            assert!(matches!(got, Err(DecodeError::Malformed { .. })), "{}: {what} gave {}", s.name, brief(&got));
        }
        let mut bytes = s.bytes.clone();
        put(&mut bytes, 4, &(VERSION + 1).to_le_bytes());
        let got = s.decoder.clone().decode(&bytes);
        let unsupported = DecodeError::UnsupportedVersion { found: VERSION + 1, oldest: 3, newest: VERSION };
        assert_eq!(got, Err(unsupported), "{}", s.name);
        let mut bytes = s.bytes.clone();
        put(&mut bytes, FRAME_LEN, &(frame_len(s) + 1).to_le_bytes());
        let got = s.decoder.clone().decode(&bytes);
        assert!(matches!(got, Err(DecodeError::Incomplete { .. })), "{}: frame length +1 gave {}", s.name, brief(&got));
    }
    // Predictors the frame's mode forbids, and the extrapolation right after a keyframe.
    let predictor_swaps: [(usize, u8); 4] = [(0, 0), (2, 3), (3, 4), (4, 3)];
    for (i, predictor) in predictor_swaps {
        let mut bytes = all[i].bytes.clone();
        bytes[TABLE + 3] = predictor;
        let got = all[i].decoder.clone().decode(&bytes);
        assert!(
            matches!(got, Err(DecodeError::Malformed { .. })),
            "{}: predictor {predictor} gave {}",
            all[i].name,
            brief(&got)
        );
    }
    // Keyframes: both unordered samples, the identity keyframe and the grid frame.
    for s in all[0..3].iter().chain(&all[5..]) {
        let mut bytes = s.bytes.clone();
        bytes[FLAGS] = 0;
        let got = s.decoder.clone().decode(&bytes);
        assert!(
            matches!(got, Err(DecodeError::Malformed { .. })),
            "{}: keyframe flag cleared gave {}",
            s.name,
            brief(&got)
        );
    }
    // Delta frames.
    for s in &all[3..5] {
        let mut bytes = s.bytes.clone();
        put(&mut bytes, BASE, &77u64.to_le_bytes());
        let got = s.decoder.clone().decode(&bytes);
        assert!(
            matches!(got, Err(DecodeError::NeedKeyframe { base: 77, .. })),
            "{}: base gave {}",
            s.name,
            brief(&got)
        );
        let mut bytes = s.bytes.clone();
        bytes[SEQUENCE..SEQUENCE + 8].copy_from_slice(&s.bytes[BASE..BASE + 8]);
        let got = s.decoder.clone().decode(&bytes);
        assert!(matches!(got, Err(DecodeError::Malformed { .. })), "{}: self-predicting gave {}", s.name, brief(&got));
    }
}

#[test]
fn limits_are_checked_before_anything_is_allocated() {
    let s = &samples()[0];
    let tight = Limits { max_particles: 299, ..Limits::default() };
    let got = Decoder::new(tight).decode(&s.bytes);
    assert_eq!(got, Err(DecodeError::TooLarge { what: "particles", declared: 300, limit: 299 }));
    let small = Limits { max_frame_bytes: 100, ..Limits::default() };
    let got = Decoder::new(small).decode(&s.bytes[..FIXED_HEADER_LEN]);
    assert!(matches!(got, Err(DecodeError::TooLarge { what: "bytes", limit: 100, .. })), "{}", brief(&got));
    // A tiny frame that claims 16 Mi particles is refused by the plane-length check,
    // not by running out of memory.
    let mut bytes = samples()[1].bytes.clone();
    put(&mut bytes, COUNT, &(1u32 << 24).to_le_bytes());
    assert!(matches!(Decoder::new(Limits::default()).decode(&bytes), Err(DecodeError::Malformed { .. })));
}

#[test]
fn a_refused_frame_leaves_the_decoder_as_it_was() {
    let all = samples();
    let s = &all[4];
    let mut decoder = s.decoder.clone();
    let mut bytes = s.bytes.clone();
    let last = bytes.len() - 1;
    bytes[FRAME_LEN] ^= 1;
    assert!(decoder.decode(&bytes).is_err());
    bytes = s.bytes.clone();
    bytes.truncate(last);
    assert!(decoder.decode(&bytes).is_err());
    assert_eq!(decoder.held_sequence(), s.decoder.held_sequence());
    assert_consistent(&decoder.decode(&s.bytes).unwrap(), s.name);
}
