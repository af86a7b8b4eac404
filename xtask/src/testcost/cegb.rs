//! CEGB, LightGBM's cost-efficient gradient boosting, as the family's peer in the
//! benchmark: its jobs run through Python workers (`crates/csrl-py/python/csrl/cegb.py
//! --worker`, one JSON request and one JSON response per line), one started per worker
//! thread that runs CEGB's jobs and kept for the whole run.
//!
//! A job sees what the family's jobs see: the run's folds, the job's prices, the learner's
//! seed of each fold. For each fold the worker trains CEGB on the other folds (its
//! tradeoff chosen at each mc by cross-validation inside them) and answers, for each
//! held-out object, its class, its class probabilities and the features it uses, in the
//! order first met. What the object pays for them is counted here, with the family's
//! [`Basket`] (Turney's group discounts as for the trees); its misclassification cost
//! follows from its class, its AUROC from its probabilities.
//!
//! `cargo xtask budget` asks the same workers for CEGB's curve ([`sweep_job`]): per fold,
//! one sweep request trains CEGB at each tradeoff of a list on the other folds (no
//! cross-validation: the curve is the sweep) and answers the held-out objects as above,
//! once per tradeoff.

use std::io::{BufRead as _, BufReader, Write as _};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};
use std::sync::Mutex;

use anyhow::{Context, Result, bail, ensure};
use cslearn::testcost::{Basket, Column, Frame, MISSING, MisclassCosts, TestPrices};
use serde::{Deserialize, Serialize};

use super::{Definition, Job, JobResult, Learner, Score, job_parts, learner_seed, scores};

/// The worker's script, relative to the workspace root.
pub const SCRIPT: &str = "crates/csrl-py/python/csrl/cegb.py";

/// The worker's grid of `cegb_tradeoff` (its `TRADEOFFS`): 0, then `10^(-4 + k/4)` for
/// k = 0..20, from 10^-4 to 10 in quarter decades. `cargo xtask budget` sweeps CEGB over
/// it by default.
pub(crate) fn tradeoff_grid() -> Vec<f64> {
    std::iter::once(0.0)
        .chain((0..=20).map(|k| 10f64.powf(-4.0 + f64::from(k) / 4.0)))
        .collect()
}

/// One worker process.
struct Worker {
    child: Child,
    stdin: Option<ChildStdin>,
    stdout: BufReader<ChildStdout>,
    /// The command, for messages.
    shown: String,
}

impl Worker {
    fn start(python: &Path, script: &Path) -> Result<Worker> {
        let mut command = Command::new(python);
        command
            .arg(script)
            .arg("--worker")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit());
        let shown = format!("{command:?}");
        let mut child = command
            .spawn()
            .with_context(|| format!("cannot start CEGB's worker {shown}"))?;
        let stdin = child.stdin.take();
        let stdout = child
            .stdout
            .take()
            .context("CEGB's worker has no standard output")?;
        Ok(Worker {
            child,
            stdin,
            stdout: BufReader::new(stdout),
            shown,
        })
    }

    /// Send one request, read its response; a response `{"error": ...}` is an error.
    fn ask<T: for<'de> Deserialize<'de>>(&mut self, request: &impl Serialize) -> Result<T> {
        let line = serde_json::to_string(request)? + "\n";
        let stdin = self.stdin.as_mut().context("CEGB's worker is closed")?;
        stdin
            .write_all(line.as_bytes())
            .and_then(|()| stdin.flush())
            .with_context(|| {
                format!(
                    "CEGB's worker {} stopped reading (its error, if any, is above)",
                    self.shown
                )
            })?;
        let mut answer = String::new();
        let read = self
            .stdout
            .read_line(&mut answer)
            .with_context(|| format!("cannot read CEGB's worker {}", self.shown))?;
        if read == 0 {
            bail!(
                "CEGB's worker {} ended without answering (its error, if any, is above)",
                self.shown
            );
        }
        let value: serde_json::Value = serde_json::from_str(&answer).with_context(|| {
            format!(
                "CEGB's worker {} answered a line that is not JSON: {}",
                self.shown,
                answer.trim_end()
            )
        })?;
        if let Some(error) = value.get("error") {
            bail!("CEGB's worker refused the request: {error}");
        }
        serde_json::from_value(value).with_context(|| {
            format!(
                "CEGB's worker {} answered a response of another form",
                self.shown
            )
        })
    }
}

impl Drop for Worker {
    /// Closing its input ends the worker (it serves until the end of its input).
    fn drop(&mut self) {
        drop(self.stdin.take());
        let _ = self.child.wait();
    }
}

/// What the worker says of itself: LightGBM's version and the settings it runs with.
#[derive(Deserialize)]
struct Described {
    settings: serde_json::Value,
    description: String,
}

/// The worker's description (`describe` in `cegb.py`: LightGBM's version, the boosting's
/// settings, then `; cegb_tradeoff chosen by ...`) without what it says of the
/// cross-validation.
fn sweep_description(description: &str) -> &str {
    description
        .split_once("; cegb_tradeoff chosen")
        .map_or(description, |(boosting, _)| boosting)
}

/// CEGB's workers, one per worker thread that runs its jobs: a job takes an idle worker
/// (or starts one), and gives it back when it ends well. Dropping the pool ends them.
pub(crate) struct Peer {
    python: PathBuf,
    script: PathBuf,
    /// The settings every request carries (the worker's defaults, as it described them).
    settings: serde_json::Value,
    /// LightGBM's version and the settings, for the results and the report.
    description: String,
    idle: Mutex<Vec<Worker>>,
}

impl Peer {
    /// Start a first worker with `python` (default: the project's virtual environment,
    /// made or brought up to date) and ask it what it runs.
    pub fn start(python: Option<&Path>) -> Result<Peer> {
        let root = crate::python::root()?;
        let python = match python {
            Some(p) => p.to_path_buf(),
            None => {
                crate::python::venv(&root, &crate::python::target(&root))
                    .context("CEGB's worker needs the project's Python environment (or --python)")?
                    .python
            }
        };
        let script = root.join(SCRIPT);
        let mut first = Worker::start(&python, &script)?;
        let described: Described = first
            .ask(&serde_json::json!({"op": "describe"}))
            .context("CEGB's worker could not describe itself")?;
        crate::note(&format!("cegb: {}", described.description));
        Ok(Peer {
            python,
            script,
            settings: described.settings,
            description: described.description,
            idle: Mutex::new(vec![first]),
        })
    }

    /// LightGBM's version and the boosting's settings, one line, for a sweep: the worker's
    /// description without its cross-validation, which a sweep does not run.
    pub fn sweep_description(&self) -> &str {
        sweep_description(&self.description)
    }

    /// The worker's grid of tradeoffs, as it described its settings.
    pub fn grid(&self) -> Option<Vec<f64>> {
        serde_json::from_value(self.settings.get("tradeoffs")?.clone()).ok()
    }

    /// Answer one request on an idle worker (or a new one). A worker that failed is ended,
    /// not reused.
    fn ask<T: for<'de> Deserialize<'de>>(&self, request: &impl Serialize) -> Result<T> {
        let idle = self.idle.lock().ok().and_then(|mut idle| idle.pop());
        let mut worker = match idle {
            Some(w) => w,
            None => Worker::start(&self.python, &self.script)?,
        };
        match worker.ask(request) {
            Ok(answer) => {
                if let Ok(mut idle) = self.idle.lock() {
                    idle.push(worker);
                }
                Ok(answer)
            }
            Err(e) => {
                let _ = worker.child.kill();
                Err(e)
            }
        }
    }
}

/// One fit or sweep request: the training rows of a fold and its held-out rows, and
/// either the misclassification costs (`"op": "fit"`) or the tradeoffs (`"op": "sweep"`).
#[derive(Serialize)]
pub(crate) struct FitRequest<'a> {
    pub op: &'static str,
    pub train: Vec<&'a [Option<f64>]>,
    pub classes: Vec<u32>,
    pub class_count: usize,
    pub nominal: &'a [usize],
    pub prices: &'a [f64],
    pub test: Vec<&'a [Option<f64>]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mc: Option<&'a [f64]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tradeoffs: Option<&'a [f64]>,
    pub seed: u64,
    pub settings: &'a serde_json::Value,
    pub timing: bool,
}

/// The worker's answer to a fit request.
#[derive(Debug, Deserialize)]
pub(crate) struct FitResponse {
    /// One per mc of the request, in its order.
    pub by_mc: Vec<Answer>,
    pub learn_seconds: f64,
    pub classify_seconds: f64,
}

/// CEGB at one mc: the tradeoff chosen, the model's size, and its answer for each
/// held-out object.
#[derive(Debug, Deserialize)]
pub(crate) struct Answer {
    pub mc: f64,
    pub tradeoff: f64,
    /// Nodes over all the model's trees (splits and leaves).
    pub nodes: usize,
    pub predicted: Vec<usize>,
    pub probabilities: Vec<Vec<f64>>,
    /// The features each object uses, in the order first met.
    pub features: Vec<Vec<usize>>,
}

/// The worker's answer to a sweep request.
#[derive(Debug, Deserialize)]
pub(crate) struct SweepResponse {
    /// One per tradeoff of the request, in its order.
    pub by_tradeoff: Vec<Swept>,
    pub learn_seconds: f64,
    pub classify_seconds: f64,
}

/// CEGB trained at one tradeoff: the model's size and its answer for each held-out
/// object.
#[derive(Debug, Deserialize)]
pub(crate) struct Swept {
    pub tradeoff: f64,
    /// Nodes over all the model's trees (splits and leaves).
    pub nodes: usize,
    pub predicted: Vec<usize>,
    pub probabilities: Vec<Vec<f64>>,
    /// The features each object uses, in the order first met.
    pub features: Vec<Vec<usize>>,
}

/// One model's answers, whatever the request: its size, and per held-out object its
/// class, its class probabilities and its ordered features.
#[derive(Clone, Copy)]
struct Answered<'a> {
    nodes: usize,
    predicted: &'a [usize],
    probabilities: &'a [Vec<f64>],
    features: &'a [Vec<usize>],
}

impl Answer {
    fn view(&self) -> Answered<'_> {
        Answered {
            nodes: self.nodes,
            predicted: &self.predicted,
            probabilities: &self.probabilities,
            features: &self.features,
        }
    }
}

impl Swept {
    fn view(&self) -> Answered<'_> {
        Answered {
            nodes: self.nodes,
            predicted: &self.predicted,
            probabilities: &self.probabilities,
            features: &self.features,
        }
    }
}

/// What every request of one job on `frame` shares: each object's cells as the worker
/// reads them, the nominal features, and the price of each feature that LightGBM's lazy
/// penalty takes (its listed, full price).
struct JobData<'a> {
    frame: &'a Frame,
    cells: Vec<Vec<Option<f64>>>,
    nominal: Vec<usize>,
    listed: Vec<f64>,
}

impl<'a> JobData<'a> {
    fn new(frame: &'a Frame, prices: &TestPrices) -> JobData<'a> {
        JobData {
            frame,
            cells: rows(frame),
            nominal: (0..frame.feature_count())
                .filter(|&f| !frame.column(f).is_numeric())
                .collect(),
            listed: (0..prices.len()).map(|t| prices.test(t).full).collect(),
        }
    }

    /// The request `op` to learn from the objects `train` and answer the objects `test`:
    /// at the misclassification costs `mc` (a fit) or at each of `tradeoffs` (a sweep).
    #[expect(
        clippy::too_many_arguments,
        reason = "the request's own fields: what is asked, on which objects, at what"
    )]
    fn request<'r>(
        &'r self,
        op: &'static str,
        train: &[usize],
        test: &[usize],
        mc: Option<&'r [f64]>,
        tradeoffs: Option<&'r [f64]>,
        seed: u64,
        settings: &'r serde_json::Value,
    ) -> FitRequest<'r> {
        FitRequest {
            op,
            train: train.iter().map(|&r| self.cells[r].as_slice()).collect(),
            classes: train.iter().map(|&r| self.frame.class(r)).collect(),
            class_count: self.frame.class_count(),
            nominal: &self.nominal,
            prices: &self.listed,
            test: test.iter().map(|&r| self.cells[r].as_slice()).collect(),
            mc,
            tradeoffs,
            seed,
            settings,
            timing: true,
        }
    }
}

/// Where a request was made, for its errors: `what` (CEGB, or its sweep) on data set
/// `name`, the job's prices, run and fold `f`.
fn place(what: &str, name: &str, job: Job, f: usize) -> String {
    format!(
        "{what} on `{name}`, {} prices {}, run {}, fold {f}",
        job.costs.name(),
        job.assignment,
        job.run
    )
}

/// Each object's cells as the worker reads them: a nominal value's code, a number, or
/// `None` where the cell is missing.
fn rows(frame: &Frame) -> Vec<Vec<Option<f64>>> {
    (0..frame.len())
        .map(|r| {
            (0..frame.feature_count())
                .map(|f| match frame.column(f) {
                    Column::Nominal { codes, .. } => {
                        (codes[r] != MISSING).then(|| f64::from(codes[r]))
                    }
                    Column::Numeric(x) => (!x[r].is_nan()).then_some(x[r]),
                })
                .collect()
        })
        .collect()
}

/// What an object pays for the features it uses, bought in the order given: each at its
/// price when it comes, after the ones before it (Turney's group discounts: the first of
/// a group in full, later ones at their discount), a feature met again for nothing.
pub(crate) fn ordered_test_cost(prices: &TestPrices, features: &[usize]) -> Result<f64> {
    let mut basket = Basket::new(prices);
    for &f in features {
        ensure!(
            f < prices.len(),
            "feature {f} is not a feature of the data set ({} features)",
            prices.len()
        );
        basket.buy(prices, f);
    }
    Ok(basket.spent())
}

/// Running sums of a job over its held-out objects, per mc (as the family's jobs keep
/// them): total cost, test cost and errors, and each object's class probabilities.
pub(crate) struct Tally {
    pub sums: Vec<(f64, f64, usize)>,
    pub probabilities: Vec<Vec<Vec<f64>>>,
    pub actual: Vec<usize>,
    /// Nodes summed over the models (one per fold and mc).
    pub nodes: usize,
    pub models: usize,
    /// The tradeoff chosen, per mc, one per fold.
    pub tradeoffs: Vec<Vec<f64>>,
}

impl Tally {
    pub fn new(mcs: usize) -> Tally {
        Tally {
            sums: vec![(0.0, 0.0, 0); mcs],
            probabilities: vec![Vec::new(); mcs],
            actual: Vec::new(),
            nodes: 0,
            models: 0,
            tradeoffs: vec![Vec::new(); mcs],
        }
    }

    /// Add one fold's answers for its held-out objects `test` (checked against the
    /// request: one answer per mc and per object, classes and features of the data set).
    pub fn add(
        &mut self,
        frame: &Frame,
        prices: &TestPrices,
        mcs: &[(f64, MisclassCosts)],
        test: &[usize],
        response: &FitResponse,
    ) -> Result<()> {
        ensure!(
            response.by_mc.len() == mcs.len(),
            "{} answers for {} misclassification costs",
            response.by_mc.len(),
            mcs.len()
        );
        for (m, ((value, mc), answer)) in mcs.iter().zip(&response.by_mc).enumerate() {
            ensure!(
                answer.mc == *value,
                "an answer for mc {} where mc {value} was asked",
                answer.mc
            );
            self.tradeoffs[m].push(answer.tradeoff);
            self.add_model(m, frame, prices, mc, test, answer.view())?;
        }
        Ok(())
    }

    /// Add one fold's answers of a sweep for its held-out objects `test`, point `m` of the
    /// sweep being tradeoff `tradeoffs[m]`, every point scored at `mc` (checked against
    /// the request as [`Tally::add`] checks, each answer's tradeoff the one asked for, to
    /// the bit).
    pub fn add_sweep(
        &mut self,
        frame: &Frame,
        prices: &TestPrices,
        mc: &MisclassCosts,
        tradeoffs: &[f64],
        test: &[usize],
        response: &SweepResponse,
    ) -> Result<()> {
        ensure!(
            response.by_tradeoff.len() == tradeoffs.len(),
            "{} answers for {} tradeoffs",
            response.by_tradeoff.len(),
            tradeoffs.len()
        );
        for (m, (&t, answer)) in tradeoffs.iter().zip(&response.by_tradeoff).enumerate() {
            ensure!(
                answer.tradeoff.to_bits() == t.to_bits(),
                "an answer for tradeoff {} where tradeoff {t} was asked",
                answer.tradeoff
            );
            self.add_model(m, frame, prices, mc, test, answer.view())?;
        }
        Ok(())
    }

    /// Add one model's answers for the held-out objects of `test` to the sums of point
    /// `m`, each object scored at `mc`.
    fn add_model(
        &mut self,
        m: usize,
        frame: &Frame,
        prices: &TestPrices,
        mc: &MisclassCosts,
        test: &[usize],
        Answered {
            nodes,
            predicted,
            probabilities,
            features,
        }: Answered<'_>,
    ) -> Result<()> {
        let k = frame.class_count();
        ensure!(
            predicted.len() == test.len()
                && probabilities.len() == test.len()
                && features.len() == test.len(),
            "answers for other than the {} held-out objects",
            test.len()
        );
        self.nodes += nodes;
        self.models += 1;
        for (i, &r) in test.iter().enumerate() {
            let class = predicted[i];
            let p = &probabilities[i];
            ensure!(class < k, "class {class} of a data set of {k} classes");
            ensure!(
                p.len() == k && p.iter().all(|x| x.is_finite() && *x >= 0.0),
                "probabilities {p:?}: expected {k}, finite and not negative"
            );
            let tests = ordered_test_cost(prices, &features[i])?;
            let actual = frame.class(r) as usize;
            self.sums[m].0 += tests + mc.cost(class, actual);
            self.sums[m].1 += tests;
            self.sums[m].2 += usize::from(class != actual);
            self.probabilities[m].push(p.clone());
            if m == 0 {
                self.actual.push(actual);
            }
        }
        Ok(())
    }
}

/// One job of CEGB: the run's folds, each trained and answered by a worker.
pub(crate) fn run_job(
    def: &Definition,
    id: u64,
    job: Job,
    name: &str,
    frame: &Frame,
    prices: &TestPrices,
    peer: &Peer,
) -> Result<JobResult> {
    let k = frame.class_count();
    let mcs: Vec<(f64, MisclassCosts)> = def
        .mc
        .iter()
        .map(|&m| Ok((m, MisclassCosts::uniform(k, m)?)))
        .collect::<Result<_>>()?;
    let data = JobData::new(frame, prices);
    let mut tally = Tally::new(mcs.len());
    let (mut learn, mut classify) = (0.0, 0.0);
    for (f, train, test) in job_parts(def, name, job, frame) {
        let seed = learner_seed(def, name, job, f);
        let request = data.request(
            "fit",
            &train,
            &test,
            Some(&def.mc),
            None,
            seed,
            &peer.settings,
        );
        let place = || place("CEGB", name, job, f);
        let response: FitResponse = peer.ask(&request).with_context(place)?;
        tally
            .add(frame, prices, &mcs, &test, &response)
            .with_context(place)?;
        learn += response.learn_seconds;
        classify += response.classify_seconds;
    }
    let costs: Vec<MisclassCosts> = mcs.into_iter().map(|(_, c)| c).collect();
    Ok(JobResult {
        id,
        dataset: name.to_string(),
        costs: job.costs,
        assignment: job.assignment,
        run: job.run,
        learner: Learner::Cegb,
        by_mc: scores(
            &def.mc,
            frame,
            prices,
            &costs,
            &tally.sums,
            &tally.probabilities,
            &tally.actual,
        ),
        nodes: tally.nodes as f64 / tally.models.max(1) as f64,
        learn_seconds: learn,
        classify_seconds: classify,
        library: Some(peer.description.clone()),
        tradeoffs: Some(tally.tradeoffs),
    })
}

/// What one run of CEGB's curve measured.
#[derive(Debug)]
pub(crate) struct Sweep {
    /// One score per tradeoff, in the order asked, each at the one misclassification cost
    /// asked for.
    pub points: Vec<Score>,
    /// Mean nodes per model (one per fold and tradeoff).
    pub nodes: f64,
    /// The worker's wall time to train every fold's models.
    pub learn_seconds: f64,
    /// The worker's wall time to answer every held-out object.
    pub classify_seconds: f64,
}

/// One job of CEGB's curve on `frame` under `prices`: the run's folds, each trained at
/// every tradeoff of `tradeoffs` by a worker (one sweep request per fold), every point
/// scored at the misclassification cost `mc`.
pub(crate) fn sweep_job(
    def: &Definition,
    job: Job,
    name: &str,
    (frame, prices): (&Frame, &TestPrices),
    (tradeoffs, mc): (&[f64], f64),
    peer: &Peer,
) -> Result<Sweep> {
    sweep_folds(
        def,
        job,
        name,
        (frame, prices),
        (tradeoffs, mc),
        &peer.settings,
        |request| peer.ask(request),
    )
}

/// [`sweep_job`] with the worker given as `ask`, which answers one fold's request: the
/// folds and seeds of the job, the answers priced with [`Basket`] and scored.
pub(crate) fn sweep_folds(
    def: &Definition,
    job: Job,
    name: &str,
    (frame, prices): (&Frame, &TestPrices),
    (tradeoffs, mc): (&[f64], f64),
    settings: &serde_json::Value,
    mut ask: impl FnMut(&FitRequest<'_>) -> Result<SweepResponse>,
) -> Result<Sweep> {
    let costs = MisclassCosts::uniform(frame.class_count(), mc)?;
    let data = JobData::new(frame, prices);
    let mut tally = Tally::new(tradeoffs.len());
    let (mut learn, mut classify) = (0.0, 0.0);
    for (f, train, test) in job_parts(def, name, job, frame) {
        let seed = learner_seed(def, name, job, f);
        let request = data.request(
            "sweep",
            &train,
            &test,
            None,
            Some(tradeoffs),
            seed,
            settings,
        );
        let place = || place("CEGB's sweep", name, job, f);
        let response = ask(&request).with_context(place)?;
        tally
            .add_sweep(frame, prices, &costs, tradeoffs, &test, &response)
            .with_context(place)?;
        learn += response.learn_seconds;
        classify += response.classify_seconds;
    }
    let mcs = vec![costs; tradeoffs.len()];
    Ok(Sweep {
        points: scores(
            &vec![mc; tradeoffs.len()],
            frame,
            prices,
            &mcs,
            &tally.sums,
            &tally.probabilities,
            &tally.actual,
        ),
        nodes: tally.nodes as f64 / tally.models.max(1) as f64,
        learn_seconds: learn,
        classify_seconds: classify,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use cslearn::testcost::TestPrice;

    /// Two tests of group A (10 in full, 8 after another of A) and one alone (5).
    fn grouped() -> TestPrices {
        let a = |full, discount| TestPrice {
            full,
            discount,
            group: Some(0),
            delayed: false,
        };
        let alone = TestPrice {
            full: 5.0,
            discount: 5.0,
            group: None,
            delayed: false,
        };
        TestPrices::new(vec![a(10.0, 8.0), alone, a(6.0, 2.0)], vec!["A".into()]).unwrap()
    }

    #[test]
    fn an_ordered_list_pays_each_feature_once_with_its_group_discount() {
        let prices = grouped();
        // The first of group A in full, the second at its discount, whatever the order.
        assert_eq!(ordered_test_cost(&prices, &[0, 2]).unwrap(), 10.0 + 2.0);
        assert_eq!(ordered_test_cost(&prices, &[2, 0]).unwrap(), 6.0 + 8.0);
        // The lone test at its price wherever it comes; a test met again is free.
        assert_eq!(
            ordered_test_cost(&prices, &[1, 2, 0, 2]).unwrap(),
            5.0 + 6.0 + 8.0
        );
        assert_eq!(ordered_test_cost(&prices, &[]).unwrap(), 0.0);
        // Flat prices: the sum of the distinct features' prices.
        let flat = TestPrices::flat(&[3.0, 4.0]).unwrap();
        assert_eq!(ordered_test_cost(&flat, &[1, 0, 1]).unwrap(), 7.0);
        let err = ordered_test_cost(&flat, &[2]).unwrap_err().to_string();
        assert!(
            err.contains("feature 2") && err.contains("2 features"),
            "{err}"
        );
    }

    fn frame() -> Frame {
        Frame::new(
            vec!["a".into(), "b".into(), "c".into()],
            vec![
                Column::Numeric(vec![1.0, f64::NAN, 3.0, 4.0]),
                Column::Nominal {
                    values: vec!["x".into(), "y".into()],
                    codes: vec![0, 1, MISSING, 1],
                },
                Column::Numeric(vec![0.5; 4]),
            ],
            vec![0, 1, 1, 0],
            vec!["no".into(), "yes".into()],
        )
        .unwrap()
    }

    #[test]
    fn the_worker_reads_codes_numbers_and_missing_cells() {
        let cells = rows(&frame());
        assert_eq!(cells[0], [Some(1.0), Some(0.0), Some(0.5)]);
        assert_eq!(cells[1], [None, Some(1.0), Some(0.5)]);
        assert_eq!(cells[2], [Some(3.0), None, Some(0.5)]);
    }

    fn answer(mc: f64, predicted: Vec<usize>, features: Vec<Vec<usize>>) -> Answer {
        let probabilities = predicted
            .iter()
            .map(|&c| {
                if c == 0 {
                    vec![0.75, 0.25]
                } else {
                    vec![0.25, 0.75]
                }
            })
            .collect();
        Answer {
            mc,
            tradeoff: 0.01,
            nodes: 7,
            predicted,
            probabilities,
            features,
        }
    }

    /// A fold's answers scored: test cost from each object's ordered features with the
    /// group discount, misclassification cost from its class, at each mc.
    #[test]
    fn a_folds_answers_are_scored_as_the_trees_are() {
        let frame = frame();
        let prices = grouped();
        let mcs: Vec<(f64, MisclassCosts)> = [100.0, 500.0]
            .iter()
            .map(|&m| (m, MisclassCosts::uniform(2, m).unwrap()))
            .collect();
        // Objects 1 (class 1) and 3 (class 0) held out.
        let response = FitResponse {
            by_mc: vec![
                answer(100.0, vec![1, 1], vec![vec![2, 0], vec![1]]),
                answer(500.0, vec![1, 0], vec![vec![0, 2, 1], vec![]]),
            ],
            learn_seconds: 0.5,
            classify_seconds: 0.1,
        };
        let mut tally = Tally::new(2);
        tally
            .add(&frame, &prices, &mcs, &[1, 3], &response)
            .unwrap();
        // mc 100: object 1 pays 6 + 8 and is right; object 3 pays 5 and is wrong.
        assert_eq!(tally.sums[0], (14.0 + 5.0 + 100.0, 19.0, 1));
        // mc 500: object 1 pays 10 + 2 + 5, right; object 3 nothing, right.
        assert_eq!(tally.sums[1], (17.0, 17.0, 0));
        assert_eq!(tally.actual, [1, 0]);
        assert_eq!(tally.probabilities[1][1], [0.75, 0.25]);
        assert_eq!((tally.nodes, tally.models), (14, 2));
        assert_eq!(tally.tradeoffs, [[0.01], [0.01]]);

        // Answers that do not fit the request are refused, naming what is wrong.
        let refuse = |response: FitResponse| {
            let mut tally = Tally::new(2);
            tally
                .add(&frame, &prices, &mcs, &[1, 3], &response)
                .unwrap_err()
                .to_string()
        };
        let one = |a: Answer, b: Answer| FitResponse {
            by_mc: vec![a, b],
            learn_seconds: 0.0,
            classify_seconds: 0.0,
        };
        let good = || answer(500.0, vec![0, 0], vec![vec![], vec![]]);
        let err = refuse(one(answer(100.0, vec![2, 0], vec![vec![], vec![]]), good()));
        assert!(err.contains("class 2"), "{err}");
        let err = refuse(one(answer(100.0, vec![0], vec![vec![]]), good()));
        assert!(err.contains("2 held-out objects"), "{err}");
        let err = refuse(one(
            answer(100.0, vec![0, 0], vec![vec![3], vec![]]),
            good(),
        ));
        assert!(err.contains("feature 3"), "{err}");
        let err = refuse(one(good(), good()));
        assert!(err.contains("mc 500 where mc 100"), "{err}");
        let mut nan = answer(100.0, vec![0, 0], vec![vec![], vec![]]);
        nan.probabilities[0][1] = f64::NAN;
        let err = refuse(one(nan, good()));
        assert!(err.contains("finite"), "{err}");
    }
}
