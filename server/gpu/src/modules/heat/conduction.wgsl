// Conduction (floe-engine `modules::heat::conduction`, term by term in the same
// order): dT/dt = 1/(rho_i c_i) [sum_j m_j / rho_j K_ij (T_i - T_j) F_ij
// + walls held at a temperature T_b, each the mirror image of the particle
// (2 (T_i - T_b)) + sources], F_ij = r dW/dr / (r^2 + 0.01 h^2).

@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> rho: array<f32>;
@group(0) @binding(4) var<storage, read> temperature: array<f32>;
@group(0) @binding(5) var<storage, read> starts: array<u32>;
@group(0) @binding(6) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> heat_rate: array<f32>;

fn pair_factor(r: f32) -> f32 {
    return r * kernel_dw_dr(r) / (r * r + heat.eps_h2);
}

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    let ti = temperature[i];
    let ma = material_of(pos[i]);
    var sum = 0.0;
    let b = block_of(xi, params.grid_origin, params.grid_inv_cell, params.grid_dims);
    for (var k = 0u; k < block_runs(b); k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = starts[run.x]; j < starts[run.y]; j++) {
            let x_ij = separation(xi, pos[j].xyz);
            let r2 = dot(x_ij, x_ij);
            if (r2 >= params.h2 || r2 == 0.0) {
                continue;
            }
            let mb = material_of(pos[j]);
            let m = params.materials[mb].y;
            let f = pair_factor(sqrt(r2));
            sum += m / rho[j] * heat.pair[ma * 16u + mb].x * (ti - temperature[j]) * f;
        }
    }
    if (params.n_walls > 0u && heat.n_walls > 0u) {
        let mat = params.materials[ma];
        let k_wall = heat.pair[ma * 16u + ma].x;
        let bw = block_of(xi, params.wall_origin, params.wall_inv_cell, params.wall_dims);
        for (var k = 0u; k < block_runs(bw); k++) {
            let run = run_cells(bw, k, params.wall_dims);
            for (var j = starts[params.wall_start + run.x]; j < starts[params.wall_start + run.y]; j++) {
                let w = walls[j];
                let x_ib = separation(xi, w.xyz);
                let r2 = dot(x_ib, x_ib);
                if (r2 >= params.h2 || r2 == 0.0) {
                    continue;
                }
                // The first box holding the wall particle gives its temperature.
                var box = heat.n_walls;
                for (var q = 0u; q < heat.n_walls; q++) {
                    if (inside(w.xyz, heat.wall_min[q], heat.wall_max[q])) {
                        box = q;
                        break;
                    }
                }
                if (box == heat.n_walls) {
                    continue;
                }
                let f = pair_factor(sqrt(r2));
                sum += w.w * mat.w / mat.x * k_wall * 2.0 * (ti - heat.wall_min[box].w) * f;
            }
        }
    }
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
    heat_rate[i] = (sum + source) / (rho[i] * heat.material[ma].y);
}
