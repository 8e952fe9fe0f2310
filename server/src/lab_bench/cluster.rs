//! `floe bench --cluster`: a cluster under load through its proxy. `deploy/local/
//! cluster.sh` starts PostgreSQL, three workers (this very binary, CPU backend) and
//! nginx on loopback; three dam breaks run at real time, one per worker; viewers
//! stream them through the proxy; scripted users each create a scene through the
//! proxy and then, at a steady rate, read it alternately through the proxy and
//! directly from its worker, so the proxy hop's added latency is measured on the
//! same calls, interleaved, in the same run. Reported: calls, calls lost (no answer
//! within 10 s) and failed, frames the viewers read, and the latency percentiles of
//! both paths.

use super::CALL_TIMEOUT;
use floe_client::{Client, FrameRequest};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// What to run.
#[derive(Debug, Clone)]
pub struct ClusterLoad {
    /// The `floe` binary the workers run.
    pub floe: PathBuf,
    /// Seconds under load.
    pub seconds: u64,
    /// Viewers streaming the running scenes through the proxy.
    pub viewers: usize,
    /// Scripted users.
    pub scripts: usize,
    /// Calls per second of each scripted user.
    pub script_rate: f64,
}

/// What happened.
#[derive(Debug, Clone, Default)]
pub struct ClusterReport {
    /// Calls through the proxy and directly, each with its latency (s).
    pub proxied: Vec<f64>,
    /// Calls sent directly to the scene's worker (s).
    pub direct: Vec<f64>,
    /// Calls with no answer within 10 s.
    pub lost: u64,
    /// Calls that failed.
    pub errors: Vec<String>,
    /// Frames the viewers read.
    pub frames: u64,
    /// Viewers whose stream failed.
    pub viewer_failures: Vec<String>,
    /// Scenes per worker at the end (scripted users' and the running ones).
    pub placement: Vec<(String, usize)>,
}

/// The cluster's addresses, from `cluster.sh start`'s `export NAME=VALUE` lines (URLs
/// and pids: no quoting to undo).
fn exports(text: &str) -> HashMap<String, String> {
    text.lines()
        .filter_map(|l| l.strip_prefix("export ")?.split_once('='))
        .map(|(k, v)| (k.to_owned(), v.to_owned()))
        .collect()
}

/// `deploy/local/cluster.sh` of this source tree, else of the working directory.
fn script() -> PathBuf {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("../deploy/local/cluster.sh");
    if source.exists() { source } else { PathBuf::from("deploy/local/cluster.sh") }
}

/// The `p`-th percentile (0 to 1) of `v` (sorted here), in ms.
pub fn percentile_ms(v: &[f64], p: f64) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    if s.is_empty() {
        return f64::NAN;
    }
    1e3 * s[((s.len() - 1) as f64 * p).round() as usize]
}

/// Starts the cluster, runs the load, stops the cluster.
pub async fn run(cfg: &ClusterLoad) -> anyhow::Result<ClusterReport> {
    let dir = tempfile::tempdir()?;
    let out = Command::new("bash")
        .arg(script())
        .args(["start", &dir.path().display().to_string(), "3"])
        .env("FLOE_BIN", &cfg.floe)
        .env("FLOE_BACKEND", "cpu")
        .output()?;
    anyhow::ensure!(out.status.success(), "cluster.sh start failed:\n{}", String::from_utf8_lossy(&out.stderr));
    let env = exports(&String::from_utf8_lossy(&out.stdout));
    let result = load(cfg, &env).await;
    let stop = Command::new("bash").arg(script()).args(["stop", &dir.path().display().to_string()]).output()?;
    anyhow::ensure!(stop.status.success(), "cluster.sh stop failed:\n{}", String::from_utf8_lossy(&stop.stderr));
    result
}

async fn load(cfg: &ClusterLoad, env: &HashMap<String, String>) -> anyhow::Result<ClusterReport> {
    let proxy = env.get("FLOE_PROXY_GRPC").ok_or_else(|| anyhow::anyhow!("cluster.sh printed no proxy address"))?;
    let direct: HashMap<String, String> = (1..=3)
        .filter_map(|k| Some((format!("floe-{k}"), env.get(&format!("FLOE_CLUSTER_WORKER_{k}_GRPC"))?.clone())))
        .collect();
    let mut c = Client::connect(proxy).await?;
    let mut running = Vec::new();
    for _ in 0..3 {
        let id = c.create_preset("dam_break", &["particle_spacing=0.05"]).await?.scene_id;
        c.run(id, 1.0).await?;
        running.push(id);
    }
    let stop = Arc::new(AtomicBool::new(false));
    let frames = Arc::new(AtomicU64::new(0));
    let mut viewers = Vec::new();
    for k in 0..cfg.viewers {
        let (proxy, stop, frames, scene) = (proxy.clone(), stop.clone(), frames.clone(), running[k % 3]);
        viewers.push(tokio::spawn(async move {
            let mut c = Client::connect(&proxy).await.map_err(|e| format!("viewer {k}: {e}"))?;
            let request = FrameRequest { max_fps: 10.0, ..FrameRequest::default() };
            let mut stream = c.frames(scene, request).await.map_err(|e| format!("viewer {k}: {e}"))?;
            while !stop.load(Ordering::Relaxed) {
                match tokio::time::timeout(Duration::from_secs(1), stream.next_raw()).await {
                    Ok(Ok(Some(_))) => {
                        frames.fetch_add(1, Ordering::Relaxed);
                    }
                    Ok(Ok(None)) => return Err(format!("viewer {k}: the stream ended")),
                    Ok(Err(e)) => return Err(format!("viewer {k}: {e}")),
                    Err(_) => {}
                }
            }
            Ok(())
        }));
    }
    let period = Duration::from_secs_f64(1.0 / cfg.script_rate.max(0.01));
    let mut scripts = Vec::new();
    for k in 0..cfg.scripts {
        let (proxy, direct, stop) = (proxy.clone(), direct.clone(), stop.clone());
        scripts.push(tokio::spawn(async move { script_user(k, &proxy, &direct, stop, period).await }));
    }
    tokio::time::sleep(Duration::from_secs(cfg.seconds)).await;
    stop.store(true, Ordering::Relaxed);
    let mut report = ClusterReport::default();
    for s in scripts {
        let (proxied, direct, lost, errors) = s.await?;
        report.proxied.extend(proxied);
        report.direct.extend(direct);
        report.lost += lost;
        report.errors.extend(errors);
    }
    for v in viewers {
        if let Err(e) = v.await? {
            report.viewer_failures.push(e);
        }
    }
    report.frames = frames.load(Ordering::Relaxed);
    let mut per: HashMap<String, usize> = HashMap::new();
    for s in c.list().await? {
        *per.entry(s.worker).or_default() += 1;
    }
    report.placement = per.into_iter().collect();
    report.placement.sort();
    Ok(report)
}

type ScriptResult = (Vec<f64>, Vec<f64>, u64, Vec<String>);

/// One scripted user: a scene of its own through the proxy, then reads of it through
/// the proxy and directly from its worker in turn, `period` apart.
async fn script_user(
    k: usize,
    proxy: &str,
    direct: &HashMap<String, String>,
    stop: Arc<AtomicBool>,
    period: Duration,
) -> ScriptResult {
    let (mut proxied, mut straight, mut lost, mut errors) = (Vec::new(), Vec::new(), 0, Vec::new());
    let setup = async {
        let mut via = Client::connect(proxy).await?;
        let info = via.create_preset("hydrostatic", &["particle_spacing=0.1"]).await?;
        let at = direct.get(&info.worker).ok_or_else(|| anyhow::anyhow!("no address for worker '{}'", info.worker))?;
        anyhow::Ok((via, Client::connect(at).await?, info.scene_id))
    };
    let (mut via, mut to, id) = match setup.await {
        Ok(v) => v,
        Err(e) => return (proxied, straight, lost, vec![format!("script {k}: {e}")]),
    };
    let mut tick = tokio::time::interval(period);
    for n in 0u64.. {
        tick.tick().await;
        if stop.load(Ordering::Relaxed) {
            break;
        }
        let through_proxy = n % 2 == 0;
        let client = if through_proxy { &mut via } else { &mut to };
        let t0 = Instant::now();
        match tokio::time::timeout(CALL_TIMEOUT, client.get(id)).await {
            Ok(Ok(_)) => (if through_proxy { &mut proxied } else { &mut straight }).push(t0.elapsed().as_secs_f64()),
            Ok(Err(e)) => errors.push(format!("script {k}: {e}")),
            Err(_) => lost += 1,
        }
    }
    (proxied, straight, lost, errors)
}

/// Prints the report as a table.
pub fn print(cfg: &ClusterLoad, r: &ClusterReport) {
    println!(
        "Cluster under load: 3 workers (CPU) behind nginx, 3 dam breaks at real time, {} viewers, {} scripted users \
         at {} calls/s, {} s",
        cfg.viewers, cfg.scripts, cfg.script_rate, cfg.seconds
    );
    println!("\n| path | calls | p50 (ms) | p99 (ms) |\n|---|---|---|---|");
    for (name, v) in [("through the proxy", &r.proxied), ("directly to the worker", &r.direct)] {
        println!("| {name} | {} | {:.2} | {:.2} |", v.len(), percentile_ms(v, 0.5), percentile_ms(v, 0.99));
    }
    println!(
        "\nadded by the proxy hop: p50 {:.2} ms, p99 {:.2} ms",
        percentile_ms(&r.proxied, 0.5) - percentile_ms(&r.direct, 0.5),
        percentile_ms(&r.proxied, 0.99) - percentile_ms(&r.direct, 0.99)
    );
    println!("calls lost (no answer within 10 s): {}; failed: {}", r.lost, r.errors.len());
    for e in r.errors.iter().take(5) {
        println!("  {e}");
    }
    println!("frames read by the viewers: {}; viewers failed: {}", r.frames, r.viewer_failures.len());
    for e in r.viewer_failures.iter().take(5) {
        println!("  {e}");
    }
    let placement: Vec<String> = r.placement.iter().map(|(w, n)| format!("{w}: {n}")).collect();
    println!("scenes per worker: {}", placement.join(", "));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exports_and_percentiles() {
        let e = exports("export FLOE_PROXY_GRPC=http://127.0.0.1:5\nexport FLOE_CLUSTER_WORKER_1_PID=42\nnoise\n");
        assert_eq!(e["FLOE_PROXY_GRPC"], "http://127.0.0.1:5");
        assert_eq!((e["FLOE_CLUSTER_WORKER_1_PID"].as_str(), e.len()), ("42", 2));
        let v: Vec<f64> = (1..=100).map(|i| f64::from(i) * 1e-3).collect();
        assert!((percentile_ms(&v, 0.5) - 51.0).abs() < 1e-9 && (percentile_ms(&v, 0.99) - 99.0).abs() < 1e-9);
        assert!(percentile_ms(&[], 0.5).is_nan());
    }
}
