//! `GET /api/v1/scenes/{id}/terrain`: the height grid of each terrain of a scene, for
//! the viewer's ground mesh. Watching rights as for the scene itself (another user's
//! scene is 404).

use super::{ApiResult, SceneId, Who};
use crate::service::{Need, Registry};
use axum::Json;
use axum::extract::State as AxState;
use serde::Serialize;
use std::sync::Arc;

/// A scene's terrains.
#[derive(Debug, Serialize)]
pub struct TerrainsView {
    /// One per terrain wall, in the order of `boundaries`.
    pub terrains: Vec<TerrainView>,
}

/// One terrain's height grid.
#[derive(Debug, Serialize)]
pub struct TerrainView {
    /// Its index in the scene's `boundaries`.
    pub boundary: usize,
    /// Footprint's lower and upper corners `[x, z]` (m).
    pub min: [f32; 2],
    pub max: [f32; 2],
    /// Grid nodes along x and z.
    pub nx: u32,
    pub nz: u32,
    /// Heights (m), node `(i, k)` at `k nx + i`; y is up.
    pub heights: Vec<f32>,
}

pub(super) async fn terrain(
    AxState(r): AxState<Arc<Registry>>,
    Who(who): Who,
    SceneId(id): SceneId,
) -> ApiResult<TerrainsView> {
    let handle = r.get(&who, id, Need::Watch)?;
    let terrains = (handle.shared.terrains.iter())
        .map(|(boundary, g)| TerrainView {
            boundary: *boundary,
            min: g.min,
            max: g.max(),
            nx: g.nx,
            nz: g.nz,
            heights: g.heights.clone(),
        })
        .collect();
    Ok(Json(TerrainsView { terrains }))
}
