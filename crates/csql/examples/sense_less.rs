//! Measure the levels of `predict_sensing` against the paper's four strategies.
//!
//! ```text
//! cargo run --release -p csql --example sense_less -- [SEEDS] [MAP,MAP,...] [KEY=VALUE ...]
//! ```
//!
//! For every map: the mean sensing cost to convergence of each strategy at each level
//! over seeds 1..=SEEDS (default 10; maps default to `tan8x8`), the ratio of each level's
//! best strategy to the best of the paper's four (level `off`), the runs that converged,
//! and navigation's cost per move and success. `KEY=VALUE` sets a field of
//! `[prediction]` (for example `memory_moves=100`) at the levels that take it (a level
//! that refuses it runs with the defaults, and says so). The weighed level weighs sensing at
//! `[costly] price` = the environment variable `PRICE` (default 0.01 reward units per
//! unit of sensing cost).

use std::sync::Mutex;

use csql::{CostlySettings, PredictSensing, RunReport, RunSettings, Setup, StrategyKind};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let seeds: u64 = args.next().map_or(Ok(10), |s| s.parse())?;
    let maps: Vec<String> = args
        .next()
        .unwrap_or_else(|| "tan8x8".to_string())
        .split(',')
        .map(str::to_string)
        .collect();
    let overrides: Vec<String> = args.collect();
    let price: f64 = std::env::var("PRICE").map_or(Ok(0.01), |p| p.parse())?;
    let toml = format!("[prediction]\n{}", overrides.join("\n"));
    for map in &maps {
        let base = RunSettings::tan1991(map, StrategyKind::Lazy, 1);
        let setup = Setup::new(&base)?;
        let mut jobs = Vec::new();
        for level in PredictSensing::ALL {
            for strategy in StrategyKind::ALL {
                for seed in 1..=seeds {
                    let mut s = RunSettings::tan1991(map, strategy, seed);
                    if let Some(q) = s.cs_ql_mut() {
                        q.predict_sensing = level;
                    }
                    if level == PredictSensing::Weighed {
                        s.costly = Some(CostlySettings::new(price));
                    }
                    // The overrides tune the levels that take them (`memory_moves`: motion).
                    if level != PredictSensing::Off && !overrides.is_empty() {
                        let mut tuned = s.clone();
                        match tuned.apply_toml(&toml, "arguments") {
                            Ok(()) => s = tuned,
                            Err(e) if strategy == StrategyKind::ALL[0] && seed == 1 => {
                                eprintln!("{map}, {level}: the overrides are not applied ({e})");
                            }
                            Err(_) => {}
                        }
                    }
                    jobs.push(s);
                }
            }
        }
        let next = Mutex::new(0usize);
        let results: Mutex<Vec<Option<RunReport>>> = Mutex::new(vec![None; jobs.len()]);
        std::thread::scope(|scope| {
            for _ in 0..2 {
                scope.spawn(|| {
                    loop {
                        let i = {
                            let Ok(mut n) = next.lock() else { return };
                            *n += 1;
                            *n - 1
                        };
                        let Some(job) = jobs.get(i) else { return };
                        let report = csql::run_on(&setup, job).unwrap();
                        if let Ok(mut r) = results.lock() {
                            r[i] = Some(report);
                        }
                    }
                });
            }
        });
        let results = results.into_inner()?;
        let mut best_off = f64::INFINITY;
        println!("## {map} ({seeds} seeds)");
        let states = setup.world.states();
        let distance: f64 = states
            .iter()
            .filter_map(|&s| setup.oracle.distance(s))
            .map(f64::from)
            .sum::<f64>()
            / states.len() as f64;
        println!("mean optimal path: {distance:.2} moves");
        println!(
            "| level | strategy | converged | cost to converge | ratio to best off | skipped | wrong | longest wrong run | nav cost/move | nav success |"
        );
        println!("|---|---|---|---|---|---|---|---|---|---|");
        let mut k = 0;
        for level in PredictSensing::ALL {
            let mut best = f64::INFINITY;
            for strategy in StrategyKind::ALL {
                let runs: Vec<&RunReport> =
                    results[k..k + seeds as usize].iter().flatten().collect();
                k += seeds as usize;
                let n = runs.len() as f64;
                let converged = runs.iter().filter(|r| r.converged).count();
                let cost = runs
                    .iter()
                    .map(|r| r.table1.cost_to_converge.unwrap_or(r.total_cost))
                    .sum::<f64>()
                    / n;
                best = best.min(cost);
                if level == PredictSensing::Off {
                    best_off = best_off.min(cost);
                }
                let mean = |f: &dyn Fn(&RunReport) -> Option<f64>| {
                    runs.iter().filter_map(|r| f(r)).sum::<f64>() / n
                };
                let stats = |f: &dyn Fn(&csql::PredictionStats) -> u64| {
                    runs.iter()
                        .filter_map(|r| r.prediction.as_ref())
                        .map(f)
                        .sum::<u64>() as f64
                        / n
                };
                let longest = runs
                    .iter()
                    .filter_map(|r| r.prediction.map(|p| p.longest_wrong_run))
                    .max()
                    .unwrap_or(0);
                println!(
                    "| {level} | {} | {converged}/{} | {cost:.0} | {:.3} | {:.0} | {:.0} | {longest} | {:.2} | {:.3} |",
                    strategy.name(),
                    runs.len(),
                    cost / best_off,
                    stats(&|p| p.skipped),
                    stats(&|p| p.wrong),
                    mean(&|r| r.navigation_cost_per_move),
                    mean(&|r| r.navigation_success),
                );
            }
            println!("best {level}: {best:.0}, ratio {:.3}", best / best_off);
            let tree: Vec<f64> = results[k - seeds as usize * 4..k]
                .iter()
                .flatten()
                .filter_map(|r| r.table1.tree_cost_per_state)
                .collect();
            let tree = tree.iter().sum::<f64>() / tree.len().max(1) as f64;
            println!(
                "localisation alone: {tree:.2} per trial, {:.2} per move",
                tree / distance
            );
        }
        println!();
    }
    Ok(())
}
