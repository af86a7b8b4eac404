//! `cargo xtask robustness`: CS-QL and two baselines in worlds beyond the paper's
//! assumptions (slip, sensor noise, a sensing range), one departure at a time.
//!
//! # The job list
//!
//! In a fixed order, numbered from 0 (see [`crate::shard`] for shards and resuming): for
//! each map, each [`Condition`] (the paper's world, slip 0.05, 0.1 and 0.2, sensor noise
//! 0.01, 0.05 and 0.1, sensing radius 2 and 1), each [`Learner`] and each run `i` (seed
//! `S + i`):
//!
//! * `resetting`, `lazy`, `random`, `eager`: plain CS-QL (the paper's decrease rule and
//!   exact matching);
//! * `lazy+fit`: lazy CS-QL with the extension that fits the departure: the statistical
//!   detector under slip; under noise the statistical detector, nearest matching, new
//!   descriptions confirmed by 3 sightings and every feature read 5 times (the majority
//!   kept, each read charged); a memory of 2 steps under a sensing radius (not run in the paper's world, where it
//!   would be `lazy`);
//! * `u-tree`: the U-Tree baseline; `full-sensing`: Q-learning on the whole sensable view.
//!
//! Every run is judged by the policy quality (`judge.judge_by_quality`), evaluated
//! every `--quality-every` trials, and ends once it has stayed at or above 0.95 for
//! `--patience` evaluations, or at the trial cap. Under slip or noise every learner uses
//! beta 0.2 (with beta 1 a stochastic target overwrites Q at every update); elsewhere the
//! paper's settings.
//!
//! # The report
//!
//! When every job is done (`--shard 1/1`, or `--report` after all shards), the report is
//! written under `--out`: `robustness.md` and `robustness.csv` (per condition and
//! learner, over maps and runs; the CSV also per map), and one figure per departure,
//! `robustness_{slip,noise,radius}.svg`. With `--bless` the table and figures are also
//! written to `docs/robustness_table.md` and `docs/figures/`.
//!
//! # The files
//!
//! This file holds the arguments, the sweep's definition, its jobs and their running;
//! `robustness/report.rs` writes the table, the CSV and the figures (and redraws the
//! figures from a CSV).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::Args;
use csql::{DetectorKind, LearnerKind, Matching, RunSettings, Setup, StrategyKind};
use mdp::{Map, SensorNoise, Slip};
use serde::{Deserialize, Serialize};

use crate::shard::JobLine;

mod report;

/// Arguments of `cargo xtask robustness`.
#[derive(Args, Clone, Debug)]
pub struct RobustnessArgs {
    /// Maps, comma-separated (as for `cargo xtask sweep`).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "tan8x8,tan8x8-maze,dyna9x6,corridors9x5"
    )]
    maps: Vec<String>,
    /// Runs per map, condition and learner.
    #[arg(long, default_value_t = 10)]
    runs: u64,
    /// Base seed: run i uses seed S + i.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Trial cap of each run.
    #[arg(long, default_value_t = 1500)]
    max_trials: u32,
    /// Trials between two evaluations of the policy quality.
    #[arg(long, default_value_t = 25)]
    quality_every: u32,
    /// Evaluations at or above 0.95 in a row that end a run.
    #[arg(long, default_value_t = 8)]
    patience: u32,
    /// This machine's shard, `K/N` (K from 1 to N).
    #[arg(long, default_value = "1/1")]
    shard: String,
    /// Worker threads (default: every core). Results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// Output folder (shared by all shards).
    #[arg(long, default_value = "results/robustness")]
    out: PathBuf,
    /// Run nothing: write the report from the shards under `--out`.
    #[arg(long)]
    report: bool,
    /// Also write the table and figures into `docs/`.
    #[arg(long)]
    bless: bool,
    /// Run nothing: redraw the three figures from a `robustness.csv` written by an earlier
    /// report (its rows of map `all`), into `--out` (or `docs/figures` with `--bless`).
    #[arg(long, value_name = "FILE.csv", conflicts_with_all = ["report", "shard"])]
    figures_from: Option<PathBuf>,
}

/// One departure from the paper's world.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Condition {
    /// The paper's world.
    Paper,
    /// Slippery moves.
    Slip(f64),
    /// Noisy sensors.
    Noise(f64),
    /// A bounded sensing range.
    Radius(u32),
}

impl Condition {
    /// The conditions of the sweep, in order.
    pub const ALL: [Condition; 9] = [
        Condition::Paper,
        Condition::Slip(0.05),
        Condition::Slip(0.1),
        Condition::Slip(0.2),
        Condition::Noise(0.01),
        Condition::Noise(0.05),
        Condition::Noise(0.1),
        Condition::Radius(2),
        Condition::Radius(1),
    ];

    fn label(self) -> String {
        match self {
            Condition::Paper => "paper's world".into(),
            Condition::Slip(p) => format!("slip {p}"),
            Condition::Noise(p) => format!("noise {p}"),
            Condition::Radius(r) => format!("radius {r}"),
        }
    }

    fn stochastic(self) -> bool {
        matches!(self, Condition::Slip(_) | Condition::Noise(_))
    }
}

/// A learner of the sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Learner {
    /// Plain CS-QL with a strategy.
    Plain(StrategyKind),
    /// Lazy CS-QL with the extension that fits the condition.
    LazyFit,
    /// The U-Tree baseline.
    UTree,
    /// Full sensing.
    FullSensing,
}

impl Learner {
    const ALL: [Learner; 7] = [
        Learner::Plain(StrategyKind::Resetting),
        Learner::Plain(StrategyKind::Lazy),
        Learner::Plain(StrategyKind::Random),
        Learner::Plain(StrategyKind::Eager),
        Learner::LazyFit,
        Learner::UTree,
        Learner::FullSensing,
    ];

    fn label(self) -> String {
        match self {
            Learner::Plain(k) => k.to_string(),
            Learner::LazyFit => "lazy+fit".into(),
            Learner::UTree => "u-tree".into(),
            Learner::FullSensing => "full-sensing".into(),
        }
    }
}

/// What shards of the same sweep agree on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct Definition {
    maps: Vec<String>,
    runs: u64,
    seed: u64,
    max_trials: u32,
    quality_every: u32,
    patience: u32,
}

/// The measures of one run.
#[derive(Clone, Debug, Serialize, Deserialize)]
struct JobResult {
    id: u64,
    map: String,
    condition: Condition,
    learner: Learner,
    seed: u64,
    trials: u32,
    total_cost: f64,
    quality: f64,
    method: String,
    trials_to_quality: Option<u32>,
    cost_to_quality: Option<f64>,
    sensing_cost_per_state: f64,
    descriptions: usize,
    mean_features: f64,
}

impl JobLine for JobResult {
    fn id(&self) -> u64 {
        self.id
    }
}

/// The (condition, learner) pairs of each map, in job order.
fn pairs() -> Vec<(Condition, Learner)> {
    let mut out = Vec::new();
    for c in Condition::ALL {
        for l in Learner::ALL {
            if c == Condition::Paper && l == Learner::LazyFit {
                continue;
            }
            out.push((c, l));
        }
    }
    out
}

/// The job list in order (map, condition, learner, run), found from a job's number: a
/// shard never lists the whole of it.
struct Jobs {
    pairs: Vec<(Condition, Learner)>,
    runs: u64,
    per_map: u64,
    total: u64,
}

impl Jobs {
    fn new(def: &Definition) -> Result<Jobs> {
        let pairs = pairs();
        let per_map = (pairs.len() as u64)
            .checked_mul(def.runs)
            .context("--runs is more jobs than can be numbered")?;
        let total = (def.maps.len() as u64)
            .checked_mul(per_map)
            .context("--runs times the maps is more jobs than can be numbered")?;
        Ok(Jobs {
            pairs,
            runs: def.runs,
            per_map,
            total,
        })
    }

    /// Job `id`: (map, condition, learner, run).
    fn get(&self, id: u64) -> (usize, Condition, Learner, u64) {
        let (m, rest) = (id / self.per_map, id % self.per_map);
        let (c, l) = self.pairs[(rest / self.runs) as usize];
        (m as usize, c, l, rest % self.runs)
    }
}

/// The settings of one job.
fn settings(
    def: &Definition,
    map: &str,
    condition: Condition,
    learner: Learner,
    run: u64,
) -> Result<RunSettings> {
    let strategy = match learner {
        Learner::Plain(k) => k,
        _ => StrategyKind::Lazy,
    };
    let mut s = RunSettings::tan1991(map, strategy, def.seed + run);
    s.max_trials = csql::TrialCap::new(def.max_trials)?;
    s.judge.judge_by_quality = true;
    s.judge.quality_every = def.quality_every;
    s.judge.quality_patience = def.patience;
    match condition {
        Condition::Paper => {}
        Condition::Slip(p) => s.world.slip = Some(Slip::new(p)?),
        Condition::Noise(p) => s.world.sensor_noise = Some(SensorNoise::new(p)?),
        Condition::Radius(r) => s.world.sensing_radius = Some(r),
    }
    if condition.stochastic() {
        s.beta = qlearn::LearningRate::new(0.2)?;
    }
    match learner {
        Learner::Plain(_) => {}
        Learner::LazyFit => {
            let e = &mut s.cs_ql_mut().expect("CS-QL").extensions;
            match condition {
                Condition::Paper => {}
                Condition::Slip(_) => e.detector = DetectorKind::Statistical,
                Condition::Noise(_) => {
                    e.detector = DetectorKind::Statistical;
                    e.matching = Matching::Nearest;
                    e.confirm_new = 3;
                    e.reads = 5;
                }
                Condition::Radius(_) => e.memory = 2,
            }
        }
        Learner::UTree => s = s.with_learner(LearnerKind::UTree),
        Learner::FullSensing => s = s.with_learner(LearnerKind::FullSensing),
    }
    s.validate()?;
    Ok(s)
}

/// `cargo xtask robustness`.
pub fn robustness(args: &RobustnessArgs) -> Result<()> {
    if let Some(csv) = &args.figures_from {
        return report::redraw(csv, args);
    }
    if args.runs == 0 || args.quality_every == 0 || args.patience == 0 {
        bail!("robustness needs --runs, --quality-every and --patience of at least 1");
    }
    crate::files::seeds(args.seed, args.runs)?;
    crate::files::distinct("--maps", &args.maps)?;
    let def = Definition {
        maps: args.maps.clone(),
        runs: args.runs,
        seed: args.seed,
        max_trials: args.max_trials,
        quality_every: args.quality_every,
        patience: args.patience,
    };
    if !args.report {
        let maps: Vec<Map> = args
            .maps
            .iter()
            .map(|m| mdp::resolve(m))
            .collect::<Result<_, _>>()?;
        crate::files::distinct_maps(&args.maps, &maps)?;
        let list = Jobs::new(&def)?;
        // Check every job's settings before running any: the run changes only the seed,
        // and every seed exists (checked above).
        for m in &args.maps {
            for &(c, l) in &list.pairs {
                settings(&def, m, c, l, 0)?;
            }
        }
        let total = list.total;
        crate::shard::run_shard(
            &args.out,
            &args.shard,
            def.clone(),
            total,
            args.threads,
            |_| 1.0,
            |id| {
                let (m, condition, learner, run) = list.get(id);
                let s = settings(&def, &args.maps[m], condition, learner, run)?;
                let setup = Setup::for_map(maps[m].clone(), &s)?;
                let report = csql::run_on(&setup, &s)?;
                let q = &report.quality;
                Ok(JobResult {
                    id,
                    map: args.maps[m].clone(),
                    condition,
                    learner,
                    seed: s.seed,
                    trials: report.trials,
                    total_cost: report.total_cost,
                    quality: q.policy_quality,
                    method: serde_json::to_value(q.method)?
                        .as_str()
                        .unwrap_or_default()
                        .to_string(),
                    trials_to_quality: q.trials_to_quality,
                    cost_to_quality: q.cost_to_quality,
                    sensing_cost_per_state: q.learner_cost_per_state,
                    descriptions: q.descriptions,
                    mean_features: q.mean_features,
                })
            },
        )?;
        if crate::shard::one_of_several(&args.shard, "robustness")? {
            return Ok(());
        }
    }
    let by_id: BTreeMap<u64, JobResult> = crate::shard::collect_of(&args.out, &def)?;
    let results: Vec<JobResult> = by_id.into_values().collect();
    report::write(&def, &results, &args.out)?;
    if args.bless {
        report::write(&def, &results, Path::new("docs"))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn def() -> Definition {
        Definition {
            maps: vec!["tan3x3".into()],
            runs: 1,
            seed: 1,
            max_trials: 200,
            quality_every: 10,
            patience: 2,
        }
    }

    #[test]
    fn every_job_has_valid_settings_that_say_what_the_job_is() {
        let d = def();
        let jobs = Jobs::new(&d).unwrap();
        assert_eq!(jobs.total, 9 * 7 - 1);
        let list: Vec<_> = (0..jobs.total).map(|id| jobs.get(id)).collect();
        for &(m, c, l, run) in &list {
            let s = settings(&d, &d.maps[m], c, l, run).unwrap();
            assert!(s.judged_by_quality(true));
            assert_eq!(s.beta.get() < 1.0, c.stochastic());
            assert_eq!(s.learner.kind() == LearnerKind::UTree, l == Learner::UTree);
            let e = s.extensions();
            let extended = e.memory > 0
                || e.matching == Matching::Nearest
                || e.detector == DetectorKind::Statistical
                || e.reads > 1;
            assert_eq!(extended, l == Learner::LazyFit, "{c:?} {l:?}");
        }
    }

    #[test]
    fn jobs_are_numbered_in_the_order_of_the_nested_loops() {
        let d = Definition {
            maps: vec!["tan3x3".into(), "tan8x8".into()],
            runs: 3,
            ..def()
        };
        let mut listed = Vec::new();
        for m in 0..d.maps.len() {
            for c in Condition::ALL {
                for l in Learner::ALL {
                    if c == Condition::Paper && l == Learner::LazyFit {
                        continue;
                    }
                    for run in 0..d.runs {
                        listed.push((m, c, l, run));
                    }
                }
            }
        }
        let jobs = Jobs::new(&d).unwrap();
        assert_eq!(jobs.total, listed.len() as u64);
        for (id, job) in listed.iter().enumerate() {
            assert_eq!(jobs.get(id as u64), *job, "job {id}");
        }
        // Too many jobs to number is refused, not wrapped.
        assert!(
            Jobs::new(&Definition {
                runs: u64::MAX,
                ..d
            })
            .is_err()
        );
    }

    /// A small sweep on tan3x3 into `out`: one run, 60 trials at the most.
    fn small(out: &Path) -> RobustnessArgs {
        RobustnessArgs {
            maps: vec!["tan3x3".into()],
            runs: 1,
            seed: 1,
            max_trials: 60,
            quality_every: 10,
            patience: 2,
            shard: "1/1".into(),
            threads: Some(1),
            out: out.to_path_buf(),
            report: false,
            bless: false,
            figures_from: None,
        }
    }

    #[test]
    fn one_shard_of_a_huge_job_list_runs_its_own_job_only() {
        // Once: the whole list of 62 * 10^8 jobs was built to run one.
        let dir = tempfile::tempdir().unwrap();
        let args = RobustnessArgs {
            runs: 100_000_000,
            max_trials: 20,
            shard: "1/100000000000".into(),
            ..small(dir.path())
        };
        robustness(&args).unwrap();
        let text =
            std::fs::read_to_string(dir.path().join("shard-1-of-100000000000/results.jsonl"))
                .unwrap();
        assert_eq!(text.lines().count(), 1);
    }

    #[test]
    fn a_small_sweep_runs_resumes_and_reports() {
        let dir = tempfile::tempdir().unwrap();
        let args = small(dir.path());
        robustness(&args).unwrap();
        let table = std::fs::read_to_string(dir.path().join("robustness.md")).unwrap();
        assert_eq!(table.matches("| u-tree |").count(), 9);
        for name in ["slip", "noise", "radius"] {
            let svg =
                std::fs::read_to_string(dir.path().join(format!("robustness_{name}.svg"))).unwrap();
            let tree = resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).unwrap();
            assert!(tree.size().width() > 1000.0);
        }
        // Another thread count gives the same results, job by job.
        let other = tempfile::tempdir().unwrap();
        robustness(&RobustnessArgs {
            threads: Some(2),
            out: other.path().to_path_buf(),
            ..args.clone()
        })
        .unwrap();
        let lines = |dir: &Path| {
            let (_, by_id): (Definition, BTreeMap<u64, JobResult>) =
                crate::shard::collect(&[dir.to_path_buf()]).unwrap();
            by_id
                .values()
                .map(|r| serde_json::to_string(r).unwrap())
                .collect::<Vec<_>>()
        };
        assert_eq!(lines(dir.path()), lines(other.path()));
        // Resuming runs nothing again; the report is the same.
        robustness(&RobustnessArgs {
            report: true,
            ..args
        })
        .unwrap();
        assert_eq!(
            std::fs::read_to_string(dir.path().join("robustness.md")).unwrap(),
            table
        );
    }

    #[test]
    fn figures_from_a_csv_refuse_what_a_report_never_writes() {
        let dir = tempfile::tempdir().unwrap();
        let header = "map,condition,learner,runs,reached,quality_mean,cost_to_quality_median,trials_to_quality_median,cost_per_state_mean,descriptions_mean,features_mean\n";
        let per_map = "\"m\",paper's world,lazy,4,4,1,,,1,1,1\n";
        for (row, want) in [
            (
                "\"all\",paper's world,lazy,4,4,NaN,,,1,1,1",
                "line 2: field 6 is `NaN`",
            ),
            (
                "\"all\",paper's world,lazy,4,4,-5,,,1,1,1",
                "line 2: quality -5 is not in [0, 1]",
            ),
            (
                "\"all\",paper's world,lazy,4,4,1,-1,,1,1,1",
                "line 2: -1e0 is not a cost",
            ),
            (
                "\"all\",paper's world,lazy,4,4,1,1e308,,1,1,1",
                "line 2: 1e308 is not a cost",
            ),
            (
                "\"all\",paper's world,lazy,0,0,1,,,1,1,1",
                "line 2: 0 runs of which 0",
            ),
            (
                "\"all\",paper's world,lazy,4,5,1,,,1,1,1",
                "line 2: 4 runs of which 5",
            ),
            (
                "\"all\",paper's world,lazi,4,4,1,,,1,1,1",
                "line 2: unknown learner `lazi`",
            ),
            (
                "all,paper's world,lazy,4,4,1,,,1,1,1",
                "line 2: the map is not a quoted first field",
            ),
        ] {
            let csv = dir.path().join("r.csv");
            std::fs::write(&csv, format!("{header}{row}\n{per_map}")).unwrap();
            let args = RobustnessArgs {
                figures_from: Some(csv),
                ..small(&dir.path().join("out"))
            };
            let err = robustness(&args).unwrap_err().to_string();
            assert!(err.contains(want), "{row}: {err}");
        }
    }
}
