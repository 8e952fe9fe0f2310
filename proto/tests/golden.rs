//! Golden frames: encoded frames committed in `proto/testdata/` with JSON sidecars of
//! their header fields and decoded values, so the format cannot change unnoticed and a
//! decoder in another language can be tested against the same files.
//!
//! Regenerate (only when the format changes on purpose, with a version bump):
//! `FLOE_REGEN_GOLDEN=1 cargo test -p floe-proto --test golden`. Frames of older versions
//! live in `testdata/v3/` and `testdata/v4/`: they are only decoded, to show old recordings
//! still read.

mod common;

use common::{Particles, Rng, tolerance};
use floe_proto::{
    Bounds, ChannelInfo, ChannelKind, Decoder, Encoder, EncoderConfig, Frame, GridInfo, Header, Limits, Mode,
    Predictor, Values,
};
use serde_json::{Value, json};
use std::path::PathBuf;

/// One golden file: its name, what it shows, and the files to decode before it.
struct Golden {
    name: &'static str,
    description: &'static str,
    decode_after: &'static [&'static str],
}

/// Frames of the current format version, which today's encoder reproduces.
const GOLDEN: [Golden; 8] = [
    Golden {
        name: "unordered_positions",
        description: "Unordered, 200 particles, 16-bit positions only (Morton predictor).",
        decode_after: &[],
    },
    Golden {
        name: "unordered_channels",
        description: "Unordered, 300 particles of particle set 1, 12-bit positions, velocity (10 bits), density (12), \
                      pressure (8), temperature (16), material, and a per-scene channel (tag 64, 2 components, 9 bits); \
                      the other channels use the previous-particle predictor.",
        decode_after: &[],
    },
    Golden {
        name: "identity_keyframe",
        description: "Identity-ordered keyframe, 256 particles, 16-bit positions, velocity (10 bits) and material, \
                      each predicted from the previous particle.",
        decode_after: &[],
    },
    Golden {
        name: "identity_delta",
        description: "Identity-ordered delta frame after identity_keyframe: positions and material use the base \
                      predictor, velocity (new per-frame range) the previous-particle one.",
        decode_after: &["identity_keyframe"],
    },
    Golden {
        name: "identity_linear",
        description: "Identity-ordered delta frame after identity_delta: positions use the linear predictor, over an \
                      interval twice the previous one (gains near 2).",
        decode_after: &["identity_keyframe", "identity_delta"],
    },
    Golden {
        name: "grid_field",
        description: "Grid frame of grid set 2: 8 x 1 x 6 cells over [0, 2] x [0, 0.1] x [0, 1.5] m, a per-scene \
                      channel (tag 70, 1 component, 12 bits, a snow depth map) and temperature.",
        decode_after: &[],
    },
    Golden {
        name: "identity_ids",
        description: "Identity-ordered keyframe of 150 particles whose ids are not 0 .. n (born and died): ids from \
                      5000 on in gaps of 0 to 3, 16-bit positions and velocity (10 bits).",
        decode_after: &[],
    },
    Golden {
        name: "identity_ids_delta",
        description: "Identity-ordered delta frame after identity_ids, the same particles: positions use the base \
                      predictor, and the frame names their ids again.",
        decode_after: &["identity_ids"],
    },
];

/// Frames of format version 4, decoded (never re-encoded) to show old frames still decode.
const VERSION_4: [Golden; 6] = [
    Golden { name: "v4/unordered_positions", description: "", decode_after: &[] },
    Golden { name: "v4/unordered_channels", description: "", decode_after: &[] },
    Golden { name: "v4/identity_keyframe", description: "", decode_after: &[] },
    Golden { name: "v4/identity_delta", description: "", decode_after: &["v4/identity_keyframe"] },
    Golden {
        name: "v4/identity_linear",
        description: "",
        decode_after: &["v4/identity_keyframe", "v4/identity_delta"],
    },
    Golden { name: "v4/grid_field", description: "", decode_after: &[] },
];

/// Frames of format version 3, decoded (never re-encoded) to show old frames still decode.
const VERSION_3: [Golden; 5] = [
    Golden { name: "v3/unordered_positions", description: "", decode_after: &[] },
    Golden { name: "v3/unordered_channels", description: "", decode_after: &[] },
    Golden { name: "v3/identity_keyframe", description: "", decode_after: &[] },
    Golden { name: "v3/identity_delta", description: "", decode_after: &["v3/identity_keyframe"] },
    Golden {
        name: "v3/identity_linear",
        description: "",
        decode_after: &["v3/identity_keyframe", "v3/identity_delta"],
    },
];

fn path(name: &str, ext: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("testdata").join(format!("{name}.{ext}"))
}

/// Encodes the golden inputs, in the order of [`GOLDEN`], with the inputs they came from.
fn encode_all() -> Vec<(Vec<u8>, Particles)> {
    let bounds = Bounds { min: [0.0, 0.0, 0.0], max: [2.0, 1.2, 0.25] }.with_margin(0.05);
    let mut rng = Rng::new(2024);
    let mut out = Vec::new();

    let p = Particles::random(&mut rng, 200, &bounds, 0.0);
    let mut enc = Encoder::new(EncoderConfig::new(Mode::Unordered, 1, bounds)).unwrap();
    out.push((enc.encode(120, 0.5, &p.input()).unwrap(), p));

    let mut p = Particles::random(&mut rng, 300, &bounds, 1.0);
    p.set = 1;
    p.extra = Some((ChannelKind(64), 2, (0..600).map(|_| rng.range(-1.0, 1.0)).collect()));
    let mut config = EncoderConfig::new(Mode::Unordered, 2, bounds);
    config.position_bits = 12;
    config.channel_bits = vec![
        (ChannelKind::DENSITY, 12),
        (ChannelKind::PRESSURE, 8),
        (ChannelKind::TEMPERATURE, 16),
        (ChannelKind(64), 9),
    ];
    let mut enc = Encoder::new(config).unwrap();
    out.push((enc.encode(7, 0.125, &p.input()).unwrap(), p));

    let mut p = Particles::random(&mut rng, 256, &bounds, 0.0);
    p.velocities = Some((0..256).map(|_| std::array::from_fn(|_| rng.range(-2.0, 2.0))).collect());
    p.materials = Some((0..256).map(|i| (i % 3) as u8).collect());
    let mut enc = Encoder::new(EncoderConfig::new(Mode::IdentityOrdered, 3, bounds)).unwrap();
    // Frames 10 and then 20 steps apart (a subscriber that skipped one), so the linear
    // predictor's gains are near 2, not 1.
    let (mut step, mut time) = (60, 1.0);
    for steps in [10u64, 20, 0] {
        out.push((enc.encode(step, time, &p.input()).unwrap(), p.clone()));
        step += steps;
        let dt = steps as f32 / 640.0;
        p.drift(&bounds, dt);
        p.advance(&mut rng, &bounds, 0.001);
        time += f64::from(dt);
    }

    let grid = GridInfo { origin: [0.0; 3], size: [2.0, 0.1, 1.5], dims: [8, 1, 6] };
    let mut p = Particles { set: 2, grid: Some(grid), ..Default::default() };
    p.temperatures = Some((0..48).map(|_| rng.range(260.0, 275.0)).collect());
    p.extra = Some((ChannelKind(70), 1, (0..48).map(|i| 0.02 * (i % 8) as f32 + rng.range(0.0, 0.01)).collect()));
    let mut config = EncoderConfig::new(Mode::Grid, 4, bounds);
    config.channel_bits = vec![(ChannelKind(70), 12)];
    let mut enc = Encoder::new(config).unwrap();
    out.push((enc.encode(300, 2.5, &p.input()).unwrap(), p));

    let mut p = Particles::random(&mut rng, 150, &bounds, 0.0);
    p.velocities = Some((0..150).map(|_| std::array::from_fn(|_| rng.range(-2.0, 2.0))).collect());
    let mut next = 5000;
    let ids: Vec<u32> = (0..150)
        .map(|_| {
            let id = next;
            next += 1 + rng.int(0, 3) as u32;
            id
        })
        .collect();
    p.ids = Some(ids);
    let mut enc = Encoder::new(EncoderConfig::new(Mode::IdentityOrdered, 5, bounds)).unwrap();
    out.push((enc.encode(40, 0.2, &p.input()).unwrap(), p.clone()));
    p.drift(&bounds, 1.0 / 640.0);
    out.push((enc.encode(41, 0.2 + 1.0 / 640.0, &p.input()).unwrap(), p));
    out
}

fn mode_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Unordered => "unordered",
        Mode::IdentityOrdered => "identity_ordered",
        Mode::Grid => "grid",
    }
}

fn predictor_name(p: Predictor) -> &'static str {
    match p {
        Predictor::None => "none",
        Predictor::Previous => "previous",
        Predictor::Base => "base",
        Predictor::Morton => "morton",
        Predictor::Linear => "linear",
        Predictor::Gaps => "gaps",
    }
}

fn channel_json(c: &ChannelInfo) -> Value {
    json!({
        "kind": c.kind().name(),
        "tag": c.tag,
        "components": c.components,
        "bits": c.bits,
        "predictor": predictor_name(c.predictor),
        "predictor_tag": c.predictor as u8,
        "payload_len": c.payload_len,
        "ranges": c.ranges.iter().map(|r| json!({"min": r.min, "max": r.max, "max_error": r.max_error})).collect::<Vec<_>>(),
    })
}

fn header_json(h: &Header) -> Value {
    json!({
        "version": h.version,
        "mode": mode_name(h.mode),
        "keyframe": h.keyframe,
        "frame_len": h.frame_len,
        "particle_count": h.particle_count,
        "scene_id": h.scene_id,
        "set": h.set,
        "sequence": h.sequence,
        "base_sequence": h.base_sequence,
        "step": h.step,
        "time": h.time,
        "channels": h.channels.iter().map(channel_json).collect::<Vec<_>>(),
    })
}

/// The sidecar: header fields and every decoded value (f32 values written exactly).
fn sidecar(g: &Golden, frame: &Frame) -> Value {
    let channels: serde_json::Map<String, Value> = frame
        .channels
        .iter()
        .map(|(kind, values)| {
            let per_particle: Vec<Value> = match values {
                Values::Exact(v) => v.iter().map(|&x| json!(x)).collect(),
                Values::Float { components: 1, data } => data.iter().map(|&x| json!(x)).collect(),
                Values::Float { components, data } => {
                    data.chunks_exact(usize::from(*components)).map(|c| json!(c)).collect()
                }
            };
            (kind.name(), Value::Array(per_particle))
        })
        .collect();
    let mut v = json!({
        "description": g.description,
        "decode_after": g.decode_after.iter().map(|n| format!("{}.bin", n.rsplit('/').next().unwrap_or(n))).collect::<Vec<_>>(),
        "header": header_json(&frame.header),
        "positions": frame.positions,
        "channels": channels,
    });
    if let Some(grid) = &frame.grid {
        v["grid"] = json!({"origin": grid.origin, "size": grid.size, "dims": grid.dims});
    }
    if let Some(ids) = &frame.ids {
        v["ids"] = json!(ids);
    }
    v
}

fn decode_golden(g: &Golden, bytes: &[u8]) -> Frame {
    let mut decoder = Decoder::new(Limits::default());
    for before in g.decode_after {
        decoder.decode(&std::fs::read(path(before, "bin")).unwrap()).unwrap();
    }
    decoder.decode(bytes).unwrap_or_else(|e| panic!("{}: {e}", g.name))
}

/// The sidecar as text: the header indented, each particle's values on one line.
fn render(sidecar: &Value) -> String {
    let list = |items: &[Value], indent: &str| {
        let lines: Vec<String> = items.iter().map(|x| format!("{indent}  {x}")).collect();
        if lines.is_empty() { "[]".to_string() } else { format!("[\n{}\n{indent}]", lines.join(",\n")) }
    };
    let fields: Vec<String> = sidecar
        .as_object()
        .expect("an object")
        .iter()
        .map(|(key, v)| {
            let value = match (key.as_str(), v) {
                ("channels", Value::Object(channels)) if !channels.is_empty() => {
                    let parts: Vec<String> = channels
                        .iter()
                        .map(|(name, values)| {
                            format!("    {}: {}", Value::from(name.as_str()), list(values.as_array().unwrap(), "    "))
                        })
                        .collect();
                    format!("{{\n{}\n  }}", parts.join(",\n"))
                }
                (k, Value::Array(items)) if k != "decode_after" => list(items, "  "),
                _ => serde_json::to_string_pretty(v).unwrap().replace('\n', "\n  "),
            };
            format!("  {}: {value}", Value::from(key.as_str()))
        })
        .collect();
    format!("{{\n{}\n}}\n", fields.join(",\n"))
}

/// Writes the golden frames and their sidecars, after checking that identity-ordered
/// positions decode within their stated error (the round-trip tests cover the rest).
fn regenerate() {
    for (g, (bytes, input)) in GOLDEN.iter().zip(encode_all()) {
        std::fs::write(path(g.name, "bin"), &bytes).unwrap();
        let frame = decode_golden(g, &bytes);
        if frame.header.mode == Mode::IdentityOrdered {
            for (got, want) in frame.positions.iter().zip(&input.positions) {
                for c in 0..3 {
                    assert!((got[c] - want[c]).abs() <= tolerance(&frame.header.channels[0], c), "{}", g.name);
                }
            }
        }
        std::fs::write(path(g.name, "json"), render(&sidecar(g, &frame))).unwrap();
    }
}

/// Where `got` and `want` first differ, as a JSON path with both values.
fn first_difference(path: &str, got: &Value, want: &Value) -> Option<String> {
    match (got, want) {
        (Value::Object(g), Value::Object(w)) => {
            let keys: std::collections::BTreeSet<&String> = g.keys().chain(w.keys()).collect();
            keys.into_iter().find_map(|k| {
                let (a, b) = (g.get(k).unwrap_or(&Value::Null), w.get(k).unwrap_or(&Value::Null));
                first_difference(&format!("{path}.{k}"), a, b)
            })
        }
        (Value::Array(g), Value::Array(w)) if g.len() == w.len() => {
            g.iter().zip(w).enumerate().find_map(|(i, (a, b))| first_difference(&format!("{path}[{i}]"), a, b))
        }
        _ => (got != want).then(|| format!("{path}: decoded {got}, sidecar {want}")),
    }
}

/// Regenerates the golden files once per test run, when asked to.
fn regenerate_if_asked() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    if std::env::var_os("FLOE_REGEN_GOLDEN").is_some_and(|v| v == "1") {
        ONCE.call_once(regenerate);
    }
}

fn read_sidecar(g: &Golden) -> Value {
    let text = std::fs::read_to_string(path(g.name, "json")).unwrap_or_else(|e| panic!("{}.json: {e}", g.name));
    serde_json::from_str(&text).unwrap()
}

#[test]
fn golden_frames_decode_to_their_sidecars() {
    regenerate_if_asked();
    for g in GOLDEN.iter().chain(&VERSION_4).chain(&VERSION_3) {
        let bytes = std::fs::read(path(g.name, "bin")).unwrap_or_else(|e| panic!("{}.bin: {e}", g.name));
        let frame = decode_golden(g, &bytes);
        assert_eq!(frame.header.frame_len as usize, bytes.len(), "{}", g.name);
        let (mut got, want) = (sidecar(g, &frame), read_sidecar(g));
        if g.description.is_empty() {
            got["description"] = want["description"].clone();
        }
        // Exact comparison: f32 values are written as the f64 of the same value, which
        // reads back exactly, so any change in the format or its arithmetic shows.
        if let Some(d) = first_difference(g.name, &got, &want) {
            panic!("golden frame differs: {d}");
        }
    }
}

#[test]
fn todays_encoder_reproduces_the_golden_values() {
    regenerate_if_asked();
    let mut unordered = Decoder::new(Limits::default());
    let mut identity = Decoder::new(Limits::default());
    for (g, (bytes, _)) in GOLDEN.iter().zip(encode_all()) {
        let want = read_sidecar(g);
        let decoder = if g.name.starts_with("identity") { &mut identity } else { &mut unordered };
        if g.decode_after.is_empty() {
            decoder.reset();
        }
        let frame = decoder.decode(&bytes).unwrap();
        if let Some(d) = first_difference(g.name, &sidecar(g, &frame), &want) {
            panic!("today's encoder differs from the golden frame: {d}");
        }
    }
}
