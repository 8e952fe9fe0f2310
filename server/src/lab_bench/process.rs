//! A `floe serve` child process for benchmarks and tests: started on free ports
//! with JSON logs (which say where it listens), its users made with `floe admin`,
//! stopped with SIGKILL (a crash) or SIGTERM (a graceful shutdown), its resident
//! memory read from /proc.

use anyhow::Context;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// Where a server keeps its data: `--data-dir DIR [--database URL]`.
#[derive(Debug, Clone)]
pub struct Data {
    /// The data directory.
    pub dir: PathBuf,
    /// A PostgreSQL URL, or none for SQLite in the directory.
    pub database: Option<String>,
}

impl Data {
    fn args(&self) -> Vec<String> {
        let mut args = vec!["--data-dir".to_string(), self.dir.display().to_string()];
        if let Some(url) = &self.database {
            args.extend(["--database".to_string(), url.clone()]);
        }
        args
    }
}

/// A running `floe serve`.
#[derive(Debug)]
pub struct ServerProcess {
    child: Child,
    /// `http://127.0.0.1:PORT` of its gRPC listener.
    pub grpc: String,
    /// `127.0.0.1:PORT` of its HTTP listener.
    pub http: String,
    /// Its log (JSON lines).
    pub log: PathBuf,
}

/// A server still running when its handle goes (a test that failed or ended without
/// stopping it) is killed: it would otherwise outlive the test process, holding its
/// database connections and a core's worth of polling.
impl Drop for ServerProcess {
    fn drop(&mut self) {
        if let Ok(None) = self.child.try_wait() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

/// The `HOST:PORT` after the first " on " of the first logged message starting with
/// `start` (`gRPC (...) on 127.0.0.1:50051`, `REST ... on http://127.0.0.1:8080/api/v1, ...`).
fn logged_address(log: &str, start: &str) -> Option<String> {
    let message = log
        .lines()
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter_map(|v| v["message"].as_str().map(str::to_owned))
        .find(|m| m.starts_with(start))?;
    let after = message.split(" on ").nth(1)?.split([',', ' ']).next()?;
    Some(after.trim_start_matches("http://").trim_end_matches("/api/v1").to_owned())
}

impl ServerProcess {
    /// Starts `floe` (the binary at `floe`) serving `data` on free loopback ports, with
    /// `extra` arguments, logging to `log`; waits until it listens.
    pub fn start(floe: &Path, data: &Data, extra: &[&str], log: PathBuf) -> anyhow::Result<Self> {
        let out = std::fs::File::create(&log).with_context(|| format!("cannot create {}", log.display()))?;
        let mut child = Command::new(floe)
            .args(["--log-format", "json", "serve", "--grpc", "127.0.0.1:0", "--http", "127.0.0.1:0"])
            .args(data.args())
            .args(extra)
            .stdout(Stdio::null())
            .stderr(out)
            .spawn()
            .with_context(|| format!("cannot start {}", floe.display()))?;
        let t0 = Instant::now();
        loop {
            let text = std::fs::read_to_string(&log).unwrap_or_default();
            if let (Some(grpc), Some(http)) =
                (logged_address(&text, "gRPC ("), logged_address(&text, "REST and WebSocket API"))
            {
                return Ok(Self { child, grpc: format!("http://{grpc}"), http, log });
            }
            if let Some(status) = child.try_wait()? {
                anyhow::bail!("floe serve exited ({status}) before listening:\n{text}");
            }
            if t0.elapsed() > Duration::from_secs(120) {
                let _ = child.kill();
                anyhow::bail!("floe serve did not listen within 120 s:\n{text}");
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// `floe serve --scene none --backend BACKEND` (no scene at start) on `data`,
    /// logging to `dir/server.log`: the server a benchmark fills itself.
    pub fn start_empty(floe: &Path, data: &Data, backend: &str, dir: &Path) -> anyhow::Result<Self> {
        Self::start(floe, data, &["--scene", "none", "--backend", backend], dir.join("server.log"))
    }

    /// kill -9; returns the log.
    pub fn kill(mut self) -> anyhow::Result<String> {
        self.child.kill()?;
        self.child.wait()?;
        Ok(std::fs::read_to_string(&self.log)?)
    }

    /// Sends a signal (`STOP`, `CONT`, ...) by name.
    pub fn signal(&self, name: &str) -> anyhow::Result<()> {
        let pid = self.child.id().to_string();
        anyhow::ensure!(
            Command::new("kill").args([&format!("-{name}"), &pid]).status()?.success(),
            "kill -{name} {pid} failed"
        );
        Ok(())
    }

    /// SIGTERM and wait; whether it exited successfully.
    pub fn terminate(mut self) -> anyhow::Result<bool> {
        let pid = self.child.id().to_string();
        anyhow::ensure!(Command::new("kill").args(["-TERM", &pid]).status()?.success(), "kill -TERM {pid} failed");
        Ok(self.child.wait()?.success())
    }

    /// CPU time it has used so far (user and system, s), from /proc.
    pub fn cpu_seconds(&self) -> Option<f64> {
        cpu_seconds(&format!("/proc/{}/stat", self.child.id()))
    }

    /// Resident memory now (bytes), from /proc.
    pub fn rss(&self) -> Option<u64> {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.child.id())).ok()?;
        let kib: u64 = status.lines().find(|l| l.starts_with("VmRSS:"))?.split_whitespace().nth(1)?.parse().ok()?;
        Some(kib * 1024)
    }
}

/// Runs `floe admin` on `data` with `args`; returns what it printed on stdout.
pub fn admin(floe: &Path, data: &Data, args: &[&str]) -> anyhow::Result<String> {
    let out = Command::new(floe).arg("admin").args(data.args()).args(args).output()?;
    anyhow::ensure!(out.status.success(), "floe admin {}: {}", args.join(" "), String::from_utf8_lossy(&out.stderr));
    Ok(String::from_utf8(out.stdout)?.trim().to_owned())
}

/// `floe admin user add NAME`: the user's token.
pub fn add_user(floe: &Path, data: &Data, name: &str) -> anyhow::Result<String> {
    admin(floe, data, &["user", "add", name])
}

/// User plus system CPU time (s) of the process whose `stat` file is at `path`.
pub fn cpu_seconds(path: &str) -> Option<f64> {
    let stat = std::fs::read_to_string(path).ok()?;
    // Fields after the command name (in parentheses, which may hold spaces): utime and
    // stime are the 12th and 13th, in clock ticks of 1/100 s on Linux.
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let ticks: u64 = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
    Some(ticks as f64 / 100.0)
}

/// A new, empty database on the PostgreSQL server `base` names (a test's own); its URL.
pub async fn fresh_database(base: &str, purpose: &str) -> anyhow::Result<String> {
    use sqlx::Connection;
    let nanos = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH)?.subsec_nanos();
    let name = format!("floe_{purpose}_{}_{nanos}", std::process::id());
    let mut conn = sqlx::PgConnection::connect(base).await?;
    sqlx::Executor::execute(&mut conn, format!("CREATE DATABASE {name}").as_str()).await?;
    conn.close().await?;
    let (prefix, query) = base.split_once('?').map_or((base, None), |(p, q)| (p, Some(q)));
    let server = &prefix[..prefix.rfind('/').context("a database URL with a path")?];
    Ok(match query {
        Some(q) => format!("{server}/{name}?{q}"),
        None => format!("{server}/{name}"),
    })
}
