// Gravity and viscosity, and under WCSPH the pressure force, in one neighbour
// walk (floe-engine `modules::fluid::forces`, term by term in the same order):
// symmetric pressure (Monaghan 1992, eq. 3.3; several materials after Solenthaler
// & Pajarola 2008, eq. 6) with wall particles weighted by Akinci's pseudo-mass and
// given Adami's extrapolated pressure; viscosity per the material pair's model.
// The pressure terms come from forces_pressure.wgsl (WCSPH) or forces_plain.wgsl;
// the walk (walk.wgsl) calls the terms below through forces_walk.wgsl, or through
// another module's file that walks these neighbours for its own pass as well.

struct Fluid {
    // Per material: viscosity kind (0 none, 1 Laplacian, 2 artificial), its
    // constants a and b, and the XSPH factor.
    material: array<vec4<f32>, 16>,
    // Per material pair (a * 16 + b): the mixed viscosity (kind, a, b) and m_a / m_b.
    pair: array<vec4<f32>, 256>,
}

@group(0) @binding(1) var<uniform> fluid: Fluid;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> starts: array<u32>;
@group(0) @binding(6) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> acc: array<vec4<f32>>;

const VISC_LAPLACIAN: f32 = 1.0;
const VISC_ARTIFICIAL: f32 = 2.0;

// Viscous acceleration on i from j (floe-engine `ViscosityModel::pair`) for the
// model (kind, a, b) in `model`.
fn viscosity(model: vec4<f32>, x_ij: vec3<f32>, r: f32, v_ij: vec3<f32>, m_j: f32, rho_i: f32, rho_j: f32, grad: vec3<f32>) -> vec3<f32> {
    if (model.x == VISC_LAPLACIAN) {
        return -v_ij * (model.y * m_j / (rho_i * rho_j) * kernel_laplacian(r));
    }
    if (model.x == VISC_ARTIFICIAL) {
        let mu_ij = min(dot(v_ij, x_ij), 0.0) / (r * r + model.z);
        let pi_ij = -model.y * mu_ij * 2.0 / (rho_i + rho_j);
        return -grad * (m_j * pi_ij);
    }
    return vec3<f32>(0.0);
}

// The sum over i's neighbours, and what it needs of i.
var<private> forces_a: vec3<f32>;
var<private> forces_vi: vec3<f32>;
var<private> forces_rho_i: f32;
var<private> forces_ma: u32;
var<private> forces_pt_i: f32;
var<private> forces_mat: vec4<f32>;
var<private> forces_own: vec4<f32>;

fn forces_begin(i: u32) {
    forces_vi = vel[i].xyz;
    forces_rho_i = rho[i];
    forces_ma = material_of(pos[i]);
    forces_pt_i = pressure_term(i);
    forces_mat = params.materials[forces_ma];
    forces_own = fluid.material[forces_ma];
    forces_a = params.gravity;
}

fn forces_pair(j: u32, x_ij: vec3<f32>, r2: f32) {
    let r = sqrt(r2);
    let grad = x_ij * (kernel_dw_dr(r) / r);
    let ma = forces_ma;
    let mb = material_of(pos[j]);
    let m = params.materials[mb].y;
    let pair = fluid.pair[ma * 16u + mb];
    forces_a -= grad * pressure_pair(forces_pt_i, j, m, pair.w, fluid.pair[mb * 16u + ma].w);
    let v_ij = forces_vi - vel[j].xyz;
    forces_a += viscosity(pair, x_ij, r, v_ij, m, forces_rho_i, rho[j], grad);
}

fn forces_wall(b: u32, x_ib: vec3<f32>, r2: f32) {
    let mat = forces_mat;
    let own = forces_own;
    let r = sqrt(r2);
    let grad = x_ib * (kernel_dw_dr(r) / r);
    let psi = walls[b].w * mat.w;
    forces_a -= grad * pressure_wall(forces_pt_i, b, psi, mat.z);
    // Laplacian viscosity sees the wall as the mirror image of i
    // (`ViscosityModel::wall`).
    let v_ib = select(forces_vi, forces_vi * 2.0, own.x == VISC_LAPLACIAN);
    forces_a += viscosity(own, x_ib, r, v_ib, psi, forces_rho_i, mat.x, grad);
}

fn forces_end(i: u32) {
    acc[i] = vec4<f32>(forces_a, 0.0);
}
