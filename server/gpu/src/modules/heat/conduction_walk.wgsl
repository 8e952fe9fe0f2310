// Conduction walking its neighbours alone (walk.wgsl's hooks); `conduction_done`
// (conduction_plain.wgsl or conduction_input.wgsl) follows each particle's sum.

@group(0) @binding(1) var<uniform> heat: Heat;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> rho: array<f32>;
@group(0) @binding(4) var<storage, read> temperature: array<f32>;
@group(0) @binding(5) var<storage, read> starts: array<u32>;
@group(0) @binding(6) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> heat_rate: array<f32>;

fn walk_begin(i: u32) {
    conduction_begin(i);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    conduction_pair(j, r2);
}

fn walk_walls() -> bool {
    return conduction_walls();
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    conduction_wall(b, r2);
}

fn walk_end(i: u32) {
    conduction_end(i);
    conduction_done(i);
}
