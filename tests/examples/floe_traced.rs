//! `floe` with the tests' tracer module compiled in (`tests/tests/tracer/`): a module
//! added from outside the engine's crates, registered before the command runs, so
//! the Python client's and the viewer's tests can stream its sets and grid from a
//! real server (`cargo build -p floe-tests --example floe_traced`).

#[path = "../tests/tracer/mod.rs"]
mod tracer;

fn main() -> std::process::ExitCode {
    floe_engine::module::register(&tracer::MODULE);
    floe_gpu::pass::register(&tracer::gpu::MODULE);
    floe_server::entry::main()
}
