// A CG solve's start (floe-engine `schemes::dfsph::cg_cpu::Start`): the residual
// `r = b` from the current velocities, `(rho + dt Drho/Dt - rho0) / dt^2`
// (`density`) or `(Drho/Dt) / dt` (`divergence`), 0 for a held particle.

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
// z: the walls' factor.
@group(0) @binding(2) var<uniform> dfsph: vec4<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> rho: array<f32>;
@group(0) @binding(6) var<storage, read> starts: array<u32>;
@group(0) @binding(7) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read> held: array<f32>;
@group(0) @binding(9) var<storage, read_write> res: array<f32>;

// Writes r, the density solve's if `density`.
fn start(i: u32, density: bool) {
    if (held[i] != 0.0) {
        res[i] = 0.0;
        return;
    }
    let dt = step_dt.x;
    let r = rate(i);
    if (density) {
        res[i] = (rho[i] + dt * r.x - params.materials[material_of(pos[i])].x) / (dt * dt);
    } else {
        res[i] = r.x / dt;
    }
}

@compute @workgroup_size(WG)
fn density(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i < params.n) {
        start(i, true);
    }
}

@compute @workgroup_size(WG)
fn divergence(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i < params.n) {
        start(i, false);
    }
}
