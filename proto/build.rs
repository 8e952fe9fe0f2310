//! Generates the gRPC types of `floe/v1/scenes.proto` and the file descriptor
//! set the server registers for reflection. `protoc` comes from the
//! protoc-bin-vendored crate (a system protoc is not needed), or from `PROTOC`.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::path::PathBuf::from(std::env::var("OUT_DIR")?);
    let protoc = match std::env::var_os("PROTOC") {
        Some(p) => p.into(),
        None => protoc_bin_vendored::protoc_bin_path()?,
    };
    let mut config = prost_build::Config::new();
    config.protoc_executable(protoc);
    tonic_prost_build::configure()
        .build_transport(false)
        .file_descriptor_set_path(out.join("floe_v1_descriptor.bin"))
        .compile_with_config(config, &["floe/v1/scenes.proto"], &["."])?;
    println!("cargo:rerun-if-changed=floe/v1/scenes.proto");
    println!("cargo:rerun-if-env-changed=PROTOC");
    Ok(())
}
