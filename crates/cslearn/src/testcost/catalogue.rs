//! Data sets described by a manifest (`data/uci/datasets.toml`): where their files are,
//! how to read them, and their test prices where Turney's files give them.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::data::{Frame, FrameSpec, read_rows};
use super::prices::{TestPrices, TurneyExtra};
use crate::Error;
use crate::dataset::Condition;

/// How to read one data set; the keys of a `[[dataset]]` table of the manifest (its
/// header comment documents each).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Source {
    /// The short name command lines use.
    pub name: String,
    /// Its row's name in Esmeir's published tables, if it has one.
    #[serde(default)]
    pub published: Option<String>,
    /// The data files, relative to the manifest's folder, concatenated.
    pub files: Vec<String>,
    /// A name for every column of the files.
    pub columns: Vec<String>,
    /// The class column.
    pub target: String,
    /// Two classes, `yes` where the target satisfies this condition.
    #[serde(default)]
    pub positive_if: Option<String>,
    /// Columns summed into a new numeric target column called `target`.
    #[serde(default)]
    pub target_sum: Vec<String>,
    /// Columns that are not features.
    #[serde(default)]
    pub ignore: Vec<String>,
    /// Number-coded columns that are categories.
    #[serde(default)]
    pub nominal: Vec<String>,
    /// Cells that mean "missing".
    #[serde(default)]
    pub missing: Vec<String>,
    /// Lines starting with this are not data.
    #[serde(default)]
    pub skip_prefix: String,
    /// Turney's cost files, without their extension.
    #[serde(default)]
    pub costs: Option<String>,
    /// More `.expense` lines.
    #[serde(default)]
    pub extra_prices: String,
    /// More `.group` lines.
    #[serde(default)]
    pub extra_groups: String,
    /// Whether the data set is one of the benchmark's ([`Catalogue::benchmark`]); true when
    /// the manifest does not say.
    #[serde(default = "in_the_benchmark")]
    pub benchmark: bool,
    /// Every test costs 1: a caller that would draw random prices takes
    /// [`TestPrices::unit`] instead (one assignment, since every draw would be the same).
    #[serde(default)]
    pub unit_prices: bool,
}

/// A data set of the manifest is one of the benchmark's unless it says `benchmark = false`.
fn in_the_benchmark() -> bool {
    true
}

/// The data sets of a manifest.
///
/// ```
/// let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
/// let catalogue = cslearn::testcost::Catalogue::read(&root.join("datasets.toml")).unwrap();
/// let heart = catalogue.load("heart").unwrap();
/// assert_eq!((heart.frame.len(), heart.frame.class_count()), (303, 2));
/// assert!((heart.turney.unwrap().total() - 323.97).abs() < 1e-9);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Catalogue {
    root: PathBuf,
    sources: Vec<Source>,
}

/// A data set read: its objects, and its prices if Turney's files give them.
#[derive(Clone, Debug, PartialEq)]
pub struct Loaded {
    /// The objects.
    pub frame: Frame,
    /// Turney's prices, with groups and discounts.
    pub turney: Option<TestPrices>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    dataset: Vec<Source>,
}

impl Catalogue {
    /// Reads a manifest; the data files are found relative to its folder.
    ///
    /// ```
    /// let err = cslearn::testcost::Catalogue::read(std::path::Path::new("no/such.toml")).unwrap_err();
    /// assert!(err.to_string().contains("no/such.toml"));
    /// ```
    pub fn read(manifest: &Path) -> Result<Catalogue, Error> {
        // A FIFO or a device is refused unread, and a file is read only so far.
        let file = crate::dataset::open_regular(manifest)?;
        let bytes = crate::dataset::read_bounded(file, manifest)?;
        let text = String::from_utf8(bytes).map_err(|e| Error::BadInput {
            path: manifest.to_path_buf(),
            at: format!("byte {}", e.utf8_error().valid_up_to()),
            reason: "not UTF-8 text".into(),
        })?;
        let file: File = toml::from_str(&text).map_err(|e| Error::BadInput {
            path: manifest.to_path_buf(),
            at: e
                .span()
                .map(|s| format!("line {}", 1 + text[..s.start].matches('\n').count()))
                .unwrap_or_else(|| "the file".into()),
            reason: e.message().to_string(),
        })?;
        for (i, s) in file.dataset.iter().enumerate() {
            if file.dataset[..i].iter().any(|o| o.name == s.name) {
                return Err(Error::BadInput {
                    path: manifest.to_path_buf(),
                    at: format!("data set `{}`", s.name),
                    reason: "a second data set of this name".into(),
                });
            }
            if s.files.is_empty() {
                return Err(Error::BadInput {
                    path: manifest.to_path_buf(),
                    at: format!("data set `{}`", s.name),
                    reason: "`files` is empty: a data set needs at least one file".into(),
                });
            }
        }
        Ok(Catalogue {
            root: manifest.parent().unwrap_or(Path::new(".")).to_path_buf(),
            sources: file.dataset,
        })
    }

    /// Every data set, in the manifest's order.
    ///
    /// ```
    /// let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
    /// let catalogue = cslearn::testcost::Catalogue::read(&root.join("datasets.toml")).unwrap();
    /// assert!(catalogue.sources().iter().any(|s| s.name == "iris"));
    /// ```
    pub fn sources(&self) -> &[Source] {
        &self.sources
    }

    /// The benchmark's data sets, in the manifest's order: every one but those the manifest
    /// marks `benchmark = false` (kept for budgets and curves, such as `spambase`). What
    /// `cargo xtask testcost` runs when no data set is named.
    ///
    /// ```
    /// let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
    /// let catalogue = cslearn::testcost::Catalogue::read(&root.join("datasets.toml")).unwrap();
    /// let benchmark: Vec<&str> = catalogue.benchmark().map(|s| s.name.as_str()).collect();
    /// assert_eq!(benchmark.len(), 18);
    /// assert!(benchmark.contains(&"iris") && !benchmark.contains(&"spambase"));
    /// ```
    pub fn benchmark(&self) -> impl Iterator<Item = &Source> {
        self.sources.iter().filter(|s| s.benchmark)
    }

    /// The data set called `name`, read.
    ///
    /// ```
    /// let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
    /// let catalogue = cslearn::testcost::Catalogue::read(&root.join("datasets.toml")).unwrap();
    /// assert!(catalogue.load("nope").unwrap_err().to_string().contains("iris"));
    /// ```
    pub fn load(&self, name: &str) -> Result<Loaded, Error> {
        let source = self
            .sources
            .iter()
            .find(|s| s.name == name)
            .ok_or_else(|| Error::Invalid {
                what: format!("data set `{name}`"),
                reason: format!(
                    "not in the manifest (data sets: {})",
                    self.sources
                        .iter()
                        .map(|s| s.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            })?;
        source.load(&self.root)
    }
}

impl Source {
    /// Reads this data set, its files relative to `root`.
    ///
    /// ```
    /// let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
    /// let catalogue = cslearn::testcost::Catalogue::read(&root.join("datasets.toml")).unwrap();
    /// let flare = catalogue.sources().iter().find(|s| s.name == "flare").unwrap();
    /// let loaded = flare.load(&root).unwrap();
    /// assert_eq!(loaded.frame.class_totals().iter().sum::<usize>(), 1066);
    /// ```
    pub fn load(&self, root: &Path) -> Result<Loaded, Error> {
        let mut rows = Vec::new();
        for file in &self.files {
            rows.extend(read_rows(
                &root.join(file),
                self.columns.len(),
                &self.skip_prefix,
            )?);
        }
        let mut columns = self.columns.clone();
        let mut spec = FrameSpec::new(self.target.clone())
            .ignore(self.ignore.iter().cloned())
            .nominal(self.nominal.iter().cloned())
            .missing(self.missing.iter().cloned());
        let source_name = root.join(&self.files[0]).display().to_string();
        if !self.target_sum.is_empty() {
            let at: Vec<usize> = self
                .target_sum
                .iter()
                .map(|c| {
                    columns
                        .iter()
                        .position(|n| n == c)
                        .ok_or_else(|| Error::BadInput {
                            path: source_name.clone().into(),
                            at: format!("data set `{}`", self.name),
                            reason: format!("target_sum names `{c}`, which is not a column"),
                        })
                })
                .collect::<Result<_, _>>()?;
            for (i, row) in rows.iter_mut().enumerate() {
                let mut sum = 0.0;
                for &c in &at {
                    sum += row[c].parse::<f64>().map_err(|_| Error::BadInput {
                        path: source_name.clone().into(),
                        at: format!("row {}", i + 1),
                        reason: format!("`{}` in column `{}` is not a number", row[c], columns[c]),
                    })?;
                }
                row.push(sum.to_string());
            }
            columns.push("target".into());
            spec = spec.ignore(self.target_sum.iter().cloned());
        }
        let mut frame = Frame::from_cells(&source_name, &columns, &rows, &spec)?;
        if let Some(expr) = &self.positive_if {
            frame = frame.binarise(expr)?;
        }
        let turney = match &self.costs {
            None => None,
            Some(base) => Some(TestPrices::read_turney(
                &root.join(base),
                frame.names(),
                &TurneyExtra {
                    prices: self.extra_prices.clone(),
                    groups: self.extra_groups.clone(),
                },
            )?),
        };
        Ok(Loaded { frame, turney })
    }
}

impl Frame {
    /// Two classes, `no` and `yes`: `yes` for the objects whose class name satisfies
    /// `expr` (`>0`, `>=3`, `==sick`, `!=none`; numbers compare as numbers).
    ///
    /// ```
    /// # use cslearn::testcost::{Column, Frame};
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0, 1.0, 2.0])],
    ///     vec![0, 1, 2], vec!["0".into(), "1".into(), "4".into()]).unwrap();
    /// let two = frame.binarise(">0").unwrap();
    /// assert_eq!((two.classes(), two.class_names()), (&[0, 1, 1][..], &["no".to_string(), "yes".to_string()][..]));
    /// assert!(frame.binarise(">x").is_err());
    /// ```
    pub fn binarise(&self, expr: &str) -> Result<Frame, Error> {
        let condition = Condition::parse(expr)?;
        let map = self
            .class_names()
            .iter()
            .map(|name| {
                condition
                    .holds(name)
                    .map(u32::from)
                    .map_err(|()| Error::Invalid {
                        what: format!("class `{name}`"),
                        reason: format!("not a number, but `{expr}` compares numbers"),
                    })
            })
            .collect::<Result<Vec<u32>, Error>>()?;
        self.with_classes(&map, vec!["no".into(), "yes".into()])
    }
}
