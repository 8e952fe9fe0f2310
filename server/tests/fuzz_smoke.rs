//! Every fuzz target survives a short run of its seeds and mutations (the long runs and
//! their counts are in docs/fuzzing.md): keeps the targets and seeds working.

use floe_server::fuzz::{Target, fuzz};

#[test]
fn every_target_survives_a_short_run() {
    for target in Target::ALL {
        let outcome = fuzz(target, 3000, 7, 2, None);
        assert_eq!(outcome.inputs, 3000, "{target:?}");
        assert_eq!(outcome.panics, 0, "{target:?} panicked");
    }
}
