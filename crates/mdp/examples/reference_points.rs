//! The reference points of the costly-sensing benchmark: FrozenLake 4x4 and 8x8 with row
//! and column sensing, three dynamics, two price variants, two sensing menus and two
//! sensing rules. Prints two Markdown tables: the values, then what the policies measure
//! in an episode.
//!
//! ```text
//! cargo run --release -p mdp --example reference_points [-- K [TRIALS]]
//! ```
//!
//! `K` (default 3) bounds the steps in a row after which the agent may be uncertain of
//! the state in the search for the best policy; episodes are capped at Gymnasium's limits
//! (100 moves on 4x4, 200 on 8x8). The open loop keeps at most 2000 plans a step on 4x4
//! and 500 on 8x8 (beyond, its value is a lower bound, shown `>=`).
//!
//! The last columns bracket the optimum of every policy with `mdp::optimum_bounds`,
//! searched until the two bounds are within 0.001 or a budget of trials is spent (20,000
//! on 4x4; on 8x8 `TRIALS`, 300 by default; a bracket the budget stopped is marked
//! `budget`), with the search's trials, the vectors and points it kept, and its wall
//! time on this machine.

use std::process::ExitCode;
use std::time::Instant;

use mdp::{
    BoundOptions, ReferenceError, ReferenceOptions, SensingMenu, SensingModel, SensingRule,
    WorldOptions,
};

/// How far apart the bounds of the optimum may be.
const GAP: f64 = 1e-3;

fn main() -> ExitCode {
    let usage = "usage: reference_points [K [TRIALS]] (K: a whole number of steps; TRIALS: \
                 the most trials of the bounds on 8x8)";
    let k = match std::env::args().nth(1).map(|a| a.parse::<u32>()) {
        None => 3,
        Some(Ok(k)) => k,
        Some(Err(_)) => {
            eprintln!("{usage}");
            return ExitCode::FAILURE;
        }
    };
    let trials = match std::env::args().nth(2).map(|a| a.parse::<usize>()) {
        None => 300,
        Some(Ok(t)) => t,
        Some(Err(_)) => {
            eprintln!("{usage}");
            return ExitCode::FAILURE;
        }
    };
    match table(k, trials) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn table(k: u32, trials_8x8: usize) -> Result<(), Box<dyn std::error::Error>> {
    println!(
        "| world | dynamics | price per coordinate | sensing | rule | free sensing | always measuring | open loop | best (K = {k}) | nodes | ceiling (K = {k}) | optimum | optimum, bounds | trials | vectors / points | seconds |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    // The second table, printed after the first: measurements an episode, whole states
    // where the whole state is measured, coordinates where they are apart.
    let mut sensed = vec![
        String::new(),
        format!(
            "| world | dynamics | price per coordinate | sensing | rule | always measuring | open loop | best (K = {k}) |"
        ),
        "|---|---|---|---|---|---|---|---|".to_string(),
    ];
    let dynamics = [
        ("deterministic", 0.0, 0.0),
        ("semi-slippery", 0.0, 0.5),
        ("slippery", 2.0 / 3.0, 0.0),
    ];
    for (world, horizon, max_plans, max_trials) in [
        ("frozenlake4x4", 100, 2000, 20_000),
        ("frozenlake8x8", 200, 500, trials_8x8),
    ] {
        for (name, slip, slide) in dynamics {
            let mut open = None;
            let mut free_cache = None;
            for price in [0.025, 0.05] {
                let lake = mdp::builtin_world(
                    world,
                    &WorldOptions {
                        slip: Some(slip),
                        slide: Some(slide),
                        sensing: Some(SensingModel::Factors),
                        factor_costs: Some(vec![price, price]),
                    },
                )?;
                let options = ReferenceOptions {
                    horizon,
                    max_uncertain: Some(k),
                    ..ReferenceOptions::default()
                };
                let open_loop = match open {
                    Some(o) => o,
                    None => {
                        let o = mdp::open_loop(
                            &lake,
                            &ReferenceOptions {
                                max_plans,
                                ..options
                            },
                        )?;
                        open = Some(o);
                        o
                    }
                };
                let free = match free_cache {
                    Some(c) => c,
                    None => {
                        let c = mdp::free_sensing(&lake, &options)?;
                        free_cache = Some(c);
                        c
                    }
                };
                let open_text = if open_loop.exact {
                    format!("{:.4}", open_loop.value)
                } else {
                    format!(">= {:.4}", open_loop.value)
                };
                for (menu, menu_name) in [
                    (SensingMenu::whole(&lake), "whole state"),
                    (SensingMenu::Features, "row, column apart"),
                ] {
                    for rule in [SensingRule::WithMove, SensingRule::AfterOutcome] {
                        let always = mdp::always_measuring(&lake, menu, rule, &options)?;
                        let always_sensed =
                            mdp::always_measuring_sensing(&lake, menu, rule, &options)?;
                        let (best, best_text, nodes, best_sensed) =
                            match mdp::best_sensing(&lake, menu, rule, &options) {
                                Ok(b) => (
                                    b.value,
                                    format!("{:.4}", b.value),
                                    b.beliefs.to_string(),
                                    format!("{:.2}", b.sensing),
                                ),
                                Err(e @ ReferenceError::TooManyBeliefs { .. }) => (
                                    f64::NEG_INFINITY,
                                    "refused".to_string(),
                                    format!("({e})"),
                                    "refused".to_string(),
                                ),
                                Err(e) => return Err(e.into()),
                            };
                        sensed.push(format!(
                            "| {world} | {name} | {price} | {menu_name} | {} | {always_sensed:.2} | 0 | {best_sensed} |",
                            rule.name(),
                        ));
                        let ceiling = match mdp::sensing_ceiling(&lake, menu, rule, &options) {
                            Ok(b) => b.value.min(free),
                            Err(ReferenceError::TooManyBeliefs { .. }) => free,
                            Err(e) => return Err(e.into()),
                        };
                        // Every reference point is a policy's value, so the best of them
                        // is a lower bound of the optimum; where it meets the ceiling it
                        // is the optimum.
                        let known = always.max(open_loop.value).max(best);
                        let known_text = if known >= ceiling - 1e-9 {
                            format!("**{known:.4}**")
                        } else {
                            format!("{known:.4} to {ceiling:.4}")
                        };
                        let bound_options = BoundOptions {
                            horizon,
                            gap: GAP,
                            max_trials,
                            ..BoundOptions::default()
                        };
                        let started = Instant::now();
                        let b = mdp::optimum_bounds(&lake, menu, rule, &bound_options)?;
                        let seconds = started.elapsed().as_secs_f64();
                        let stopped = if b.converged { "" } else { " (budget)" };
                        println!(
                            "| {world} | {name} | {price} | {menu_name} | {} | {free:.4} | {always:.4} | {open_text} | {best_text} | {nodes} | {ceiling:.4} | {known_text} | {:.4} to {:.4}{stopped} | {} | {} / {} | {seconds:.1} |",
                            rule.name(),
                            b.lower,
                            b.upper,
                            b.trials,
                            b.vectors,
                            b.points,
                        );
                    }
                }
            }
        }
    }
    for line in sensed {
        println!("{line}");
    }
    Ok(())
}
