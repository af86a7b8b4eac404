//! CS-QL, U-Tree and full sensing on the built-in worlds beyond grid maps: for each
//! world, sensing model and dynamics, how many seeds reach the criterion (the oracle's
//! convergence in a deterministic world, policy quality 0.95 kept otherwise), at what
//! sensing cost and after how many trials, and what was learned (descriptions, features
//! per description, sensing per state after learning). Prints a Markdown table.
//!
//! `cargo run --release -p csql --example worlds -- [SEEDS] [NAME-PART]`
//!
//! SEEDS (default 5) runs each configuration with seeds 1 to SEEDS, two at a time;
//! NAME-PART keeps the rows whose world, sensing or dynamics contains it.

use csql::{LearnerKind, RunReport, RunSettings, StrategyKind};

/// One row of the table: a world, its `[world]` settings, extra top-level settings.
struct Config {
    world: &'static str,
    sensing: &'static str,
    dynamics: &'static str,
    toml: String,
}

fn configs() -> Vec<Config> {
    let mut out = Vec::new();
    for world in ["frozenlake4x4", "frozenlake8x8", "cliffwalking"] {
        for sensing in ["local", "factors"] {
            out.push(Config {
                world,
                sensing,
                dynamics: "deterministic",
                toml: format!("[world]\nsensing = \"{sensing}\""),
            });
        }
    }
    out.push(Config {
        world: "taxi",
        sensing: "factors",
        dynamics: "deterministic",
        toml: String::new(),
    });
    for (dynamics, world) in [
        ("slip 2/3", "slip = 0.6666666666666666"),
        ("slide 0.5", "slide = 0.5"),
    ] {
        for sensing in ["local", "factors"] {
            out.push(Config {
                world: "frozenlake4x4",
                sensing,
                dynamics,
                toml: format!(
                    "beta = 0.2\nmax_trials = 3000\n[world]\nsensing = \"{sensing}\"\n{world}\n[extensions]\nquality_every = 25"
                ),
            });
        }
    }
    out
}

fn learners() -> Vec<(&'static str, LearnerKind, StrategyKind)> {
    let mut out: Vec<_> = StrategyKind::ALL
        .iter()
        .map(|&k| (k.name(), LearnerKind::CsQl, k))
        .collect();
    out.push(("u-tree", LearnerKind::UTree, StrategyKind::Lazy));
    out.push(("full sensing", LearnerKind::FullSensing, StrategyKind::Lazy));
    out
}

/// Whether a run reached its criterion, and the trials and cost until then.
fn reached(r: &RunReport) -> Option<(u32, f64)> {
    match &r.quality {
        Some(q) => q.trials_to_quality.zip(q.cost_to_quality),
        None => r.table1.trials_to_converge.zip(r.table1.cost_to_converge),
    }
}

fn mean(xs: &[f64]) -> String {
    if xs.is_empty() {
        "-".to_string()
    } else {
        let m = xs.iter().sum::<f64>() / xs.len() as f64;
        if m >= 100.0 {
            format!("{m:.0}")
        } else {
            format!("{m:.2}")
        }
    }
}

fn main() -> Result<(), csql::Error> {
    let args: Vec<String> = std::env::args().collect();
    let seeds: u64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(5);
    let only = args.get(2).cloned();
    println!(
        "| world | sensing | dynamics | learner | reached | trials | sensing cost until then | descriptions | features each | sensing per state after |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for c in configs() {
        let name = format!("{} {} {}", c.world, c.sensing, c.dynamics);
        if only.as_ref().is_some_and(|o| !name.contains(o.as_str())) {
            continue;
        }
        for (label, learner, strategy) in learners() {
            let settings: Vec<RunSettings> = (1..=seeds)
                .map(|seed| {
                    let mut s = RunSettings::tan1991(c.world, strategy, seed);
                    s.apply_toml(&c.toml, "worlds example")?;
                    s.learner = learner;
                    s.validate()?;
                    Ok(s)
                })
                .collect::<Result<_, csql::Error>>()?;
            let reports: Vec<RunReport> = std::thread::scope(|scope| {
                let halves: Vec<_> = settings
                    .chunks(settings.len().div_ceil(2).max(1))
                    .map(|part| scope.spawn(move || part.iter().map(csql::run).collect::<Vec<_>>()))
                    .collect();
                halves
                    .into_iter()
                    .flat_map(|h| h.join().unwrap_or_default())
                    .collect::<Result<Vec<_>, _>>()
            })?;
            let hits: Vec<(u32, f64)> = reports.iter().filter_map(reached).collect();
            let done: Vec<&RunReport> = reports.iter().filter(|r| reached(r).is_some()).collect();
            let per_state = |r: &RunReport| match &r.quality {
                Some(q) => Some(q.sensing_cost_per_state),
                None => r.table1.tree_cost_per_state,
            };
            println!(
                "| {} | {} | {} | {} | {}/{} | {} | {} | {} | {} | {} |",
                c.world,
                c.sensing,
                c.dynamics,
                label,
                hits.len(),
                reports.len(),
                mean(&hits.iter().map(|h| f64::from(h.0)).collect::<Vec<_>>()),
                mean(&hits.iter().map(|h| h.1).collect::<Vec<_>>()),
                mean(
                    &done
                        .iter()
                        .map(|r| r.descriptions.len() as f64)
                        .collect::<Vec<_>>()
                ),
                mean(
                    &done
                        .iter()
                        .map(|r| {
                            let n = r.descriptions.len().max(1) as f64;
                            r.descriptions
                                .iter()
                                .map(|d| d.features.len())
                                .sum::<usize>() as f64
                                / n
                        })
                        .collect::<Vec<_>>()
                ),
                mean(&done.iter().filter_map(|r| per_state(r)).collect::<Vec<_>>()),
            );
        }
    }
    Ok(())
}
