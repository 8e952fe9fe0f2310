//! What is fuzzed, each a function of arbitrary bytes that must return (an error is
//! fine) and never panic: the frame decoder, the scene parser (documents and
//! overrides), the snapshot loader, the REST API (requests through the real router)
//! and the WebSocket control messages. Each has seeds: valid inputs the mutations
//! start from.

use crate::auth::Caller;
use crate::service::{Limits, Options, Registry, SceneSource};
use axum::body::Body;
use axum::http::Request;
use floe_engine::Simulation;
use floe_engine::scene::load::{self, Format};
use floe_proto::{Bounds, ChannelKind, Decoder, Encoder, EncoderConfig, FrameInput, Limits as FrameLimits, Mode};
use std::sync::{Arc, OnceLock};
use tower::ServiceExt;

/// A fuzz target.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Target {
    /// floe-proto's frame decoder.
    Frame,
    /// Scene documents (TOML, JSON) and `key=value` overrides.
    Scene,
    /// The snapshot loader.
    Snapshot,
    /// REST requests through the router.
    Rest,
    /// WebSocket control messages.
    Ws,
}

impl Target {
    /// Every target.
    pub const ALL: [Target; 5] = [Target::Frame, Target::Scene, Target::Snapshot, Target::Rest, Target::Ws];

    /// Runs the target on one input.
    pub fn run(self, data: &[u8]) {
        match self {
            Target::Frame => frame(data),
            Target::Scene => scene(data),
            Target::Snapshot => snapshot(data),
            Target::Rest => rest(data),
            Target::Ws => ws(data),
        }
    }

    /// Valid inputs to start from.
    pub fn seeds(self) -> &'static [Vec<u8>] {
        static SEEDS: OnceLock<Vec<Vec<Vec<u8>>>> = OnceLock::new();
        let all = SEEDS.get_or_init(|| Target::ALL.iter().map(|t| t.make_seeds()).collect());
        &all[Target::ALL.iter().position(|t| *t == self).expect("listed")]
    }

    fn make_seeds(self) -> Vec<Vec<u8>> {
        match self {
            Target::Frame => frames().to_vec(),
            Target::Scene => scene_seeds(),
            Target::Snapshot => snapshot_seeds(),
            Target::Rest => REST_SEEDS.iter().map(|s| s.as_bytes().to_vec()).collect(),
            Target::Ws => WS_SEEDS.iter().map(|s| s.as_bytes().to_vec()).collect(),
        }
    }
}

/// A small scene's state: the particles frames and snapshots are made of.
fn small_scene() -> Simulation {
    let scene = load::from_preset("dam_break", &["particle_spacing=0.1".into()]).expect("a valid preset");
    Simulation::new_cpu(scene).expect("a small scene builds")
}

/// Frames of a small scene: unordered and identity-ordered (a keyframe, then delta
/// frames that predict from it), with and without channels.
fn frames() -> &'static [Vec<u8>] {
    static FRAMES: OnceLock<Vec<Vec<u8>>> = OnceLock::new();
    FRAMES.get_or_init(|| {
        let mut sim = small_scene();
        let bounds = Bounds { min: [0.0, 0.0, 0.0], max: [2.0, 1.2, 0.25] };
        let mut identity = Encoder::new(EncoderConfig::new(Mode::IdentityOrdered, 1, bounds)).expect("config");
        let mut out = Vec::new();
        for step in 0..3 {
            let p = sim.read(&["velocity", "density"]);
            let all = ["velocity", "density"].iter().fold(FrameInput::positions(&p.positions), |input, &name| {
                let kind = ChannelKind::named(name).expect("a fixed channel");
                input.with(kind, p.channel(name).expect("read").as_ref())
            });
            let mut unordered = Encoder::new(EncoderConfig::new(Mode::Unordered, 1, bounds)).expect("config");
            out.push(unordered.encode(step, sim.time(), &FrameInput::positions(&p.positions)).expect("encodes"));
            out.push(identity.encode(step, sim.time(), &all).expect("encodes"));
            sim.step().expect("a stable scene");
        }
        out
    })
}

/// Frame decoder: a fresh decoder, or one holding a keyframe when the first byte is
/// odd (so delta frames reach their prediction). Tight limits keep a forged header
/// from allocating much.
pub fn frame(data: &[u8]) {
    let limits = FrameLimits { max_particles: 1 << 16, max_frame_bytes: 1 << 22 };
    let mut decoder = Decoder::new(limits);
    if data.first().is_some_and(|b| b % 2 == 1) {
        let _ = decoder.decode(&frames()[1]);
    }
    let _ = decoder.decode(data);
    let _ = floe_proto::read_header(data, &limits);
}

fn scene_seeds() -> Vec<Vec<u8>> {
    let mut out = Vec::new();
    for name in floe_engine::scene::presets::names() {
        let scene = floe_engine::scene::presets::get(name).expect("a preset");
        out.push(
            format!("{}\0particle_spacing=0.05\ngravity=[0,-1,0]", toml::to_string(&scene).expect("serialises"))
                .into_bytes(),
        );
        out.push(serde_json::to_vec(&scene).expect("serialises"));
    }
    out.push(include_bytes!("../../../examples/column.toml").to_vec());
    out.push(b"\0fluids[0].viscosity={\"model\":\"artificial\",\"alpha\":0.1}\nsolver.kernel=mueller".to_vec());
    out
}

/// Scene parser: text up to a NUL is a document (JSON if it starts with `{`, else
/// TOML), the lines after it overrides, applied to the document and to a preset.
/// Parsing and validation only: nothing is built.
pub fn scene(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let (document, overrides) = text.split_once('\0').unwrap_or((&text, ""));
    let overrides: Vec<String> = overrides.lines().map(str::to_owned).collect();
    let format = if document.trim_start().starts_with('{') { Format::Json } else { Format::Toml };
    let _ = load::from_str(document, format, &overrides);
    let _ = load::from_preset("dam_break", &overrides);
}

fn snapshot_seeds() -> Vec<Vec<u8>> {
    let mut sim = small_scene();
    let mut out = vec![sim.snapshot()];
    for _ in 0..3 {
        sim.step().expect("a stable scene");
    }
    out.push(sim.snapshot());
    out
}

/// Most particles a fuzzed snapshot may build (larger scenes are valid but slow).
const SNAPSHOT_PARTICLES: u64 = 4000;

/// Snapshot loader: its scene is read first (as the server does) and, when small,
/// the snapshot is restored and stepped once.
pub fn snapshot(data: &[u8]) {
    let Ok(scene) = Simulation::snapshot_scene(data) else { return };
    let particles = floe_engine::module::counts(&scene).iter().map(|(_, n)| *n).fold(0, u64::saturating_add);
    if particles <= SNAPSHOT_PARTICLES
        && let Ok(mut sim) = Simulation::restore(data)
    {
        let _ = sim.step();
    }
}

/// Request seeds: `METHOD PATH\n` then the body.
const REST_SEEDS: &[&str] = &[
    "POST /api/v1/scenes\n{\"preset\": \"dam_break\", \"overrides\": [\"particle_spacing=0.1\"]}",
    "POST /api/v1/scenes\n{\"document\": \"particle_spacing = 0.1\", \"document_format\": \"toml\"}",
    "GET /api/v1/scenes\n",
    "GET /api/v1/scenes/1\n",
    "POST /api/v1/scenes/1/step\n{\"steps\": 2}",
    "POST /api/v1/scenes/1/step\n{\"until_time\": 0.001}",
    "POST /api/v1/scenes/1/run\n{\"real_time_factor\": 1}",
    "POST /api/v1/scenes/1/pause\n",
    "POST /api/v1/scenes/1/parameters\n{\"overrides\": [\"gravity=[0,-1,0]\"]}",
    "GET /api/v1/scenes/1/ws?channels=velocity&max_fps=30&bits=16&mode=identity\n",
    "POST /api/v1/scenes/1/reset\n",
    "GET /api/v1/presets\n",
    "PUT /api/v1/users/alice/quotas/open_streams\n{\"value\": 3}",
];

/// A registry with one small scene and low limits, and its router: requests that
/// would create large scenes are refused early.
fn app() -> &'static (Arc<Registry>, axum::Router, tokio::runtime::Runtime) {
    static APP: OnceLock<(Arc<Registry>, axum::Router, tokio::runtime::Runtime)> = OnceLock::new();
    APP.get_or_init(|| {
        let runtime =
            tokio::runtime::Builder::new_multi_thread().worker_threads(1).enable_all().build().expect("runtime");
        let options = Options { limits: Limits { max_scenes: 4, max_particles: 2000 }, ..Options::default() };
        let registry = Arc::new(Registry::new(options, Arc::new(floe_engine::simulation::cpu_backend)));
        let preset = SceneSource::Preset("dam_break".into());
        runtime
            .block_on(registry.create(&Caller::local(), preset, vec!["particle_spacing=0.1".into()]))
            .expect("a small scene");
        let router = crate::http::router(registry.clone(), "web".into());
        (registry, router, runtime)
    })
}

/// HTTP methods a mutated method name maps onto.
const METHODS: [&str; 7] = ["GET", "POST", "PUT", "DELETE", "PATCH", "HEAD", "OPTIONS"];

/// A request line's path made a valid URI: bytes a URI cannot hold are percent-encoded,
/// so a mutated path still reaches the router (and its extractors) rather than failing
/// before it.
fn uri(path: &[u8]) -> String {
    let mut out = String::from(if path.first() == Some(&b'/') { "" } else { "/" });
    for &b in path {
        if b.is_ascii_alphanumeric() || b"-._~/?&=%:@!$'()*+,;".contains(&b) {
            out.push(b as char);
        } else {
            out += &format!("%{b:02X}");
        }
    }
    out
}

/// REST: the first line is `METHOD PATH`, the rest the JSON body, sent through the
/// router (extractors, bodies, handlers, errors). Scenes the requests create beyond
/// the first are deleted again, and the first is paused, so inputs do not pile up work.
pub fn rest(data: &[u8]) {
    let (registry, router, runtime) = app();
    let (head, body) = data.split_at(data.iter().position(|&b| b == b'\n').unwrap_or(data.len()));
    let (method, path) = head.split_at(head.iter().position(|&b| b == b' ').unwrap_or(0));
    let method = METHODS
        .into_iter()
        .find(|m| m.as_bytes() == method)
        .unwrap_or(METHODS[method.iter().map(|&b| b as usize).sum::<usize>() % METHODS.len()]);
    let Ok(request) = Request::builder()
        .method(method)
        .uri(uri(path.get(1..).unwrap_or_default()))
        .header("content-type", "application/json")
        .body(Body::from(body.get(1..).unwrap_or_default().to_vec()))
    else {
        return;
    };
    runtime.block_on(async {
        // A request that steps far is abandoned (as a client that gives up): the
        // scene stops at its next step.
        let _ = tokio::time::timeout(std::time::Duration::from_millis(200), router.clone().oneshot(request)).await;
        let local = Caller::local();
        for h in registry.list(&local).into_iter().skip(1) {
            let _ = registry.delete(&local, h.shared.id).await;
        }
        if let Some(first) = registry.list(&local).first() {
            let _ = first.pause().await;
        }
    });
}

const WS_SEEDS: &[&str] = &[
    r#"{"op": "run", "real_time_factor": 1}"#,
    r#"{"op": "pause"}"#,
    r#"{"op": "step", "steps": 1}"#,
    r#"{"op": "step", "until_time": 0.5}"#,
    r#"{"op": "set", "overrides": ["gravity=[0,-1,0]", "fluids[0].xsph=0.1"]}"#,
    r#"{"op": "reset"}"#,
    r#"{"op": "status"}"#,
];

/// WebSocket control messages: parsed and checked as the socket does.
pub fn ws(data: &[u8]) {
    let _ = crate::ws::parse_control(&String::from_utf8_lossy(data));
}
