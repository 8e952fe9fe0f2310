//! cargo fuzz target: floe_server::fuzz::Target::Scene (see docs/fuzzing.md).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| floe_server::fuzz::Target::Scene.run(data));
