// Conduction (floe-engine `modules::heat::conduction`, term by term in the same
// order): dT/dt = 1/(rho_i c_i) [sum_j m_j / rho_j K_ij (T_i - T_j) F_ij
// + walls held at a temperature T_b, each the mirror image of the particle
// (2 (T_i - T_b)) + sources], F_ij = r dW/dr / (r^2 + 0.01 h^2).
// The terms, for walk.wgsl: conduction_walk.wgsl walks for them alone,
// forces_conduction.wgsl in the fluid's force walk. Both bind `heat`,
// `temperature` and `heat_rate`; `pos`, `rho` and `walls` are the walk's.

fn pair_factor(r: f32) -> f32 {
    return r * kernel_dw_dr(r) / (r * r + heat.eps_h2);
}

// The sum over i's neighbours, and what it needs of i; the walls' part of the
// sum and the sources' power density (for heat_input, conduction_input.wgsl).
var<private> conduction_sum: f32;
var<private> conduction_outside: f32;
var<private> conduction_source: f32;
var<private> conduction_ti: f32;
var<private> conduction_ma: u32;

fn conduction_begin(i: u32) {
    conduction_ti = temperature[i];
    conduction_ma = material_of(pos[i]);
    conduction_sum = 0.0;
    conduction_outside = 0.0;
}

fn conduction_pair(j: u32, r2: f32) {
    let mb = material_of(pos[j]);
    let m = params.materials[mb].y;
    let f = pair_factor(sqrt(r2));
    conduction_sum += m / rho[j] * heat.pair[conduction_ma * 16u + mb].x * (conduction_ti - temperature[j]) * f;
}

// Only walls held at a temperature conduct; without any, the walls need no visit.
fn conduction_walls() -> bool {
    return heat.n_walls > 0u;
}

fn conduction_wall(b: u32, r2: f32) {
    let w = walls[b];
    // The first box holding the wall particle gives its temperature.
    var box = heat.n_walls;
    for (var q = 0u; q < heat.n_walls; q++) {
        if (inside(w.xyz, heat.wall_min[q], heat.wall_max[q])) {
            box = q;
            break;
        }
    }
    if (box == heat.n_walls) {
        return;
    }
    let ma = conduction_ma;
    let mat = params.materials[ma];
    let k_wall = heat.pair[ma * 16u + ma].x;
    let f = pair_factor(sqrt(r2));
    let term = w.w * mat.w / mat.x * k_wall * 2.0 * (conduction_ti - heat.wall_min[box].w) * f;
    conduction_sum += term;
    conduction_outside += term;
}

fn conduction_end(i: u32) {
    let xi = pos[i].xyz;
    let ma = conduction_ma;
    var source = 0.0;
    for (var q = 0u; q < heat.n_sources; q++) {
        let lo = heat.source_min[q];
        let hi = heat.source_max[q];
        let layer = hi.w;
        if (layer > 0.0) {
            // A wall flux's layer: lo.w watts to each particle in it.
            if (!inside(xi, lo, hi) && all(xi >= lo.xyz - layer) && all(xi <= hi.xyz + layer)) {
                source += lo.w * rho[i] / params.materials[ma].y;
            }
        } else if (inside(xi, lo, hi)) {
            source += lo.w;
        }
    }
    conduction_source = source;
    heat_rate[i] = (conduction_sum + source) / (rho[i] * heat.material[ma].y);
}
