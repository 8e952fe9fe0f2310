//! A backend that fails unexpectedly (a bug, a lost GPU) halts its own scene
//! with the reason; the scene still answers and the server's other scenes go on.

use floe_engine::attrs::{Allocation, Column};
use floe_engine::backend::Backend;
use floe_engine::cpu::CpuBackend;
use floe_engine::guard::Measures;
use floe_engine::model::Model;
use floe_engine::plan::Stage;
use floe_engine::scheme::{Reduction, Stages};
use floe_engine::simulation::BackendFactory;
use floe_server::auth::Caller;
use floe_server::service::{CommandError, State};
use floe_server::service::{Registry, SceneSource};
use std::sync::Arc;

/// The CPU backend, except that it panics in its 5th evaluation when it holds
/// exactly `FAULTY_PARTICLES` particles.
struct Faulty(CpuBackend, u32);

const FAULTY_PARTICLES: usize = 1000;

impl Stages for Faulty {
    fn model(&self) -> &Model {
        self.0.model()
    }
    fn run(&mut self, stage: Stage, dt: f32) {
        self.0.run(stage, dt)
    }
    fn run_pass(&mut self, name: &str, dt: f32) {
        self.0.run_pass(name, dt)
    }
    fn measure(&mut self) -> Result<Measures, String> {
        self.1 += 1;
        if self.0.particle_count() == FAULTY_PARTICLES && self.1 == 5 {
            panic!("simulated driver failure");
        }
        self.0.measure()
    }
    fn reduce(&mut self, r: &Reduction) -> Result<f64, String> {
        self.0.reduce(r)
    }
    fn sum_into(&mut self, attr: &'static str, into: &'static str, slot: u32) {
        self.0.sum_into(attr, into, slot)
    }
    fn kick(&mut self, dt: f32, keep: f32) {
        self.0.kick(dt, keep)
    }
    fn drift(&mut self, dt: f32) {
        self.0.drift(dt)
    }
    fn sweep(&mut self, k: u32) {
        self.0.sweep(k)
    }
    fn particle_id(&mut self, slot: u32) -> u32 {
        self.0.particle_id(slot)
    }
    fn first_outside(&mut self, attr: &str, min: f32, max: f32) -> Option<(u32, f32)> {
        self.0.first_outside(attr, min, max)
    }
}

impl Backend for Faulty {
    fn name(&self) -> &'static str {
        "faulty"
    }
    fn download(&self, names: &[&str]) -> Vec<Column> {
        self.0.download(names)
    }
    fn upload(&mut self, name: &str, column: Column) {
        self.0.upload(name, column)
    }
    fn restored(&mut self) {
        self.0.restored()
    }
    fn retuned(&mut self) {
        self.0.retuned()
    }
    fn model_mut(&mut self) -> &mut Model {
        self.0.model_mut()
    }
    fn allocations(&self) -> Vec<Allocation> {
        self.0.allocations()
    }
    fn passes_run(&self) -> Vec<&'static str> {
        self.0.passes_run()
    }
    fn compact(&mut self) {
        self.0.compact()
    }
    fn emit(&mut self, births: &floe_engine::population::Births, first_id: u32) {
        self.0.emit(births, first_id)
    }
    fn set_particle_count(&mut self, n: usize) {
        self.0.set_particle_count(n)
    }
}

#[tokio::test]
async fn a_panicking_backend_halts_its_scene_and_the_others_go_on() {
    let factory: Arc<BackendFactory> =
        Arc::new(|model| Ok(Box::new(Faulty(CpuBackend::new(model), 0)) as Box<dyn Backend>));
    let registry = Registry::new(Default::default(), factory);
    let preset = || SceneSource::Preset("dam_break".into());
    let local = Caller::local();
    let faulty = registry.create(&local, preset(), vec!["particle_spacing=0.05".into()]).await.unwrap();
    let healthy = registry.create(&local, preset(), vec!["particle_spacing=0.1".into()]).await.unwrap();
    assert_eq!(faulty.shared.particles, FAULTY_PARTICLES);
    assert_ne!(healthy.shared.particles, FAULTY_PARTICLES);

    let status = faulty.step(20, None).await.unwrap();
    assert_eq!(status.state, State::Halted);
    assert_eq!(status.steps, 4);
    let reason = status.halt_reason.unwrap();
    assert!(reason.contains("internal error in the faulty backend: simulated driver failure"), "{reason}");
    // The scene still answers: stepping is refused with the reason, a snapshot still works.
    assert!(
        matches!(faulty.step(1, None).await, Err(CommandError::Halted(r)) if r.contains("simulated driver failure"))
    );
    assert!(!faulty.save().await.unwrap().is_empty());

    let status = healthy.step(20, None).await.unwrap();
    assert_eq!((status.state, status.steps), (State::Paused, 20));
    registry.shutdown().await;
}
