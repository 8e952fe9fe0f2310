//! The pass plan: every pass a scene's step runs, in order, for both backends.
//!
//! The core, the scene's scheme and each of its modules declare their passes
//! ([`PassSpec`]: a name both backends implement, a stage, and the attributes it
//! reads, writes and accumulates into). [`Plan::build`] orders them by stage and,
//! within a stage, by what they read and write: a pass comes after the passes of
//! its stage that write or accumulate into what it reads, and after those that
//! write what it accumulates into. Passes that share nothing (or accumulate into
//! the same attribute) keep a fixed order, whatever order they were declared in:
//! the core's, then the scheme's, then the modules' in registry order, then the
//! core's shared quantities' ([`crate::viscosity`], which act on what the modules
//! wrote). So both backends run the same sequence and sums happen in the same
//! order. It refuses a scene whose passes conflict (two writers of one attribute
//! that do not both accumulate into it), wait on each other, or read what nothing
//! provides, naming both sides.
//! `floe plan SCENE` prints the plan.

/// When in a step a pass runs. A scheme runs the stages in its own order (WCSPH:
/// sort, density, pre-force, force, measure, kick, drift, post-step).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Stage {
    /// Particles re-sorted by grid cell (state permuted).
    Sort,
    /// Density, and the neighbour lists on the CPU.
    Density,
    /// What forces need: pressure terms, wall pressures, per-particle viscosity.
    PreForce,
    /// Accelerations.
    Force,
    /// The passes of a scheme's iterative solves (DFSPH's): the scheme runs them by
    /// name, iteration by iteration ([`crate::scheme::Iterate`]), never as a stage.
    Solve,
    /// Velocity-level updates after the kick that follows an evaluation (XSPH), and
    /// fields integrated once per step (temperature).
    Kick,
    /// Position-level corrections after the drift.
    Drift,
    /// After the step: deposits, bookkeeping.
    PostStep,
}

impl Stage {
    /// Every stage, in the order a step goes through them.
    pub const ALL: [Stage; 8] = [
        Stage::Sort,
        Stage::Density,
        Stage::PreForce,
        Stage::Force,
        Stage::Solve,
        Stage::Kick,
        Stage::Drift,
        Stage::PostStep,
    ];

    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Sort => "sort",
            Stage::Density => "density",
            Stage::PreForce => "pre-force",
            Stage::Force => "force",
            Stage::Solve => "solve",
            Stage::Kick => "kick",
            Stage::Drift => "drift",
            Stage::PostStep => "post-step",
        }
    }
}

/// A pass: the unit both backends implement under the same name.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassSpec {
    /// `module.pass` (`fluid.forces`).
    pub name: &'static str,
    /// The module (or `core`, or the scheme) that declares it.
    pub module: &'static str,
    /// When it runs.
    pub stage: Stage,
    /// Attributes it reads.
    pub reads: &'static [&'static str],
    /// Attributes it writes (overwrites).
    pub writes: &'static [&'static str],
    /// Attributes it adds into (after their writer; several passes may).
    pub accumulates: &'static [&'static str],
    /// Largest difference between the GPU's and the CPU's results of what it writes,
    /// relative to the largest magnitude (f32 rounding and fused multiply-adds).
    pub tolerance: f32,
}

impl PassSpec {
    /// A pass of module `module`'s iterative solve (stage [`Stage::Solve`], run by
    /// name from a [`crate::scheme::Iterate`]), within 1e-4 of the CPU on a GPU.
    pub const fn solve(
        module: &'static str,
        name: &'static str,
        reads: &'static [&'static str],
        writes: &'static [&'static str],
        accumulates: &'static [&'static str],
    ) -> PassSpec {
        PassSpec { name, module, stage: Stage::Solve, reads, writes, accumulates, tolerance: 1e-4 }
    }
}

/// Where a pass's module stands among passes of a stage that share nothing: the
/// core first, then the scheme, then the modules in registry order, then the
/// core's shared quantities.
fn rank(module: &str) -> usize {
    if module == "core" {
        return 0;
    }
    if module == crate::viscosity::MODULE {
        return usize::MAX;
    }
    match crate::module::all().iter().position(|m| m.id == module) {
        Some(i) => i + 2,
        // A scheme's (or a test's own passes).
        None => 1,
    }
}

/// Whether `first` must run before `then` among a stage's `passes`: it writes what
/// `then` reads or accumulates into, or it accumulates into what `then` reads where
/// a pass of the stage writes it (a sum the stage computes, such as the
/// accelerations). Accumulating into what no pass of the stage writes updates
/// state the step carries (the density a continuity equation integrates): a pass
/// reading it keeps its ranked place, before or after.
fn precedes(first: &PassSpec, then: &PassSpec, passes: &[&PassSpec]) -> bool {
    let computed = |a: &str| passes.iter().any(|p| p.writes.contains(&a));
    let produces = |p: &PassSpec, a: &str| p.writes.contains(&a) || (p.accumulates.contains(&a) && computed(a));
    then.reads.iter().any(|a| produces(first, a) && !produces(then, a))
        || then.accumulates.iter().any(|a| first.writes.contains(a))
}

/// One stage's passes ordered by [`precedes`], each as early as its inputs allow
/// in the ranked order.
fn by_dependencies(mut left: Vec<&'static PassSpec>) -> Result<Vec<&'static PassSpec>, PlanError> {
    let all = left.clone();
    let mut out = Vec::with_capacity(left.len());
    while !left.is_empty() {
        let free = |p: &&PassSpec| !left.iter().any(|q| q.name != p.name && precedes(q, p, &all));
        let Some(i) = left.iter().position(free) else {
            return Err(PlanError::Cycle(left.iter().map(|p| p.name).collect::<Vec<_>>().join(", ")));
        };
        out.push(left.remove(i));
    }
    Ok(out)
}

/// The module of the pass called `name` among `passes`.
fn module_of(passes: &[&'static PassSpec], name: &str) -> &'static str {
    passes.iter().find(|p| p.name == name).map_or("", |p| p.module)
}

/// Why a scene's passes cannot form a plan.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlanError {
    /// Two passes write the same attribute.
    #[error("passes {first} and {second} both write {attr}; one of them must accumulate into it instead")]
    Conflict {
        /// The attribute.
        attr: &'static str,
        /// The pass that writes it first.
        first: &'static str,
        /// The other.
        second: &'static str,
    },
    /// A pass reads an attribute nothing provides.
    #[error("{pass} reads {attr}, which no attribute of this scene holds and no pass of it writes")]
    Missing {
        /// The pass.
        pass: &'static str,
        /// The attribute.
        attr: &'static str,
    },
    /// Passes of one stage each need what another writes first.
    #[error("passes {0} each read what another of them writes; none can run first")]
    Cycle(String),
    /// A pass accumulates into an attribute that no earlier pass writes and the
    /// scene does not hold.
    #[error("{pass} accumulates into {attr} before any pass writes it")]
    Unwritten {
        /// The pass.
        pass: &'static str,
        /// The attribute.
        attr: &'static str,
    },
}

/// The ordered passes of one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    passes: Vec<&'static PassSpec>,
}

impl Plan {
    /// Orders `passes` by stage and by what they read and write (see the module
    /// doc), and checks them against the attributes the scene allocates, `attrs`.
    pub fn build(passes: Vec<&'static PassSpec>, attrs: &[&str]) -> Result<Plan, PlanError> {
        let mut ranked = passes;
        // A stable sort: declaration order within one module's passes of a stage.
        ranked.sort_by_key(|p| (p.stage, rank(p.module)));
        let mut ordered: Vec<&'static PassSpec> = Vec::with_capacity(ranked.len());
        for stage in Stage::ALL {
            let passes: Vec<_> = ranked.iter().copied().filter(|p| p.stage == stage).collect();
            // A solve's passes run in the order its scheme calls them.
            ordered.extend(if stage == Stage::Solve { passes } else { by_dependencies(passes)? });
        }
        let mut writer: Vec<(&'static str, &'static str)> = Vec::new();
        for p in &ordered {
            for &attr in p.writes {
                if let Some(&(_, first)) = writer.iter().find(|(a, _)| *a == attr) {
                    // A solve's passes run in the order its scheme calls them, so two
                    // of one solve may write the same attribute (a warm start and an
                    // iteration both set the increment).
                    let solve = |name: &str| ordered.iter().any(|q| q.name == name && q.stage == Stage::Solve);
                    if !(solve(first) && p.stage == Stage::Solve && p.module == module_of(&ordered, first)) {
                        return Err(PlanError::Conflict { attr, first, second: p.name });
                    }
                }
                writer.push((attr, p.name));
            }
        }
        for (i, p) in ordered.iter().enumerate() {
            for &attr in p.reads {
                let written = writer.iter().any(|(a, _)| *a == attr);
                if !written && !attrs.contains(&attr) {
                    return Err(PlanError::Missing { pass: p.name, attr });
                }
            }
            for &attr in p.accumulates {
                // Into a state attribute the integrator keeps (velocity), or one an
                // earlier pass wrote this step.
                let before = ordered[..i].iter().any(|q| q.writes.contains(&attr));
                if !before && !attrs.contains(&attr) {
                    return Err(PlanError::Unwritten { pass: p.name, attr });
                }
            }
        }
        Ok(Plan { passes: ordered })
    }

    /// Every pass, in order.
    pub fn passes(&self) -> &[&'static PassSpec] {
        &self.passes
    }

    /// The passes of `stage`, in order.
    pub fn stage(&self, stage: Stage) -> impl Iterator<Item = &'static PassSpec> + '_ {
        self.passes.iter().copied().filter(move |p| p.stage == stage)
    }

    /// The pass called `name`.
    pub fn pass(&self, name: &str) -> Option<&'static PassSpec> {
        self.passes.iter().copied().find(|p| p.name == name)
    }

    /// The plan as a table, for `floe plan`.
    pub fn table(&self) -> String {
        let mut out = String::from("stage      pass                       reads -> writes (+ accumulates)\n");
        for p in &self.passes {
            let plus: Vec<String> = p.accumulates.iter().map(|a| format!("+{a}")).collect();
            let writes =
                [p.writes.join(", "), plus.join(", ")].iter().filter(|s| !s.is_empty()).cloned().collect::<Vec<_>>();
            out += &format!("{:<10} {:<26} {} -> {}\n", p.stage.name(), p.name, p.reads.join(", "), writes.join(", "));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const fn pass(
        name: &'static str,
        stage: Stage,
        reads: &'static [&'static str],
        writes: &'static [&'static str],
    ) -> PassSpec {
        PassSpec { name, module: "test", stage, reads, writes, accumulates: &[], tolerance: 0.0 }
    }

    static A: PassSpec = pass("a.force", Stage::Force, &["x"], &["acc"]);
    static B: PassSpec = pass("b.density", Stage::Density, &["x"], &["rho"]);
    static C: PassSpec = pass("c.force", Stage::Force, &["rho"], &["acc"]);
    static D: PassSpec = PassSpec { accumulates: &["acc"], writes: &[], ..pass("d.force", Stage::Force, &["t"], &[]) };
    static E: PassSpec = PassSpec { accumulates: &["acc"], writes: &[], ..pass("e.pre", Stage::PreForce, &[], &[]) };
    static S1: PassSpec = pass("s.warm", Stage::Solve, &["x"], &["inc"]);
    static S2: PassSpec = pass("s.error", Stage::Solve, &["x"], &["inc"]);
    static S3: PassSpec = PassSpec { module: "other", ..pass("o.error", Stage::Solve, &["x"], &["inc"]) };

    #[test]
    fn orders_by_stage_then_declaration() {
        let plan = Plan::build(vec![&A, &B, &D], &["x", "t"]).unwrap();
        let names: Vec<&str> = plan.passes().iter().map(|p| p.name).collect();
        assert_eq!(names, ["b.density", "a.force", "d.force"]);
        assert!(plan.table().contains("force      d.force"));
    }

    static READS_ACC: PassSpec = pass("r.force", Stage::Force, &["acc"], &["out"]);
    static READS_OUT: PassSpec = pass("q.force", Stage::Force, &["out"], &["more"]);
    static LOOP: PassSpec = pass("l.force", Stage::Force, &["more"], &["out2"]);
    static LOOP_BACK: PassSpec = pass("k.force", Stage::Force, &["out2"], &["more"]);

    #[test]
    fn a_pass_follows_what_it_reads_whatever_order_it_was_declared_in() {
        let want = ["a.force", "d.force", "r.force", "q.force"];
        for list in [vec![&READS_OUT, &READS_ACC, &D, &A], vec![&A, &D, &READS_ACC, &READS_OUT]] {
            let plan = Plan::build(list, &["x", "t"]).unwrap();
            let names: Vec<&str> = plan.passes().iter().map(|p| p.name).collect();
            assert_eq!(names, want);
        }
        let e = Plan::build(vec![&LOOP, &LOOP_BACK], &[]).unwrap_err();
        assert_eq!(e.to_string(), "passes l.force, k.force each read what another of them writes; none can run first");
    }

    #[test]
    fn refuses_conflicts_and_missing_inputs_naming_both_sides() {
        let e = Plan::build(vec![&A, &B, &C], &["x"]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "passes a.force and c.force both write acc; one of them must accumulate into it instead"
        );
        let e = Plan::build(vec![&A, &D], &["x"]).unwrap_err();
        assert_eq!(e.to_string(), "d.force reads t, which no attribute of this scene holds and no pass of it writes");
        let e = Plan::build(vec![&E, &A], &["x"]).unwrap_err();
        assert_eq!(e.to_string(), "e.pre accumulates into acc before any pass writes it");
    }

    #[test]
    fn passes_of_one_solve_may_share_an_output() {
        assert!(Plan::build(vec![&S1, &S2], &["x"]).is_ok());
        let e = Plan::build(vec![&S1, &S3], &["x"]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "passes s.warm and o.error both write inc; one of them must accumulate into it instead"
        );
    }
}
