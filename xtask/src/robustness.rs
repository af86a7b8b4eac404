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

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use csql::{DetectorKind, LearnerKind, Matching, RunSettings, Setup, StrategyKind};
use mdp::{Map, SensorNoise, Slip};
use plotters::prelude::*;
use serde::{Deserialize, Serialize};

use crate::figures::{PALETTE, marker};
use crate::shard::JobLine;

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
        return redraw(csv, args);
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
        if crate::shard::parse_shard(&args.shard)?.1 > 1 {
            crate::note("run `cargo xtask robustness --report` once every shard is done");
            return Ok(());
        }
    }
    let (found, by_id): (Definition, BTreeMap<u64, JobResult>) =
        crate::shard::collect(std::slice::from_ref(&args.out))?;
    if found != def {
        bail!(
            "{} holds another sweep ({found:?}); give its arguments, or another --out",
            args.out.display()
        );
    }
    let results: Vec<JobResult> = by_id.into_values().collect();
    write_report(&def, &results, &args.out)?;
    if args.bless {
        write_report(&def, &results, Path::new("docs"))?;
    }
    Ok(())
}

/// The three figures (slip, noise, radius) into the folder `figures`, from each
/// condition's and learner's cell over every map.
fn draw_figures(
    figures: &Path,
    maps: usize,
    runs: u64,
    all: &dyn Fn(Condition, Learner) -> Option<Cell>,
) -> Result<()> {
    // Each figure: the paper's world, then the conditions of one departure, in order.
    let along = |departs: fn(&Condition) -> bool| -> Vec<Condition> {
        std::iter::once(Condition::Paper)
            .chain(Condition::ALL.into_iter().filter(departs))
            .collect()
    };
    for (name, axis, conditions) in [
        (
            "slip",
            "slip probability",
            along(|c| matches!(c, Condition::Slip(_))),
        ),
        (
            "noise",
            "sensor noise",
            along(|c| matches!(c, Condition::Noise(_))),
        ),
        (
            "radius",
            "sensing radius",
            along(|c| matches!(c, Condition::Radius(_))),
        ),
    ] {
        let series: Vec<Series> = Learner::ALL
            .iter()
            .map(|&l| Series {
                name: l.label(),
                points: conditions
                    .iter()
                    .enumerate()
                    .map(|(i, &c)| (i, all(c, l)))
                    .collect(),
            })
            .collect();
        let ticks: Vec<String> = conditions
            .iter()
            .map(|c| match c {
                Condition::Paper => {
                    if name == "radius" {
                        "unbounded".into()
                    } else {
                        "0".into()
                    }
                }
                Condition::Slip(p) | Condition::Noise(p) => format!("{p}"),
                Condition::Radius(r) => r.to_string(),
            })
            .collect();
        let path = figures.join(format!("robustness_{name}.svg"));
        let title = format!("Every learner against {axis}: means over {maps} maps x {runs} runs");
        figure(&path, &title, axis, &ticks, &series)?;
    }
    Ok(())
}

/// The largest cost, count or mean `--figures-from` draws (a log axis needs room above).
const MAX_MEASURE: f64 = 1e100;

/// `--figures-from`: the figures again from a report's CSV, without running anything.
fn redraw(csv: &Path, args: &RobustnessArgs) -> Result<()> {
    let text = crate::files::read_text(csv, 64 << 20, "a robustness.csv")?;
    let mut lines = text.lines();
    let header = lines.next().unwrap_or_default();
    let want = "map,condition,learner,runs,reached,quality_mean,cost_to_quality_median,trials_to_quality_median,cost_per_state_mean,descriptions_mean,features_mean";
    if header.trim_end() != want {
        bail!(
            "{}: line 1: not a robustness.csv header (want `{want}`)",
            csv.display()
        );
    }
    let mut cells: Vec<(Condition, Learner, Cell)> = Vec::new();
    let mut maps = std::collections::BTreeSet::new();
    let mut runs_all = 0;
    for (i, line) in lines.enumerate() {
        let at = i + 2;
        let bad = |what: &str| anyhow!("{}: line {at}: {what}", csv.display());
        // The map is the one quoted field; the others hold no comma.
        let rest = line
            .strip_prefix('"')
            .and_then(|l| l.split_once("\","))
            .ok_or_else(|| bad("the map is not a quoted first field"))?;
        let (map, rest) = rest;
        let f: Vec<&str> = rest.split(',').collect();
        if f.len() != 10 {
            return Err(bad(&format!("{} fields after the map, want 10", f.len())));
        }
        let condition = Condition::ALL
            .into_iter()
            .find(|c| c.label() == f[0])
            .ok_or_else(|| bad(&format!("unknown condition `{}`", f[0])))?;
        let learner = Learner::ALL
            .into_iter()
            .find(|l| l.label() == f[1])
            .ok_or_else(|| bad(&format!("unknown learner `{}`", f[1])))?;
        let num = |k: usize| -> Result<f64> {
            f[k].parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| bad(&format!("field {} is `{}`, not a number", k + 2, f[k])))
        };
        let opt = |k: usize| -> Result<Option<f64>> {
            if f[k].is_empty() {
                Ok(None)
            } else {
                num(k).map(Some)
            }
        };
        let count = |k: usize| -> Result<usize> {
            f[k].parse::<usize>()
                .map_err(|_| bad(&format!("field {} is `{}`, not a count", k + 2, f[k])))
        };
        if map != "all" {
            maps.insert(map.to_string());
            continue;
        }
        let runs = count(2)?;
        runs_all = runs_all.max(runs);
        let cell = Cell {
            runs,
            reached: count(3)?,
            quality: num(4)?,
            cost_to_quality: opt(5)?,
            trials_to_quality: opt(6)?,
            cost_per_state: num(7)?,
            descriptions: num(8)?,
            features: num(9)?,
        };
        // What a report writes, and nothing a figure would draw wrongly.
        if runs == 0 || cell.reached > runs {
            return Err(bad(&format!(
                "{} runs of which {} reached 0.95: want at least 1 run, and no more reached than run",
                runs, cell.reached
            )));
        }
        if !(0.0..=1.0).contains(&cell.quality) {
            return Err(bad(&format!("quality {} is not in [0, 1]", cell.quality)));
        }
        let measures = [
            cell.cost_to_quality.unwrap_or(0.0),
            cell.trials_to_quality.unwrap_or(0.0),
            cell.cost_per_state,
            cell.descriptions,
            cell.features,
        ];
        if let Some(x) = measures.iter().find(|x| !(0.0..=MAX_MEASURE).contains(*x)) {
            return Err(bad(&format!(
                "{x:e} is not a cost, count or mean between 0 and {MAX_MEASURE:e}"
            )));
        }
        cells.push((condition, learner, cell));
    }
    if cells.is_empty() || maps.is_empty() {
        bail!("{}: no rows of map `all` and of each map", csv.display());
    }
    let all = |c: Condition, l: Learner| {
        cells
            .iter()
            .find(|(cc, ll, _)| *cc == c && *ll == l)
            .map(|(_, _, x)| x.clone())
    };
    let out = if args.bless {
        Path::new("docs/figures").to_path_buf()
    } else {
        args.out.clone()
    };
    crate::files::create_dir(&out)?;
    draw_figures(&out, maps.len(), (runs_all / maps.len()) as u64, &all)?;
    crate::emit(&format!(
        "Wrote the robustness figures into {}\n",
        out.display()
    ))?;
    Ok(())
}

/// Aggregates of a group of runs.
#[derive(Clone, Debug)]
struct Cell {
    runs: usize,
    reached: usize,
    quality: f64,
    /// Median over the runs that reached 0.95.
    cost_to_quality: Option<f64>,
    trials_to_quality: Option<f64>,
    cost_per_state: f64,
    descriptions: f64,
    features: f64,
}

fn median(mut xs: Vec<f64>) -> Option<f64> {
    if xs.is_empty() {
        return None;
    }
    xs.sort_by(f64::total_cmp);
    let n = xs.len();
    Some(if n % 2 == 1 {
        xs[n / 2]
    } else {
        (xs[n / 2 - 1] + xs[n / 2]) / 2.0
    })
}

fn cell(rs: &[&JobResult]) -> Option<Cell> {
    if rs.is_empty() {
        return None;
    }
    let n = rs.len() as f64;
    let mean = |f: fn(&JobResult) -> f64| rs.iter().map(|r| f(r)).sum::<f64>() / n;
    // A median over fewer than half the runs would describe the lucky ones only.
    let reached: Vec<&&JobResult> = rs.iter().filter(|r| r.cost_to_quality.is_some()).collect();
    let enough = 2 * reached.len() >= rs.len();
    Some(Cell {
        runs: rs.len(),
        reached: reached.len(),
        quality: mean(|r| r.quality),
        cost_to_quality: enough
            .then(|| median(reached.iter().filter_map(|r| r.cost_to_quality).collect()))
            .flatten(),
        trials_to_quality: enough
            .then(|| {
                median(
                    reached
                        .iter()
                        .filter_map(|r| r.trials_to_quality.map(f64::from))
                        .collect(),
                )
            })
            .flatten(),
        cost_per_state: mean(|r| r.sensing_cost_per_state),
        descriptions: mean(|r| r.descriptions as f64),
        features: mean(|r| r.mean_features),
    })
}

fn write_report(def: &Definition, results: &[JobResult], out: &Path) -> Result<()> {
    let figures = if out == Path::new("docs") {
        out.join("figures")
    } else {
        out.to_path_buf()
    };
    crate::files::create_dir(&figures)?;
    let group = |map: Option<&str>, c: Condition, l: Learner| -> Vec<&JobResult> {
        results
            .iter()
            .filter(|r| r.condition == c && r.learner == l && map.is_none_or(|m| r.map == m))
            .collect()
    };
    let mut md = String::from("# Robustness: CS-QL beyond the paper's assumptions\n\n");
    let _ = writeln!(
        md,
        "Generated by `cargo xtask robustness` (maps {}; {} runs each, seeds {}..={}; trial cap {}; \
         quality every {} trials, a run ends after {} evaluations in a row at or above 0.95). \
         Each cell is over every map and run: runs that reached quality 0.95 and stayed there, \
         the mean final quality, the median sensing cost (and trials) until the quality was \
         reached over the runs that reached it (— when fewer than half did), and the mean \
         sensing cost per state after learning and descriptions (rows of the Q table). \
         The reading is in `docs/robustness.md`.\n",
        def.maps.join(", "),
        def.runs,
        def.seed,
        def.seed + def.runs - 1,
        def.max_trials,
        def.quality_every,
        def.patience
    );
    md.push_str("| condition | learner | reached 0.95 | final quality | cost to quality | trials to quality | cost/state after | descriptions | features/description |\n|---|---|---|---|---|---|---|---|---|\n");
    let mut csv = String::from(
        "map,condition,learner,runs,reached,quality_mean,cost_to_quality_median,trials_to_quality_median,cost_per_state_mean,descriptions_mean,features_mean\n",
    );
    let opt = |x: Option<f64>, d: usize| x.map_or("—".to_string(), |v| format!("{v:.d$}"));
    for c in Condition::ALL {
        for l in Learner::ALL {
            let Some(x) = cell(&group(None, c, l)) else {
                continue;
            };
            let _ = writeln!(
                md,
                "| {} | {} | {}/{} | {:.3} | {} | {} | {:.1} | {:.1} | {:.2} |",
                c.label(),
                l.label(),
                x.reached,
                x.runs,
                x.quality,
                opt(x.cost_to_quality, 0),
                opt(x.trials_to_quality, 0),
                x.cost_per_state,
                x.descriptions,
                x.features
            );
            for map in std::iter::once(None).chain(def.maps.iter().map(|m| Some(m.as_str()))) {
                let Some(x) = cell(&group(map, c, l)) else {
                    continue;
                };
                let _ = writeln!(
                    csv,
                    "\"{}\",{},{},{},{},{:.6},{},{},{:.6},{:.6},{:.6}",
                    map.unwrap_or("all"),
                    c.label(),
                    l.label(),
                    x.runs,
                    x.reached,
                    x.quality,
                    x.cost_to_quality
                        .map_or(String::new(), |v| format!("{v:.1}")),
                    x.trials_to_quality
                        .map_or(String::new(), |v| format!("{v:.1}")),
                    x.cost_per_state,
                    x.descriptions,
                    x.features
                );
            }
        }
    }
    let table = if out == Path::new("docs") {
        out.join("robustness_table.md")
    } else {
        out.join("robustness.md")
    };
    crate::files::write_atomic(&table, &md)?;
    crate::files::write_atomic(&out.join("robustness.csv"), &csv)?;
    let all = |c: Condition, l: Learner| cell(&group(None, c, l));
    draw_figures(&figures, def.maps.len(), def.runs, &all)?;
    crate::emit(&format!("{md}\nWrote {}\n", table.display()))?;
    Ok(())
}

struct Series {
    name: String,
    points: Vec<(usize, Option<Cell>)>,
}

/// Three panels against one departure: final quality, sensing cost until quality 0.95
/// (log scale), sensing cost per state after learning (log scale).
fn figure(path: &Path, title: &str, axis: &str, ticks: &[String], series: &[Series]) -> Result<()> {
    crate::figures::register_font();
    let plot_err = |e: &dyn std::fmt::Display| anyhow!("drawing {}: {e}", path.display());
    let mut svg = String::new();
    let base = SVGBackend::with_string(&mut svg, (1500, 550)).into_drawing_area();
    base.fill(&WHITE).map_err(|e| plot_err(&e))?;
    let root = base
        .titled(title, ("sans-serif", 22))
        .map_err(|e| plot_err(&e))?;
    let height = root.dim_in_pixel().1;
    let (upper, footer) = root.split_vertically(height - 82);
    let (plots, legend) = upper.split_horizontally(1290);
    let panels = plots.split_evenly((1, 3));
    let n = ticks.len();
    // Room on both sides for the sideways shift of the series (`draw_series`).
    let x_range = -0.5..(n as f64 - 0.5);
    // Per panel, the learners with no point in it, named under it.
    let mut missing: [Vec<&str>; 3] = Default::default();
    let tick_label = |x: &f64| {
        let i = x.round();
        if (x - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < n {
            ticks[i as usize].clone()
        } else {
            String::new()
        }
    };
    // Panel 1: final quality.
    {
        let mut chart = ChartBuilder::on(&panels[0])
            .caption("final policy quality", ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(46)
            .y_label_area_size(56)
            .build_cartesian_2d(x_range.clone(), 0.0..1.05)
            .map_err(|e| plot_err(&e))?;
        chart
            .configure_mesh()
            .x_desc(axis)
            .y_desc("quality (1 = optimal)")
            .axis_desc_style(("sans-serif", 15))
            .label_style(("sans-serif", 13))
            .x_labels(n)
            .x_label_formatter(&tick_label)
            .light_line_style(WHITE)
            .bold_line_style(RGBColor(230, 230, 230))
            .draw()
            .map_err(|e| plot_err(&e))?;
        for (k, s) in series.iter().enumerate() {
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter_map(|(i, c)| c.as_ref().map(|c| (*i as f64, c.quality)))
                .collect();
            if pts.is_empty() {
                missing[0].push(&s.name);
            }
            draw_series(&mut chart, k, series.len(), &pts).map_err(|e| plot_err(&e))?;
        }
    }
    // Panels 2 and 3: costs on log scales.
    type Pick = fn(&Cell) -> Option<f64>;
    let costs: [(&str, &str, Pick); 2] = [
        (
            "sensing cost until quality 0.95",
            "median cost (log)",
            |c| c.cost_to_quality,
        ),
        (
            "sensing cost per state after learning",
            "mean cost per state (log)",
            |c| Some(c.cost_per_state),
        ),
    ];
    for (p, (panel, (caption, y_desc, pick))) in panels[1..].iter().zip(costs).enumerate() {
        let values: Vec<f64> = series
            .iter()
            .flat_map(|s| {
                s.points
                    .iter()
                    .filter_map(|(_, c)| c.as_ref().and_then(pick))
            })
            .filter(|v| *v > 0.0)
            .collect();
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = values.iter().copied().fold(0.0, f64::max);
        let (lo, hi) = if values.is_empty() {
            (1.0, 10.0)
        } else {
            (lo / 1.5, hi * 1.5)
        };
        let mut chart = ChartBuilder::on(panel)
            .caption(caption, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(46)
            .y_label_area_size(70)
            .build_cartesian_2d(x_range.clone(), (lo..hi).log_scale())
            .map_err(|e| plot_err(&e))?;
        chart
            .configure_mesh()
            .x_desc(axis)
            .y_desc(y_desc)
            .axis_desc_style(("sans-serif", 15))
            .label_style(("sans-serif", 13))
            .x_labels(n)
            .x_label_formatter(&tick_label)
            .y_labels(5)
            .y_label_formatter(&|y| crate::figures::short(*y))
            .light_line_style(WHITE)
            .bold_line_style(RGBColor(230, 230, 230))
            .draw()
            .map_err(|e| plot_err(&e))?;
        for (k, s) in series.iter().enumerate() {
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter_map(|(i, c)| c.as_ref().and_then(pick).map(|v| (*i as f64, v)))
                .filter(|p| p.1 > 0.0)
                .collect();
            if pts.is_empty() {
                missing[p + 1].push(&s.name);
            }
            draw_series(&mut chart, k, series.len(), &pts).map_err(|e| plot_err(&e))?;
        }
    }
    // Under each panel, the learners it lacks; then how to read the shift and the gaps.
    let note = ("sans-serif", 14).into_font();
    let width = 1290 / 3;
    for (p, names) in missing.iter().enumerate() {
        let text = if names.is_empty() {
            "every learner shown".to_string()
        } else {
            format!("not shown (no point): {}", names.join(", "))
        };
        footer
            .draw(&Text::new(text, (width * p as i32 + 70, 6), note.clone()))
            .map_err(|e| plot_err(&e))?;
    }
    footer
        .draw(&Text::new(
            "Learners are drawn side by side at each setting so that equal values stay \
             visible. A point is left out where fewer than half the runs reached quality \
             0.95 (middle panel) or the cost is 0 (log scales).",
            (70, 32),
            note.clone(),
        ))
        .map_err(|e| plot_err(&e))?;
    // Settings where a learner was not run at all (lazy+fit in the paper's world, where
    // it is lazy).
    let not_run: Vec<String> = series
        .iter()
        .filter_map(|s| {
            let at: Vec<&str> = s
                .points
                .iter()
                .filter(|(_, c)| c.is_none())
                .map(|(i, _)| ticks[*i].as_str())
                .collect();
            (!at.is_empty()).then(|| format!("{} at {}", s.name, at.join(", ")))
        })
        .collect();
    if !not_run.is_empty() {
        footer
            .draw(&Text::new(
                format!(
                    "Not run: {} (in the paper's world lazy+fit is lazy).",
                    not_run.join("; ")
                ),
                (70, 54),
                note,
            ))
            .map_err(|e| plot_err(&e))?;
    }
    // The legend, once, to the right.
    for (k, s) in series.iter().enumerate() {
        let y = 90 + 34 * k as i32;
        let color = PALETTE[k % PALETTE.len()];
        legend
            .draw(&PathElement::new(
                vec![(10, y), (50, y)],
                color.stroke_width(2),
            ))
            .map_err(|e| plot_err(&e))?;
        legend
            .draw(&marker(k, (30, y), color))
            .map_err(|e| plot_err(&e))?;
        legend
            .draw(&Text::new(
                s.name.clone(),
                (60, y - 8),
                ("sans-serif", 16).into_font(),
            ))
            .map_err(|e| plot_err(&e))?;
    }
    root.present().map_err(|e| plot_err(&e))?;
    drop(panels);
    drop(plots);
    drop(legend);
    drop(upper);
    drop(footer);
    drop(root);
    drop(base);
    crate::files::write_atomic(path, svg)
}

/// The sideways step between two series' points at one setting, in settings.
const DODGE: f64 = 0.1;

fn draw_series<DB: DrawingBackend, Y: Ranged<ValueType = f64>>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<plotters::coord::types::RangedCoordf64, Y>>,
    k: usize,
    count: usize,
    pts: &[(f64, f64)],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let color = PALETTE[k % PALETTE.len()];
    // Series side by side around each setting, a marker's width apart, so that equal
    // values (every learner at quality 1) stay visible.
    let shift = (k as f64 - (count as f64 - 1.0) / 2.0) * DODGE;
    let pts: Vec<(f64, f64)> = pts.iter().map(|&(x, y)| (x + shift, y)).collect();
    chart.draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))?;
    chart.draw_series(
        pts.iter()
            .map(|&(x, y)| EmptyElement::at((x, y)) + marker::<DB>(k, (0, 0), color)),
    )?;
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
    fn figures_say_which_learners_they_lack_and_tell_equal_values_apart() {
        let dir = tempfile::tempdir().unwrap();
        let cell = |q: f64, cost: Option<f64>| Cell {
            runs: 10,
            reached: 10,
            quality: q,
            cost_to_quality: cost,
            trials_to_quality: cost,
            cost_per_state: 5.0,
            descriptions: 1.0,
            features: 1.0,
        };
        // Every learner at quality 1; one never reaches 0.95; lazy+fit not run at 0.
        let all = |c: Condition, l: Learner| match (c, l) {
            (Condition::Paper, Learner::LazyFit) => None,
            (_, Learner::UTree) => Some(cell(1.0, None)),
            _ => Some(cell(1.0, Some(2.5e6))),
        };
        draw_figures(dir.path(), 2, 3, &all).unwrap();
        let svg = std::fs::read_to_string(dir.path().join("robustness_slip.svg")).unwrap();
        assert!(svg.contains("not shown (no point): u-tree"), "{svg}");
        assert!(svg.contains("Not run: lazy+fit at 0"));
        assert!(svg.contains("means over 2 maps x 3 runs"));
        // Seven learners at one setting, a marker's width apart: no two at one place.
        let xs: Vec<f64> = (0..7).map(|k| (k as f64 - 3.0) * DODGE).collect();
        assert!(xs.windows(2).all(|w| w[1] - w[0] >= 0.1 - 1e-12));
        assert!(
            xs[6] < 0.5,
            "a setting's learners stay clear of the next setting"
        );
    }

    #[test]
    fn cost_ticks_have_one_style() {
        let ticks: Vec<String> = [1.0, 12.5, 100.0, 1e3, 2.5e3, 1e5, 1e6, 1.25e6, 1e7]
            .iter()
            .map(|&y| crate::figures::short(y))
            .collect();
        assert_eq!(
            ticks,
            [
                "1", "12.5", "100", "1k", "2.5k", "100k", "1M", "1.2M", "10M"
            ]
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
