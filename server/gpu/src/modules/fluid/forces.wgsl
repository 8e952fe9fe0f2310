// Gravity and viscosity, and under WCSPH the pressure force, in one neighbour
// loop (floe-engine `modules::fluid::forces`, term by term in the same order):
// symmetric pressure (Monaghan 1992, eq. 3.3; several materials after Solenthaler
// & Pajarola 2008, eq. 6) with wall particles weighted by Akinci's pseudo-mass and
// given Adami's extrapolated pressure; viscosity per the material pair's model.
// The pressure terms come from forces_pressure.wgsl (WCSPH) or forces_plain.wgsl.

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

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    let vi = vel[i].xyz;
    let rho_i = rho[i];
    let ma = material_of(pos[i]);
    let pt_i = pressure_term(i);
    var a = params.gravity;
    let b = block_of(xi, params.grid_origin, params.grid_inv_cell, params.grid_dims);
    for (var k = 0u; k < block_runs(b); k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = starts[run.x]; j < starts[run.y]; j++) {
            let x_ij = separation(xi, pos[j].xyz);
            let r2 = dot(x_ij, x_ij);
            if (r2 >= params.h2 || r2 == 0.0) {
                continue;
            }
            let r = sqrt(r2);
            let grad = x_ij * (kernel_dw_dr(r) / r);
            let mb = material_of(pos[j]);
            let m = params.materials[mb].y;
            let pair = fluid.pair[ma * 16u + mb];
            a -= grad * pressure_pair(pt_i, j, m, pair.w, fluid.pair[mb * 16u + ma].w);
            let v_ij = vi - vel[j].xyz;
            a += viscosity(pair, x_ij, r, v_ij, m, rho_i, rho[j], grad);
        }
    }
    if (params.n_walls > 0u) {
        let mat = params.materials[ma];
        let own = fluid.material[ma];
        let bw = block_of(xi, params.wall_origin, params.wall_inv_cell, params.wall_dims);
        for (var k = 0u; k < block_runs(bw); k++) {
            let run = run_cells(bw, k, params.wall_dims);
            for (var j = starts[params.wall_start + run.x]; j < starts[params.wall_start + run.y]; j++) {
                let w = walls[j];
                let x_ib = separation(xi, w.xyz);
                let r2 = dot(x_ib, x_ib);
                if (r2 >= params.h2 || r2 == 0.0) {
                    continue;
                }
                let r = sqrt(r2);
                let grad = x_ib * (kernel_dw_dr(r) / r);
                let psi = w.w * mat.w;
                a -= grad * pressure_wall(pt_i, j, psi, mat.z);
                // Laplacian viscosity sees the wall as the mirror image of i
                // (`ViscosityModel::wall`).
                let v_ib = select(vi, vi * 2.0, own.x == VISC_LAPLACIAN);
                a += viscosity(own, x_ib, r, v_ib, psi, rho_i, mat.x, grad);
            }
        }
    }
    acc[i] = vec4<f32>(a, 0.0);
}
