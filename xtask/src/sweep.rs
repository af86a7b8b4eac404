//! `cargo xtask sweep` and `cargo xtask merge`: a grid of maps and strategies, cut into
//! shards that can run on different machines, and the merge of their outputs.
//!
//! The job list is built in a fixed order (map, then strategy, then run) and numbered
//! from 0; run `i` uses seed `S + i`. Shards, resuming and merging are those of
//! [`crate::shard`].

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use csql::{RunSettings, Setup, StrategyKind, Table1};
use mdp::Map;
use serde::{Deserialize, Serialize};

use crate::shard::JobLine;
use crate::stats::Summary;

/// Arguments of `cargo xtask sweep`.
#[derive(Args, Clone, Debug)]
pub struct SweepArgs {
    /// Maps, comma-separated: built-in names, map files, `random:WxH:DENSITY:SEED`, or
    /// `MAP@ROW:COL` for a map with its goal moved to (ROW, COL).
    #[arg(long, value_delimiter = ',', required = true)]
    maps: Vec<String>,
    /// Strategies, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "resetting,lazy,random,eager"
    )]
    strategies: Vec<StrategyKind>,
    /// Runs per map and strategy.
    #[arg(long, default_value_t = 5)]
    runs: u64,
    /// Base seed: run i uses seed S + i.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Trial cap of each run.
    #[arg(long, default_value_t = 20_000)]
    max_trials: u32,
    /// This machine's shard, `K/N` (K from 1 to N).
    #[arg(long, default_value = "1/1")]
    shard: String,
    /// Worker threads (default: every core).
    #[arg(long)]
    threads: Option<usize>,
    /// Output folder (shared by all shards).
    #[arg(long)]
    out: PathBuf,
}

/// Arguments of `cargo xtask merge`.
#[derive(Args, Clone, Debug)]
pub struct MergeArgs {
    /// Folders holding shard outputs (`shard-K-of-N` folders, or folders of them).
    #[arg(required = true)]
    dirs: Vec<PathBuf>,
    /// Where to write `sweep.md` and `sweep.csv`.
    #[arg(long, default_value = "results/sweep")]
    out: PathBuf,
}

/// What a sweep is: shards of the same sweep must agree on it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct Definition {
    maps: Vec<String>,
    strategies: Vec<StrategyKind>,
    runs: u64,
    seed: u64,
    max_trials: u32,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
struct JobResult {
    id: u64,
    map: String,
    strategy: StrategyKind,
    seed: u64,
    states: usize,
    converged: bool,
    trials: u32,
    table1: Table1Row,
}

/// The Table 1 measures, in a form that reads back from JSON.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
struct Table1Row {
    cost_to_sufficient: Option<f64>,
    trials_to_sufficient: Option<u32>,
    cost_to_converge: Option<f64>,
    trials_to_converge: Option<u32>,
    descriptions: Option<usize>,
    mean_features: Option<f64>,
    max_features: Option<usize>,
    tree_cost_per_state: Option<f64>,
    description_cost_per_state: Option<f64>,
}

impl From<&Table1> for Table1Row {
    fn from(t: &Table1) -> Self {
        Table1Row {
            cost_to_sufficient: t.cost_to_sufficient,
            trials_to_sufficient: t.trials_to_sufficient,
            cost_to_converge: t.cost_to_converge,
            trials_to_converge: t.trials_to_converge,
            descriptions: t.descriptions,
            mean_features: t.mean_features,
            max_features: t.max_features,
            tree_cost_per_state: t.tree_cost_per_state,
            description_cost_per_state: t.description_cost_per_state,
        }
    }
}

impl JobLine for JobResult {
    fn id(&self) -> u64 {
        self.id
    }
}

/// Job `id` of a sweep with `strategies` strategies and `runs` runs per map and strategy:
/// (map, strategy, run) as indices, in the order map, then strategy, then run.
fn job_of(id: u64, strategies: u64, runs: u64) -> (u64, u64, u64) {
    let per_map = strategies * runs;
    let rest = id % per_map;
    (id / per_map, rest / runs, rest % runs)
}

/// `cargo xtask sweep`.
pub fn sweep(args: &SweepArgs) -> Result<()> {
    if args.runs == 0 || args.strategies.is_empty() {
        bail!("a sweep needs --runs >= 1 and at least one strategy");
    }
    crate::files::seeds(args.seed, args.runs)?;
    crate::files::distinct("--maps", &args.maps)?;
    crate::files::distinct("--strategies", &args.strategies)?;
    let maps: Vec<Map> = args
        .maps
        .iter()
        .map(|m| mdp::resolve(m))
        .collect::<Result<_, _>>()?;
    crate::files::distinct_maps(&args.maps, &maps)?;
    let definition = Definition {
        maps: args.maps.clone(),
        strategies: args.strategies.clone(),
        runs: args.runs,
        seed: args.seed,
        max_trials: args.max_trials,
    };
    // Jobs in order (map, then strategy, then run), found from their number: never listed.
    let per_map = (args.strategies.len() as u64)
        .checked_mul(args.runs)
        .context("--runs times the strategies is more jobs than can be numbered")?;
    let total = (maps.len() as u64)
        .checked_mul(per_map)
        .context("--runs times the maps and strategies is more jobs than can be numbered")?;
    let job = |id: u64| {
        let (m, s, run) = job_of(id, args.strategies.len() as u64, args.runs);
        (m as usize, args.strategies[s as usize], run)
    };
    let setups: Vec<Setup> = maps
        .iter()
        .map(|m| {
            let s = RunSettings::tan1991(m.name(), StrategyKind::Resetting, 0);
            Setup::for_map(m.clone(), &s)
        })
        .collect::<Result<_, _>>()?;
    let cap = csql::TrialCap::new(args.max_trials)?;
    crate::shard::run_shard(
        &args.out,
        &args.shard,
        definition,
        total,
        args.threads,
        |_| 1.0,
        |id| {
            let (m, strategy, run) = job(id);
            let mut settings = RunSettings::tan1991(&args.maps[m], strategy, args.seed + run);
            settings.max_trials = cap;
            let report = csql::run_on(&setups[m], &settings)?;
            Ok(JobResult {
                id,
                map: args.maps[m].clone(),
                strategy,
                seed: settings.seed,
                states: setups[m].map.states().len(),
                converged: report.converged,
                trials: report.trials,
                table1: Table1Row::from(&report.table1),
            })
        },
    )
}

/// `cargo xtask merge`.
pub fn merge(args: &MergeArgs) -> Result<()> {
    let (definition, by_id): (Definition, BTreeMap<u64, JobResult>) =
        crate::shard::collect(&args.dirs)?;
    let total = by_id.len();
    let mut md = String::from("# Sweep\n\n");
    let _ = writeln!(
        md,
        "{} runs per map and strategy, seeds {}..={}, trial cap {}. Mean ± sd [min–max] over converged runs.\n",
        definition.runs,
        definition.seed,
        definition.seed + definition.runs - 1,
        definition.max_trials
    );
    md.push_str("| map | states | strategy | converged | trials to convergence | cost to convergence | descriptions | mean features | max features | tree cost/state |\n|---|---|---|---|---|---|---|---|---|---|\n");
    let mut csv = String::from(
        "map,states,strategy,runs,converged,trials_mean,cost_mean,descriptions_mean,mean_features_mean,max_features_mean,tree_cost_mean\n",
    );
    for map in &definition.maps {
        for &k in &definition.strategies {
            let rs: Vec<&JobResult> = by_id
                .values()
                .filter(|r| &r.map == map && r.strategy == k)
                .collect();
            let conv: Vec<&JobResult> = rs.iter().copied().filter(|r| r.converged).collect();
            let col = |f: fn(&Table1Row) -> Option<f64>| {
                Summary::of(&conv.iter().filter_map(|r| f(&r.table1)).collect::<Vec<_>>())
            };
            let cols = [
                col(|t| t.trials_to_converge.map(f64::from)),
                col(|t| t.cost_to_converge),
                col(|t| t.descriptions.map(|x| x as f64)),
                col(|t| t.mean_features),
                col(|t| t.max_features.map(|x| x as f64)),
                col(|t| t.tree_cost_per_state),
            ];
            let decimals = [1, 0, 1, 2, 1, 2];
            let states = rs.first().map_or(0, |r| r.states);
            let _ = write!(
                md,
                "| {map} | {states} | {k} | {}/{} |",
                conv.len(),
                rs.len()
            );
            let _ = write!(csv, "\"{map}\",{states},{k},{},{}", rs.len(), conv.len());
            for (c, d) in cols.iter().zip(decimals) {
                let _ = write!(md, " {} |", c.map_or("—".to_string(), |s| s.show(d)));
                let _ = write!(
                    csv,
                    ",{}",
                    c.map_or(String::new(), |s| format!("{:.6}", s.mean))
                );
            }
            md.push('\n');
            csv.push('\n');
        }
    }
    crate::files::create_dir(&args.out)?;
    let _lock = crate::files::OutLock::acquire(&args.out)?;
    crate::files::write_atomic(&args.out.join("sweep.md"), &md)?;
    crate::files::write_atomic(&args.out.join("sweep.csv"), &csv)?;
    crate::emit(&format!(
        "{md}\nMerged {total} jobs: {}\n",
        args.out.join("sweep.md").display()
    ))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn result(id: u64) -> String {
        let r = JobResult {
            id,
            map: "m".into(),
            strategy: StrategyKind::Lazy,
            seed: 1,
            states: 3,
            converged: true,
            trials: 2,
            table1: Table1Row::default(),
        };
        serde_json::to_string(&r).unwrap()
    }

    #[test]
    fn jobs_are_numbered_in_the_order_of_the_nested_loops() {
        let (maps, strategies, runs) = (3, 4, 5);
        let mut id = 0;
        for m in 0..maps {
            for s in 0..strategies {
                for run in 0..runs {
                    assert_eq!(job_of(id, strategies, runs), (m, s, run));
                    id += 1;
                }
            }
        }
    }

    #[test]
    fn one_shard_of_a_huge_sweep_runs_its_own_job_only() {
        // Once: 4 * 10^8 jobs were listed (gigabytes) to run one.
        let dir = tempfile::tempdir().unwrap();
        let args = SweepArgs {
            maps: vec!["tan3x3".into()],
            strategies: vec![StrategyKind::Lazy],
            runs: u64::MAX,
            seed: 0,
            max_trials: 50,
            shard: format!("{}/{}", u64::MAX, u64::MAX),
            threads: Some(1),
            out: dir.path().to_path_buf(),
        };
        sweep(&args).unwrap();
        let shard = dir.path().join(format!("shard-{0}-of-{0}", u64::MAX));
        let text = std::fs::read_to_string(shard.join("results.jsonl")).unwrap();
        let r: JobResult = serde_json::from_str(text.trim()).unwrap();
        assert_eq!((r.id, r.seed), (u64::MAX - 1, u64::MAX - 1));
        // A shard of more jobs than a shard may run is refused before anything runs.
        let err = sweep(&SweepArgs {
            shard: "1/1".into(),
            ..args.clone()
        })
        .err()
        .unwrap()
        .to_string();
        assert!(err.contains("at most"), "{err}");
        // More jobs than can be numbered is refused.
        let err = sweep(&SweepArgs {
            strategies: vec![StrategyKind::Lazy, StrategyKind::Eager],
            ..args
        })
        .err()
        .unwrap()
        .to_string();
        assert!(err.contains("more jobs than can be numbered"), "{err}");
    }

    #[test]
    fn merge_refuses_a_corrupt_line_and_names_it() {
        let dir = tempfile::tempdir().unwrap();
        let shard = dir.path().join("shard-1-of-1");
        std::fs::create_dir_all(&shard).unwrap();
        let manifest = crate::shard::Manifest {
            sweep: Definition {
                maps: vec!["m".into()],
                strategies: vec![StrategyKind::Lazy],
                runs: 2,
                seed: 1,
                max_trials: 10,
            },
            shard: 1,
            shards: 1,
            total_jobs: 2,
            job_ids: vec![0, 1],
        };
        std::fs::write(
            shard.join("manifest.json"),
            serde_json::to_string(&manifest).unwrap(),
        )
        .unwrap();
        let text = format!("{}\ngarbage\n{}\n", result(0), result(1));
        std::fs::write(shard.join("results.jsonl"), &text).unwrap();
        let args = MergeArgs {
            dirs: vec![dir.path().to_path_buf()],
            out: dir.path().join("merged"),
        };
        let err = merge(&args).err().unwrap().to_string();
        assert!(err.contains("results.jsonl:2"), "{err}");
        assert_eq!(
            std::fs::read_to_string(shard.join("results.jsonl")).unwrap(),
            text
        );
    }
}
