//! `floectl top`: a live table of the scenes (every scene, for an admin), refreshed
//! every second: state, size, steps/s, simulated time, viewers, frame bandwidth and
//! frames dropped since the previous refresh. Through a cluster's proxy, every
//! worker's scenes with a worker column and a summary line per worker.

use floe_proto::pb::{SceneState, SceneStats};

fn state(s: &SceneStats) -> String {
    SceneState::try_from(s.state).map_or("?", |x| x.as_str_name()).trim_start_matches("SCENE_STATE_").to_lowercase()
}

/// The table for `now`, with rates from `before` (the previous refresh, `seconds` ago).
pub fn table(now: &[SceneStats], before: Option<(&[SceneStats], f64)>) -> String {
    let cluster = now.iter().any(|s| !s.worker.is_empty());
    let worker = |w: &str| if cluster { format!("{:<10} ", clip(w, 10)) } else { String::new() };
    let mut out = format!(
        "{:>5}  {}{:<12} {:<16} {:<8} {:>10} {:>9} {:>10} {:>5} {:>10} {:>8}\n",
        "scene",
        worker("worker"),
        "owner",
        "name",
        "state",
        "particles",
        "steps/s",
        "sim t (s)",
        "subs",
        "frames kB/s",
        "dropped"
    );
    for s in now {
        let prev = before.and_then(|(b, dt)| b.iter().find(|p| p.scene_id == s.scene_id).map(|p| (p, dt)));
        let kbps = prev.map_or("-".to_string(), |(p, dt)| {
            format!("{:.1}", s.frame_bytes.saturating_sub(p.frame_bytes) as f64 / 1e3 / dt.max(1e-9))
        });
        let dropped =
            prev.map_or("-".to_string(), |(p, _)| s.dropped_frames.saturating_sub(p.dropped_frames).to_string());
        out += &format!(
            "{:>5}  {}{:<12} {:<16} {:<8} {:>10} {:>9.1} {:>10.4} {:>5} {:>10} {:>8}\n",
            s.scene_id,
            worker(&s.worker),
            clip(&s.owner, 12),
            clip(&s.name, 16),
            state(s),
            s.particles,
            s.steps_per_second,
            s.sim_time,
            s.subscribers,
            kbps,
            dropped
        );
    }
    if cluster {
        let workers: std::collections::BTreeSet<&str> = now.iter().map(|s| s.worker.as_str()).collect();
        for w in workers {
            out += &format!("{w}: {}\n", summary(now.iter().filter(|s| s.worker == *w)));
        }
    }
    out += &summary(now.iter());
    out += "\n";
    out
}

/// "N scenes, P particles, R M particle-steps/s running" over `scenes`.
fn summary<'a>(scenes: impl Iterator<Item = &'a SceneStats>) -> String {
    let (mut count, mut particles, mut rate) = (0, 0, 0.0);
    for s in scenes {
        count += 1;
        particles += s.particles;
        if s.state == SceneState::Running as i32 {
            rate += s.steps_per_second * s.particles as f64;
        }
    }
    format!("{count} scenes, {particles} particles, {:.2} M particle-steps/s running", rate / 1e6)
}

fn clip(s: &str, n: usize) -> String {
    if s.chars().count() <= n { s.to_owned() } else { s.chars().take(n - 1).chain(['…']).collect() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_come_from_the_previous_refresh() {
        let stats = |frame_bytes, dropped| SceneStats {
            scene_id: 3,
            state: SceneState::Running as i32,
            particles: 1000,
            steps_per_second: 250.0,
            sim_time: 1.5,
            subscribers: 2,
            frame_bytes,
            dropped_frames: dropped,
            name: "a very long scene name".into(),
            owner: "alice".into(),
            ..SceneStats::default()
        };
        let before = [stats(10_000, 4)];
        let t = table(&[stats(30_000, 7)], Some((&before, 2.0)));
        let row = t.lines().nth(1).unwrap();
        assert_eq!(
            row.split_whitespace().collect::<Vec<_>>(),
            ["3", "alice", "a", "very", "long", "sce…", "running", "1000", "250.0", "1.5000", "2", "10.0", "3"]
        );
        assert!(t.ends_with("1 scenes, 1000 particles, 0.25 M particle-steps/s running\n"), "{t}");
        assert!(table(&[stats(0, 0)], None).lines().nth(1).unwrap().ends_with("-        -"));
    }

    #[test]
    fn a_cluster_shows_each_scenes_worker_and_each_workers_totals() {
        let stats = |id, worker: &str, particles| SceneStats {
            scene_id: id,
            state: SceneState::Running as i32,
            particles,
            steps_per_second: 100.0,
            worker: worker.into(),
            ..SceneStats::default()
        };
        let t = table(&[stats(1, "w2", 1000), stats(2, "w1", 3000), stats(3, "w2", 2000)], None);
        let lines: Vec<&str> = t.lines().collect();
        assert_eq!(lines[0].split_whitespace().take(3).collect::<Vec<_>>(), ["scene", "worker", "owner"]);
        assert_eq!(lines[1].split_whitespace().take(2).collect::<Vec<_>>(), ["1", "w2"]);
        assert_eq!(lines[4], "w1: 1 scenes, 3000 particles, 0.30 M particle-steps/s running");
        assert_eq!(lines[5], "w2: 2 scenes, 3000 particles, 0.30 M particle-steps/s running");
        assert_eq!(lines[6], "3 scenes, 6000 particles, 0.60 M particle-steps/s running");
    }
}
