//! The crate's one error type.

use std::path::PathBuf;

/// Everything that can go wrong: an invalid cost, or a data or costs file that cannot be
/// used. Variants about a file name it and, where there is one, the 1-based line. The
/// operating system's or the CSV reader's own error, where there is one, is the
/// [`source`](std::error::Error::source), not repeated in the message.
///
/// ```
/// let err = cslearn::Cost::new(-3.0).unwrap_err();
/// assert!(matches!(err, cslearn::Error::InvalidCost { .. }));
/// assert_eq!(err.to_string(), "invalid cost -3: costs must be finite and not negative");
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A cost is negative, infinite or NaN.
    #[error("invalid cost {value}: costs must be finite and not negative")]
    InvalidCost {
        /// The rejected number.
        value: f64,
    },
    /// A path that is not a regular file (a directory, a device, a pipe), refused before
    /// it is opened.
    #[error("{}: not a regular file", path.display())]
    NotAFile {
        /// The path.
        path: PathBuf,
    },
    /// A file longer than [`MAX_FILE_BYTES`](crate::MAX_FILE_BYTES); reading stopped there.
    #[error("{}: longer than the {max} bytes a data or costs file may have", path.display())]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// The limit.
        max: u64,
    },
    /// A quoted field is never closed: the quote opens on `line` and the file ends inside it.
    #[error("{}: line {line}: a quoted field is never closed (its quote opens here)", path.display())]
    UnterminatedQuote {
        /// The file.
        path: PathBuf,
        /// The line of the opening quote.
        line: u64,
    },
    /// A file could not be opened or read.
    #[error("{}: cannot read", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// A file is not UTF-8 text.
    #[error("{}: line {line}: not UTF-8 text", path.display())]
    NotUtf8 {
        /// The file.
        path: PathBuf,
        /// The line with the first invalid byte.
        line: u64,
    },
    /// A file has no header line.
    #[error("{}: the file is empty", path.display())]
    EmptyFile {
        /// The file.
        path: PathBuf,
    },
    /// A file has a header but no records.
    #[error("{}: the file has a header but no records", path.display())]
    NoRecords {
        /// The file.
        path: PathBuf,
    },
    /// A record has more or fewer fields than the header.
    #[error("{}: line {line}: {found} fields, but the header has {expected}", path.display())]
    RaggedRecord {
        /// The file.
        path: PathBuf,
        /// The line of the record.
        line: u64,
        /// The number of fields in the header.
        expected: u64,
        /// The number of fields in the record.
        found: u64,
    },
    /// The CSV reader failed for a reason other than the ones above.
    #[error("{}: line {}: malformed CSV", path.display(), line.map_or_else(|| "?".to_string(), |l| l.to_string()))]
    Malformed {
        /// The file.
        path: PathBuf,
        /// The line, when the reader knows it.
        line: Option<u64>,
        /// The reader's error.
        source: csv::Error,
    },
    /// Two columns of the header have the same name.
    #[error("{}: column `{column}` appears twice in the header", path.display())]
    DuplicateColumn {
        /// The file.
        path: PathBuf,
        /// The repeated name.
        column: String,
    },
    /// The target column is not in the data file.
    #[error("{}: no target column `{target}` (columns: {})", path.display(), columns.join(", "))]
    UnknownTarget {
        /// The data file.
        path: PathBuf,
        /// The requested column.
        target: String,
        /// The columns the file has.
        columns: Vec<String>,
    },
    /// The data file has no column besides the target.
    #[error("{}: no feature columns besides the target", path.display())]
    NoFeatures {
        /// The data file.
        path: PathBuf,
    },
    /// A record has no value in the target column.
    #[error("{}: line {line}: the target column is empty", path.display())]
    MissingTarget {
        /// The data file.
        path: PathBuf,
        /// The line of the record.
        line: u64,
    },
    /// `--positive-if` compares numbers but a target cell is not a number.
    #[error("{}: line {line}: target value `{text}` is not a number, but the positive-if expression compares numbers", path.display())]
    NonNumericTarget {
        /// The data file.
        path: PathBuf,
        /// The line of the record.
        line: u64,
        /// The cell.
        text: String,
    },
    /// The expression that splits the target into two classes cannot be parsed.
    #[error("bad positive-if expression `{expr}`: {reason}")]
    BadExpression {
        /// The expression as given.
        expr: String,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A positive-if expression that no target value satisfies: every object would be
    /// negative.
    #[error("{}: the positive-if expression `{expr}` matches no value of column `{column}` (values present: {}{}; {count} value{})", path.display(), values.join(", "), if *count > values.len() { ", ..." } else { "" }, if *count == 1 { "" } else { "s" })]
    PositiveIfMatchesNothing {
        /// The data file.
        path: PathBuf,
        /// The target column.
        column: String,
        /// The expression, normalised (`male` reads `==male`).
        expr: String,
        /// The first few distinct target values, in class order.
        values: Vec<String>,
        /// How many distinct target values there are.
        count: usize,
    },
    /// Prices whose total over the objects cannot be represented (see
    /// [`MAX_TOTAL_COST`](crate::MAX_TOTAL_COST)).
    #[error("{}: the prices sum to {per_object:e} per object, so a total over the {objects} objects cannot be represented (the sum of all prices times the number of objects must be at most {max:e})", path.display())]
    CostsTooLarge {
        /// The costs file.
        path: PathBuf,
        /// The sum of all prices (infinite if it overflows).
        per_object: f64,
        /// The number of objects.
        objects: usize,
        /// The limit, [`MAX_TOTAL_COST`](crate::MAX_TOTAL_COST).
        max: f64,
    },
    /// The costs file's header is not `feature,cost`.
    #[error("{}: the header must be `feature,cost`, found `{}`", path.display(), found.join(","))]
    CostsHeader {
        /// The costs file.
        path: PathBuf,
        /// The header found.
        found: Vec<String>,
    },
    /// A feature column of the data has no cost.
    #[error("{}: no cost for column `{feature}`", path.display())]
    MissingCost {
        /// The costs file.
        path: PathBuf,
        /// The column without a cost.
        feature: String,
    },
    /// The costs file prices a column the data file does not have.
    #[error("{}: line {line}: cost for `{feature}`, which is not a column of the data", path.display())]
    UnknownCostFeature {
        /// The costs file.
        path: PathBuf,
        /// The line.
        line: u64,
        /// The unknown name.
        feature: String,
    },
    /// The costs file prices a column twice.
    #[error("{}: line {line}: a second cost for `{feature}`", path.display())]
    DuplicateCost {
        /// The costs file.
        path: PathBuf,
        /// The line of the repeat.
        line: u64,
        /// The column.
        feature: String,
    },
    /// A cost in the costs file is not a finite, non-negative number.
    #[error("{}: line {line}: the cost of `{feature}` is `{text}`, but costs must be finite, non-negative numbers", path.display())]
    BadCost {
        /// The costs file.
        path: PathBuf,
        /// The line.
        line: u64,
        /// The column priced.
        feature: String,
        /// The cell as written.
        text: String,
    },
    /// A model file that cannot be used: `at` says where (a line and column, a key, a
    /// feature, a library example), `reason` what is wrong there.
    #[error("{}: {at}: {reason}", path.display())]
    BadModel {
        /// The file.
        path: PathBuf,
        /// Where in it.
        at: String,
        /// What is wrong.
        reason: String,
    },
    /// An input that cannot be used: `at` says where in it (a line, the header), `reason`
    /// what is wrong there.
    #[error("{}: {at}: {reason}", path.display())]
    BadInput {
        /// The file (or the name the caller gave its source).
        path: PathBuf,
        /// Where in it.
        at: String,
        /// What is wrong.
        reason: String,
    },
    /// A value given in code that cannot be used: `what` names it, `reason` says why.
    #[error("{what}: {reason}")]
    Invalid {
        /// What was given.
        what: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A JSON file whose `format` is not a model's.
    #[error("{}: not a csrl-classifier model file (its format is `{format}`)", path.display())]
    NotAModel {
        /// The file.
        path: PathBuf,
        /// The format it says it has.
        format: String,
    },
    /// A table to classify lacks columns the model reads.
    #[error("{}: no column {}, which the model reads (columns: {})", path.display(), missing.iter().map(|m| format!("`{m}`")).collect::<Vec<_>>().join(", "), columns.join(", "))]
    MissingColumns {
        /// The file.
        path: PathBuf,
        /// The model's features that are not columns.
        missing: Vec<String>,
        /// The columns present.
        columns: Vec<String>,
    },
    /// A cell of a numeric feature that is not a finite number.
    #[error("{}: line {line}: `{text}` in column `{column}` is not a number, but the model reads that column as numbers", path.display())]
    NotANumber {
        /// The file.
        path: PathBuf,
        /// The 1-based line.
        line: u64,
        /// The column.
        column: String,
        /// The cell.
        text: String,
    },
    /// A table with more than [`MAX_CELLS`](crate::MAX_CELLS) cells.
    #[error("{}: line {line}: more than the {max} cells (records times columns) a table may have", path.display())]
    TooManyCells {
        /// The file.
        path: PathBuf,
        /// The line of the record that passed the limit.
        line: u64,
        /// The limit.
        max: u64,
    },
    /// A fit stopped before it ended, because its
    /// [`Stop`](crate::testcost::Stop) was requested; what it had grown is dropped.
    #[error("the fit was stopped before it ended")]
    Stopped,
}
