//! The bounds of the optimum of every policy on one FrozenLake configuration of the
//! costly-sensing benchmark (`reference_points` prints them for all at a gap of 0.001),
//! to a gap and a budget of trials given here.
//!
//! ```text
//! cargo run --release -p mdp --example optimum_bounds -- WORLD DYNAMICS PRICE MENU RULE GAP TRIALS
//! cargo run --release -p mdp --example optimum_bounds -- frozenlake4x4 slippery 0.025 whole with-move 0.0001 50000
//! ```
//!
//! `WORLD`: `frozenlake4x4` (100 moves an episode) or `frozenlake8x8` (200); `DYNAMICS`:
//! `deterministic`, `semi-slippery` or `slippery`; `PRICE`: the price of a coordinate
//! (row or column); `MENU`: `whole` (both at once) or `apart`; `RULE`: `with-move` or
//! `after-outcome`. Prints the two bounds, whether they met within the gap, the trials,
//! the vectors and points kept, and the wall time.

use std::process::ExitCode;
use std::time::Instant;

use mdp::{BoundOptions, SensingMenu, SensingModel, SensingRule, WorldOptions};

const USAGE: &str = "usage: optimum_bounds WORLD DYNAMICS PRICE MENU RULE GAP TRIALS \
    (frozenlake4x4|frozenlake8x8, deterministic|semi-slippery|slippery, a price, whole|apart, \
    with-move|after-outcome, a gap, a number of trials)";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}\n{USAGE}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &[String]) -> Result<(), Box<dyn std::error::Error>> {
    let [world, dynamics, price, menu, rule, gap, trials] = args else {
        return Err(format!("{} arguments, 7 wanted", args.len()).into());
    };
    let horizon = match world.as_str() {
        "frozenlake4x4" => 100,
        "frozenlake8x8" => 200,
        other => return Err(format!("unknown world {other}").into()),
    };
    let (slip, slide) = match dynamics.as_str() {
        "deterministic" => (0.0, 0.0),
        "semi-slippery" => (0.0, 0.5),
        "slippery" => (2.0 / 3.0, 0.0),
        other => return Err(format!("unknown dynamics {other}").into()),
    };
    let price: f64 = price.parse()?;
    let lake = mdp::builtin_world(
        world,
        &WorldOptions {
            slip: Some(slip),
            slide: Some(slide),
            sensing: Some(SensingModel::Factors),
            factor_costs: Some(vec![price, price]),
        },
    )?;
    let menu = match menu.as_str() {
        "whole" => SensingMenu::whole(&lake),
        "apart" => SensingMenu::Features,
        other => return Err(format!("unknown menu {other}").into()),
    };
    let rule = match rule.as_str() {
        "with-move" => SensingRule::WithMove,
        "after-outcome" => SensingRule::AfterOutcome,
        other => return Err(format!("unknown rule {other}").into()),
    };
    let options = BoundOptions {
        horizon,
        gap: gap.parse()?,
        max_trials: trials.parse()?,
        ..BoundOptions::default()
    };
    let started = Instant::now();
    let b = mdp::optimum_bounds(&lake, menu, rule, &options)?;
    let seconds = started.elapsed().as_secs_f64();
    println!(
        "lower {:.6} upper {:.6} {} trials {} vectors {} points {} (states {}) seconds {seconds:.1}",
        b.lower,
        b.upper,
        if b.converged {
            "met"
        } else {
            "stopped by the budget"
        },
        b.trials,
        b.vectors,
        b.points,
        b.point_states,
    );
    Ok(())
}
