//! `csrl predict`: classify new rows with a model saved by `csrl classify --save`.

use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;

/// Arguments of `csrl predict`.
#[derive(Args)]
pub struct PredictArgs {
    /// The model: a file written by `csrl classify --save` (format `csrl-classifier`, or
    /// `csrl-cost-tree` for a tree of the test-cost family).
    #[arg(long, value_name = "MODEL.json")]
    model: PathBuf,
    /// The rows to classify: a CSV file with a header. Columns are matched to the model's
    /// features by name, in any order; other columns (the target too) are ignored.
    #[arg(long, value_name = "FILE.csv")]
    data: PathBuf,
    /// Write the classified rows to this file instead of stdout.
    #[arg(long, value_name = "FILE.csv")]
    out: Option<PathBuf>,
    /// Add the probability of each class, one column per class named `p_CLASS`, in the
    /// model's class order: for a tree, the class weights of the leaf (or mix of leaves,
    /// below a missing value) that answered; for CS-ID3 or CS-IBL, the classes of the
    /// examples its prediction went by; either way smoothed by Laplace's rule (one added
    /// to each class, then normalised).
    #[arg(long)]
    probabilities: bool,
    /// Trees only: the most one row may pay for its tests (after group discounts; a test
    /// done once is free further down). A test that would take the row past it is not
    /// bought: the row is answered from the node that asked for it.
    #[arg(long, value_name = "B", allow_negative_numbers = true)]
    max_test_cost: Option<f64>,
    /// Trees only: the most distinct tests one row may buy, held as --max-test-cost is.
    #[arg(long, value_name = "K")]
    max_tests: Option<usize>,
    /// Trees only: instead of the table, explain how the row at line LINE of --data (the
    /// header is line 1) is classified: each test it buys, in order, with what it paid,
    /// the class probabilities where it was asked for and, for VOI's trees, what it was
    /// expected to save per object; then the answer and its probabilities.
    #[arg(long, value_name = "LINE")]
    explain: Option<u64>,
}

/// Quote a CSV field when it needs it.
fn field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) || text.trim() != text {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// A model of either format, as `predict` uses it.
enum Loaded {
    Classifier(cslearn::Model),
    Tree(cslearn::testcost::TreeModel),
}

impl Loaded {
    fn class_name(&self, class: cslearn::ClassId) -> Option<&str> {
        match self {
            Loaded::Classifier(m) => m.class_name(class),
            Loaded::Tree(m) => m.class_name(class.0),
        }
    }

    /// The names of the classes, in class order.
    fn class_names(&self) -> Vec<&str> {
        (0u32..)
            .map_while(|c| self.class_name(cslearn::ClassId(c)))
            .collect()
    }

    fn feature_name(&self, feature: cslearn::FeatureId) -> Option<&str> {
        match self {
            Loaded::Classifier(m) => m.feature_name(feature),
            Loaded::Tree(m) => m.feature_names().get(feature.index()).copied(),
        }
    }

    fn predict_file_each(
        &self,
        path: &std::path::Path,
        budget: &cslearn::testcost::Budget,
        each: &mut dyn FnMut(cslearn::Prediction, usize),
    ) -> Result<usize, cslearn::Error> {
        match self {
            Loaded::Classifier(m) => m.predict_file_each(path, each),
            Loaded::Tree(m) => m.predict_file_each_within(path, budget, each),
        }
    }

    /// The learner and the size of what it learned, for the summary.
    fn describe(&self) -> String {
        match self {
            Loaded::Classifier(m) => {
                let name = match m.learner() {
                    cslearn::LearnerKind::CsId3 => "cs-id3",
                    cslearn::LearnerKind::CsIbl { .. } => "cs-ibl",
                    cslearn::LearnerKind::Id3 => "id3",
                };
                format!("{name}, {} examples", m.library().len())
            }
            Loaded::Tree(m) => format!("{}, {} nodes", m.learner().name(), m.tree().len()),
        }
    }
}

/// Run `csrl predict`.
pub fn run(args: &PredictArgs, out: &mut dyn Write) -> Result<()> {
    if let Some(path) = &args.out {
        // A FIFO would block the run until something reads it; a device is no file.
        let special = std::fs::metadata(path).is_ok_and(|m| !m.is_file());
        anyhow::ensure!(
            !special,
            "--out {} is not a regular file: give the name of a file to write",
            path.display()
        );
        for (input, given) in [("--model", &args.model), ("--data", &args.data)] {
            anyhow::ensure!(
                !crate::classify::same_file(path, given),
                "--out {} names the {input} file: it would overwrite it; give the output a \
                 name of its own",
                path.display()
            );
        }
    }
    let model =
        match cslearn::testcost::SavedModel::load(&args.model).context("cannot load the model")? {
            cslearn::testcost::SavedModel::Classifier(m) => Loaded::Classifier(m),
            cslearn::testcost::SavedModel::Tree(m) => Loaded::Tree(m),
        };
    let budget = crate::testcost::budget_from_flags(args.max_test_cost, args.max_tests)?;
    if let Loaded::Classifier(_) = &model
        && !budget.is_unlimited()
    {
        let flag = if args.max_test_cost.is_some() {
            "--max-test-cost"
        } else {
            "--max-tests"
        };
        anyhow::bail!(
            "{flag} is read with a tree of the test-cost family (format `csrl-cost-tree`); {} \
             is a model of {}",
            args.model.display(),
            model.describe()
        );
    }
    if let Some(line) = args.explain {
        let Loaded::Tree(tree) = &model else {
            anyhow::bail!(
                "--explain is read with a tree of the test-cost family (format \
                 `csrl-cost-tree`); {} is a model of {}",
                args.model.display(),
                model.describe()
            );
        };
        anyhow::ensure!(
            args.out.is_none() && !args.probabilities,
            "--explain prints one row's account instead of the table: it takes neither \
             --out nor --probabilities"
        );
        let why = tree
            .explain_line(&args.data, line, &budget)
            .context("cannot explain the row")?;
        write!(
            out,
            "line {line} of {}, by {} ({}):\n{}",
            args.data.display(),
            args.model.display(),
            model.describe(),
            tree.explanation_text(&why)
        )?;
        out.flush()?;
        return Ok(());
    }
    // Rows are written as they are classified, so memory does not grow with the output.
    // The table is read and checked whole before the first row comes, so `--out` is
    // created only then: a refused table leaves an existing file as it was.
    let mut file: Option<std::io::BufWriter<std::fs::File>> = None;
    let mut failed: Option<std::io::Error> = None;
    let mut started = false;
    let mut write = |text: &str| {
        if failed.is_some() {
            return;
        }
        let sink: &mut dyn Write = match (&args.out, &mut file) {
            (None, _) => &mut *out,
            (Some(_), Some(f)) => f,
            (Some(path), None) => match std::fs::File::create(path) {
                Ok(f) => file.insert(std::io::BufWriter::new(f)),
                Err(e) => {
                    failed = Some(e);
                    return;
                }
            },
        };
        if let Err(e) = sink.write_all(text.as_bytes()) {
            failed = Some(e);
        }
    };
    let mut header = String::from("line,class,cost,measured");
    if args.probabilities {
        for name in model.class_names() {
            header.push(',');
            header.push_str(&field(&format!("p_{name}")));
        }
    }
    header.push('\n');
    let bar = crate::progress::progress_bar(0);
    let mut total = 0.0;
    let mut line = String::new();
    let rows = model
        .predict_file_each(&args.data, &budget, &mut |row, rows| {
            bar.set_length(rows as u64);
            bar.inc(1);
            let class = row.class.and_then(|c| model.class_name(c)).unwrap_or("");
            let measured: Vec<&str> = row
                .measured
                .iter()
                .map(|&f| model.feature_name(f).unwrap_or("?"))
                .collect();
            total += row.cost.get();
            line.clear();
            let _ = write!(
                line,
                "{},{},{},{}",
                row.line,
                field(class),
                row.cost.get(),
                field(&measured.join(";"))
            );
            if args.probabilities {
                for p in &row.probabilities {
                    let _ = write!(line, ",{p}");
                }
            }
            line.push('\n');
            if !started {
                started = true;
                write(&header);
            }
            write(&line);
        })
        .context("cannot classify the data")?;
    bar.finish_and_clear();
    let flushed = match &mut file {
        Some(f) => f.flush(),
        None => out.flush(),
    };
    match (failed.or(flushed.err()), &args.out) {
        (None, _) => {}
        (Some(e), Some(path)) => return Err(crate::cannot_write(path, e)),
        (Some(e), None) => return Err(e.into()),
    }
    crate::note(format_args!(
        "classified {} row{} of {} with {} ({}): total cost {}, mean {:.4} per row{}",
        rows,
        if rows == 1 { "" } else { "s" },
        args.data.display(),
        args.model.display(),
        model.describe(),
        total,
        total / rows.max(1) as f64,
        args.out
            .as_ref()
            .map_or(String::new(), |p| format!("; written to {}", p.display()))
    ));
    Ok(())
}
