// A CG solve's dot-product terms and residual (floe-engine
// `schemes::dfsph::cg_cpu::Residual`): r alpha r and |r| dt^2 / rho0.

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> alpha: array<f32>;
@group(0) @binding(4) var<storage, read> res: array<f32>;
@group(0) @binding(5) var<storage, read_write> dots: array<f32>;
@group(0) @binding(6) var<storage, read_write> residual: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let r = res[i];
    let dt = step_dt.x;
    dots[i] = r * alpha[i] * r;
    residual[i] = abs(r) * dt * dt / params.materials[material_of(pos[i])].x;
}
