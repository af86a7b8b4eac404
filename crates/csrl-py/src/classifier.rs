//! `csrl._csrl.Classifier`: CS-ID3 or CS-IBL over integer-coded objects, for the
//! scikit-learn estimators of `csrl.sklearn` (which code the values and the classes).

use cslearn::{ClassId, DecisionTree, FeatureCosts, FeatureId, Labels, TreeOptions, Value};
use std::time::{Duration, Instant};

use pyo3::prelude::*;

use crate::DataError;

enum Inner {
    Id3(cslearn::IndexedCsId3),
    Ibl(cslearn::CsIbl),
}

/// An incremental cost-sensitive learner over objects whose values are small integers
/// (`None` for a missing value), with a price per feature.
#[pyclass(module = "csrl._csrl")]
pub struct Classifier {
    inner: Inner,
    costs: FeatureCosts,
    /// The most every `learn` so far could have charged: the summed prices times the
    /// objects learned. Kept at most [`cslearn::MAX_TOTAL_COST`], so that any sum of what
    /// `learn` returned is finite.
    most_charged: f64,
}

type Rows = Vec<Vec<Option<u32>>>;

/// How long the objects are worked through without the GIL before Python's signal
/// handlers get a turn.
const SLICE: Duration = Duration::from_millis(50);

/// Runs `step` on `0..n` in order with the GIL released, in slices of about [`SLICE`];
/// between slices it takes the GIL back and lets Python's signal handlers run, so Ctrl-C
/// stops a long `fit` or `predict` within a slice. The slicing changes when signals are
/// seen, never what `step` computes.
fn interruptible(py: Python<'_>, n: usize, mut step: impl FnMut(usize) + Send) -> PyResult<()> {
    let mut at = 0;
    while at < n {
        at = py.detach(|| {
            let start = Instant::now();
            let mut i = at;
            while i < n {
                step(i);
                i += 1;
                if start.elapsed() >= SLICE {
                    break;
                }
            }
            i
        });
        py.check_signals()?;
    }
    Ok(())
}

impl Classifier {
    fn check(&self, rows: &Rows) -> PyResult<Vec<Vec<Option<Value>>>> {
        let n = self.costs.len();
        rows.iter()
            .enumerate()
            .map(|(i, row)| {
                if row.len() == n {
                    Ok(row.iter().map(|v| v.map(Value)).collect())
                } else {
                    Err(DataError::new_err(format!(
                        "row {i} has {} values; the learner has {n} features (one price each)",
                        row.len()
                    )))
                }
            })
            .collect()
    }

    fn library(&self) -> &cslearn::Library {
        match &self.inner {
            Inner::Id3(l) => l.library(),
            Inner::Ibl(l) => l.library(),
        }
    }
}

struct Names<'a> {
    features: &'a [String],
    values: &'a [Vec<String>],
    classes: &'a [String],
}

impl Labels for Names<'_> {
    fn feature(&self, feature: FeatureId) -> String {
        self.features
            .get(feature.index())
            .cloned()
            .unwrap_or_else(|| feature.to_string())
    }
    fn value(&self, feature: FeatureId, value: Value) -> String {
        self.values
            .get(feature.index())
            .and_then(|v| v.get(value.0 as usize))
            .cloned()
            .unwrap_or_else(|| value.to_string())
    }
    fn class(&self, class: ClassId) -> String {
        self.classes
            .get(class.0 as usize)
            .cloned()
            .unwrap_or_else(|| class.to_string())
    }
}

#[pymethods]
impl Classifier {
    /// `kind` is `"cs-id3"` or `"cs-ibl"`; `costs` the price of each feature (finite, at
    /// least 0); `tolerance` the wrong values CS-IBL tolerates on an object.
    #[new]
    #[pyo3(signature = (kind, costs, tolerance=1))]
    fn new(kind: &str, costs: Vec<f64>, tolerance: u32) -> PyResult<Classifier> {
        let costs = FeatureCosts::from_f64(&costs)
            .map_err(|e| DataError::new_err(format!("feature_costs: {e}")))?;
        let per_object: f64 = costs.as_slice().iter().map(|c| c.get()).sum();
        if !(per_object.is_finite() && per_object <= cslearn::MAX_TOTAL_COST) {
            return Err(DataError::new_err(format!(
                "feature_costs: the prices sum to {per_object:e}, more than {:e} \
                 (cslearn::MAX_TOTAL_COST, so that the cost of learning stays finite)",
                cslearn::MAX_TOTAL_COST
            )));
        }
        let inner = match kind {
            "cs-id3" => Inner::Id3(cslearn::cs_id3_indexed(costs.clone())),
            "cs-ibl" => Inner::Ibl(cslearn::cs_ibl(costs.clone(), tolerance)),
            other => {
                return Err(DataError::new_err(format!(
                    "learner {other:?}: expected \"cs-id3\" or \"cs-ibl\""
                )));
            }
        };
        Ok(Classifier {
            inner,
            costs,
            most_charged: 0.0,
        })
    }

    /// Learn the objects in order, each predicted and then learned (the paper's cycle),
    /// and return the wrong predictions and what was charged. Refused when the summed
    /// prices times every object learned so far would pass [`cslearn::MAX_TOTAL_COST`].
    /// Ctrl-C stops it with `KeyboardInterrupt` (the objects learned by then stay
    /// learned).
    fn learn(&mut self, py: Python<'_>, rows: Rows, classes: Vec<u32>) -> PyResult<(usize, f64)> {
        if rows.len() != classes.len() {
            return Err(DataError::new_err(format!(
                "{} rows but {} classes",
                rows.len(),
                classes.len()
            )));
        }
        let per_object: f64 = self.costs.as_slice().iter().map(|c| c.get()).sum();
        let most = self.most_charged + per_object * rows.len() as f64;
        if !(most.is_finite() && most <= cslearn::MAX_TOTAL_COST) {
            return Err(DataError::new_err(format!(
                "{} objects at prices summing to {per_object:e} could cost {most:e} in all, \
                 more than {:e} (cslearn::MAX_TOTAL_COST, so that the cost of learning stays finite)",
                rows.len(),
                cslearn::MAX_TOTAL_COST
            )));
        }
        let rows = self.check(&rows)?;
        self.most_charged = most;
        let inner = &mut self.inner;
        let (mut errors, mut cost) = (0, 0.0);
        interruptible(py, rows.len(), |i| {
            let outcome = match inner {
                Inner::Id3(l) => l.learn(&rows[i][..], ClassId(classes[i])),
                Inner::Ibl(l) => l.learn(&rows[i][..], ClassId(classes[i])),
            };
            errors += usize::from(!outcome.correct());
            cost += outcome.cost.get();
        })?;
        Ok((errors, cost))
    }

    /// Classify the objects without learning: the class of each (`None` where nothing
    /// can be predicted) and what classifying it cost. Ctrl-C stops it with
    /// `KeyboardInterrupt`.
    fn classify(&mut self, py: Python<'_>, rows: Rows) -> PyResult<(Vec<Option<u32>>, Vec<f64>)> {
        let rows = self.check(&rows)?;
        let inner = &mut self.inner;
        let mut classes = Vec::with_capacity(rows.len());
        let mut costs = Vec::with_capacity(rows.len());
        interruptible(py, rows.len(), |i| {
            let c = match inner {
                Inner::Id3(l) => l.classify(&rows[i][..]),
                Inner::Ibl(l) => l.classify(&rows[i][..]),
            };
            classes.push(c.class.map(|c| c.0));
            costs.push(c.cost.get());
        })?;
        Ok((classes, costs))
    }

    /// [`classify`](Classifier::classify), with the probability of each of `classes`
    /// classes per object: the classes of the examples its prediction went by
    /// (`cslearn::Votes`: CS-ID3's attended examples, CS-IBL's agreeing or nearest ones),
    /// smoothed by Laplace's rule; uniform where nothing could be predicted. The classes
    /// and costs are `classify`'s. Ctrl-C stops it with `KeyboardInterrupt`.
    #[expect(
        clippy::type_complexity,
        reason = "the tuple Python receives: classes, costs, probabilities"
    )]
    fn classify_proba(
        &mut self,
        py: Python<'_>,
        rows: Rows,
        classes: usize,
    ) -> PyResult<(Vec<Option<u32>>, Vec<f64>, Vec<Vec<f64>>)> {
        let rows = self.check(&rows)?;
        let inner = &mut self.inner;
        let mut answers = Vec::with_capacity(rows.len());
        let mut costs = Vec::with_capacity(rows.len());
        let mut probabilities = Vec::with_capacity(rows.len());
        interruptible(py, rows.len(), |i| {
            let (c, votes) = match inner {
                Inner::Id3(l) => l.classify_with_votes(&rows[i][..]),
                Inner::Ibl(l) => l.classify_with_votes(&rows[i][..]),
            };
            answers.push(c.class.map(|c| c.0));
            costs.push(c.cost.get());
            probabilities.push(votes.probabilities(classes));
        })?;
        Ok((answers, costs, probabilities))
    }

    /// The number of examples in the learner's library.
    #[getter]
    fn library_size(&self) -> usize {
        self.library().len()
    }

    /// The cost-sensitive decision tree grown from the library, as Graphviz DOT, with
    /// the names given (numbers where a name is missing).
    #[pyo3(signature = (feature_names, value_names, class_names))]
    fn tree_dot(
        &self,
        feature_names: Vec<String>,
        value_names: Vec<Vec<String>>,
        class_names: Vec<String>,
    ) -> String {
        let tree = DecisionTree::build(self.library(), &self.costs, TreeOptions::observations());
        tree.to_dot(&Names {
            features: &feature_names,
            values: &value_names,
            classes: &class_names,
        })
    }
}
