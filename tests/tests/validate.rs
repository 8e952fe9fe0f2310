//! `floe validate --quick`: every supported case and the stability battery run,
//! their stated bounds hold, and the report is written.

use clap::Parser;
use floe_server::cli::Cli;

#[test]
fn quick_validation_meets_every_stated_bound() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let cli = Cli::try_parse_from(["floe", "validate", "--quick", "--out", out]).unwrap();
    let result = floe_server::execute(cli);
    let report = std::fs::read_to_string(dir.path().join("report.md")).expect("report.md written");
    result.unwrap_or_else(|e| panic!("{e:#}\n\n{report}"));
    assert!(report.contains("**All stated bounds met.**"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("report.json")).unwrap()).unwrap();
    // Every case's variants at each of its quick resolutions, and every battery case.
    let runs: usize =
        floe_engine::validation::cases::all().iter().map(|c| c.variants.len() * c.spacings(false).len()).sum();
    assert_eq!(json["runs"].as_array().unwrap().len(), runs);
    assert_eq!(json["stability"].as_array().unwrap().len(), floe_engine::validation::stability::all().len());
    for case in ["hydrostatic", "dam_break", "poiseuille", "bingham_channel"] {
        for plot in ["work_precision", "convergence"] {
            let svg = std::fs::read_to_string(dir.path().join(format!("{case}_{plot}.svg"))).unwrap();
            assert!(svg.starts_with("<svg") && svg.contains("<polyline"), "{case}_{plot}.svg has no lines");
        }
    }
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
             conduction, layers_at_rest, layers_at_rest_ratio_100, heated_cavity, heated_cavity_ra1e5, heated_channel, \
             power_law_channel, bingham_channel, cross_channel, stability"
        ),
        "{err}"
    );
}
