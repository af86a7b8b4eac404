//! `cargo xtask anytime`: ACT's cost against its time as its number of samples `r` grows,
//! on the benchmark's folds and prices.
//!
//! ACT is an anytime learner: each candidate test is valued by the cheapest of `r` trees
//! sampled under each of its branches, so more samples give a better estimate for more
//! time. For each `r` the sweep runs `cargo xtask testcost --learners act --act-samples r`
//! (random prices, listed selection prices, the benchmark's seed and folds) into a folder of
//! its own, then writes `anytime.csv` (per data set, `r` and mc: the mean normalised cost,
//! its 95% interval and the milliseconds per tree), `anytime.md` and `anytime.svg` (a panel
//! per data set: cost against time, one line per mc, each point one `r`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use plotters::prelude::*;

use super::{TestcostArgs, testcost};
use crate::figures::{PALETTE, marker};

/// Arguments of `cargo xtask anytime`.
#[derive(Args, Clone, Debug)]
pub struct AnytimeArgs {
    /// Data sets, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "monks1,heart,pima,tic-tac-toe"
    )]
    datasets: Vec<String>,
    /// ACT's samples per branch (`r`), comma-separated, each at most 1000.
    #[arg(long, value_delimiter = ',', default_value = "1,3,5,10,20")]
    samples: Vec<usize>,
    /// Uniform misclassification costs, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "500,1000")]
    mc: Vec<f64>,
    /// Random price assignments per data set.
    #[arg(long, default_value_t = 4)]
    assignments: u64,
    /// Runs of 10-fold cross-validation per data set and price assignment.
    #[arg(long, default_value_t = 1)]
    runs: u64,
    /// Worker threads (default: every core); the costs do not depend on it, the times do.
    #[arg(long)]
    threads: Option<usize>,
    /// The manifest of the data sets.
    #[arg(long, default_value = "data/uci/datasets.toml")]
    manifest: PathBuf,
    /// Output folder (one `testcost` folder per `r` inside, and the sweep's files).
    #[arg(long, default_value = "results/anytime")]
    out: PathBuf,
    /// Also write `anytime.csv`, `anytime.md` and `anytime.svg` into `docs/testcost/`.
    #[arg(long)]
    bless: bool,
}

/// One point of the sweep.
#[derive(Clone, Debug, PartialEq)]
struct Point {
    dataset: String,
    samples: usize,
    mc: f64,
    cost: f64,
    ci95: f64,
    ms_per_tree: f64,
}

/// The benchmark's arguments for one `r`.
fn testcost_args(args: &AnytimeArgs, samples: usize, out: PathBuf) -> TestcostArgs {
    TestcostArgs {
        datasets: args.datasets.clone(),
        learners: vec!["act".into()],
        mc: args.mc.clone(),
        costs: vec!["random".into()],
        assignments: args.assignments,
        price_draw: "uniform".into(),
        selection_prices: "listed".into(),
        icet_pruning: "costs".into(),
        icet_search_objects: 1000,
        cvt_folds: 5,
        act_samples: samples,
        cvt_samples: 5,
        voi_lookahead: None,
        voi_confidence: None,
        voi_m: None,
        max_tests: None,
        max_test_cost: None,
        price_range: vec![1.0, 100.0],
        runs: args.runs,
        folds: 10,
        seed: 1,
        manifest: args.manifest.clone(),
        out,
        threads: args.threads,
        shard: "1/1".into(),
        with: Vec::new(),
        python: None,
        report: false,
        bless: false,
    }
}

/// The rows of a CSV file written by the benchmark, by column name.
fn read_csv(path: &Path) -> Result<Vec<std::collections::BTreeMap<String, String>>> {
    let text = std::fs::read_to_string(path).with_context(|| format!("{}", path.display()))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines
        .next()
        .with_context(|| format!("{}: empty", path.display()))?
        .split(',')
        .collect();
    Ok(lines
        .map(|l| {
            header
                .iter()
                .zip(l.split(','))
                .map(|(h, v)| (h.to_string(), v.to_string()))
                .collect()
        })
        .collect())
}

/// A number of a row, or an error naming the file and the column.
fn number(row: &std::collections::BTreeMap<String, String>, key: &str, path: &Path) -> Result<f64> {
    row.get(key)
        .and_then(|v| v.parse().ok())
        .ok_or_else(|| anyhow!("{}: no number in column `{key}`", path.display()))
}

/// The points of one `r`, read from its benchmark folder.
fn points_of(dir: &Path, samples: usize) -> Result<Vec<Point>> {
    let table = dir.join("testcost.csv");
    let timing = dir.join("timing.csv");
    let times = read_csv(&timing)?;
    let mut points = Vec::new();
    for row in read_csv(&table)? {
        if row.get("learner").map(String::as_str) != Some("act") {
            continue;
        }
        let dataset = row.get("dataset").cloned().unwrap_or_default();
        let time = times
            .iter()
            .find(|t| {
                t.get("dataset") == Some(&dataset)
                    && t.get("learner").map(String::as_str) == Some("act")
            })
            .with_context(|| format!("{}: no time for {dataset}", timing.display()))?;
        points.push(Point {
            samples,
            mc: number(&row, "mc", &table)?,
            cost: number(&row, "normalised_cost", &table)?,
            ci95: number(&row, "ci95", &table)?,
            ms_per_tree: number(time, "ms_per_tree", &timing)?,
            dataset,
        });
    }
    Ok(points)
}

/// `cargo xtask anytime`.
pub fn anytime(args: &AnytimeArgs) -> Result<()> {
    if args.samples.is_empty() || args.datasets.is_empty() || args.mc.is_empty() {
        bail!("anytime needs at least one data set, one --samples and one --mc");
    }
    crate::files::distinct("--samples", &args.samples)?;
    let mut points = Vec::new();
    for &samples in &args.samples {
        crate::note(&format!("ACT with {samples} samples per branch"));
        let dir = args.out.join(format!("r{samples}"));
        testcost(&testcost_args(args, samples, dir.clone()))?;
        points.extend(points_of(&dir, samples)?);
    }
    points.sort_by(|a, b| {
        (a.dataset.as_str(), a.mc, a.samples)
            .partial_cmp(&(b.dataset.as_str(), b.mc, b.samples))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let mut targets = vec![args.out.clone()];
    if args.bless {
        targets.push(PathBuf::from("docs/testcost"));
    }
    for dir in &targets {
        write(dir, args, &points)?;
    }
    crate::emit(&table(args, &points))?;
    Ok(())
}

/// `anytime.csv`, `anytime.md` and `anytime.svg` into `dir`.
fn write(dir: &Path, args: &AnytimeArgs, points: &[Point]) -> Result<()> {
    let mut csv = String::from("dataset,samples,mc,normalised_cost,ci95,ms_per_tree\n");
    for p in points {
        let _ = writeln!(
            csv,
            "{},{},{},{:.3},{:.3},{:.3}",
            p.dataset, p.samples, p.mc, p.cost, p.ci95, p.ms_per_tree
        );
    }
    crate::files::write_atomic(&dir.join("anytime.csv"), csv)?;
    crate::files::write_atomic(&dir.join("anytime.md"), table(args, points))?;
    figure(&dir.join("anytime.svg"), args, points)
}

/// The Markdown table: per data set and mc, the cost and time of each `r`.
fn table(args: &AnytimeArgs, points: &[Point]) -> String {
    let mut md = String::from("# ACT's cost against its time, by samples per branch\n\n");
    let _ = writeln!(
        md,
        "`cargo xtask anytime --datasets {} --samples {} --mc {} --assignments {} --runs {}`: \
         random prices, listed selection prices, the benchmark's folds and seed; mean \
         normalised cost (% of the standard cost) ± its 95% interval over runs and draws, \
         and in parentheses the milliseconds per tree (learning time over trees, measured).\n",
        args.datasets.join(","),
        args.samples
            .iter()
            .map(usize::to_string)
            .collect::<Vec<_>>()
            .join(","),
        args.mc
            .iter()
            .map(f64::to_string)
            .collect::<Vec<_>>()
            .join(","),
        args.assignments,
        args.runs
    );
    let _ = write!(md, "| data set | mc |");
    for r in &args.samples {
        let _ = write!(md, " r = {r} |");
    }
    let _ = write!(md, "\n|---|---|{}\n", "---|".repeat(args.samples.len()));
    for d in &args.datasets {
        for &mc in &args.mc {
            let _ = write!(md, "| {d} | {mc} |");
            for &r in &args.samples {
                match points
                    .iter()
                    .find(|p| &p.dataset == d && p.mc == mc && p.samples == r)
                {
                    Some(p) => {
                        let _ = write!(
                            md,
                            " {:.1} ± {:.1} ({:.1}) |",
                            p.cost, p.ci95, p.ms_per_tree
                        );
                    }
                    None => md.push_str(" - |"),
                }
            }
            md.push('\n');
        }
    }
    md.push_str("\n![ACT's cost against its time](anytime.svg)\n");
    md
}

/// A panel per data set: cost against milliseconds per tree (log scale), one line per mc,
/// each point an `r` (labelled).
fn figure(path: &Path, args: &AnytimeArgs, points: &[Point]) -> Result<()> {
    crate::figures::register_font();
    let plot_err = |e: &dyn std::fmt::Display| anyhow!("drawing {}: {e}", path.display());
    let cols = args.datasets.len().min(2);
    let rows = args.datasets.len().div_ceil(cols);
    let (pw, ph) = (520_u32, 380_u32);
    let mut svg = String::new();
    {
        let base = SVGBackend::with_string(&mut svg, (pw * cols as u32, ph * rows as u32 + 40))
            .into_drawing_area();
        base.fill(&WHITE).map_err(|e| plot_err(&e))?;
        let root = base
            .titled(
                "ACT: cost against time per tree as the samples per branch grow (r = 1 to 20)",
                ("sans-serif", 20),
            )
            .map_err(|e| plot_err(&e))?;
        let panels = root.split_evenly((rows, cols));
        for (panel, d) in panels.iter().zip(&args.datasets) {
            let mine: Vec<&Point> = points.iter().filter(|p| &p.dataset == d).collect();
            if mine.is_empty() {
                continue;
            }
            let (tlo, thi) = mine.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), p| {
                (lo.min(p.ms_per_tree), hi.max(p.ms_per_tree))
            });
            let (clo, chi) = mine.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), p| {
                (lo.min(p.cost), hi.max(p.cost))
            });
            let pad = ((chi - clo) * 0.15).max(0.5);
            let (tlo, thi) = (tlo.max(1e-3) / 1.5, thi.max(tlo * 2.0) * 1.5);
            // Ticks at 1, 2 and 5 times the powers of ten in the range.
            let ticks: Vec<f64> = (-3..7)
                .flat_map(|e| [1.0, 2.0, 5.0].map(|m| m * 10f64.powi(e)))
                .filter(|t| (tlo..=thi).contains(t))
                .collect();
            let mut chart = ChartBuilder::on(panel)
                .caption(d, ("sans-serif", 18))
                .margin(12)
                .x_label_area_size(44)
                .y_label_area_size(60)
                .build_cartesian_2d(
                    (tlo..thi).log_scale().with_key_points(ticks),
                    // Room above the points for the legend.
                    (clo - pad)..(chi + 4.0 * pad),
                )
                .map_err(|e| plot_err(&e))?;
            chart
                .configure_mesh()
                .x_desc("ms per tree (log scale)")
                .y_desc("cost, % of standard")
                .axis_desc_style(("sans-serif", 14))
                .label_style(("sans-serif", 13))
                .light_line_style(WHITE)
                .bold_line_style(RGBColor(230, 230, 230))
                .x_label_formatter(&|x| {
                    if *x < 1.0 {
                        format!("{x}")
                    } else {
                        crate::figures::short(*x)
                    }
                })
                .y_label_formatter(&|y| format!("{y:.1}"))
                .draw()
                .map_err(|e| plot_err(&e))?;
            for (k, &mc) in args.mc.iter().enumerate() {
                let color = PALETTE[k % PALETTE.len()];
                let line: Vec<(f64, f64)> = mine
                    .iter()
                    .filter(|p| p.mc == mc)
                    .map(|p| (p.ms_per_tree, p.cost))
                    .collect();
                chart
                    .draw_series(LineSeries::new(line.clone(), color.stroke_width(2)))
                    .map_err(|e| plot_err(&e))?
                    .label(format!("mc {mc}"))
                    .legend(move |(x, y)| {
                        EmptyElement::at((x + 12, y))
                            + PathElement::new(vec![(-12, 0), (12, 0)], color.stroke_width(2))
                            + marker::<SVGBackend<'_>>(k, (0, 0), color)
                    });
                chart
                    .draw_series(mine.iter().filter(|p| p.mc == mc).map(|p| {
                        EmptyElement::at((p.ms_per_tree, p.cost))
                            + marker::<SVGBackend<'_>>(k, (0, 0), color)
                            + Text::new(
                                format!("r={}", p.samples),
                                (6, -16),
                                ("sans-serif", 12).into_font().color(&RGBColor(80, 80, 80)),
                            )
                    }))
                    .map_err(|e| plot_err(&e))?;
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.9))
                .border_style(RGBColor(150, 150, 150))
                .label_font(("sans-serif", 13))
                .draw()
                .map_err(|e| plot_err(&e))?;
        }
        root.present().map_err(|e| plot_err(&e))?;
    }
    crate::files::write_atomic(path, svg)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two values of `r` on iris: a point per `r` and mc, each read from its own benchmark
    /// folder, the costs those folders' tables give, and a figure.
    #[test]
    fn the_sweep_reads_each_samples_benchmark() {
        let out = tempfile::tempdir().unwrap();
        let args = AnytimeArgs {
            datasets: vec!["iris".into()],
            samples: vec![0, 2],
            mc: vec![100.0, 1000.0],
            assignments: 1,
            runs: 1,
            threads: Some(1),
            manifest: Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/uci/datasets.toml"),
            out: out.path().to_path_buf(),
            bless: false,
        };
        anytime(&args).unwrap();
        let csv = std::fs::read_to_string(out.path().join("anytime.csv")).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 1 + 2 * 2, "{csv}");
        for r in [0, 2] {
            let table =
                std::fs::read_to_string(out.path().join(format!("r{r}/testcost.csv"))).unwrap();
            for mc in ["100", "1000"] {
                let cost = table
                    .lines()
                    .find(|l| l.starts_with(&format!("iris,random,{mc},act,")))
                    .unwrap()
                    .split(',')
                    .nth(6)
                    .unwrap()
                    .to_string();
                let point = format!("iris,{r},{mc},{cost},");
                assert!(csv.contains(&point), "{point} not in {csv}");
            }
        }
        let md = std::fs::read_to_string(out.path().join("anytime.md")).unwrap();
        assert!(
            md.contains("| iris | 100 |") && md.contains("r = 2"),
            "{md}"
        );
        let svg = std::fs::read_to_string(out.path().join("anytime.svg")).unwrap();
        crate::render::check(&svg, "anytime.svg").unwrap();
        let refused = AnytimeArgs {
            samples: vec![2, 2],
            ..args
        };
        let e = anytime(&refused).unwrap_err().to_string();
        assert!(e.contains("--samples") && e.contains("twice"), "{e}");
    }
}
