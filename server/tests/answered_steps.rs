//! No answered step is lost to a crash. The real `floe serve` is killed with SIGKILL
//! [`KILLS`] times, each at a random moment while a client steps a paused dam break
//! one step per call and records every step count it was answered; after each
//! restart the scene is at or after the last answered step, and one step on from there
//! its state is, bit for bit, the scene's first snapshot stepped as many times in this
//! process (a snapshot also holds what the last step computed on the way, which a
//! restored scene recomputes in its first step). The moments come from a seed,
//! printed, and `FLOE_TEST_SEED` repeats a run.

use floe_client::Client;
use floe_engine::Simulation;
use floe_server::lab_bench::process::{Data, ServerProcess};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// Crashes per run.
const KILLS: usize = 50;

fn start(data: &Data, log: PathBuf) -> ServerProcess {
    let floe = Path::new(env!("CARGO_BIN_EXE_floe"));
    ServerProcess::start(floe, data, &["--scene", "none", "--backend", "cpu"], log).unwrap()
}

/// The next of a xorshift sequence.
fn next(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

#[tokio::test(flavor = "multi_thread")]
async fn kill_9_at_random_moments_loses_no_answered_step() {
    let seed = std::env::var("FLOE_TEST_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or_else(|| {
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap().as_nanos() as u64 | 1
    });
    eprintln!("seed {seed}: FLOE_TEST_SEED={seed} repeats these moments");
    let mut rng = seed;
    let dir = tempfile::tempdir().unwrap();
    let data = Data { dir: dir.path().join("data"), database: None };
    let mut server = start(&data, dir.path().join("server-0.log"));
    let mut c = Client::connect(&server.grpc).await.unwrap();
    let id = c.create_preset("dam_break", &["particle_spacing=0.05"]).await.unwrap().scene_id;
    let mut reference = Simulation::restore(&c.snapshot(id).await.unwrap()).unwrap();
    for kill in 0..KILLS {
        let answered = Arc::new(AtomicU64::new(reference.steps()));
        let stepper = {
            let (mut c, answered) = (c.clone(), answered.clone());
            tokio::spawn(async move {
                while let Ok(info) = c.step(id, 1).await {
                    answered.store(info.steps, Ordering::SeqCst);
                }
            })
        };
        tokio::time::sleep(Duration::from_millis(20 + next(&mut rng) % 400)).await;
        server.kill().unwrap();
        tokio::time::timeout(Duration::from_secs(10), stepper).await.expect("a step call outlived its server").unwrap();
        let last = answered.load(Ordering::SeqCst);

        server = start(&data, dir.path().join(format!("server-{}.log", kill + 1)));
        c = Client::connect(&server.grpc).await.unwrap();
        let at = c.get(id).await.unwrap().steps;
        assert!(at >= last, "seed {seed}, crash {kill}: back at step {at}, but step {last} was answered");
        let on = c.step(id, 1).await.unwrap().steps;
        while reference.steps() < on {
            reference.step().unwrap();
        }
        assert!(
            c.snapshot(id).await.unwrap() == reference.snapshot(),
            "seed {seed}, crash {kill}: one step on from step {at}, the state differs from the replay"
        );
    }
    assert!(reference.steps() > KILLS as u64, "the script stepped: {} steps", reference.steps());
    assert!(server.terminate().unwrap(), "floe serve exited with an error");
}
