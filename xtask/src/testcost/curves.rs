//! `cargo xtask budget`: accuracy against test cost, each learner swept over its cost knob
//! on the benchmark's folds and prices.
//!
//! A **curve** is one learner swept over one knob ([`Knob`]): the uniform
//! misclassification cost `mc` (for the learners whose tree depends on it), or a hard
//! budget per object, either a share of the price of every test or at most `k` tests
//! (held at a fixed large mc; the greedy learners grow within it, the others are cut at
//! classification), or, for CEGB, its `cegb_tradeoff` (a model trained at each value on
//! each training part, through CEGB's Python workers: [`super::cegb::sweep_job`]). One
//! job is one data set, one price assignment, one run of `K`-fold cross-validation and
//! one curve: every value of its knob comes out of one job, so a learner grows its trees
//! at every mc at once (`fit_each`), and a learner that does not grow within a budget
//! grows them once for every budget. The jobs run through the benchmark's machinery
//! ([`super::cross_validate`], its folds, prices and seeds, shards and resumption), so a
//! point of a curve is the benchmark's job at that setting, to the bit.
//!
//! Per data set, price set, curve and knob value the report gives the mean over runs and
//! draws of the accuracy, the AUROC, the test cost per object (also over the price of
//! every test of its draw: the normalised cost) and the total cost, each with its 95%
//! interval; per curve, the area under accuracy against normalised cost on [0, 1] with
//! step interpolation ([`area`], `docs/specification.md` 2.8). It writes `budget.csv`,
//! `budget.md` and one `budget-DATASET.svg` per data set.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, Result, anyhow, bail};
use clap::Args;
use cslearn::testcost::{Budget, Frame, Loaded, Method, folds};
use plotters::prelude::*;
use serde::{Deserialize, Serialize};

use super::{
    Definition, Job, Learner, Prepared, PriceSet, Priced, Score, TestcostArgs, cegb,
    cross_validate, job_prices, mix, prepare, work,
};
use crate::figures::{PALETTE, marker};
use crate::shard::JobLine;

/// Arguments of `cargo xtask budget`.
#[derive(Args, Clone, Debug)]
pub struct BudgetArgs {
    /// Data sets, comma-separated (default: every data set of the manifest, the
    /// benchmark's and those kept for budgets, such as `spambase`).
    #[arg(long, value_delimiter = ',')]
    datasets: Vec<String>,
    /// Learners, comma-separated. Each whose tree depends on mc (`dtmc`, `icet`, `act`,
    /// `cvt`) gets an mc curve; each of `--budget-learners` gets the budget curves;
    /// `cegb` (LightGBM's CEGB, through Python; not a default: it is slow) gets a curve
    /// over its tradeoff.
    #[arg(long, value_delimiter = ',', default_value = "c45,eg2,dtmc,icet")]
    learners: Vec<String>,
    /// The learners swept over the budgets, comma-separated, among `--learners` (default:
    /// those of `--learners` whose tree does not depend on mc, whose only knob a budget is,
    /// and those that grow within a budget: with the default learners C4.5, EG2 and DTMC).
    #[arg(long, value_delimiter = ',')]
    budget_learners: Vec<String>,
    /// The mc curves' uniform misclassification costs, in the prices' units, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1,3,10,30,100,300,1000,3000,10000,30000,100000"
    )]
    mc: Vec<f64>,
    /// The budget curves' budgets, each a share of the price of every test of the job's
    /// prices (1 or more: no limit), comma-separated; the flag alone for none.
    #[arg(
        long,
        value_delimiter = ',',
        num_args = 0..,
        default_value = "0.01,0.02,0.05,0.1,0.2,0.5,1"
    )]
    budgets: Vec<f64>,
    /// The k-tests curves' budgets, at most k distinct tests per object, comma-separated;
    /// the flag alone for none.
    #[arg(long, value_delimiter = ',', num_args = 0.., default_value = "1,2,3,5,10")]
    max_tests: Vec<usize>,
    /// CEGB's `cegb_tradeoff` values, comma-separated: its curve has a point per value,
    /// a model trained at it on each training part (default: the grid of its
    /// cross-validation in `cargo xtask testcost`, 0 and 21 values from 10^-4 to 10 in
    /// quarter decades). Needs `cegb` among `--learners`.
    #[arg(long, value_delimiter = ',')]
    tradeoffs: Vec<f64>,
    /// The uniform misclassification cost the budget curves are run at, and at which
    /// CEGB's tradeoff curve counts its total cost.
    #[arg(long, default_value_t = 100_000.0)]
    budget_mc: f64,
    /// Price sets, comma-separated: `random` and `turney`, as `cargo xtask testcost`'s.
    #[arg(long, value_delimiter = ',', default_value = "random,turney")]
    costs: Vec<String>,
    /// Random price assignments per data set (the benchmark's first draws; a data set with
    /// unit prices has one).
    #[arg(long, default_value_t = 2)]
    assignments: u64,
    /// Runs of cross-validation per data set and price assignment (the benchmark's first
    /// runs: the same folds).
    #[arg(long, default_value_t = 2)]
    runs: u64,
    /// Folds of each run.
    #[arg(long, default_value_t = 10)]
    folds: usize,
    /// Base seed of folds, prices and the learners' draws (the benchmark's).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The manifest of the data sets.
    #[arg(long, default_value = "data/uci/datasets.toml")]
    manifest: PathBuf,
    /// Output folder.
    #[arg(long, default_value = "results/budget")]
    out: PathBuf,
    /// Worker threads (default: every core); results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// This machine's shard, `K/N`.
    #[arg(long, default_value = "1/1")]
    shard: String,
    /// The Python interpreter of CEGB's worker (`--learners ...,cegb`), as `cargo xtask
    /// testcost --python` (default: the project's virtual environment).
    #[arg(long, value_name = "PATH")]
    python: Option<PathBuf>,
    /// Results folders of other `cargo xtask budget` runs whose curves join the report:
    /// the same data sets, price sets, draws, runs, folds, seed, settings and knob values,
    /// but their own learners. Only the curves of learners this run does not have are
    /// added: a learner joins without running the others again.
    #[arg(long, value_delimiter = ',')]
    with: Vec<PathBuf>,
    /// Only write the report from the results already in `--out`.
    #[arg(long)]
    report: bool,
    /// Also write the report, the CSV and the figures into `docs/testcost/budget/`.
    #[arg(long)]
    bless: bool,
}

/// What a curve sweeps. Adding a learner with a knob of another kind is one variant
/// here, its values in [`CurvesDefinition`], and one arm in [`run_curve`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(crate) enum Knob {
    /// The uniform misclassification cost, no budget.
    Mc,
    /// A budget per object in price: a share of the price of every test.
    Budget,
    /// A budget per object of at most `k` distinct tests.
    MaxTests,
    /// CEGB's `cegb_tradeoff`: its penalty per object newly paying for a feature, per
    /// unit of the feature's price.
    Tradeoff,
}

impl Knob {
    /// The knob's name in the CSV, as its flag names it.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Knob::Mc => "mc",
            Knob::Budget => "budget",
            Knob::MaxTests => "max-tests",
            Knob::Tradeoff => "tradeoff",
        }
    }

    /// The knob in a table's head.
    fn short(self) -> &'static str {
        match self {
            Knob::Mc => "mc",
            Knob::Budget => "price budget",
            Knob::MaxTests => "k tests",
            Knob::Tradeoff => "tradeoff",
        }
    }

    /// The knob in a figure's legend, after the learner's name.
    fn legend(self) -> &'static str {
        match self {
            Knob::Mc => "over mc",
            Knob::Budget => "within a price budget",
            Knob::MaxTests => "within k tests",
            Knob::Tradeoff => "over its tradeoff",
        }
    }
}

/// One learner swept over one knob. Its learner is written as the benchmark writes its
/// learners (the family's as they always were, CEGB as `"cegb"`), so results written
/// before CEGB had a curve read and write back byte for byte.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub(crate) struct Curve {
    pub learner: Learner,
    pub knob: Knob,
}

impl Curve {
    /// `eg2, price budget`, `dtmc, mc`, `c45, k tests`.
    pub(crate) fn label(self) -> String {
        format!("{}, {}", self.learner.name(), self.knob.short())
    }
}

/// The knobs a learner is swept over: mc where its tree depends on it, the budgets where
/// it is a budget learner; CEGB's tradeoff for CEGB.
fn knobs_of(learner: Learner, budget_learner: bool, def: &CurvesDefinition) -> Vec<Knob> {
    let learner = match learner {
        Learner::Cegb if def.tradeoffs.is_empty() => return Vec::new(),
        Learner::Cegb => return vec![Knob::Tradeoff],
        Learner::Family(m) => m,
    };
    let mut knobs = Vec::new();
    if learner.depends_on_mc() && !def.benchmark.mc.is_empty() {
        knobs.push(Knob::Mc);
    }
    if budget_learner && !def.budgets.is_empty() {
        knobs.push(Knob::Budget);
    }
    if budget_learner && !def.max_tests.is_empty() {
        knobs.push(Knob::MaxTests);
    }
    knobs
}

/// What a sweep is: shards must agree on it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct CurvesDefinition {
    /// The benchmark whose folds, prices and settings every job uses: its learners are
    /// the curves' learners, its `mc` the mc curves' values; it has no budget.
    pub benchmark: Definition,
    /// The curves, in order.
    pub curves: Vec<Curve>,
    /// The budget curves' shares of the price of every test.
    pub budgets: Vec<f64>,
    /// The k-tests curves' budgets.
    pub max_tests: Vec<usize>,
    /// The mc of the budget curves (and of the tradeoff curve's total cost).
    pub budget_mc: f64,
    /// CEGB's tradeoffs, where it has a curve; results written before it existed have
    /// none (and a definition without them is written as before).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tradeoffs: Vec<f64>,
}

impl CurvesDefinition {
    /// Adds `other`'s curves of the learners this definition does not have, and returns
    /// those learners; refused unless `other` is the same sweep but for its learners
    /// (data sets, prices, draws, runs, folds, seed, settings and every knob's values,
    /// CEGB's tradeoffs where both have them).
    fn join(&mut self, other: &CurvesDefinition) -> Result<Vec<Learner>> {
        let tradeoffs = match (self.tradeoffs.is_empty(), other.tradeoffs.is_empty()) {
            (true, _) => other.tradeoffs.clone(),
            (false, true) => self.tradeoffs.clone(),
            (false, false) => {
                if self.tradeoffs != other.tradeoffs {
                    bail!("its CEGB tradeoffs differ from this sweep's");
                }
                self.tradeoffs.clone()
            }
        };
        let same = CurvesDefinition {
            benchmark: Definition {
                learners: self.benchmark.learners.clone(),
                voi: self.benchmark.voi,
                voi_by_width: self.benchmark.voi_by_width,
                ..other.benchmark.clone()
            },
            curves: self.curves.clone(),
            tradeoffs: self.tradeoffs.clone(),
            ..other.clone()
        };
        if same != *self {
            bail!(
                "it was run over other data sets, prices, folds, seed, settings or knob values \
                 ({other:?}, against {self:?})"
            );
        }
        let new: Vec<Learner> = other
            .benchmark
            .learners
            .iter()
            .filter(|l| !self.benchmark.learners.contains(l))
            .copied()
            .collect();
        self.benchmark.learners.extend(new.iter().copied());
        if new.contains(&Learner::Family(Method::Voi)) {
            self.benchmark.take_voi(&other.benchmark);
        }
        self.curves.extend(
            other
                .curves
                .iter()
                .filter(|c| new.contains(&c.learner))
                .copied(),
        );
        self.tradeoffs = tradeoffs;
        Ok(new)
    }

    /// The values a curve of `knob` takes, in order.
    fn values(&self, knob: Knob) -> Vec<f64> {
        match knob {
            Knob::Mc => self.benchmark.mc.clone(),
            Knob::Budget => self.budgets.clone(),
            Knob::MaxTests => self.max_tests.iter().map(|&k| k as f64).collect(),
            Knob::Tradeoff => self.tradeoffs.clone(),
        }
    }
}

/// One job's result: a curve's points on one run under one price assignment.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct CurveResult {
    pub id: u64,
    pub dataset: String,
    pub costs: PriceSet,
    pub assignment: u64,
    pub run: u64,
    pub curve: Curve,
    /// The price of every test under the job's prices (discounts applied, in the cheapest
    /// order): what a normalised cost is a share of.
    pub all_tests: f64,
    /// One per value of the curve's knob, in the definition's order.
    pub points: Vec<Score>,
    /// Mean nodes per tree.
    pub nodes: f64,
    /// CPU seconds to learn every fold's trees (a measurement).
    pub learn_seconds: f64,
    /// CPU seconds to classify every object.
    pub classify_seconds: f64,
    /// For a learner run through another library (CEGB), that library's version and
    /// settings, one line; absent for the family's learners (and so in results written
    /// before CEGB had a curve).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub library: Option<String>,
}

impl JobLine for CurveResult {
    fn id(&self) -> u64 {
        self.id
    }
}

/// One job: the benchmark's job (its learner the curve's) and the curve.
#[derive(Clone, Copy, Debug)]
struct CurveJob {
    job: Job,
    curve: usize,
}

/// The job list in its fixed order: data set, price set, assignment, run, curve.
fn jobs(def: &CurvesDefinition, priced: &[Priced]) -> Vec<CurveJob> {
    let base = &def.benchmark;
    let mut out = Vec::new();
    for (d, priced) in priced.iter().enumerate() {
        for &costs in &base.costs {
            for assignment in 0..priced.assignments(base, costs) {
                for run in 0..base.runs {
                    for (c, curve) in def.curves.iter().enumerate() {
                        let learner = base
                            .learners
                            .iter()
                            .position(|&m| m == curve.learner)
                            .unwrap_or(0);
                        out.push(CurveJob {
                            job: Job {
                                dataset: d,
                                costs,
                                assignment,
                                run,
                                learner,
                            },
                            curve: c,
                        });
                    }
                }
            }
        }
    }
    out
}

/// A budget of `share` of the price of every test, `all`: no limit from 1 on (an object
/// that buys every test in the cheapest order pays `all`).
fn share_budget(share: f64, all: f64) -> Result<Budget> {
    let max = (share < 1.0).then_some(share * all);
    Budget::new(max, None).map_err(|e| anyhow!("--budgets {share}: {e}"))
}

/// Runs one job: the curve's every point on one run of cross-validation. CEGB's curve
/// runs through `peer`'s workers (which must be there when the sweep has it).
fn run_curve(
    def: &CurvesDefinition,
    id: u64,
    cj: CurveJob,
    name: &str,
    (loaded, unit): (&Loaded, bool),
    peer: Option<&cegb::Peer>,
) -> Result<CurveResult> {
    let base = &def.benchmark;
    let job = cj.job;
    let curve = def.curves[cj.curve];
    let frame = &loaded.frame;
    let prices = job_prices(
        base,
        name,
        frame,
        loaded.turney.as_ref(),
        unit,
        job.costs,
        job.assignment,
    )?;
    let all_tests = prices.total();
    let result = |points, nodes, learn_seconds, classify_seconds, library| CurveResult {
        id,
        dataset: name.to_string(),
        costs: job.costs,
        assignment: job.assignment,
        run: job.run,
        curve,
        all_tests,
        points,
        nodes,
        learn_seconds,
        classify_seconds,
        library,
    };
    let (mc, budgets) = match curve.knob {
        Knob::Tradeoff => {
            let peer = peer.context("CEGB's curve has no worker to run it")?;
            let swept = cegb::sweep_job(
                base,
                job,
                name,
                (frame, &prices),
                (&def.tradeoffs, def.budget_mc),
                peer,
            )?;
            return Ok(result(
                swept.points,
                swept.nodes,
                swept.learn_seconds,
                swept.classify_seconds,
                Some(peer.sweep_description().to_string()),
            ));
        }
        Knob::Mc => (base.mc.clone(), vec![Budget::UNLIMITED]),
        Knob::Budget => (
            vec![def.budget_mc],
            def.budgets
                .iter()
                .map(|&s| share_budget(s, all_tests))
                .collect::<Result<_>>()?,
        ),
        Knob::MaxTests => (
            vec![def.budget_mc],
            def.max_tests
                .iter()
                .map(|&k| Budget::new(None, Some(k)))
                .collect::<Result<_, _>>()?,
        ),
    };
    let measured = cross_validate(base, job, name, frame, &prices, &mc, &budgets)?;
    let points = match curve.knob {
        // One budget, a score per mc.
        Knob::Mc => measured.by_budget.into_iter().flatten().collect(),
        // One mc, a score per budget.
        Knob::Budget | Knob::MaxTests | Knob::Tradeoff => measured
            .by_budget
            .into_iter()
            .filter_map(|scores| scores.into_iter().next())
            .collect(),
    };
    Ok(result(
        points,
        measured.nodes,
        measured.learn_seconds,
        measured.classify_seconds,
        None,
    ))
}

/// The area under accuracy against normalised test cost on [0, 1], step-interpolated:
/// the integral over x in [0, 1] of the best accuracy among the points `(cost, accuracy)`
/// that cost at most x, the accuracy `at_no_cost` (answering the majority class without a
/// test) counting as a point at cost 0. A point costing 1 or more adds nothing (its step
/// starts where the interval ends); points whose cost or accuracy is not a number are
/// left out.
pub(crate) fn area(at_no_cost: f64, points: &[(f64, f64)]) -> f64 {
    let mut inside: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(c, a)| c.is_finite() && a.is_finite() && *c < 1.0)
        .map(|(c, a)| (c.max(0.0), a))
        .collect();
    inside.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut x, mut best, mut sum) = (0.0, at_no_cost, 0.0);
    for (c, a) in inside {
        sum += best * (c - x);
        x = c;
        best = best.max(a);
    }
    sum + best * (1.0 - x)
}

/// The accuracy of answering, for each held-out object, the majority class of its
/// training folds without a test (ties to the first class, as a tree's leaf answers under
/// uniform costs), mean over the runs: on the benchmark's folds of `name`.
fn majority_accuracy(def: &Definition, name: &str, frame: &Frame) -> f64 {
    let mut sum = 0.0;
    for run in 0..def.runs {
        let mut right = 0usize;
        for test in folds(frame, def.folds, mix(def.seed, name, &[2, run])) {
            let mut counts = frame.class_totals();
            for &r in &test {
                counts[frame.class(r) as usize] -= 1;
            }
            let mut majority = 0;
            for (c, &n) in counts.iter().enumerate() {
                if n > counts[majority] {
                    majority = c;
                }
            }
            right += test
                .iter()
                .filter(|&&r| frame.class(r) as usize == majority)
                .count();
        }
        sum += right as f64 / frame.len() as f64;
    }
    sum / def.runs.max(1) as f64
}

/// A mean and the half-width of its 95% interval (Student's t; `None` from one value).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Spread {
    pub mean: f64,
    pub ci95: Option<f64>,
}

impl Spread {
    fn of(values: &[f64]) -> Spread {
        Spread {
            mean: values.iter().sum::<f64>() / values.len().max(1) as f64,
            ci95: crate::stats::ci95(values),
        }
    }
}

/// One point of a curve: the mean over runs and draws at one knob value.
#[derive(Clone, Debug)]
pub(crate) struct Point {
    pub dataset: String,
    pub costs: PriceSet,
    pub curve: Curve,
    /// The knob's value (mc, share or k).
    pub knob: f64,
    pub mc: f64,
    /// The (run, draw) pairs averaged.
    pub n: usize,
    pub accuracy: Spread,
    /// `None` where a job did not measure it (a single class).
    pub auroc: Option<Spread>,
    pub test_cost: Spread,
    pub normalised: Spread,
    pub total: Spread,
}

/// One curve's summary: its area and its most accurate point.
#[derive(Clone, Debug)]
pub(crate) struct Summary {
    pub dataset: String,
    pub costs: PriceSet,
    pub curve: Curve,
    pub area: f64,
    /// The most accurate point's accuracy and mean normalised cost (the cheaper on ties).
    pub best: (f64, f64),
}

/// The points, in the order of data sets, price sets, curves and knob values.
fn aggregate(def: &CurvesDefinition, results: &[CurveResult]) -> Vec<Point> {
    type Key = (String, PriceSet, Curve);
    let mut by: BTreeMap<Key, Vec<&CurveResult>> = BTreeMap::new();
    for r in results {
        by.entry((r.dataset.clone(), r.costs, r.curve))
            .or_default()
            .push(r);
    }
    let mut points = Vec::new();
    for d in &def.benchmark.datasets {
        for &costs in &def.benchmark.costs {
            for &curve in &def.curves {
                let Some(jobs) = by.get(&(d.clone(), costs, curve)) else {
                    continue;
                };
                for (i, &knob) in def.values(curve.knob).iter().enumerate() {
                    let at: Vec<(&Score, f64)> = jobs
                        .iter()
                        .filter_map(|r| r.points.get(i).map(|s| (s, r.all_tests)))
                        .collect();
                    let of = |f: &dyn Fn(&Score, f64) -> f64| {
                        Spread::of(&at.iter().map(|&(s, all)| f(s, all)).collect::<Vec<_>>())
                    };
                    let aurocs: Option<Vec<f64>> = at.iter().map(|(s, _)| s.auroc).collect();
                    points.push(Point {
                        dataset: d.clone(),
                        costs,
                        curve,
                        knob,
                        mc: at.first().map_or(f64::NAN, |(s, _)| s.mc),
                        n: at.len(),
                        accuracy: of(&|s, _| 1.0 - s.error_rate),
                        auroc: aurocs.map(|a| Spread::of(&a)),
                        test_cost: of(&|s, _| s.tests),
                        normalised: of(&|s, all| if all > 0.0 { s.tests / all } else { 0.0 }),
                        total: of(&|s, _| s.total),
                    });
                }
            }
        }
    }
    points
}

/// Each curve's area and best point, in the points' order.
fn summarise(points: &[Point], majority: &BTreeMap<String, f64>) -> Vec<Summary> {
    let mut out: Vec<Summary> = Vec::new();
    for p in points {
        let same = |s: &Summary| s.dataset == p.dataset && s.costs == p.costs && s.curve == p.curve;
        if out.last().is_some_and(same) {
            continue;
        }
        let mine: Vec<&Point> = points
            .iter()
            .filter(|q| q.dataset == p.dataset && q.costs == p.costs && q.curve == p.curve)
            .collect();
        let xy: Vec<(f64, f64)> = mine
            .iter()
            .map(|q| (q.normalised.mean, q.accuracy.mean))
            .collect();
        let best = xy
            .iter()
            .copied()
            .fold((f64::NEG_INFINITY, 0.0), |b, (c, a)| {
                if a > b.0 || (a == b.0 && c < b.1) {
                    (a, c)
                } else {
                    b
                }
            });
        out.push(Summary {
            dataset: p.dataset.clone(),
            costs: p.costs,
            curve: p.curve,
            area: area(majority.get(&p.dataset).copied().unwrap_or(0.0), &xy),
            best,
        });
    }
    out
}

/// The data sets a sweep runs: those named, or every data set of the manifest (the
/// benchmark's and those kept for budgets and curves).
fn datasets_of(catalogue: &cslearn::testcost::Catalogue, named: &[String]) -> Vec<String> {
    if named.is_empty() {
        catalogue.sources().iter().map(|s| s.name.clone()).collect()
    } else {
        named.to_vec()
    }
}

/// `cargo xtask budget`.
pub fn budget(args: &BudgetArgs) -> Result<()> {
    let catalogue = cslearn::testcost::Catalogue::read(&args.manifest)?;
    let datasets = datasets_of(&catalogue, &args.datasets);
    let learners: Vec<Learner> = args
        .learners
        .iter()
        .map(|l| Learner::parse(l))
        .collect::<Result<_>>()?;
    crate::files::distinct("--learners", &args.learners)?;
    let budget_learners: Vec<Learner> = if args.budget_learners.is_empty() {
        learners
            .iter()
            .copied()
            .filter(|l| {
                l.method()
                    .is_some_and(|m| !m.depends_on_mc() || m.grows_within_budget())
            })
            .collect()
    } else {
        args.budget_learners
            .iter()
            .map(|l| {
                Method::parse(l).map(Learner::Family).map_err(|e| {
                    if l == "cegb" {
                        anyhow!(
                            "--budget-learners cegb: LightGBM's trees cannot be cut where an \
                             object's budget ends; CEGB's curve is over its tradeoff \
                             (--tradeoffs)"
                        )
                    } else {
                        anyhow!("--budget-learners: {e}")
                    }
                })
            })
            .collect::<Result<_>>()?
    };
    crate::files::distinct("--budget-learners", &args.budget_learners)?;
    if let Some(m) = budget_learners.iter().find(|m| !learners.contains(m)) {
        bail!(
            "--budget-learners names `{}`, which --learners does not",
            m.name()
        );
    }
    let with_cegb = learners.contains(&Learner::Cegb);
    if !args.tradeoffs.is_empty() && !with_cegb {
        bail!("--tradeoffs are CEGB's: they need `cegb` among --learners");
    }
    if let Some(t) = args
        .tradeoffs
        .iter()
        .find(|t| !(t.is_finite() && **t >= 0.0))
    {
        bail!("--tradeoffs {t}: a tradeoff is a finite number of at least 0");
    }
    crate::files::distinct("--tradeoffs", &args.tradeoffs)?;
    let tradeoffs = match (with_cegb, args.tradeoffs.is_empty()) {
        (false, _) => Vec::new(),
        (true, true) => cegb::tradeoff_grid(),
        (true, false) => args.tradeoffs.clone(),
    };
    if args.mc.is_empty() || args.mc.iter().any(|m| !m.is_finite() || *m < 0.0) {
        bail!("--mc: every misclassification cost must be a finite number of at least 0");
    }
    crate::files::distinct("--mc", &args.mc)?;
    if let Some(b) = args.budgets.iter().find(|b| !(b.is_finite() && **b >= 0.0)) {
        bail!("--budgets {b}: a budget is a share of the price of every test, at least 0");
    }
    crate::files::distinct("--budgets", &args.budgets)?;
    crate::files::distinct("--max-tests", &args.max_tests)?;
    if !(args.budget_mc.is_finite() && args.budget_mc >= 0.0) {
        bail!(
            "--budget-mc {}: a misclassification cost must be a finite number of at least 0",
            args.budget_mc
        );
    }
    let Prepared {
        catalogue: _,
        datasets,
        def: benchmark,
        loaded,
        priced,
    } = prepare(&TestcostArgs {
        datasets,
        learners: args.learners.clone(),
        mc: args.mc.clone(),
        costs: args.costs.clone(),
        assignments: args.assignments,
        price_draw: "uniform".into(),
        selection_prices: "listed".into(),
        icet_pruning: "costs".into(),
        icet_search_objects: 1000,
        cvt_folds: 5,
        act_samples: 5,
        cvt_samples: 5,
        voi_lookahead: None,
        voi_confidence: None,
        voi_m: None,
        max_tests: None,
        max_test_cost: None,
        price_range: vec![1.0, 100.0],
        runs: args.runs,
        folds: args.folds,
        seed: args.seed,
        manifest: args.manifest.clone(),
        out: args.out.clone(),
        threads: args.threads,
        shard: args.shard.clone(),
        with: Vec::new(),
        python: args.python.clone(),
        report: args.report,
        bless: false,
    })?;
    let mut def = CurvesDefinition {
        benchmark,
        curves: Vec::new(),
        budgets: args.budgets.clone(),
        max_tests: args.max_tests.clone(),
        budget_mc: args.budget_mc,
        tradeoffs,
    };
    for &learner in &learners {
        let knobs = knobs_of(learner, budget_learners.contains(&learner), &def);
        if knobs.is_empty() {
            bail!(
                "--learners names `{}`, which has no curve: its tree does not depend on mc, \
                 and it is not among --budget-learners (or --budgets and --max-tests are empty)",
                learner.name()
            );
        }
        def.curves
            .extend(knobs.into_iter().map(|knob| Curve { learner, knob }));
    }
    if !args.report {
        let list = jobs(&def, &priced);
        // CEGB's workers: one Python per worker thread that runs its curves, started once.
        let peer = if with_cegb {
            let peer = cegb::Peer::start(args.python.as_deref())?;
            if args.tradeoffs.is_empty() && peer.grid().as_ref() != Some(&def.tradeoffs) {
                bail!(
                    "CEGB's worker chooses its tradeoff among {:?}, not the grid this sweep \
                     takes by default ({:?}); give --tradeoffs",
                    peer.grid(),
                    def.tradeoffs
                );
            }
            Some(peer)
        } else {
            None
        };
        crate::shard::run_shard(
            &args.out,
            &args.shard,
            def.clone(),
            list.len() as u64,
            args.threads,
            |id| {
                let cj = list[id as usize];
                let frame = &loaded[cj.job.dataset].frame;
                let curve = def.curves[cj.curve];
                // The trees a job grows: one set per mc or per budget where they differ;
                // CEGB's sweep, one model per tradeoff against the 110 of its
                // cross-validation per mc that the benchmark's estimate counts.
                let fits = match curve.knob {
                    Knob::Mc => def.benchmark.mc.len() as f64,
                    Knob::Tradeoff => def.tradeoffs.len() as f64 / 110.0,
                    _ if curve
                        .learner
                        .method()
                        .is_some_and(Method::grows_within_budget) =>
                    {
                        def.values(curve.knob).len() as f64
                    }
                    _ => 1.0,
                };
                work(curve.learner, frame.len(), frame.feature_count()) * fits
            },
            |id| {
                let cj = list[id as usize];
                let d = cj.job.dataset;
                run_curve(
                    &def,
                    id,
                    cj,
                    &datasets[d],
                    (&loaded[d], priced[d].unit),
                    peer.as_ref(),
                )
            },
        )?;
        if crate::shard::one_of_several(&args.shard, "budget")? {
            return Ok(());
        }
    }
    let by_id: BTreeMap<u64, CurveResult> = crate::shard::collect_of(&args.out, &def)?;
    let mut results: Vec<CurveResult> = by_id.into_values().collect();
    for dir in &args.with {
        let (other, by_id): (CurvesDefinition, BTreeMap<u64, CurveResult>) =
            crate::shard::collect(std::slice::from_ref(dir))?;
        let joined = def.join(&other).with_context(|| {
            format!(
                "--with {}: its curves cannot join this report",
                dir.display()
            )
        })?;
        results.extend(
            by_id
                .into_values()
                .filter(|r| joined.contains(&r.curve.learner)),
        );
    }
    let points = aggregate(&def, &results);
    let majority: BTreeMap<String, f64> = datasets
        .iter()
        .zip(&loaded)
        .map(|(d, l)| (d.clone(), majority_accuracy(&def.benchmark, d, &l.frame)))
        .collect();
    let summaries = summarise(&points, &majority);
    let shapes: BTreeMap<String, Shape> = datasets
        .iter()
        .zip(&loaded)
        .zip(&priced)
        .map(|((d, l), p)| {
            let shape = Shape {
                objects: l.frame.len(),
                tests: l.frame.feature_count(),
                unit: p.unit,
            };
            (d.clone(), shape)
        })
        .collect();
    let report = Report {
        def: &def,
        points: &points,
        summaries: &summaries,
        majority: &majority,
        shapes: &shapes,
        command: args_line(args),
        library: results.iter().find_map(|r| r.library.clone()),
    };
    report.write(&args.out)?;
    if args.bless {
        report.write(Path::new("docs/testcost/budget"))?;
    }
    Ok(())
}

/// Everything the outputs are made of.
struct Report<'a> {
    def: &'a CurvesDefinition,
    points: &'a [Point],
    summaries: &'a [Summary],
    /// Per data set, the accuracy of the majority class with no test.
    majority: &'a BTreeMap<String, f64>,
    /// Per data set, its size and whether every test costs 1.
    shapes: &'a BTreeMap<String, Shape>,
    command: String,
    /// The library CEGB's curve ran on (its version and settings), as its results say.
    library: Option<String>,
}

/// A data set's size, and whether its random prices are every test at 1.
#[derive(Clone, Copy, Debug, Default)]
struct Shape {
    objects: usize,
    tests: usize,
    unit: bool,
}

/// A number with `d` decimals, or nothing.
fn cell(x: Option<f64>, d: usize) -> String {
    x.map_or(String::new(), |x| format!("{x:.d$}"))
}

/// GDFS on Spambase, as its authors' notebook reports it (Covert et al., ICML 2023;
/// `data/uci/spambase/README.md`): k, accuracy % and AUROC % on 920 test objects.
const GDFS_SPAMBASE: [(usize, f64, f64); 8] = [
    (1, 78.48, 82.74),
    (2, 82.28, 88.83),
    (3, 85.76, 92.62),
    (4, 90.54, 95.25),
    (5, 90.87, 95.76),
    (10, 92.17, 96.92),
    (15, 93.37, 97.99),
    (25, 93.80, 97.97),
];

impl Report<'_> {
    /// `budget.csv`, `budget.md` and one SVG per data set into `dir`.
    fn write(&self, dir: &Path) -> Result<()> {
        crate::files::create_dir(dir)?;
        crate::files::write_atomic(&dir.join("budget.csv"), self.csv())?;
        crate::files::write_atomic(&dir.join("budget.md"), self.markdown())?;
        for d in &self.def.benchmark.datasets {
            figure(&dir.join(svg_name(d)), self, d)?;
        }
        crate::note(&format!(
            "wrote {}/budget.csv, budget.md and {} figures",
            dir.display(),
            self.def.benchmark.datasets.len()
        ));
        Ok(())
    }

    /// One line per point.
    fn csv(&self) -> String {
        let mut out = String::from(
            "dataset,costs,learner,curve,knob,mc,runs,folds,accuracy,accuracy_ci95,auroc,\
             auroc_ci95,test_cost,test_cost_ci95,normalised_test_cost,normalised_ci95,\
             total_cost,total_ci95\n",
        );
        for p in self.points {
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{},{:.4},{},{},{},{:.4},{},{:.5},{},{:.3},{}",
                p.dataset,
                p.costs.name(),
                p.curve.learner.name(),
                p.curve.knob.name(),
                p.knob,
                p.mc,
                p.n,
                self.def.benchmark.folds,
                p.accuracy.mean,
                cell(p.accuracy.ci95, 4),
                cell(p.auroc.map(|a| a.mean), 4),
                cell(p.auroc.and_then(|a| a.ci95), 4),
                p.test_cost.mean,
                cell(p.test_cost.ci95, 4),
                p.normalised.mean,
                cell(p.normalised.ci95, 5),
                p.total.mean,
                cell(p.total.ci95, 3),
            );
        }
        out
    }

    /// Per data set and price set, each curve's area and best point; the Spambase k table
    /// beside the published one; the figures.
    fn markdown(&self) -> String {
        let def = self.def;
        let base = &def.benchmark;
        let mut md = String::from("# Accuracy against test cost: budget curves\n\n");
        let _ = writeln!(
            md,
            "Written by `{}`. The benchmark's folds and prices ({} run{} of {}-fold \
             stratified cross-validation; random prices: {} draw{} per data set, each test \
             uniform in [{}, {}], every test 1 where the manifest says `unit_prices`; \
             listed selection prices, ICET pruned by costs). Curves: each learner whose \
             tree depends on mc over mc in {{{}}}; the budget learners over a budget of a \
             share {{{}}} of the price of every test, and of at most k in {{{}}} tests, at \
             mc {}.{} The **area** is that under accuracy against the test cost per object \
             over the price of every test, on [0, 1]: at each cost the best accuracy of the \
             curve's points that cost no more, the majority class's with no test below its \
             cheapest (`docs/specification.md`, 2.8). Accuracy and area in %; `budget.csv` \
             has every point, with AUROC, test and total costs and their 95% intervals. \
             `docs/testcost.md` reads the results.\n",
            self.command,
            base.runs,
            if base.runs == 1 { "" } else { "s" },
            base.folds,
            base.assignments,
            if base.assignments == 1 { "" } else { "s" },
            base.price_range.0,
            base.price_range.1,
            join(&base.mc),
            join(&def.budgets),
            def.max_tests
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", "),
            def.budget_mc,
            self.tradeoff_sentence(),
        );
        let _ = writeln!(md, "## The area under each curve\n");
        let _ = write!(md, "| data set | prices | majority, no test |");
        for c in &def.curves {
            let _ = write!(md, " {} |", c.label());
        }
        let _ = writeln!(md, " best area |");
        let _ = writeln!(md, "|---|---|---|{}---|", "---|".repeat(def.curves.len()));
        for d in &base.datasets {
            for &costs in &base.costs {
                let mine: Vec<&Summary> = self
                    .summaries
                    .iter()
                    .filter(|s| &s.dataset == d && s.costs == costs)
                    .collect();
                if mine.is_empty() {
                    continue;
                }
                let top = mine
                    .iter()
                    .map(|s| s.area)
                    .fold(f64::NEG_INFINITY, f64::max);
                let _ = write!(
                    md,
                    "| {d} | {} | {:.1} |",
                    costs.name(),
                    100.0 * self.majority.get(d).copied().unwrap_or(f64::NAN)
                );
                for c in &def.curves {
                    match mine.iter().find(|s| s.curve == *c) {
                        Some(s)
                            if format!("{:.1}", 100.0 * s.area)
                                == format!("{:.1}", 100.0 * top) =>
                        {
                            let _ = write!(md, " **{:.1}** |", 100.0 * s.area);
                        }
                        Some(s) => {
                            let _ = write!(md, " {:.1} |", 100.0 * s.area);
                        }
                        None => md.push_str(" |"),
                    }
                }
                let best: Vec<String> = mine
                    .iter()
                    .filter(|s| format!("{:.1}", 100.0 * s.area) == format!("{:.1}", 100.0 * top))
                    .map(|s| s.curve.label())
                    .collect();
                let _ = writeln!(md, " {} |", best.join(", "));
            }
        }
        let _ = writeln!(
            md,
            "\nEach curve's most accurate point (accuracy %, at its test cost as a share of \
             the price of every test):\n"
        );
        let _ = write!(md, "| data set | prices |");
        for c in &def.curves {
            let _ = write!(md, " {} |", c.label());
        }
        let _ = writeln!(md, "\n|---|---|{}", "---|".repeat(def.curves.len()));
        for d in &base.datasets {
            for &costs in &base.costs {
                let mine: Vec<&Summary> = self
                    .summaries
                    .iter()
                    .filter(|s| &s.dataset == d && s.costs == costs)
                    .collect();
                if mine.is_empty() {
                    continue;
                }
                let _ = write!(md, "| {d} | {} |", costs.name());
                for c in &def.curves {
                    match mine.iter().find(|s| s.curve == *c) {
                        Some(s) => {
                            let _ = write!(md, " {:.1} at {:.3} |", 100.0 * s.best.0, s.best.1);
                        }
                        None => md.push_str(" |"),
                    }
                }
                md.push('\n');
            }
        }
        md.push_str(&self.spambase_table());
        let _ = writeln!(md, "\n## Figures\n");
        for d in &base.datasets {
            let _ = writeln!(md, "![{d}: accuracy against test cost]({})\n", svg_name(d));
        }
        md
    }

    /// What CEGB's curve is, for the header (with a space before it), where the sweep has
    /// it; nothing otherwise, so that a report without it reads as before.
    fn tradeoff_sentence(&self) -> String {
        let def = self.def;
        if !def.curves.iter().any(|c| c.knob == Knob::Tradeoff) {
            return String::new();
        }
        let values = if def.tradeoffs == cegb::tradeoff_grid() {
            "0 and 21 values from 0.0001 to 10 in quarter decades, the grid its \
             cross-validation chooses from in `cargo xtask testcost`"
                .to_string()
        } else {
            format!("{{{}}}", join(&def.tradeoffs))
        };
        format!(
            " CEGB over its `cegb_tradeoff` ({values}): at each value a model trained on \
             each training part, with no cross-validation inside it, its total cost counted \
             at mc {}{}.",
            def.budget_mc,
            self.library
                .as_ref()
                .map_or(String::new(), |l| format!(" ({l})"))
        )
    }

    /// Spambase within k tests beside GDFS's published figures, for every k of the run
    /// that has one, where the run has Spambase and a k-tests curve.
    fn spambase_table(&self) -> String {
        let k_curves: Vec<Curve> = self
            .def
            .curves
            .iter()
            .copied()
            .filter(|c| c.knob == Knob::MaxTests)
            .collect();
        let here = |k: usize, c: Curve| {
            self.points.iter().find(|p| {
                p.dataset == "spambase"
                    && p.costs == PriceSet::Random
                    && p.curve == c
                    && p.knob == k as f64
            })
        };
        let ks: Vec<&(usize, f64, f64)> = GDFS_SPAMBASE
            .iter()
            .filter(|(k, _, _)| k_curves.iter().any(|&c| here(*k, c).is_some()))
            .collect();
        if ks.is_empty() {
            return String::new();
        }
        let mut md = String::from(
            "\n## Spambase within k tests, beside greedy dynamic feature selection\n\n\
             Accuracy % (AUROC %) within a hard budget of k tests per object, every test \
             priced 1. Ours: the benchmark's 10-fold cross-validation on all 4,601 objects. \
             GDFS (Covert et al., ICML 2023): the authors' notebook, one 60/20/20 split, 920 \
             test objects (`data/uci/spambase/README.md`).\n\n| k |",
        );
        for c in &k_curves {
            let _ = write!(md, " {} |", c.learner.name());
        }
        md.push_str(" GDFS, published |\n|---|");
        md.push_str(&"---|".repeat(k_curves.len() + 1));
        md.push('\n');
        for &&(k, accuracy, auroc) in &ks {
            let _ = write!(md, "| {k} |");
            for &c in &k_curves {
                match here(k, c) {
                    Some(p) => {
                        let _ = write!(
                            md,
                            " {:.2} ({}) |",
                            100.0 * p.accuracy.mean,
                            p.auroc
                                .map_or("-".to_string(), |a| format!("{:.2}", 100.0 * a.mean))
                        );
                    }
                    None => md.push_str(" |"),
                }
            }
            let _ = writeln!(md, " {accuracy:.2} ({auroc:.2}) |");
        }
        md
    }
}

/// Numbers joined by `, `, each as Rust writes it.
fn join(values: &[f64]) -> String {
    values
        .iter()
        .map(f64::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

/// A data set's figure's file name.
fn svg_name(dataset: &str) -> String {
    format!("budget-{}.svg", crate::files::safe_name(dataset))
}

/// One data set's figure: a panel per price set, accuracy against normalised test cost
/// (log scale from the cheapest point's decade; the points that buy no test at a tick
/// `0` left of it, across a break), one line per curve through its points in order of
/// cost, a colour per learner (Okabe and Ito's palette, with a marker shape per curve, so
/// that it reads in grey), solid for mc and the budget, dashed for k tests; the majority
/// class's accuracy with no test as a grey dashed line. Under each panel a legend gives
/// every curve's area (on the linear axis, `area`).
fn figure(path: &Path, report: &Report<'_>, dataset: &str) -> Result<()> {
    crate::figures::register_font();
    let plot_err = |e: &dyn std::fmt::Display| anyhow!("drawing {}: {e}", path.display());
    let def = report.def;
    let costs: Vec<PriceSet> = def
        .benchmark
        .costs
        .iter()
        .copied()
        .filter(|&c| {
            report
                .points
                .iter()
                .any(|p| p.dataset == dataset && p.costs == c)
        })
        .collect();
    let majority = report.majority.get(dataset).copied().unwrap_or(f64::NAN);
    let shape = report.shapes.get(dataset).copied().unwrap_or_default();
    // The legend under each chart: the majority line and every curve, in two columns.
    let legend_rows = (def.curves.len() + 1).div_ceil(2);
    let legend_h = 16 + 22 * legend_rows as u32;
    // One panel wide enough for the title, two side by side.
    let (pw, ph) = (if costs.len() > 1 { 760_u32 } else { 900 }, 500_u32);
    let panels_n = costs.len().max(1) as u32;
    let mut svg = String::new();
    {
        let base = SVGBackend::with_string(&mut svg, (pw * panels_n, ph + legend_h + 40))
            .into_drawing_area();
        base.fill(&WHITE).map_err(|e| plot_err(&e))?;
        let root = base
            .titled(
                &format!(
                    "{dataset}: accuracy against test cost ({} objects, {} tests; {} of \
                     {} folds)",
                    shape.objects,
                    shape.tests,
                    match def.benchmark.runs {
                        1 => "one run".to_string(),
                        n => format!("{n} runs"),
                    },
                    def.benchmark.folds
                ),
                ("sans-serif", 20),
            )
            .map_err(|e| plot_err(&e))?;
        let panels = root.split_evenly((1, costs.len().max(1)));
        for (panel, &price_set) in panels.iter().zip(&costs) {
            let (upper, lower) = panel.split_vertically(ph);
            let mine: Vec<&Point> = report
                .points
                .iter()
                .filter(|p| p.dataset == dataset && p.costs == price_set)
                .collect();
            let accuracies = mine.iter().map(|p| p.accuracy.mean).chain([majority]);
            let (low, high) =
                accuracies.fold((1.0_f64, 0.0_f64), |(lo, hi), a| (lo.min(a), hi.max(a)));
            let y_lo = (((low - 0.03) * 20.0).floor() / 20.0).max(0.0);
            let y_hi = (((high + 0.03) * 20.0).ceil() / 20.0).min(1.0);
            // A log axis from the decade of the cheapest point that buys a test; the points
            // that buy none sit at a tick of their own, `0`, half a decade to its left.
            let least = mine
                .iter()
                .map(|p| p.normalised.mean)
                .filter(|&c| c > 0.0)
                .fold(1.0_f64, f64::min);
            let lo = 10f64.powf(least.log10().floor()).clamp(1e-6, 1e-2);
            let zero = lo / 10f64.sqrt();
            let decades = (-lo.log10()).round() as i32;
            let steps: &[f64] = if decades > 3 {
                &[1.0]
            } else {
                &[1.0, 2.0, 5.0]
            };
            let ticks: Vec<f64> = std::iter::once(zero)
                .chain((-decades..=0).flat_map(|e| steps.iter().map(move |m| m * 10f64.powi(e))))
                .filter(|&t| t == zero || (lo * 0.999..=1.0).contains(&t))
                .collect();
            let at = |c: f64| if c > 0.0 { c } else { zero };
            let caption = match price_set {
                PriceSet::Random if shape.unit => "every test priced 1".to_string(),
                PriceSet::Random if def.benchmark.assignments == 1 => {
                    "random prices, one draw".to_string()
                }
                PriceSet::Random => {
                    format!("random prices, {} draws", def.benchmark.assignments)
                }
                PriceSet::Turney => "Turney's prices, with group discounts".to_string(),
            };
            let mut chart = ChartBuilder::on(&upper)
                .caption(caption, ("sans-serif", 16))
                .margin(14)
                .x_label_area_size(48)
                .y_label_area_size(64)
                .build_cartesian_2d(
                    (zero / 1.4..1.3).log_scale().with_key_points(ticks),
                    y_lo..y_hi,
                )
                .map_err(|e| plot_err(&e))?;
            chart
                .configure_mesh()
                .x_desc("test cost per object / price of every test (log scale; 0: no test)")
                .y_desc("accuracy (share of objects right)")
                .axis_desc_style(("sans-serif", 15))
                .label_style(("sans-serif", 13))
                .light_line_style(WHITE)
                .bold_line_style(RGBColor(230, 230, 230))
                .x_label_formatter(&|x| {
                    if *x < lo * 0.999 {
                        "0".to_string()
                    } else {
                        format!("{x}")
                    }
                })
                .y_label_formatter(&|y| format!("{y:.2}"))
                .draw()
                .map_err(|e| plot_err(&e))?;
            let grey = RGBColor(120, 120, 120);
            chart
                .draw_series(DashedLineSeries::new(
                    [(zero / 1.4, majority), (1.3, majority)],
                    2,
                    4,
                    grey.stroke_width(2),
                ))
                .map_err(|e| plot_err(&e))?;
            // The axis's break between `0` and the log scale.
            let (bx, by) = chart.backend_coord(&((zero * lo).sqrt(), y_lo));
            let ink = RGBColor(60, 60, 60).stroke_width(1);
            base.draw(&Rectangle::new(
                [(bx - 4, by - 3), (bx + 4, by + 3)],
                WHITE.filled(),
            ))
            .map_err(|e| plot_err(&e))?;
            for dx in [-4, 2] {
                base.draw(&PathElement::new(
                    vec![(bx + dx - 2, by + 6), (bx + dx + 2, by - 6)],
                    ink,
                ))
                .map_err(|e| plot_err(&e))?;
            }
            // The legend's entries, in order: (label, colour, dashed, marker).
            let mut entries: Vec<(String, RGBColor, bool, Option<usize>)> = vec![(
                format!("majority class, no test ({:.1}%)", 100.0 * majority),
                grey,
                true,
                None,
            )];
            for (k, curve) in def.curves.iter().enumerate() {
                let mut points: Vec<(f64, f64)> = mine
                    .iter()
                    .filter(|p| p.curve == *curve)
                    .map(|p| (at(p.normalised.mean), p.accuracy.mean))
                    .collect();
                if points.is_empty() {
                    continue;
                }
                points.sort_by(|a, b| a.0.total_cmp(&b.0));
                let area = report
                    .summaries
                    .iter()
                    .find(|s| s.dataset == dataset && s.costs == price_set && s.curve == *curve)
                    .map_or(f64::NAN, |s| s.area);
                let learner = def
                    .benchmark
                    .learners
                    .iter()
                    .position(|&m| m == curve.learner)
                    .unwrap_or(0);
                let color = PALETTE[learner % PALETTE.len()];
                let style = color.stroke_width(2);
                let dashed = curve.knob == Knob::MaxTests;
                // The line joins the points that buy a test: across the break it would
                // draw a slope that is not there.
                let line: Vec<(f64, f64)> = points.iter().copied().filter(|p| p.0 > zero).collect();
                if dashed {
                    chart.draw_series(DashedLineSeries::new(line, 7, 4, style))
                } else {
                    chart.draw_series(LineSeries::new(line, style))
                }
                .map_err(|e| plot_err(&e))?;
                chart
                    .draw_series(
                        points.iter().map(|&p| {
                            EmptyElement::at(p) + marker::<SVGBackend<'_>>(k, (0, 0), color)
                        }),
                    )
                    .map_err(|e| plot_err(&e))?;
                entries.push((
                    format!(
                        "{} {}: area {:.1}",
                        curve.learner.name(),
                        curve.knob.legend(),
                        100.0 * area
                    ),
                    color,
                    dashed,
                    Some(k),
                ));
            }
            legend(&lower, &entries).map_err(|e| plot_err(&e))?;
        }
        root.present().map_err(|e| plot_err(&e))?;
    }
    crate::files::write_atomic(path, svg)
}

/// A legend in its own area, in two columns filled one after the other: a line sample
/// (dashed or solid) with the series' marker, and its label.
fn legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    entries: &[(String, RGBColor, bool, Option<usize>)],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (width, _) = area.dim_in_pixel();
    let column = (width as i32 - 80) / 2;
    let rows = entries.len().div_ceil(2);
    let font = ("sans-serif", 14).into_font().color(&BLACK);
    for (i, (label, color, dashed, mark)) in entries.iter().enumerate() {
        let x = 70 + column * (i / rows) as i32;
        let y = 14 + 22 * (i % rows) as i32;
        let style = color.stroke_width(2);
        let ends = vec![(x, y), (x + 28, y)];
        if *dashed {
            let dash = if mark.is_some() { 7 } else { 2 };
            area.draw(&plotters::element::DashedPathElement::new(
                ends, dash, 4, style,
            ))?;
        } else {
            area.draw(&PathElement::new(ends, style))?;
        }
        if let Some(k) = mark {
            area.draw(&(EmptyElement::at((x + 14, y)) + marker::<DB>(*k, (0, 0), *color)))?;
        }
        area.draw(&Text::new(label.clone(), (x + 38, y - 8), font.clone()))?;
    }
    Ok(())
}

/// The command that made a report, for its header.
fn args_line(args: &BudgetArgs) -> String {
    let mut line = String::from("cargo xtask budget");
    let list = |v: &[f64]| v.iter().map(f64::to_string).collect::<Vec<_>>().join(",");
    if !args.datasets.is_empty() {
        let _ = write!(line, " --datasets {}", args.datasets.join(","));
    }
    if args.learners.join(",") != "c45,eg2,dtmc,icet" {
        let _ = write!(line, " --learners {}", args.learners.join(","));
    }
    if !args.budget_learners.is_empty() {
        let _ = write!(
            line,
            " --budget-learners {}",
            args.budget_learners.join(",")
        );
    }
    if list(&args.mc) != "1,3,10,30,100,300,1000,3000,10000,30000,100000" {
        let _ = write!(line, " --mc {}", list(&args.mc));
    }
    if list(&args.budgets) != "0.01,0.02,0.05,0.1,0.2,0.5,1" {
        let _ = write!(line, " --budgets {}", list(&args.budgets));
    }
    let k: Vec<String> = args.max_tests.iter().map(usize::to_string).collect();
    if k.join(",") != "1,2,3,5,10" {
        let _ = write!(line, " --max-tests {}", k.join(","));
    }
    if !args.tradeoffs.is_empty() {
        let _ = write!(line, " --tradeoffs {}", list(&args.tradeoffs));
    }
    if args.budget_mc != 100_000.0 {
        let _ = write!(line, " --budget-mc {}", args.budget_mc);
    }
    if args.costs.join(",") != "random,turney" {
        let _ = write!(line, " --costs {}", args.costs.join(","));
    }
    if args.assignments != 2 {
        let _ = write!(line, " --assignments {}", args.assignments);
    }
    if args.runs != 2 {
        let _ = write!(line, " --runs {}", args.runs);
    }
    if args.folds != 10 {
        let _ = write!(line, " --folds {}", args.folds);
    }
    if args.seed != 1 {
        let _ = write!(line, " --seed {}", args.seed);
    }
    if !args.with.is_empty() {
        let with: Vec<String> = args.with.iter().map(|d| d.display().to_string()).collect();
        let _ = write!(line, " --with {}", with.join(","));
    }
    line
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testcost::JobResult;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-12
    }

    /// The area by hand: the best accuracy so far, stepped at each point's cost, from the
    /// majority class's at cost 0; a point at cost 0 counts from the start, a point past
    /// cost 1 not at all.
    #[test]
    fn the_area_steps_to_the_best_accuracy_so_far() {
        // No point: the majority class's accuracy over the whole interval.
        assert!(close(area(0.6, &[]), 0.6));
        // 0.6 on [0, 0.2), 0.8 on [0.2, 0.5), 0.9 on [0.5, 1]: 0.12 + 0.24 + 0.45.
        let two = [(0.2, 0.8), (0.5, 0.9)];
        assert!(close(area(0.6, &two), 0.81));
        // In any order.
        assert!(close(area(0.6, &[(0.5, 0.9), (0.2, 0.8)]), 0.81));
        // A dearer point less accurate than a cheaper one does not lower the step: 0.6 on
        // [0, 0.2), then 0.9 to the end.
        assert!(close(area(0.6, &[(0.2, 0.9), (0.4, 0.7)]), 0.12 + 0.72));
        // A point below the majority class's accuracy does not lower it either.
        assert!(close(area(0.6, &[(0.1, 0.5)]), 0.6));
        // A point at cost 0 counts from 0: 0.7 everywhere.
        assert!(close(area(0.6, &[(0.0, 0.7)]), 0.7));
        // A point past cost 1, or at 1, adds nothing; the rest is as without it.
        let clipped = [(0.5, 0.8), (1.5, 1.0), (1.0, 1.0)];
        assert!(close(area(0.6, &clipped), 0.3 + 0.4));
        // Nor does a point that is not a number.
        assert!(close(area(0.6, &[(f64::NAN, 1.0), (0.5, f64::NAN)]), 0.6));
        // Accuracy 1 from the cheapest point at 0.25: 0.6 / 4 + 3 / 4.
        assert!(close(area(0.6, &[(0.25, 1.0)]), 0.15 + 0.75));
    }

    fn args(out: &Path, threads: usize) -> BudgetArgs {
        BudgetArgs {
            datasets: vec!["iris".into(), "monks1".into()],
            learners: vec!["eg2".into(), "dtmc".into()],
            budget_learners: Vec::new(),
            mc: vec![100.0, 1000.0],
            budgets: vec![0.05, 1.0],
            max_tests: vec![0, 1, 10],
            budget_mc: 1000.0,
            tradeoffs: Vec::new(),
            costs: vec!["random".into()],
            assignments: 1,
            runs: 1,
            folds: 3,
            seed: 5,
            manifest: Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/uci/datasets.toml"),
            out: out.to_path_buf(),
            threads: Some(threads),
            shard: "1/1".into(),
            python: None,
            with: Vec::new(),
            report: false,
            bless: false,
        }
    }

    /// A learner's curves run alone join a sweep of the same protocol with `--with`: the
    /// joined report is the report of one sweep of every learner, byte for byte (its
    /// header's command aside), and a sweep over other folds is refused, naming it.
    #[test]
    fn curves_run_apart_join_as_one_sweep() {
        let (both, eg2, dtmc) = (
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
        );
        budget(&args(both.path(), 2)).unwrap();
        let mut alone = args(eg2.path(), 2);
        alone.learners = vec!["eg2".into()];
        budget(&alone).unwrap();
        let mut other = args(dtmc.path(), 2);
        other.learners = vec!["dtmc".into()];
        budget(&other).unwrap();
        let mut joined = alone.clone();
        (joined.report, joined.with) = (true, vec![dtmc.path().to_path_buf()]);
        budget(&joined).unwrap();
        let read = |dir: &Path, file: &str| std::fs::read_to_string(dir.join(file)).unwrap();
        assert_eq!(
            read(eg2.path(), "budget.csv"),
            read(both.path(), "budget.csv")
        );
        let body = |text: String| -> String {
            text.lines()
                .filter(|l| !l.contains("cargo xtask budget"))
                .collect::<Vec<_>>()
                .join("\n")
        };
        assert_eq!(
            body(read(eg2.path(), "budget.md")),
            body(read(both.path(), "budget.md"))
        );
        assert!(read(eg2.path(), "budget.md").contains(" --with "));
        // Other folds: refused.
        let elsewhere = tempfile::tempdir().unwrap();
        let mut seeded = other.clone();
        (seeded.out, seeded.seed) = (elsewhere.path().to_path_buf(), 6);
        budget(&seeded).unwrap();
        joined.with = vec![elsewhere.path().to_path_buf()];
        let err = format!("{:#}", budget(&joined).unwrap_err());
        assert!(err.contains("cannot join this report"), "{err}");
    }

    /// The results of a folder, by job.
    fn results<D, T>(dir: &Path) -> (D, Vec<T>)
    where
        D: serde::de::DeserializeOwned + PartialEq + Clone,
        T: JobLine,
    {
        let (def, by_id) = crate::shard::collect::<D, T>(&[dir.to_path_buf()]).unwrap();
        (def, by_id.into_values().collect())
    }

    /// A sweep on iris and monks1: the CSV has a row per curve and knob value, in order;
    /// the points are the benchmark's jobs at those settings, to the bit (no budget at
    /// all against a budget that binds no object); a budget of no test answers the
    /// majority class of the training folds; a budget in price is kept; the outputs do not
    /// depend on the thread count, and `--report` writes them again.
    #[test]
    fn a_sweep_is_the_benchmark_at_each_setting() {
        let (one, two) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
        budget(&args(one.path(), 1)).unwrap();
        budget(&args(two.path(), 2)).unwrap();
        let read = |dir: &Path, file: &str| std::fs::read_to_string(dir.join(file)).unwrap();
        let csv = read(one.path(), "budget.csv");
        assert_eq!(csv, read(two.path(), "budget.csv"));
        assert_eq!(read(one.path(), "budget.md"), read(two.path(), "budget.md"));
        // eg2 (its tree does not depend on mc): 2 budgets and 3 k; dtmc (it grows within
        // a budget): 2 mc, 2 budgets and 3 k.
        let rows: Vec<Vec<&str>> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').collect())
            .collect();
        let keys: Vec<String> = rows
            .iter()
            .map(|r| format!("{} {} {} {}", r[0], r[2], r[3], r[4]))
            .collect();
        let mut expected = Vec::new();
        for d in ["iris", "monks1"] {
            for knob in [
                "budget 0.05",
                "budget 1",
                "max-tests 0",
                "max-tests 1",
                "max-tests 10",
            ] {
                expected.push(format!("{d} eg2 {knob}"));
            }
            for knob in [
                "mc 100",
                "mc 1000",
                "budget 0.05",
                "budget 1",
                "max-tests 0",
                "max-tests 1",
                "max-tests 10",
            ] {
                expected.push(format!("{d} dtmc {knob}"));
            }
        }
        assert_eq!(keys, expected);
        assert!(
            rows.iter()
                .all(|r| r.len() == 18 && r[6] == "1" && r[7] == "3")
        );

        // The benchmark on the same folds and prices, at the budget curves' mc and the mc
        // curve's, without a budget.
        let plain = tempfile::tempdir().unwrap();
        let mut tc = crate::testcost::tests::args(plain.path(), 1);
        tc.datasets = vec!["iris".into(), "monks1".into()];
        tc.learners = vec!["eg2".into(), "dtmc".into()];
        tc.mc = vec![100.0, 1000.0];
        tc.costs = vec!["random".into()];
        tc.assignments = 1;
        tc.icet_search_objects = 1000;
        (tc.runs, tc.folds, tc.seed) = (1, 3, 5);
        crate::testcost::testcost(&tc).unwrap();
        let (_, benchmark): (Definition, Vec<JobResult>) = results(plain.path());
        let (def, curves): (CurvesDefinition, Vec<CurveResult>) = results(one.path());
        assert_eq!(def.benchmark.datasets, ["iris", "monks1"]);
        let bits = |s: &Score| {
            (
                s.mc.to_bits(),
                s.total.to_bits(),
                s.tests.to_bits(),
                s.error_rate.to_bits(),
                s.standard.to_bits(),
                s.auroc.map(f64::to_bits),
            )
        };
        let curve = |d: &str, learner, knob| {
            curves
                .iter()
                .find(|r| {
                    r.dataset == d
                        && r.curve
                            == Curve {
                                learner: Learner::Family(learner),
                                knob,
                            }
                })
                .unwrap()
        };
        let mut majorities = Vec::new();
        for d in ["iris", "monks1"] {
            let of = |m: Method| {
                benchmark
                    .iter()
                    .find(|r| r.dataset == d && r.learner == Learner::Family(m))
                    .unwrap()
            };
            // eg2 at mc 1000 unbudgeted: a budget of every test's price and one of 10 tests
            // (iris has 4, monks1 6) bind no object.
            let unbudgeted = bits(&of(Method::Eg2).by_mc[1]);
            let share = curve(d, Method::Eg2, Knob::Budget);
            let k = curve(d, Method::Eg2, Knob::MaxTests);
            assert_eq!(bits(&share.points[1]), unbudgeted, "{d}");
            assert_eq!(bits(&k.points[2]), unbudgeted, "{d}");
            // dtmc's mc curve is its benchmark row at each mc.
            let dtmc = curve(d, Method::Dtmc, Knob::Mc);
            assert_eq!(
                dtmc.points.iter().map(bits).collect::<Vec<_>>(),
                of(Method::Dtmc).by_mc.iter().map(bits).collect::<Vec<_>>()
            );
            // No test: the training folds' majority class, and nothing paid.
            let loaded = cslearn::testcost::Catalogue::read(&args(one.path(), 1).manifest)
                .unwrap()
                .load(d)
                .unwrap();
            let majority = majority_accuracy(&def.benchmark, d, &loaded.frame);
            assert!(close(1.0 - k.points[0].error_rate, majority), "{d}");
            majorities.push(majority);
            assert_eq!(k.points[0].tests, 0.0);
            // A budget of 5% of every test's price: no object pays more.
            assert!(
                share.points[0].tests <= 0.05 * share.all_tests + 1e-9,
                "{d}"
            );
        }
        // Written so; iris's three classes of 50 leave each training part nearly tied, and
        // its majority class is right on about a third of the objects.
        let row = |d: &str, knob: &str| {
            rows.iter()
                .find(|r| r[0] == d && format!("{} {}", r[3], r[4]) == knob)
                .unwrap()
        };
        assert_eq!(
            row("iris", "max-tests 0")[8],
            format!("{:.4}", majorities[0])
        );
        assert_eq!(row("iris", "max-tests 0")[14], "0.00000");
        assert!((majorities[0] - 1.0 / 3.0).abs() < 0.05, "{majorities:?}");

        // The report: an area per curve, the majority class's accuracy, a figure per data
        // set; and again from the results alone.
        let md = read(one.path(), "budget.md");
        let iris = format!("| iris | random | {:.1} |", 100.0 * majorities[0]);
        assert!(md.contains(&iris), "{md}");
        for d in ["iris", "monks1"] {
            let svg = read(one.path(), &svg_name(d));
            crate::render::check(&svg, d).unwrap();
            assert!(svg.contains("eg2 within a price budget: area"), "{d}");
        }
        let mut again = args(one.path(), 1);
        again.report = true;
        std::fs::remove_file(one.path().join("budget.csv")).unwrap();
        budget(&again).unwrap();
        assert_eq!(read(one.path(), "budget.csv"), csv);
    }

    /// Spambase is out of the benchmark's default data sets and in the sweep's; its
    /// random prices are every test at 1, in one draw however many are asked for.
    #[test]
    fn spambase_is_swept_but_not_benchmarked_and_every_test_costs_1() {
        let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/uci/datasets.toml");
        let catalogue = cslearn::testcost::Catalogue::read(&manifest).unwrap();
        let swept = datasets_of(&catalogue, &[]);
        assert!(swept.contains(&"spambase".to_string()));
        assert_eq!(swept.len(), catalogue.sources().len());
        let benchmark = crate::testcost::benchmark_datasets(&catalogue, &[]);
        assert!(!benchmark.contains(&"spambase".to_string()));
        assert_eq!(benchmark.len(), 18);
        assert_eq!(benchmark, swept[..18]);
        // Named, it is swept like any other.
        assert_eq!(datasets_of(&catalogue, &["spambase".into()]), ["spambase"]);
        let loaded = catalogue.load("spambase").unwrap();
        let datasets = vec!["spambase".to_string(), "iris".to_string()];
        let iris = catalogue.load("iris").unwrap();
        let priced = Priced::of(&catalogue, &datasets, &[loaded.clone(), iris]);
        assert_eq!(
            priced,
            [
                Priced {
                    turney: false,
                    unit: true
                },
                Priced {
                    turney: false,
                    unit: false
                }
            ]
        );
        let dir = tempfile::tempdir().unwrap();
        let def = prepare(&TestcostArgs {
            datasets: vec!["iris".into()],
            ..crate::testcost::tests::args(dir.path(), 1)
        })
        .unwrap()
        .def;
        assert_eq!(priced[0].assignments(&def, PriceSet::Random), 1);
        assert_eq!(
            priced[1].assignments(&def, PriceSet::Random),
            def.assignments
        );
        assert!(def.assignments > 1);
        for assignment in 0..3 {
            let prices = job_prices(
                &def,
                "spambase",
                &loaded.frame,
                None,
                true,
                PriceSet::Random,
                assignment,
            )
            .unwrap();
            assert_eq!(prices, cslearn::testcost::TestPrices::unit(57));
        }
        // Without unit prices, a random draw is not every test at 1.
        let drawn = job_prices(
            &def,
            "spambase",
            &loaded.frame,
            None,
            false,
            PriceSet::Random,
            0,
        )
        .unwrap();
        assert_ne!(drawn, cslearn::testcost::TestPrices::unit(57));
    }

    #[test]
    fn a_learner_without_a_curve_and_bad_knobs_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let mut no_curve = args(dir.path(), 1);
        no_curve.budget_learners = vec!["dtmc".into()];
        let err = budget(&no_curve).unwrap_err().to_string();
        assert!(err.contains("`eg2`") && err.contains("no curve"), "{err}");
        let mut stranger = args(dir.path(), 1);
        stranger.budget_learners = vec!["c45".into()];
        let err = budget(&stranger).unwrap_err().to_string();
        assert!(
            err.contains("--budget-learners") && err.contains("`c45`"),
            "{err}"
        );
        let mut negative = args(dir.path(), 1);
        negative.budgets = vec![0.5, -0.1];
        let err = budget(&negative).unwrap_err().to_string();
        assert!(err.contains("--budgets -0.1"), "{err}");
        let mut twice = args(dir.path(), 1);
        twice.max_tests = vec![1, 1];
        let err = budget(&twice).unwrap_err().to_string();
        assert!(
            err.contains("--max-tests") && err.contains("twice"),
            "{err}"
        );
    }

    /// `--budgets` and `--max-tests` alone leave their curves out.
    #[test]
    fn an_empty_knob_list_is_no_curve() {
        use clap::Parser;
        #[derive(Parser)]
        struct Cli {
            #[command(flatten)]
            args: BudgetArgs,
        }
        let cli = Cli::parse_from(["budget", "--max-tests", "--budgets", "0.5"]);
        assert!(cli.args.max_tests.is_empty());
        assert_eq!(cli.args.budgets, [0.5]);
        let cli = Cli::parse_from(["budget"]);
        assert_eq!(cli.args.max_tests, [1, 2, 3, 5, 10]);
        assert_eq!(cli.args.learners, ["c45", "eg2", "dtmc", "icet"]);
    }

    /// The tradeoff knob: its names, how it is written, its default grid (the worker's
    /// `TRADEOFFS`: 0, then 10^-4 to 10 in quarter decades), and the flags that give it.
    #[test]
    fn the_tradeoff_knob_is_cegbs_and_parses() {
        use clap::Parser;
        #[derive(Parser)]
        struct Cli {
            #[command(flatten)]
            args: BudgetArgs,
        }
        assert_eq!(Knob::Tradeoff.name(), "tradeoff");
        assert_eq!(
            serde_json::to_string(&Knob::Tradeoff).unwrap(),
            r#""tradeoff""#
        );
        let curve = Curve {
            learner: Learner::Cegb,
            knob: Knob::Tradeoff,
        };
        let text = serde_json::to_string(&curve).unwrap();
        assert_eq!(text, r#"{"learner":"cegb","knob":"tradeoff"}"#);
        assert_eq!(serde_json::from_str::<Curve>(&text).unwrap(), curve);
        assert_eq!(curve.label(), "cegb, tradeoff");
        let grid = cegb::tradeoff_grid();
        assert_eq!(grid.len(), 22);
        assert_eq!((grid[0], grid[1], grid[21]), (0.0, 1e-4, 10.0));
        assert!(grid[1..].windows(2).all(|w| {
            let ratio = w[1] / w[0];
            (ratio - 10f64.powf(0.25)).abs() < 1e-12
        }));
        let cli = Cli::parse_from(["budget", "--learners", "eg2,cegb", "--tradeoffs", "0,0.01"]);
        assert_eq!(cli.args.learners, ["eg2", "cegb"]);
        assert_eq!(cli.args.tradeoffs, [0.0, 0.01]);
        assert!(Cli::parse_from(["budget"]).args.tradeoffs.is_empty());
        // A definition whose sweep has CEGB takes the grid unless told otherwise; the
        // tradeoff curve is CEGB's only one.
        let dir = tempfile::tempdir().unwrap();
        let base = prepare(&TestcostArgs {
            datasets: vec!["iris".into()],
            learners: vec!["cegb".into()],
            ..crate::testcost::tests::args(dir.path(), 1)
        })
        .unwrap()
        .def;
        let def = CurvesDefinition {
            benchmark: base,
            curves: Vec::new(),
            budgets: vec![0.5],
            max_tests: vec![1],
            budget_mc: 1000.0,
            tradeoffs: vec![0.0, 0.01],
        };
        assert_eq!(knobs_of(Learner::Cegb, false, &def), [Knob::Tradeoff]);
        assert_eq!(def.values(Knob::Tradeoff), [0.0, 0.01]);
        let none = CurvesDefinition {
            tradeoffs: Vec::new(),
            ..def.clone()
        };
        assert!(knobs_of(Learner::Cegb, false, &none).is_empty());
        assert_eq!(
            knobs_of(Learner::Family(Method::Eg2), true, &def),
            [Knob::Budget, Knob::MaxTests]
        );
    }

    /// Results written before CEGB had a curve: a definition without tradeoffs and a
    /// result line of the family read, and write back byte for byte.
    #[test]
    fn results_written_before_the_tradeoff_knob_read_and_write_back_alike() {
        let line = r#"{"id":3,"dataset":"iris","costs":"random","assignment":0,"run":0,"curve":{"learner":"Eg2","knob":"max-tests"},"all_tests":258.3731560486528,"points":[{"mc":100000.0,"total":4696.2118489351415,"tests":29.545182268458696,"error_rate":0.04666666666666667,"standard":66925.03982271532,"auroc":0.9656666666666668}],"nodes":7.64,"learn_seconds":0.006158953000000001,"classify_seconds":0.00004676699999999999}"#;
        let read: CurveResult = serde_json::from_str(line).unwrap();
        assert_eq!(
            read.curve,
            Curve {
                learner: Learner::Family(Method::Eg2),
                knob: Knob::MaxTests
            }
        );
        assert_eq!(read.library, None);
        assert_eq!(serde_json::to_string(&read).unwrap(), line);
        let dir = tempfile::tempdir().unwrap();
        let base = prepare(&TestcostArgs {
            datasets: vec!["iris".into()],
            ..crate::testcost::tests::args(dir.path(), 1)
        })
        .unwrap()
        .def;
        let old = format!(
            r#"{{"benchmark":{},"curves":[{{"learner":"Dtmc","knob":"mc"}}],"budgets":[0.5],"max_tests":[1],"budget_mc":1000.0}}"#,
            serde_json::to_string(&base).unwrap()
        );
        let def: CurvesDefinition = serde_json::from_str(&old).unwrap();
        assert!(def.tradeoffs.is_empty());
        assert_eq!(serde_json::to_string(&def).unwrap(), old);
    }

    /// CEGB's flags are refused where they cannot hold, by flag, before any worker starts.
    #[test]
    fn cegbs_flags_are_refused_where_they_cannot_hold() {
        let dir = tempfile::tempdir().unwrap();
        let refused = |edit: &dyn Fn(&mut BudgetArgs), expected: &[&str]| {
            let mut a = args(dir.path(), 1);
            edit(&mut a);
            let err = format!("{:#}", budget(&a).unwrap_err());
            for e in expected {
                assert!(err.contains(e), "{e}: {err}");
            }
        };
        refused(
            &|a| a.tradeoffs = vec![0.1],
            &["--tradeoffs", "need `cegb` among --learners"],
        );
        refused(
            &|a| {
                a.learners = vec!["eg2".into(), "cegb".into()];
                a.budget_learners = vec!["cegb".into()];
            },
            &["--budget-learners cegb", "--tradeoffs"],
        );
        refused(
            &|a| {
                a.learners = vec!["cegb".into()];
                a.tradeoffs = vec![0.0, -1.0];
            },
            &["--tradeoffs -1"],
        );
        refused(
            &|a| {
                a.learners = vec!["cegb".into()];
                a.tradeoffs = vec![f64::NAN];
            },
            &["--tradeoffs NaN"],
        );
        refused(
            &|a| {
                a.learners = vec!["cegb".into()];
                a.tradeoffs = vec![0.1, 0.1];
            },
            &["--tradeoffs", "twice"],
        );
        refused(
            &|a| a.python = Some("/usr/bin/python3".into()),
            &["--python", "cegb"],
        );
        assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none());
    }

    /// CEGB's curve from canned worker answers, with no Python: one sweep request per fold
    /// with the fold's rows, the tradeoffs and the benchmark's learner seed; each answer
    /// matched to its held-out object, priced and scored at the curve's mc; the CSV row
    /// per tradeoff; answers that do not fit the request refused by place.
    #[test]
    fn cegbs_curve_is_scored_and_written_from_the_workers_answers() {
        use crate::testcost::cegb::{SweepResponse, Swept, sweep_folds};
        use cslearn::testcost::Column;
        let dir = tempfile::tempdir().unwrap();
        let prepared = prepare(&TestcostArgs {
            datasets: vec!["iris".into()],
            learners: vec!["eg2".into(), "cegb".into()],
            costs: vec!["random".into()],
            assignments: 1,
            ..crate::testcost::tests::args(dir.path(), 1)
        })
        .unwrap();
        let base = prepared.def;
        let frame = &prepared.loaded[0].frame;
        let job = Job {
            dataset: 0,
            costs: PriceSet::Random,
            assignment: 0,
            run: 0,
            learner: 1,
        };
        let prices = job_prices(&base, "iris", frame, None, false, PriceSet::Random, 0).unwrap();
        let (tradeoffs, mc) = ([0.0, 0.5], 1000.0);
        let settings = serde_json::json!({"trees": 50});
        // The canned worker: at tradeoff 0, petal length (feature 2) below 2.5 answers
        // setosa for that test alone, else versicolor after petal width (3) too; at 0.5,
        // setosa for everyone, no test.
        let canned = |request: &crate::testcost::cegb::FitRequest<'_>, asked: &[f64]| {
            let small: Vec<bool> = request
                .test
                .iter()
                .map(|row| row[2].is_some_and(|x| x < 2.5))
                .collect();
            let one_hot = |c: usize| (0..3).map(|k| f64::from(u8::from(k == c))).collect();
            let at_zero = Swept {
                tradeoff: asked[0],
                nodes: 9,
                predicted: small.iter().map(|&s| if s { 0 } else { 1 }).collect(),
                probabilities: small.iter().map(|&s| one_hot(usize::from(!s))).collect(),
                features: small
                    .iter()
                    .map(|&s| if s { vec![2] } else { vec![2, 3, 2] })
                    .collect(),
            };
            let at_half = Swept {
                tradeoff: asked[1],
                nodes: 3,
                predicted: vec![0; small.len()],
                probabilities: vec![vec![1.0 / 3.0; 3]; small.len()],
                features: vec![Vec::new(); small.len()],
            };
            SweepResponse {
                by_tradeoff: vec![at_zero, at_half],
                learn_seconds: 0.25,
                classify_seconds: 0.5,
            }
        };
        let mut seeds = Vec::new();
        let mut held_out = 0;
        let swept = sweep_folds(
            &base,
            job,
            "iris",
            (frame, &prices),
            (&tradeoffs, mc),
            &settings,
            |request| {
                assert_eq!(request.op, "sweep");
                assert_eq!(request.tradeoffs, Some(&tradeoffs[..]));
                assert!(request.mc.is_none());
                assert_eq!(request.train.len() + request.test.len(), 150);
                assert_eq!(request.classes.len(), request.train.len());
                assert_eq!(request.settings, &settings);
                seeds.push(request.seed);
                held_out += request.test.len();
                Ok(canned(request, &tradeoffs))
            },
        )
        .unwrap();
        // One request per fold, each with the fold's learner seed, as the benchmark's CEGB.
        let expected: Vec<u64> = (0..3)
            .map(|f| crate::testcost::learner_seed(&base, "iris", job, f))
            .collect();
        assert_eq!(seeds, expected);
        assert_eq!(held_out, 150);
        // By hand: every setosa has petal length below 2.5, no other iris does.
        let Column::Numeric(petal) = frame.column(2) else {
            panic!("iris's petal length is numeric")
        };
        let setosa = petal.iter().filter(|&&x| x < 2.5).count();
        assert_eq!(setosa, 50);
        let (p2, p3) = (prices.test(2).full, prices.test(3).full);
        let tests = (50.0 * p2 + 100.0 * (p2 + p3)) / 150.0;
        let zero = &swept.points[0];
        assert_eq!(zero.mc, mc);
        assert!((zero.error_rate - 50.0 / 150.0).abs() < 1e-12);
        assert!((zero.tests - tests).abs() < 1e-9);
        assert!((zero.total - (tests + mc * 50.0 / 150.0)).abs() < 1e-9);
        let half = &swept.points[1];
        assert_eq!(half.tests, 0.0);
        assert!((half.error_rate - 100.0 / 150.0).abs() < 1e-12);
        assert_eq!(half.auroc, Some(0.5));
        assert_eq!((swept.nodes, swept.learn_seconds), (6.0, 0.75));

        // The CSV: a row per tradeoff, at the curve's mc.
        let all_tests = prices.total();
        let def = CurvesDefinition {
            benchmark: base.clone(),
            curves: vec![Curve {
                learner: Learner::Cegb,
                knob: Knob::Tradeoff,
            }],
            budgets: Vec::new(),
            max_tests: Vec::new(),
            budget_mc: mc,
            tradeoffs: tradeoffs.to_vec(),
        };
        let result = CurveResult {
            id: 0,
            dataset: "iris".into(),
            costs: PriceSet::Random,
            assignment: 0,
            run: 0,
            curve: def.curves[0],
            all_tests,
            points: swept.points,
            nodes: swept.nodes,
            learn_seconds: swept.learn_seconds,
            classify_seconds: swept.classify_seconds,
            library: Some("LightGBM 4.7.0, 50 rounds".into()),
        };
        let points = aggregate(&def, std::slice::from_ref(&result));
        let majority = BTreeMap::from([("iris".to_string(), 1.0 / 3.0)]);
        let summaries = summarise(&points, &majority);
        let report = Report {
            def: &def,
            points: &points,
            summaries: &summaries,
            majority: &majority,
            shapes: &BTreeMap::new(),
            command: "cargo xtask budget".into(),
            library: result.library.clone(),
        };
        let csv = report.csv();
        let rows: Vec<&str> = csv.lines().skip(1).collect();
        let auroc = |row: &str| row.split(',').nth(10).unwrap().parse::<f64>().unwrap();
        assert_eq!(rows.len(), 2, "{csv}");
        let cells = |row: &str| {
            let c: Vec<&str> = row.split(',').collect();
            [&c[..8], &c[8..10], &c[12..18]].concat().join(",")
        };
        assert_eq!(
            cells(rows[0]),
            format!(
                "iris,random,cegb,tradeoff,0,1000,1,3,0.6667,,{tests:.4},,{:.5},,{:.3},",
                tests / all_tests,
                tests + mc / 3.0
            )
        );
        assert!(auroc(rows[0]) > 0.5 && auroc(rows[0]) <= 1.0, "{csv}");
        assert_eq!(
            cells(rows[1]),
            "iris,random,cegb,tradeoff,0.5,1000,1,3,0.3333,,0.0000,,0.00000,,666.667,"
        );
        assert_eq!(auroc(rows[1]), 0.5);
        // Its area: a third with no test, two thirds from the first point's cost on.
        let x = tests / all_tests;
        assert!((summaries[0].area - (x / 3.0 + (1.0 - x) * 2.0 / 3.0)).abs() < 1e-9);
        let md = report.markdown();
        assert!(
            md.contains("CEGB over its `cegb_tradeoff` ({0, 0.5})")
                && md.contains("counted at mc 1000 (LightGBM 4.7.0, 50 rounds)."),
            "{md}"
        );
        assert!(md.contains("| cegb, tradeoff |"), "{md}");

        // Answers that do not fit the request are refused, naming the fold.
        let refuse = |edit: &dyn Fn(&mut SweepResponse)| {
            let err = sweep_folds(
                &base,
                job,
                "iris",
                (frame, &prices),
                (&tradeoffs, mc),
                &settings,
                |request| {
                    let mut answer = canned(request, &tradeoffs);
                    edit(&mut answer);
                    Ok(answer)
                },
            )
            .unwrap_err();
            format!("{err:#}")
        };
        let err = refuse(&|a| a.by_tradeoff[1].tradeoff = 0.25);
        assert!(
            err.contains("CEGB's sweep on `iris`, random prices 0, run 0, fold 0")
                && err.contains("tradeoff 0.25 where tradeoff 0.5 was asked"),
            "{err}"
        );
        let err = refuse(&|a| {
            a.by_tradeoff.pop();
        });
        assert!(err.contains("1 answers for 2 tradeoffs"), "{err}");
        let err = refuse(&|a| a.by_tradeoff[0].features[0] = vec![4]);
        assert!(err.contains("feature 4"), "{err}");
        let err = refuse(&|a| {
            a.by_tradeoff[1].predicted.pop();
        });
        assert!(err.contains("held-out objects"), "{err}");
    }
}
