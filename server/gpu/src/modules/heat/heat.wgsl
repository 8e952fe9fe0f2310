// The heat module's uniform (floe-gpu `modules::heat::uniform`), shared by its kernels;
// each binds it where its layout has it (`heat`).

struct Heat {
    // Per material: conductivity k (W/(m K)), heat capacity c (J/(kg K)),
    // expansion beta (1/K), unused.
    material: array<vec4<f32>, 16>,
    // Per material pair (a * 16 + b): 4 k_a k_b / (k_a + k_b) with the lattice
    // normalisation, in x.
    pair: array<vec4<f32>, 256>,
    // Boussinesq reference temperature T0 (K).
    reference: f32,
    // 0.01 h^2 (m^2), the pair factor's singularity guard.
    eps_h2: f32,
    n_walls: u32,
    n_sources: u32,
    // Walls held at a temperature: box corners, the temperature (K) in min.w.
    wall_min: array<vec4<f32>, 8>,
    wall_max: array<vec4<f32>, 8>,
    // Heat sources and wall fluxes: box corners; in min.w a source's power density
    // (W/m^3) or a flux's power per particle of its layer (W); in max.w 0 for a
    // source (inside the box), else the flux's layer thickness (m: the particles
    // outside the box within it).
    source_min: array<vec4<f32>, 8>,
    source_max: array<vec4<f32>, 8>,
    // The acceleration buoyancy acts along (m/s^2), in xyz.
    gravity: vec4<f32>,
    // Per material: the viscosity law's kind (as u32 bits; 0 none, 1 exponential,
    // 2 Arrhenius, 3 table) and its three parameters (mu_ref, T_ref, b or mu_ref,
    // 1/T_ref, E/R).
    law: array<vec4<f32>, 16>,
    // Per material: the clamp (Pa s), the table's number of points (u32 bits), and
    // 1 / law(T0) (1/(Pa s)) for the shift factor.
    law_clamp: array<vec4<f32>, 16>,
    // Per material, 4 each: the table's points (T K, mu Pa s), two per vec4.
    table: array<vec4<f32>, 64>,
    // Per material that melts or freezes (both phases): melting point (K), latent
    // heat (J/kg), the solid's and the melt's heat capacity (J/(kg K)).
    phase: array<vec4<f32>, 16>,
    // Per material: the solid's and the melt's material index, 1 where it changes
    // phase (0: never), unused.
    phase_of: array<vec4<u32>, 16>,
}

fn inside(p: vec3<f32>, lo: vec4<f32>, hi: vec4<f32>) -> bool {
    return all(p >= lo.xyz) && all(p <= hi.xyz);
}
