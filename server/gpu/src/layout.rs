//! Structs shared with the WGSL kernels, laid out to match WGSL's rules
//! (`vec3` aligned to 16 bytes, so each is followed by a scalar) and checked by
//! size assertions; the field order mirrors the WGSL declarations.

use bytemuck::{Pod, Zeroable};
use floe_engine::boundary::WallConstraint;
use floe_engine::kernel::KernelKind;
use floe_engine::model::Model;
use floe_engine::neighbors::Grid;

/// Materials a GPU scene may hold (the material table lives in the scene uniform).
pub const MAX_MATERIALS: usize = 16;

/// Scene constants of every particle kernel (`Params` in common.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct Params {
    /// SPH particles.
    pub n: u32,
    /// Wall particles.
    pub n_walls: u32,
    /// Wall constraints.
    pub n_constraints: u32,
    /// 0 Müller, 1 cubic spline.
    pub kernel_kind: u32,
    /// Particle grid: origin (m), cell count, inverse cell edge per axis (1/m), the
    /// wall grid's cell count, cells per axis, periodic axes (bit per axis).
    pub grid_origin: [f32; 3],
    pub cell_count: u32,
    pub grid_inv_cell: [f32; 3],
    pub wall_cell_count: u32,
    pub grid_dims: [u32; 3],
    pub periodic: u32,
    /// Wall grid, likewise; its run starts follow the particle grid's in `starts`,
    /// from index `wall_start`.
    pub wall_origin: [f32; 3],
    pub wall_start: u32,
    pub wall_inv_cell: [f32; 3],
    pub n_materials: u32,
    pub wall_dims: [u32; 3],
    /// Kernel normalisation.
    pub w_norm: f32,
    /// Gravity (m/s^2) and kernel support (m).
    pub gravity: [f32; 3],
    pub support: f32,
    /// Domain (m) and support squared (m^2).
    pub domain_min: [f32; 3],
    pub h2: f32,
    pub domain_max: [f32; 3],
    pub inv_h: f32,
    /// Period per axis (m, 0 on open axes), the gradient normalisation, half the
    /// period (the largest float on open axes).
    pub period: [f32; 3],
    pub g_norm: f32,
    pub half_period: [f32; 3],
    pub _pad: u32,
    /// Per material: rest density (kg/m^3), mass (kg), `1 / rho0^2`, and the ratio
    /// of its rest density to material 0's (wall pseudo-masses scale by it).
    pub materials: [[f32; 4]; MAX_MATERIALS],
}
const _: () = assert!(std::mem::size_of::<Params>() == 192 + 16 * MAX_MATERIALS);

impl Params {
    /// The constants of `model` on the particle grid `grid`.
    pub fn new(model: &Model, grid: &Grid) -> Self {
        let k = &model.kernel;
        let (w_norm, g_norm) = k.norms();
        let walls = &model.wall_particles.grid;
        let h = k.support();
        // (A scene without SPH particles has no material.)
        let rho00 = model.materials.iter().next().map_or(1.0, |m| m.rest_density);
        let mut materials = [[0.0; 4]; MAX_MATERIALS];
        for (slot, m) in materials.iter_mut().zip(model.materials.iter()) {
            *slot = [m.rest_density, m.mass, 1.0 / (m.rest_density * m.rest_density), m.rest_density / rho00];
        }
        Self {
            n: model.particle_count() as u32,
            n_walls: model.wall_particles.len() as u32,
            n_constraints: model.wall_constraints.len() as u32,
            kernel_kind: match k.kind() {
                KernelKind::Mueller => 0,
                KernelKind::CubicSpline => 1,
                KernelKind::WendlandC2 => 2,
            },
            grid_origin: grid.origin().to_array(),
            cell_count: grid.cell_count() as u32,
            grid_inv_cell: grid.inv_cell().to_array(),
            wall_cell_count: walls.cell_count() as u32,
            grid_dims: grid.dims(),
            periodic: (0..3).filter(|&a| model.periodic.axes[a]).map(|a| 1u32 << a).sum(),
            wall_origin: walls.origin().to_array(),
            wall_start: grid.cell_count() as u32 + 1,
            wall_inv_cell: walls.inv_cell().to_array(),
            n_materials: model.materials.len() as u32,
            wall_dims: walls.dims(),
            w_norm,
            gravity: model.gravity.to_array(),
            support: h,
            domain_min: model.domain.min.to_array(),
            h2: h * h,
            domain_max: model.domain.max.to_array(),
            inv_h: 1.0 / h,
            period: model.periodic.period().to_array(),
            g_norm,
            half_period: model.periodic.half().to_array(),
            _pad: 0,
            materials,
        }
    }
}

/// One kick or drift (`Step` in integrate.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, Pod, Zeroable)]
pub struct Step {
    /// dt of the kick (s).
    pub kick_dt: f32,
    /// Damping factor applied with the kick.
    pub keep: f32,
    /// dt of the drift (s).
    pub drift_dt: f32,
    /// 1 when the drift adds `dt/2 a_transport` to the velocity it moves with.
    pub transport: u32,
}
const _: () = assert!(std::mem::size_of::<Step>() == 16);

/// A wall's non-penetration constraint (`Constraint` in integrate.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, Pod, Zeroable)]
pub struct Constraint {
    /// 0 box, 1 plane, 2 terrain.
    pub kind: u32,
    /// Box: bit `2 axis + side` set for each closed face; terrain: index of its first
    /// height in the core's `ground_height`.
    pub closed: u32,
    /// How far outside the surface the constraint reaches (m).
    pub reach: f32,
    pub _pad: u32,
    /// Box: lower interior corner; plane: centre (m); terrain: the grid's lower
    /// corner `[x, z]` and node spacing `[x, z]` (m).
    pub a: [f32; 4],
    /// Box: upper interior corner; plane: unit normal; terrain: friction
    /// coefficient, contact distance (m), nodes along x and along z.
    pub b: [f32; 4],
    /// Plane: unit tangents with half edge lengths (m) in `w`.
    pub t1: [f32; 4],
    pub t2: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<Constraint>() == 80);

impl Constraint {
    /// The GPU constraints of `walls` (a terrain's gives where its heights start in
    /// the core's `ground_height`, every terrain's nodes one after another).
    pub fn all(walls: &[WallConstraint]) -> Vec<Constraint> {
        walls
            .iter()
            .map(|w| {
                let mut c = Constraint::from(w);
                if let WallConstraint::Terrain(t) = w {
                    c.closed = t.first as u32;
                }
                c
            })
            .collect()
    }
}

impl From<&WallConstraint> for Constraint {
    fn from(w: &WallConstraint) -> Self {
        let v4 = |v: glam::Vec3, w: f32| [v.x, v.y, v.z, w];
        match w {
            WallConstraint::Box { min, max, closed, reach } => {
                let mut bits = 0;
                for (axis, sides) in closed.iter().enumerate() {
                    for (side, &c) in sides.iter().enumerate() {
                        if c {
                            bits |= 1 << (2 * axis + side);
                        }
                    }
                }
                Constraint {
                    kind: 0,
                    closed: bits,
                    reach: *reach,
                    a: v4(*min, 0.0),
                    b: v4(*max, 0.0),
                    ..Default::default()
                }
            }
            WallConstraint::Plane { center, normal, tangents, reach } => Constraint {
                kind: 1,
                reach: *reach,
                a: v4(*center, 0.0),
                b: v4(*normal, 0.0),
                t1: v4(tangents[0].0, tangents[0].1),
                t2: v4(tangents[1].0, tangents[1].1),
                ..Default::default()
            },
            WallConstraint::Terrain(t) => {
                let g = &t.grid;
                Constraint {
                    kind: 2,
                    a: [g.min[0], g.min[1], g.cell[0], g.cell[1]],
                    b: [t.friction, t.contact, g.nx as f32, g.nz as f32],
                    ..Default::default()
                }
            }
        }
    }
}

/// The guard's and time step's measures (`Measures` in measure.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, Pod, Zeroable)]
pub struct Measures {
    pub speed2: f32,
    pub speed_slot: u32,
    pub accel2: f32,
    pub compression: f32,
    pub compression_slot: u32,
    pub compression_sum: f32,
    /// First non-finite slot, `u32::MAX` if none.
    pub non_finite: u32,
    /// First slot outside the domain, `u32::MAX` if none.
    pub outside: u32,
}
const _: () = assert!(std::mem::size_of::<Measures>() == 32);

impl From<Measures> for floe_engine::guard::Measures {
    fn from(m: Measures) -> Self {
        let slot = |s: u32| (s != u32::MAX).then_some(s);
        Self {
            max_speed2: (m.speed2, m.speed_slot),
            max_accel2: m.accel2,
            max_compression: (m.compression, m.compression_slot),
            sum_compression: m.compression_sum as f64,
            non_finite: slot(m.non_finite),
            outside: slot(m.outside),
        }
    }
}

/// A frame's position grid (`QuantGrid` in quantize.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, Pod, Zeroable)]
pub struct QuantGrid {
    /// Value of code 0 per axis (m).
    pub min: [f32; 3],
    /// The largest code.
    pub top: f32,
    /// Codes per metre per axis.
    pub scale: [f32; 3],
    pub _pad: f32,
}
const _: () = assert!(std::mem::size_of::<QuantGrid>() == 32);

impl From<&floe_engine::quantize::PositionGrid> for QuantGrid {
    fn from(g: &floe_engine::quantize::PositionGrid) -> Self {
        Self { min: g.min, top: g.top() as f32, scale: std::array::from_fn(|k| g.scale(k)), _pad: 0.0 }
    }
}

/// Parameters of one prefix-sum level (`ScanParams` in scan.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, Pod, Zeroable)]
pub struct ScanParams {
    /// Values at this level.
    pub len: u32,
    pub _pad: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<ScanParams>() == 16);

/// A strided copy or a reduction over one buffer (`Words` in reorder.wgsl and reduce.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, Pod, Zeroable)]
pub struct Words {
    /// Elements.
    pub n: u32,
    /// 32-bit words per element.
    pub stride: u32,
    /// Reduction: 0 sum, 1 max, 2 max of magnitudes, 3 count outside `[lo, hi]`.
    pub op: u32,
    pub _pad: u32,
    /// The range of reduction 3.
    pub lo: f32,
    pub hi: f32,
    pub _pad2: [u32; 2],
}
const _: () = assert!(std::mem::size_of::<Words>() == 32);
