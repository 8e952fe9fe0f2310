// The walk (walk.wgsl) of a pass that takes no part of the walls.

fn walk_wall_neighbours(i: u32, xi: vec3<f32>) {}
