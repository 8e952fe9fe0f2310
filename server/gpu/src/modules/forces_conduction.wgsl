// The fluid's force pass and conduction in one neighbour walk (walk.wgsl's hooks):
// the force terms of fluid/forces.wgsl, then conduction's, for each pair. Heat's
// bindings follow the force pass's ten.

@group(0) @binding(10) var<uniform> heat: Heat;
@group(0) @binding(11) var<storage, read> temperature: array<f32>;
@group(0) @binding(12) var<storage, read_write> heat_rate: array<f32>;

fn walk_begin(i: u32) {
    forces_begin(i);
    conduction_begin(i);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    forces_pair(j, x_ij, r2);
    conduction_pair(j, r2);
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    forces_wall(b, x_ib, r2);
    conduction_wall(b, r2);
}

fn walk_end(i: u32) {
    forces_end(i);
    conduction_end(i);
}
