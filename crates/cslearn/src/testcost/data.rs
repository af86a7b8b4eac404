//! A table of objects for the batch learners: nominal and numeric columns kept as they
//! are (no binning), missing cells marked, and one class per object.

use crate::Error;
use crate::dataset::parse_number;

/// The code of a missing nominal cell.
pub const MISSING: u32 = u32::MAX;

/// One feature column of a [`Frame`].
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Column {
    /// Named values; `codes[row]` indexes `values`, [`MISSING`] where the cell is missing.
    Nominal {
        /// The values, in order of first appearance.
        values: Vec<String>,
        /// One code per object.
        codes: Vec<u32>,
    },
    /// Numbers; NaN where the cell is missing.
    Numeric(Vec<f64>),
}

impl Column {
    /// Whether the cell of `row` is missing.
    ///
    /// ```
    /// let column = cslearn::testcost::Column::Numeric(vec![1.0, f64::NAN]);
    /// assert!(!column.is_missing(0) && column.is_missing(1));
    /// ```
    pub fn is_missing(&self, row: usize) -> bool {
        match self {
            Column::Nominal { codes, .. } => codes[row] == MISSING,
            Column::Numeric(x) => x[row].is_nan(),
        }
    }

    /// Whether the column holds numbers.
    ///
    /// ```
    /// assert!(cslearn::testcost::Column::Numeric(vec![]).is_numeric());
    /// ```
    pub fn is_numeric(&self) -> bool {
        matches!(self, Column::Numeric(_))
    }
}

/// How to read a table of text cells into a [`Frame`].
///
/// ```
/// let spec = cslearn::testcost::FrameSpec::new("class").nominal(["colour"]);
/// assert_eq!(spec.target, "class");
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FrameSpec {
    /// The class column.
    pub target: String,
    /// Columns that are not features (row ids, names) and are dropped.
    pub ignore: Vec<String>,
    /// Columns read as nominal even where every cell is a number (integer codes).
    pub nominal: Vec<String>,
    /// Cells that mean "missing" besides the empty cell and `?`.
    pub missing: Vec<String>,
    /// The most distinct classes [`Frame::read_csv`] accepts in the class column (`None`:
    /// [`FrameSpec::DEFAULT_MAX_CLASSES`]; after `positive_if`, which makes two). A numeric column named as the class by mistake
    /// has as many values as objects, every node of a tree keeps a weight for each, and a
    /// misclassification matrix that is not uniform grows with their square: it is
    /// refused before anything is learned.
    pub max_classes: Option<usize>,
}

impl FrameSpec {
    /// A spec with the class column `target`; every other column a feature, numeric
    /// where every present cell is a finite number, nominal otherwise.
    ///
    /// ```
    /// assert!(cslearn::testcost::FrameSpec::new("y").ignore.is_empty());
    /// ```
    pub fn new(target: impl Into<String>) -> FrameSpec {
        FrameSpec {
            target: target.into(),
            ..FrameSpec::default()
        }
    }

    /// The most classes a frame read without [`FrameSpec::max_classes`] may have.
    pub const DEFAULT_MAX_CLASSES: usize = 1000;

    /// Allow at most `classes` distinct classes.
    ///
    /// ```
    /// use cslearn::testcost::{Frame, FrameSpec};
    /// let dir = tempfile::tempdir().unwrap();
    /// let path = dir.path().join("d.csv");
    /// std::fs::write(&path, "x,y\n1,a\n2,b\n3,c\n").unwrap();
    /// let spec = FrameSpec::new("y").max_classes(2);
    /// let err = Frame::read_csv(&path, &spec, None).unwrap_err().to_string();
    /// assert!(err.contains("3 distinct values") && err.contains("at most 2"), "{err}");
    /// // Two classes once binarised.
    /// std::fs::write(&path, "x,y\n1,1\n2,2\n3,3\n").unwrap();
    /// assert_eq!(Frame::read_csv(&path, &spec, Some(">1")).unwrap().class_count(), 2);
    /// ```
    pub fn max_classes(mut self, classes: usize) -> FrameSpec {
        self.max_classes = Some(classes);
        self
    }

    /// Also drop these columns.
    ///
    /// ```
    /// let spec = cslearn::testcost::FrameSpec::new("y").ignore(["id"]);
    /// assert_eq!(spec.ignore, ["id"]);
    /// ```
    pub fn ignore<S: Into<String>>(mut self, columns: impl IntoIterator<Item = S>) -> FrameSpec {
        self.ignore.extend(columns.into_iter().map(Into::into));
        self
    }

    /// Read these columns as nominal.
    ///
    /// ```
    /// let spec = cslearn::testcost::FrameSpec::new("y").nominal(["code"]);
    /// assert_eq!(spec.nominal, ["code"]);
    /// ```
    pub fn nominal<S: Into<String>>(mut self, columns: impl IntoIterator<Item = S>) -> FrameSpec {
        self.nominal.extend(columns.into_iter().map(Into::into));
        self
    }

    /// Also read these cells as missing.
    ///
    /// ```
    /// let spec = cslearn::testcost::FrameSpec::new("y").missing(["NA"]);
    /// assert_eq!(spec.missing, ["NA"]);
    /// ```
    pub fn missing<S: Into<String>>(mut self, cells: impl IntoIterator<Item = S>) -> FrameSpec {
        self.missing.extend(cells.into_iter().map(Into::into));
        self
    }
}

/// Objects with their features and classes, column by column.
///
/// ```
/// use cslearn::testcost::{Frame, FrameSpec};
/// let header = ["size", "colour", "class"];
/// let rows = [["1.5", "red", "a"], ["?", "blue", "b"], ["3", "red", "a"]];
/// let frame = Frame::from_cells("toy", &header, &rows, &FrameSpec::new("class")).unwrap();
/// assert_eq!((frame.len(), frame.feature_count(), frame.class_count()), (3, 2, 2));
/// assert!(frame.column(0).is_numeric() && frame.column(0).is_missing(1));
/// ```
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Frame {
    names: Vec<String>,
    columns: Vec<Column>,
    classes: Vec<u32>,
    class_names: Vec<String>,
}

impl Frame {
    /// A frame from columns and classes, checked for equal lengths and valid codes.
    ///
    /// ```
    /// use cslearn::testcost::{Column, Frame};
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0, 1.0])],
    ///     vec![0, 1], vec!["no".into(), "yes".into()]).unwrap();
    /// assert_eq!(frame.class(1), 1);
    /// assert!(Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0])],
    ///     vec![0, 1], vec!["no".into(), "yes".into()]).is_err());
    /// ```
    pub fn new(
        names: Vec<String>,
        columns: Vec<Column>,
        classes: Vec<u32>,
        class_names: Vec<String>,
    ) -> Result<Frame, Error> {
        let bad = |reason: String| Error::Invalid {
            what: "frame".into(),
            reason,
        };
        if names.len() != columns.len() {
            return Err(bad(format!(
                "{} names for {} columns",
                names.len(),
                columns.len()
            )));
        }
        if classes.is_empty() {
            return Err(bad("no objects".into()));
        }
        for (name, column) in names.iter().zip(&columns) {
            let (len, bad_code) = match column {
                Column::Nominal { values, codes } => (
                    codes.len(),
                    codes
                        .iter()
                        .any(|&c| c != MISSING && c as usize >= values.len()),
                ),
                Column::Numeric(x) => (x.len(), x.iter().any(|v| v.is_infinite())),
            };
            if len != classes.len() {
                return Err(bad(format!(
                    "column `{name}` has {len} cells for {} objects",
                    classes.len()
                )));
            }
            if bad_code {
                return Err(bad(format!(
                    "column `{name}` has a code past its values or an infinite number"
                )));
            }
        }
        if let Some(c) = classes.iter().find(|&&c| c as usize >= class_names.len()) {
            return Err(bad(format!(
                "class {c} but only {} class names",
                class_names.len()
            )));
        }
        Ok(Frame {
            names,
            columns,
            classes,
            class_names,
        })
    }

    /// A frame from a header and rows of text cells; `source` names them in errors (a
    /// file's path). A column is numeric where every present cell is a finite number and
    /// the spec does not call it nominal; classes are named by their cells, in order of
    /// first appearance.
    ///
    /// ```
    /// use cslearn::testcost::{Frame, FrameSpec};
    /// let err = Frame::from_cells("t.csv", &["a", "b"], &[["1", "x"]], &FrameSpec::new("c"))
    ///     .unwrap_err();
    /// assert!(err.to_string().contains("no class column `c`"));
    /// ```
    pub fn from_cells<H: AsRef<str>, R: AsRef<[C]>, C: AsRef<str>>(
        source: &str,
        header: &[H],
        rows: &[R],
        spec: &FrameSpec,
    ) -> Result<Frame, Error> {
        let bad = |at: String, reason: String| Error::BadInput {
            path: source.into(),
            at,
            reason,
        };
        let header: Vec<&str> = header.iter().map(AsRef::as_ref).collect();
        if let Some(reason) = crate::dataset::unprintable_name(&header) {
            return Err(bad("header".into(), reason));
        }
        let target = header
            .iter()
            .position(|h| *h == spec.target)
            .ok_or_else(|| {
                bad(
                    "header".into(),
                    format!(
                        "no class column `{}` (columns: {})",
                        spec.target,
                        header.join(", ")
                    ),
                )
            })?;
        for named in spec.ignore.iter().chain(&spec.nominal) {
            if !header.contains(&named.as_str()) {
                return Err(bad(
                    "header".into(),
                    format!("no column `{named}`, which the spec names"),
                ));
            }
        }
        if rows.is_empty() {
            return Err(bad("data".into(), "no objects".into()));
        }
        for (i, row) in rows.iter().enumerate() {
            if row.as_ref().len() != header.len() {
                return Err(bad(
                    format!("row {}", i + 1),
                    format!(
                        "{} cells, but the header has {}",
                        row.as_ref().len(),
                        header.len()
                    ),
                ));
            }
        }
        let missing = |cell: &str| {
            let cell = cell.trim();
            cell.is_empty() || cell == "?" || spec.missing.iter().any(|m| m == cell)
        };
        let mut class_coder = Coder::default();
        let mut classes = Vec::with_capacity(rows.len());
        for (i, row) in rows.iter().enumerate() {
            let cell = row.as_ref()[target].as_ref().trim();
            if missing(cell) {
                return Err(bad(
                    format!("row {}", i + 1),
                    format!("the class `{}` is missing", spec.target),
                ));
            }
            classes.push(class_coder.code(cell));
        }
        let mut names = Vec::new();
        let mut columns = Vec::new();
        for (c, name) in header.iter().enumerate() {
            if c == target || spec.ignore.iter().any(|i| i == name) {
                continue;
            }
            let cells = || rows.iter().map(move |r| r.as_ref()[c].as_ref().trim());
            let numeric = !spec.nominal.iter().any(|n| n == name)
                && cells().all(|cell| missing(cell) || parse_number(cell).is_some());
            let column = if numeric {
                Column::Numeric(
                    cells()
                        .map(|cell| {
                            if missing(cell) {
                                f64::NAN
                            } else {
                                parse_number(cell).unwrap_or(f64::NAN)
                            }
                        })
                        .collect(),
                )
            } else {
                let mut coder = Coder::default();
                let codes = cells()
                    .map(|cell| {
                        if missing(cell) {
                            MISSING
                        } else {
                            coder.code(cell)
                        }
                    })
                    .collect();
                Column::Nominal {
                    values: coder.values,
                    codes,
                }
            };
            names.push((*name).to_string());
            columns.push(column);
        }
        if columns.is_empty() {
            return Err(bad(
                "header".into(),
                "no feature columns besides the class".into(),
            ));
        }
        Frame::new(names, columns, classes, class_coder.values)
    }

    /// A frame from a text file without a header, such as UCI's `.data` files: `columns`
    /// names its columns in order. Each line is split on commas if it has one, else on
    /// runs of whitespace; surrounding whitespace (a `\r` included) is ignored, and blank
    /// lines and lines starting with `skip_prefix` (when not empty) are not data.
    ///
    /// ```
    /// use cslearn::testcost::{Frame, FrameSpec};
    /// let dir = tempfile::tempdir().unwrap();
    /// let path = dir.path().join("toy.data");
    /// std::fs::write(&path, "@relation toy\n1.5 red a\r\n2 blue b\n\n").unwrap();
    /// let columns = ["size", "colour", "class"].map(String::from);
    /// let frame = Frame::read_delimited(&path, &columns, "@", &FrameSpec::new("class")).unwrap();
    /// assert_eq!((frame.len(), frame.class_names()), (2, &["a".to_string(), "b".to_string()][..]));
    /// ```
    pub fn read_delimited(
        path: &std::path::Path,
        columns: &[String],
        skip_prefix: &str,
        spec: &FrameSpec,
    ) -> Result<Frame, Error> {
        let rows = read_rows(path, columns.len(), skip_prefix)?;
        Frame::from_cells(&path.display().to_string(), columns, &rows, spec)
    }

    /// A frame from a CSV file with a header (the data file of `csrl classify`): numeric
    /// columns kept as numbers (no binning), the others nominal, as
    /// [`from_cells`](Frame::from_cells) reads them; with `positive_if` (`>0`, `==sick`,
    /// ...) two classes, `no` and `yes`, as [`binarise`](Frame::binarise) makes them.
    /// The file is read as [`Dataset::load`](crate::Dataset::load) reads it (a regular
    /// file of at most [`MAX_FILE_BYTES`](crate::MAX_FILE_BYTES) bytes and
    /// [`MAX_CELLS`](crate::MAX_CELLS) cells, quoted cells, trimmed), and every problem
    /// names the file and, where there is one, the line: a ragged record, a column named
    /// twice, no class column, an empty class cell, a class that is not a number where
    /// `positive_if` compares numbers, or a `positive_if` that no class satisfies.
    ///
    /// ```
    /// use cslearn::testcost::{Frame, FrameSpec};
    /// let dir = tempfile::tempdir().unwrap();
    /// let path = dir.path().join("d.csv");
    /// std::fs::write(&path, "size,colour,num\n1.5,red,0\n?,\"blue\",2\n3,red,1\n").unwrap();
    /// let frame = Frame::read_csv(&path, &FrameSpec::new("num"), Some(">0")).unwrap();
    /// assert_eq!(frame.classes(), [0, 1, 1]);
    /// assert!(frame.column(0).is_numeric() && !frame.column(1).is_numeric());
    /// std::fs::write(&path, "size,num\n1,0\n2,\n").unwrap();
    /// let err = Frame::read_csv(&path, &FrameSpec::new("num"), None).unwrap_err();
    /// assert!(err.to_string().ends_with("d.csv: line 3: the target column is empty"));
    /// ```
    pub fn read_csv(
        path: &std::path::Path,
        spec: &FrameSpec,
        positive_if: Option<&str>,
    ) -> Result<Frame, Error> {
        use crate::dataset::{Condition, classes, open_regular, read_table};
        let condition = positive_if.map(Condition::parse).transpose()?;
        let table = read_table(open_regular(path)?, path)?;
        let at = || path.to_path_buf();
        let mut seen = std::collections::BTreeSet::new();
        if let Some(twice) = table.header.iter().find(|h| !seen.insert(h.as_str())) {
            return Err(Error::DuplicateColumn {
                path: at(),
                column: twice.clone(),
            });
        }
        let target = table
            .header
            .iter()
            .position(|h| *h == spec.target)
            .ok_or_else(|| Error::UnknownTarget {
                path: at(),
                target: spec.target.clone(),
                columns: table.header.clone(),
            })?;
        if table.header.len() < 2 {
            return Err(Error::NoFeatures { path: at() });
        }
        if table.is_empty() {
            return Err(Error::NoRecords { path: at() });
        }
        // The class cells, line by line: an empty one, or one the rule cannot compare,
        // is named with its line here (from_cells knows rows, not lines).
        classes(&table, target, condition.as_ref(), path)?;
        let rows: Vec<Vec<&str>> = table
            .records()
            .map(|(_, record)| (0..table.header.len()).map(|c| record.get(c)).collect())
            .collect();
        let frame = Frame::from_cells(&path.display().to_string(), &table.header, &rows, spec)?;
        let frame = match positive_if {
            Some(expr) => frame.binarise(expr)?,
            None => frame,
        };
        let limit = spec.max_classes.unwrap_or(FrameSpec::DEFAULT_MAX_CLASSES);
        let found = frame.class_count();
        if found > limit {
            return Err(Error::BadInput {
                path: at(),
                at: format!("class column `{}`", spec.target),
                reason: format!(
                    "{found} distinct values, but a class column may have at most {limit} \
                     classes (a numeric column named as the class?); raise the limit if they \
                     are classes"
                ),
            });
        }
        Ok(frame)
    }

    /// The number of objects.
    ///
    /// ```
    /// # let frame = cslearn::testcost::Frame::new(vec!["x".into()],
    /// #     vec![cslearn::testcost::Column::Numeric(vec![0.0])], vec![0], vec!["a".into()]).unwrap();
    /// assert_eq!(frame.len(), 1);
    /// ```
    pub fn len(&self) -> usize {
        self.classes.len()
    }

    /// Never true: a frame has at least one object.
    ///
    /// ```
    /// # let frame = cslearn::testcost::Frame::new(vec!["x".into()],
    /// #     vec![cslearn::testcost::Column::Numeric(vec![0.0])], vec![0], vec!["a".into()]).unwrap();
    /// assert!(!frame.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.classes.is_empty()
    }

    /// The number of feature columns.
    ///
    /// ```
    /// # let frame = cslearn::testcost::Frame::new(vec!["x".into()],
    /// #     vec![cslearn::testcost::Column::Numeric(vec![0.0])], vec![0], vec!["a".into()]).unwrap();
    /// assert_eq!(frame.feature_count(), 1);
    /// ```
    pub fn feature_count(&self) -> usize {
        self.columns.len()
    }

    /// The number of classes.
    ///
    /// ```
    /// # let frame = cslearn::testcost::Frame::new(vec!["x".into()],
    /// #     vec![cslearn::testcost::Column::Numeric(vec![0.0])], vec![0], vec!["a".into()]).unwrap();
    /// assert_eq!(frame.class_count(), 1);
    /// ```
    pub fn class_count(&self) -> usize {
        self.class_names.len()
    }

    /// Column `feature`.
    ///
    /// ```
    /// # let frame = cslearn::testcost::Frame::new(vec!["x".into()],
    /// #     vec![cslearn::testcost::Column::Numeric(vec![0.0])], vec![0], vec!["a".into()]).unwrap();
    /// assert!(frame.column(0).is_numeric());
    /// ```
    pub fn column(&self, feature: usize) -> &Column {
        &self.columns[feature]
    }

    /// The feature names.
    ///
    /// ```
    /// # let frame = cslearn::testcost::Frame::new(vec!["x".into()],
    /// #     vec![cslearn::testcost::Column::Numeric(vec![0.0])], vec![0], vec!["a".into()]).unwrap();
    /// assert_eq!(frame.names(), ["x"]);
    /// ```
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The class of object `row`.
    ///
    /// ```
    /// # let frame = cslearn::testcost::Frame::new(vec!["x".into()],
    /// #     vec![cslearn::testcost::Column::Numeric(vec![0.0])], vec![0], vec!["a".into()]).unwrap();
    /// assert_eq!(frame.class(0), 0);
    /// ```
    pub fn class(&self, row: usize) -> u32 {
        self.classes[row]
    }

    /// Every object's class.
    ///
    /// ```
    /// # let frame = cslearn::testcost::Frame::new(vec!["x".into()],
    /// #     vec![cslearn::testcost::Column::Numeric(vec![0.0])], vec![0], vec!["a".into()]).unwrap();
    /// assert_eq!(frame.classes(), [0]);
    /// ```
    pub fn classes(&self) -> &[u32] {
        &self.classes
    }

    /// The class names.
    ///
    /// ```
    /// # let frame = cslearn::testcost::Frame::new(vec!["x".into()],
    /// #     vec![cslearn::testcost::Column::Numeric(vec![0.0])], vec![0], vec!["a".into()]).unwrap();
    /// assert_eq!(frame.class_names(), ["a"]);
    /// ```
    pub fn class_names(&self) -> &[String] {
        &self.class_names
    }

    /// The number of objects of each class.
    ///
    /// ```
    /// # let frame = cslearn::testcost::Frame::new(vec!["x".into()],
    /// #     vec![cslearn::testcost::Column::Numeric(vec![0.0, 1.0])], vec![0, 0], vec!["a".into()]).unwrap();
    /// assert_eq!(frame.class_totals(), [2]);
    /// ```
    pub fn class_totals(&self) -> Vec<usize> {
        let mut totals = vec![0; self.class_count()];
        for &c in &self.classes {
            totals[c as usize] += 1;
        }
        totals
    }

    /// The index of the feature called `name`.
    ///
    /// ```
    /// # let frame = cslearn::testcost::Frame::new(vec!["x".into()],
    /// #     vec![cslearn::testcost::Column::Numeric(vec![0.0])], vec![0], vec!["a".into()]).unwrap();
    /// assert_eq!(frame.feature("x"), Some(0));
    /// ```
    pub fn feature(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }

    /// The same objects with their classes mapped through `map` (old class index to new)
    /// and the classes renamed, to merge classes (say, "any disease" against "none").
    ///
    /// ```
    /// # use cslearn::testcost::{Column, Frame};
    /// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0, 1.0, 2.0])],
    ///     vec![0, 1, 2], vec!["0".into(), "1".into(), "2".into()]).unwrap();
    /// let merged = frame.with_classes(&[0, 1, 1], vec!["none".into(), "some".into()]).unwrap();
    /// assert_eq!(merged.classes(), [0, 1, 1]);
    /// ```
    pub fn with_classes(&self, map: &[u32], names: Vec<String>) -> Result<Frame, Error> {
        if map.len() != self.class_count() {
            return Err(Error::Invalid {
                what: "class map".into(),
                reason: format!("{} entries for {} classes", map.len(), self.class_count()),
            });
        }
        let classes = self.classes.iter().map(|&c| map[c as usize]).collect();
        Frame::new(self.names.clone(), self.columns.clone(), classes, names)
    }
}

/// Codes for the distinct cells of a column, in order of first appearance.
#[derive(Default)]
struct Coder {
    values: Vec<String>,
    index: std::collections::BTreeMap<String, u32>,
}

impl Coder {
    fn code(&mut self, cell: &str) -> u32 {
        if let Some(&code) = self.index.get(cell) {
            return code;
        }
        let code = self.values.len() as u32;
        self.values.push(cell.to_string());
        self.index.insert(cell.to_string(), code);
        code
    }
}

/// The data lines of a headerless file, each split into `width` cells (the splitting of
/// [`Frame::read_delimited`]).
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("t.data");
/// std::fs::write(&path, " 1 2\n3 4 5\n").unwrap();
/// let err = cslearn::testcost::read_rows(&path, 2, "").unwrap_err();
/// assert!(err.to_string().ends_with("line 2: 3 cells, but 2 columns are named"));
/// ```
pub fn read_rows(
    path: &std::path::Path,
    width: usize,
    skip_prefix: &str,
) -> Result<Vec<Vec<String>>, Error> {
    let meta = std::fs::metadata(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    if !meta.is_file() {
        return Err(Error::NotAFile {
            path: path.to_path_buf(),
        });
    }
    if meta.len() > crate::MAX_FILE_BYTES {
        return Err(Error::TooLarge {
            path: path.to_path_buf(),
            max: crate::MAX_FILE_BYTES,
        });
    }
    let bytes = std::fs::read(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let text = String::from_utf8(bytes).map_err(|e| Error::NotUtf8 {
        path: path.to_path_buf(),
        line: 1 + e.as_bytes()[..e.utf8_error().valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count() as u64,
    })?;
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || (!skip_prefix.is_empty() && line.starts_with(skip_prefix)) {
            continue;
        }
        let cells: Vec<String> = if line.contains(',') {
            line.split(',').map(|c| c.trim().to_string()).collect()
        } else {
            line.split_whitespace().map(str::to_string).collect()
        };
        if cells.len() != width {
            return Err(Error::BadInput {
                path: path.to_path_buf(),
                at: format!("line {}", i + 1),
                reason: format!("{} cells, but {width} columns are named", cells.len()),
            });
        }
        rows.push(cells);
    }
    Ok(rows)
}
