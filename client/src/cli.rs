//! `floectl`, the command line on top of [`Client`]: parsed by [`Cli`], run by [`execute`].
//! A library module so that tests drive it the way a user does; `src/bin/floectl.rs` is only
//! the entry point.

use crate::recording::{self, Recorder};
use crate::{Client, FrameRequest};
use anyhow::Context;
use clap::{Parser, Subcommand, ValueEnum};
use floe_proto::Particles;
use floe_proto::export::{self, Format};
use std::path::{Path, PathBuf};

/// Drive a Floe server: create, step, run, watch and record scenes.
#[derive(Debug, Parser)]
#[command(name = "floectl", version, about)]
pub struct Cli {
    /// The server's gRPC address.
    #[arg(long, env = "FLOE_SERVER", default_value = "http://127.0.0.1:50051")]
    pub server: String,
    /// API token (from `floe admin user add`), or a share link's token; needed on a
    /// server with users.
    #[arg(long, env = "FLOE_TOKEN", hide_env_values = true)]
    pub token: Option<String>,
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// File format of `floectl export`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ExportFormat {
    /// Legacy VTK polydata, for ParaView.
    Vtk,
    /// Comma-separated values with a header line.
    Csv,
}

/// A `floectl` command.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Create a scene from a preset name or a scene file (.toml / .json).
    Create {
        /// Preset or file.
        scene: String,
        /// Field overrides, e.g. --set particle_spacing=0.02 (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        overrides: Vec<String>,
        /// The backend the scene must run on (a cluster places it on a worker that
        /// runs it); any when not given.
        #[arg(long, value_parser = ["gpu", "cpu"])]
        backend: Option<String>,
    },
    /// List the scenes.
    List,
    /// Step a paused scene.
    Step {
        /// Scene id.
        id: u64,
        /// Steps to take.
        #[arg(long, default_value = "1", conflicts_with = "until")]
        steps: u64,
        /// Or: simulated time to reach (s).
        #[arg(long, allow_negative_numbers = true)]
        until: Option<f64>,
    },
    /// Run a scene continuously.
    Run {
        /// Scene id.
        id: u64,
        /// Simulated seconds per wall second (0: as fast as possible).
        #[arg(long, default_value = "0", allow_negative_numbers = true)]
        rtf: f64,
    },
    /// Pause a running scene.
    Pause {
        /// Scene id.
        id: u64,
    },
    /// Put a paused or halted scene back at t = 0 (current settings kept).
    Reset {
        /// Scene id.
        id: u64,
    },
    /// Change tunable settings of a scene, e.g. `floectl set 2 gravity=[0,-1,0]`.
    Set {
        /// Scene id.
        id: u64,
        /// `key=value` overrides.
        #[arg(required = true, value_name = "KEY=VALUE")]
        overrides: Vec<String>,
    },
    /// Print a live statistics line every second.
    Watch {
        /// Scene id.
        id: u64,
        /// Stop after this many lines (default: until interrupted).
        #[arg(long)]
        count: Option<u64>,
    },
    /// Record frames to a file.
    Record {
        /// Scene id.
        id: u64,
        /// The recording.
        #[arg(long)]
        out: PathBuf,
        /// Frames to record.
        #[arg(long, default_value = "100")]
        frames: u64,
        /// Most frames per second.
        #[arg(long, default_value = "30")]
        fps: f64,
        /// The particle set to record (`floectl get ID` lists them: `solid`, `flakes`, ...).
        #[arg(long, default_value = "particles")]
        set: String,
    },
    /// Export frames of a live scene, or of a recording, as VTK or CSV files.
    Export {
        /// Scene id (live), unless --recording is given.
        id: Option<u64>,
        /// Export this recording instead.
        #[arg(long, conflicts_with = "id")]
        recording: Option<PathBuf>,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
        /// File format.
        #[arg(long, value_enum, default_value = "vtk")]
        format: ExportFormat,
        /// Frames to take from a live scene.
        #[arg(long, default_value = "1")]
        frames: u64,
        /// The particle set to export from a live scene (a recording holds one).
        #[arg(long, default_value = "particles", conflicts_with = "recording")]
        set: String,
    },
    /// Save a scene's full state to a file.
    Snapshot {
        /// Scene id.
        id: u64,
        /// The file.
        #[arg(long)]
        out: PathBuf,
    },
    /// Restore a paused scene from a snapshot file.
    Restore {
        /// Scene id.
        id: u64,
        /// The file.
        file: PathBuf,
    },
    /// Delete a scene.
    Delete {
        /// Scene id.
        id: u64,
    },
    /// A live table of the scenes (every scene, for an admin), refreshed every second.
    Top {
        /// Stop after this many refreshes (default: until interrupted).
        #[arg(long)]
        count: Option<u64>,
    },
    /// Write a checkpoint of a scene now.
    Checkpoint {
        /// Scene id.
        id: u64,
    },
    /// Create a read-only share link of a scene: prints its id and token.
    Share {
        /// Scene id.
        id: u64,
    },
    /// List a scene's share links.
    Shares {
        /// Scene id.
        id: u64,
    },
    /// Revoke a share link.
    Unshare {
        /// Scene id.
        id: u64,
        /// The link's id (from `floectl shares`).
        share_id: String,
    },
    /// Who the token belongs to: quotas and usage.
    Whoami,
    /// Admin: every user with quotas and usage.
    Users,
    /// Admin: set a user's quota, e.g. `floectl quota alice running_scenes=2` (=0 clears it).
    Quota {
        /// Login name.
        user: String,
        /// NAME=VALUE.
        #[arg(value_name = "NAME=VALUE")]
        quota: String,
    },
}

fn user_line(u: &floe_proto::pb::UserInfo) -> String {
    let quotas: Vec<String> =
        u.quotas.iter().map(|q| format!("{}={}{}", q.name, q.value, if q.overridden { "*" } else { "" })).collect();
    format!(
        "{}{}  {} scenes ({} running, {} particles)  {} streams  quotas: {}",
        u.name,
        if u.admin { " (admin)" } else { "" },
        u.scenes,
        u.running_scenes,
        u.running_particles,
        u.open_streams,
        quotas.join(" ")
    )
}

fn line(s: &crate::SceneInfo) -> String {
    let state = floe_proto::pb::SceneState::try_from(s.state).map_or("?", |x| x.as_str_name());
    let state = state.trim_start_matches("SCENE_STATE_").to_lowercase();
    let halt = if s.halt_reason.is_empty() { String::new() } else { format!("  {}", s.halt_reason) };
    format!(
        "{:>4}  {:<16} {:>9} particles on {}  t = {:.4} s  step {}  {state}{halt}",
        s.scene_id, s.name, s.particles, s.backend, s.sim_time, s.steps
    )
}

/// The error and its causes, `: `-separated, each said once: the transport layers under tonic
/// wrap a cause in an error of the same message ("tcp connect error: tcp connect error: ...").
pub fn error_chain(e: &anyhow::Error) -> String {
    let mut messages: Vec<String> = Vec::new();
    for cause in e.chain() {
        let message = cause.to_string();
        if messages.last() != Some(&message) {
            messages.push(message);
        }
    }
    messages.join(": ")
}

/// Runs one command, printing its result; an error says what went wrong (print it with
/// [`error_chain`]).
pub async fn execute(cli: Cli) -> anyhow::Result<()> {
    // Exporting a recording needs no server.
    if let Command::Export { recording: Some(path), out, format, .. } = &cli.command {
        let file = std::fs::File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
        let frames = recording::read(file)?
            .into_iter()
            .map(|f| {
                let t = f.header.time;
                (crate::particles(f, None), t)
            })
            .collect();
        return export_frames(frames, out, *format);
    }
    let mut floe = Client::connect_with_token(&cli.server, cli.token.as_deref()).await?;
    match cli.command {
        Command::Create { scene, overrides, backend } => {
            let o: Vec<&str> = overrides.iter().map(String::as_str).collect();
            floe.set_backend(backend.as_deref().unwrap_or_default());
            let path = Path::new(&scene);
            // A name with a scene file's extension is a file even when it is missing, so the
            // error names the file rather than an unknown preset.
            let is_file = path.exists() || scene.ends_with(".toml") || scene.ends_with(".json");
            let info = if is_file {
                let text = std::fs::read_to_string(path).with_context(|| format!("cannot read {scene}"))?;
                let format = if scene.ends_with(".json") { "json" } else { "toml" };
                floe.create_document(&text, format, &o).await?
            } else {
                floe.create_preset(&scene, &o).await?
            };
            println!("{}", line(&info));
        }
        Command::List => {
            for s in floe.list().await? {
                println!("{}", line(&s));
            }
        }
        Command::Step { id, steps, until } => {
            let info = match until {
                Some(t) => floe.step_until(id, t).await?,
                None => floe.step(id, steps).await?,
            };
            println!("{}", line(&info));
        }
        Command::Run { id, rtf } => println!("{}", line(&floe.run(id, rtf).await?)),
        Command::Pause { id } => println!("{}", line(&floe.pause(id).await?)),
        Command::Reset { id } => println!("{}", line(&floe.reset(id).await?)),
        Command::Set { id, overrides } => {
            let o: Vec<&str> = overrides.iter().map(String::as_str).collect();
            println!("{}", line(&floe.set_parameters(id, &o).await?));
        }
        Command::Delete { id } => println!("{}", line(&floe.delete(id).await?)),
        Command::Watch { id, count } => {
            let mut n = 0;
            while count.is_none_or(|c| n < c) {
                let s = floe.stats(id).await?;
                println!(
                    "t = {:.4} s  step {}  {:.0} steps/s  dt {:.2e} s  {} subscribers  {} frames published  {} dropped",
                    s.sim_time, s.steps, s.steps_per_second, s.dt, s.subscribers, s.frames_published, s.dropped_frames
                );
                n += 1;
                if count.is_none_or(|c| n < c) {
                    tokio::time::sleep(std::time::Duration::from_secs(1)).await;
                }
            }
        }
        Command::Record { id, out, frames, fps, set } => {
            let file = std::fs::File::create(&out).with_context(|| format!("cannot create {}", out.display()))?;
            let mut rec = Recorder::new(std::io::BufWriter::new(file))?;
            let info = floe.get(id).await?;
            if info.state != floe_proto::pb::SceneState::Running as i32 {
                eprintln!("scene {id} is not running: one frame now, more only as it steps (`floectl run {id}`)");
            }
            let mut stream = floe.frames(id, FrameRequest { max_fps: fps, set, ..FrameRequest::default() }).await?;
            let mut n = 0;
            // Ctrl-C ends the recording with the frames so far, a file that reads back whole.
            let interrupt = tokio::signal::ctrl_c();
            tokio::pin!(interrupt);
            while n < frames {
                let bytes = tokio::select! {
                    next = stream.next_raw() => next?,
                    _ = &mut interrupt => None,
                };
                let Some(bytes) = bytes else { break };
                rec.push(&bytes)?;
                n += 1;
            }
            rec.finish()?;
            eprintln!("recorded {n} frames to {}", out.display());
        }
        Command::Export { id, out, format, frames, set, .. } => {
            let Some(id) = id else { anyhow::bail!("give a scene id or --recording FILE") };
            // Every channel of the set (a part of the SPH particles offers theirs); a set
            // the scene lacks is refused by the server, naming those it has.
            let info = floe.get(id).await?;
            let offers = info
                .sets
                .iter()
                .find(|s| s.name == set)
                .map_or(set.as_str(), |s| if s.part_of.is_empty() { s.name.as_str() } else { s.part_of.as_str() });
            let channels = info.channels.iter().filter(|c| c.set == offers).map(|c| c.name.clone()).collect();
            let mut stream = floe.frames(id, FrameRequest { channels, set, ..FrameRequest::default() }).await?;
            let mut decoded = Vec::new();
            while (decoded.len() as u64) < frames {
                let Some(f) = stream.next().await? else { break };
                let t = f.header.time;
                decoded.push((stream.particles(f), t));
            }
            export_frames(decoded, &out, format)?;
        }
        Command::Snapshot { id, out } => {
            let state = floe.snapshot(id).await?;
            std::fs::write(&out, &state).with_context(|| format!("cannot write {}", out.display()))?;
            eprintln!("saved {} bytes to {}", state.len(), out.display());
        }
        Command::Restore { id, file } => {
            let state = std::fs::read(&file).with_context(|| format!("cannot read {}", file.display()))?;
            println!("{}", line(&floe.restore(id, state).await?));
        }
        Command::Top { count } => {
            use std::io::IsTerminal;
            let mut before: Option<(Vec<crate::SceneStats>, std::time::Instant)> = None;
            let mut n = 0;
            while count.is_none_or(|c| n < c) {
                let now = floe.all_stats().await?;
                let previous = before.as_ref().map(|(b, t)| (b.as_slice(), t.elapsed().as_secs_f64()));
                let table = crate::top::table(&now, previous);
                // On a terminal the table replaces the previous one.
                let clear = if std::io::stdout().is_terminal() { "\x1b[2J\x1b[H" } else { "" };
                println!("{clear}{table}");
                before = Some((now, std::time::Instant::now()));
                n += 1;
                if count.is_none_or(|c| n < c) {
                    tokio::time::sleep(std::time::Duration::from_secs(1)).await;
                }
            }
        }
        Command::Checkpoint { id } => {
            let c = floe.checkpoint(id).await?;
            println!("scene {id}: checkpoint {} at step {} (t = {:.4} s)", c.sequence, c.step, c.sim_time);
        }
        Command::Share { id } => {
            let s = floe.share(id).await?;
            println!("share {} of scene {id}; token (shown once): {}", s.share_id, s.token);
            println!("viewer: http://<the server's HTTP address>/#scene={id}&token={}", s.token);
        }
        Command::Shares { id } => {
            for s in floe.shares(id).await? {
                println!("{s}");
            }
        }
        Command::Unshare { id, share_id } => {
            floe.revoke_share(id, &share_id).await?;
            eprintln!("revoked share {share_id} of scene {id}");
        }
        Command::Whoami => println!("{}", user_line(&floe.whoami().await?)),
        Command::Users => {
            for u in floe.users().await? {
                println!("{}", user_line(&u));
            }
        }
        Command::Quota { user, quota } => {
            let (name, value) = quota.split_once('=').context("expected NAME=VALUE, e.g. running_scenes=2")?;
            let value: u64 = value.trim().parse().with_context(|| format!("{name}: not a whole number"))?;
            println!("{}", user_line(&floe.set_quota(&user, name.trim(), value).await?));
        }
    }
    Ok(())
}

/// Writes each frame (particles and the time) to `out/frame_NNNNN.vtk` (or `.csv`;
/// another set than the SPH particles' as `out/SET_NNNNN.vtk`).
fn export_frames(frames: Vec<(Particles, f64)>, out: &Path, format: ExportFormat) -> anyhow::Result<()> {
    let format = match format {
        ExportFormat::Vtk => Format::Vtk,
        ExportFormat::Csv => Format::Csv,
    };
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let count = frames.len();
    for (k, (particles, time)) in frames.into_iter().enumerate() {
        let path = out.join(export::file_name(&particles.set, k, format));
        export::write(&path, format, &particles, time).with_context(|| format!("cannot write {}", path.display()))?;
    }
    eprintln!("wrote {count} frames to {}", out.display());
    Ok(())
}
