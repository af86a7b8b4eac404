//! CS-QL, U-Tree and full sensing on the built-in worlds beyond grid maps, every learner
//! on the same two criteria side by side: for each world, sensing model and dynamics, how
//! many seeds the oracle judged converged (in a deterministic world; such a run ends
//! there) and how many reached policy quality 0.95 and kept it, at what sensing cost and
//! after how many trials, and what was learned (descriptions, features per description,
//! what a state costs after learning classified by a decision tree over the final
//! descriptions, Table 1's row 8, and by the learner's own classification). Prints a
//! Markdown table.
//!
//! `cargo run --release -p csql --example worlds -- [SEEDS] [NAME-PART]`
//!
//! Deterministic worlds use the paper's settings, and CS-QL on Taxi and CliffWalking the
//! detector `action` (specification 1.11); those two are run at the paper's temperature
//! and at one scaled to their rewards. On the slippery and sliding lakes every
//! learner has beta 0.02 (a constant step that averages the random outcomes), 20000
//! trials and a quality evaluation every 100 trials, and CS-QL the statistical detector.
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
    for world in ["frozenlake4x4", "frozenlake8x8"] {
        for sensing in ["local", "factors"] {
            out.push(Config {
                world,
                sensing,
                dynamics: "deterministic",
                toml: format!("[world]\nsensing = \"{sensing}\""),
            });
        }
    }
    // Rewards of -100 to -1 and -10 to 20: the paper's temperature (0.4, for rewards of
    // size 1), and one scaled to the world's largest reward (0.4 times it).
    for (world, sensings, scaled) in [
        ("cliffwalking", &["local", "factors"][..], 40.0),
        ("taxi", &["factors"][..], 8.0),
    ] {
        for &sensing in sensings {
            out.push(Config {
                world,
                sensing,
                dynamics: "deterministic, T 0.4",
                toml: format!("[world]\nsensing = \"{sensing}\""),
            });
            out.push(Config {
                world,
                sensing,
                dynamics: if scaled == 8.0 {
                    "deterministic, T 8"
                } else {
                    "deterministic, T 40"
                },
                toml: format!("temperature = {scaled}\n[world]\nsensing = \"{sensing}\""),
            });
        }
    }
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
                    "beta = 0.02\nmax_trials = 20000\n[world]\nsensing = \"{sensing}\"\n{world}\n[judge]\nquality_every = 100"
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

/// The trials and cost until the oracle's convergence, if the run got there.
fn converged(r: &RunReport) -> Option<(u32, f64)> {
    r.table1.trials_to_converge.zip(r.table1.cost_to_converge)
}

/// The trials and cost until the policy quality reached 0.95 and stayed there.
fn kept_quality(r: &RunReport) -> Option<(u32, f64)> {
    r.quality.trials_to_quality.zip(r.quality.cost_to_quality)
}

/// `hits/runs`, mean trials and mean cost of the runs that got there (`-` when none did);
/// all three `-` where the criterion does not apply.
fn criterion(
    reports: &[RunReport],
    applies: bool,
    of: fn(&RunReport) -> Option<(u32, f64)>,
) -> String {
    if !applies {
        return "- | - | -".to_string();
    }
    let hits: Vec<(u32, f64)> = reports.iter().filter_map(of).collect();
    format!(
        "{}/{} | {} | {}",
        hits.len(),
        reports.len(),
        mean(&hits.iter().map(|h| f64::from(h.0)).collect::<Vec<_>>()),
        mean(&hits.iter().map(|h| h.1).collect::<Vec<_>>()),
    )
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
        "| world | sensing | dynamics | learner | converged | trials | sensing cost until then | quality 0.95 kept | trials | sensing cost until then | descriptions | features each | per state, decision tree | per state, own classification |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
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
                    if learner != LearnerKind::CsQl {
                        s = s.with_learner(learner);
                    }
                    if let Some(q) = s.cs_ql_mut() {
                        if !c.dynamics.starts_with("deterministic") {
                            // A single decrease is noise where moves are random: ask the
                            // statistical detector for evidence (specification 6.8).
                            q.extensions.detector = csql::DetectorKind::Statistical;
                        }
                        if ["taxi", "cliffwalking"].contains(&c.world) {
                            // Penalties for one state of a description fall on Q, not V
                            // (specification 1.11).
                            q.extensions.detector = csql::DetectorKind::Action;
                        }
                    }
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
            // What was learned, over the runs that met either criterion.
            let done: Vec<&RunReport> = reports
                .iter()
                .filter(|r| converged(r).is_some() || kept_quality(r).is_some())
                .collect();
            println!(
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                c.world,
                c.sensing,
                c.dynamics,
                label,
                // The oracle judges only deterministic worlds.
                criterion(
                    &reports,
                    reports.iter().any(|r| r.judged_by == csql::Judging::Oracle),
                    converged
                ),
                criterion(&reports, true, kept_quality),
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
                mean(
                    &done
                        .iter()
                        .filter_map(|r| r.table1.tree_cost_per_state)
                        .collect::<Vec<_>>()
                ),
                mean(
                    &done
                        .iter()
                        .map(|r| r.quality.learner_cost_per_state)
                        .collect::<Vec<_>>()
                ),
            );
        }
    }
    Ok(())
}
