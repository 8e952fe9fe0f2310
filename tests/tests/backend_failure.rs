//! A backend that fails unexpectedly (a bug, a lost GPU) halts its own scene
//! with the reason; the scene still answers and the server's other scenes go on.

use floe_engine::backend::{Backend, Channel, Particles};
use floe_engine::cpu::CpuBackend;
use floe_engine::guard::Measures;
use floe_engine::model::Model;
use floe_engine::scene::Scene;
use floe_engine::simulation::BackendFactory;
use floe_engine::stepping::{Clock, Passes, SortedState};
use floe_server::auth::Caller;
use floe_server::service::{CommandError, State};
use floe_server::service::{Registry, SceneSource};
use std::sync::Arc;

/// The CPU backend, except that it panics in its 5th evaluation when it holds
/// exactly `FAULTY_PARTICLES` particles.
struct Faulty(CpuBackend);

const FAULTY_PARTICLES: usize = 1000;

impl Passes for Faulty {
    fn model(&self) -> &Model {
        self.0.model()
    }
    fn evaluate(&mut self) -> Result<Measures, String> {
        if self.0.particle_count() == FAULTY_PARTICLES && self.0.clock().steps() == 4 {
            panic!("simulated driver failure");
        }
        self.0.evaluate()
    }
    fn kick(&mut self, dt: f32, keep: f32, with_xsph: bool) {
        self.0.kick(dt, keep, with_xsph)
    }
    fn drift(&mut self, dt: f32) {
        self.0.drift(dt)
    }
    fn particle_id(&mut self, slot: u32) -> u32 {
        self.0.particle_id(slot)
    }
}

impl Backend for Faulty {
    fn name(&self) -> &'static str {
        "faulty"
    }
    fn clock(&self) -> &Clock {
        self.0.clock()
    }
    fn clock_mut(&mut self) -> &mut Clock {
        self.0.clock_mut()
    }
    fn particle_count(&self) -> usize {
        self.0.particle_count()
    }
    fn sorted_state(&self) -> SortedState {
        self.0.sorted_state()
    }
    fn restore_state(&mut self, state: SortedState) {
        self.0.restore_state(state)
    }
    fn read(&self, channels: &[Channel]) -> Particles {
        self.0.read(channels)
    }
    fn retune(&mut self, scene: &Scene) {
        self.0.retune(scene)
    }
}

#[tokio::test]
async fn a_panicking_backend_halts_its_scene_and_the_others_go_on() {
    let factory: Arc<BackendFactory> =
        Arc::new(|model| Ok(Box::new(Faulty(CpuBackend::new(model))) as Box<dyn Backend>));
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
