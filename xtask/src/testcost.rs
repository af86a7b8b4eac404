//! `cargo xtask testcost`: the test-cost tree family on the UCI benchmark of Esmeir's
//! thesis (chapter 4), beside the published figures.
//!
//! One job is one data set, one price assignment (Turney's, or random draw `a`), one run
//! of `K`-fold cross-validation and one learner; it reports, for every misclassification
//! cost `mc`, the mean total cost, test cost and error rate over the data set's objects
//! (each object is tested once per run), and the area under the ROC curve of the trees'
//! class probabilities ([`auroc`]). Jobs are sharded and resumable like `sweep`'s.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::Args;
use cslearn::testcost::{
    ActParams, Budget, Catalogue, CvtParams, FamilyParams, Frame, IcetParams, Loaded, Method,
    MisclassCosts, Pruning, SelectionPrices, TestPrices, VoiParams, fit_each, folds, gain_prices,
    random_prices, standard_cost,
};
use serde::{Deserialize, Serialize};

use crate::shard::JobLine;

pub mod anytime;
mod cegb;
pub mod cube;
pub mod curves;
mod published;
mod report;

/// Arguments of `cargo xtask testcost`.
#[derive(Args, Clone, Debug)]
pub struct TestcostArgs {
    /// Data sets, comma-separated, as `data/uci/datasets.toml` names them (default: the
    /// benchmark's, every data set the manifest does not mark `benchmark = false`).
    #[arg(long, value_delimiter = ',')]
    datasets: Vec<String>,
    /// Learners, comma-separated (`c45,id3-batch,idx,cs-id3-batch,eg2,dtmc,icet,act,cvt`,
    /// `voi`, and `cegb`, LightGBM's cost-efficient gradient boosting run through Python;
    /// default: the nine of the family, all but `voi` and `cegb`, which are run by naming
    /// them).
    #[arg(long, value_delimiter = ',')]
    learners: Vec<String>,
    /// Uniform misclassification costs, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "100,500,1000,5000")]
    mc: Vec<f64>,
    /// Price sets, comma-separated: `random` (every data set, `--assignments` draws) and
    /// `turney` (the data sets with Turney's cost files).
    #[arg(long, value_delimiter = ',', default_value = "random,turney")]
    costs: Vec<String>,
    /// Random price assignments per data set.
    #[arg(long, default_value_t = 4)]
    assignments: u64,
    /// How random prices are drawn: `uniform` (each test uniform in the range) or `gain`
    /// (each test uniform between LOW and a ceiling in proportion to its information gain
    /// on the whole data set).
    #[arg(long, default_value = "uniform")]
    price_draw: String,
    /// The price selection functions see: `listed` (each test's listed price whatever
    /// the path, as the published implementations score tests), `path` (after the
    /// node's path, the library's default) or `listed-once` (listed, but nothing for a
    /// test the path already did). Objects always pay after their path.
    #[arg(long, default_value = "listed")]
    selection_prices: String,
    /// How ICET prunes: `costs` (a test must pay for itself at the real prices, which
    /// reproduces the published ICET's ratios) or `errors` (C4.5's, Turney's own and the
    /// library's default).
    #[arg(long, default_value = "costs")]
    icet_pruning: String,
    /// The most training objects ICET's search uses (half to grow, half to score); the
    /// final tree always grows on every training object. 1000 here (the library's
    /// default is 400): on the large data sets the search then sees trees of the size
    /// the final one has, which reproduces the published ICET at mc 1000.
    #[arg(long, default_value_t = 1000)]
    icet_search_objects: usize,
    /// The folds of CVT's cross-validation on each training part (the library's 5).
    #[arg(long, default_value_t = 5)]
    cvt_folds: usize,
    /// ACT's trees sampled under each branch of each candidate test (`r`, the library's
    /// 5; 0 values each branch as a leaf): ACT is anytime in it, more samples giving a
    /// better estimate for more time (`docs/testcost.md` has the curve). CVT's lookahead
    /// grower has its own, `--cvt-samples`.
    #[arg(long, default_value_t = 5)]
    act_samples: usize,
    /// The trees CVT's lookahead grower samples under each branch (the library's 5, as
    /// ACT's; 0 leaves the lookahead out of CVT's growers): fewer, a faster CVT.
    #[arg(long, default_value_t = 5)]
    cvt_samples: usize,
    /// VOI's lookahead: how many tests ahead a test is valued, 1 to 3 (the library's: 3 on
    /// at most 21 features, 2 beyond).
    #[arg(long, value_name = "D")]
    voi_lookahead: Option<usize>,
    /// VOI's leaf estimate, pessimistic at this confidence (the library's 0.25).
    #[arg(long, value_name = "C")]
    voi_confidence: Option<f64>,
    /// VOI's leaf estimate, an m-estimate of the classes with the class shares weighing
    /// this many objects (instead of the pessimistic estimate).
    #[arg(long, value_name = "M")]
    voi_m: Option<f64>,
    /// A hard budget per object: at most K distinct tests. The greedy learners grow within
    /// it, every learner's trees classify within it (none by default).
    #[arg(long, value_name = "K")]
    max_tests: Option<usize>,
    /// A hard budget per object: at most B paid for its tests (after the path's discounts),
    /// held as `--max-tests` is (none by default).
    #[arg(long, value_name = "B", allow_negative_numbers = true)]
    max_test_cost: Option<f64>,
    /// The range random prices are drawn from: `LOW,HIGH`.
    #[arg(long, value_delimiter = ',', default_value = "1,100")]
    price_range: Vec<f64>,
    /// Runs of cross-validation per data set and price assignment.
    #[arg(long, default_value_t = 10)]
    runs: u64,
    /// Folds of each run.
    #[arg(long, default_value_t = 10)]
    folds: usize,
    /// Base seed of folds, prices and ICET's search.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The manifest of the data sets.
    #[arg(long, default_value = "data/uci/datasets.toml")]
    manifest: PathBuf,
    /// Output folder.
    #[arg(long, default_value = "results/testcost")]
    out: PathBuf,
    /// Worker threads (default: every core); results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// This machine's shard, `K/N`.
    #[arg(long, default_value = "1/1")]
    shard: String,
    /// Results folders of other `cargo xtask testcost` runs whose learners join the report:
    /// the same data sets, price sets, draws, folds, seed and settings, but their own
    /// learners, runs and mc (a subset of `--mc`). Only learners this run does not have are
    /// added, each row saying how many runs it averages and each ratio to CS-ID3 taken on
    /// its own runs. The committed table takes ACT, CVT and VOI this way, each from ten
    /// runs of the same protocol (`docs/testcost.md`).
    #[arg(long, value_delimiter = ',')]
    with: Vec<PathBuf>,
    /// The Python interpreter of CEGB's worker (`--learners ...,cegb`), which must have
    /// numpy and lightgbm. Default: the project's virtual environment under the target
    /// folder (`py-venv`), made or brought up to date with the pinned packages of
    /// `crates/csrl-py/requirements-test.txt`.
    #[arg(long, value_name = "PATH")]
    python: Option<PathBuf>,
    /// Only write the report from the results already in `--out`.
    #[arg(long)]
    report: bool,
    /// Also write the report, the table and the figure into `docs/`.
    #[arg(long)]
    bless: bool,
}

/// A learner of the benchmark: one of the test-cost family (`cslearn::testcost`), or CEGB,
/// LightGBM's cost-efficient gradient boosting, run beside them as their peer through
/// the Python worker of `crates/csrl-py/python/csrl/cegb.py` ([`cegb`]).
///
/// It is written to results and manifests as the family's learners always were (their
/// variant names: `"Eg2"`, `"CsId3Batch"`, ...), and CEGB as `"cegb"`, so that results
/// written before CEGB existed read and write back byte for byte.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum Learner {
    /// A learner of the test-cost family.
    Family(Method),
    /// LightGBM's CEGB.
    Cegb,
}

impl Learner {
    /// The name `--learners` takes and the tables show.
    pub fn name(self) -> &'static str {
        match self {
            Learner::Family(m) => m.name(),
            Learner::Cegb => "cegb",
        }
    }

    /// The learner called `name` on the command line.
    pub fn parse(name: &str) -> Result<Learner> {
        if name == "cegb" {
            return Ok(Learner::Cegb);
        }
        Method::parse(name)
            .map(Learner::Family)
            .map_err(|e| anyhow::anyhow!("--learners: {e}, or `cegb` (LightGBM's CEGB)"))
    }

    /// The family's learner, if it is one.
    pub fn method(self) -> Option<Method> {
        match self {
            Learner::Family(m) => Some(m),
            Learner::Cegb => None,
        }
    }

    /// Whether its model depends on the misclassification cost (CEGB's does: its
    /// tradeoff is chosen at each cost).
    pub fn depends_on_mc(self) -> bool {
        match self {
            Learner::Family(m) => m.depends_on_mc(),
            Learner::Cegb => true,
        }
    }
}

impl Serialize for Learner {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Learner::Family(m) => m.serialize(serializer),
            Learner::Cegb => serializer.serialize_str("cegb"),
        }
    }
}

impl<'de> Deserialize<'de> for Learner {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Learner, D::Error> {
        use serde::de::{Error as _, IntoDeserializer as _};
        let name = String::deserialize(deserializer)?;
        if name == "cegb" {
            return Ok(Learner::Cegb);
        }
        let family: Result<Method, serde::de::value::Error> =
            Method::deserialize(name.as_str().into_deserializer());
        family
            .map(Learner::Family)
            .map_err(|e| D::Error::custom(format!("{e}, nor `cegb`")))
    }
}

/// What a benchmark is: shards must agree on it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct Definition {
    pub datasets: Vec<String>,
    pub learners: Vec<Learner>,
    pub mc: Vec<f64>,
    pub costs: Vec<PriceSet>,
    pub assignments: u64,
    pub price_range: (f64, f64),
    #[serde(default)]
    pub price_draw: PriceDraw,
    /// Results written before this setting existed were priced after the path.
    #[serde(default)]
    pub selection_prices: SelectionPrices,
    /// Results written before this setting existed were pruned by errors.
    #[serde(default)]
    pub icet_pruning: Pruning,
    /// Results written before this setting existed searched on at most 400 objects.
    #[serde(default = "library_search_objects")]
    pub icet_search_objects: usize,
    /// Results written before this setting existed used the library's 5.
    #[serde(default = "library_cvt_folds")]
    pub cvt_folds: usize,
    /// Results written before this setting existed sampled the library's 5.
    #[serde(default = "library_act_samples")]
    pub act_samples: usize,
    /// CVT's lookahead samples; the library's 5 is left out of the file (and results
    /// written before this setting existed read as it).
    #[serde(
        default = "library_cvt_samples",
        skip_serializing_if = "is_library_cvt_samples"
    )]
    pub cvt_samples: usize,
    /// VOI's settings; the library's are left out of the file (and results written before
    /// VOI existed read as them).
    #[serde(default, skip_serializing_if = "VoiParams::is_default")]
    pub voi: VoiParams,
    /// Whether VOI's default lookahead follows the data's width (`VoiParams::lookahead_for`):
    /// set by every benchmark that runs VOI at its default since it does. Results written
    /// before, when the default looked two tests ahead everywhere, read as such
    /// ([`voi_params`](Definition::voi_params)) and neither resume nor join with these.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub voi_by_width: bool,
    /// The budget per object in tests; results written before it existed had none (and
    /// a definition without it is written as before).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_tests: Option<usize>,
    /// The budget per object in price, as `max_tests`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_test_cost: Option<f64>,
    pub runs: u64,
    pub folds: usize,
    pub seed: u64,
}

impl Definition {
    /// VOI's settings as its jobs run them: two tests ahead where the lookahead is the
    /// default and the definition was written before the default followed the width.
    pub(crate) fn voi_params(&self) -> VoiParams {
        match self.voi.lookahead {
            None if !self.voi_by_width => VoiParams {
                lookahead: Some(2),
                ..self.voi
            },
            _ => self.voi,
        }
    }

    /// Takes `other`'s VOI settings: a table that adds `other`'s VOI rows shows them.
    pub(crate) fn take_voi(&mut self, other: &Definition) {
        self.voi = other.voi;
        self.voi_by_width = other.voi_by_width;
    }
}

/// ICET's search size in the library's defaults.
fn library_search_objects() -> usize {
    IcetParams::default().search_objects
}

/// CVT's folds in the library's defaults.
fn library_cvt_folds() -> usize {
    CvtParams::default().folds
}

/// ACT's samples in the library's defaults.
fn library_act_samples() -> usize {
    ActParams::default().samples
}

/// CVT's lookahead samples in the library's defaults.
fn library_cvt_samples() -> usize {
    CvtParams::default().samples
}

fn is_library_cvt_samples(samples: &usize) -> bool {
    *samples == library_cvt_samples()
}

/// How random prices are drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum PriceDraw {
    /// Uniform in the range.
    #[default]
    Uniform,
    /// Uniform below a ceiling in proportion to the test's information gain.
    Gain,
}

/// Where a job's prices come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum PriceSet {
    Random,
    Turney,
}

impl PriceSet {
    pub fn name(self) -> &'static str {
        match self {
            PriceSet::Random => "random",
            PriceSet::Turney => "turney",
        }
    }
}

/// One job's result.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct JobResult {
    pub id: u64,
    pub dataset: String,
    pub costs: PriceSet,
    pub assignment: u64,
    pub run: u64,
    pub learner: Learner,
    /// One per `mc` of the definition, in its order.
    pub by_mc: Vec<Score>,
    /// Mean nodes per tree.
    pub nodes: f64,
    /// CPU seconds to learn every fold's trees (not reproducible: a measurement).
    pub learn_seconds: f64,
    /// CPU seconds to classify every object.
    pub classify_seconds: f64,
    /// For a learner run through another library (CEGB), that library's version and the
    /// settings it ran with, one line; absent for the family's learners (and so in
    /// results written before CEGB existed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub library: Option<String>,
    /// CEGB's tradeoff chosen by its cross-validation, per mc (in the definition's
    /// order), one per fold; absent for the family's learners.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tradeoffs: Option<Vec<Vec<f64>>>,
}

/// Scores of one job at one misclassification cost.
#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
pub(crate) struct Score {
    pub mc: f64,
    /// Mean total cost per object.
    pub total: f64,
    /// Mean test cost per object.
    pub tests: f64,
    /// Share of objects misclassified.
    pub error_rate: f64,
    /// Turney's standard cost under the job's prices and this mc.
    pub standard: f64,
    /// The area under the ROC curve of the trees' class probabilities
    /// ([`Classification::probabilities`](cslearn::testcost::Classification::probabilities))
    /// on the held-out objects, pooled over the run's folds ([`auroc`]); `None` in
    /// results written before it was measured, and where it is undefined.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub auroc: Option<f64>,
}

/// The area under the ROC curve of class probabilities `scores` (one row per object,
/// one column per class) against the objects' `actual` classes: for two classes, that
/// of the second class's probability (the first's is its mirror); for more, the mean
/// over classes of each class's one-vs-rest area (its probability ranking its objects
/// against all the others), over the classes that have objects both in and out. Each
/// area is the Mann-Whitney statistic, ties counted half. `None` when no class has
/// objects both in and out (a single class).
pub(crate) fn auroc(scores: &[Vec<f64>], actual: &[usize]) -> Option<f64> {
    let k = scores.first().map_or(0, Vec::len);
    let classes: Vec<usize> = if k == 2 { vec![1] } else { (0..k).collect() };
    let mut areas = Vec::new();
    for c in classes {
        let mut ranked: Vec<(f64, bool)> = scores
            .iter()
            .zip(actual)
            .map(|(p, &a)| (p[c], a == c))
            .collect();
        let positives = ranked.iter().filter(|x| x.1).count();
        let negatives = ranked.len() - positives;
        if positives == 0 || negatives == 0 {
            continue;
        }
        ranked.sort_by(|a, b| a.0.total_cmp(&b.0));
        // Ranks from 1, a run of equal scores sharing its mean rank.
        let mut rank_sum = 0.0;
        let mut i = 0;
        while i < ranked.len() {
            let mut j = i;
            while j < ranked.len() && ranked[j].0 == ranked[i].0 {
                j += 1;
            }
            let mean_rank = (i + 1 + j) as f64 / 2.0;
            rank_sum += mean_rank * ranked[i..j].iter().filter(|x| x.1).count() as f64;
            i = j;
        }
        let (p, n) = (positives as f64, negatives as f64);
        areas.push((rank_sum - p * (p + 1.0) / 2.0) / (p * n));
    }
    (!areas.is_empty()).then(|| areas.iter().sum::<f64>() / areas.len() as f64)
}

impl JobLine for JobResult {
    fn id(&self) -> u64 {
        self.id
    }
}

/// One job, from its number.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Job {
    pub dataset: usize,
    pub costs: PriceSet,
    pub assignment: u64,
    pub run: u64,
    pub learner: usize,
}

/// The job list in its fixed order: data set, price set, assignment, run, learner.
struct Jobs {
    jobs: Vec<Job>,
}

impl Jobs {
    /// `priced`: per data set of the definition, how it is priced.
    fn new(def: &Definition, priced: &[Priced]) -> Jobs {
        let mut jobs = Vec::new();
        for (d, priced) in priced.iter().enumerate() {
            for &costs in &def.costs {
                let assignments = priced.assignments(def, costs);
                for assignment in 0..assignments {
                    for run in 0..def.runs {
                        for learner in 0..def.learners.len() {
                            jobs.push(Job {
                                dataset: d,
                                costs,
                                assignment,
                                run,
                                learner,
                            });
                        }
                    }
                }
            }
        }
        Jobs { jobs }
    }
}

/// How a data set is priced, besides the definition's price sets: whether it has
/// Turney's prices, and whether every test costs 1 where random prices would be drawn
/// (the manifest's `unit_prices`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Priced {
    /// Whether the data set has Turney's prices.
    pub turney: bool,
    /// Whether its random prices are every test at 1 (the manifest's `unit_prices`).
    pub unit: bool,
}

impl Priced {
    /// How the manifest prices each of `datasets` (each one of its sources).
    pub(crate) fn of(catalogue: &Catalogue, datasets: &[String], loaded: &[Loaded]) -> Vec<Priced> {
        datasets
            .iter()
            .zip(loaded)
            .map(|(d, l)| Priced {
                turney: l.turney.is_some(),
                unit: catalogue
                    .sources()
                    .iter()
                    .any(|s| &s.name == d && s.unit_prices),
            })
            .collect()
    }

    /// The price assignments a data set has under a price set: the definition's random
    /// draws (one when every test costs 1: every draw would be the same), and Turney's
    /// one where the data set has it.
    pub(crate) fn assignments(self, def: &Definition, costs: PriceSet) -> u64 {
        match costs {
            PriceSet::Random if self.unit => 1,
            PriceSet::Random => def.assignments,
            PriceSet::Turney if self.turney => 1,
            PriceSet::Turney => 0,
        }
    }
}

/// A seed from the base seed, a data set's name and some numbers (SplitMix64 over an
/// FNV-1a hash of the name): adding a data set or a learner changes no other job's draws.
pub(crate) fn mix(seed: u64, name: &str, parts: &[u64]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in name.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    let mut x = seed ^ h.rotate_left(17);
    for &p in parts {
        x = splitmix(x ^ p.wrapping_mul(0x9e37_79b9_7f4a_7c15));
    }
    splitmix(x)
}

fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The prices of one job: for random prices, the draw `assignment`, or every test at 1
/// where the data set is `unit` priced.
pub(crate) fn job_prices(
    def: &Definition,
    name: &str,
    frame: &Frame,
    turney: Option<&TestPrices>,
    unit: bool,
    costs: PriceSet,
    assignment: u64,
) -> Result<TestPrices> {
    match costs {
        PriceSet::Random if unit => Ok(TestPrices::unit(frame.feature_count())),
        PriceSet::Random => {
            let seed = mix(def.seed, name, &[1, assignment]);
            let (low, high) = def.price_range;
            Ok(match def.price_draw {
                PriceDraw::Uniform => random_prices(frame.feature_count(), low, high, seed),
                PriceDraw::Gain => gain_prices(frame, low, high, seed),
            })
        }
        PriceSet::Turney => turney
            .cloned()
            .with_context(|| format!("data set `{name}` has no Turney prices")),
    }
}

/// Runs one job: `runs`-th cross-validation of one learner under one price assignment.
/// CEGB's jobs run through `peer`'s workers (which must be there when the benchmark has
/// CEGB).
fn run_job(
    def: &Definition,
    id: u64,
    job: Job,
    name: &str,
    (loaded, priced): (&Loaded, Priced),
    peer: Option<&cegb::Peer>,
) -> Result<JobResult> {
    let frame = &loaded.frame;
    let turney = loaded.turney.as_ref();
    let prices = job_prices(
        def,
        name,
        frame,
        turney,
        priced.unit,
        job.costs,
        job.assignment,
    )?;
    let method = match def.learners[job.learner] {
        Learner::Family(method) => method,
        Learner::Cegb => {
            let peer = peer.context("CEGB's job has no worker to run it")?;
            return cegb::run_job(def, id, job, name, frame, &prices, peer);
        }
    };
    let budget = Budget::new(def.max_test_cost, def.max_tests)?;
    let mut measured = cross_validate(def, job, name, frame, &prices, &def.mc, &[budget])?;
    Ok(JobResult {
        id,
        dataset: name.to_string(),
        costs: job.costs,
        assignment: job.assignment,
        run: job.run,
        learner: Learner::Family(method),
        by_mc: measured.by_budget.remove(0),
        nodes: measured.nodes,
        learn_seconds: measured.learn_seconds,
        classify_seconds: measured.classify_seconds,
        library: None,
        tradeoffs: None,
    })
}

/// The job's run of cross-validation as (fold, training objects, held-out objects), the
/// folds dealt from the definition's seed, the data set's name and the run, every empty
/// fold left out: the parts every learner of the benchmark, tree or peer, is fitted on.
pub(crate) fn job_parts(
    def: &Definition,
    name: &str,
    job: Job,
    frame: &Frame,
) -> Vec<(usize, Vec<usize>, Vec<usize>)> {
    folds(frame, def.folds, mix(def.seed, name, &[2, job.run]))
        .into_iter()
        .enumerate()
        .filter(|(_, test)| !test.is_empty())
        .map(|(f, test)| {
            let train = (0..frame.len())
                .filter(|r| test.binary_search(r).is_err())
                .collect();
            (f, train, test)
        })
        .collect()
}

/// The learner's seed for fold `f` of a job (ICET's search, ACT's and CVT's draws,
/// CEGB's inner folds and LightGBM's seed).
fn learner_seed(def: &Definition, name: &str, job: Job, f: usize) -> u64 {
    mix(
        def.seed,
        name,
        &[3, job.costs as u64, job.assignment, job.run, f as u64],
    )
}

/// The scores at each mc from the sums over a job's held-out objects: per mc, the total
/// cost, the test cost and the errors, and each object's class probabilities (in the
/// order of `actual_classes`).
fn scores(
    mc: &[f64],
    frame: &Frame,
    prices: &TestPrices,
    mcs: &[MisclassCosts],
    sums: &[(f64, f64, usize)],
    probabilities: &[Vec<Vec<f64>>],
    actual_classes: &[usize],
) -> Vec<Score> {
    let n = frame.len() as f64;
    mcs.iter()
        .zip(sums)
        .zip(mc)
        .zip(probabilities)
        .map(|(((costs, &(total, tests, errors)), &m), scores)| Score {
            mc: m,
            total: total / n,
            tests: tests / n,
            error_rate: errors as f64 / n,
            standard: standard_cost(frame, prices, costs),
            auroc: auroc(scores, actual_classes),
        })
        .collect()
}

/// What one cross-validation of a learner measured.
pub(crate) struct Measured {
    /// Per budget, one score per misclassification cost, in the orders given.
    pub by_budget: Vec<Vec<Score>>,
    /// Mean nodes per tree grown.
    pub nodes: f64,
    /// CPU seconds to learn every fold's trees.
    pub learn_seconds: f64,
    /// CPU seconds to classify every object.
    pub classify_seconds: f64,
}

/// The job's run of `K`-fold cross-validation of its learner under `prices`, scored at
/// each misclassification cost of `mc` and each budget of `budgets`: the folds and the
/// learners' seeds come from the definition's seed, the data set's name, the price set,
/// the assignment, the run and the fold, as in every job of the benchmark. A learner that
/// grows within a budget ([`Method::grows_within_budget`]) grows its trees once per
/// budget; the others grow them once, and each budget only cuts their classification.
/// With one budget this is the benchmark's job, to the bit. The job's learner is one of
/// the family's.
pub(crate) fn cross_validate(
    def: &Definition,
    job: Job,
    name: &str,
    frame: &Frame,
    prices: &TestPrices,
    mc: &[f64],
    budgets: &[Budget],
) -> Result<Measured> {
    let Learner::Family(method) = def.learners[job.learner] else {
        bail!(
            "{} is not a learner of the family",
            def.learners[job.learner].name()
        );
    };
    let mut params = FamilyParams {
        selection_prices: def.selection_prices,
        icet: IcetParams {
            pruning: def.icet_pruning,
            search_objects: def.icet_search_objects,
            ..IcetParams::default()
        },
        cvt: CvtParams {
            folds: def.cvt_folds,
            samples: def.cvt_samples,
            ..CvtParams::default()
        },
        act: ActParams {
            samples: def.act_samples,
            ..ActParams::default()
        },
        voi: def.voi_params(),
        ..FamilyParams::default()
    };
    let k = frame.class_count();
    let mcs: Vec<MisclassCosts> = mc
        .iter()
        .map(|&m| MisclassCosts::uniform(k, m))
        .collect::<Result<_, _>>()?;
    let mut sums = vec![vec![(0.0, 0.0, 0usize); mcs.len()]; budgets.len()];
    // Each held-out object's class probabilities, per budget and mc, with its class.
    let mut probabilities: Vec<Vec<Vec<Vec<f64>>>> =
        vec![vec![Vec::new(); mcs.len()]; budgets.len()];
    let mut actual_classes = Vec::new();
    let (mut nodes, mut trees) = (0usize, 0usize);
    let (mut learn, mut classify) = (0.0, 0.0);
    for (f, train, test) in job_parts(def, name, job, frame) {
        let icet_seed = learner_seed(def, name, job, f);
        let mut fitted = Vec::new();
        for (b, budget) in budgets.iter().enumerate() {
            // Learners whose tree does not depend on mc grow once and are relabelled; ACT
            // and CVT grow their trees at every mc through the same split tries (the same
            // trees). A budget changes the trees of the learners that grow within it only.
            let grown = b == 0 || method.grows_within_budget();
            if grown {
                params.budget = *budget;
                let start = Instant::now();
                fitted = fit_each(method, frame, &train, prices, &mcs, &params, icet_seed);
                learn += start.elapsed().as_secs_f64();
            }
            for (m, (mc, fitted)) in mcs.iter().zip(&fitted).enumerate() {
                let tree = &fitted.tree;
                if grown && (method.depends_on_mc() || m == 0) {
                    nodes += tree.len();
                    trees += 1;
                }
                let start = Instant::now();
                for &r in &test {
                    let c = tree.classify_within(frame, r, prices, budget);
                    let actual = frame.class(r) as usize;
                    let sum = &mut sums[b][m];
                    sum.0 += c.test_cost + mc.cost(c.class as usize, actual);
                    sum.1 += c.test_cost;
                    sum.2 += usize::from(c.class as usize != actual);
                    probabilities[b][m].push(c.probabilities);
                    if b == 0 && m == 0 {
                        actual_classes.push(actual);
                    }
                }
                classify += start.elapsed().as_secs_f64();
            }
        }
    }
    let by_budget = sums
        .iter()
        .zip(&probabilities)
        .map(|(sums, probabilities)| {
            scores(
                mc,
                frame,
                prices,
                &mcs,
                sums,
                probabilities,
                &actual_classes,
            )
        })
        .collect();
    Ok(Measured {
        by_budget,
        nodes: nodes as f64 / trees.max(1) as f64,
        learn_seconds: learn,
        classify_seconds: classify,
    })
}

/// A benchmark made ready from its arguments: its manifest, data sets (read, and how
/// each is priced) and definition.
pub(crate) struct Prepared {
    /// The manifest.
    pub catalogue: Catalogue,
    /// The data sets, in the definition's order.
    pub datasets: Vec<String>,
    /// The benchmark.
    pub def: Definition,
    /// Each data set, read.
    pub loaded: Vec<Loaded>,
    /// How each data set is priced.
    pub priced: Vec<Priced>,
}

/// `cargo xtask testcost`.
pub fn testcost(args: &TestcostArgs) -> Result<()> {
    let Prepared {
        catalogue,
        datasets,
        def,
        loaded,
        priced,
    } = prepare(args)?;
    if !args.report {
        let list = Jobs::new(&def, &priced);
        // CEGB's workers: one Python per worker thread that runs its jobs, started once.
        let peer = if def.learners.contains(&Learner::Cegb) {
            Some(cegb::Peer::start(args.python.as_deref())?)
        } else {
            None
        };
        crate::shard::run_shard(
            &args.out,
            &args.shard,
            def.clone(),
            list.jobs.len() as u64,
            args.threads,
            |id| {
                let job = list.jobs[id as usize];
                let frame = &loaded[job.dataset].frame;
                work(
                    def.learners[job.learner],
                    frame.len(),
                    frame.feature_count(),
                )
            },
            |id| {
                let job = list.jobs[id as usize];
                let l = &loaded[job.dataset];
                run_job(
                    &def,
                    id,
                    job,
                    &datasets[job.dataset],
                    (l, priced[job.dataset]),
                    peer.as_ref(),
                )
            },
        )?;
        if crate::shard::one_of_several(&args.shard, "testcost")? {
            return Ok(());
        }
    }
    let by_id: BTreeMap<u64, JobResult> = crate::shard::collect_of(&args.out, &def)?;
    check_results(&def, &priced, &by_id, &args.out)?;
    let results: Vec<JobResult> = by_id.into_values().collect();
    let rows = report::aggregate(&def, &results);
    let mut table = report::Table {
        def: def.clone(),
        rows,
        results,
        added: Vec::new(),
    };
    for dir in &args.with {
        let (other, by_id): (Definition, BTreeMap<u64, JobResult>) =
            crate::shard::collect(std::slice::from_ref(dir))?;
        check_joinable(&def, &other).with_context(|| {
            format!(
                "--with {}: its results cannot join this table",
                dir.display()
            )
        })?;
        // Its jobs are numbered over its own data sets; the table keeps its own.
        let other_priced = other
            .datasets
            .iter()
            .map(|d| match datasets.iter().position(|t| t == d) {
                Some(i) => Ok(priced[i]),
                None => {
                    let l = catalogue
                        .load(d)
                        .with_context(|| format!("--with {}: data set `{d}`", dir.display()))?;
                    Ok(Priced::of(&catalogue, std::slice::from_ref(d), &[l])[0])
                }
            })
            .collect::<Result<Vec<Priced>>>()?;
        check_results(&other, &other_priced, &by_id, dir)?;
        let results: Vec<JobResult> = by_id
            .into_values()
            .filter(|r| def.datasets.contains(&r.dataset))
            .collect();
        let other = Definition {
            datasets: def.datasets.clone(),
            ..other
        };
        let rows = report::aggregate(&other, &results);
        table.join(&other, rows, results);
    }
    let published: BTreeMap<String, String> = catalogue
        .sources()
        .iter()
        .filter_map(|s| s.published.clone().map(|p| (s.name.clone(), p)))
        .collect();
    let objects: BTreeMap<String, usize> = datasets
        .iter()
        .zip(&loaded)
        .map(|(d, l)| (d.clone(), l.frame.len()))
        .collect();
    report::write(&table, &published, &objects, &args.out, &args_line(args))?;
    if args.bless {
        report::write(
            &table,
            &published,
            &objects,
            Path::new("docs/testcost"),
            &args_line(args),
        )?;
    }
    Ok(())
}

/// The data sets a benchmark runs: those named, or the benchmark's (every data set of the
/// manifest but those it marks `benchmark = false`).
pub(crate) fn benchmark_datasets(catalogue: &Catalogue, named: &[String]) -> Vec<String> {
    if named.is_empty() {
        catalogue.benchmark().map(|s| s.name.clone()).collect()
    } else {
        named.to_vec()
    }
}

/// Reads the manifest and the data sets and checks the arguments: the benchmark they ask
/// for, or an error naming the flag at fault.
pub(crate) fn prepare(args: &TestcostArgs) -> Result<Prepared> {
    let catalogue = Catalogue::read(&args.manifest)?;
    let datasets = benchmark_datasets(&catalogue, &args.datasets);
    crate::files::distinct("--datasets", &datasets)?;
    let learners: Vec<Learner> = if args.learners.is_empty() {
        Method::ALL
            .into_iter()
            .filter(|m| !matches!(m, Method::Voi))
            .map(Learner::Family)
            .collect()
    } else {
        args.learners
            .iter()
            .map(|l| Learner::parse(l))
            .collect::<Result<_>>()?
    };
    crate::files::distinct(
        "--learners",
        &learners.iter().map(|m| m.name()).collect::<Vec<_>>(),
    )?;
    let costs: Vec<PriceSet> = args
        .costs
        .iter()
        .map(|c| match c.as_str() {
            "random" => Ok(PriceSet::Random),
            "turney" => Ok(PriceSet::Turney),
            other => bail!("--costs: `{other}` is neither `random` nor `turney`"),
        })
        .collect::<Result<_>>()?;
    crate::files::distinct("--costs", &args.costs)?;
    if args.mc.is_empty() || args.mc.iter().any(|m| !m.is_finite() || *m < 0.0) {
        bail!("--mc: every misclassification cost must be a finite number of at least 0");
    }
    let price_range = match args.price_range[..] {
        [lo, hi] if lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo <= hi => (lo, hi),
        _ => bail!("--price-range: expected LOW,HIGH with 0 <= LOW <= HIGH, finite"),
    };
    let price_draw = match args.price_draw.as_str() {
        "uniform" => PriceDraw::Uniform,
        "gain" => PriceDraw::Gain,
        other => bail!("--price-draw: `{other}` is neither `uniform` nor `gain`"),
    };
    let selection_prices = SelectionPrices::parse(&args.selection_prices)
        .map_err(|e| anyhow::anyhow!("--selection-prices: {e}"))?;
    let icet_pruning =
        Pruning::parse(&args.icet_pruning).map_err(|e| anyhow::anyhow!("--icet-pruning: {e}"))?;
    let cvt =
        CvtParams::with_folds(args.cvt_folds).map_err(|e| anyhow::anyhow!("--cvt-folds: {e}"))?;
    let cvt = cvt
        .with_samples(args.cvt_samples)
        .map_err(|e| anyhow::anyhow!("--cvt-samples: {e}"))?;
    let act = ActParams::with_samples(args.act_samples)
        .map_err(|e| anyhow::anyhow!("--act-samples: {e}"))?;
    let voi = VoiParams::from_options(args.voi_lookahead, args.voi_confidence, args.voi_m)
        .map_err(|e| anyhow::anyhow!("--voi-lookahead / --voi-confidence / --voi-m: {e}"))?;
    let budget = match args.max_test_cost {
        Some(b) if !(b.is_finite() && b >= 0.0) => {
            bail!("--max-test-cost {b}: a budget must be a finite price, not negative")
        }
        b => Budget::new(b, args.max_tests).map_err(|e| anyhow::anyhow!("--max-test-cost: {e}"))?,
    };
    if learners.contains(&Learner::Cegb)
        && (args.max_tests.is_some() || args.max_test_cost.is_some())
    {
        bail!(
            "--learners cegb cannot run with a budget per object (--max-tests, --max-test-cost): \
             LightGBM's trees cannot be cut where an object's budget ends, so CEGB would be \
             scored without it; run CEGB without a budget"
        );
    }
    if args.python.is_some() && !learners.contains(&Learner::Cegb) {
        bail!("--python is the interpreter of CEGB's worker: it needs --learners with cegb");
    }
    if args.icet_search_objects < 2 {
        bail!("--icet-search-objects: ICET's search needs at least 2 objects (one per half)");
    }
    if args.runs == 0 || args.folds < 2 || args.assignments == 0 {
        bail!("testcost needs --runs and --assignments of at least 1 and --folds of at least 2");
    }
    let voi_by_width = voi.lookahead.is_none() && learners.contains(&Learner::Family(Method::Voi));
    let def = Definition {
        datasets: datasets.clone(),
        learners,
        mc: args.mc.clone(),
        costs,
        assignments: args.assignments,
        price_range,
        price_draw,
        selection_prices,
        icet_pruning,
        icet_search_objects: args.icet_search_objects,
        cvt_folds: cvt.folds,
        act_samples: act.samples,
        cvt_samples: cvt.samples,
        voi,
        voi_by_width,
        max_tests: args.max_tests,
        max_test_cost: budget.max_test_cost(),
        runs: args.runs,
        folds: args.folds,
        seed: args.seed,
    };
    if price_range.1 == 0.0 && def.mc.contains(&0.0) {
        bail!(
            "--mc 0 with every price 0 (--price-range {},0): Turney's standard cost is 0, so no \
             cost can be normalised by it",
            price_range.0
        );
    }
    let loaded: Vec<_> = datasets
        .iter()
        .map(|d| catalogue.load(d).with_context(|| format!("data set `{d}`")))
        .collect::<Result<_>>()?;
    for (d, l) in datasets.iter().zip(&loaded) {
        check_dataset(&def, d, l)?;
    }
    let priced = Priced::of(&catalogue, &datasets, &loaded);
    if def.costs == [PriceSet::Turney] && !priced.iter().any(|p| p.turney) {
        bail!(
            "--costs turney: none of the data sets ({}) has Turney's prices; name one that has \
             (heart, hepatitis, pima, thyroid) or add --costs random",
            datasets.join(", ")
        );
    }
    job_count(&def, &priced)?;
    Ok(Prepared {
        catalogue,
        datasets,
        def,
        loaded,
        priced,
    })
}

/// The most jobs one benchmark may have: each keeps a line of results, and the job list
/// is made whole before the first runs.
const MAX_JOBS: u64 = 10_000_000;

/// The number of jobs of `def`, judged before any is made: at most [`MAX_JOBS`].
fn job_count(def: &Definition, priced: &[Priced]) -> Result<u64> {
    let mut sets: u64 = 0;
    for p in priced {
        for &costs in &def.costs {
            sets = sets.saturating_add(p.assignments(def, costs));
        }
    }
    let jobs = sets
        .saturating_mul(def.runs)
        .saturating_mul(def.learners.len() as u64);
    if jobs > MAX_JOBS {
        bail!(
            "{} price sets (data sets times --assignments, and Turney's) times --runs {} times \
             {} learners make more than the {MAX_JOBS} jobs a benchmark may have",
            sets,
            def.runs,
            def.learners.len()
        );
    }
    Ok(jobs)
}

/// What a data set must allow before a job is made: at least two objects of every class
/// (the stratified folds hold a class of one object out of one fold's training part, and
/// a tree must see every class it is judged on), a fold per `--folds` (and per
/// `--cvt-folds` inside a training part, with CVT), and every total cost a true number at
/// the dearest price and mc.
fn check_dataset(def: &Definition, name: &str, loaded: &cslearn::testcost::Loaded) -> Result<()> {
    let frame = &loaded.frame;
    let totals = frame.class_totals();
    if let Some(c) = totals.iter().position(|&t| t < 2) {
        bail!(
            "data set `{name}`: class `{}` has {} object{}: the stratified folds would judge \
             a tree on a class its training part lacks (every class needs at least 2)",
            frame.class_names()[c],
            totals[c],
            if totals[c] == 1 { "" } else { "s" }
        );
    }
    let n = frame.len();
    if def.folds > n {
        bail!(
            "--folds {}: more folds than the {n} objects of data set `{name}`",
            def.folds
        );
    }
    let training = n - n.div_ceil(def.folds);
    if def.learners.contains(&Learner::Family(Method::Cvt)) && def.cvt_folds > training {
        bail!(
            "--cvt-folds {}: more folds than the {training} objects of a training part of data \
             set `{name}`",
            def.cvt_folds
        );
    }
    let dearest = match &loaded.turney {
        Some(t) if def.costs.contains(&PriceSet::Turney) => (0..t.len())
            .map(|i| t.test(i).full)
            .fold(def.price_range.1, f64::max),
        _ => def.price_range.1,
    };
    let prices = TestPrices::flat(&vec![dearest; frame.feature_count()])
        .map_err(|e| anyhow::anyhow!("--price-range: {e}"))?;
    for &mc in &def.mc {
        let shown = if mc >= 1e9 {
            format!("{mc:e}")
        } else {
            mc.to_string()
        };
        MisclassCosts::uniform(frame.class_count(), mc)
            .and_then(|m| m.check_totals(&prices, n))
            .map_err(|e| {
                anyhow::anyhow!("--mc {shown} and --price-range on data set `{name}`: {e}")
            })?;
    }
    Ok(())
}

/// Every result line is what its job number says and holds true numbers: its data set,
/// price set, draw, run and learner those of its job in `def`'s list, one score per mc
/// in order, totals and test costs finite and not negative, error rates and areas
/// between 0 and 1, standard costs above 0. A line edited by hand (labels swapped, a
/// total made negative) is refused by name rather than put in another learner's row.
fn check_results(
    def: &Definition,
    priced: &[Priced],
    results: &BTreeMap<u64, JobResult>,
    dir: &Path,
) -> Result<()> {
    let list = Jobs::new(def, priced);
    for (&id, r) in results {
        let bad = |why: String| {
            anyhow::anyhow!(
                "{}: the result of job {id} {why}; the line was changed after it was written \
                 (run its job again: delete the line and rerun the same command)",
                dir.display()
            )
        };
        let Some(job) = list.jobs.get(id as usize) else {
            return Err(bad(format!(
                "is not a job of this benchmark's {} jobs",
                list.jobs.len()
            )));
        };
        let expected = (
            def.datasets[job.dataset].as_str(),
            job.costs,
            job.assignment,
            job.run,
            def.learners[job.learner],
        );
        if (r.dataset.as_str(), r.costs, r.assignment, r.run, r.learner) != expected {
            return Err(bad(format!(
                "says {} on `{}` ({} prices, draw {}, run {}), but job {id} is {} on `{}` ({} \
                 prices, draw {}, run {})",
                r.learner.name(),
                r.dataset,
                r.costs.name(),
                r.assignment,
                r.run,
                expected.4.name(),
                expected.0,
                expected.1.name(),
                expected.2,
                expected.3
            )));
        }
        if r.by_mc.len() != def.mc.len() || r.by_mc.iter().zip(&def.mc).any(|(s, &m)| s.mc != m) {
            return Err(bad(
                "has other misclassification costs than the benchmark".into()
            ));
        }
        for s in &r.by_mc {
            // A total beyond the bound every front end holds (cslearn::MAX_TOTAL_COST)
            // was not written by a job.
            let cost = |x: f64| (0.0..=cslearn::MAX_TOTAL_COST).contains(&x);
            let share = |x: f64| (0.0..=1.0).contains(&x);
            let true_score = cost(s.total)
                && cost(s.tests)
                && share(s.error_rate)
                && s.standard > 0.0
                && s.standard <= cslearn::MAX_TOTAL_COST
                && s.auroc.is_none_or(share);
            if !true_score {
                return Err(bad(format!(
                    "holds a score that is not a true one at mc {} (total {}, tests {}, error \
                     rate {}, standard cost {})",
                    s.mc, s.total, s.tests, s.error_rate, s.standard
                )));
            }
        }
    }
    Ok(())
}

/// Whether another benchmark's rows may join `def`'s table: the same data sets, price sets,
/// draws, folds, seed and settings (so the same folds and prices), any learners and runs,
/// and misclassification costs among `def`'s.
fn check_joinable(def: &Definition, other: &Definition) -> Result<()> {
    if let Some(mc) = other.mc.iter().find(|m| !def.mc.contains(m)) {
        bail!("it has mc {mc}, which this table does not");
    }
    if let Some(d) = def.datasets.iter().find(|d| !other.datasets.contains(d)) {
        bail!("it lacks the data set `{d}` (it may have more than the table, not fewer)");
    }
    // VOI's settings are those of the rows that come with VOI: only its learners join.
    let same_protocol = Definition {
        learners: def.learners.clone(),
        runs: def.runs,
        mc: def.mc.clone(),
        voi: def.voi,
        voi_by_width: def.voi_by_width,
        datasets: def.datasets.clone(),
        ..other.clone()
    };
    if &same_protocol != def {
        bail!(
            "it was run over other data sets, prices, folds, seed or settings \
             ({other:?}, against {def:?})"
        );
    }
    Ok(())
}

/// A rough estimate of a job's work, to hand out the heaviest jobs first: objects times
/// tests, times a factor for the learners that grow many trees per tree kept (ICET's
/// search, ACT's sampling, CVT's cross-validation). It orders jobs only; it changes no result.
pub(crate) fn work(learner: Learner, objects: usize, tests: usize) -> f64 {
    let trees_per_tree = match learner {
        Learner::Family(Method::Icet) => 300.0,
        Learner::Family(Method::Act) => 1000.0,
        // Six trees of ACT's lookahead per fit (one per fold and one on every object).
        Learner::Family(Method::Cvt) => 5000.0,
        // About a hundred boosted models per fit (its tradeoff's cross-validation).
        Learner::Cegb => 1000.0,
        Learner::Family(_) => 1.0,
    };
    trees_per_tree * objects as f64 * tests as f64
}

/// The command that made a report, for its header.
fn args_line(args: &TestcostArgs) -> String {
    let mut line = String::from("cargo xtask testcost");
    if !args.datasets.is_empty() {
        let _ = write!(line, " --datasets {}", args.datasets.join(","));
    }
    if !args.learners.is_empty() {
        let _ = write!(line, " --learners {}", args.learners.join(","));
    }
    if !args.with.is_empty() {
        let with: Vec<String> = args.with.iter().map(|d| d.display().to_string()).collect();
        let _ = write!(line, " --with {}", with.join(","));
    }
    let mc: Vec<String> = args.mc.iter().map(|m| m.to_string()).collect();
    if mc.join(",") != "100,500,1000,5000" {
        let _ = write!(line, " --mc {}", mc.join(","));
    }
    if args.costs.join(",") != "random,turney" {
        let _ = write!(line, " --costs {}", args.costs.join(","));
    }
    if args.price_draw != "uniform" {
        let _ = write!(line, " --price-draw {}", args.price_draw);
    }
    if args.selection_prices != "listed" {
        let _ = write!(line, " --selection-prices {}", args.selection_prices);
    }
    if args.icet_pruning != "costs" {
        let _ = write!(line, " --icet-pruning {}", args.icet_pruning);
    }
    if args.icet_search_objects != 1000 {
        let _ = write!(line, " --icet-search-objects {}", args.icet_search_objects);
    }
    if args.cvt_folds != 5 {
        let _ = write!(line, " --cvt-folds {}", args.cvt_folds);
    }
    if args.act_samples != 5 {
        let _ = write!(line, " --act-samples {}", args.act_samples);
    }
    if args.cvt_samples != 5 {
        let _ = write!(line, " --cvt-samples {}", args.cvt_samples);
    }
    for (flag, value) in [
        ("--voi-lookahead", args.voi_lookahead.map(|d| d.to_string())),
        (
            "--voi-confidence",
            args.voi_confidence.map(|c| c.to_string()),
        ),
        ("--voi-m", args.voi_m.map(|m| m.to_string())),
    ] {
        if let Some(value) = value {
            let _ = write!(line, " {flag} {value}");
        }
    }
    if let Some(k) = args.max_tests {
        let _ = write!(line, " --max-tests {k}");
    }
    if let Some(b) = args.max_test_cost {
        let _ = write!(line, " --max-test-cost {b}");
    }
    if args.price_range != [1.0, 100.0] {
        let _ = write!(
            line,
            " --price-range {},{}",
            args.price_range[0], args.price_range[1]
        );
    }
    if args.assignments != 4 {
        let _ = write!(line, " --assignments {}", args.assignments);
    }
    if args.runs != 10 {
        let _ = write!(line, " --runs {}", args.runs);
    }
    if args.folds != 10 {
        let _ = write!(line, " --folds {}", args.folds);
    }
    if args.seed != 1 {
        let _ = write!(line, " --seed {}", args.seed);
    }
    line
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A small benchmark: iris and heart, three learners, two mc, two draws, one run of
    /// three folds.
    pub(crate) fn args(out: &Path, threads: usize) -> TestcostArgs {
        TestcostArgs {
            datasets: vec!["iris".into(), "heart".into()],
            learners: vec!["eg2".into(), "cs-id3-batch".into(), "dtmc".into()],
            mc: vec![100.0, 500.0],
            costs: vec!["random".into(), "turney".into()],
            assignments: 2,
            price_draw: "uniform".into(),
            selection_prices: "listed".into(),
            icet_pruning: "costs".into(),
            icet_search_objects: 400,
            cvt_folds: 5,
            act_samples: 5,
            cvt_samples: 5,
            voi_lookahead: None,
            voi_confidence: None,
            voi_m: None,
            max_tests: None,
            max_test_cost: None,
            price_range: vec![1.0, 100.0],
            runs: 1,
            folds: 3,
            seed: 5,
            manifest: Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/uci/datasets.toml"),
            out: out.to_path_buf(),
            threads: Some(threads),
            shard: "1/1".into(),
            with: Vec::new(),
            python: None,
            report: false,
            bless: false,
        }
    }

    /// Counts beyond what the data allow, totals that cannot be true numbers, and price
    /// sets that hold nothing are refused by flag before a job is made (each once aborted
    /// on gigabytes, ran without end, or wrote NaN or an empty table).
    #[test]
    fn hostile_counts_and_degenerate_benchmarks_are_refused_by_flag() {
        let dir = tempfile::tempdir().unwrap();
        let refused = |edit: &dyn Fn(&mut TestcostArgs), expected: &[&str]| {
            let mut a = args(dir.path(), 1);
            edit(&mut a);
            let err = format!("{:#}", testcost(&a).unwrap_err());
            for e in expected {
                assert!(err.contains(e), "{e}: {err}");
            }
        };
        refused(
            &|a| a.folds = 1_000_000_000,
            &["--folds 1000000000: more folds than the 150 objects of data set `iris`"],
        );
        refused(
            &|a| a.runs = 1_000_000_000,
            &["--runs 1000000000", "jobs a benchmark"],
        );
        refused(
            &|a| a.assignments = 1_000_000_000_000,
            &["more than the 10000000 jobs"],
        );
        refused(
            &|a| {
                a.learners = vec!["cvt".into()];
                a.cvt_folds = 1_000_000_000_000;
            },
            &["--cvt-folds 1000000000000: more folds than the 100 objects of a training part"],
        );
        refused(
            &|a| a.mc = vec![1e308],
            &["--mc 1e308", "cannot be represented"],
        );
        refused(
            &|a| a.price_range = vec![1e307, 1e307],
            &["--price-range on data set `iris`", "cannot be represented"],
        );
        refused(
            &|a| {
                a.mc = vec![0.0];
                a.price_range = vec![0.0, 0.0];
            },
            &["standard cost is 0"],
        );
        refused(
            &|a| {
                a.datasets = vec!["iris".into()];
                a.costs = vec!["turney".into()];
            },
            &["--costs turney: none of the data sets (iris) has Turney's prices"],
        );
        assert!(
            std::fs::read_dir(dir.path()).unwrap().next().is_none(),
            "nothing was written"
        );
    }

    /// A data set of one object, or with a class of one object, is refused by name before
    /// a job is made: stratified folds would judge a tree on a class its training part
    /// lacks (once both ran).
    #[test]
    fn data_sets_with_a_class_of_one_object_are_refused_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let data = "1,a\n2,a\n3,a\n4,b\n5,b\n6,b\n7,c\n";
        std::fs::write(dir.path().join("lone.data"), data).unwrap();
        std::fs::write(dir.path().join("one.data"), "1,a\n").unwrap();
        let table = |name: &str| {
            format!(
                "[[dataset]]\nname = \"{name}\"\nfiles = [\"{name}.data\"]\n\
                 columns = [\"x\", \"t\"]\ntarget = \"t\"\nmissing = []\n"
            )
        };
        let manifest = dir.path().join("datasets.toml");
        std::fs::write(&manifest, table("lone") + &table("one")).unwrap();
        for (name, expected) in [
            ("lone", "data set `lone`: class `c` has 1 object"),
            ("one", "data set `one`: class `a` has 1 object"),
        ] {
            let out = dir.path().join(format!("out-{name}"));
            let mut a = args(&out, 1);
            a.manifest.clone_from(&manifest);
            a.datasets = vec![name.into()];
            a.costs = vec!["random".into()];
            let err = format!("{:#}", testcost(&a).unwrap_err());
            assert!(err.contains(expected), "{err}");
            assert!(err.contains("every class needs at least 2"), "{err}");
            assert!(!out.exists(), "nothing was written");
        }
    }

    /// A results line edited by hand is refused by name, never put in another row: labels
    /// swapped between two learners' lines, a negative total.
    #[test]
    fn tampered_result_lines_are_refused_not_joined() {
        let dir = tempfile::tempdir().unwrap();
        let a = args(dir.path(), 1);
        testcost(&a).unwrap();
        let path = dir.path().join("shard-1-of-1/results.jsonl");
        let original = std::fs::read_to_string(&path).unwrap();
        let report = TestcostArgs {
            report: true,
            ..a.clone()
        };
        let tampered = |text: String, expected: &str| {
            std::fs::write(&path, text).unwrap();
            let err = format!("{:#}", testcost(&report).unwrap_err());
            assert!(err.contains(expected), "{expected}: {err}");
        };
        let swapped = original
            .replacen("\"learner\":\"Eg2\"", "\"learner\":\"X\"", 1)
            .replacen("\"learner\":\"CsId3Batch\"", "\"learner\":\"Eg2\"", 1)
            .replacen("\"learner\":\"X\"", "\"learner\":\"CsId3Batch\"", 1);
        assert_ne!(swapped, original, "the lines name their learners so");
        tampered(swapped, "says cs-id3-batch on `");
        let negative = original.replacen("\"total\":", "\"total\":-", 1);
        tampered(negative, "holds a score that is not a true one");
        let huge = original.replacen("\"total\":", "\"total\":1e308,\"x\":", 1);
        tampered(huge, "holds a score that is not a true one");
        std::fs::write(&path, &original).unwrap();
        testcost(&report).unwrap();
    }

    #[test]
    fn the_table_does_not_depend_on_the_thread_count_and_has_the_issue_columns() {
        let (one, two) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
        testcost(&args(one.path(), 1)).unwrap();
        testcost(&args(two.path(), 2)).unwrap();
        let a = std::fs::read_to_string(one.path().join("testcost.csv")).unwrap();
        let b = std::fs::read_to_string(two.path().join("testcost.csv")).unwrap();
        assert_eq!(a, b);
        let mut lines = a.lines();
        assert_eq!(
            lines.next().unwrap(),
            "dataset,costs,mc,learner,runs,folds,normalised_cost,ci95,test_cost,error_rate,ratio_to_cs_id3"
        );
        // iris: random prices only; heart: random and Turney's; 2 mc, 3 learners.
        assert_eq!(lines.clone().count(), (1 + 2) * 2 * 3);
        for line in lines {
            let cells: Vec<&str> = line.split(',').collect();
            assert_eq!(cells.len(), 11, "{line}");
            let normalised: f64 = cells[6].parse().unwrap();
            assert!(normalised > 0.0 && normalised < 200.0, "{line}");
            if cells[3] == "cs-id3-batch" {
                assert_eq!(cells[10], "1.0000", "{line}");
            }
        }
        // The report names the published figure beside ours where there is one.
        let md = std::fs::read_to_string(one.path().join("testcost.md")).unwrap();
        assert!(md.contains("(35.0)"), "heart's published EG2 at mc 500");
        // The times: per tree, per job and per classification, one row per data set and
        // learner.
        let timing = std::fs::read_to_string(one.path().join("timing.csv")).unwrap();
        let mut rows = timing.lines();
        assert_eq!(
            rows.next().unwrap(),
            "dataset,learner,ms_per_tree,nodes_per_tree,learn_seconds_per_job,us_per_classification"
        );
        assert_eq!(rows.clone().count(), 2 * 3);
        for row in rows {
            let per_object: f64 = row.rsplit(',').next().unwrap().parse().unwrap();
            assert!(per_object >= 0.0 && per_object.is_finite(), "{row}");
        }
        // AUROC beside the error rate, in a file of its own, one line per row of the
        // table; the trees rank the held-out objects far better than chance.
        let auroc = std::fs::read_to_string(one.path().join("auroc.csv")).unwrap();
        assert_eq!(
            auroc,
            std::fs::read_to_string(two.path().join("auroc.csv")).unwrap()
        );
        let mut rows = auroc.lines();
        assert_eq!(
            rows.next().unwrap(),
            "dataset,costs,mc,learner,runs,folds,error_rate,auroc"
        );
        assert_eq!(rows.clone().count(), (1 + 2) * 2 * 3);
        for (row, table) in rows.zip(a.lines().skip(1)) {
            let cells: Vec<&str> = row.split(',').collect();
            let area: f64 = cells[7].parse().unwrap();
            assert!(area > 0.6 && area <= 1.0, "{row}");
            // The same row of the table, its error rate too.
            let t: Vec<&str> = table.split(',').collect();
            assert_eq!(cells[..6], t[..6], "{row}");
            assert_eq!(cells[6], t[9], "{row}");
        }
    }

    /// A budget is a setting of the benchmark's definition: absent from results written
    /// before it (which read as no budget and write back the same), and held to: with a
    /// budget of nothing no object pays for a test.
    #[test]
    fn a_budget_is_a_setting_that_old_results_do_not_have() {
        let dir = tempfile::tempdir().unwrap();
        let mut free = args(dir.path(), 1);
        free.datasets = vec!["iris".into()];
        free.costs = vec!["random".into()];
        let mut zero = free.clone();
        zero.max_test_cost = Some(0.0);
        zero.out = dir.path().join("zero");
        testcost(&zero).unwrap();
        let table = std::fs::read_to_string(zero.out.join("testcost.csv")).unwrap();
        for line in table.lines().skip(1) {
            assert_eq!(line.split(',').nth(8), Some("0.000"), "{line}");
        }
        // The definition without a budget is written as before, and read back so.
        let budgetless = Definition {
            datasets: vec!["iris".into()],
            learners: vec![Learner::Family(Method::Eg2)],
            mc: vec![100.0],
            costs: vec![PriceSet::Random],
            assignments: 1,
            price_range: (1.0, 100.0),
            price_draw: PriceDraw::Uniform,
            selection_prices: SelectionPrices::Listed,
            icet_pruning: Pruning::Costs,
            icet_search_objects: 400,
            cvt_folds: 5,
            act_samples: 5,
            cvt_samples: 5,
            voi: VoiParams::default(),
            voi_by_width: false,
            max_tests: None,
            max_test_cost: None,
            runs: 1,
            folds: 3,
            seed: 5,
        };
        let text = serde_json::to_string(&budgetless).unwrap();
        assert!(!text.contains("max_test"), "{text}");
        assert_eq!(
            serde_json::from_str::<Definition>(&text).unwrap(),
            budgetless
        );
        let with = Definition {
            max_tests: Some(2),
            ..budgetless.clone()
        };
        let text = serde_json::to_string(&with).unwrap();
        assert!(text.contains("\"max_tests\":2"), "{text}");
        assert_eq!(serde_json::from_str::<Definition>(&text).unwrap(), with);
        let mut bad = free.clone();
        bad.max_test_cost = Some(-1.0);
        let err = testcost(&bad).unwrap_err().to_string();
        assert!(err.contains("--max-test-cost -1"), "{err}");
    }

    #[test]
    fn auroc_by_hand() {
        let two = |p: &[f64]| -> Vec<Vec<f64>> { p.iter().map(|&x| vec![1.0 - x, x]).collect() };
        // Perfect, reversed, and all tied.
        assert_eq!(auroc(&two(&[0.1, 0.2, 0.8, 0.9]), &[0, 0, 1, 1]), Some(1.0));
        assert_eq!(auroc(&two(&[0.9, 0.8, 0.2, 0.1]), &[0, 0, 1, 1]), Some(0.0));
        assert_eq!(auroc(&two(&[0.5; 4]), &[0, 1, 0, 1]), Some(0.5));
        // Positives 0.4, 0.8 against negatives 0.1, 0.4, 0.6: of 6 pairs, 4 won and one
        // tied: 4.5 / 6.
        let area = auroc(&two(&[0.4, 0.8, 0.1, 0.4, 0.6]), &[1, 1, 0, 0, 0]).unwrap();
        assert!((area - 0.75).abs() < 1e-15, "{area}");
        // Three classes: the mean of each one-vs-rest area; a class with no object is
        // left out; one class alone has no area.
        let three = vec![
            vec![0.8, 0.1, 0.1],
            vec![0.2, 0.7, 0.1],
            vec![0.6, 0.3, 0.1],
            vec![0.1, 0.1, 0.8],
        ];
        // Class 0 ranks {0, 2} above {1, 3}: 1; class 1 ranks object 1 first: 1; class 2
        // ranks object 3 first: 1.
        assert_eq!(auroc(&three, &[0, 1, 0, 2]), Some(1.0));
        // Class 0 (objects 0, 1, 3 at 0.8, 0.2, 0.1 against object 2 at 0.6: one pair
        // of three won, 1/3), class 1 (object 2 at 0.3 against 0.1, 0.7, 0.1: 2/3); class
        // 2 has no object.
        let area = auroc(&three, &[0, 0, 1, 0]).unwrap();
        assert!(
            (area - (1.0 / 3.0 + 2.0 / 3.0) / 2.0).abs() < 1e-15,
            "{area}"
        );
        assert_eq!(auroc(&two(&[0.3, 0.6]), &[1, 1]), None);
        assert_eq!(auroc(&[], &[]), None);
    }

    #[test]
    fn results_written_before_auroc_still_read_and_leave_the_table_alone() {
        let old = r#"{"mc":100.0,"total":20.5,"tests":3.0,"error_rate":0.25,"standard":41.0}"#;
        let score: Score = serde_json::from_str(old).unwrap();
        assert_eq!(score.auroc, None);
        // Written back, it is the same line: no field for what was not measured.
        assert_eq!(serde_json::to_string(&score).unwrap(), old);
        let result = JobResult {
            id: 0,
            dataset: "iris".into(),
            costs: PriceSet::Random,
            assignment: 0,
            run: 0,
            learner: Learner::Family(Method::Eg2),
            by_mc: vec![score],
            nodes: 3.0,
            learn_seconds: 0.0,
            classify_seconds: 0.0,
            library: None,
            tradeoffs: None,
        };
        let def = Definition {
            datasets: vec!["iris".into()],
            learners: vec![Learner::Family(Method::Eg2)],
            mc: vec![100.0],
            costs: vec![PriceSet::Random],
            assignments: 1,
            price_range: (1.0, 100.0),
            price_draw: PriceDraw::Uniform,
            selection_prices: SelectionPrices::Listed,
            icet_pruning: Pruning::Costs,
            icet_search_objects: 400,
            cvt_folds: 5,
            act_samples: 5,
            cvt_samples: 5,
            voi: VoiParams::default(),
            voi_by_width: false,
            max_tests: None,
            max_test_cost: None,
            runs: 1,
            folds: 3,
            seed: 5,
        };
        let rows = report::aggregate(&def, std::slice::from_ref(&result));
        assert_eq!(rows.len(), 1);
        assert_eq!(report::auroc_csv(&def, &rows), None);
        let mut measured = result;
        measured.by_mc[0].auroc = Some(0.875);
        let rows = report::aggregate(&def, &[measured]);
        assert_eq!(
            report::auroc_csv(&def, &rows).unwrap().lines().nth(1),
            Some("iris,random,100,eg2,1,3,0.2500,0.8750")
        );
    }

    #[test]
    fn a_learner_measured_alone_over_the_same_protocol_joins_as_the_tables_own() {
        let (main, other, joined, whole) = (
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
        );
        testcost(&args(main.path(), 1)).unwrap();
        // C4.5 alone (no CS-ID3 beside it), on the table's runs and mc.
        let mut alone = args(other.path(), 1);
        alone.learners = vec!["c45".into()];
        testcost(&alone).unwrap();
        let mut with = args(joined.path(), 1);
        with.with = vec![other.path().to_path_buf()];
        testcost(&with).unwrap();
        // The same rows, ratios included, as one benchmark of the four learners.
        let mut four = args(whole.path(), 1);
        four.learners.push("c45".into());
        testcost(&four).unwrap();
        let read = |dir: &Path| std::fs::read_to_string(dir.join("testcost.csv")).unwrap();
        let c45 = |csv: &str| -> Vec<String> {
            csv.lines()
                .filter(|l| l.contains(",c45,"))
                .map(String::from)
                .collect()
        };
        let (both, all) = (c45(&read(joined.path())), c45(&read(whole.path())));
        assert_eq!(
            both.len(),
            2 * 3,
            "iris random, heart random and Turney, two mc"
        );
        assert_eq!(both, all);
        assert!(both.iter().all(|l| !l.ends_with(',')), "{both:?}");
        let md = std::fs::read_to_string(joined.path().join("testcost.md")).unwrap();
        assert!(
            md.contains("c45: from another benchmark of the same protocol"),
            "{md}"
        );
        assert!(!md.contains("[1 run]") && !md.contains("the first"), "{md}");

        // Alone on fewer runs than the table's, its ratio is taken on the table's CS-ID3
        // of those runs: what one benchmark of both on those runs gives.
        let (main2, other2, joined2, whole2) = (
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
        );
        let mut two = args(main2.path(), 1);
        two.runs = 2;
        testcost(&two).unwrap();
        let mut first = args(other2.path(), 1);
        first.learners = vec!["c45".into()];
        first.mc = vec![500.0];
        testcost(&first).unwrap();
        let mut with = args(joined2.path(), 1);
        with.runs = 2;
        with.with = vec![other2.path().to_path_buf()];
        testcost(&with).unwrap();
        let mut both_one = args(whole2.path(), 1);
        both_one.learners = vec!["cs-id3-batch".into(), "c45".into()];
        both_one.mc = vec![500.0];
        testcost(&both_one).unwrap();
        let ratios = |csv: &str| -> Vec<f64> {
            c45(csv)
                .iter()
                .map(|l| l.rsplit(',').next().unwrap().parse().unwrap())
                .collect()
        };
        let (got, want) = (ratios(&read(joined2.path())), ratios(&read(whole2.path())));
        assert_eq!(got.len(), 3);
        assert_eq!(got, want);
    }

    #[test]
    fn another_benchmark_over_the_same_folds_adds_its_learners_with_their_runs() {
        let (main, other, joined) = (
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
        );
        let alone = args(main.path(), 1);
        testcost(&alone).unwrap();
        // Two runs, one mc, a learner the main table lacks and one it has.
        let mut dear = args(other.path(), 1);
        dear.learners = vec!["cs-id3-batch".into(), "c45".into(), "eg2".into()];
        dear.mc = vec![500.0];
        dear.runs = 2;
        testcost(&dear).unwrap();
        let mut with = args(joined.path(), 1);
        with.with = vec![other.path().to_path_buf()];
        testcost(&with).unwrap();
        let read = |dir: &Path| std::fs::read_to_string(dir.join("testcost.csv")).unwrap();
        let (base, both, dear_csv) = (read(main.path()), read(joined.path()), read(other.path()));
        // The table's own rows are unchanged; the added learner's are the other run's,
        // at its mc only, saying their runs.
        let added: Vec<&str> = both.lines().filter(|l| l.contains(",c45,")).collect();
        assert_eq!(
            both.lines()
                .filter(|l| !l.contains(",c45,"))
                .collect::<Vec<_>>(),
            base.lines().collect::<Vec<_>>()
        );
        assert_eq!(
            added,
            dear_csv
                .lines()
                .filter(|l| l.contains(",c45,"))
                .collect::<Vec<_>>()
        );
        assert_eq!(
            added.len(),
            1 + 2,
            "iris random, heart random and Turney, mc 500"
        );
        for line in &added {
            let cells: Vec<&str> = line.split(',').collect();
            assert_eq!((cells[2], cells[4]), ("500", "2"), "{line}");
            assert!(
                !cells[10].is_empty(),
                "a ratio to CS-ID3 on its own runs: {line}"
            );
        }
        // Rows stay in the table's order: c45 after the table's learners at mc 500.
        let order: Vec<&str> = both
            .lines()
            .skip(1)
            .filter(|l| l.starts_with("iris,random,500,"))
            .map(|l| l.split(',').nth(3).unwrap())
            .collect();
        assert_eq!(order, ["eg2", "cs-id3-batch", "dtmc", "c45"]);
        let md = std::fs::read_to_string(joined.path().join("testcost.md")).unwrap();
        assert!(
            md.contains("c45: the first 2 runs only (the same folds and prices), at mc 500 only"),
            "{md}"
        );
        // Each of its cells says it measured other runs than the table's.
        let mc500 = md.split("mc = 500").nth(1).unwrap();
        let iris = mc500.lines().find(|l| l.starts_with("| iris |")).unwrap();
        let last = iris
            .trim_end()
            .trim_end_matches('|')
            .rsplit('|')
            .next()
            .unwrap();
        assert!(last.contains("± ") && last.contains(" [2 runs]"), "{iris}");
        assert_eq!(iris.matches("[2 runs]").count(), 1, "{iris}");
        let mc100 = md
            .split("mc = 100")
            .nth(1)
            .unwrap()
            .split("mc = 500")
            .next()
            .unwrap();
        assert!(
            !mc100.contains("c45"),
            "no empty column where it was not run: {mc100}"
        );
        assert!(md.contains(" --with "), "the command names the folder");
        let timing = std::fs::read_to_string(joined.path().join("timing.csv")).unwrap();
        assert_eq!(timing.lines().filter(|l| l.contains(",c45,")).count(), 2);

        // Other folds (another seed) cannot join.
        let (elsewhere, refused) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
        let mut reseeded = dear.clone();
        reseeded.out = elsewhere.path().to_path_buf();
        reseeded.seed = 6;
        testcost(&reseeded).unwrap();
        let mut with = args(refused.path(), 1);
        with.with = vec![elsewhere.path().to_path_buf()];
        let err = format!("{:#}", testcost(&with).unwrap_err());
        assert!(err.contains("cannot join") && err.contains("seed"), "{err}");
        // Nor an mc the table does not have.
        let mut dearer = dear.clone();
        let (third, refused) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
        dearer.out = third.path().to_path_buf();
        dearer.mc = vec![1000.0];
        testcost(&dearer).unwrap();
        let mut with = args(refused.path(), 1);
        with.with = vec![third.path().to_path_buf()];
        let err = format!("{:#}", testcost(&with).unwrap_err());
        assert!(err.contains("mc 1000"), "{err}");
    }

    /// A benchmark over more data sets joins a table over some of them (its rows of the
    /// table's data sets, as its own report has them); one over fewer is refused.
    #[test]
    fn a_benchmark_over_more_data_sets_joins_with_the_tables_data_sets() {
        let (small, wide, joined, refused) = (
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
            tempfile::tempdir().unwrap(),
        );
        let mut iris = args(small.path(), 1);
        iris.datasets = vec!["iris".into()];
        testcost(&iris).unwrap();
        let mut both = args(wide.path(), 1);
        both.learners = vec!["cs-id3-batch".into(), "c45".into()];
        testcost(&both).unwrap();
        let mut with = iris.clone();
        with.out = joined.path().to_path_buf();
        with.with = vec![wide.path().to_path_buf()];
        testcost(&with).unwrap();
        let read = |dir: &Path| std::fs::read_to_string(dir.join("testcost.csv")).unwrap();
        let c45 = |csv: &str| -> Vec<String> {
            csv.lines()
                .filter(|l| l.contains(",c45,") && l.starts_with("iris,"))
                .map(String::from)
                .collect()
        };
        let added = c45(&read(joined.path()));
        assert_eq!(added.len(), 2, "iris, random prices, two mc");
        assert_eq!(added, c45(&read(wide.path())));
        assert!(!read(joined.path()).contains("heart"));
        // The table over both cannot take a benchmark over iris alone.
        let mut narrow = args(refused.path(), 1);
        narrow.with = vec![small.path().to_path_buf()];
        let err = format!("{:#}", testcost(&narrow).unwrap_err());
        assert!(err.contains("lacks the data set `heart`"), "{err}");
    }

    /// A benchmark with VOI written when its default looked two tests ahead everywhere
    /// reads as such, and differs from one written since (which says it follows the
    /// width); the definitions of the other learners read and write as before.
    #[test]
    fn voi_before_its_default_followed_the_width_reads_as_two_tests_ahead() {
        let before = r#"{"datasets":["iris"],"learners":["Voi"],"mc":[500.0],"costs":["random"],"assignments":1,"price_range":[1.0,100.0],"price_draw":"uniform","selection_prices":"listed","icet_pruning":"costs","icet_search_objects":1000,"cvt_folds":5,"act_samples":5,"runs":1,"folds":3,"seed":1}"#;
        let old: Definition = serde_json::from_str(before).unwrap();
        assert_eq!(old.voi_params().lookahead, Some(2));
        assert_eq!(serde_json::to_string(&old).unwrap(), before);
        let now = Definition {
            voi_by_width: true,
            ..old.clone()
        };
        assert_ne!(now, old);
        assert_eq!(now.voi_params().lookahead, None);
        let text = serde_json::to_string(&now).unwrap();
        assert!(text.contains(r#""voi_by_width":true"#), "{text}");
        assert_eq!(serde_json::from_str::<Definition>(&text).unwrap(), now);
        // A run of VOI at its default now writes it; without VOI nothing changes.
        let dir = tempfile::tempdir().unwrap();
        let mut voi = args(dir.path(), 1);
        voi.learners = vec!["voi".into()];
        assert!(prepare(&voi).unwrap().def.voi_by_width);
        voi.voi_lookahead = Some(2);
        assert!(!prepare(&voi).unwrap().def.voi_by_width);
        assert!(!prepare(&args(dir.path(), 1)).unwrap().def.voi_by_width);
        // Without `--learners`, the nine of the family, in their order: VOI and CEGB are
        // named.
        let mut default = args(dir.path(), 1);
        default.learners.clear();
        let names: Vec<&str> = prepare(&default)
            .unwrap()
            .def
            .learners
            .iter()
            .map(|l| l.name())
            .collect();
        assert_eq!(
            names,
            [
                "c45",
                "id3-batch",
                "idx",
                "cs-id3-batch",
                "eg2",
                "dtmc",
                "icet",
                "act",
                "cvt"
            ]
        );
        // The report says how far VOI looked.
        for (lookahead, said) in [
            (
                None,
                "VOI values a test three tests ahead on data of at most 21 features",
            ),
            (Some(1), "VOI values a test one test ahead."),
            (Some(2), "VOI values a test 2 tests ahead."),
        ] {
            let out = tempfile::tempdir().unwrap();
            let mut run = args(out.path(), 1);
            run.datasets = vec!["iris".into()];
            run.learners = vec!["cs-id3-batch".into(), "voi".into()];
            run.voi_lookahead = lookahead;
            testcost(&run).unwrap();
            let md = std::fs::read_to_string(out.path().join("testcost.md")).unwrap();
            assert!(md.contains(said), "{md}");
        }
    }

    /// A definition and a result line as written before CEGB existed (every learner of
    /// the family), read and written back byte for byte; CEGB's name is `cegb`.
    #[test]
    fn the_learners_are_written_as_before_and_cegb_as_its_name() {
        let definition = r#"{"datasets":["iris"],"learners":["C45","Id3","Idx","CsId3Batch","Eg2","Dtmc","Icet","Act","Cvt"],"mc":[500.0],"costs":["random"],"assignments":1,"price_range":[1.0,100.0],"price_draw":"uniform","selection_prices":"listed","icet_pruning":"costs","icet_search_objects":1000,"cvt_folds":5,"act_samples":5,"runs":1,"folds":3,"seed":1}"#;
        let def: Definition = serde_json::from_str(definition).unwrap();
        let before_voi: Vec<Learner> = Method::ALL
            .into_iter()
            .filter(|m| *m != Method::Voi)
            .map(Learner::Family)
            .collect();
        assert_eq!(def.learners, before_voi, "in the order written");
        assert_eq!(serde_json::to_string(&def).unwrap(), definition);
        let result = r#"{"id":0,"dataset":"iris","costs":"random","assignment":0,"run":0,"learner":"Eg2","by_mc":[{"mc":500.0,"total":60.95974067846856,"tests":37.62640734513521,"error_rate":0.04666666666666667,"standard":591.7064893819861,"auroc":0.9758}],"nodes":5.666666666666667,"learn_seconds":0.000412743,"classify_seconds":0.000017947}"#;
        let read: JobResult = serde_json::from_str(result).unwrap();
        assert_eq!(read.learner, Learner::Family(Method::Eg2));
        assert_eq!(
            (read.library.as_deref(), read.tradeoffs.as_ref()),
            (None, None)
        );
        assert_eq!(serde_json::to_string(&read).unwrap(), result);

        // CEGB beside them.
        let with = Definition {
            learners: vec![Learner::Family(Method::Eg2), Learner::Cegb],
            ..def
        };
        let text = serde_json::to_string(&with).unwrap();
        assert!(text.contains(r#""learners":["Eg2","cegb"]"#), "{text}");
        assert_eq!(serde_json::from_str::<Definition>(&text).unwrap(), with);
        // A name that is neither is refused, saying so.
        let err = serde_json::from_str::<Learner>(r#""Cegb""#)
            .unwrap_err()
            .to_string();
        assert!(err.contains("Cegb") && err.contains("cegb"), "{err}");
        // On the command line, the names the tables show.
        for l in Method::ALL
            .map(Learner::Family)
            .into_iter()
            .chain([Learner::Cegb])
        {
            assert_eq!(Learner::parse(l.name()).unwrap(), l);
        }
        let err = Learner::parse("lightgbm").unwrap_err().to_string();
        assert!(err.contains("lightgbm") && err.contains("cegb"), "{err}");
        assert!(Learner::Cegb.depends_on_mc());
        assert_eq!(Learner::Cegb.method(), None);
    }

    /// CEGB cannot be held to a budget per object, and `--python` is its worker's: both
    /// are refused before anything runs (no Python is needed to say so).
    #[test]
    fn cegb_refuses_a_budget_and_python_needs_cegb() {
        let dir = tempfile::tempdir().unwrap();
        let mut budget = args(dir.path(), 1);
        budget.learners = vec!["eg2".into(), "cegb".into()];
        budget.max_tests = Some(2);
        let err = testcost(&budget).unwrap_err().to_string();
        assert!(err.contains("cegb") && err.contains("--max-tests"), "{err}");
        let mut python = args(dir.path(), 1);
        python.python = Some(PathBuf::from("/no/such/python"));
        let err = testcost(&python).unwrap_err().to_string();
        assert!(err.contains("--python") && err.contains("cegb"), "{err}");
        assert!(
            std::fs::read_dir(dir.path()).unwrap().next().is_none(),
            "nothing written"
        );
    }

    #[test]
    fn seeds_depend_on_the_data_set_name_and_the_numbers_only() {
        assert_eq!(mix(1, "heart", &[1, 0]), mix(1, "heart", &[1, 0]));
        assert_ne!(mix(1, "heart", &[1, 0]), mix(1, "heart", &[1, 1]));
        assert_ne!(mix(1, "heart", &[1, 0]), mix(1, "iris", &[1, 0]));
        assert_ne!(mix(1, "heart", &[1, 0]), mix(2, "heart", &[1, 0]));
    }
}
