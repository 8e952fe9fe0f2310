//! The JSON views of a scene the REST calls answer with: the scene, its channels,
//! particle sets, materials and measures.

use crate::service::{Shared, State};
use serde::Serialize;
use std::sync::atomic::Ordering;

/// A scene as JSON.
#[derive(Debug, Default, Serialize)]
pub struct SceneView {
    /// Scene id.
    pub scene_id: u64,
    /// In a cluster's scene list, the worker holding it: calls for it go to
    /// `/w/WORKER/api/v1/...` through the proxy. Absent on a single server. A list
    /// from one worker gives the others' scenes with their id, name, owner, state,
    /// particles and worker only.
    #[serde(skip_serializing_if = "String::is_empty")]
    pub worker: String,
    /// Name.
    pub name: String,
    /// The user who created it.
    pub owner: String,
    /// `paused`, `running`, `halted` or `deleted`.
    pub state: &'static str,
    /// Simulated time (s).
    pub sim_time: f64,
    /// Steps taken.
    pub steps: u64,
    /// Fluid particles.
    pub particles: usize,
    /// Particle spacing (m), for drawing particles at their size.
    pub particle_spacing: f32,
    /// The backend stepping the scene: `gpu` or `cpu`.
    pub backend: &'static str,
    /// Domain (m).
    pub bounds_min: [f32; 3],
    /// Domain (m).
    pub bounds_max: [f32; 3],
    /// Why it halted, if it did.
    pub halt_reason: Option<String>,
    /// Steps per wall second.
    pub steps_per_second: f64,
    /// The last dt (s).
    pub dt: f64,
    /// Open frame streams.
    pub subscribers: u32,
    /// Frames skipped by slow subscribers.
    pub dropped_frames: u64,
    /// The resolved scene, live changes included.
    pub scene: serde_json::Value,
    /// Snapshots published.
    pub frames_published: u64,
    /// The channels the scene offers for frames, with wire tags and units.
    pub channels: Vec<ChannelView>,
    /// The scene's particle sets, with counts and the index frames carry.
    pub sets: Vec<SetView>,
    /// The scene's materials, in the order of the `material` channel's indices.
    pub materials: Vec<MaterialView>,
    /// The settings `parameters` may change.
    pub tunables: Vec<floe_engine::scene::tunable::Tunable>,
    /// What the scheme and modules measured (refreshed at most twice a second while
    /// running, and whenever stepping stops), by name.
    pub measures: std::collections::BTreeMap<String, MeasureView>,
    /// The resolution the server chose for a preset created without one (`floe
    /// serve --preset-size auto`); absent for a scene its creator sized.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sizing: Option<SizingView>,
}

/// A preset sized to the server's backend ([`crate::sizing::Sizing`]).
#[derive(Debug, Serialize)]
pub struct SizingView {
    /// The chosen particle spacing (m).
    pub spacing: f32,
    /// Particles at that spacing.
    pub particles: usize,
    /// Simulated seconds per wall second measured at that spacing, stepped alone.
    pub real_time_factor: f64,
    /// The preset's own spacing (m): `particle_spacing` for its full size.
    pub full_spacing: f32,
    /// Particles at the full size.
    pub full_particles: u64,
}

/// A channel a scene offers.
#[derive(Debug, Serialize)]
pub struct ChannelView {
    /// Name to ask for.
    pub name: &'static str,
    /// Wire tag.
    pub tag: u8,
    /// SI unit.
    pub unit: &'static str,
    /// Values per particle.
    pub components: u8,
    /// Particle set.
    pub set: &'static str,
    /// Sent exactly (raw u8).
    pub exact: bool,
    /// What it holds.
    pub about: &'static str,
    /// Declaring module.
    pub module: &'static str,
}

/// A particle set of a scene.
#[derive(Debug, Serialize)]
pub struct SetView {
    /// Name.
    pub name: &'static str,
    /// Particles (or cells) in it.
    pub count: usize,
    /// Its frames' set byte.
    pub index: usize,
    /// Whether it is a grid (its frames are grid frames, cells x fastest).
    pub grid: bool,
    /// How viewers draw it (`snow`, ...; absent: as a module's points or a field's colours).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub look: Option<&'static str>,
    /// For a grid: the channel of its cells' surface heights (m), where viewers draw them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface: Option<&'static str>,
    /// For a grid in a look: the channel (0 to 1) scaling how much of the look viewers draw.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shade: Option<&'static str>,
    /// For a part of another set (`solid`, `fluid` of `particles`): that set, whose
    /// channels it offers; its members change as particles change phase, keeping ids.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub part_of: Option<&'static str>,
}

/// A material of a scene.
#[derive(Debug, Serialize)]
pub struct MaterialView {
    /// Name, as the scene file gives it.
    pub name: String,
    /// `fluid` or `solid`.
    pub kind: &'static str,
    /// Rest density (kg/m^3).
    pub rest_density: f32,
    /// How viewers draw it: `water`, `snow`, `ice` or `solid`.
    pub look: &'static str,
}

/// A value a scene reports.
#[derive(Debug, Serialize)]
pub struct MeasureView {
    /// The value.
    pub value: f64,
    /// Its SI unit.
    pub unit: String,
}

/// Name of a state in JSON.
pub fn state_name(s: State) -> &'static str {
    match s {
        State::Paused => "paused",
        State::Running => "running",
        State::Halted => "halted",
        State::Deleted => "deleted",
    }
}

impl SceneView {
    /// The view now of a scene held by `worker` (empty on a single server).
    pub fn of(shared: &Shared, worker: &str) -> Self {
        let s = shared.status();
        Self {
            scene_id: shared.id,
            worker: worker.to_owned(),
            name: shared.name.clone(),
            owner: shared.owner.clone(),
            state: state_name(s.state),
            sim_time: s.time,
            steps: s.steps,
            particles: shared.particles,
            particle_spacing: shared.particle_spacing,
            backend: shared.backend,
            bounds_min: shared.bounds.0,
            bounds_max: shared.bounds.1,
            halt_reason: s.halt_reason,
            steps_per_second: s.steps_per_second,
            dt: s.dt,
            subscribers: shared.subscribers.load(Ordering::Relaxed),
            dropped_frames: shared.dropped_frames(),
            frames_published: shared.published.load(Ordering::Relaxed),
            scene: serde_json::from_str(&shared.scene_json()).unwrap_or_default(),
            sizing: shared.sizing().map(|s| SizingView {
                spacing: s.spacing,
                particles: s.particles,
                real_time_factor: s.rtf,
                full_spacing: s.full_spacing,
                full_particles: s.full_particles,
            }),
            channels: shared
                .channels
                .iter()
                .map(|c| ChannelView {
                    name: c.spec.name,
                    tag: c.kind.tag(),
                    unit: c.spec.unit,
                    components: c.spec.components,
                    set: c.spec.set,
                    exact: c.spec.exact,
                    about: c.spec.about,
                    module: c.spec.module,
                })
                .collect(),
            sets: shared
                .sets
                .iter()
                .enumerate()
                .map(|(index, s)| SetView {
                    name: s.name,
                    count: s.count,
                    index,
                    grid: s.grid,
                    look: s.look,
                    surface: s.surface,
                    shade: s.shade,
                    part_of: s.part_of,
                })
                .collect(),
            materials: shared
                .materials
                .iter()
                .map(|m| MaterialView {
                    name: m.name.clone(),
                    kind: m.kind.name(),
                    rest_density: m.rest_density,
                    look: m.look.name(),
                })
                .collect(),
            tunables: shared.tunables.clone(),
            measures: s
                .measures
                .iter()
                .map(|m| (m.name.clone(), MeasureView { value: m.value, unit: m.unit.clone() }))
                .collect(),
        }
    }
}
