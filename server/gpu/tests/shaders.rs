//! Every WGSL kernel parses and validates with naga, without any GPU: a
//! shader error fails plain `cargo test` on any machine.

use floe_gpu::passes::SOURCES;

#[test]
fn every_shader_validates_with_naga() {
    assert!(SOURCES.len() >= 8);
    for (name, source) in SOURCES {
        let module = naga::front::wgsl::parse_str(source)
            .unwrap_or_else(|e| panic!("{name}.wgsl: {}", e.emit_to_string(source)));
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::default())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}.wgsl: {}", e.emit_to_string(source)));
        assert!(!module.entry_points.is_empty(), "{name}.wgsl has no entry point");
    }
}
