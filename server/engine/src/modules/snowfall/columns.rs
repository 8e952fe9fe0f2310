//! Mesh objects (a rock, a statue, a car from `--assets`) as columns over the snow
//! grid's cells: per cell, the lowest and the highest point where the vertical
//! line through the cell's centre crosses the mesh. A flake over the cell lands
//! on the column's top by the rule of the boxes and cylinders (it is in the
//! column, or crossed its top this step), and rays of the coverage are occluded
//! where they pass through a column. So a mesh is as fine as the grid, and what
//! lies under an overhang within one column counts as inside it.

use super::SnowfallConsts;
use crate::attrs::{AttrSpec, Elem, Role};
use crate::math::Vec3;
use crate::mesh::TriMesh;

/// Per cell: the bottom and top of the meshes' column over it (m); the top below
/// the bottom where there is none.
pub static COLUMNS: AttrSpec = AttrSpec {
    name: "snow_columns",
    elem: Elem::Vec4,
    unit: "m",
    role: Role::Constant,
    added_later: false,
    space: super::CELLS,
    module: "snowfall",
    about: "Bottom and top (m) of the mesh objects over each cell (top below bottom: none).",
};

/// No column: the top below the bottom.
pub const NONE: [f32; 4] = [f32::MAX, f32::MIN, 0.0, 0.0];

/// The columns of `meshes` (already fitted in place) over the grid of `c`.
pub fn columns(c: &SnowfallConsts, meshes: &[TriMesh]) -> Vec<[f32; 4]> {
    let mut out = vec![NONE; (c.nx * c.nz) as usize];
    for mesh in meshes {
        for tri in &mesh.triangles {
            let [a, b, d] = tri.map(|i| mesh.vertices[i as usize]);
            let (lo, hi) = (a.min(b).min(d), a.max(b).max(d));
            let range = |lo: f32, hi: f32, origin: f32, n: u32| {
                let first = ((lo - origin) / c.cell - 0.5).ceil().max(0.0) as u32;
                let last = ((hi - origin) / c.cell - 0.5).floor().min(n as f32 - 1.0);
                if last < 0.0 { first..0 } else { first..last as u32 + 1 }
            };
            for k in range(lo.z, hi.z, c.origin[1], c.nz) {
                for i in range(lo.x, hi.x, c.origin[0], c.nx) {
                    let cell = (k * c.nx + i) as usize;
                    let (x, z) = super::flakes::centre(c, cell);
                    if let Some(y) = crossing(a, b, d, x, z) {
                        let column = &mut out[cell];
                        column[0] = column[0].min(y);
                        column[1] = column[1].max(y);
                    }
                }
            }
        }
    }
    out
}

/// The height where the vertical line through `(x, z)` crosses triangle `abd`,
/// if it does (barycentric coordinates in the x-z plane, edges included).
fn crossing(a: Vec3, b: Vec3, d: Vec3, x: f32, z: f32) -> Option<f32> {
    let det = (b.x - a.x) * (d.z - a.z) - (d.x - a.x) * (b.z - a.z);
    if det.abs() < 1e-12 {
        return None;
    }
    let u = ((x - a.x) * (d.z - a.z) - (d.x - a.x) * (z - a.z)) / det;
    let v = ((b.x - a.x) * (z - a.z) - (x - a.x) * (b.z - a.z)) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0).then_some(a.y + u * (b.y - a.y) + v * (d.y - a.y))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube's two triangles on top and two at the bottom: the cells whose
    /// centres lie over it get its bottom and top, the others none.
    #[test]
    fn a_cube_is_a_column_over_its_cells() {
        let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
        let mesh = TriMesh {
            vertices: vec![
                v(1., 0., 1.),
                v(2., 0., 1.),
                v(2., 0., 2.),
                v(1., 0., 2.),
                v(1., 1., 1.),
                v(2., 1., 1.),
                v(2., 1., 2.),
                v(1., 1., 2.),
            ],
            triangles: vec![[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7]],
        };
        let c = SnowfallConsts { origin: [0.0, 0.0], cell: 0.5, nx: 8, nz: 8, ..test_consts() };
        let cols = columns(&c, &[mesh]);
        let at = |x: f32, z: f32| cols[super::super::flakes::cell(&c, x, z)];
        assert_eq!(at(1.25, 1.75)[..2], [0.0, 1.0]);
        assert_eq!(at(0.75, 1.25), NONE);
        assert_eq!(at(2.25, 1.25), NONE);
        assert_eq!(cols.iter().filter(|c| c[1] >= c[0]).count(), 4);
    }

    fn test_consts() -> SnowfallConsts {
        let scene = crate::scene::presets::get("snow_roof").unwrap();
        SnowfallConsts::new(&scene)
    }
}
