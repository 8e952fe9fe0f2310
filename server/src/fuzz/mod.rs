//! `floe fuzz`: the parsers facing the network and the disk, run on generated and
//! mutated inputs on every core, counting inputs and panics. Coverage-guided fuzzing
//! (cargo fuzz) needs a nightly compiler with sanitizers for its usual mode; this
//! runs anywhere the tests run. A panicking input is written out to replay.
//!
//! - [`targets`]: what is fuzzed, with seeds.
//! - [`mutate`]: how seeds become inputs.

pub mod mutate;
pub mod targets;

use crate::cli::FuzzArgs;
use mutate::{Rng, mutate};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;
pub use targets::Target;

/// Inputs tried and panics found.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Outcome {
    /// Inputs run.
    pub inputs: u64,
    /// Inputs that panicked (each written out when a directory was given).
    pub panics: u64,
}

/// Runs `inputs` inputs of `target` (the seeds themselves first) on `threads` threads,
/// mutations seeded from `seed`; panicking inputs are written to `out` if given.
pub fn fuzz(target: Target, inputs: u64, seed: u64, threads: usize, out: Option<&std::path::Path>) -> Outcome {
    let seeds = target.seeds();
    let (done, panics) = (AtomicU64::new(0), AtomicU64::new(0));
    let run = |data: &[u8]| {
        if std::panic::catch_unwind(|| target.run(data)).is_err() {
            let n = panics.fetch_add(1, Ordering::Relaxed);
            if let Some(dir) = out {
                let path = dir.join(format!("{target:?}-{seed}-{n}.bin").to_lowercase());
                let _ = std::fs::create_dir_all(dir).and_then(|()| std::fs::write(&path, data));
                eprintln!("panic: input written to {}", path.display());
            }
        }
        done.fetch_add(1, Ordering::Relaxed);
    };
    seeds.iter().for_each(|s| run(s));
    let (mutated, threads) = (inputs.saturating_sub(seeds.len() as u64), threads.max(1) as u64);
    std::thread::scope(|scope| {
        for t in 0..threads {
            let run = &run;
            let count = mutated / threads + u64::from(t < mutated % threads);
            scope.spawn(move || {
                let mut rng = Rng::new(seed.wrapping_mul(0x1000_0001).wrapping_add(t));
                for _ in 0..count {
                    run(&mutate(&mut rng, seeds));
                }
            });
        }
    });
    Outcome { inputs: done.into_inner(), panics: panics.into_inner() }
}

/// `floe fuzz` from the command line: a table of inputs, panics and rate per target.
pub fn command(args: FuzzArgs) -> anyhow::Result<()> {
    let targets = if args.targets.is_empty() { Target::ALL.to_vec() } else { args.targets.clone() };
    if let Some(dir) = &args.write_seeds {
        for target in targets {
            let sub = dir.join(format!("{target:?}").to_lowercase());
            std::fs::create_dir_all(&sub)?;
            for (k, seed) in target.seeds().iter().enumerate() {
                std::fs::write(sub.join(format!("seed-{k:03}")), seed)?;
            }
        }
        return Ok(());
    }
    let threads = args.threads.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    println!("| target | inputs | panics | inputs/s |");
    println!("|---|---:|---:|---:|");
    let mut total = Outcome::default();
    for target in targets {
        let t0 = Instant::now();
        let o = fuzz(target, args.inputs, args.seed, threads, args.out.as_deref());
        let rate = o.inputs as f64 / t0.elapsed().as_secs_f64();
        println!("| {target:?} | {} | {} | {rate:.0} |", o.inputs, o.panics);
        total.inputs += o.inputs;
        total.panics += o.panics;
    }
    println!("| all | {} | {} | |", total.inputs, total.panics);
    anyhow::ensure!(total.panics == 0, "{} inputs panicked", total.panics);
    Ok(())
}
