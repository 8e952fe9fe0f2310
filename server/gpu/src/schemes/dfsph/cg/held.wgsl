// The particles a CG solve holds at P = 0 (floe-engine
// `schemes::dfsph::cg_cpu::Held`): 1 with fewer neighbours than `dfsph.y` or a
// summed density below `dfsph.w` of rest, else 0. The count comes from the rate's
// walk (rate.wgsl), which reads the velocities.

// y: the neighbours a particle needs, z: the walls' factor, w: the fraction of the
// rest density below which a particle is held.
@group(0) @binding(1) var<uniform> dfsph: vec4<f32>;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> starts: array<u32>;
@group(0) @binding(6) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> held: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let rest = params.materials[material_of(pos[i])].x;
    held[i] = select(0.0, 1.0, rate(i).y < dfsph.y || rho[i] < dfsph.w * rest);
}
