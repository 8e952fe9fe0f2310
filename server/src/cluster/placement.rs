//! Which worker a scene goes to: the rule for new scenes and for scenes moved off a
//! worker that stopped or drains.
//!
//! A worker can take a scene when it is up and not draining, runs the backend the
//! scene asks for (any, when it asks for none), holds fewer scenes than its
//! `--max-scenes` and would stay within its `--max-particles` (a budget over all its
//! scenes, the GPU memory they share). Among those, the one left with the largest
//! share of its particle budget free wins; then the one with fewer scenes; then the
//! first name, so the choice is the same on every worker that makes it.

use std::cmp::Ordering;

/// A worker as placement sees it.
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    /// Worker name.
    pub name: String,
    /// `gpu` or `cpu`.
    pub backend: String,
    /// Most scenes it holds.
    pub max_scenes: u64,
    /// Most particles over all its scenes.
    pub max_particles: u64,
    /// Scenes it holds now.
    pub scenes: u64,
    /// Particles over those scenes.
    pub particles: u64,
    /// Taking no new scenes (maintenance).
    pub draining: bool,
}

impl Candidate {
    /// The share of its particle budget left free after a scene of `particles`.
    fn free_after(&self, particles: u64) -> f64 {
        let used = self.particles.saturating_add(particles);
        self.max_particles.saturating_sub(used) as f64 / self.max_particles.max(1) as f64
    }

    /// Why it cannot take a scene of `particles` on `backend`, if it cannot.
    fn refusal(&self, particles: u64, backend: Option<&str>) -> Option<String> {
        if self.draining {
            Some(format!("{} drains", self.name))
        } else if backend.is_some_and(|b| b != self.backend) {
            Some(format!("{} runs {}", self.name, self.backend))
        } else if self.scenes >= self.max_scenes {
            Some(format!("{} holds its {} scenes", self.name, self.max_scenes))
        } else if self.particles.saturating_add(particles) > self.max_particles {
            Some(format!(
                "{} has {} of its {} particles free",
                self.name,
                self.max_particles - self.particles.min(self.max_particles),
                self.max_particles
            ))
        } else {
            None
        }
    }
}

/// The worker for a scene of `particles` asking for `backend` (`None`: any), or why
/// none can take it (each worker's reason).
pub fn choose<'a>(workers: &'a [Candidate], particles: u64, backend: Option<&str>) -> Result<&'a Candidate, String> {
    let best = workers.iter().filter(|w| w.refusal(particles, backend).is_none()).max_by(|a, b| {
        a.free_after(particles)
            .partial_cmp(&b.free_after(particles))
            .unwrap_or(Ordering::Equal)
            .then(b.scenes.cmp(&a.scenes))
            .then(b.name.cmp(&a.name))
    });
    best.ok_or_else(|| {
        if workers.is_empty() {
            return "no worker is up".to_string();
        }
        let reasons: Vec<String> = workers.iter().filter_map(|w| w.refusal(particles, backend)).collect();
        format!("no worker can take a scene of {particles} particles: {}", reasons.join("; "))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn worker(name: &str, scenes: u64, particles: u64) -> Candidate {
        Candidate {
            name: name.into(),
            backend: "gpu".into(),
            max_scenes: 4,
            max_particles: 1_000_000,
            scenes,
            particles,
            draining: false,
        }
    }

    #[test]
    fn the_most_free_particle_budget_wins() {
        let ws = [worker("a", 1, 600_000), worker("b", 3, 100_000), worker("c", 0, 300_000)];
        assert_eq!(choose(&ws, 50_000, None).unwrap().name, "b");
        // Budgets of different sizes compare as shares: 2M with 1M used beats 1M with 0.4M.
        let mut big = worker("big", 0, 1_000_000);
        big.max_particles = 2_000_000;
        let ws = [worker("small", 0, 400_000), big];
        assert_eq!(choose(&ws, 100_000, None).unwrap().name, "small");
    }

    #[test]
    fn ties_go_to_fewer_scenes_then_the_first_name() {
        let ws = [worker("b", 2, 0), worker("a", 2, 0), worker("c", 1, 0)];
        assert_eq!(choose(&ws, 10, None).unwrap().name, "c");
        let ws = [worker("b", 1, 0), worker("a", 1, 0)];
        assert_eq!(choose(&ws, 10, None).unwrap().name, "a");
    }

    #[test]
    fn full_draining_and_other_backend_workers_are_passed_over() {
        let mut draining = worker("d", 0, 0);
        draining.draining = true;
        let mut cpu = worker("cpu", 0, 0);
        cpu.backend = "cpu".into();
        let ws = [worker("full", 4, 0), worker("tight", 0, 990_000), draining, cpu, worker("ok", 3, 500_000)];
        assert_eq!(choose(&ws, 20_000, Some("gpu")).unwrap().name, "ok");
        assert_eq!(choose(&ws, 20_000, None).unwrap().name, "cpu");
        let e = choose(&ws, 600_000, Some("gpu")).unwrap_err();
        for reason in
            ["full holds its 4 scenes", "tight has 10000 of its 1000000 particles free", "d drains", "cpu runs cpu"]
        {
            assert!(e.contains(reason), "{e}");
        }
        assert_eq!(choose(&[], 1, None).unwrap_err(), "no worker is up");
    }
}
