// The `viscosity` uniform (floe-gpu `viscosity::uniform`) of the
// per-particle viscosity's force and implicit solve: x is the walls' shear factor
// (1 no slip, 0 slip), y the pair sum's lattice normalisation.

@group(0) @binding(1) var<uniform> viscous_walls: vec4<f32>;
