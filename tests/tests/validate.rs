//! `floe validate`: every stated bound holds (`--bounds`, the stability battery
//! included), and a quick report holds every run of the cases it was asked for,
//! with its plots. The whole quick report, every case at every quick spacing, is
//! `floe validate --quick` (docs/validation/).

use clap::Parser;
use floe_server::cli::Cli;

/// Every stated bound, each at the spacing its case checks it at, and the stability
/// battery: `floe validate --bounds`, two runs at once.
#[test]
fn every_stated_bound_holds() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let cli = Cli::try_parse_from(["floe", "validate", "--bounds", "--jobs", "2", "--out", out]).unwrap();
    let result = floe_server::execute(cli);
    let report = std::fs::read_to_string(dir.path().join("report.md")).expect("report.md written");
    result.unwrap_or_else(|e| panic!("{e:#}\n\n{report}"));
    assert!(report.contains("**All stated bounds met.**"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("report.json")).unwrap()).unwrap();
    // One run per case with quick spacings, at its checked spacing, of its first variant.
    let cases: Vec<_> = floe_engine::validation::cases::all().into_iter().filter(|c| c.checked_at.is_some()).collect();
    let runs = json["runs"].as_array().unwrap();
    assert_eq!(runs.len(), cases.len());
    for (run, case) in runs.iter().zip(&cases) {
        assert_eq!(run["case"], case.name);
        assert_eq!(run["variant"], case.default_variant());
        assert_eq!(run["spacing"].as_f64(), case.checked_at);
    }
    assert_eq!(json["stability"].as_array().unwrap().len(), floe_engine::validation::stability::all().len());
}

/// A quick report of two cases: every variant at every quick spacing, and plots of
/// error against run time and of convergence, with lines.
#[test]
fn a_quick_report_has_every_run_and_its_plots() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let args =
        ["floe", "validate", "--quick", "--case", "dam_break", "--case", "conduction", "--jobs", "2", "--out", out];
    floe_server::execute(Cli::try_parse_from(args).unwrap()).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("report.json")).unwrap()).unwrap();
    let chosen: Vec<_> = floe_engine::validation::cases::all()
        .into_iter()
        .filter(|c| c.name == "dam_break" || c.name == "conduction")
        .collect();
    let runs: usize = chosen.iter().map(|c| c.variants.len() * c.spacings(false).len()).sum();
    assert_eq!(json["runs"].as_array().unwrap().len(), runs);
    assert!(json["stability"].as_array().unwrap().is_empty());
    for case in ["dam_break", "conduction"] {
        for plot in ["work_precision", "convergence"] {
            let svg = std::fs::read_to_string(dir.path().join(format!("{case}_{plot}.svg"))).unwrap();
            assert!(svg.starts_with("<svg") && svg.contains("<polyline"), "{case}_{plot}.svg has no lines");
        }
    }
}

/// `--set` changes every accuracy run before its variant's own overrides: the
/// conduction case on DFSPH reports DFSPH's solves; a variant that sets the scheme
/// itself keeps it.
#[test]
fn set_overrides_every_run_before_its_variant() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let args =
        ["floe", "validate", "--bounds", "--case", "conduction", "--set", "solver.method=\"dfsph\"", "--out", out];
    floe_server::execute(Cli::try_parse_from(args).unwrap()).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("report.json")).unwrap()).unwrap();
    let runs = json["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 1);
    assert!(runs[0]["solves"].get("dfsph.density").is_some(), "{}", runs[0]);
    let conduction = floe_engine::validation::cases::all().into_iter().find(|c| c.name == "conduction").unwrap();
    let wcsph = floe_engine::validation::cases::Variant { name: "wcsph", overrides: &["solver.method=\"wcsph\""] };
    let extra = ["solver.method=\"dfsph\"".to_string()];
    let run =
        floe_engine::validation::cases::run(conduction, 0.002, &wcsph, &extra, &floe_engine::simulation::cpu_backend)
            .unwrap();
    assert!(run.solves.is_empty(), "the variant's scheme, WCSPH, has no solves: {:?}", run.solves);
    // An extra spacing replaces the ladder's, in the scene and in the report.
    let extra = ["particle_spacing=0.0016".to_string()];
    let run =
        floe_engine::validation::cases::run(conduction, 0.002, &wcsph, &extra, &floe_engine::simulation::cpu_backend)
            .unwrap();
    let ladder =
        floe_engine::validation::cases::run(conduction, 0.002, &wcsph, &[], &floe_engine::simulation::cpu_backend)
            .unwrap();
    assert_eq!(run.spacing, 0.0016, "the run is reported at the spacing it ran at");
    assert!(
        run.particles > ladder.particles,
        "{} particles at 0.0016 m, {} at 0.002 m",
        run.particles,
        ladder.particles
    );
}

#[test]
fn unknown_cases_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let cli =
        Cli::try_parse_from(["floe", "validate", "--case", "lid_driven_cavity", "--out", dir.path().to_str().unwrap()])
            .unwrap();
    let err = floe_server::execute(cli).unwrap_err();
    assert!(
        format!("{err}").starts_with(
            "unknown case 'lid_driven_cavity'; cases are: hydrostatic, dam_break, poiseuille, taylor_green, \
             conduction, stefan, layers_at_rest, layers_at_rest_ratio_100, heated_cavity, heated_cavity_ra1e5, heated_channel, \
             power_law_channel, bingham_channel, cross_channel, snowfall_open, snowfall_shelter, snowfall_coverage, \
             snowfall_release, solid_rest, solid_rigid, solid_drop, solid_solvers, solid_weighting, solid_orientation, \
             ice_insulated, solid_stiffness, stability"
        ),
        "{err}"
    );
}
