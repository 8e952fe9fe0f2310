//! The solid module's stability battery: stiff and extreme scenes of elastic
//! bodies, and of ice that melts, each of which must finish or halt naming why.

use crate::validation::stability::{Expect, StabilityCase};

/// The stability battery (VALIDATION.md's stiff and extreme cases for solids):
/// each must finish, or halt naming why.
pub const STABILITY: &[StabilityCase] = &[
    StabilityCase {
        name: "solid_rigid_many_iterations",
        what: "alpha = 1 with 50 cluster iterations a step: a rigid jelly dropped on the floor",
        preset: "elastic_drop",
        spacing: (0.04, 0.02),
        overrides: &["solid.stiffness=1", "solid.iterations=50"],
        until: (0.4, 1.0),
        expect: Expect::FinishOrHalt,
    },
    StabilityCase {
        name: "solid_small_clusters",
        what: "clusters of a particle and its 6 face neighbours (radius 1 spacing), alpha = 1",
        preset: "elastic_drop",
        spacing: (0.04, 0.02),
        overrides: &["solid.cluster_radius=1", "solid.stiffness=1"],
        until: (0.4, 1.0),
        expect: Expect::FinishOrHalt,
    },
    StabilityCase {
        name: "solid_impact_20",
        what: "the jelly thrown at the floor at 20 m/s",
        preset: "elastic_drop",
        spacing: (0.04, 0.02),
        overrides: &["fluids[0].blocks[0].velocity=[0,-20,0]", "solver.expected_max_speed=20"],
        until: (0.1, 0.3),
        expect: Expect::FinishOrHalt,
    },
    StabilityCase {
        name: "solid_rod_clusters_2_3",
        what: "a rod one particle thick (at 2 cm) with clusters of radius 1 spacing: 2 or 3 members each, alpha = 1, falling on the floor",
        preset: "elastic_drop",
        spacing: (0.02, 0.01),
        overrides: &[
            "solid.stiffness=1",
            "solid.cluster_radius=1",
            r#"fluids[0].blocks=[{"min":[0.1,0.4,0.29],"max":[0.5,0.42,0.31]}]"#,
        ],
        until: (0.4, 1.0),
        expect: Expect::FinishOrHalt,
    },
    StabilityCase {
        name: "solid_stack_5",
        what: "five elastic cubes 8 cm wide, 4 cm apart, falling onto each other into a stack, alpha = 1",
        preset: "elastic_drop",
        spacing: (0.02, 0.01),
        overrides: &[
            "solid.stiffness=1",
            "fluids[0].blocks=[{\"min\":[0.26,0.02,0.26],\"max\":[0.34,0.1,0.34]},{\"min\":[0.26,0.14,0.26],\"max\":[0.34,0.22,0.34]},{\"min\":[0.26,0.26,0.26],\"max\":[0.34,0.34,0.34]},{\"min\":[0.26,0.38,0.26],\"max\":[0.34,0.46,0.34]},{\"min\":[0.26,0.5,0.26],\"max\":[0.34,0.58,0.34]}]",
        ],
        until: (0.5, 1.5),
        expect: Expect::FinishOrHalt,
    },
    StabilityCase {
        name: "solid_bunny_thrown_5",
        what: "the bunny thrown at the floor at 5 m/s, alpha = 1: its ears one or two lattice layers thick, clusters of 3 to 5 members at their tips",
        preset: "bunny",
        spacing: (0.0196, 0.0146),
        overrides: &["fluids[0].blocks[0].velocity=[0,-5,0]", "solver.expected_max_speed=5", "solid.stiffness=1"],
        until: (0.2, 0.5),
        expect: Expect::FinishOrHalt,
    },
    StabilityCase {
        name: "solid_heavy_into_water_10",
        what: "the 2000 kg/m^3 block of floating_blocks thrown into the water at 10 m/s",
        preset: "floating_blocks",
        spacing: (0.04, 0.02),
        overrides: &["fluids[2].blocks[0].velocity=[0,-10,0]", "solver.expected_max_speed=10"],
        until: (0.2, 0.5),
        expect: Expect::FinishOrHalt,
    },
    // Ice that melts, on `ice_cube_in_glass` at 1 cm (864 particles; 2,800 at
    // 7.5 mm in `--full`).
    StabilityCase {
        name: "ice_into_water_100k",
        what: "the ice cube dropped into water 100 K above the melting point",
        preset: "ice_cube_in_glass",
        spacing: (0.01, 0.0075),
        overrides: &["heat.fluids[0].temperature=373.15"],
        until: (0.3, 1.0),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "ice_into_water_1000k",
        what: "the ice cube dropped into water 1000 K above the melting point",
        preset: "ice_cube_in_glass",
        spacing: (0.01, 0.0075),
        overrides: &["heat.fluids[0].temperature=1273.15"],
        until: (0.3, 1.0),
        expect: Expect::FinishOrHalt,
    },
    StabilityCase {
        name: "ice_instant_melting",
        what: "ice at its melting point with a latent heat of 1 J/kg: it melts in the step it touches the water",
        preset: "ice_cube_in_glass",
        spacing: (0.01, 0.0075),
        overrides: &["heat.fluids[1].temperature=273.15", "heat.fluids[1].melting.latent_heat=1"],
        until: (0.3, 1.0),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "ice_refreezing",
        what: "the cube 4 K above its melting point, without gravity, under a heat sink of 1e9 W/m^3: it melts in its first step, freezes again where it is by 0.35 s and its members rejoin their clusters",
        preset: "ice_cube_in_glass",
        spacing: (0.01, 0.0075),
        overrides: &[
            "gravity=[0,0,0]",
            "heat.fluids[1].temperature=277.15",
            r#"heat.sources=[{"min":[0.02,0.09,0.02],"max":[0.08,0.15,0.08],"power":-1e9}]"#,
        ],
        until: (0.35, 0.6),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "ice_denser_than_water",
        what: "ice of 1100 kg/m^3 sinks to the floor of the glass as it melts",
        preset: "ice_cube_in_glass",
        spacing: (0.01, 0.0075),
        overrides: &["fluids[1].rest_density=1100", "heat.fluids[0].temperature=320"],
        until: (0.3, 1.0),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "ice_on_heated_wall",
        what: "the ice cube dropped on the empty glass's floor held at 373 K: it melts where it touches",
        preset: "ice_cube_in_glass",
        spacing: (0.01, 0.0075),
        overrides: &["fluids[0].blocks=[]", r#"heat.walls=[{"min":[-1,-1,-1],"max":[1,0,1],"temperature":373.15}]"#],
        until: (0.3, 1.0),
        expect: Expect::Finish,
    },
];
