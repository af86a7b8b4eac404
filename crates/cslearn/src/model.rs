//! A learned classifier saved to a file, and new rows classified by it ([`Model`]).

use std::io::Read;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::dataset::{
    Dataset, check_totals, is_missing, open_regular, parse_number, read_bounded, read_table,
};
use crate::error::Error;
use crate::example::{Example, Library};
use crate::indexed::{cs_id3_indexed, id3_indexed};
use crate::learner::{Classified, cs_ibl};
use crate::predict::Votes;
use crate::stream::LearnerKind;
use crate::types::{ClassId, Cost, FeatureCosts, FeatureId, Value};
use rand::SeedableRng;

/// The `format` of a model file.
///
/// ```
/// assert_eq!(cslearn::MODEL_FORMAT, "csrl-classifier");
/// ```
pub const MODEL_FORMAT: &str = "csrl-classifier";

/// The version of the model file format this crate writes and reads.
///
/// ```
/// assert_eq!(cslearn::MODEL_VERSION, 1);
/// ```
pub const MODEL_VERSION: u32 = 1;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum Kind {
    CsId3,
    CsIbl,
    Id3,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FeatureEntry {
    name: String,
    cost: Cost,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    cuts: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    values: Option<Vec<String>>,
}

impl FeatureEntry {
    /// How many values the feature has.
    fn value_count(&self) -> usize {
        match (&self.cuts, &self.values) {
            (Some(cuts), _) => cuts.len() + 1,
            (None, Some(values)) => values.len(),
            (None, None) => 0,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ExampleEntry {
    class: u32,
    values: Vec<(u32, u32)>,
}

/// The file's contents, as read. A [`Model`] keeps all but the library here (as a
/// [`Library`] of its own), and writes the file through [`FileView`].
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    format: String,
    version: u32,
    learner: Kind,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    tolerance: Option<u32>,
    target: String,
    classes: Vec<String>,
    features: Vec<FeatureEntry>,
    library: Vec<ExampleEntry>,
}

/// A model as the file writes it, borrowing every part: no copy of the library.
#[derive(Serialize)]
struct FileView<'a> {
    format: &'a str,
    version: u32,
    learner: Kind,
    #[serde(skip_serializing_if = "Option::is_none")]
    tolerance: Option<u32>,
    target: &'a str,
    classes: &'a [String],
    features: &'a [FeatureEntry],
    library: LibraryView<'a>,
}

struct LibraryView<'a>(&'a Library);

impl Serialize for LibraryView<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.0.iter().map(ExampleView))
    }
}

struct ExampleView<'a>(&'a Example);

impl Serialize for ExampleView<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut out = serializer.serialize_struct("Example", 2)?;
        out.serialize_field("class", &self.0.class().0)?;
        let pairs: Vec<(u32, u32)> = self.0.pairs().iter().map(|&(f, v)| (f.0, v.0)).collect();
        out.serialize_field("values", &pairs)?;
        out.end()
    }
}

/// Only the keys that say what a file is; the others are skipped unread. Shared by the
/// readers of both model formats (this one and `testcost`'s saved trees).
#[derive(Deserialize)]
pub(crate) struct Probe {
    pub(crate) format: Option<serde_json::Value>,
    pub(crate) version: Option<serde_json::Value>,
}

impl Probe {
    /// `Err((where, what))` unless the file's `version` is `expected`.
    pub(crate) fn check_version(&self, expected: u32) -> Result<(), (String, String)> {
        match self.version.as_ref().and_then(serde_json::Value::as_u64) {
            Some(v) if v == u64::from(expected) => Ok(()),
            Some(v) => Err((
                "key `version`".into(),
                format!("version {v} is not supported (this build reads version {expected})"),
            )),
            None => Err((
                "key `version`".into(),
                "missing or not a whole number".into(),
            )),
        }
    }
}

/// A learned classifier: the learner, the columns it reads (names, prices, how cells
/// become values), the class names and the library. Saved as a versioned JSON file
/// ([`MODEL_FORMAT`], [`MODEL_VERSION`]), read back with every number checked, and used to
/// classify new rows.
///
///
/// # The model file (format `csrl-classifier`, version 1)
///
/// One JSON object:
///
/// | key | what |
/// |---|---|
/// | `format` | always `"csrl-classifier"` |
/// | `version` | always `1`; a reader refuses any other |
/// | `learner` | `"cs-id3"`, `"cs-ibl"` or `"id3"` |
/// | `tolerance` | CS-IBL only (and required there): the most wrong values tolerated |
/// | `target` | the name of the class column it was learned from |
/// | `classes` | the class names, indexed by class number |
/// | `features` | one object per feature, in feature order: `name`, `cost` (finite, not negative) and either `cuts` (a numeric column: the ascending cut points of its bins, a value equal to a cut falling in the lower bin) or `values` (a nominal column: the distinct texts, indexed by value number) |
/// | `library` | the learned examples: `class` (a class number) and `values`, pairs `[feature, value]` in ascending feature order, for the features measured for it |
///
/// Unknown keys are refused, and so is every number out of range (a class, feature or
/// value that does not exist), naming where it is.
///
/// # Classifying new rows
///
/// [`Model::predict`] reads a CSV table with a header. Columns are matched by name: every
/// feature of the model must be a column (in any order); other columns, the target
/// included, are ignored. A numeric feature's cell is binned by the model's cut points
/// and must be a number; a nominal feature's cell that the model never saw is a value of
/// its own, which no example has. Empty cells and `?` are missing. Each row is classified
/// as the learner classifies (measuring, and paying for, only what it asks for), without
/// learning.
///
/// ```
/// use cslearn::{Dataset, DatasetOptions, LearnerKind, Model};
/// let data = "a,b,t\np,x,n\np,y,n\nq,x,y\nq,y,y\np,x,n\nq,y,y\np,y,n\nq,x,y\n";
/// let ds = Dataset::from_readers(data.as_bytes(), "d.csv", "feature,cost\na,1\nb,5\n".as_bytes(), "c.csv", &DatasetOptions::new("t")).unwrap();
/// let (_, library) = cslearn::stream_dataset_keeping(&ds, LearnerKind::CsId3, 1, &mut |_, _| {});
/// let model = Model::new(&ds, LearnerKind::CsId3, library);
/// let again = Model::from_json(model.to_json().as_bytes(), "m.json").unwrap();
/// assert_eq!(again, model);
/// let rows = again.predict("b,a\ny,q\nx,p\n".as_bytes(), "new.csv", &mut |_, _| {}).unwrap();
/// assert_eq!(again.class_name(rows[0].class.unwrap()), Some("y"));
/// assert_eq!(rows[1].cost.get(), 1.0); // only `a` measured
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// Everything but the library, which is `library` (`file.library` stays empty).
    file: File,
    costs: FeatureCosts,
    library: Library,
}

/// One row classified by a [`Model`].
///
/// ```
/// let p = cslearn::Prediction {
///     line: 2, class: None, cost: cslearn::Cost::ZERO, measured: vec![],
///     probabilities: vec![0.5, 0.5],
/// };
/// assert_eq!(p.line, 2);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Prediction {
    /// The row's line in the file (the header is line 1).
    pub line: u64,
    /// The class predicted (none for a model with an empty library).
    pub class: Option<ClassId>,
    /// What the measurements cost.
    pub cost: Cost,
    /// The features measured, in the order they were measured.
    pub measured: Vec<FeatureId>,
    /// The probability of each of the model's classes (indexed by class, summing to 1),
    /// by Laplace's rule: for an incremental learner's model over the examples its
    /// prediction went by ([`Votes`](crate::Votes)), for a tree over the node that
    /// answered ([`Classification::probabilities`](crate::testcost::Classification::probabilities)).
    pub probabilities: Vec<f64>,
}

impl Model {
    /// The model of a learner of `kind` that learned `library` from `dataset`.
    ///
    /// ```
    /// use cslearn::{Dataset, DatasetOptions, LearnerKind, Library, Model};
    /// let ds = Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &DatasetOptions::new("t")).unwrap();
    /// let model = Model::new(&ds, LearnerKind::CsIbl { tolerance: 1 }, Library::new());
    /// assert_eq!(model.learner(), LearnerKind::CsIbl { tolerance: 1 });
    /// ```
    pub fn new(dataset: &Dataset, kind: LearnerKind, library: Library) -> Model {
        let (learner, tolerance) = match kind {
            LearnerKind::CsId3 => (Kind::CsId3, None),
            LearnerKind::CsIbl { tolerance } => (Kind::CsIbl, Some(tolerance)),
            LearnerKind::Id3 => (Kind::Id3, None),
        };
        let features = (0..dataset.feature_count())
            .map(|f| {
                let id = FeatureId(f as u32);
                let cuts = dataset.cut_points(id).map(<[f64]>::to_vec);
                let values = cuts.is_none().then(|| {
                    (0u32..)
                        .map_while(|v| dataset.value_name(id, Value(v)).map(str::to_string))
                        .collect()
                });
                FeatureEntry {
                    name: dataset.feature_name(id).unwrap_or_default().to_string(),
                    cost: dataset.costs().as_slice()[f],
                    cuts,
                    values,
                }
            })
            .collect();
        let file = File {
            format: MODEL_FORMAT.to_string(),
            version: MODEL_VERSION,
            learner,
            tolerance,
            target: dataset.target().to_string(),
            classes: (0..dataset.class_count() as u32)
                .map(|c| {
                    dataset
                        .class_name(ClassId(c))
                        .unwrap_or_default()
                        .to_string()
                })
                .collect(),
            features,
            library: Vec::new(),
        };
        Model {
            costs: dataset.costs().clone(),
            library,
            file,
        }
    }

    /// The model as the text of a model file (compact JSON on one line, ending in a
    /// newline).
    ///
    /// ```
    /// # use cslearn::*;
    /// # let ds = Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &DatasetOptions::new("t")).unwrap();
    /// let text = Model::new(&ds, LearnerKind::CsId3, Library::new()).to_json();
    /// assert!(text.starts_with("{\"format\":\"csrl-classifier\",\"version\":1,"));
    /// ```
    pub fn to_json(&self) -> String {
        let f = &self.file;
        let view = FileView {
            format: &f.format,
            version: f.version,
            learner: f.learner,
            tolerance: f.tolerance,
            target: &f.target,
            classes: &f.classes,
            features: &f.features,
            library: LibraryView(&self.library),
        };
        // Compact: a large library takes about 20 bytes an example.
        let mut text = serde_json::to_string(&view).unwrap_or_default();
        text.push('\n');
        text
    }

    /// Read a model file from its bytes, checking every number; `path` is for messages.
    ///
    /// ```
    /// let err = cslearn::Model::from_json(br#"{"format": "other"}"#, "m.json").unwrap_err();
    /// assert_eq!(err.to_string(), "m.json: not a csrl-classifier model file (its format is `other`)");
    /// ```
    pub fn from_json(bytes: &[u8], path: impl AsRef<Path>) -> Result<Model, Error> {
        let path = path.as_ref();
        let bad = |at: String, reason: String| Error::BadModel {
            path: path.to_path_buf(),
            at,
            reason,
        };
        // The format and version first, so that another kind of file or a newer version
        // is named as such rather than as a missing key.
        let probe: Probe = serde_json::from_slice(bytes).map_err(|e| {
            let first = bytes.iter().find(|b| !b.is_ascii_whitespace());
            if e.classify() == serde_json::error::Category::Data && first != Some(&b'{') {
                bad("the top level".into(), "not a JSON object".into())
            } else {
                json_error(path, &e)
            }
        })?;
        match &probe.format {
            Some(serde_json::Value::String(f)) if f == MODEL_FORMAT => {}
            Some(serde_json::Value::String(f)) => {
                return Err(Error::NotAModel {
                    path: path.to_path_buf(),
                    format: f.clone(),
                });
            }
            _ => {
                return Err(bad(
                    "key `format`".into(),
                    format!("missing or not a string; a model file says \"{MODEL_FORMAT}\""),
                ));
            }
        }
        probe
            .check_version(MODEL_VERSION)
            .map_err(|(at, reason)| bad(at, reason))?;
        // Read again as a model, for the line and column of what is wrong.
        let mut file: File = serde_json::from_slice(bytes).map_err(|e| json_error(path, &e))?;
        check(&file).map_err(|(at, reason)| bad(at, reason))?;
        let costs = FeatureCosts::new(file.features.iter().map(|f| f.cost).collect());
        let library = std::mem::take(&mut file.library)
            .into_iter()
            .map(|e| {
                Example::from_pairs(
                    e.values.iter().map(|&(f, v)| (FeatureId(f), Value(v))),
                    ClassId(e.class),
                )
            })
            .collect();
        Ok(Model {
            file,
            costs,
            library,
        })
    }

    /// Read a model file: a regular file of at most [`MAX_FILE_BYTES`](crate::MAX_FILE_BYTES).
    ///
    /// ```
    /// let err = cslearn::Model::load("no/such/model.json".as_ref()).unwrap_err();
    /// assert!(matches!(err, cslearn::Error::Io { .. }));
    /// ```
    pub fn load(path: &Path) -> Result<Model, Error> {
        let bytes = read_bounded(open_regular(path)?, path)?;
        Model::from_json(&bytes, path)
    }

    /// The learner the model was learned by.
    ///
    /// ```
    /// # use cslearn::*;
    /// # let ds = Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &DatasetOptions::new("t")).unwrap();
    /// assert_eq!(Model::new(&ds, LearnerKind::Id3, Library::new()).learner(), LearnerKind::Id3);
    /// ```
    pub fn learner(&self) -> LearnerKind {
        match self.file.learner {
            Kind::CsId3 => LearnerKind::CsId3,
            Kind::CsIbl => LearnerKind::CsIbl {
                tolerance: self.file.tolerance.unwrap_or_default(),
            },
            Kind::Id3 => LearnerKind::Id3,
        }
    }

    /// The learned examples.
    ///
    /// ```
    /// # use cslearn::*;
    /// # let ds = Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &DatasetOptions::new("t")).unwrap();
    /// assert!(Model::new(&ds, LearnerKind::CsId3, Library::new()).library().is_empty());
    /// ```
    pub fn library(&self) -> &Library {
        &self.library
    }

    /// The name of a class.
    ///
    /// ```
    /// # use cslearn::*;
    /// # let ds = Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &DatasetOptions::new("t")).unwrap();
    /// assert_eq!(Model::new(&ds, LearnerKind::CsId3, Library::new()).class_name(ClassId(0)), Some("x"));
    /// ```
    pub fn class_name(&self, class: ClassId) -> Option<&str> {
        self.file.classes.get(class.0 as usize).map(String::as_str)
    }

    /// The column name of a feature.
    ///
    /// ```
    /// # use cslearn::*;
    /// # let ds = Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &DatasetOptions::new("t")).unwrap();
    /// assert_eq!(Model::new(&ds, LearnerKind::CsId3, Library::new()).feature_name(FeatureId(0)), Some("a"));
    /// ```
    pub fn feature_name(&self, feature: FeatureId) -> Option<&str> {
        self.file
            .features
            .get(feature.index())
            .map(|f| f.name.as_str())
    }

    /// Classify every row of a CSV table (see [`Model`] for how columns and cells are
    /// read), without learning; `name` is for messages, and `progress(done, total)` is
    /// called before each row.
    ///
    /// ```
    /// # use cslearn::*;
    /// # let ds = Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &DatasetOptions::new("t")).unwrap();
    /// let model = Model::new(&ds, LearnerKind::CsId3, Library::new());
    /// let err = model.predict("b\n1\n".as_bytes(), "new.csv", &mut |_, _| {}).unwrap_err();
    /// assert_eq!(err.to_string(), "new.csv: no column `a`, which the model reads (columns: b)");
    /// ```
    pub fn predict(
        &self,
        data: impl Read,
        name: impl AsRef<Path>,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Vec<Prediction>, Error> {
        let mut out = Vec::new();
        self.predict_each(data, name, &mut |row, total| {
            progress(out.len(), total);
            out.push(row);
        })?;
        Ok(out)
    }

    /// [`predict`](Model::predict), handing each row's prediction to `each` with the
    /// number of rows, in file order, instead of keeping them: memory does not grow with
    /// the predictions. The whole table is read and checked before the first row is
    /// classified, so an error comes before any prediction. Returns the number of rows.
    ///
    /// ```
    /// # use cslearn::*;
    /// # let ds = Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &DatasetOptions::new("t")).unwrap();
    /// # let (_, library) = cslearn::stream_dataset_keeping(&ds, LearnerKind::CsId3, 1, &mut |_, _| {});
    /// let model = Model::new(&ds, LearnerKind::CsId3, library);
    /// let mut lines = Vec::new();
    /// let n = model.predict_each("a\n1\n2\n".as_bytes(), "new.csv", &mut |p, _| lines.push(p.line)).unwrap();
    /// assert_eq!((n, lines), (2, vec![2, 3]));
    /// ```
    pub fn predict_each(
        &self,
        data: impl Read,
        name: impl AsRef<Path>,
        each: &mut dyn FnMut(Prediction, usize),
    ) -> Result<usize, Error> {
        let path = name.as_ref();
        let (rows, lines) = self.encode(data, path)?;
        let n = self.file.features.len();
        let total = lines.len();
        let classes = self.file.classes.len();
        let mut classify = self.classifier();
        for (i, line) in lines.into_iter().enumerate() {
            let (c, votes, measured) = classify(&rows[i * n..(i + 1) * n]);
            let row = Prediction {
                line,
                class: c.class,
                cost: c.cost,
                measured,
                probabilities: votes.probabilities(classes),
            };
            each(row, total);
        }
        Ok(total)
    }

    /// [`predict_each`](Model::predict_each) on a regular file of at most
    /// [`MAX_FILE_BYTES`](crate::MAX_FILE_BYTES).
    ///
    /// ```
    /// # use cslearn::*;
    /// # let ds = Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &DatasetOptions::new("t")).unwrap();
    /// let model = Model::new(&ds, LearnerKind::CsId3, Library::new());
    /// assert!(model.predict_file_each("no/such.csv".as_ref(), &mut |_, _| {}).is_err());
    /// ```
    pub fn predict_file_each(
        &self,
        path: &Path,
        each: &mut dyn FnMut(Prediction, usize),
    ) -> Result<usize, Error> {
        self.predict_each(open_regular(path)?, path, each)
    }

    /// The rows of a table as dense rows of values in feature order, and their lines.
    fn encode(
        &self,
        data: impl Read,
        path: &Path,
    ) -> Result<(Vec<Option<Value>>, Vec<u64>), Error> {
        let table = read_table(data, path)?;
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
        let missing: Vec<String> = self
            .file
            .features
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
        let columns: Vec<usize> = self
            .file
            .features
            .iter()
            .map(|f| index[f.name.as_str()])
            .collect();
        let nominal: Vec<Option<std::collections::BTreeMap<&str, u32>>> = self
            .file
            .features
            .iter()
            .map(|f| {
                f.values.as_ref().map(|vs| {
                    vs.iter()
                        .enumerate()
                        .map(|(i, v)| (v.as_str(), i as u32))
                        .collect()
                })
            })
            .collect();
        // Every total printed must be a true one.
        check_totals(&self.costs, table.len(), path)?;
        let mut rows = Vec::with_capacity(table.len() * columns.len());
        let mut lines = Vec::with_capacity(table.len());
        for (line, record) in table.records() {
            for (f, &c) in columns.iter().enumerate() {
                let cell = &record[c];
                let feature = &self.file.features[f];
                let value = if is_missing(cell) {
                    None
                } else if let Some(cuts) = &feature.cuts {
                    let x = parse_number(cell).ok_or_else(|| Error::NotANumber {
                        path: path.to_path_buf(),
                        line,
                        column: feature.name.clone(),
                        text: cell.to_string(),
                    })?;
                    Some(Value(cuts.partition_point(|&cut| cut < x) as u32))
                } else {
                    let known = nominal[f].as_ref();
                    // A text never seen: a value of its own, one past the known ones.
                    let unseen = feature.value_count() as u32;
                    Some(Value(
                        known.and_then(|k| k.get(cell).copied()).unwrap_or(unseen),
                    ))
                };
                rows.push(value);
            }
            lines.push(line);
        }
        Ok((rows, lines))
    }

    /// A learner of the model's kind holding its library, as a function from a row to its
    /// classification and the features measured.
    #[expect(
        clippy::type_complexity,
        reason = "a boxed classifier closure: its type is its signature"
    )]
    fn classifier(
        &self,
    ) -> Box<dyn FnMut(&[Option<Value>]) -> (Classified, Votes, Vec<FeatureId>) + '_> {
        let costs = self.costs.clone();
        let library = self.library.clone();
        let measured = |ledger: &crate::Ledger| ledger.measured().iter().map(|&(f, _)| f).collect();
        match self.learner() {
            LearnerKind::CsId3 => {
                let mut learner = cs_id3_indexed(costs).with_library(library);
                Box::new(move |row| {
                    let (c, votes) = learner.classify_with_votes(row);
                    (c, votes, measured(learner.ledger()))
                })
            }
            LearnerKind::Id3 => {
                // Classifying draws nothing: the generator is only for discrimination,
                // which happens only in learning.
                let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(0);
                let mut learner = id3_indexed(costs, rng).with_library(library);
                Box::new(move |row| {
                    let (c, votes) = learner.classify_with_votes(row);
                    (c, votes, measured(learner.ledger()))
                })
            }
            LearnerKind::CsIbl { tolerance } => {
                let mut learner = cs_ibl(costs, tolerance);
                *learner.library_mut() = library;
                Box::new(move |row| {
                    let (c, votes) = learner.classify_with_votes(row);
                    (c, votes, measured(learner.ledger()))
                })
            }
        }
    }
}

/// A JSON syntax or type error, with its line and column.
pub(crate) fn json_error(path: &Path, e: &serde_json::Error) -> Error {
    let text = e.to_string();
    let reason = text
        .rsplit_once(" at line ")
        .map_or(text.as_str(), |(r, _)| r)
        .to_string();
    // A text that is not JSON at all (a CSV file, say) is said to be so.
    let reason = match e.classify() {
        serde_json::error::Category::Syntax | serde_json::error::Category::Eof => {
            format!("not valid JSON ({reason})")
        }
        _ => reason,
    };
    Error::BadModel {
        path: path.to_path_buf(),
        at: format!("line {}, column {}", e.line(), e.column()),
        reason,
    }
}

/// The names of a model file (of either kind) are sound: at least one class, each
/// named once; at least one feature, each with a name of its own that is not the
/// `target`'s. `Err((where, what))`.
pub(crate) fn check_names<'a>(
    classes: &[String],
    features: impl ExactSizeIterator<Item = &'a str>,
    target: &str,
) -> Result<(), (String, String)> {
    let s = |x: &str| x.to_string();
    if classes.is_empty() {
        return Err((s("key `classes`"), s("no classes")));
    }
    let mut names = std::collections::BTreeSet::new();
    for (i, c) in classes.iter().enumerate() {
        if !names.insert(c.as_str()) {
            return Err((format!("class {i}"), format!("`{c}` appears twice")));
        }
    }
    if features.len() == 0 {
        return Err((s("key `features`"), s("no features")));
    }
    let mut names = std::collections::BTreeSet::new();
    for (i, name) in features.enumerate() {
        let at = || format!("feature {i} (`{name}`)");
        if name.is_empty() {
            return Err((format!("feature {i}"), s("an empty name")));
        }
        if name == target {
            return Err((at(), s("the target column cannot be a feature")));
        }
        if !names.insert(name) {
            return Err((at(), s("the name appears twice")));
        }
    }
    Ok(())
}

/// A nominal feature's values, each once: `Err(what)` naming the first repeated.
pub(crate) fn check_values(values: &[String]) -> Result<(), String> {
    let mut seen = std::collections::BTreeSet::new();
    match values.iter().find(|v| !seen.insert(v.as_str())) {
        Some(v) => Err(format!("value `{v}` appears twice")),
        None => Ok(()),
    }
}

/// Every number of a model file in range, every name once: `Err((where, what))`.
fn check(file: &File) -> Result<(), (String, String)> {
    let s = |x: &str| x.to_string();
    match (file.learner, file.tolerance) {
        (Kind::CsIbl, None) => return Err((s("key `tolerance`"), s("a cs-ibl model needs one"))),
        (Kind::CsId3 | Kind::Id3, Some(_)) => {
            return Err((s("key `tolerance`"), s("only a cs-ibl model has one")));
        }
        _ => {}
    }
    check_names(
        &file.classes,
        file.features.iter().map(|f| f.name.as_str()),
        &file.target,
    )?;
    for (i, f) in file.features.iter().enumerate() {
        let at = || format!("feature {i} (`{}`)", f.name);
        match (&f.cuts, &f.values) {
            (Some(cuts), None) => {
                if let Some(w) = cuts.windows(2).position(|w| w[0] >= w[1]) {
                    return Err((at(), format!("cut points not ascending at cut {}", w + 1)));
                }
            }
            (None, Some(values)) => check_values(values).map_err(|what| (at(), what))?,
            _ => return Err((at(), s("needs exactly one of `cuts` and `values`"))),
        }
    }
    if file.library.is_empty() {
        // Never saved so (a stream learns at least one example): a model that could only
        // abstain.
        return Err((
            s("key `library`"),
            s("no examples: the model could not classify"),
        ));
    }
    for (i, e) in file.library.iter().enumerate() {
        let at = || format!("library example {i}");
        if e.class as usize >= file.classes.len() {
            let n = file.classes.len();
            return Err((
                at(),
                format!("class {} does not exist (the model has {n})", e.class),
            ));
        }
        for (k, &(f, v)) in e.values.iter().enumerate() {
            let Some(feature) = file.features.get(f as usize) else {
                let n = file.features.len();
                return Err((
                    at(),
                    format!("feature {f} does not exist (the model has {n})"),
                ));
            };
            if k > 0 && e.values[k - 1].0 >= f {
                return Err((at(), s("features not in ascending order, or one twice")));
            }
            if v as usize >= feature.value_count() {
                let n = feature.value_count();
                return Err((
                    at(),
                    format!(
                        "value {v} of feature {f} (`{}`) does not exist (it has {n})",
                        feature.name
                    ),
                ));
            }
        }
    }
    Ok(())
}
