// The force pass walking its neighbours alone (walk.wgsl's hooks).

fn walk_begin(i: u32) {
    forces_begin(i);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    forces_pair(j, x_ij, r2);
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    forces_wall(b, x_ib, r2);
}

fn walk_end(i: u32) {
    forces_end(i);
}
