// The tracer's uniform (tests/tests/tracer/gpu.rs `uniform`).

struct Tracer {
    floor: f32,
    colours: u32,
    probes: u32,
    // How fast the ground rises (m/s).
    rise: f32,
    // The columns' grid: origin and size (m), cells per axis.
    origin: vec3<f32>,
    // Particles older than this (s) are removed (infinite: none).
    lifetime: f32,
    size: vec3<f32>,
    // Particles older than this (s) change into the phase `aged` (infinite: none).
    phase_age: f32,
    dims: vec3<u32>,
    // The material index of the phase `aged`.
    aged: u32,
}

@group(0) @binding(1) var<uniform> tracer: Tracer;
