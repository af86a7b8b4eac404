//! Every built-in world and every built-in map, learned by CS-QL with every strategy from
//! its defaults: the settings a run gets from the world's name, the strategy and the seed
//! alone (as `csrl run --world NAME --strategy S --seed N` has them; the built-in worlds'
//! own temperature, detector and trial cap where they ask for them, the paper's values
//! otherwise). Prints a Markdown table: per world and strategy, the runs that converged,
//! the lowest final policy quality, the trials and moves (mean and most), and the wall
//! time of the slowest run.
//!
//! `cargo run --release -p csql --example world_defaults -- [SEEDS]`
//!
//! SEEDS (default 5) runs seeds 1 to SEEDS, two runs at a time.

use std::time::Instant;

use csql::{RunReport, SettingsDraft, StrategyKind};

fn main() -> Result<(), csql::Error> {
    let seeds: u64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(5);
    println!(
        "| world | strategy | temperature | detector | max_trials | converged | lowest quality | trials, mean | trials, most | moves, mean | moves, most | slowest run (s) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    let worlds = mdp::builtin_world_names()
        .iter()
        .copied()
        .chain(mdp::builtin_names());
    for world in worlds {
        for strategy in StrategyKind::ALL {
            let settings = (1..=seeds)
                .map(|seed| {
                    SettingsDraft {
                        map: Some(world.into()),
                        strategy: Some(strategy),
                        seed: Some(seed),
                        ..SettingsDraft::default()
                    }
                    .build()
                })
                .collect::<Result<Vec<_>, _>>()?;
            let timed = |s: &csql::RunSettings| {
                let start = Instant::now();
                csql::run(s).map(|r| (r, start.elapsed().as_secs_f64()))
            };
            let runs: Vec<(RunReport, f64)> = std::thread::scope(|scope| {
                let halves: Vec<_> = settings
                    .chunks(settings.len().div_ceil(2).max(1))
                    .map(|part| scope.spawn(move || part.iter().map(timed).collect::<Vec<_>>()))
                    .collect();
                halves
                    .into_iter()
                    .flat_map(|h| h.join().unwrap_or_default())
                    .collect::<Result<Vec<_>, _>>()
            })?;
            let n = runs.len().max(1) as f64;
            let s = &settings[0];
            let trials: Vec<f64> = runs.iter().map(|(r, _)| f64::from(r.trials)).collect();
            let moves: Vec<f64> = runs.iter().map(|(r, _)| r.moves as f64).collect();
            let most = |xs: &[f64]| xs.iter().copied().fold(0.0, f64::max);
            println!(
                "| {world} | {strategy} | {} | {} | {} | {}/{} | {:.3} | {:.0} | {:.0} | {:.0} | {:.0} | {:.1} |",
                s.temperature.get(),
                s.extensions().detector.name(),
                s.max_trials.get(),
                runs.iter().filter(|(r, _)| r.converged).count(),
                runs.len(),
                runs.iter()
                    .map(|(r, _)| r.quality.policy_quality)
                    .fold(f64::INFINITY, f64::min),
                trials.iter().sum::<f64>() / n,
                most(&trials),
                moves.iter().sum::<f64>() / n,
                most(&moves),
                runs.iter().map(|(_, t)| *t).fold(0.0, f64::max),
            );
            for (r, _) in &runs {
                if let Some(not) = &r.not_learned {
                    eprintln!("{world} {strategy} seed {}: {}", r.seed, not.why);
                }
            }
        }
    }
    Ok(())
}
