//! The scene section of a terrain wall (`kind = "terrain"` in `boundaries`) and its
//! validation.

use super::source::MAX_NODES;
use crate::scene::validate::Checker;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A heightfield wall: the ground under `[min, max]` in x and z, y up. Fluid stays
/// above the surface `y = h(x, z)`; particles in contact with it feel Coulomb
/// friction (see `floe_engine::terrain`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Terrain {
    /// Lower corner of the footprint, `[x, z]` (m).
    pub min: [f32; 2],
    /// Upper corner of the footprint, `[x, z]` (m).
    pub max: [f32; 2],
    /// Where the heights come from (default: the procedural mountain slope).
    #[serde(default)]
    pub heights: Heights,
    /// Coulomb friction coefficient mu (dimensionless, >= 0): a particle in contact
    /// loses at most `mu` times its normal speed change of the step in tangential
    /// speed. Fluid rests on slopes gentler than `atan(mu)`. 0 is a free-slip ground.
    #[serde(default)]
    pub friction: f32,
    /// Layers of boundary particles below the surface (1 to 4).
    #[serde(default = "crate::scene::default_layers")]
    pub layers: u32,
}

/// A terrain's height source.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "source", rename_all = "snake_case", deny_unknown_fields)]
pub enum Heights {
    /// A mountain side: heights fall along +x from `top` at `min.x` at `angle` to the
    /// `valley`, with a rounded foot, and vary gently along z:
    /// `h = valley + f(r) (1 + ripple / (top - valley) sin(2 pi (z - min.z) / wavelength))`,
    /// `r = top - valley - tan(angle) (x - min.x)`, `f(r) = r` above the foot, 0 in
    /// the valley, and `(r + foot)^2 / (4 foot)` for `|r| < foot` (continuous slope).
    Slope(Slope),
    /// A grayscale PNG (8 or 16 bits), black at `height_range[0]`, white at
    /// `height_range[1]`; pixel column i at `x = min.x + i (max.x - min.x) / (width - 1)`,
    /// row j at `z = min.z + j (max.z - min.z) / (height - 1)` (the first row at min.z).
    /// Exactly one of `asset` and `png_base64`.
    Png {
        /// A file name in the server's assets directory (`--assets DIR`): a plain name,
        /// no `/`, `\`, `..` or absolute path. Read once when the scene is created and
        /// kept in the scene as `png_base64`, so the scene does not depend on the file.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        asset: Option<String>,
        /// The PNG file itself, base64 (at most 2 MiB decoded).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        png_base64: Option<String>,
        /// Heights of black and white (m).
        height_range: [f32; 2],
    },
}

impl Default for Heights {
    fn default() -> Self {
        Heights::Slope(Slope::default())
    }
}

/// The procedural mountain side's parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Slope {
    /// Height at `min.x`, the top of the slope (m).
    #[serde(default = "default_top")]
    pub top: f32,
    /// Height of the flat valley (m).
    #[serde(default)]
    pub valley: f32,
    /// Slope angle from the horizontal (degrees, 0 to 80).
    #[serde(default = "default_angle")]
    pub angle: f32,
    /// Half-height of the rounded foot between slope and valley (m; 0 for a kink).
    #[serde(default = "default_foot")]
    pub foot: f32,
    /// Amplitude of the variation along z at the top (m), scaled down to 0 in the valley.
    #[serde(default = "default_ripple")]
    pub ripple: f32,
    /// Wavelength of the variation along z (m).
    #[serde(default = "default_wavelength")]
    pub wavelength: f32,
}

fn default_top() -> f32 {
    1.0
}
fn default_angle() -> f32 {
    30.0
}
fn default_foot() -> f32 {
    0.1
}
fn default_ripple() -> f32 {
    0.05
}
fn default_wavelength() -> f32 {
    1.0
}

impl Default for Slope {
    fn default() -> Self {
        Self {
            top: default_top(),
            valley: 0.0,
            angle: default_angle(),
            foot: default_foot(),
            ripple: default_ripple(),
            wavelength: default_wavelength(),
        }
    }
}

/// Whether `name` is a plain file name (no directory, no parent, not absolute).
pub fn plain_name(name: &str) -> bool {
    !name.is_empty() && !name.contains(['/', '\\']) && !name.contains("..") && !std::path::Path::new(name).is_absolute()
}

impl Terrain {
    /// Checks every field of the terrain at `path` (e.g. `boundaries[2].terrain`),
    /// decoding an inline PNG.
    pub fn validate(&self, c: &mut Checker, path: &str, spacing: f32) {
        c.vector(&format!("{path}.min"), &self.min);
        c.vector(&format!("{path}.max"), &self.max);
        for (k, axis) in ["x", "z"].iter().enumerate() {
            let (lo, hi) = (self.min[k], self.max[k]);
            if lo.is_finite() && hi.is_finite() && hi <= lo {
                c.fail(&format!("{path}.max"), format!("must exceed min along {axis}, got {hi} <= {lo}"));
            }
        }
        c.non_negative(&format!("{path}.friction"), self.friction);
        c.within(&format!("{path}.layers"), self.layers as f32, 1.0, 4.0);
        let heights = format!("{path}.heights");
        match &self.heights {
            Heights::Slope(s) => {
                c.finite(&format!("{heights}.top"), s.top);
                c.finite(&format!("{heights}.valley"), s.valley);
                if s.top.is_finite() && s.valley.is_finite() && s.top < s.valley {
                    c.fail(&format!("{heights}.top"), format!("must be >= valley ({}), got {}", s.valley, s.top));
                }
                c.within(&format!("{heights}.angle"), s.angle, 0.0, 80.0);
                c.non_negative(&format!("{heights}.foot"), s.foot);
                c.non_negative(&format!("{heights}.ripple"), s.ripple);
                c.positive(&format!("{heights}.wavelength"), s.wavelength);
                if spacing.is_finite() && spacing > 0.0 {
                    for (k, axis) in ["x", "z"].iter().enumerate() {
                        let nodes = ((self.max[k] - self.min[k]) / spacing).ceil() + 1.0;
                        if nodes > MAX_NODES as f32 {
                            c.fail(
                                &format!("{path}.max"),
                                format!(
                                    "the terrain is {nodes} particle spacings long along {axis}; at most {MAX_NODES} are sampled"
                                ),
                            );
                        }
                    }
                }
            }
            Heights::Png { asset, png_base64, height_range } => {
                c.vector(&format!("{heights}.height_range"), height_range);
                if height_range.iter().all(|h| h.is_finite()) && height_range[1] < height_range[0] {
                    c.fail(&format!("{heights}.height_range"), "must be [lo, hi] with lo <= hi".into());
                }
                match (asset, png_base64) {
                    (Some(_), Some(_)) | (None, None) => {
                        c.fail(&heights, "give exactly one of asset and png_base64".into());
                    }
                    (Some(name), None) if !plain_name(name) => c.fail(
                        &format!("{heights}.asset"),
                        format!("must be a plain file name in the server's assets directory (no '/', '\\', '..' or absolute path), got {name:?}"),
                    ),
                    (Some(_), None) => {}
                    (None, Some(text)) => {
                        if let Err(e) = super::source::decode_base64(text).and_then(|b| super::source::decode_png(&b)) {
                            c.fail(&format!("{heights}.png_base64"), e);
                        }
                    }
                }
            }
        }
    }
}
