//! cargo fuzz target: floe_server::fuzz::Target::Rest (see docs/fuzzing.md).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| floe_server::fuzz::Target::Rest.run(data));
