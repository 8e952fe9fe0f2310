//! The cluster's figures in `/metrics`, the same from every worker: per worker (label
//! `worker`), its scenes, running scenes, particles, open frame streams and
//! particle-steps per second, as each worker published them with its last
//! heartbeat, and whether it drains. Summed over `worker`, the cluster's totals.
//! A single server has no cluster series.

use super::SceneSample;
use prometheus_client::collector::Collector;
use prometheus_client::encoding::{DescriptorEncoder, EncodeMetric};
use prometheus_client::metrics::MetricType;
use prometheus_client::metrics::gauge::ConstGauge;
use std::sync::RwLock;

/// A cluster worker and its scenes' figures as of its last heartbeat.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct WorkerSample {
    /// Worker name.
    pub name: String,
    /// Taking no new scenes, handing its own to others.
    pub draining: bool,
    /// Its `--max-particles`.
    pub max_particles: u64,
    /// Its scenes.
    pub scenes: Vec<SceneSample>,
}

impl WorkerSample {
    /// Particle-steps per second over its running scenes.
    pub fn particle_steps_per_second(&self) -> f64 {
        self.scenes.iter().filter(|s| s.running).fold(0.0, |sum, s| sum + s.steps_per_second * s.particles as f64)
    }
}

/// The cluster's workers as of the last cluster tick; empty on a single server.
#[derive(Debug, Default)]
pub struct ClusterSamples(RwLock<Vec<WorkerSample>>);

impl ClusterSamples {
    /// Replaces the workers' figures (each cluster tick).
    pub fn set(&self, workers: Vec<WorkerSample>) {
        *self.0.write().expect("lock") = workers;
    }

    /// The workers' figures.
    pub fn get(&self) -> Vec<WorkerSample> {
        self.0.read().expect("lock").clone()
    }
}

/// Reads [`ClusterSamples`] when scraped.
#[derive(Debug)]
pub(super) struct ClusterCollector(pub(super) std::sync::Arc<ClusterSamples>);

/// A per-worker series: name, help, and its value.
type Series<T> = (&'static str, &'static str, fn(&WorkerSample) -> T);

impl Collector for ClusterCollector {
    fn encode(&self, mut encoder: DescriptorEncoder) -> Result<(), std::fmt::Error> {
        let workers = self.0.get();
        if workers.is_empty() {
            return Ok(());
        }
        let counts: [Series<i64>; 6] = [
            ("cluster_worker_draining", "1 while the worker drains (takes no new scenes)", |w| i64::from(w.draining)),
            (
                "cluster_worker_max_particles",
                "The worker's particle budget over all its scenes (--max-particles)",
                |w| count(w.max_particles),
            ),
            ("cluster_scenes", "Scenes the worker holds", |w| count(w.scenes.len() as u64)),
            ("cluster_running_scenes", "Scenes the worker runs continuously", |w| {
                count(w.scenes.iter().filter(|s| s.running).count() as u64)
            }),
            ("cluster_particles", "Particles over the worker's scenes", |w| {
                count(w.scenes.iter().map(|s| s.particles).sum())
            }),
            ("cluster_subscribers", "Open frame streams on the worker", |w| {
                count(w.scenes.iter().map(|s| s.subscribers).sum())
            }),
        ];
        for (name, help, value) in counts {
            let mut m = encoder.encode_descriptor(name, help, None, MetricType::Gauge)?;
            for w in &workers {
                ConstGauge::new(value(w)).encode(m.encode_family(&[("worker", w.name.clone())])?)?;
            }
        }
        let mut m = encoder.encode_descriptor(
            "cluster_particle_steps_per_second",
            "Particle-steps per wall second over the worker's running scenes",
            None,
            MetricType::Gauge,
        )?;
        for w in &workers {
            ConstGauge::new(w.particle_steps_per_second()).encode(m.encode_family(&[("worker", w.name.clone())])?)?;
        }
        Ok(())
    }
}

fn count(n: u64) -> i64 {
    i64::try_from(n).unwrap_or(i64::MAX)
}
