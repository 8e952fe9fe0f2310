// The snow module's uniform (floe-gpu `modules::snow::uniform`) and the viscosity
// laws (floe-engine `modules::snow::rheology::Law::viscosity`, term by term).

struct Snow {
    // Per material: the law's kind (as u32 bits), the clamp (Pa s), the walls'
    // shear factor (1 no slip, 0 slip; the same for every material), unused.
    kind: array<vec4<f32>, 16>,
    // Per material: the law's four parameters.
    p: array<vec4<f32>, 16>,
}

@group(0) @binding(1) var<uniform> snow: Snow;

// x^y with Rust's powf at x = 0 (0 for y > 0, 1 for y = 0, beyond any clamp for
// y < 0), where WGSL's pow is undefined.
fn power(x: f32, y: f32) -> f32 {
    if (x > 0.0) {
        return pow(x, y);
    }
    if (y > 0.0) {
        return 0.0;
    }
    if (y == 0.0) {
        return 1.0;
    }
    return 3.0e38;
}

fn yield_term(tau0: f32, m: f32, g: f32) -> f32 {
    let x = m * g;
    if (x < 1e-3) {
        return tau0 * m * (1.0 - 0.5 * x);
    }
    return tau0 * (1.0 - exp(-x)) / g;
}

fn viscosity_of(material: u32, g: f32) -> f32 {
    let kind = bitcast<u32>(snow.kind[material].x);
    let p = snow.p[material];
    var mu = 0.0;
    switch kind {
        case 1u: { mu = p.x; }
        case 2u: { mu = p.y + (p.x - p.y) / (1.0 + power(p.z * g, p.w)); }
        case 3u: { mu = p.x * power(g, p.y - 1.0); }
        case 4u: { mu = p.y + yield_term(p.x, p.z, g); }
        case 5u: { mu = p.y * power(g, p.z - 1.0) + yield_term(p.x, p.w, g); }
        case 6u: { mu = p.y + (p.x - p.y) * power(1.0 + (p.z * g) * (p.z * g), 0.5 * (p.w - 1.0)); }
        default: {}
    }
    return max(min(mu, snow.kind[material].y), 0.0);
}
