//! Rasterising a terrain's heights once, at build: the procedural slope sampled at
//! about the particle spacing, a PNG at its own pixel grid; and reading a named
//! asset from the assets directory into the scene.

use super::HeightGrid;
use super::spec::{Heights, Slope, Terrain, plain_name};
use crate::scene::{Boundary, Scene};
use base64::Engine as _;
use std::path::Path;

/// Most grid points along either axis of a terrain.
pub const MAX_NODES: u32 = 4096;

/// Largest PNG file a scene may carry or name (bytes, 2 MiB).
pub const MAX_PNG_BYTES: usize = 2 << 20;

/// The height grid of `terrain` for a scene of particle spacing `spacing` (m).
pub fn rasterise(terrain: &Terrain, spacing: f32) -> Result<HeightGrid, String> {
    let extent = [terrain.max[0] - terrain.min[0], terrain.max[1] - terrain.min[1]];
    let (nx, nz, heights) = match &terrain.heights {
        Heights::Slope(s) => {
            let n = |e: f32| (((e / spacing).ceil() as u32) + 1).clamp(2, MAX_NODES);
            let (nx, nz) = (n(extent[0]), n(extent[1]));
            let mut heights = Vec::with_capacity((nx * nz) as usize);
            for k in 0..nz {
                for i in 0..nx {
                    let x = extent[0] * i as f32 / (nx - 1) as f32;
                    let z = extent[1] * k as f32 / (nz - 1) as f32;
                    heights.push(slope_height(s, x, z));
                }
            }
            (nx, nz, heights)
        }
        Heights::Png { png_base64: Some(text), height_range, .. } => {
            let image = decode_png(&decode_base64(text)?)?;
            let [lo, hi] = *height_range;
            let heights = image.values.iter().map(|&v| lo + (hi - lo) * v).collect();
            (image.width, image.height, heights)
        }
        Heights::Png { asset: Some(name), .. } => {
            return Err(format!("asset {name:?} was not read: scenes naming an asset load with an assets directory"));
        }
        Heights::Png { .. } => return Err("give exactly one of asset and png_base64".into()),
    };
    let cell = [extent[0] / (nx - 1) as f32, extent[1] / (nz - 1) as f32];
    Ok(HeightGrid { min: terrain.min, cell, nx, nz, heights })
}

/// The slope's height at `x`, `z` from the footprint's lower corner (m).
fn slope_height(s: &Slope, x: f32, z: f32) -> f32 {
    let drop = s.top - s.valley;
    let r = drop - s.angle.to_radians().tan() * x;
    let f = if r >= s.foot {
        r
    } else if r <= -s.foot {
        0.0
    } else {
        (r + s.foot) * (r + s.foot) / (4.0 * s.foot)
    };
    let ripple = if drop > 0.0 { s.ripple / drop * (std::f32::consts::TAU * z / s.wavelength).sin() } else { 0.0 };
    s.valley + f * (1.0 + ripple)
}

/// Every terrain of `scene` rasterised, `None` for the other walls, in boundary order.
pub fn rasterise_all(scene: &Scene) -> Result<Vec<Option<HeightGrid>>, String> {
    scene
        .boundaries
        .iter()
        .enumerate()
        .map(|(i, b)| match b {
            Boundary::Terrain(t) => {
                rasterise(t, scene.particle_spacing).map(Some).map_err(|e| format!("boundaries[{i}].heights: {e}"))
            }
            _ => Ok(None),
        })
        .collect()
}

/// Reads every terrain asset `scene` names from `dir` into the scene (`png_base64`),
/// so the scene no longer depends on the file. Errors name the field.
pub fn read_assets(scene: &mut Scene, dir: Option<&Path>) -> Result<(), Vec<String>> {
    let mut errors = Vec::new();
    for (i, b) in scene.boundaries.iter_mut().enumerate() {
        let Boundary::Terrain(Terrain { heights: Heights::Png { asset, png_base64, .. }, .. }) = b else {
            continue;
        };
        let Some(name) = asset.as_deref() else { continue };
        let path = format!("boundaries[{i}].heights.asset");
        let read = match dir {
            _ if !plain_name(name) => Err(format!(
                "must be a plain file name in the server's assets directory (no '/', '\\', '..' or absolute path), got {name:?}"
            )),
            None => Err(format!("{name:?}: no assets directory was given (--assets DIR)")),
            Some(dir) => read_asset(&dir.join(name), name),
        };
        match read {
            Ok(bytes) => {
                *png_base64 = Some(base64::engine::general_purpose::STANDARD.encode(bytes));
                *asset = None;
            }
            Err(e) => errors.push(format!("{path}: {e}")),
        }
    }
    if errors.is_empty() { Ok(()) } else { Err(errors) }
}

fn read_asset(path: &Path, name: &str) -> Result<Vec<u8>, String> {
    let meta = std::fs::metadata(path).map_err(|_| format!("no asset named {name:?} in the assets directory"))?;
    if !meta.is_file() {
        return Err(format!("asset {name:?} is not a file"));
    }
    if meta.len() > MAX_PNG_BYTES as u64 {
        return Err(format!("asset {name:?} has {} bytes, more than the limit of {MAX_PNG_BYTES} (2 MiB)", meta.len()));
    }
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read asset {name:?}: {e}"))?;
    decode_png(&bytes).map_err(|e| format!("asset {name:?}: {e}"))?;
    Ok(bytes)
}

/// Decodes inline base64, refusing more than [`MAX_PNG_BYTES`].
pub fn decode_base64(text: &str) -> Result<Vec<u8>, String> {
    // 4 characters carry 3 bytes: refuse before decoding anything larger.
    if text.len() / 4 * 3 > MAX_PNG_BYTES + 3 {
        return Err(format!("holds more than the limit of {MAX_PNG_BYTES} bytes (2 MiB) decoded"));
    }
    let bytes = base64::engine::general_purpose::STANDARD.decode(text).map_err(|e| format!("not base64: {e}"))?;
    if bytes.len() > MAX_PNG_BYTES {
        return Err(format!("holds {} bytes decoded, more than the limit of {MAX_PNG_BYTES} (2 MiB)", bytes.len()));
    }
    Ok(bytes)
}

/// A decoded grayscale image: values in 0..=1, row-major, first row first.
#[derive(Debug)]
pub struct Gray {
    /// Pixels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Black 0, white 1.
    pub values: Vec<f32>,
}

/// Decodes an 8- or 16-bit grayscale PNG of 2 to [`MAX_NODES`] pixels a side.
pub fn decode_png(bytes: &[u8]) -> Result<Gray, String> {
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::IDENTITY);
    let mut reader = decoder.read_info().map_err(|e| format!("not a PNG file: {e}"))?;
    let info = reader.info();
    let (width, height, color, depth) = (info.width, info.height, info.color_type, info.bit_depth);
    if color != png::ColorType::Grayscale {
        return Err(format!("must be a grayscale PNG, got colour type {color:?}"));
    }
    let wide = match depth {
        png::BitDepth::Eight => false,
        png::BitDepth::Sixteen => true,
        other => return Err(format!("must have 8 or 16 bits per pixel, got {other:?}")),
    };
    if !(2..=MAX_NODES).contains(&width) || !(2..=MAX_NODES).contains(&height) {
        return Err(format!("must be 2 to {MAX_NODES} pixels a side, got {width} x {height}"));
    }
    let mut buf = vec![0; reader.output_buffer_size().ok_or("image too large")?];
    let frame = reader.next_frame(&mut buf).map_err(|e| format!("corrupt PNG: {e}"))?;
    let (w, h) = (width as usize, height as usize);
    let mut values = Vec::with_capacity(w * h);
    for row in buf[..frame.buffer_size()].chunks_exact(frame.line_size).take(h) {
        if wide {
            values.extend(row.chunks_exact(2).take(w).map(|p| u16::from_be_bytes([p[0], p[1]]) as f32 / 65535.0));
        } else {
            values.extend(row.iter().take(w).map(|&p| p as f32 / 255.0));
        }
    }
    Ok(Gray { width, height, values })
}
