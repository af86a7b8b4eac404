//! Tables of objects from CSV files: a data file with one object per row and a costs file
//! with the price of each column.
//!
//! # Reading
//!
//! * The data file has a header. One column is the target (the class); every other column
//!   is a feature, numbered from 0 in header order (skipping the target).
//! * Cells are trimmed; an empty cell or `?` is a missing value, which stays missing.
//! * A column whose every present cell is a finite number is numeric. Numeric columns are
//!   cut into quantile bins computed from the whole column before any learning (quartiles
//!   by default, [`Binning`]); a value equal to a cut point falls in the lower bin. The other
//!   columns are nominal: each distinct text is a value, numbered in sorted order.
//! * The target becomes classes: with a [`positive_if`](DatasetOptions::positive_if)
//!   expression two classes, 1 where it holds and 0 where not; otherwise one class per
//!   distinct target text, numbered in sorted order (numerically if every target is a
//!   number). A record with an empty target is an error.
//! * The costs file has the header `feature,cost` and one row per feature column. A cost
//!   for the target column is ignored (it is never measured).
//!
//! Every problem is an [`Error`] naming the file and, where there is one, the line.
//! [`Dataset::load`] reads regular files only (a directory, a device or a pipe is refused
//! before it is opened), and every reader stops after [`MAX_FILE_BYTES`] bytes, whatever
//! the file's metadata says.

use std::cmp::Ordering;
use std::collections::{BTreeMap, BTreeSet};
use std::io::Read;
use std::num::NonZeroU32;
use std::path::{Path, PathBuf};

use rand::Rng;
use rand::seq::SliceRandom;

use crate::error::Error;
use crate::tree::Labels;
use crate::types::{ClassId, Cost, FeatureCosts, FeatureId, Value};

/// How numeric columns become values.
///
/// ```
/// assert_eq!(cslearn::Binning::quartiles(), cslearn::Binning::Quantiles(std::num::NonZeroU32::new(4).unwrap()));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Binning {
    /// Cut into this many bins of about equal count, at the column's quantiles (linear
    /// interpolation between order statistics). Repeated cut points merge, so a column
    /// with few distinct numbers gets fewer bins.
    Quantiles(NonZeroU32),
    /// Treat every distinct number as a category of its own.
    Nominal,
}

impl Binning {
    /// Four bins at the quartiles: the default (specification §2).
    ///
    /// ```
    /// assert!(matches!(cslearn::Binning::quartiles(), cslearn::Binning::Quantiles(_)));
    /// ```
    pub fn quartiles() -> Binning {
        Binning::Quantiles(NonZeroU32::MIN.saturating_add(3))
    }
}

/// What to read from a data file.
///
/// ```
/// let options = cslearn::DatasetOptions::new("num").positive_if(">0");
/// assert_eq!(options.target, "num");
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DatasetOptions {
    /// The column holding the class.
    pub target: String,
    /// An expression that splits the target into two classes: `>0`, `>=1`, `<2`, `<=2`,
    /// `==1`, `!=0` compare numbers (`==` and `!=` compare text when either side is not a
    /// number); a bare word such as `present` means `==present`.
    pub positive_if: Option<String>,
    /// How numeric columns are cut into values.
    pub binning: Binning,
}

impl DatasetOptions {
    /// Options for `target`, one class per target value, quartile bins.
    ///
    /// ```
    /// let options = cslearn::DatasetOptions::new("class");
    /// assert_eq!(options.positive_if, None);
    /// ```
    pub fn new(target: impl Into<String>) -> DatasetOptions {
        DatasetOptions {
            target: target.into(),
            positive_if: None,
            binning: Binning::quartiles(),
        }
    }

    /// The same options with a positive-if expression.
    ///
    /// ```
    /// let options = cslearn::DatasetOptions::new("num").positive_if("!=0");
    /// assert_eq!(options.positive_if.as_deref(), Some("!=0"));
    /// ```
    pub fn positive_if(mut self, expr: impl Into<String>) -> DatasetOptions {
        self.positive_if = Some(expr.into());
        self
    }

    /// The same options with another binning.
    ///
    /// ```
    /// let options = cslearn::DatasetOptions::new("num").binning(cslearn::Binning::Nominal);
    /// assert_eq!(options.binning, cslearn::Binning::Nominal);
    /// ```
    pub fn binning(mut self, binning: Binning) -> DatasetOptions {
        self.binning = binning;
        self
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Op {
    Gt,
    Ge,
    Lt,
    Le,
    Eq,
    Ne,
}

/// A parsed positive-if expression.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Condition {
    op: Op,
    text: String,
    number: Option<f64>,
}

impl Condition {
    pub(crate) fn parse(expr: &str) -> Result<Condition, Error> {
        let bad = |reason| Error::BadExpression {
            expr: expr.to_string(),
            reason,
        };
        let trimmed = expr.trim();
        if trimmed.is_empty() {
            return Err(bad("it is empty"));
        }
        let ops = [
            (">=", Op::Ge),
            ("<=", Op::Le),
            ("==", Op::Eq),
            ("!=", Op::Ne),
            (">", Op::Gt),
            ("<", Op::Lt),
            ("=", Op::Eq),
        ];
        let (op, rest) = ops
            .iter()
            .find_map(|&(prefix, op)| trimmed.strip_prefix(prefix).map(|rest| (op, rest.trim())))
            .unwrap_or((Op::Eq, trimmed));
        if rest.is_empty() {
            return Err(bad("nothing to compare with"));
        }
        let number = parse_number(rest);
        if matches!(op, Op::Gt | Op::Ge | Op::Lt | Op::Le) && number.is_none() {
            return Err(bad("an ordering comparison needs a number"));
        }
        Ok(Condition {
            op,
            text: rest.to_string(),
            number,
        })
    }

    /// Whether `cell` satisfies the condition; `Err(())` if it must be a number and is not.
    pub(crate) fn holds(&self, cell: &str) -> Result<bool, ()> {
        let cell_number = parse_number(cell);
        let ordering = match (self.number, cell_number) {
            (Some(n), Some(c)) => c.partial_cmp(&n),
            _ => None,
        };
        Ok(match self.op {
            Op::Eq | Op::Ne => {
                let equal = match ordering {
                    Some(o) => o == Ordering::Equal,
                    None => cell == self.text,
                };
                equal == (self.op == Op::Eq)
            }
            Op::Gt => ordering.ok_or(())? == Ordering::Greater,
            Op::Ge => ordering.ok_or(())? != Ordering::Less,
            Op::Lt => ordering.ok_or(())? == Ordering::Less,
            Op::Le => ordering.ok_or(())? != Ordering::Greater,
        })
    }
}

pub(crate) fn parse_number(text: &str) -> Option<f64> {
    text.parse::<f64>().ok().filter(|x| x.is_finite())
}

pub(crate) fn is_missing(cell: &str) -> bool {
    cell.is_empty() || cell == "?"
}

/// A number for a label: at most four decimals, no trailing zeros.
fn format_number(x: f64) -> String {
    let text = format!("{x:.4}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_string()
    } else {
        text.to_string()
    }
}

/// A header and its records, each with its 1-based line, stored compactly: every cell's
/// text one after another in one string, and where each ends.
#[derive(Debug)]
pub(crate) struct Table {
    pub(crate) header: Vec<String>,
    text: String,
    /// Where each cell ends in `text`, `header.len()` per record.
    ends: Vec<u32>,
    /// The 1-based line of each record.
    lines: Vec<u32>,
}

/// One record of a [`Table`]: its cells by column, `record[c]`.
pub(crate) struct Record<'a> {
    table: &'a Table,
    first: usize,
}

impl<'a> Record<'a> {
    /// The cell in `column`.
    pub(crate) fn get(&self, column: usize) -> &'a str {
        let k = self.first + column;
        let start = if k == 0 {
            0
        } else {
            self.table.ends[k - 1] as usize
        };
        &self.table.text[start..self.table.ends[k] as usize]
    }
}

impl std::ops::Index<usize> for Record<'_> {
    type Output = str;
    fn index(&self, column: usize) -> &str {
        self.get(column)
    }
}

impl Table {
    /// The number of records.
    pub(crate) fn len(&self) -> usize {
        self.lines.len()
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.lines.is_empty()
    }

    /// Each record with its line, in file order.
    pub(crate) fn records(&self) -> impl Iterator<Item = (u64, Record<'_>)> + '_ {
        let width = self.header.len();
        self.lines.iter().enumerate().map(move |(i, &line)| {
            (
                u64::from(line),
                Record {
                    table: self,
                    first: i * width,
                },
            )
        })
    }

    /// The cells of column `c`, record by record.
    pub(crate) fn column(&self, c: usize) -> impl Iterator<Item = &str> + '_ {
        self.records().map(move |(_, r)| r.get(c))
    }
}

/// The most cells (records times columns) a data or costs table may have: 2^25, so that
/// reading and encoding a table stays within about 2 GB whatever its shape.
///
/// ```
/// assert_eq!(cslearn::MAX_CELLS, 33_554_432);
/// ```
pub const MAX_CELLS: u64 = 1 << 25;

/// The 1-based line of the record the CSV reader places at byte `offset`: one more than
/// the newlines before its first byte. The reader's own line count, and its offset, can
/// sit on the line end before the record (after a CRLF), so line ends there are skipped:
/// no record starts with one.
fn line_at(bytes: &[u8], offset: u64) -> u64 {
    let end = record_start(bytes, offset);
    1 + bytes[..end].iter().filter(|&&b| b == b'\n').count() as u64
}

/// Byte `offset`, moved past any line-end bytes, within `bytes`.
fn record_start(bytes: &[u8], offset: u64) -> usize {
    let mut at = usize::try_from(offset)
        .unwrap_or(usize::MAX)
        .min(bytes.len());
    while at < bytes.len() && matches!(bytes[at], b'\r' | b'\n') {
        at += 1;
    }
    at
}

fn csv_error(path: &Path, err: csv::Error, bytes: &[u8]) -> Error {
    let path = path.to_path_buf();
    let line = err.position().map(|p| line_at(bytes, p.byte()));
    match err.kind() {
        csv::ErrorKind::Utf8 { pos, .. } => {
            return Error::NotUtf8 {
                path,
                line: pos.as_ref().map_or(1, |p| line_at(bytes, p.byte())),
            };
        }
        csv::ErrorKind::UnequalLengths {
            pos,
            expected_len,
            len,
        } => {
            return Error::RaggedRecord {
                path,
                line: pos.as_ref().map_or(0, |p| line_at(bytes, p.byte())),
                expected: *expected_len,
                found: *len,
            };
        }
        csv::ErrorKind::Io(e) => {
            return Error::Io {
                path,
                source: std::io::Error::new(e.kind(), e.to_string()),
            };
        }
        _ => {}
    }
    Error::Malformed {
        path,
        line,
        source: err,
    }
}

/// Open a regular file; a directory, a device or a pipe is refused before it is opened.
pub(crate) fn open_regular(path: &Path) -> Result<std::fs::File, Error> {
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let not_a_file = || Error::NotAFile {
        path: path.to_path_buf(),
    };
    // Judged from the metadata first: opening a FIFO would block until a writer
    // comes; then on the opened file, in case the path changed in between.
    if !std::fs::metadata(path).map_err(io)?.is_file() {
        return Err(not_a_file());
    }
    let file = std::fs::File::open(path).map_err(io)?;
    if !file.metadata().map_err(io)?.is_file() {
        return Err(not_a_file());
    }
    Ok(file)
}

/// The most bytes a data or costs file may have (256 MiB); reading stops after them.
///
/// ```
/// assert_eq!(cslearn::MAX_FILE_BYTES, 256 << 20);
/// ```
pub const MAX_FILE_BYTES: u64 = 256 << 20;

/// Read at most [`MAX_FILE_BYTES`] bytes, refusing anything longer.
pub(crate) fn read_bounded(mut reader: impl Read, path: &Path) -> Result<Vec<u8>, Error> {
    let mut bytes = Vec::new();
    (&mut reader)
        .take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(Error::TooLarge {
            path: path.to_path_buf(),
            max: MAX_FILE_BYTES,
        });
    }
    Ok(bytes)
}

/// The line of a quote that opens a field and is never closed, if there is one. The CSV
/// reader takes such a quote to the end of the file and then reports a field count, which
/// points at the wrong line and the wrong cause.
fn unterminated_quote(bytes: &[u8]) -> Option<u64> {
    let (mut line, mut open_line) = (1u64, 0u64);
    let (mut in_quotes, mut field_start) = (false, true);
    let mut i = 0;
    while i < bytes.len() {
        let b = bytes[i];
        if in_quotes {
            if b == b'"' {
                if bytes.get(i + 1) == Some(&b'"') {
                    i += 1;
                } else {
                    in_quotes = false;
                }
            }
        } else if b == b'"' && field_start {
            in_quotes = true;
            open_line = line;
        }
        if b == b'\n' {
            line += 1;
        }
        // Cells are trimmed, so a quote may follow blanks at the start of a field.
        field_start = !in_quotes
            && (b == b','
                || b == b'\n'
                || (field_start && (b == b' ' || b == b'\t' || b == b'\r')));
        i += 1;
    }
    in_quotes.then_some(open_line)
}

pub(crate) fn read_table(reader: impl Read, path: &Path) -> Result<Table, Error> {
    read_table_within(reader, path, MAX_CELLS)
}

/// [`read_table`] with at most `max_cells` cells.
fn read_table_within(reader: impl Read, path: &Path, max_cells: u64) -> Result<Table, Error> {
    let bytes = read_bounded(reader, path)?;
    if let Some(line) = unterminated_quote(&bytes) {
        return Err(Error::UnterminatedQuote {
            path: path.to_path_buf(),
            line,
        });
    }
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .trim(csv::Trim::All)
        .from_reader(bytes.as_slice());
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| csv_error(path, e, &bytes))?
        .iter()
        .map(str::to_string)
        .collect();
    if header.is_empty() || header.iter().all(String::is_empty) {
        return Err(Error::EmptyFile {
            path: path.to_path_buf(),
        });
    }
    if let Some(reason) = unprintable_name(&header) {
        return Err(Error::BadInput {
            path: path.to_path_buf(),
            at: "line 1".into(),
            reason,
        });
    }
    let (mut text, mut ends, mut lines) = (String::new(), Vec::new(), Vec::new());
    // Lines counted from byte offsets, in one pass over the file.
    let (mut counted, mut line) = (0usize, 1u64);
    let mut record = csv::StringRecord::new();
    while reader
        .read_record(&mut record)
        .map_err(|e| csv_error(path, e, &bytes))?
    {
        let at = record
            .position()
            .map_or(counted, |p| record_start(&bytes, p.byte()))
            .max(counted);
        line += bytes[counted..at].iter().filter(|&&b| b == b'\n').count() as u64;
        counted = at;
        if (ends.len() + record.len()) as u64 > max_cells {
            return Err(Error::TooManyCells {
                path: path.to_path_buf(),
                line,
                max: max_cells,
            });
        }
        for cell in &record {
            text.push_str(cell);
            // The text is no longer than the file, at most MAX_FILE_BYTES < 2^32.
            ends.push(text.len() as u32);
        }
        lines.push(line as u32);
    }
    Ok(Table {
        header,
        text,
        ends,
        lines,
    })
}

/// One feature column.
#[derive(Clone, Debug, PartialEq)]
struct Column {
    name: String,
    /// The name of each value, indexed by [`Value`].
    values: Vec<String>,
    /// For a binned numeric column, the cut points between bins.
    cuts: Option<Vec<f64>>,
}

/// Quantile cut points of sorted, finite `xs` for `bins` bins, repeats merged.
fn quantile_cuts(xs: &[f64], bins: u32) -> Vec<f64> {
    let mut cuts: Vec<f64> = (1..bins)
        .filter_map(|j| {
            let last = xs.len().checked_sub(1)?;
            let p = f64::from(j) / f64::from(bins) * last as f64;
            let lo = p.floor() as usize;
            let hi = (lo + 1).min(last);
            Some(xs[lo] + (p - lo as f64) * (xs[hi] - xs[lo]))
        })
        .collect();
    cuts.dedup();
    cuts
}

fn bin_names(cuts: &[f64]) -> Vec<String> {
    if cuts.is_empty() {
        return vec!["any".to_string()];
    }
    let mut names = vec![format!("<= {}", format_number(cuts[0]))];
    for pair in cuts.windows(2) {
        names.push(format!(
            "({}, {}]",
            format_number(pair[0]),
            format_number(pair[1])
        ));
    }
    names.push(format!("> {}", format_number(cuts[cuts.len() - 1])));
    names
}

/// Sort texts numerically when all are numbers, otherwise as text.
fn sort_texts(texts: &mut [String]) {
    if texts.iter().all(|t| parse_number(t).is_some()) {
        texts.sort_by(|a, b| {
            let (x, y) = (
                parse_number(a).unwrap_or(0.0),
                parse_number(b).unwrap_or(0.0),
            );
            x.total_cmp(&y).then_with(|| a.cmp(b))
        });
    } else {
        texts.sort();
    }
}

/// Objects read from a CSV file, with their classes and the price of each feature.
///
/// Each object is a dense row of values (`None` for missing), usable directly as a
/// [`Sensor`](crate::Sensor). Names of features, values and classes are kept for
/// pictures ([`Labels`]).
///
/// ```
/// use cslearn::{ClassId, Dataset, DatasetOptions, FeatureId, Value};
/// let data = "age,chest,sick\n30,pain,1\n60,,0\n45,none,2\n";
/// let costs = "feature,cost\nage,1\nchest,2.5\n";
/// let options = DatasetOptions::new("sick").positive_if(">0");
/// let ds = Dataset::from_readers(data.as_bytes(), "data.csv", costs.as_bytes(), "costs.csv", &options).unwrap();
/// assert_eq!(ds.len(), 3);
/// assert_eq!(ds.labels(), &[ClassId(1), ClassId(0), ClassId(1)]);
/// assert_eq!(ds.object(1)[1], None); // the missing chest cell
/// assert_eq!(ds.feature_id("chest"), Some(FeatureId(1)));
/// assert_eq!(ds.costs().total().get(), 3.5);
/// assert_eq!(ds.value_name(FeatureId(1), Value(0)), Some("none"));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Dataset {
    target: String,
    columns: Vec<Column>,
    costs: FeatureCosts,
    rows: Vec<Option<Value>>,
    labels: Vec<ClassId>,
    class_names: Vec<String>,
}

impl Dataset {
    /// Read a data file and a costs file.
    ///
    /// ```
    /// let err = cslearn::Dataset::load(
    ///     "no/such/data.csv".as_ref(),
    ///     "no/such/costs.csv".as_ref(),
    ///     &cslearn::DatasetOptions::new("num"),
    /// )
    /// .unwrap_err();
    /// assert!(matches!(err, cslearn::Error::Io { .. }));
    /// ```
    pub fn load(data: &Path, costs: &Path, options: &DatasetOptions) -> Result<Dataset, Error> {
        let data_file = open_regular(data)?;
        let costs_file = open_regular(costs)?;
        Dataset::from_readers(data_file, data, costs_file, costs, options)
    }

    /// Read a data table and a costs table from readers; the names are only for messages.
    ///
    /// ```
    /// let err = cslearn::Dataset::from_readers(
    ///     "a,b\n1,2\n".as_bytes(), "d.csv", "feature,cost\na,1\n".as_bytes(), "c.csv",
    ///     &cslearn::DatasetOptions::new("z"),
    /// )
    /// .unwrap_err();
    /// assert_eq!(err.to_string(), "d.csv: no target column `z` (columns: a, b)");
    /// ```
    pub fn from_readers(
        data: impl Read,
        data_name: impl AsRef<Path>,
        costs: impl Read,
        costs_name: impl AsRef<Path>,
        options: &DatasetOptions,
    ) -> Result<Dataset, Error> {
        let data_path = data_name.as_ref();
        let costs_path = costs_name.as_ref();
        let condition = options
            .positive_if
            .as_deref()
            .map(Condition::parse)
            .transpose()?;
        let table = read_table(data, data_path)?;
        let path = || data_path.to_path_buf();
        // One index of the header, so that reading stays linear in the number of columns.
        let mut seen: BTreeMap<&str, usize> = BTreeMap::new();
        for (i, name) in table.header.iter().enumerate() {
            if seen.insert(name.as_str(), i).is_some() {
                return Err(Error::DuplicateColumn {
                    path: path(),
                    column: name.clone(),
                });
            }
        }
        let target = table
            .header
            .iter()
            .position(|h| *h == options.target)
            .ok_or_else(|| Error::UnknownTarget {
                path: path(),
                target: options.target.clone(),
                columns: table.header.clone(),
            })?;
        let feature_columns: Vec<usize> =
            (0..table.header.len()).filter(|&c| c != target).collect();
        if feature_columns.is_empty() {
            return Err(Error::NoFeatures { path: path() });
        }
        if table.is_empty() {
            return Err(Error::NoRecords { path: path() });
        }
        let names: Vec<&str> = feature_columns
            .iter()
            .map(|&c| table.header[c].as_str())
            .collect();
        let costs = read_costs(costs, costs_path, &names, &options.target)?;
        check_totals(&costs, table.len(), costs_path)?;
        let (labels, class_names) = classes(&table, target, condition.as_ref(), data_path)?;

        let n_features = feature_columns.len();
        let mut rows = vec![None; table.len() * n_features];
        let mut columns = Vec::with_capacity(n_features);
        for (f, &c) in feature_columns.iter().enumerate() {
            let cells: Vec<&str> = table.column(c).collect();
            let (column, values) = encode_column(&table.header[c], &cells, options.binning);
            for (row, value) in values.into_iter().enumerate() {
                rows[row * n_features + f] = value;
            }
            columns.push(column);
        }
        Ok(Dataset {
            target: options.target.clone(),
            columns,
            costs,
            rows,
            labels,
            class_names,
        })
    }

    /// The number of objects.
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert_eq!(ds.len(), 1);
    /// ```
    pub fn len(&self) -> usize {
        self.labels.len()
    }

    /// Whether there are no objects (never, for a loaded data set).
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert!(!ds.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.labels.is_empty()
    }

    /// The number of features (columns other than the target).
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert_eq!(ds.feature_count(), 1);
    /// ```
    pub fn feature_count(&self) -> usize {
        self.columns.len()
    }

    /// Object `index` as a dense row, feature `i` at index `i` (panics past the end).
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert_eq!(ds.object(0), &[Some(cslearn::Value(0))]);
    /// ```
    pub fn object(&self, index: usize) -> &[Option<Value>] {
        let n = self.columns.len();
        &self.rows[index * n..(index + 1) * n]
    }

    /// The class of every object.
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert_eq!(ds.labels(), &[cslearn::ClassId(0)]);
    /// ```
    pub fn labels(&self) -> &[ClassId] {
        &self.labels
    }

    /// The objects with their classes, in file order.
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert_eq!(ds.objects().count(), 1);
    /// ```
    pub fn objects(&self) -> impl Iterator<Item = (&[Option<Value>], ClassId)> + '_ {
        (0..self.len()).map(|i| (self.object(i), self.labels[i]))
    }

    /// The object indices in a random order drawn from `rng`.
    ///
    /// ```
    /// use rand::SeedableRng;
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n2,y\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(3);
    /// let mut order = ds.shuffled(&mut rng);
    /// order.sort();
    /// assert_eq!(order, vec![0, 1]);
    /// ```
    pub fn shuffled<R: Rng + ?Sized>(&self, rng: &mut R) -> Vec<usize> {
        let mut order: Vec<usize> = (0..self.len()).collect();
        order.shuffle(rng);
        order
    }

    /// The price of each feature.
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1.5\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert_eq!(ds.costs().total().get(), 1.5);
    /// ```
    pub fn costs(&self) -> &FeatureCosts {
        &self.costs
    }

    /// The column name of a feature.
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert_eq!(ds.feature_name(cslearn::FeatureId(0)), Some("a"));
    /// ```
    pub fn feature_name(&self, feature: FeatureId) -> Option<&str> {
        self.columns.get(feature.index()).map(|c| c.name.as_str())
    }

    /// The feature read from column `name`.
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert_eq!(ds.feature_id("t"), None); // the target is not a feature
    /// ```
    pub fn feature_id(&self, name: &str) -> Option<FeatureId> {
        self.columns
            .iter()
            .position(|c| c.name == name)
            .map(|i| FeatureId(i as u32))
    }

    /// The name of a value: the category, or the numeric bin as an interval.
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n5,y\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert_eq!(ds.value_name(cslearn::FeatureId(0), cslearn::Value(0)), Some("<= 2"));
    /// ```
    pub fn value_name(&self, feature: FeatureId, value: Value) -> Option<&str> {
        let column = self.columns.get(feature.index())?;
        column.values.get(value.0 as usize).map(String::as_str)
    }

    /// For a binned numeric feature, the cut points between its bins.
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n5,y\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert_eq!(ds.cut_points(cslearn::FeatureId(0)), Some(&[2.0, 3.0, 4.0][..]));
    /// ```
    pub fn cut_points(&self, feature: FeatureId) -> Option<&[f64]> {
        self.columns.get(feature.index())?.cuts.as_deref()
    }

    /// The name of a class: the target text, or for a positive-if split `not EXPR`
    /// (class 0) and `EXPR` (class 1).
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,3\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t").positive_if(">0")).unwrap();
    /// assert_eq!(ds.class_name(cslearn::ClassId(1)), Some("t >0"));
    /// ```
    pub fn class_name(&self, class: ClassId) -> Option<&str> {
        self.class_names.get(class.0 as usize).map(String::as_str)
    }

    /// The name of the target column.
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert_eq!(ds.target(), "t");
    /// ```
    pub fn target(&self) -> &str {
        &self.target
    }

    /// The number of classes.
    ///
    /// ```
    /// # let ds = cslearn::Dataset::from_readers("a,t\n1,x\n2,y\n".as_bytes(), "d", "feature,cost\na,1\n".as_bytes(), "c", &cslearn::DatasetOptions::new("t")).unwrap();
    /// assert_eq!(ds.class_count(), 2);
    /// ```
    pub fn class_count(&self) -> usize {
        self.class_names.len()
    }
}

impl Labels for Dataset {
    fn feature(&self, feature: FeatureId) -> String {
        self.feature_name(feature)
            .map_or_else(|| feature.to_string(), str::to_string)
    }
    fn value(&self, feature: FeatureId, value: Value) -> String {
        self.value_name(feature, value)
            .map_or_else(|| value.to_string(), str::to_string)
    }
    fn class(&self, class: ClassId) -> String {
        self.class_name(class)
            .map_or_else(|| class.to_string(), str::to_string)
    }
}

/// The values of one column and its description.
fn encode_column(name: &str, cells: &[&str], binning: Binning) -> (Column, Vec<Option<Value>>) {
    let present = cells.iter().filter(|c| !is_missing(c));
    let numbers: Option<Vec<f64>> = present.clone().map(|c| parse_number(c)).collect();
    if let (Binning::Quantiles(bins), Some(mut xs)) = (binning, numbers)
        && !xs.is_empty()
    {
        xs.sort_by(f64::total_cmp);
        let cuts = quantile_cuts(&xs, bins.get());
        let values = cells
            .iter()
            .map(|c| {
                let x = parse_number(c)?;
                Some(Value(cuts.partition_point(|&cut| cut < x) as u32))
            })
            .collect();
        let column = Column {
            name: name.to_string(),
            values: bin_names(&cuts),
            cuts: Some(cuts),
        };
        return (column, values);
    }
    let texts = distinct_sorted(present.copied());
    let index = index_of(&texts);
    let values = cells
        .iter()
        .map(|c| {
            if is_missing(c) {
                return None;
            }
            index.get(c).map(|&i| Value(i))
        })
        .collect();
    let column = Column {
        name: name.to_string(),
        values: texts,
        cuts: None,
    };
    (column, values)
}

/// The class of every record and the class names.
pub(crate) fn classes(
    table: &Table,
    target: usize,
    condition: Option<&Condition>,
    path: &Path,
) -> Result<(Vec<ClassId>, Vec<String>), Error> {
    let mut cells = Vec::with_capacity(table.len());
    for (line, record) in table.records() {
        let cell = record.get(target);
        if is_missing(cell) {
            return Err(Error::MissingTarget {
                path: path.to_path_buf(),
                line,
            });
        }
        cells.push((line, cell));
    }
    let target_name = &table.header[target];
    if let Some(condition) = condition {
        let labels = cells
            .iter()
            .map(|&(line, cell)| {
                let holds = condition
                    .holds(cell)
                    .map_err(|()| Error::NonNumericTarget {
                        path: path.to_path_buf(),
                        line,
                        text: cell.to_string(),
                    })?;
                Ok(ClassId(u32::from(holds)))
            })
            .collect::<Result<Vec<_>, Error>>()?;
        if !labels.contains(&ClassId(1)) {
            // Every object would be negative: a misspelt or miscased rule, most likely.
            let values = distinct_sorted(cells.iter().map(|&(_, c)| c));
            return Err(Error::PositiveIfMatchesNothing {
                path: path.to_path_buf(),
                column: target_name.clone(),
                expr: describe(condition),
                count: values.len(),
                values: values.into_iter().take(SHOWN_VALUES).collect(),
            });
        }
        let expr = format!("{target_name} {}", describe(condition));
        return Ok((labels, vec![format!("not {expr}"), expr]));
    }
    let names = distinct_sorted(cells.iter().map(|&(_, c)| c));
    let index = index_of(&names);
    let labels = cells
        .iter()
        .map(|&(_, c)| ClassId(index.get(c).copied().unwrap_or(0)))
        .collect();
    Ok((labels, names))
}

/// How many of a column's values an error names (the count says how many there are).
const SHOWN_VALUES: usize = 5;

/// The distinct texts, in [`sort_texts`] order.
fn distinct_sorted<'a>(texts: impl Iterator<Item = &'a str>) -> Vec<String> {
    let distinct: BTreeSet<&str> = texts.collect();
    let mut texts: Vec<String> = distinct.into_iter().map(str::to_string).collect();
    sort_texts(&mut texts);
    texts
}

/// Each text's position in `texts`, so that a cell finds its value in logarithmic time.
fn index_of(texts: &[String]) -> BTreeMap<&str, u32> {
    texts
        .iter()
        .enumerate()
        .map(|(i, t)| (t.as_str(), i as u32))
        .collect()
}

/// The largest total cost a data set may lead to: the sum of all prices times the number
/// of objects. Below it, every total a learner reports over the objects (a stream, a
/// held-out part, the folds) is a finite number, with room for rounding.
///
/// ```
/// assert_eq!(cslearn::MAX_TOTAL_COST, 1e300);
/// ```
pub const MAX_TOTAL_COST: f64 = 1e300;

/// Refuse prices whose total over `objects` objects cannot be represented.
pub(crate) fn check_totals(costs: &FeatureCosts, objects: usize, path: &Path) -> Result<(), Error> {
    // Summed without saturation: an infinite sum must show as one.
    let per_object: f64 = costs.as_slice().iter().map(|c| c.get()).sum();
    let total = per_object * objects as f64;
    if total.is_finite() && total <= MAX_TOTAL_COST {
        Ok(())
    } else {
        Err(Error::CostsTooLarge {
            path: path.to_path_buf(),
            per_object,
            objects,
            max: MAX_TOTAL_COST,
        })
    }
}

fn describe(condition: &Condition) -> String {
    let op = match condition.op {
        Op::Gt => ">",
        Op::Ge => ">=",
        Op::Lt => "<",
        Op::Le => "<=",
        Op::Eq => "==",
        Op::Ne => "!=",
    };
    format!("{op}{}", condition.text)
}

/// Read the costs file for the feature columns `names`.
pub(crate) fn read_costs(
    reader: impl Read,
    path: &Path,
    names: &[&str],
    target: &str,
) -> Result<FeatureCosts, Error> {
    let table = read_table(reader, path)?;
    let header_ok = table.header.len() == 2
        && table.header[0].eq_ignore_ascii_case("feature")
        && table.header[1].eq_ignore_ascii_case("cost");
    if !header_ok {
        return Err(Error::CostsHeader {
            path: path.to_path_buf(),
            found: table.header,
        });
    }
    let mut costs: Vec<Option<Cost>> = vec![None; names.len()];
    let path_buf = || -> PathBuf { path.to_path_buf() };
    let index: BTreeMap<&str, usize> = names.iter().enumerate().map(|(i, &n)| (n, i)).collect();
    for (line, record) in table.records() {
        let (feature, text) = (&record[0], &record[1]);
        if feature == target {
            continue;
        }
        let Some(&f) = index.get(feature) else {
            return Err(Error::UnknownCostFeature {
                path: path_buf(),
                line,
                feature: feature.to_string(),
            });
        };
        if costs[f].is_some() {
            return Err(Error::DuplicateCost {
                path: path_buf(),
                line,
                feature: feature.to_string(),
            });
        }
        let cost = text
            .parse::<f64>()
            .ok()
            .and_then(|x| Cost::new(x).ok())
            .ok_or_else(|| Error::BadCost {
                path: path_buf(),
                line,
                feature: feature.to_string(),
                text: text.to_string(),
            })?;
        costs[f] = Some(cost);
    }
    let costs = costs
        .into_iter()
        .zip(names)
        .map(|(c, name)| {
            c.ok_or_else(|| Error::MissingCost {
                path: path_buf(),
                feature: name.to_string(),
            })
        })
        .collect::<Result<Vec<_>, Error>>()?;
    Ok(FeatureCosts::new(costs))
}

/// Why a header cannot name columns: one of its names holds a control character (a
/// terminal's escape sequence would be printed raw in every message that names the
/// column); `None` when every name is printable text.
pub(crate) fn unprintable_name<S: AsRef<str>>(header: &[S]) -> Option<String> {
    header.iter().enumerate().find_map(|(i, name)| {
        let bad = name.as_ref().chars().find(|c| c.is_control())?;
        Some(format!(
            "column {}'s name holds the control character U+{:04X}; a column name must be \
             printable text",
            i + 1,
            u32::from(bad)
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_past_its_cells_is_refused_at_the_record_that_passes_them() {
        let text = "a,b\n1,2\n3,4\n5,6\n";
        let table = read_table_within(text.as_bytes(), "t.csv".as_ref(), 6).unwrap();
        assert_eq!(table.len(), 3);
        let cells: Vec<&str> = table.column(1).collect();
        assert_eq!(cells, ["2", "4", "6"]);
        let err = read_table_within(text.as_bytes(), "t.csv".as_ref(), 5).unwrap_err();
        assert!(
            matches!(
                err,
                Error::TooManyCells {
                    line: 4,
                    max: 5,
                    ..
                }
            ),
            "{err:?}"
        );
        assert_eq!(
            err.to_string(),
            "t.csv: line 4: more than the 5 cells (records times columns) a table may have"
        );
    }

    #[test]
    fn cells_keep_their_unquoted_trimmed_text() {
        let text = "a,b\n\" x \",\"y,\"\"z\"\"\"\n,?\n";
        let table = read_table(text.as_bytes(), "t.csv".as_ref()).unwrap();
        let rows: Vec<(u64, String, String)> = table
            .records()
            .map(|(line, r)| (line, r[0].to_string(), r[1].to_string()))
            .collect();
        assert_eq!(
            rows,
            [
                (2, "x".to_string(), "y,\"z\"".to_string()),
                (3, String::new(), "?".to_string())
            ]
        );
    }
}
