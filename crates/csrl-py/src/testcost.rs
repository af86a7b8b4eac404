//! `csrl._csrl.TestCostTree`: a tree of the test-cost family (`cslearn::testcost`: ID3,
//! C4.5, IDX, batch CS-ID3, EG2, DTMC, ICET) over numeric and nominal columns, for the
//! scikit-learn estimators of `csrl.sklearn` (which read the data, code nominal values
//! and classes, and check the parameters with scikit-learn's messages).
//!
//! A column crosses the boundary as `(None, cells)` for a numeric feature (floats, NaN
//! where missing) or `(values, codes)` for a nominal one (value names, and one code per
//! object: an index into `values`, -1 where missing, `len(values)` for a value the tree
//! never saw). The fitted tree keeps its prices, column kinds and names, and pickles as
//! plain Python values (`__reduce__`).

use cslearn::testcost::{
    ActParams, Budget, Column, CostTree, CvtChoice, CvtParams, FamilyParams, FeatureShape, Frame,
    IcetGenome, IcetParams, MISSING, Method, MisclassCosts, Pruning, SelectionPrices, Split, Stop,
    TestPrice, TestPrices, VoiParams,
};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyType};
use serde_json::{Value, json};

use crate::{DataError, message};

/// One column as Python hands it over: `(None, cells)` or `(values, codes)`.
type PyColumn<'py> = (Option<Vec<String>>, Bound<'py, PyAny>);

/// A feature's kind, as the tree was grown on it: numeric, or nominal with these values.
#[derive(Clone, Debug, PartialEq)]
enum Kind {
    Numeric,
    Nominal(Vec<String>),
}

fn data_error(e: &cslearn::Error) -> PyErr {
    DataError::new_err(message(e))
}

/// The budget of `max_test_cost` and `max_tests`; a price that is negative or not finite
/// is refused, naming it.
fn budget(max_test_cost: Option<f64>, max_tests: Option<usize>) -> PyResult<Budget> {
    Budget::new(max_test_cost, max_tests).map_err(|e| data_error(&e))
}

/// The columns as a frame (classes given for training, all 0 for classifying), checked
/// against `kinds` when the tree already has them.
fn frame(
    names: &[String],
    columns: Vec<PyColumn<'_>>,
    classes: Vec<u32>,
    class_names: &[String],
    kinds: Option<&[Kind]>,
) -> PyResult<(Frame, Vec<Kind>)> {
    if columns.len() != names.len() {
        return Err(DataError::new_err(format!(
            "{} columns for {} feature names",
            columns.len(),
            names.len()
        )));
    }
    let mut out = Vec::with_capacity(columns.len());
    let mut out_kinds = Vec::with_capacity(columns.len());
    for (j, (values, cells)) in columns.into_iter().enumerate() {
        let name = &names[j];
        let known = kinds.map(|k| &k[j]);
        match values {
            None => {
                if let Some(Kind::Nominal(_)) = known {
                    return Err(DataError::new_err(format!(
                        "column `{name}` is numeric, but the tree was grown on it as nominal"
                    )));
                }
                let x: Vec<f64> = cells.extract().map_err(|_| {
                    DataError::new_err(format!("column `{name}`: numeric cells must be floats"))
                })?;
                out.push(Column::Numeric(x));
                out_kinds.push(Kind::Numeric);
            }
            Some(mut values) => {
                if let Some(Kind::Numeric) = known {
                    return Err(DataError::new_err(format!(
                        "column `{name}` is nominal, but the tree was grown on it as numeric"
                    )));
                }
                let raw: Vec<i64> = cells.extract().map_err(|_| {
                    DataError::new_err(format!("column `{name}`: nominal codes must be ints"))
                })?;
                let kind = Kind::Nominal(values.clone());
                // A value the tree never saw (code `len(values)`) gets a place of its own,
                // which no branch has: the tree sends it down its largest branch.
                let seen = values.len() as i64;
                let mut unseen = false;
                let codes = raw
                    .iter()
                    .map(|&c| match c {
                        -1 => Ok(MISSING),
                        c if (0..seen).contains(&c) => Ok(c as u32),
                        c if c == seen && kinds.is_some() => {
                            unseen = true;
                            Ok(c as u32)
                        }
                        c => Err(DataError::new_err(format!(
                            "column `{name}`: code {c} is not -1 (missing) or the index of one of its {seen} values"
                        ))),
                    })
                    .collect::<PyResult<Vec<u32>>>()?;
                if let Some(Kind::Nominal(fitted)) = known
                    && *fitted != values
                {
                    return Err(DataError::new_err(format!(
                        "column `{name}`: the values differ from those the tree was grown on"
                    )));
                }
                if unseen {
                    values.push("(unseen)".to_string());
                }
                out.push(Column::Nominal { values, codes });
                out_kinds.push(kind);
            }
        }
    }
    let frame = Frame::new(names.to_vec(), out, classes, class_names.to_vec())
        .map_err(|e| data_error(&e))?;
    Ok((frame, out_kinds))
}

/// A fitted tree of the test-cost family with the prices it pays, the kinds of its
/// columns, and for ICET the individual it was grown from.
#[pyclass(module = "csrl._csrl", frozen)]
pub struct TestCostTree {
    learner: Method,
    names: Vec<String>,
    kinds: Vec<Kind>,
    class_names: Vec<String>,
    prices: TestPrices,
    tree: CostTree,
    genome: Option<IcetGenome>,
    cvt: Option<CvtChoice>,
}

impl TestCostTree {
    /// The objects to classify as a frame over the tree's features (columns as in `fit`),
    /// or `None` when there are none.
    fn objects(&self, columns: Vec<PyColumn<'_>>) -> PyResult<Option<Frame>> {
        let n = match columns.first() {
            None => 0,
            Some((_, cells)) => cells.len()?,
        };
        if columns.len() != self.names.len() {
            return Err(DataError::new_err(format!(
                "{} columns, but the tree was grown on {} features",
                columns.len(),
                self.names.len()
            )));
        }
        if n == 0 {
            return Ok(None);
        }
        let (frame, _) = frame(
            &self.names,
            columns,
            vec![0; n],
            &self.class_names,
            Some(&self.kinds),
        )?;
        Ok(Some(frame))
    }

    fn to_value(&self) -> PyResult<Value> {
        let ser = |e: serde_json::Error| DataError::new_err(format!("cannot save the tree: {e}"));
        let kinds: Vec<Value> = self
            .kinds
            .iter()
            .map(|k| match k {
                Kind::Numeric => Value::Null,
                Kind::Nominal(values) => json!(values),
            })
            .collect();
        Ok(json!({
            "learner": self.learner.name(),
            "names": self.names,
            "kinds": kinds,
            "class_names": self.class_names,
            "prices": serde_json::to_value(&self.prices).map_err(ser)?,
            "tree": serde_json::to_value(&self.tree).map_err(ser)?,
            "genome": serde_json::to_value(&self.genome).map_err(ser)?,
            "cvt": serde_json::to_value(self.cvt).map_err(ser)?,
        }))
    }

    fn from_value(v: &Value) -> Result<TestCostTree, String> {
        let field = |key: &str| v.get(key).cloned().ok_or(format!("no `{key}`"));
        let learner: String =
            serde_json::from_value(field("learner")?).map_err(|e| e.to_string())?;
        let learner = Method::parse(&learner).map_err(|e| e.to_string())?;
        let kinds: Vec<Option<Vec<String>>> =
            serde_json::from_value(field("kinds")?).map_err(|e| e.to_string())?;
        let tree = TestCostTree {
            learner,
            names: serde_json::from_value(field("names")?).map_err(|e| e.to_string())?,
            kinds: kinds
                .into_iter()
                .map(|k| k.map_or(Kind::Numeric, Kind::Nominal))
                .collect(),
            class_names: serde_json::from_value(field("class_names")?)
                .map_err(|e| e.to_string())?,
            prices: serde_json::from_value(field("prices")?).map_err(|e| e.to_string())?,
            tree: serde_json::from_value(field("tree")?).map_err(|e| e.to_string())?,
            genome: serde_json::from_value(field("genome")?).map_err(|e| e.to_string())?,
            // A tree saved before CVT existed has no choice to report.
            cvt: match v.get("cvt") {
                Some(c) => serde_json::from_value(c.clone()).map_err(|e| e.to_string())?,
                None => None,
            },
        };
        if tree.kinds.len() != tree.names.len() || tree.prices.len() != tree.names.len() {
            return Err("the features, their kinds and their prices differ in number".into());
        }
        // Checked as a model file is: a tampered state is refused here, never met later
        // as an index out of range or a walk without end.
        let prices = tree.prices.clone().checked().map_err(|e| e.to_string())?;
        let shapes: Vec<FeatureShape<'_>> = tree
            .names
            .iter()
            .zip(&tree.kinds)
            .map(|(name, kind)| FeatureShape {
                name,
                values: match kind {
                    Kind::Numeric => None,
                    Kind::Nominal(values) => Some(values.len()),
                },
            })
            .collect();
        tree.tree
            .check(&shapes, tree.class_names.len())
            .map_err(|e| e.to_string())?;
        Ok(TestCostTree { prices, ..tree })
    }
}

/// How long the calling thread waits for a fit before it asks Python, again, whether a
/// signal (Ctrl-C) came.
const SIGNAL_CHECK: std::time::Duration = std::time::Duration::from_millis(50);

/// `fit` run on a thread of its own, without the GIL, while the calling thread (Python's
/// main thread, where signal handlers run) waits for it and, every [`SIGNAL_CHECK`], takes
/// the GIL to run Python's signal handlers: when one raises (`KeyboardInterrupt` on
/// Ctrl-C), the fit's [`Stop`] is requested, the fit ends at once, and the exception is
/// raised in its place.
fn until_interrupted<T: Send>(
    py: Python<'_>,
    fit: impl FnOnce(&Stop) -> Result<T, cslearn::Error> + Send,
) -> PyResult<T> {
    use std::sync::mpsc::{RecvTimeoutError, channel};
    let stop = Stop::default();
    let (result, raised) = py.detach(|| {
        std::thread::scope(|scope| {
            let (done, finished) = channel::<()>();
            let stop = &stop;
            let worker = scope.spawn(move || {
                let result = fit(stop);
                // The receiver may be gone only if the waiting thread was: nothing to tell.
                let _ = done.send(());
                result
            });
            let mut raised = None;
            while let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(SIGNAL_CHECK) {
                if let Err(e) = Python::attach(|py| py.check_signals()) {
                    raised = Some(e);
                    stop.request();
                    break;
                }
            }
            let result = worker
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            (result, raised)
        })
    });
    if let Some(e) = raised {
        return Err(e);
    }
    result.map_err(|e| data_error(&e))
}

fn check_unit(value: f64, what: &str, low_open: bool, high_open: bool) -> PyResult<()> {
    let low_ok = if low_open { value > 0.0 } else { value >= 0.0 };
    let high_ok = if high_open { value < 1.0 } else { value <= 1.0 };
    if value.is_finite() && low_ok && high_ok {
        Ok(())
    } else {
        let (l, h) = (
            if low_open { "(" } else { "[" },
            if high_open { ")" } else { "]" },
        );
        Err(DataError::new_err(format!(
            "{what} must be in {l}0, 1{h}, found {value}"
        )))
    }
}

#[pymethods]
impl TestCostTree {
    /// Grow a tree with `learner` ("id3-batch", "c45", "idx", "cs-id3-batch", "eg2", "dtmc",
    /// "icet", "act", "cvt", "voi") on every object. `prices` is `(full, discount, group)` per feature (group
    /// an index into `group_names`, or `None`); `misclassification[actual][predicted]`
    /// the cost of each answer; `confidence` C4.5's pruning confidence, `w` EG2's weight
    /// of the price; `seed`, `population` and `generations` ICET's search (`seed` also
    /// ACT's samples); `samples` ACT's trees sampled per branch; `selection_prices` the
    /// price selection functions see ("path", "listed" or "listed-once"); `icet_pruning` how ICET
    /// prunes ("errors" or "costs") and `search_objects` the most objects its search
    /// uses; `folds` CVT's cross-validation (`seed` also its folds) and `cvt_samples` its
    /// lookahead grower's samples per branch (0: no lookahead grower); `max_test_cost` and
    /// `max_tests` a budget per object (`Budget`), within which the greedy learners grow
    /// (`None`: no limit); `voi_lookahead`, `voi_confidence` and `voi_m` VOI's settings
    /// (`VoiParams::from_options`; `None`: the library's). The GIL is released while it grows, and Ctrl-C stops it
    /// (`KeyboardInterrupt`, checked every 50 ms).
    #[staticmethod]
    #[pyo3(signature = (learner, names, columns, classes, class_names, prices, group_names, misclassification, confidence=0.25, w=1.0, seed=0, population=50, generations=20, samples=5, selection_prices="path", icet_pruning="errors", search_objects=400, folds=5, max_test_cost=None, max_tests=None, threads=1, voi_lookahead=None, voi_confidence=None, voi_m=None, cvt_samples=5))]
    #[expect(
        clippy::too_many_arguments,
        reason = "one argument per setting, all keywords from Python"
    )]
    fn fit(
        py: Python<'_>,
        learner: &str,
        names: Vec<String>,
        columns: Vec<PyColumn<'_>>,
        classes: Vec<u32>,
        class_names: Vec<String>,
        prices: Vec<(f64, f64, Option<u32>)>,
        group_names: Vec<String>,
        misclassification: Vec<Vec<f64>>,
        confidence: f64,
        w: f64,
        seed: u64,
        population: usize,
        generations: usize,
        samples: usize,
        selection_prices: &str,
        icet_pruning: &str,
        search_objects: usize,
        folds: usize,
        max_test_cost: Option<f64>,
        max_tests: Option<usize>,
        threads: usize,
        voi_lookahead: Option<usize>,
        voi_confidence: Option<f64>,
        voi_m: Option<f64>,
        cvt_samples: usize,
    ) -> PyResult<TestCostTree> {
        let budget = budget(max_test_cost, max_tests)?;
        let method = Method::parse(learner).map_err(|e| data_error(&e))?;
        if prices.len() != names.len() {
            return Err(DataError::new_err(format!(
                "{} prices for {} features",
                prices.len(),
                names.len()
            )));
        }
        check_unit(confidence, "confidence", true, true)?;
        check_unit(w, "w", false, false)?;
        let selection_prices = SelectionPrices::parse(selection_prices)
            .map_err(|e| DataError::new_err(format!("selection_prices: {}", message(&e))))?;
        let icet_pruning = Pruning::parse(icet_pruning)
            .map_err(|e| DataError::new_err(format!("icet_pruning: {}", message(&e))))?;
        let act = ActParams::with_samples(samples)
            .map_err(|e| data_error(&e))?
            .with_threads(threads);
        let voi = VoiParams::from_options(voi_lookahead, voi_confidence, voi_m)
            .map_err(|e| data_error(&e))?;
        let cvt = CvtParams::with_folds(folds)
            .and_then(|p| p.with_samples(cvt_samples))
            .map_err(|e| data_error(&e))?
            .with_threads(threads);
        let prices = TestPrices::new(
            prices
                .into_iter()
                .map(|(full, discount, group)| TestPrice {
                    full,
                    discount,
                    group,
                    delayed: false,
                })
                .collect(),
            group_names,
        )
        .map_err(|e| data_error(&e))?;
        let mc = MisclassCosts::from_rows(&misclassification).map_err(|e| data_error(&e))?;
        if mc.classes() != class_names.len() {
            return Err(DataError::new_err(format!(
                "a {0}x{0} misclassification matrix for {1} classes",
                mc.classes(),
                class_names.len()
            )));
        }
        let (frame, kinds) = frame(&names, columns, classes, &class_names, None)?;
        let params = FamilyParams {
            confidence,
            eg2_w: w,
            icet: IcetParams {
                population,
                generations,
                pruning: icet_pruning,
                search_objects,
                ..IcetParams::default()
            },
            selection_prices,
            act,
            cvt,
            voi,
            budget,
            // The lookahead's limit is the library's: `MAX_LOOKAHEAD_FEATURES`.
            ..FamilyParams::default()
        };
        let rows: Vec<usize> = (0..frame.len()).collect();
        mc.check_totals(&prices, rows.len())
            .map_err(|e| data_error(&e))?;
        // Counts are judged against the data before anything is allocated.
        params
            .check(method, &frame, rows.len())
            .map_err(|e| data_error(&e))?;
        let fitted = until_interrupted(py, |stop| {
            cslearn::testcost::fit_until(method, &frame, &rows, &prices, &mc, &params, seed, stop)
        })?;
        Ok(TestCostTree {
            learner: method,
            names,
            kinds,
            class_names,
            prices,
            tree: fitted.tree,
            genome: fitted.genome,
            cvt: fitted.cvt,
        })
    }

    /// Classify the objects (columns as in `fit`; a nominal column's values must be
    /// those of `fit`): the class code of each, the price of the tests it paid for,
    /// those tests (feature indices, in the order done) and the probability of each
    /// class (`Classification::probabilities`: the Laplace-smoothed class weights of the
    /// leaf, or mix of leaves, that answered).
    /// With `max_test_cost` or `max_tests`, each object is held to that budget
    /// (`CostTree::classify_within`): a test that would take it past the budget is not
    /// bought, and the node that asked for it answers.
    #[expect(
        clippy::type_complexity,
        reason = "the tuple Python receives: classes, costs, tests, probabilities"
    )]
    #[pyo3(signature = (columns, max_test_cost=None, max_tests=None))]
    fn classify(
        &self,
        py: Python<'_>,
        columns: Vec<PyColumn<'_>>,
        max_test_cost: Option<f64>,
        max_tests: Option<usize>,
    ) -> PyResult<(Vec<u32>, Vec<f64>, Vec<Vec<usize>>, Vec<Vec<f64>>)> {
        let budget = budget(max_test_cost, max_tests)?;
        let Some(frame) = self.objects(columns)? else {
            return Ok((Vec::new(), Vec::new(), Vec::new(), Vec::new()));
        };
        let n = frame.len();
        let (tree, prices) = (&self.tree, &self.prices);
        Ok(py.detach(|| {
            let mut classes = Vec::with_capacity(n);
            let mut costs = Vec::with_capacity(n);
            let mut tests = Vec::with_capacity(n);
            let mut probabilities = Vec::with_capacity(n);
            for row in 0..n {
                let c = tree.classify_within(&frame, row, prices, &budget);
                classes.push(c.class);
                costs.push(c.test_cost);
                tests.push(c.tests);
                probabilities.push(c.probabilities);
            }
            (classes, costs, tests, probabilities)
        }))
    }

    /// How each object is classified, test by test (`CostTree::explain`; columns and
    /// budget as in `classify`): per object, its steps, each `(feature, paid, node,
    /// probabilities, expected_gain)` in the order bought (`node` and `probabilities`
    /// `None` for a test bought on a branch below a missing value; `expected_gain` VOI's
    /// only), and the node it stopped at (`None` where it answered from several branches).
    #[expect(
        clippy::type_complexity,
        reason = "the tuples Python receives: steps and the node stopped at, per object"
    )]
    #[pyo3(signature = (columns, max_test_cost=None, max_tests=None))]
    fn explain(
        &self,
        py: Python<'_>,
        columns: Vec<PyColumn<'_>>,
        max_test_cost: Option<f64>,
        max_tests: Option<usize>,
    ) -> PyResult<
        Vec<(
            Vec<(usize, f64, Option<usize>, Option<Vec<f64>>, Option<f64>)>,
            Option<usize>,
        )>,
    > {
        let budget = budget(max_test_cost, max_tests)?;
        let Some(frame) = self.objects(columns)? else {
            return Ok(Vec::new());
        };
        let n = frame.len();
        let (tree, prices) = (&self.tree, &self.prices);
        Ok(py.detach(|| {
            (0..n)
                .map(|row| {
                    let why = tree.explain(&frame, row, prices, &budget);
                    let steps = why
                        .steps
                        .into_iter()
                        .map(|s| (s.feature, s.paid, s.node, s.probabilities, s.expected_gain))
                        .collect();
                    (steps, why.stopped_at)
                })
                .collect()
        }))
    }

    /// The nodes, root first: `(label, weights, split)` with the class code each answers,
    /// the training weight of each class there, and `None` at a leaf or
    /// `(feature, threshold, children)` (threshold `None` for a nominal feature, whose
    /// children follow its values).
    #[expect(
        clippy::type_complexity,
        reason = "the tuples Python receives, one per node"
    )]
    fn nodes(&self) -> Vec<(u32, Vec<f64>, Option<(usize, Option<f64>, Vec<u32>)>)> {
        (0..self.tree.len())
            .map(|i| {
                let node = self.tree.node(i);
                let split = node.split.as_ref().map(|s| match s {
                    Split::Nominal {
                        feature, children, ..
                    } => (*feature, None, children.clone()),
                    Split::Threshold {
                        feature,
                        at,
                        children,
                        ..
                    } => (*feature, Some(*at), children.to_vec()),
                });
                (node.label, node.weights.clone(), split)
            })
            .collect()
    }

    /// The learner's name.
    #[getter]
    fn learner(&self) -> &'static str {
        self.learner.name()
    }

    /// ICET's best individual, `(prices, w, confidence, fitness)`: the biased price of
    /// each test, EG2's `w`, the pruning confidence and the mean total cost on the
    /// held-out half; `None` for the other learners.
    #[getter]
    fn icet_genome(&self) -> Option<(Vec<f64>, f64, f64, f64)> {
        self.genome
            .as_ref()
            .map(|g| (g.prices.clone(), g.w, g.confidence, g.fitness))
    }

    /// For CVT, what its cross-validation chose: the grower (as `csrl classify`'s report
    /// names it), the price per leaf the tree was cut back at (`None` where it was pruned
    /// by its pessimistic cost instead), and the mean total cost per held-out object;
    /// `None` for the other learners.
    #[getter]
    fn cvt_choice(&self) -> Option<(String, Option<f64>, f64)> {
        self.cvt
            .map(|c| (c.grower_name().to_string(), c.alpha, c.held_out_cost))
    }

    /// The tree, its prices and its columns as plain Python values (dicts, lists,
    /// strings and numbers; floats exact), for pickling.
    fn state(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        to_python(py, &self.to_value()?)
    }

    /// A tree from what `state` returned.
    #[staticmethod]
    fn from_state(state: &Bound<'_, PyAny>) -> PyResult<TestCostTree> {
        TestCostTree::from_value(&from_python(state)?)
            .map_err(|e| DataError::new_err(format!("not a saved tree: {e}")))
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyAny>,))> {
        let cls: Bound<'py, PyType> = slf.get_type();
        Ok((
            cls.getattr("from_state")?,
            (slf.get().state(slf.py())?.into_bound(slf.py()),),
        ))
    }
}

/// A JSON value as Python's dicts, lists, strings and numbers (floats exactly: a text
/// round trip through serde_json's default parser can move a float by one unit in the
/// last place, and a threshold with it).
fn to_python(py: Python<'_>, value: &Value) -> PyResult<Py<PyAny>> {
    Ok(match value {
        Value::Null => py.None(),
        Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any().unbind(),
        Value::Number(n) => {
            if let Some(u) = n.as_u64() {
                u.into_pyobject(py)?.into_any().unbind()
            } else if let Some(i) = n.as_i64() {
                i.into_pyobject(py)?.into_any().unbind()
            } else {
                n.as_f64()
                    .unwrap_or(f64::NAN)
                    .into_pyobject(py)?
                    .into_any()
                    .unbind()
            }
        }
        Value::String(s) => s.into_pyobject(py)?.into_any().unbind(),
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(to_python(py, item)?)?;
            }
            list.into_any().unbind()
        }
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (k, v) in map {
                dict.set_item(k, to_python(py, v)?)?;
            }
            dict.into_any().unbind()
        }
    })
}

/// The inverse of [`to_python`].
fn from_python(obj: &Bound<'_, PyAny>) -> PyResult<Value> {
    from_python_within(obj, MAX_STATE_DEPTH)
}

/// The deepest nesting a saved tree's state may have: its tree is a flat list of nodes,
/// so a few levels; a state nested 100,000 deep would exhaust the stack.
const MAX_STATE_DEPTH: usize = 32;

fn from_python_within(obj: &Bound<'_, PyAny>, depth: usize) -> PyResult<Value> {
    let bad = || DataError::new_err("not a saved tree: a value that is not JSON");
    if depth == 0 {
        return Err(DataError::new_err(format!(
            "not a saved tree: nested deeper than the {MAX_STATE_DEPTH} levels a saved tree has"
        )));
    }
    let from_python = |o: &Bound<'_, PyAny>| from_python_within(o, depth - 1);
    Ok(if obj.is_none() {
        Value::Null
    } else if let Ok(b) = obj.cast::<PyBool>() {
        Value::Bool(b.is_true())
    } else if obj.is_instance_of::<PyInt>() {
        if let Ok(u) = obj.extract::<u64>() {
            Value::from(u)
        } else {
            Value::from(obj.extract::<i64>().map_err(|_| bad())?)
        }
    } else if let Ok(f) = obj.cast::<PyFloat>() {
        serde_json::Number::from_f64(f.value()).map_or(Value::Null, Value::Number)
    } else if obj.is_instance_of::<PyString>() {
        Value::String(obj.extract()?)
    } else if let Ok(list) = obj.cast::<PyList>() {
        Value::Array(
            list.iter()
                .map(|i| from_python(&i))
                .collect::<PyResult<_>>()?,
        )
    } else if let Ok(dict) = obj.cast::<PyDict>() {
        let mut map = serde_json::Map::new();
        for (k, v) in dict.iter() {
            let key: String = k.extract().map_err(|_| bad())?;
            map.insert(key, from_python(&v)?);
        }
        Value::Object(map)
    } else {
        return Err(bad());
    })
}
