//! `csrl predict`: classify new rows with a model saved by `csrl classify --save`.

use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;

/// Arguments of `csrl predict`.
#[derive(Args)]
pub struct PredictArgs {
    /// The model: a file written by `csrl classify --save`.
    #[arg(long, value_name = "MODEL.json")]
    model: PathBuf,
    /// The rows to classify: a CSV file with a header. Columns are matched to the model's
    /// features by name, in any order; other columns (the target too) are ignored.
    #[arg(long, value_name = "FILE.csv")]
    data: PathBuf,
    /// Write the classified rows to this file instead of stdout.
    #[arg(long, value_name = "FILE.csv")]
    out: Option<PathBuf>,
}

/// Quote a CSV field when it needs it.
fn field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) || text.trim() != text {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// Run `csrl predict`.
pub fn run(args: &PredictArgs, out: &mut dyn Write) -> Result<()> {
    let model = cslearn::Model::load(&args.model).context("cannot load the model")?;
    let bar = crate::classify::progress_bar(0);
    let rows = model
        .predict_file(&args.data, &mut |done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        })
        .context("cannot classify the data")?;
    bar.finish_and_clear();
    let mut text = String::from("line,class,cost,measured\n");
    let mut total = 0.0;
    for row in &rows {
        let class = row.class.and_then(|c| model.class_name(c)).unwrap_or("");
        let measured: Vec<&str> = row
            .measured
            .iter()
            .map(|&f| model.feature_name(f).unwrap_or("?"))
            .collect();
        total += row.cost.get();
        let _ = writeln!(
            text,
            "{},{},{},{}",
            row.line,
            field(class),
            row.cost.get(),
            field(&measured.join(";"))
        );
    }
    match &args.out {
        Some(path) => crate::write_file(path, &text)?,
        None => out.write_all(text.as_bytes())?,
    }
    let name = match model.learner() {
        cslearn::LearnerKind::CsId3 => "cs-id3",
        cslearn::LearnerKind::CsIbl { .. } => "cs-ibl",
        cslearn::LearnerKind::Id3 => "id3",
    };
    crate::note(format_args!(
        "classified {} row{} of {} with {} ({name}, {} examples): total cost {}, mean {:.4} per row{}",
        rows.len(),
        if rows.len() == 1 { "" } else { "s" },
        args.data.display(),
        args.model.display(),
        model.library().len(),
        total,
        total / rows.len().max(1) as f64,
        args.out
            .as_ref()
            .map_or(String::new(), |p| format!("; written to {}", p.display()))
    ));
    Ok(())
}
