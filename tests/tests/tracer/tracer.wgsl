// The tracer's uniform (tests/tests/tracer/gpu.rs `uniform`).

struct Tracer {
    floor: f32,
    colours: u32,
    probes: u32,
    _pad: u32,
}

@group(0) @binding(1) var<uniform> tracer: Tracer;
