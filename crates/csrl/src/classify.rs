//! `csrl classify`: stream a CSV table of objects through an incremental cost-sensitive
//! learner and report its errors and measuring costs.

use std::path::PathBuf;

use std::io::Write;

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use cslearn::{Dataset, DatasetOptions, LearnerKind};

/// The learners `csrl classify` can run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Learner {
    /// CS-ID3: I^2/C selection, cheapest-first discrimination.
    CsId3,
    /// CS-IBL: instances ranked by mismatches, tolerant of wrong values.
    CsIbl,
    /// Cost-blind ID3: every cost taken as equal, random discrimination order.
    Id3,
}

/// Arguments of `csrl classify`.
#[derive(Args)]
pub struct ClassifyArgs {
    /// The data: a CSV file with a header, one object per row; empty cells and `?` are
    /// missing values.
    #[arg(long, value_name = "FILE.csv")]
    data: PathBuf,
    /// The price of each feature: a CSV file with the header `feature,cost`.
    #[arg(long, value_name = "FILE.csv")]
    costs: PathBuf,
    /// The column holding the class.
    #[arg(long, value_name = "COLUMN")]
    target: String,
    /// Make two classes of the target: where EXPR holds and where not. EXPR is `>0`,
    /// `>=1`, `<2`, `<=2`, `==1`, `!=0` or a category name.
    #[arg(long, value_name = "EXPR", allow_hyphen_values = true)]
    positive_if: Option<String>,
    /// The learner.
    #[arg(long, value_enum)]
    learner: Learner,
    /// The seed of the random order of the objects (and of ID3's discrimination orders).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// CS-IBL only: the most wrong feature values tolerated per object.
    #[arg(long, default_value_t = 1)]
    tolerance: u32,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
}

/// Run `csrl classify`.
pub fn run(args: &ClassifyArgs, out: &mut dyn Write) -> Result<()> {
    let mut options = DatasetOptions::new(args.target.as_str());
    options.positive_if.clone_from(&args.positive_if);
    let data = Dataset::load(&args.data, &args.costs, &options).context("cannot load the data")?;
    let (kind, name) = match args.learner {
        Learner::CsId3 => (LearnerKind::CsId3, "cs-id3"),
        Learner::CsIbl => (
            LearnerKind::CsIbl {
                tolerance: args.tolerance,
            },
            "cs-ibl",
        ),
        Learner::Id3 => (LearnerKind::Id3, "id3"),
    };
    // A sign of life on long streams: a bar on a terminal's stderr, nothing otherwise.
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(data.len() as u64),
        indicatif::ProgressDrawTarget::stderr(),
    );
    let report = cslearn::stream_dataset_with_progress(&data, kind, args.seed, &mut |done, _| {
        bar.set_position(done as u64);
    });
    bar.finish_and_clear();
    if args.json {
        let json = serde_json::json!({
            "learner": name,
            "seed": args.seed,
            "data": args.data.display().to_string(),
            "features": data.feature_count(),
            "classes": data.class_count(),
            "objects": report.objects,
            "errors": report.errors,
            "accuracy": report.accuracy,
            "total_cost": report.total_cost,
            "mean_cost": report.mean_cost,
            "full_cost": report.full_cost,
        });
        writeln!(out, "{json}")?;
    } else {
        writeln!(out, "learner     {name} (seed {})", args.seed)?;
        writeln!(
            out,
            "data        {} ({} features, {} classes)",
            args.data.display(),
            data.feature_count(),
            data.class_count()
        )?;
        writeln!(out, "objects     {}", report.objects)?;
        writeln!(out, "errors      {}", report.errors)?;
        writeln!(out, "accuracy    {:.3}", report.accuracy)?;
        writeln!(out, "total cost  {:.2}", report.total_cost)?;
        writeln!(out, "mean cost   {:.2} per object", report.mean_cost)?;
        writeln!(
            out,
            "full cost   {:.2} per object (measuring every feature)",
            report.full_cost
        )?;
    }
    Ok(())
}
