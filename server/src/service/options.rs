//! Frame options: what a subscriber asks for, checked once for every transport.
//! gRPC, REST and the WebSocket each turn their request into a [`FrameRequest`]
//! and [`FrameRequest::check`] it against the scene, so the rules, defaults and
//! messages are the same everywhere.

use super::ServiceError;
use super::shared::Shared;
use super::view::{View, ViewRequest};
use floe_proto::Mode;

/// Most frames per second a subscriber may ask for.
pub const MAX_FPS: f64 = 240.0;
/// Most particles a decimated stream may skip between two it sends.
pub const MAX_DECIMATION: u32 = 1000;

/// Frame options as a request states them; `None` takes the default.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FrameRequest {
    /// Channels besides positions, by name (`SceneInfo.channels`).
    pub channels: Vec<String>,
    /// Most frames per second (default 30).
    pub max_fps: Option<f64>,
    /// Bits per position axis, 8 to 16 (default 16).
    pub position_bits: Option<u32>,
    /// `unordered` (default) or `identity`; a grid set's frames are grid frames
    /// whichever is asked.
    pub mode: Option<String>,
    /// Send every n-th particle, 1 to 1000 (default 1: all).
    pub decimation: Option<u32>,
    /// The particle set (default `particles`).
    pub set: Option<String>,
    /// A region of interest and a particle budget (default: every particle).
    pub view: super::view::ViewRequest,
}

/// Checked frame options.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameOptions {
    /// Channels besides positions, as the scene names them, each once.
    pub channels: Vec<&'static str>,
    /// Most frames per second.
    pub max_fps: f64,
    /// Bits per position axis (8 to 16).
    pub position_bits: u8,
    /// Unordered, identity-ordered, or grid (a grid set).
    pub mode: Mode,
    /// Send every n-th particle (particles 0, n, 2n, ...); 1 sends all.
    pub decimation: u32,
    /// Index of the particle set in the scene's sets (the frames' set byte).
    pub set: u8,
    /// The region of interest and budget asked for at the start (a stream may change
    /// it later: [`super::frames::ViewControl`]).
    pub view: Option<View>,
}

impl FrameRequest {
    /// The options, or an error naming the first bad field (channel names the scene
    /// lacks are refused with the list of those it has).
    pub fn check(&self, scene: &Shared) -> Result<FrameOptions, ServiceError> {
        let bad = |m: String| Err(ServiceError::InvalidArgument(m));
        let set_name = self.set.as_deref().filter(|s| !s.is_empty()).unwrap_or(floe_engine::channels::PARTICLES);
        let Some(set) = scene.sets.iter().position(|s| s.name == set_name) else {
            let names: Vec<&str> = scene.sets.iter().map(|s| s.name).collect();
            return bad(format!("particle_set: the scene has no set {set_name:?}; it has {}", names.join(", ")));
        };
        let offers = scene.sets[set].channel_set();
        let mut channels = Vec::new();
        for name in self.channels.iter().map(|c| c.trim()).filter(|c| !c.is_empty()) {
            let found = scene.channels.iter().find(|c| c.spec.name == name && c.spec.set == offers);
            match found {
                Some(c) if !channels.contains(&c.spec.name) => channels.push(c.spec.name),
                Some(_) => {}
                None => {
                    let has: Vec<&str> =
                        scene.channels.iter().filter(|c| c.spec.set == offers).map(|c| c.spec.name).collect();
                    return bad(format!(
                        "channels: the scene has no channel {:?} in set {set_name}; it has {}",
                        crate::echo::cap(name),
                        has.join(", ")
                    ));
                }
            }
        }
        let max_fps = self.max_fps.unwrap_or(30.0);
        if !(max_fps.is_finite() && max_fps > 0.0 && max_fps <= MAX_FPS) {
            return bad(format!("max_fps: must be above 0 and at most {MAX_FPS}, got {max_fps}"));
        }
        let position_bits = self.position_bits.unwrap_or(16);
        if !(8..=16).contains(&position_bits) {
            return bad(format!("position_bits: must be 8 to 16, got {position_bits}"));
        }
        let mode = match self.mode.as_deref() {
            None | Some("") | Some("unordered") => Mode::Unordered,
            Some("identity") => Mode::IdentityOrdered,
            Some(other) => {
                return bad(format!("mode: must be \"unordered\" or \"identity\", got {:?}", crate::echo::cap(other)));
            }
        };
        let decimation = self.decimation.unwrap_or(1);
        if !(1..=MAX_DECIMATION).contains(&decimation) {
            return bad(format!("decimation: must be 1 to {MAX_DECIMATION}, got {decimation}"));
        }
        // A grid is sent whole, as grid frames (its cells keep their order, so either
        // mode asked gets them).
        let mode = match (scene.sets[set].grid, decimation) {
            (false, _) => mode,
            (true, 1) => Mode::Grid,
            (true, _) => {
                return bad(format!("decimation: set {set_name} is a grid, sent whole; ask for 1, got {decimation}"));
            }
        };
        let mut options = FrameOptions {
            channels,
            max_fps,
            position_bits: position_bits as u8,
            mode,
            decimation,
            set: set as u8,
            view: None,
        };
        options.view = options.check_view(&self.view, set_name)?;
        Ok(options)
    }
}

impl FrameOptions {
    /// The checked view of `request` for a stream with these options (None for an
    /// empty request); `set_name` for messages.
    pub fn check_view(&self, request: &ViewRequest, set_name: &str) -> Result<Option<View>, ServiceError> {
        if request.is_empty() {
            return Ok(None);
        }
        let bad = |m: String| Err(ServiceError::InvalidArgument(m));
        if self.mode == Mode::Grid {
            return bad(format!("view: set {set_name} is a grid, sent whole; ask for no region or budget"));
        }
        if self.decimation > 1 {
            return bad(format!(
                "view: a region or budget replaces decimation; ask for decimation 1, got {}",
                self.decimation
            ));
        }
        request.check().map(Some)
    }
}
