//! A tree of the family saved to a file, and new rows classified by it ([`TreeModel`]);
//! and either kind of model file read by its `format` ([`SavedModel`]).

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::budget::Budget;
use super::data::{Column, Frame};
use super::family::{Fitted, IcetGenome, Method};
use super::prices::TestPrices;
use super::tree::{CostTree, FeatureShape};
use crate::dataset::{
    MAX_TOTAL_COST, is_missing, open_regular, parse_number, read_bounded, read_table,
};
use crate::error::Error;
use crate::model::{Model, Prediction, Probe, check_names, check_values, json_error};
use crate::types::{ClassId, Cost, FeatureId};

/// The `format` of a saved tree of the test-cost family.
///
/// ```
/// assert_eq!(cslearn::testcost::TREE_MODEL_FORMAT, "csrl-cost-tree");
/// ```
pub const TREE_MODEL_FORMAT: &str = "csrl-cost-tree";

/// The version of the saved-tree format this crate writes and reads.
///
/// ```
/// assert_eq!(cslearn::testcost::TREE_MODEL_VERSION, 1);
/// ```
pub const TREE_MODEL_VERSION: u32 = 1;

/// One feature of a saved tree: its name, and how its cells are read.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FeatureEntry {
    name: String,
    /// `numeric` or `nominal`.
    kind: String,
    /// A nominal feature's values, indexed by the codes the tree's splits use.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    values: Option<Vec<String>>,
}

/// The file's contents.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct TreeFile {
    format: String,
    version: u32,
    learner: String,
    target: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    positive_if: Option<String>,
    classes: Vec<String>,
    features: Vec<FeatureEntry>,
    prices: TestPrices,
    tree: CostTree,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    genome: Option<IcetGenome>,
}

/// A tree of the test-cost family ([`Method`]) learned from a [`Frame`], with what it
/// needs to classify new rows: the features (names, and the values of nominal ones, in
/// the order of the codes the tree uses), the class names and the test prices. Saved as
/// a versioned JSON file ([`TREE_MODEL_FORMAT`], [`TREE_MODEL_VERSION`]) and read back
/// with every number checked.
///
/// # The file (format `csrl-cost-tree`, version 1)
///
/// One JSON object:
///
/// | key | what |
/// |---|---|
/// | `format` | always `"csrl-cost-tree"` |
/// | `version` | always `1`; a reader refuses any other |
/// | `learner` | the learner's name ([`Method::name`]: `id3-batch`, `c45`, `idx`, `cs-id3-batch`, `eg2`, `dtmc`, `icet`, `act`, `cvt`, `voi`) |
/// | `target` | the class column it was learned from |
/// | `positive_if` | the rule that made two classes of it, if one did |
/// | `classes` | the class names, indexed by class number |
/// | `features` | one object per feature, in feature order: `name`, `kind` (`numeric` or `nominal`) and, for a nominal one, `values` (its values, indexed by value code) |
/// | `prices` | the real prices of the tests ([`TestPrices`]: `tests`, each `full`, `discount`, `group`, `delayed`; `group_names`) |
/// | `tree` | the tree ([`CostTree`]: `nodes`, each `weights` per class, `label`, `split` and, for VOI, `value` ([`NodeValue`](super::NodeValue)); `mc`, the misclassification costs its answers were chosen by) |
/// | `genome` | ICET only: the individual its search found ([`IcetGenome`]) |
///
/// Unknown keys are refused, and so is every number out of range (a class, feature or
/// node that does not exist, a child that does not come after its parent, a price or
/// weight that is negative or not finite), naming where it is.
///
/// # Classifying new rows
///
/// [`TreeModel::predict_file_each`] reads a CSV table with a header. Columns are matched
/// by name: every feature of the model must be a column (in any order); other columns,
/// the target included, are ignored. A numeric feature's cell must be a number; a nominal
/// feature's cell the model never saw goes down the branch that held most training
/// objects. Empty cells and `?` are missing: such an object goes down every branch,
/// paying for the tests of all of them (C4.5's rule, as in training).
///
/// ```
/// use cslearn::testcost::{fit, Column, FamilyParams, Frame, Method, MisclassCosts, TestPrices, TreeModel};
/// let frame = Frame::new(vec!["x".into(), "colour".into()],
///     vec![Column::Numeric((0..20).map(f64::from).collect()),
///          Column::Nominal { values: vec!["red".into(), "blue".into()], codes: vec![0; 20] }],
///     (0..20).map(|i| u32::from(i >= 10)).collect(), vec!["a".into(), "b".into()]).unwrap();
/// let prices = TestPrices::flat(&[5.0, 1.0]).unwrap();
/// let mc = MisclassCosts::uniform(2, 100.0).unwrap();
/// let rows: Vec<usize> = (0..20).collect();
/// let fitted = fit(Method::Eg2, &frame, &rows, &prices, &mc, &FamilyParams::default(), 1);
/// let model = TreeModel::new(Method::Eg2, &frame, "class", None, &fitted, &prices);
/// let again = TreeModel::from_json(model.to_json().as_bytes(), "m.json").unwrap();
/// assert_eq!(again, model);
/// let dir = tempfile::tempdir().unwrap();
/// let rows = dir.path().join("new.csv");
/// std::fs::write(&rows, "colour,x\nblue,3\nred,17\n").unwrap();
/// let mut classes = Vec::new();
/// again.predict_file_each(&rows, &mut |p, _| classes.push((p.line, p.class.unwrap().0, p.cost.get()))).unwrap();
/// assert_eq!(classes, [(2, 0, 5.0), (3, 1, 5.0)]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct TreeModel {
    file: TreeFile,
    learner: Method,
}

impl TreeModel {
    /// The model of the tree `fitted` that `learner` learned from `frame` (whose class
    /// column is `target`, binarised by `positive_if` if given), priced by `prices` (the
    /// real prices, which classifying new rows pays).
    ///
    /// ```
    /// # use cslearn::testcost::*;
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0, 1.0])],
    ///     vec![0, 1], vec!["a".into(), "b".into()]).unwrap();
    /// let prices = TestPrices::flat(&[2.0]).unwrap();
    /// let mc = MisclassCosts::uniform(2, 10.0).unwrap();
    /// let fitted = fit(Method::C45, &frame, &[0, 1], &prices, &mc, &FamilyParams::default(), 1);
    /// let model = TreeModel::new(Method::C45, &frame, "y", None, &fitted, &prices);
    /// assert_eq!((model.learner(), model.feature_names()), (Method::C45, vec!["x"]));
    /// ```
    pub fn new(
        learner: Method,
        frame: &Frame,
        target: &str,
        positive_if: Option<&str>,
        fitted: &Fitted,
        prices: &TestPrices,
    ) -> TreeModel {
        let features = frame
            .names()
            .iter()
            .enumerate()
            .map(|(f, name)| match frame.column(f) {
                Column::Numeric(_) => FeatureEntry {
                    name: name.clone(),
                    kind: "numeric".into(),
                    values: None,
                },
                Column::Nominal { values, .. } => FeatureEntry {
                    name: name.clone(),
                    kind: "nominal".into(),
                    values: Some(values.clone()),
                },
            })
            .collect();
        TreeModel {
            file: TreeFile {
                format: TREE_MODEL_FORMAT.into(),
                version: TREE_MODEL_VERSION,
                learner: learner.name().into(),
                target: target.into(),
                positive_if: positive_if.map(str::to_string),
                classes: frame.class_names().to_vec(),
                features,
                prices: prices.clone(),
                tree: fitted.tree.clone(),
                genome: fitted.genome.clone(),
            },
            learner,
        }
    }

    /// The model as the text of a model file (compact JSON on one line, ending in a
    /// newline).
    ///
    /// ```
    /// # use cslearn::testcost::*;
    /// # let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0, 1.0])],
    /// #     vec![0, 1], vec!["a".into(), "b".into()]).unwrap();
    /// # let prices = TestPrices::flat(&[2.0]).unwrap();
    /// # let mc = MisclassCosts::uniform(2, 10.0).unwrap();
    /// # let fitted = fit(Method::C45, &frame, &[0, 1], &prices, &mc, &FamilyParams::default(), 1);
    /// let text = TreeModel::new(Method::C45, &frame, "y", None, &fitted, &prices).to_json();
    /// assert!(text.starts_with("{\"format\":\"csrl-cost-tree\",\"version\":1,\"learner\":\"c45\","));
    /// ```
    pub fn to_json(&self) -> String {
        // Every number in a model is finite (checked where it is made or read), so this
        // cannot fail; an empty object would be refused on reading.
        let mut text = serde_json::to_string(&self.file).unwrap_or_default();
        text.push('\n');
        text
    }

    /// Read a model file from its bytes, checking every number; `path` is for messages.
    ///
    /// ```
    /// let err = cslearn::testcost::TreeModel::from_json(br#"{"format": "csrl-cost-tree", "version": 2}"#, "m.json").unwrap_err();
    /// assert_eq!(err.to_string(), "m.json: key `version`: version 2 is not supported (this build reads version 1)");
    /// ```
    pub fn from_json(bytes: &[u8], path: impl AsRef<Path>) -> Result<TreeModel, Error> {
        let path = path.as_ref();
        let bad = |at: String, reason: String| Error::BadModel {
            path: path.to_path_buf(),
            at,
            reason,
        };
        let probe: Probe = serde_json::from_slice(bytes).map_err(|e| json_error(path, &e))?;
        match &probe.format {
            Some(serde_json::Value::String(f)) if f == TREE_MODEL_FORMAT => {}
            Some(serde_json::Value::String(f)) => {
                return Err(bad(
                    "key `format`".into(),
                    format!("`{f}`: not a saved tree (format \"{TREE_MODEL_FORMAT}\")"),
                ));
            }
            _ => {
                return Err(bad(
                    "key `format`".into(),
                    format!("missing or not a string; a saved tree says \"{TREE_MODEL_FORMAT}\""),
                ));
            }
        }
        probe
            .check_version(TREE_MODEL_VERSION)
            .map_err(|(at, reason)| bad(at, reason))?;
        let file: TreeFile = serde_json::from_slice(bytes).map_err(|e| json_error(path, &e))?;
        // The tree's own types take any key; this file takes none it does not know.
        let value: serde_json::Value =
            serde_json::from_slice(bytes).map_err(|e| json_error(path, &e))?;
        let reread = serde_json::to_value(&file).map_err(|e| json_error(path, &e))?;
        if let Some(key) = unknown_key(&value, &reread, String::new()) {
            return Err(bad(
                format!("key `{key}`"),
                "not a key of a saved tree".into(),
            ));
        }
        let learner = check(&file).map_err(|(at, reason)| bad(at, reason))?;
        Ok(TreeModel { file, learner })
    }

    /// Read a model file: a regular file of at most [`MAX_FILE_BYTES`](crate::MAX_FILE_BYTES).
    ///
    /// ```
    /// let err = cslearn::testcost::TreeModel::load("no/such/model.json".as_ref()).unwrap_err();
    /// assert!(matches!(err, cslearn::Error::Io { .. }));
    /// ```
    pub fn load(path: &Path) -> Result<TreeModel, Error> {
        let bytes = read_bounded(open_regular(path)?, path)?;
        TreeModel::from_json(&bytes, path)
    }

    /// The learner that grew the tree.
    pub fn learner(&self) -> Method {
        self.learner
    }

    /// The features, in the tree's order.
    pub fn feature_names(&self) -> Vec<&str> {
        self.file.features.iter().map(|f| f.name.as_str()).collect()
    }

    /// The name of class `class`.
    ///
    /// ```
    /// # use cslearn::testcost::*;
    /// # let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0, 1.0])],
    /// #     vec![0, 1], vec!["a".into(), "b".into()]).unwrap();
    /// # let prices = TestPrices::flat(&[2.0]).unwrap();
    /// # let mc = MisclassCosts::uniform(2, 10.0).unwrap();
    /// # let fitted = fit(Method::C45, &frame, &[0, 1], &prices, &mc, &FamilyParams::default(), 1);
    /// let model = TreeModel::new(Method::C45, &frame, "y", None, &fitted, &prices);
    /// assert_eq!((model.class_name(1), model.class_name(2)), (Some("b"), None));
    /// ```
    pub fn class_name(&self, class: u32) -> Option<&str> {
        self.file.classes.get(class as usize).map(String::as_str)
    }

    /// The tree.
    pub fn tree(&self) -> &CostTree {
        &self.file.tree
    }

    /// The prices classifying pays.
    pub fn prices(&self) -> &TestPrices {
        &self.file.prices
    }

    /// ICET's individual, for an ICET tree.
    pub fn genome(&self) -> Option<&IcetGenome> {
        self.file.genome.as_ref()
    }

    /// The rows of a CSV table (with a header) as a [`Frame`] over the model's features,
    /// coded as the tree reads them, and the line of each row. Every class is 0 (the
    /// table's classes, if it has any, are not read).
    ///
    /// ```
    /// # use cslearn::testcost::*;
    /// # let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0, 1.0])],
    /// #     vec![0, 1], vec!["a".into(), "b".into()]).unwrap();
    /// # let prices = TestPrices::flat(&[2.0]).unwrap();
    /// # let mc = MisclassCosts::uniform(2, 10.0).unwrap();
    /// # let fitted = fit(Method::C45, &frame, &[0, 1], &prices, &mc, &FamilyParams::default(), 1);
    /// let model = TreeModel::new(Method::C45, &frame, "y", None, &fitted, &prices);
    /// let dir = tempfile::tempdir().unwrap();
    /// let path = dir.path().join("rows.csv");
    /// std::fs::write(&path, "z\n1\n").unwrap();
    /// let err = model.frame_for(&path).unwrap_err().to_string();
    /// assert!(err.ends_with("rows.csv: no column `x`, which the model reads (columns: z)"), "{err}");
    /// ```
    pub fn frame_for(&self, path: &Path) -> Result<(Frame, Vec<u64>), Error> {
        let table = read_table(open_regular(path)?, path)?;
        if table.is_empty() {
            return Err(Error::NoRecords {
                path: path.to_path_buf(),
            });
        }
        let mut index = std::collections::BTreeMap::new();
        for (i, h) in table.header.iter().enumerate() {
            if index.insert(h.as_str(), i).is_some() {
                return Err(Error::DuplicateColumn {
                    path: path.to_path_buf(),
                    column: h.clone(),
                });
            }
        }
        let features = &self.file.features;
        let missing: Vec<String> = features
            .iter()
            .filter(|f| !index.contains_key(f.name.as_str()))
            .map(|f| f.name.clone())
            .collect();
        if !missing.is_empty() {
            return Err(Error::MissingColumns {
                path: path.to_path_buf(),
                missing,
                columns: table.header.clone(),
            });
        }
        // Every total printed must be a true one: at worst a row pays every test in full.
        let per_row: f64 = (0..self.file.prices.len())
            .map(|t| self.file.prices.test(t).full)
            .sum();
        let total = per_row * table.len() as f64;
        if !(total.is_finite() && total <= MAX_TOTAL_COST) {
            return Err(Error::CostsTooLarge {
                path: path.to_path_buf(),
                per_object: per_row,
                objects: table.len(),
                max: MAX_TOTAL_COST,
            });
        }
        let mut columns = Vec::with_capacity(features.len());
        for f in features {
            let c = index[f.name.as_str()];
            let column = match &f.values {
                None => Column::Numeric(
                    table
                        .records()
                        .map(|(line, record)| {
                            let cell = record.get(c);
                            if is_missing(cell) {
                                Ok(f64::NAN)
                            } else {
                                parse_number(cell).ok_or_else(|| Error::NotANumber {
                                    path: path.to_path_buf(),
                                    line,
                                    column: f.name.clone(),
                                    text: cell.to_string(),
                                })
                            }
                        })
                        .collect::<Result<_, _>>()?,
                ),
                Some(known) => {
                    // A value never seen gets a code past the known ones, which the tree
                    // sends down its largest branch.
                    let mut values = known.clone();
                    let mut code: std::collections::BTreeMap<String, u32> = known
                        .iter()
                        .enumerate()
                        .map(|(i, v)| (v.clone(), i as u32))
                        .collect();
                    let codes = table
                        .column(c)
                        .map(|cell| {
                            if is_missing(cell) {
                                return super::data::MISSING;
                            }
                            *code.entry(cell.to_string()).or_insert_with(|| {
                                values.push(cell.to_string());
                                (values.len() - 1) as u32
                            })
                        })
                        .collect();
                    Column::Nominal { values, codes }
                }
            };
            columns.push(column);
        }
        let lines = table.records().map(|(line, _)| line).collect();
        let frame = Frame::new(
            features.iter().map(|f| f.name.clone()).collect(),
            columns,
            vec![0; table.len()],
            self.file.classes.clone(),
        )
        .map_err(|e| Error::BadInput {
            path: path.to_path_buf(),
            at: "data".into(),
            reason: e.to_string(),
        })?;
        Ok((frame, lines))
    }

    /// Classify every row of a CSV table (see [`frame_for`](TreeModel::frame_for)), in
    /// file order, calling `each` with each row's [`Prediction`] (its line, class, what
    /// its tests cost, the tests done, in order, and the probability of each class,
    /// [`Classification::probabilities`](super::Classification::probabilities)) and the
    /// number of rows. The whole
    /// table is read and checked before the first call. Returns the number of rows.
    pub fn predict_file_each(
        &self,
        path: &Path,
        each: &mut dyn FnMut(Prediction, usize),
    ) -> Result<usize, Error> {
        self.predict_file_each_within(path, &Budget::UNLIMITED, each)
    }

    /// How the row at line `line` of a CSV table (see [`frame_for`](TreeModel::frame_for);
    /// the header is line 1) is classified within `budget`, test by test
    /// ([`CostTree::explain`](super::CostTree::explain)); [`explanation_text`](TreeModel::explanation_text)
    /// puts it in words.
    ///
    /// # Errors
    /// The table's, as [`frame_for`](TreeModel::frame_for) gives them, and a line that is
    /// not one of its rows.
    ///
    /// ```
    /// # use cslearn::testcost::*;
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric((0..20).map(f64::from).collect())],
    ///     (0..20).map(|i| u32::from(i >= 10)).collect(), vec!["a".into(), "b".into()]).unwrap();
    /// let prices = TestPrices::flat(&[5.0]).unwrap();
    /// let mc = MisclassCosts::uniform(2, 100.0).unwrap();
    /// let rows: Vec<usize> = (0..20).collect();
    /// let fitted = fit(Method::Voi, &frame, &rows, &prices, &mc, &FamilyParams::default(), 1);
    /// let model = TreeModel::new(Method::Voi, &frame, "y", None, &fitted, &prices);
    /// let dir = tempfile::tempdir().unwrap();
    /// let path = dir.path().join("rows.csv");
    /// std::fs::write(&path, "x\n3\n17\n").unwrap();
    /// let why = model.explain_line(&path, 3, &Budget::UNLIMITED).unwrap();
    /// assert_eq!((why.steps.len(), why.classification.class), (1, 1));
    /// // Stopping at the root costs an error on half the objects; the test saves most of it.
    /// assert!(why.steps[0].expected_gain.unwrap() > 40.0);
    /// assert!(model.explanation_text(&why).contains("1. x: paid 5"));
    /// let err = model.explain_line(&path, 9, &Budget::UNLIMITED).unwrap_err().to_string();
    /// assert!(err.contains("line 9") && err.contains("lines 2 to 3"), "{err}");
    /// ```
    pub fn explain_line(
        &self,
        path: &Path,
        line: u64,
        budget: &Budget,
    ) -> Result<super::Explanation, Error> {
        let (frame, lines) = self.frame_for(path)?;
        let Some(row) = lines.iter().position(|&l| l == line) else {
            let span = match (lines.first(), lines.last()) {
                (Some(a), Some(b)) => format!("its rows are on lines {a} to {b}"),
                _ => "it has no rows".into(),
            };
            return Err(Error::Invalid {
                what: format!("{}: line {line}", path.display()),
                reason: format!("not a row of the table ({span}; the header is line 1)"),
            });
        };
        Ok(self
            .file
            .tree
            .explain(&frame, row, &self.file.prices, budget))
    }

    /// An explanation ([`explain_line`](TreeModel::explain_line)) in words, with the
    /// model's feature and class names: one line per test bought (what it paid, the
    /// class probabilities where it was asked for, and, for VOI's trees, what it was
    /// expected to save per object), then the answer and its probabilities, and, where
    /// the object stopped at a node of VOI's, what stopping there was expected to cost.
    pub fn explanation_text(&self, why: &super::Explanation) -> String {
        use std::fmt::Write as _;
        let name = |f: usize| self.file.features.get(f).map_or("?", |e| e.name.as_str());
        let class = |c: u32| self.class_name(c).unwrap_or("?");
        let probabilities = |p: &[f64]| {
            p.iter()
                .enumerate()
                .map(|(c, p)| format!("{} {p:.3}", class(c as u32)))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let mut text = String::new();
        if why.steps.is_empty() {
            text.push_str("no test bought\n");
        }
        for (i, step) in why.steps.iter().enumerate() {
            let _ = write!(
                text,
                "{}. {}: paid {}",
                i + 1,
                name(step.feature),
                step.paid
            );
            match (&step.node, &step.probabilities) {
                (Some(node), Some(p)) => {
                    let _ = write!(text, "; asked at node {node}, where {}", probabilities(p));
                }
                _ => text.push_str("; on a branch below a missing value"),
            }
            if let Some(gain) = step.expected_gain {
                let _ = write!(text, "; expected to save {gain:.4} per object");
            }
            text.push('\n');
        }
        let c = &why.classification;
        let _ = write!(
            text,
            "answer {} (tests {} in all); probabilities {}",
            class(c.class),
            c.test_cost,
            probabilities(&c.probabilities)
        );
        match why.stopped_at {
            Some(node) => {
                let _ = write!(text, "; stopped at node {node}");
                if let Some(value) = self.file.tree.node(node).value {
                    let _ = write!(
                        text,
                        ", where stopping was expected to cost {:.4} per object",
                        value.stop
                    );
                }
            }
            None => text.push_str("; answered from several branches (a missing value)"),
        }
        text.push('\n');
        text
    }

    /// [`predict_file_each`](TreeModel::predict_file_each) with every row held to
    /// `budget` ([`CostTree::classify_within`](super::CostTree::classify_within)): a test
    /// that would take a row past it is not bought, and the row is answered from the node
    /// that asked for it. Without a limit, the same predictions to the bit.
    pub fn predict_file_each_within(
        &self,
        path: &Path,
        budget: &Budget,
        each: &mut dyn FnMut(Prediction, usize),
    ) -> Result<usize, Error> {
        let (frame, lines) = self.frame_for(path)?;
        let rows = frame.len();
        for (row, &line) in lines.iter().enumerate() {
            let c = self
                .file
                .tree
                .classify_within(&frame, row, &self.file.prices, budget);
            each(
                Prediction {
                    line,
                    class: Some(ClassId(c.class)),
                    cost: Cost::new(c.test_cost).unwrap_or(Cost::ZERO),
                    measured: c.tests.iter().map(|&t| FeatureId(t as u32)).collect(),
                    probabilities: c.probabilities,
                },
                rows,
            );
        }
        Ok(rows)
    }
}

/// A model file of either kind, told apart by its `format`: a classifier of the
/// incremental learners (`csrl-classifier`, [`Model`]) or a tree of the test-cost family
/// (`csrl-cost-tree`, [`TreeModel`]).
#[derive(Clone, Debug, PartialEq)]
pub enum SavedModel {
    /// An incremental learner's model.
    Classifier(Model),
    /// A tree of the family.
    Tree(TreeModel),
}

impl SavedModel {
    /// Read a model file (a regular file of at most
    /// [`MAX_FILE_BYTES`](crate::MAX_FILE_BYTES)) of either format. A file that is not
    /// JSON, or whose format is `csrl-classifier`, is read as [`Model::load`] reads it;
    /// another format is refused, naming it.
    ///
    /// ```
    /// let dir = tempfile::tempdir().unwrap();
    /// let path = dir.path().join("m.json");
    /// std::fs::write(&path, r#"{"format": "zip", "version": 1}"#).unwrap();
    /// let err = cslearn::testcost::SavedModel::load(&path).unwrap_err().to_string();
    /// assert!(err.ends_with("m.json: key `format`: `zip` is not a model format `csrl predict` reads (csrl-classifier, csrl-cost-tree)"), "{err}");
    /// ```
    pub fn load(path: &Path) -> Result<SavedModel, Error> {
        let bytes = read_bounded(open_regular(path)?, path)?;
        let format = serde_json::from_slice::<Probe>(&bytes)
            .ok()
            .and_then(|p| p.format);
        match format {
            Some(serde_json::Value::String(f)) if f == TREE_MODEL_FORMAT => {
                TreeModel::from_json(&bytes, path).map(SavedModel::Tree)
            }
            Some(serde_json::Value::String(f)) if f != crate::MODEL_FORMAT => {
                Err(Error::BadModel {
                    path: path.to_path_buf(),
                    at: "key `format`".into(),
                    reason: format!(
                        "`{f}` is not a model format `csrl predict` reads ({}, {TREE_MODEL_FORMAT})",
                        crate::MODEL_FORMAT
                    ),
                })
            }
            _ => Model::from_json(&bytes, path).map(SavedModel::Classifier),
        }
    }
}

/// The first key of `original` that `reread` (the same file read and written back) does
/// not have: a key the types skipped. `at` is the path of keys so far.
fn unknown_key(
    original: &serde_json::Value,
    reread: &serde_json::Value,
    at: String,
) -> Option<String> {
    use serde_json::Value;
    let join = |key: &str| {
        if at.is_empty() {
            key.to_string()
        } else {
            format!("{at}.{key}")
        }
    };
    match (original, reread) {
        (Value::Object(a), Value::Object(b)) => a.iter().find_map(|(k, v)| match b.get(k) {
            None => Some(join(k)),
            Some(w) => unknown_key(v, w, join(k)),
        }),
        (Value::Array(a), Value::Array(b)) => a
            .iter()
            .zip(b)
            .enumerate()
            .find_map(|(i, (v, w))| unknown_key(v, w, format!("{at}[{i}]"))),
        _ => None,
    }
}

/// Every number of a saved tree in range: the learner, or `Err((where, what))`.
fn check(file: &TreeFile) -> Result<Method, (String, String)> {
    let s = |x: &str| x.to_string();
    let learner = Method::parse(&file.learner).map_err(|e| (s("key `learner`"), e.to_string()))?;
    let classes = file.classes.len();
    check_names(
        &file.classes,
        file.features.iter().map(|f| f.name.as_str()),
        &file.target,
    )?;
    for (i, f) in file.features.iter().enumerate() {
        let at = || format!("feature {i} (`{}`)", f.name);
        match (f.kind.as_str(), &f.values) {
            ("numeric", None) => {}
            ("nominal", Some(values)) => check_values(values).map_err(|what| (at(), what))?,
            ("numeric", Some(_)) => return Err((at(), s("a numeric feature has no `values`"))),
            ("nominal", None) => return Err((at(), s("a nominal feature needs `values`"))),
            (other, _) => {
                return Err((
                    at(),
                    format!("kind `{other}`: a feature is `numeric` or `nominal`"),
                ));
            }
        }
    }
    let prices = file
        .prices
        .clone()
        .checked()
        .map_err(|e| (s("key `prices`"), e.to_string()))?;
    if prices.len() != file.features.len() {
        return Err((
            s("key `prices`"),
            format!(
                "{} prices for {} features",
                prices.len(),
                file.features.len()
            ),
        ));
    }
    let shapes: Vec<FeatureShape<'_>> = file
        .features
        .iter()
        .map(|f| FeatureShape {
            name: &f.name,
            values: f.values.as_ref().map(Vec::len),
        })
        .collect();
    file.tree
        .check(&shapes, classes)
        .map_err(|fault| (fault.at, fault.reason))?;
    Ok(learner)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testcost::{FamilyParams, MisclassCosts, fit};

    /// A model of a small tree over a numeric and a nominal feature.
    fn model() -> TreeModel {
        let n = 30;
        let frame = Frame::new(
            vec!["x".into(), "colour".into()],
            vec![
                Column::Numeric((0..n).map(|i| f64::from(i % 10)).collect()),
                Column::Nominal {
                    values: vec!["red".into(), "blue".into(), "green".into()],
                    codes: (0..n).map(|i| (i % 3) as u32).collect(),
                },
            ],
            (0..n).map(|i| u32::from(i % 10 >= 5)).collect(),
            vec!["low".into(), "high".into()],
        )
        .unwrap();
        let prices = TestPrices::flat(&[2.0, 1.0]).unwrap();
        let mc = MisclassCosts::uniform(2, 50.0).unwrap();
        let rows: Vec<usize> = (0..frame.len()).collect();
        let fitted = fit(
            Method::Id3,
            &frame,
            &rows,
            &prices,
            &mc,
            &FamilyParams::default(),
            1,
        );
        TreeModel::new(Method::Id3, &frame, "y", Some(">0"), &fitted, &prices)
    }

    fn refusal(edit: impl FnOnce(&mut serde_json::Value)) -> String {
        let mut v: serde_json::Value = serde_json::from_str(&model().to_json()).unwrap();
        edit(&mut v);
        TreeModel::from_json(v.to_string().as_bytes(), "m.json")
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn a_model_reads_back_as_written_and_classifies_as_its_tree() {
        let m = model();
        assert!(m.tree().len() > 1, "the tree splits");
        let again = TreeModel::from_json(m.to_json().as_bytes(), "m.json").unwrap();
        assert_eq!(again, m);
        assert_eq!(again.learner(), Method::Id3);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("rows.csv");
        std::fs::write(&path, "colour,x,y\nred,2,no\nblue,8,\npurple,7,\n?,,\n").unwrap();
        let (frame, lines) = again.frame_for(&path).unwrap();
        assert_eq!(lines, [2, 3, 4, 5]);
        let Column::Nominal { values, codes } = frame.column(1) else {
            panic!("colour is nominal")
        };
        // A value never seen gets a code of its own, past the known ones.
        assert_eq!((values.len(), codes[2]), (4, 3));
        let mut seen = Vec::new();
        again
            .predict_file_each(&path, &mut |p, rows| {
                seen.push((p.line, p.class.map(|c| c.0), rows));
            })
            .unwrap();
        assert_eq!(seen[0], (2, Some(0), 4));
        assert_eq!(seen[1], (3, Some(1), 4));
        let both = SavedModel::load(&{
            let p = dir.path().join("m.json");
            std::fs::write(&p, m.to_json()).unwrap();
            p
        })
        .unwrap();
        assert_eq!(both, SavedModel::Tree(m));
    }

    #[test]
    fn every_number_out_of_range_is_refused_naming_where() {
        let cases: Vec<(String, &str)> = vec![
            (
                refusal(|v| v["version"] = 2.into()),
                "key `version`: version 2 is not supported",
            ),
            (
                refusal(|v| v["format"] = "csrl-classifier".into()),
                "key `format`",
            ),
            (
                refusal(|v| v["classes"] = serde_json::json!(["a"])),
                "but the model has 1",
            ),
            (
                refusal(|v| v["classes"] = serde_json::json!(["a", "a"])),
                "class 1: `a` appears twice",
            ),
            (
                refusal(|v| v["features"][1]["kind"] = "text".into()),
                "kind `text`",
            ),
            (
                refusal(|v| v["features"][0]["values"] = serde_json::json!(["1"])),
                "a numeric feature has no `values`",
            ),
            (
                refusal(|v| v["features"][1]["name"] = "x".into()),
                "the name appears twice",
            ),
            (
                refusal(|v| v["features"][0]["name"] = "y".into()),
                "the target column cannot be a feature",
            ),
            (
                refusal(|v| v["prices"]["tests"].as_array_mut().unwrap().truncate(1)),
                "1 prices for 2 features",
            ),
            (
                refusal(|v| v["tree"]["mc"]["classes"] = 3.into()),
                "key `tree.mc`",
            ),
            (
                refusal(|v| v["tree"]["nodes"][0]["label"] = 7.into()),
                "tree node 0: label 7",
            ),
            (
                refusal(|v| v["tree"]["nodes"][0]["weights"] = serde_json::json!([1.0, -1.0])),
                "tree node 0: a weight",
            ),
            (
                refusal(|v| v["tree"]["nodes"] = serde_json::json!([])),
                "no nodes",
            ),
            (
                refusal(|v| v["tree"]["extra"] = 1.into()),
                "key `tree.extra`: not a key",
            ),
            (
                refusal(|v| {
                    let split = v["tree"]["nodes"][0]["split"].as_object_mut().unwrap();
                    let (_, inner) = split.iter_mut().next().unwrap();
                    inner["feature"] = 9.into();
                }),
                "tree node 0: a test of feature 9",
            ),
            (
                refusal(|v| {
                    let split = v["tree"]["nodes"][0]["split"].as_object_mut().unwrap();
                    let (_, inner) = split.iter_mut().next().unwrap();
                    inner["children"][0] = 0.into();
                }),
                "tree node 0: child 0",
            ),
        ];
        for (message, expected) in cases {
            assert!(message.starts_with("m.json: "), "{message}");
            assert!(
                message.contains(expected),
                "`{expected}` not in `{message}`"
            );
        }
    }
}
