//! Generates the gRPC types of `floe/v1/scenes.proto` (needs `protoc`: Debian's
//! protobuf-compiler, installed by `.ci/run`) and the file descriptor set the
//! server registers for reflection.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::path::PathBuf::from(std::env::var("OUT_DIR")?);
    tonic_prost_build::configure()
        .build_transport(false)
        .file_descriptor_set_path(out.join("floe_v1_descriptor.bin"))
        .compile_protos(&["floe/v1/scenes.proto"], &["."])?;
    println!("cargo:rerun-if-changed=floe/v1/scenes.proto");
    Ok(())
}
