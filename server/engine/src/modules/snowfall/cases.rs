//! The snowfall's validation cases (docs/validation/cases.md §9), on the preset `snow_roof`:
//! flat ground under a roof 2 to 2.1 m up, x from 6 to 8 m, across the whole area.

use super::presets::ROOF;
use super::{Accounts, CELLS, GROUND_COUNT, SnowfallConsts};
use crate::Simulation;
use crate::attrs::Column;
use crate::validation::cases::{Case, Measured, Variant};
use crate::validation::run_probed;
use crate::validation::stability::{Expect, StabilityCase};

/// The cases, for the module registry.
pub const CASES: &[Case] = &[
    Case {
        name: "snowfall_open",
        module: "snowfall",
        reference: "docs/validation/cases.md §9: emitted = airborne + landed + left exactly; deposition on open flat ground = the emitted flux within 1 %, and the depth there grows at depth_per_hour; no deposit under a roof without wind",
        preset: "snow_roof",
        primary_error: "open_flux_error",
        spacings: (&[0.5, 0.25], &[0.5, 0.25, 0.125]),
        checked_at: Some(0.25),
        bounds: &[
            ("accounting_error", 0.0),
            ("open_flux_error", 0.01),
            ("open_depth_rate_error", 0.01),
            ("under_roof_flakes", 0.0),
        ],
        // With flutter: in still air without it every flake born in a step lands in
        // the same step, and where the window starts cuts a step's flakes in or out.
        variants: &[Variant { name: "flutter_1", overrides: &["snowfall.flutter=1"] }],
        measure: open_case,
    },
    Case {
        name: "snowfall_shelter",
        module: "snowfall",
        reference: "docs/validation/cases.md §9: with wind W and terminal speed v_t the bare patch behind a roof h up shifts downwind by h W / v_t (h = 2.05 m, the roof's mid-height) within one grid cell; emitted = airborne + landed + left exactly",
        preset: "snow_roof",
        primary_error: "shelter_shift_error_cells",
        spacings: (&[0.5, 0.25], &[0.5, 0.25, 0.125]),
        checked_at: Some(0.25),
        bounds: &[("shelter_shift_error_cells", 1.0), ("accounting_error", 0.0)],
        variants: &[
            Variant { name: "wind_1", overrides: &["snowfall.wind=[1,0]"] },
            Variant { name: "wind_2", overrides: &["snowfall.wind=[2,0]"] },
        ],
        measure: shelter_case,
    },
    Case {
        name: "snowfall_coverage",
        module: "snowfall",
        reference: "docs/validation/cases.md §9, the snow thesis's eqs. 2.1-2.2: coverage 0 inside the objects standing on the ground (occluded from every direction), 1 on open flat ground, cos(inclination) on the open mountain side (the terrain's own normal)",
        preset: "snowfall",
        primary_error: "slope_coverage_error",
        spacings: (&[0.5, 0.25], &[0.5, 0.25, 0.125]),
        checked_at: Some(0.25),
        bounds: &[("inside_coverage", 0.0), ("open_coverage_error", 0.0), ("slope_coverage_error", 0.01)],
        variants: &[Variant { name: "cone_25", overrides: &[] }],
        measure: coverage_case,
    },
    Case {
        name: "snowfall_release",
        module: "snowfall",
        reference: "docs/validation/cases.md §9, the release (issue: snowfall then avalanche): the snow that reached the ground is the cover left plus the released particles' mass, to 1e-6 relative; the steep cells keep less than a particle's snow; emitted = airborne + landed + left + released exactly",
        preset: "snowfall_then_avalanche",
        primary_error: "release_mass_error",
        spacings: (&[0.1], &[0.1, 0.05]),
        checked_at: Some(0.1),
        bounds: &[("release_mass_error", 1e-6), ("steep_cells_over_a_particle", 0.0), ("accounting_error", 0.0)],
        variants: &[Variant { name: "at_15", overrides: &["snowfall.release.at=15"] }],
        measure: release_case,
    },
];

/// The stability battery: flakes in a gale with violent gusts and flutter, flakes
/// almost without drag, and a grid of two-centimetre cells. Each must run to its
/// end with the flakes' accounts exact (the battery's check is that it finishes
/// finite; the accounts are checked by the module's tests).
pub const STABILITY: &[StabilityCase] = &[
    StabilityCase {
        name: "snowfall_gale",
        what: "flakes in a 40 m/s gale gusting by 100 % with 100 m/s^2 flutter: the flakes' step limit shrinks dt to ~1 ms",
        preset: "snow_roof",
        spacing: (0.25, 0.125),
        overrides: &["snowfall.wind=[40,0]", "snowfall.gusts=1", "snowfall.flutter=100"],
        until: (0.5, 5.0),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "snowfall_no_drag",
        what: "flakes with a 100 m/s terminal speed (drag time 10 s: free fall) from 4 m",
        preset: "snow_roof",
        spacing: (0.25, 0.125),
        overrides: &["snowfall.terminal_speed=100"],
        until: (1.0, 5.0),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "snowfall_fine_grid",
        what: "a snow grid of 2 cm cells (800 x 200) under 2000 flakes per m^2 per s",
        preset: "snow_roof",
        spacing: (0.25, 0.125),
        overrides: &["snowfall.cell=0.02", "snowfall.intensity={\"flakes_per_m2_s\":2000}"],
        until: (0.5, 5.0),
        expect: Expect::Finish,
    },
];

/// When the open-ground flux is first read (s): every flake then lands on flakes
/// born at least a second after the start. The window is two seconds.
const WINDOW: (f64, f64) = (6.0, 8.0);

/// Runs to just past the release; then, from the flakes' tally (not the release's
/// own counter), the flakes that reached the ground against the cover left plus
/// the particles' flakes, relative to the particles' mass.
fn release_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let r = sim.model().consts::<SnowfallConsts>().release.clone().expect("the preset releases");
    let at = f64::from(r.at.expect("the variant sets the time"));
    let (wall, halted) = run_probed(sim, at + 0.02, 1.0, |_| ());
    let a = Accounts::of(sim.backend());
    let reached = a.emitted - a.airborne - a.left - a.on_objects;
    let particles = sim.particle_count() as u64;
    let q = u64::from(r.flakes_per_particle);
    let mass = particles as f64 * f64::from(sim.model().materials.get(r.material as usize).mass);
    let missing = (a.on_ground + particles * q) as f64 - reached as f64;
    let (n, _) = ground(sim);
    let over = r.cells.iter().filter(|&&k| n[k as usize] >= r.flakes_per_particle).count();
    let errors = vec![
        ("release_mass_error", if particles == 0 { 1.0 } else { (missing * r.flake_mass()).abs() / mass }),
        ("steep_cells_over_a_particle", over as f64),
        ("accounting_error", accounting_error(sim)),
    ];
    (wall, halted, errors)
}

/// The flakes that do not add up: `|emitted - airborne - landed - left|`.
fn accounting_error(sim: &Simulation) -> f64 {
    let a = Accounts::of(sim.backend());
    (a.emitted as f64 - a.accounted() as f64).abs()
}

/// The flakes on the ground in each cell, with the grid's consts.
fn ground(sim: &Simulation) -> (Vec<u32>, SnowfallConsts) {
    let Column::U32(n) = sim.backend().download(&[GROUND_COUNT.name]).remove(0) else { panic!("counts are u32") };
    debug_assert_eq!(n.len(), sim.model().layout.count(CELLS));
    (n, sim.model().consts::<SnowfallConsts>().clone())
}

/// The cells whose centres lie in `[x0, x1] x [z0, z1]` (m), with their total count.
fn count_in(n: &[u32], c: &SnowfallConsts, x: [f32; 2], z: [f32; 2]) -> (u64, usize) {
    let mut total = (0, 0);
    for (k, &count) in n.iter().enumerate() {
        let (cx, cz) = super::flakes::centre(c, k);
        if cx >= x[0] && cx <= x[1] && cz >= z[0] && cz <= z[1] {
            total = (total.0 + u64::from(count), total.1 + 1);
        }
    }
    total
}

/// No wind: the deposit rate over open ground (x from 10.5 to 15.5 m, 0.5 m from
/// the edges) over [`WINDOW`] against the emitted flux; the flakes under the roof
/// (0.5 m in from its edges); the accounting at the end.
fn open_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let (open_x, open_z) = ([10.5, 15.5], [0.5, 3.5]);
    let mut first = None;
    let (wall, halted) = run_probed(sim, WINDOW.1, 0.5, |s| {
        if first.is_none() && s.time() >= WINDOW.0 {
            let (n, c) = ground(s);
            let (count, cells) = count_in(&n, &c, open_x, open_z);
            first = Some((s.time(), count, cells));
        }
    });
    let (n, c) = ground(sim);
    let (count, cells) = count_in(&n, &c, open_x, open_z);
    let (t0, count0, _) = first.unwrap_or((0.0, 0, cells));
    let area = cells as f64 * f64::from(c.cell * c.cell);
    let emitted = f64::from(c.rate) / f64::from((c.area_max[0] - c.area_min[0]) * (c.area_max[1] - c.area_min[1]));
    let flux = (count - count0) as f64 / (area * (sim.time() - t0));
    // The depth the cells gained, per hour, against the scene's setting.
    let depth = (count - count0) as f64 * f64::from(c.depth_per_flake) / cells as f64;
    let depth_per_hour = depth / (sim.time() - t0) * 3600.0;
    let wanted = f64::from(super::section(sim.scene()).depth_per_hour);
    let (_, [x0, x1], _) = ROOF;
    let (under, _) = count_in(&n, &c, [x0 + 0.5, x1 - 0.5], [0.0, 4.0]);
    let errors = vec![
        ("accounting_error", accounting_error(sim)),
        ("open_flux_error", (flux / emitted - 1.0).abs()),
        ("open_depth_rate_error", (depth_per_hour / wanted - 1.0).abs()),
        ("under_roof_flakes", under as f64),
    ];
    (wall, halted, errors)
}

/// With wind along x: the bare columns of cells (no flake anywhere along z) past
/// the bare strip upwind of where the first flakes land are the roof's shelter; the
/// distance of their centre from the roof's centre, against `h W / v_t`, in cells.
fn shelter_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let (wall, halted) = run_probed(sim, WINDOW.1, WINDOW.1, |_| {});
    let (n, c) = ground(sim);
    let bare: Vec<bool> =
        (0..c.nx as usize).map(|i| (0..c.nz as usize).all(|j| n[j * c.nx as usize + i] == 0)).collect();
    // Skip the upwind strip no flake reaches, then the ground they reach.
    let start = bare.iter().position(|&b| !b).unwrap_or(bare.len());
    let shelter: Vec<usize> = (start..bare.len()).skip_while(|&i| !bare[i]).take_while(|&i| bare[i]).collect();
    let (h, [x0, x1], _) = ROOF;
    let shift = 0.5 * (c.wind[0] / c.terminal_speed) * (2.0 * h + 0.1);
    let error = match (shelter.first(), shelter.last()) {
        (Some(&a), Some(&b)) => {
            let centre = c.origin[0] + 0.5 * (a + b + 1) as f32 * c.cell;
            f64::from((centre - (0.5 * (x0 + x1) + shift)).abs() / c.cell)
        }
        _ => f64::INFINITY,
    };
    let errors = vec![("shelter_shift_error_cells", error), ("accounting_error", accounting_error(sim))];
    (wall, halted, errors)
}

/// The coverage of the valley's cells, built (it depends on geometry alone):
/// inside the house, the car and the trees; on the open floor between the house
/// and the trees (x 15 to 19 m, z 0.5 to 3 m, farther from every object than the
/// cone reaches under its top); on the open mountain side (x 2 to 8 m) against the
/// cosine of the terrain's inclination from its raster's own normal.
fn coverage_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let c = sim.model().consts::<SnowfallConsts>().clone();
    let Column::F32(cover) = sim.backend().download(&[super::COVERAGE.name]).remove(0) else { panic!("f32") };
    let grid = sim
        .scene()
        .boundaries
        .iter()
        .find_map(|b| match b {
            crate::scene::Boundary::Terrain(t) => crate::terrain::source::rasterise(t, sim.model().spacing).ok(),
            _ => None,
        })
        .expect("the valley's terrain");
    let objects = &super::section(sim.scene()).objects;
    let (mut inside, mut open, mut slope, mut slope_cells) = (0.0f64, 0.0f64, 0.0f64, 0usize);
    for (k, &f) in cover.iter().enumerate() {
        let (x, z) = super::flakes::centre(&c, k);
        let within = |o: &super::spec::Object| match *o {
            super::spec::Object::Box { min, max } | super::spec::Object::Mesh { min, max, .. } => {
                x > min[0] && x < max[0] && z > min[2] && z < max[2]
            }
            super::spec::Object::Cylinder { centre, radius, .. } => (x - centre[0]).hypot(z - centre[1]) < radius,
        };
        if objects.iter().any(within) {
            inside = inside.max(f64::from(f));
        } else if (15.0..=19.0).contains(&x) && (0.5..=3.0).contains(&z) {
            open = open.max(f64::from((1.0 - f).abs()));
        } else if (2.0..=8.0).contains(&x) {
            let n = grid.eval(x, z).1;
            slope += f64::from((f - n.y).abs() / n.y);
            slope_cells += 1;
        }
    }
    let errors = vec![
        ("inside_coverage", inside),
        ("open_coverage_error", open),
        ("slope_coverage_error", slope / slope_cells.max(1) as f64),
    ];
    (0.0, None, errors)
}
