//! Prometheus metrics (`GET /metrics`, Prometheus text format 0.0.4), with the
//! prometheus-client crate: one registry per server, no global state, so tests can
//! run servers side by side.
//!
//! Per scene, read when scraped (labels `scene`, `owner`, `name`): steps, steps/s,
//! particles, simulated time, subscribers, frames published, frame bytes sent,
//! dropped frames, and backend time per pass (`pass` label). Per call: requests by
//! transport, method and code, and latency. Quota refusals by quota. Checkpoints
//! by outcome, and the time they take. In a cluster, every worker's totals
//! ([`cluster`]).

mod cluster;

pub use cluster::{ClusterSamples, WorkerSample};

use prometheus_client::collector::Collector;
use prometheus_client::encoding::{DescriptorEncoder, EncodeLabelSet, EncodeMetric};
use prometheus_client::metrics::MetricType;
use prometheus_client::metrics::counter::{ConstCounter, Counter};
use prometheus_client::metrics::family::Family;
use prometheus_client::metrics::gauge::ConstGauge;
use prometheus_client::metrics::histogram::{Histogram, exponential_buckets};
use std::sync::Arc;

/// One scene's figures at scrape time (and, in a cluster, as each worker publishes
/// its scenes' with its heartbeat).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SceneSample {
    /// Scene id.
    pub id: u64,
    /// Owner.
    pub owner: String,
    /// Scene name.
    pub name: String,
    /// Steps taken.
    pub steps: u64,
    /// Steps per wall second over the last second of stepping.
    pub steps_per_second: f64,
    /// Fluid particles.
    pub particles: u64,
    /// Simulated time (s).
    pub sim_time: f64,
    /// Open frame streams.
    pub subscribers: u64,
    /// States published for frame subscribers.
    pub frames_published: u64,
    /// Encoded frame bytes sent to subscribers.
    pub frame_bytes: u64,
    /// Frames subscribers skipped.
    pub dropped_frames: u64,
    /// Whether it is running.
    pub running: bool,
    /// Backend time per pass: label, seconds, calls (not published to the cluster).
    #[serde(skip)]
    pub passes: Vec<(&'static str, f64, u64)>,
}

/// Where the scene figures come from (the service's scenes).
pub trait SceneSamples: std::fmt::Debug + Send + Sync + 'static {
    /// Every scene's figures now.
    fn samples(&self) -> Vec<SceneSample>;
}

#[derive(Debug, Clone, Hash, PartialEq, Eq, EncodeLabelSet)]
struct Call {
    transport: &'static str,
    method: String,
    code: String,
}

#[derive(Debug, Clone, Hash, PartialEq, Eq, EncodeLabelSet)]
struct Route {
    transport: &'static str,
    method: String,
}

#[derive(Debug, Clone, Hash, PartialEq, Eq, EncodeLabelSet)]
struct Quota {
    quota: &'static str,
}

#[derive(Debug, Clone, Hash, PartialEq, Eq, EncodeLabelSet)]
struct Outcome {
    outcome: &'static str,
}

fn latency_histogram() -> Histogram {
    // 0.1 ms to ~3 s.
    Histogram::new(exponential_buckets(1e-4, 2.0, 16))
}

fn checkpoint_histogram() -> Histogram {
    // 1 ms to ~30 s.
    Histogram::new(exponential_buckets(1e-3, 2.0, 16))
}

/// The server's metrics.
#[derive(Debug)]
pub struct Metrics {
    registry: prometheus_client::registry::Registry,
    calls: Family<Call, Counter>,
    latency: Family<Route, Histogram, fn() -> Histogram>,
    quota_refusals: Family<Quota, Counter>,
    checkpoints: Family<Outcome, Counter>,
    checkpoint_seconds: Histogram,
    cluster: Arc<ClusterSamples>,
}

impl Metrics {
    /// Metrics of a server whose scenes `scenes` reports.
    pub fn new(scenes: Arc<dyn SceneSamples>) -> Self {
        let mut registry = prometheus_client::registry::Registry::with_prefix("floe");
        let calls = Family::<Call, Counter>::default();
        let latency = Family::<Route, Histogram, fn() -> Histogram>::new_with_constructor(latency_histogram);
        let quota_refusals = Family::<Quota, Counter>::default();
        let checkpoints = Family::<Outcome, Counter>::default();
        let checkpoint_seconds = checkpoint_histogram();
        registry.register("requests", "Calls by transport (grpc, http, ws), method and result code", calls.clone());
        registry.register("request_duration_seconds", "Time to answer a call", latency.clone());
        registry.register("quota_refusals", "Requests refused by a quota, by quota", quota_refusals.clone());
        registry.register("checkpoints", "Checkpoints written (ok) or failed (error)", checkpoints.clone());
        registry.register(
            "checkpoint_duration_seconds",
            "Time to take and write a checkpoint",
            checkpoint_seconds.clone(),
        );
        registry.register_collector(Box::new(SceneCollector(scenes)));
        let cluster = Arc::new(ClusterSamples::default());
        registry.register_collector(Box::new(cluster::ClusterCollector(cluster.clone())));
        Self { registry, calls, latency, quota_refusals, checkpoints, checkpoint_seconds, cluster }
    }

    /// The cluster's workers, as shown (set at each cluster tick).
    pub fn cluster(&self) -> &ClusterSamples {
        &self.cluster
    }

    /// Records one call: `transport` (grpc, http, ws), its method or route, its result
    /// code, and how long it took.
    pub fn observe(&self, transport: &'static str, method: &str, code: &str, seconds: f64) {
        self.calls.get_or_create(&Call { transport, method: method.into(), code: code.into() }).inc();
        self.latency.get_or_create(&Route { transport, method: method.into() }).observe(seconds);
    }

    /// Records a request refused by `quota`.
    pub fn quota_refused(&self, quota: &'static str) {
        self.quota_refusals.get_or_create(&Quota { quota }).inc();
    }

    /// Records a checkpoint and how long it took.
    pub fn checkpointed(&self, ok: bool, seconds: f64) {
        self.checkpoints.get_or_create(&Outcome { outcome: if ok { "ok" } else { "error" } }).inc();
        if ok {
            self.checkpoint_seconds.observe(seconds);
        }
    }

    /// Everything, in Prometheus text format.
    pub fn render(&self) -> String {
        let mut out = String::new();
        prometheus_client::encoding::prometheus_text::encode(&mut out, &self.registry)
            .expect("writing to a String cannot fail");
        out
    }
}

/// Reads the scenes' figures when scraped.
#[derive(Debug)]
struct SceneCollector(Arc<dyn SceneSamples>);

/// Labels of a scene's series.
type SceneLabels = [(&'static str, String); 3];

/// A per-scene series: name, help, and its value in a sample.
type Series<T> = (&'static str, &'static str, fn(&SceneSample) -> T);

fn labels(s: &SceneSample) -> SceneLabels {
    [("scene", s.id.to_string()), ("owner", s.owner.clone()), ("name", s.name.clone())]
}

impl Collector for SceneCollector {
    fn encode(&self, mut encoder: DescriptorEncoder) -> Result<(), std::fmt::Error> {
        let samples = self.0.samples();
        let gauges: [Series<f64>; 5] = [
            ("scene_steps_per_second", "Steps per wall second over the last second of stepping", |s| {
                s.steps_per_second
            }),
            ("scene_particles", "Fluid particles", |s| s.particles as f64),
            ("scene_sim_time_seconds", "Simulated time", |s| s.sim_time),
            ("scene_subscribers", "Open frame streams", |s| s.subscribers as f64),
            ("scene_running", "1 while the scene runs continuously", |s| f64::from(u8::from(s.running))),
        ];
        for (name, help, value) in gauges {
            let mut m = encoder.encode_descriptor(name, help, None, MetricType::Gauge)?;
            for s in &samples {
                let l = labels(s);
                ConstGauge::new(value(s)).encode(m.encode_family(&l)?)?;
            }
        }
        let counters: [Series<u64>; 4] = [
            ("scene_steps", "Steps taken", |s| s.steps),
            ("scene_frames_published", "Particle states published for frame subscribers", |s| s.frames_published),
            ("scene_frame_bytes", "Encoded frame bytes sent to subscribers", |s| s.frame_bytes),
            ("scene_dropped_frames", "Frames subscribers skipped (slow readers)", |s| s.dropped_frames),
        ];
        for (name, help, value) in counters {
            let mut m = encoder.encode_descriptor(name, help, None, MetricType::Counter)?;
            for s in &samples {
                let l = labels(s);
                ConstCounter::new(value(s)).encode(m.encode_family(&l)?)?;
            }
        }
        let mut m = encoder.encode_descriptor(
            "scene_backend_seconds",
            "Backend time per pass of the step sequence (wall time on the CPU, device time on a profiling GPU)",
            None,
            MetricType::Counter,
        )?;
        for s in &samples {
            let [scene, owner, name] = labels(s);
            for &(pass, seconds, _) in &s.passes {
                let l = [scene.clone(), owner.clone(), name.clone(), ("pass", pass.to_string())];
                ConstCounter::new(seconds).encode(m.encode_family(&l)?)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug)]
    struct One;

    impl SceneSamples for One {
        fn samples(&self) -> Vec<SceneSample> {
            vec![SceneSample {
                id: 3,
                owner: "alice".into(),
                name: "dam \"break\"".into(),
                steps: 120,
                passes: vec![("forces", 0.5, 120)],
                ..SceneSample::default()
            }]
        }
    }

    #[test]
    fn scenes_and_calls_render() {
        let m = Metrics::new(Arc::new(One));
        m.observe("grpc", "SceneService/Step", "OK", 0.002);
        m.quota_refused("running_scenes");
        let text = m.render();
        for line in [
            r#"floe_scene_steps_total{scene="3",owner="alice",name="dam \"break\""} 120"#,
            r#"floe_scene_backend_seconds_total{scene="3",owner="alice",name="dam \"break\"",pass="forces"} 0.5"#,
            r#"floe_requests_total{transport="grpc",method="SceneService/Step",code="OK"} 1"#,
            r#"floe_quota_refusals_total{quota="running_scenes"} 1"#,
            r#"floe_request_duration_seconds_count{transport="grpc",method="SceneService/Step"} 1"#,
        ] {
            assert!(text.lines().any(|l| l == line), "no line {line} in\n{text}");
        }
        assert!(!text.contains("floe_cluster"), "a single server has no cluster series");
    }

    #[test]
    fn cluster_totals_come_per_worker() {
        let m = Metrics::new(Arc::new(One));
        let scene =
            |particles, running| SceneSample { particles, running, steps_per_second: 10.0, ..One.samples()[0].clone() };
        m.cluster().set(vec![
            WorkerSample {
                name: "w1".into(),
                draining: false,
                max_particles: 1000,
                scenes: vec![scene(100, true), scene(50, false)],
            },
            WorkerSample { name: "w2".into(), draining: true, max_particles: 2000, scenes: vec![] },
        ]);
        let text = m.render();
        for line in [
            r#"floe_cluster_scenes{worker="w1"} 2"#,
            r#"floe_cluster_running_scenes{worker="w1"} 1"#,
            r#"floe_cluster_particles{worker="w1"} 150"#,
            r#"floe_cluster_particle_steps_per_second{worker="w1"} 1000.0"#,
            r#"floe_cluster_scenes{worker="w2"} 0"#,
            r#"floe_cluster_worker_draining{worker="w2"} 1"#,
            r#"floe_cluster_worker_max_particles{worker="w2"} 2000"#,
        ] {
            assert!(text.lines().any(|l| l == line), "no line {line} in\n{text}");
        }
    }
}
