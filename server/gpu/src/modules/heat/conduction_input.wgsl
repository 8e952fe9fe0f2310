// After a particle's conduction, the part of its rate from walls held at a
// temperature and from sources (floe-engine `modules::heat::conduction`, where a
// fluid melts and heat enters from outside).

@group(0) @binding(8) var<storage, read_write> heat_input: array<f32>;

fn conduction_done(i: u32) {
    let ma = conduction_ma;
    heat_input[i] = (conduction_outside + conduction_source) / (rho[i] * heat.material[ma].y);
}
