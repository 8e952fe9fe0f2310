// Weighted Jacobi (the first thesis's eqs. 2.33-2.35): each membership's way and
// weight by its cluster's deformation, the summed distance of its members from
// their goals (floe-engine `solid::cpu::Weigh`).

@group(0) @binding(2) var<storage, read> deformation: array<f32>;
@group(0) @binding(3) var<storage, read> segment: array<u32>;
@group(0) @binding(4) var<storage, read_write> way: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> weight: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= solid.sizes.y) {
        return;
    }
    let d = deformation[segment[k]];
    way[k] = vec4<f32>(way[k].xyz * d, 0.0);
    weight[k] = d;
}
