// heat_in += c heat_input dt, compensated (floe-engine `modules::heat::phase::Input`):
// the heat each particle took in from walls and sources.

@group(0) @binding(1) var<uniform> dt: vec4<f32>;
@group(0) @binding(2) var<uniform> heat: Heat;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> heat_input: array<f32>;
@group(0) @binding(5) var<storage, read_write> heat_in: array<f32>;
@group(0) @binding(6) var<storage, read_write> heat_in_carry: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let c = heat.material[material_of(pos[i])].y;
    let s = compensated_add(heat_in[i], heat_in_carry[i], dt.x * heat_input[i] * c, dt.w);
    heat_in[i] = s.x;
    heat_in_carry[i] = s.y;
}
