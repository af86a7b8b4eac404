//! Throughput of Boltzmann Q-learning on an open 8 by 8 room.
//!
//! ```text
//! cargo run --release -p qlearn --example grid_throughput -- STEPS [--reference]
//! ```
//!
//! Runs the paper's setting (beta 1, gamma 0.9, T 0.4, 100-move trials) from the
//! top-left corner towards the goal in the bottom-right corner for STEPS moves, with a
//! fixed seed, and prints one line: `steps=... steps_per_sec=... sum_q=...`, where
//! `sum_q` is the sum of every Q entry at the end. `--reference` runs the minimal
//! hand-written loop of the benchmark instead; both print the same `sum_q`.

use std::process::ExitCode;
use std::time::Instant;

use mdp::{GridWorld, Pos};
use qlearn::{Params, QLearner, Start};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

#[path = "../benches/support/reference.rs"]
mod reference;

/// The seed of every run, so that runs are comparable.
const SEED: u64 = 1991;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let reference = args.iter().any(|a| a == "--reference");
    let numbers: Vec<&String> = args.iter().filter(|a| *a != "--reference").collect();
    let steps = match numbers.as_slice() {
        [n] => match n.replace('_', "").parse::<u64>() {
            Ok(n) => n,
            Err(e) => return usage(&format!("STEPS must be a whole number ({e}): {n}")),
        },
        _ => return usage("expected exactly one STEPS argument"),
    };
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(SEED);
    let (seconds, sum_q) = if reference {
        let clock = Instant::now();
        let q = reference::run(steps, &mut rng);
        (clock.elapsed().as_secs_f64(), q.iter().sum::<f64>())
    } else {
        let Some(map) = mdp::builtin("open8x8") else {
            eprintln!("error: the built-in map open8x8 is missing");
            return ExitCode::FAILURE;
        };
        let world = GridWorld::new(&map);
        let Some(start) = world.state_at(Pos::new(0, 0)) else {
            eprintln!("error: the top-left corner of open8x8 is not free");
            return ExitCode::FAILURE;
        };
        let mut learner = match QLearner::new(&world, Params::tan1991(), Start::Fixed(start)) {
            Ok(l) => l,
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::FAILURE;
            }
        };
        let clock = Instant::now();
        learner.run_steps(steps, &mut rng);
        let seconds = clock.elapsed().as_secs_f64();
        (seconds, learner.table().q_values().iter().sum::<f64>())
    };
    println!(
        "steps={steps} steps_per_sec={:.0} sum_q={sum_q:.6}",
        steps as f64 / seconds.max(1e-9)
    );
    ExitCode::SUCCESS
}

fn usage(problem: &str) -> ExitCode {
    eprintln!("error: {problem}");
    eprintln!("usage: grid_throughput STEPS [--reference]");
    ExitCode::from(2)
}
