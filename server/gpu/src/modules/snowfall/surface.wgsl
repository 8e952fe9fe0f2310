// The surface flakes land on (floe-engine `snowfall::Surface`): per cell the
// height of the snow's surface on the ground, the snow on objects' tops, and the
// bottom and top of the meshes' column (m).

@group(0) @binding(2) var<storage, read> ground_count: array<u32>;
@group(0) @binding(3) var<storage, read> top_count: array<u32>;
@group(0) @binding(4) var<storage, read> snow_bed: array<f32>;
@group(0) @binding(5) var<storage, read> columns: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read_write> snow_surface: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= snowfall.sizes.y * snowfall.sizes.z) {
        return;
    }
    let per = snowfall.more.w;
    let ground = f32(ground_count[k]) * per;
    snow_surface[k] = vec4<f32>(snow_bed[k] + ground, f32(top_count[k]) * per, columns[k].x, columns[k].y);
}
