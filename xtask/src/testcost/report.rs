//! The benchmark's table, figure and report, from the job results.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Result, anyhow};
use cslearn::testcost::{Method, Pruning, SelectionPrices};
use plotters::prelude::*;

use super::published;
use super::{Definition, JobResult, Learner, PriceSet};
use crate::figures::{PALETTE, marker};

/// One row of `testcost.csv`.
#[derive(Clone, Debug)]
pub(crate) struct Row {
    pub dataset: String,
    pub costs: PriceSet,
    pub mc: f64,
    pub learner: Learner,
    /// Mean total cost as a percentage of the standard cost.
    pub normalised: f64,
    /// Half-width of the 95% interval of that mean (normal approximation).
    pub ci95: f64,
    /// Mean test cost per object.
    pub test_cost: f64,
    /// Mean error rate.
    pub error_rate: f64,
    /// Mean total cost per object, in the prices' units.
    pub total: f64,
    /// `normalised` over batch CS-ID3's on the same data set, prices, mc and runs.
    pub ratio: Option<f64>,
    /// Runs of cross-validation the row averages.
    pub runs: u64,
    /// Mean area under the ROC curve of the class probabilities, when every job of the
    /// row measured it (results written before it was measured did not).
    pub auroc: Option<f64>,
}

/// What a report shows: one benchmark's rows, and the learners other benchmarks over the
/// same folds and prices add to it.
pub(crate) struct Table {
    /// The benchmark, its learners extended by the added ones.
    pub def: Definition,
    /// In the order of data sets, price sets, mc and learners of `def`.
    pub rows: Vec<Row>,
    pub results: Vec<JobResult>,
    /// The learners other benchmarks added, one entry per benchmark.
    pub added: Vec<Added>,
}

/// Learners another benchmark added to a [`Table`], with the runs and mc it measured them at.
pub(crate) struct Added {
    pub learners: Vec<Learner>,
    pub runs: u64,
    pub mc: Vec<f64>,
}

impl Table {
    /// Adds the rows of `other`'s learners that the table lacks (`other` must be joinable:
    /// the same data sets, price sets, folds, seed and settings).
    pub(crate) fn join(&mut self, other: &Definition, rows: Vec<Row>, results: Vec<JobResult>) {
        let new: Vec<Learner> = other
            .learners
            .iter()
            .copied()
            .filter(|m| !self.def.learners.contains(m))
            .collect();
        if new.is_empty() {
            return;
        }
        self.def.learners.extend(&new);
        if new.contains(&Learner::Family(Method::Voi)) {
            self.def.take_voi(other);
        }
        // A row without a ratio (its benchmark ran no CS-ID3) takes it from the table's
        // CS-ID3 over the same runs: its row where the runs are the table's, otherwise
        // its results of those runs (the first ones, on the same folds and prices).
        let cs_id3 = Learner::Family(Method::CsId3Batch);
        let base = if other.runs == self.def.runs {
            self.rows.clone()
        } else {
            let def = Definition {
                learners: vec![cs_id3],
                ..other.clone()
            };
            let first: Vec<JobResult> = self
                .results
                .iter()
                .filter(|r| r.learner == cs_id3 && r.run < other.runs)
                .cloned()
                .collect();
            aggregate(&def, &first)
        };
        let mut rows: Vec<Row> = rows
            .into_iter()
            .filter(|r| new.contains(&r.learner))
            .collect();
        for r in rows.iter_mut().filter(|r| r.ratio.is_none()) {
            r.ratio = find(&base, &r.dataset, r.costs, r.mc, cs_id3)
                .map(|b| b.normalised)
                .filter(|b| *b > 0.0)
                .map(|b| r.normalised / b);
        }
        self.rows.extend(rows);
        self.results
            .extend(results.into_iter().filter(|r| new.contains(&r.learner)));
        let def = &self.def;
        let place = |r: &Row| {
            let at = |i: Option<usize>| i.unwrap_or(usize::MAX);
            (
                at(def.datasets.iter().position(|d| *d == r.dataset)),
                at(def.costs.iter().position(|c| *c == r.costs)),
                at(def.mc.iter().position(|m| *m == r.mc)),
                at(def.learners.iter().position(|m| *m == r.learner)),
            )
        };
        self.rows.sort_by_key(place);
        self.added.push(Added {
            learners: new,
            runs: other.runs,
            mc: other.mc.clone(),
        });
    }
}

type Key = (String, PriceSet, u64, Learner);

/// The rows, in the definition's order of data sets, price sets, mc and learners.
pub(crate) fn aggregate(def: &Definition, results: &[JobResult]) -> Vec<Row> {
    let mut cells: BTreeMap<Key, Vec<(f64, f64, f64, f64)>> = BTreeMap::new();
    let mut aurocs: BTreeMap<Key, Vec<Option<f64>>> = BTreeMap::new();
    for r in results {
        for s in &r.by_mc {
            let key = (r.dataset.clone(), r.costs, s.mc.to_bits(), r.learner);
            aurocs.entry(key.clone()).or_default().push(s.auroc);
            cells.entry(key).or_default().push((
                100.0 * s.total / s.standard,
                s.tests,
                s.error_rate,
                s.total,
            ));
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    let mut rows = Vec::new();
    for d in &def.datasets {
        for &costs in &def.costs {
            for &mc in &def.mc {
                let key = |m: Learner| (d.clone(), costs, mc.to_bits(), m);
                let base = cells
                    .get(&key(Learner::Family(Method::CsId3Batch)))
                    .map(|v| mean(&v.iter().map(|x| x.0).collect::<Vec<_>>()));
                for &learner in &def.learners {
                    let Some(v) = cells.get(&key(learner)) else {
                        continue;
                    };
                    let norm: Vec<f64> = v.iter().map(|x| x.0).collect();
                    let m = mean(&norm);
                    let n = norm.len();
                    let sd = if n > 1 {
                        (norm.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt()
                    } else {
                        0.0
                    };
                    rows.push(Row {
                        dataset: d.clone(),
                        costs,
                        mc,
                        learner,
                        normalised: m,
                        ci95: 1.96 * sd / (n as f64).sqrt(),
                        test_cost: mean(&v.iter().map(|x| x.1).collect::<Vec<_>>()),
                        error_rate: mean(&v.iter().map(|x| x.2).collect::<Vec<_>>()),
                        total: mean(&v.iter().map(|x| x.3).collect::<Vec<_>>()),
                        ratio: base.filter(|b| *b > 0.0).map(|b| m / b),
                        runs: def.runs,
                        auroc: aurocs
                            .get(&key(learner))
                            .and_then(|a| a.iter().copied().collect::<Option<Vec<f64>>>())
                            .map(|a| mean(&a)),
                    });
                }
            }
        }
    }
    rows
}

fn find<'a>(rows: &'a [Row], d: &str, costs: PriceSet, mc: f64, m: Learner) -> Option<&'a Row> {
    rows.iter()
        .find(|r| r.dataset == d && r.costs == costs && r.mc == mc && r.learner == m)
}

/// `testcost.csv`: one line per data set, price set, mc and learner.
pub(crate) fn csv(def: &Definition, rows: &[Row]) -> String {
    let mut out = String::from(
        "dataset,costs,mc,learner,runs,folds,normalised_cost,ci95,test_cost,error_rate,ratio_to_cs_id3\n",
    );
    for r in rows {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{:.3},{:.3},{:.3},{:.4},{}",
            r.dataset,
            r.costs.name(),
            r.mc,
            r.learner.name(),
            r.runs,
            def.folds,
            r.normalised,
            r.ci95,
            r.test_cost,
            r.error_rate,
            r.ratio.map_or(String::new(), |x| format!("{x:.4}")),
        );
    }
    out
}

/// `auroc.csv`, beside `testcost.csv` (which keeps its columns, so that a table of
/// results measured before AUROC reads the same): one line per row that measured it,
/// its error rate and mean area under the ROC curve (`auroc` in `testcost.rs`: the
/// second class's for two classes, the one-vs-rest mean over classes for more); `None`
/// when no row measured it.
pub(crate) fn auroc_csv(def: &Definition, rows: &[Row]) -> Option<String> {
    let mut out = String::from("dataset,costs,mc,learner,runs,folds,error_rate,auroc\n");
    let mut any = false;
    for r in rows {
        let Some(auroc) = r.auroc else { continue };
        any = true;
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{:.4},{:.4}",
            r.dataset,
            r.costs.name(),
            r.mc,
            r.learner.name(),
            r.runs,
            def.folds,
            r.error_rate,
            auroc,
        );
    }
    any.then_some(out)
}

/// The mean over data sets of each learner's ratio to CS-ID3, ours and published, over
/// the data sets that have both, at `mc`: (learner, ours, published, data sets).
pub(crate) fn mean_ratios(
    def: &Definition,
    rows: &[Row],
    published_names: &BTreeMap<String, String>,
    mc: f64,
) -> Vec<(Learner, f64, f64, usize)> {
    let mut out = Vec::new();
    for &m in &def.learners {
        let Some(col) = m.method().and_then(published::column) else {
            continue;
        };
        let (mut ours, mut theirs, mut n) = (0.0, 0.0, 0);
        for d in &def.datasets {
            let Some(p) = published_names
                .get(d)
                .and_then(|name| published::row(name, mc))
            else {
                continue;
            };
            let Some(r) = find(rows, d, PriceSet::Random, mc, m).and_then(|r| r.ratio) else {
                continue;
            };
            ours += r;
            theirs += p[col] / p[3];
            n += 1;
        }
        if n > 0 {
            out.push((m, ours / n as f64, theirs / n as f64, n));
        }
    }
    out
}

/// Writes `testcost.csv`, `timing.csv`, `testcost.md` and `testcost.svg` into `dir`, and
/// `auroc.csv` when the results measured AUROC ([`auroc_csv`]).
pub(crate) fn write(
    table: &Table,
    published_names: &BTreeMap<String, String>,
    objects: &BTreeMap<String, usize>,
    dir: &Path,
    command: &str,
) -> Result<()> {
    let (def, rows) = (&table.def, &table.rows);
    crate::files::create_dir(dir)?;
    crate::files::write_atomic(&dir.join("testcost.csv"), csv(def, rows))?;
    let auroc = auroc_csv(def, rows);
    if let Some(text) = &auroc {
        crate::files::write_atomic(&dir.join("auroc.csv"), text.clone())?;
    }
    crate::files::write_atomic(
        &dir.join("timing.csv"),
        timing_csv(def, &table.results, objects),
    )?;
    figure(&dir.join("testcost.svg"), def, rows)?;
    crate::files::write_atomic(
        &dir.join("testcost.md"),
        markdown(table, published_names, command),
    )?;
    crate::note(&format!(
        "wrote {}/testcost.csv, timing.csv, {}testcost.md and testcost.svg",
        dir.display(),
        if auroc.is_some() { "auroc.csv, " } else { "" }
    ));
    Ok(())
}

/// Learning and classification time per data set and learner (measurements: they vary
/// from run to run, unlike every other output). A job classifies each of the data set's
/// `objects` once per mc (each object is held out once in a run).
fn timing_csv(
    def: &Definition,
    results: &[JobResult],
    objects: &BTreeMap<String, usize>,
) -> String {
    /// One data set and learner's sums over its jobs.
    #[derive(Clone, Copy, Default)]
    struct Sums {
        per_tree: f64,
        learn: f64,
        classify: f64,
        nodes: f64,
        jobs: usize,
        /// Times each object of the data set was classified (once per mc of a job).
        classified: usize,
    }
    let mut cells: BTreeMap<(String, Learner), Sums> = BTreeMap::new();
    for r in results {
        let e = cells.entry((r.dataset.clone(), r.learner)).or_default();
        let trees = if r.learner.depends_on_mc() {
            def.folds * r.by_mc.len()
        } else {
            def.folds
        };
        e.per_tree += r.learn_seconds / trees as f64;
        e.learn += r.learn_seconds;
        e.classify += r.classify_seconds;
        e.nodes += r.nodes;
        e.jobs += 1;
        e.classified += r.by_mc.len();
    }
    let mut out = String::from(
        "dataset,learner,ms_per_tree,nodes_per_tree,learn_seconds_per_job,us_per_classification\n",
    );
    for d in &def.datasets {
        for &m in &def.learners {
            if let Some(&Sums {
                per_tree,
                learn,
                classify,
                nodes,
                jobs: n,
                classified,
            }) = cells.get(&(d.clone(), m))
            {
                let classified = objects.get(d).copied().unwrap_or(0) * classified;
                let _ = writeln!(
                    out,
                    "{d},{},{:.4},{:.1},{:.3},{:.3}",
                    m.name(),
                    1e3 * per_tree / n as f64,
                    nodes / n as f64,
                    learn / n as f64,
                    1e6 * classify / classified.max(1) as f64
                );
            }
        }
    }
    out
}

fn markdown(table: &Table, published_names: &BTreeMap<String, String>, command: &str) -> String {
    let (def, rows) = (&table.def, table.rows.as_slice());
    let mut md = String::new();
    let _ = writeln!(md, "# The test-cost benchmark\n");
    let _ = writeln!(
        md,
        "Written by `{command}`. Average total cost (tests plus misclassification) as a \
         percentage of Turney's standard cost, lower is better; {} of {}-fold stratified \
         cross-validation per data set and price assignment; random prices: {} assignments \
         per data set, each test {} [{}, {}]. Learners: {}. Selection functions see {}; \
         an object always pays after its path (a test done once is free further down). \
         ICET prunes by {}.{}{}{} \
         `docs/testcost.md` reads the results.\n",
        if def.runs == 1 {
            "1 run".to_string()
        } else {
            format!("{} runs", def.runs)
        },
        def.folds,
        def.assignments,
        match def.price_draw {
            super::PriceDraw::Uniform => "uniform in",
            super::PriceDraw::Gain =>
                "uniform below a ceiling in proportion to its information gain, within",
        },
        def.price_range.0,
        def.price_range.1,
        def.learners
            .iter()
            .map(|m| m.name())
            .collect::<Vec<_>>()
            .join(", "),
        match def.selection_prices {
            SelectionPrices::Listed => "each test's listed price, whatever the path",
            SelectionPrices::Path => "a test's price after the node's path",
            SelectionPrices::ListedOnce => {
                "each test's listed price, nothing for a test the path already did"
            }
        },
        match def.icet_pruning {
            Pruning::Costs => "total cost (a test must pay for itself at the real prices)",
            Pruning::Errors => "errors, as C4.5",
        },
        voi_sentence(def),
        added_sentence(def, &table.added),
        library_sentence(&table.results),
    );
    for &mc in &def.mc {
        if !def.costs.contains(&PriceSet::Random) {
            break;
        }
        let published_here = mc == 500.0 || mc == 1000.0;
        let _ = writeln!(
            md,
            "## Random prices, mc = {mc}{}\n",
            if published_here {
                " (published figure in parentheses)"
            } else {
                ""
            }
        );
        // The learners measured at this mc (an added one may have other mc only).
        let here: Vec<Learner> = def
            .learners
            .iter()
            .copied()
            .filter(|&m| {
                rows.iter()
                    .any(|r| r.learner == m && r.mc == mc && r.costs == PriceSet::Random)
            })
            .collect();
        let _ = write!(md, "| data set |");
        for m in &here {
            let _ = write!(md, " {} |", m.name());
        }
        let _ = writeln!(md);
        let _ = writeln!(md, "|---|{}", "---|".repeat(here.len()));
        for d in &def.datasets {
            let p = published_names.get(d).and_then(|n| published::row(n, mc));
            let _ = write!(md, "| {d} |");
            for &m in &here {
                let ours = find(rows, d, PriceSet::Random, mc, m).map_or("".to_string(), |r| {
                    format!("{:.1} ± {:.1}{}", r.normalised, r.ci95, runs_mark(r, def))
                });
                let theirs = match (p, m.method().and_then(published::column)) {
                    (Some(p), Some(c)) => format!(" ({:.1})", p[c]),
                    _ => String::new(),
                };
                let _ = write!(md, " {ours}{theirs} |");
            }
            let _ = writeln!(md);
        }
        let _ = writeln!(md);
        let ratios = mean_ratios(def, rows, published_names, mc);
        if !ratios.is_empty() {
            let _ = writeln!(
                md,
                "Mean ratio to batch CS-ID3 over the {} data sets with a published row:\n",
                ratios[0].3
            );
            let _ = writeln!(md, "| learner | ours | published | difference |");
            let _ = writeln!(md, "|---|---|---|---|");
            for (m, ours, theirs, _) in &ratios {
                let _ = writeln!(
                    md,
                    "| {} | {ours:.3} | {theirs:.3} | {:+.3} |",
                    m.name(),
                    ours - theirs
                );
            }
            let _ = writeln!(md);
        }
    }
    if def.costs.contains(&PriceSet::Turney) {
        let _ = writeln!(
            md,
            "## Turney's prices, with group discounts\n\nTotal and test cost per object in the \
             cost files' currency (Canadian dollars), error rate, and % of standard cost.\n"
        );
        let _ = writeln!(
            md,
            "| data set | mc | learner | total | tests | error rate | % standard |"
        );
        let _ = writeln!(md, "|---|---|---|---|---|---|---|");
        for r in rows.iter().filter(|r| r.costs == PriceSet::Turney) {
            let _ = writeln!(
                md,
                "| {} | {} | {} | {:.2} | {:.2} | {:.3} | {:.1} ± {:.1}{} |",
                r.dataset,
                r.mc,
                r.learner.name(),
                r.total,
                r.test_cost,
                r.error_rate,
                r.normalised,
                r.ci95,
                runs_mark(r, def)
            );
        }
        let _ = writeln!(md);
    }
    let _ = writeln!(
        md,
        "![Mean normalised cost against the misclassification cost](testcost.svg)\n\n\
         Times are in `timing.csv` (measured, so they vary between runs)."
    );
    md
}

/// What the report's header says of the learners run through another library (CEGB):
/// the library's version and settings as its results recorded them, one sentence per
/// learner and distinct line (nothing when no result has one).
fn library_sentence(results: &[JobResult]) -> String {
    let mut lines: Vec<(Learner, &str)> = results
        .iter()
        .filter_map(|r| r.library.as_deref().map(|l| (r.learner, l)))
        .collect();
    lines.sort();
    lines.dedup();
    let mut out = String::new();
    for (learner, line) in lines {
        let _ = write!(out, " {}: {line}.", learner.name());
    }
    out
}

/// What a cell of a row measured over other runs than the table's says of them
/// (` [1 run]`), so that no cell passes for the table's protocol; nothing for the table's
/// own runs.
fn runs_mark(row: &Row, def: &Definition) -> String {
    match row.runs {
        r if r == def.runs => String::new(),
        1 => " [1 run]".into(),
        r => format!(" [{r} runs]"),
    }
}

/// What the report's header says of the learners another benchmark added: their runs
/// (the first ones, on the same folds and prices) and their mc, or that they are the
/// table's own.
/// How far ahead VOI looked, where it is among the learners.
fn voi_sentence(def: &Definition) -> String {
    if !def.learners.contains(&Learner::Family(Method::Voi)) {
        return String::new();
    }
    match (def.voi.lookahead, def.voi_params().lookahead) {
        (None, None) => format!(
            " VOI values a test three tests ahead on data of at most {} features, two \
             beyond.",
            cslearn::testcost::VoiParams::NARROW
        ),
        (None, _) => " VOI values a test two tests ahead (its default before it followed \
                      the data's width)."
            .to_string(),
        (Some(1), _) => " VOI values a test one test ahead.".to_string(),
        (Some(d), _) => format!(" VOI values a test {d} tests ahead."),
    }
}

fn added_sentence(def: &Definition, added: &[Added]) -> String {
    let mut out = String::new();
    for Added { learners, runs, mc } in added {
        let names: Vec<&str> = learners.iter().map(|m| m.name()).collect();
        if *runs == def.runs && *mc == def.mc {
            let _ = write!(
                out,
                " {}: from another benchmark of the same protocol (the same folds, prices, \
                 runs and mc).",
                names.join(", "),
            );
            continue;
        }
        let mc: Vec<String> = mc.iter().map(|m| m.to_string()).collect();
        let mc = match mc.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
            _ => mc.join(""),
        };
        let runs = if *runs == 1 {
            "run".to_string()
        } else {
            format!("{runs} runs")
        };
        let _ = write!(
            out,
            " {}: the first {runs} only (the same folds and prices), at mc {mc} only, \
             each ratio to CS-ID3 on those runs; their cells say so, and their ± is over \
             those runs' (run, price draw) pairs.",
            names.join(", "),
        );
    }
    out
}

/// Mean normalised cost over the data sets (random prices) against mc, one line per
/// learner, colour-blind-safe colours and one marker shape each.
fn figure(path: &Path, def: &Definition, rows: &[Row]) -> Result<()> {
    crate::figures::register_font();
    let plot_err = |e: &dyn std::fmt::Display| anyhow!("drawing {}: {e}", path.display());
    let series: Vec<(Learner, Vec<(f64, f64)>)> = def
        .learners
        .iter()
        .map(|&m| {
            let pts = def
                .mc
                .iter()
                .filter_map(|&mc| {
                    let v: Vec<f64> = rows
                        .iter()
                        .filter(|r| r.learner == m && r.mc == mc && r.costs == PriceSet::Random)
                        .map(|r| r.normalised)
                        .collect();
                    (!v.is_empty()).then(|| (mc, v.iter().sum::<f64>() / v.len() as f64))
                })
                .collect();
            (m, pts)
        })
        .collect();
    let top = series
        .iter()
        .flat_map(|(_, p)| p.iter().map(|x| x.1))
        .fold(10.0, f64::max);
    let lo = def
        .mc
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min)
        .max(1.0);
    let hi = def.mc.iter().copied().fold(0.0, f64::max).max(lo * 2.0);
    let mut svg = String::new();
    {
        let base = SVGBackend::with_string(&mut svg, (900, 560)).into_drawing_area();
        base.fill(&WHITE).map_err(|e| plot_err(&e))?;
        let mut chart = ChartBuilder::on(&base)
            .caption(
                format!(
                    "Test-cost learners: mean cost over {} data sets, random prices",
                    def.datasets.len()
                ),
                ("sans-serif", 20),
            )
            .margin(16)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (lo / 1.3..hi * 1.3)
                    .log_scale()
                    .with_key_points(def.mc.clone()),
                0.0..top * 1.1,
            )
            .map_err(|e| plot_err(&e))?;
        chart
            .configure_mesh()
            .x_desc("misclassification cost (log scale)")
            .y_desc("total cost, % of standard cost")
            .axis_desc_style(("sans-serif", 16))
            .label_style(("sans-serif", 14))
            .light_line_style(WHITE)
            .bold_line_style(RGBColor(230, 230, 230))
            .x_label_formatter(&|x| format!("{x:.0}"))
            .draw()
            .map_err(|e| plot_err(&e))?;
        for (k, (m, pts)) in series.iter().enumerate() {
            // Past the palette's seven, lines are dashed and colours shift, so that no two
            // series share colour, marker and line.
            let dashed = k >= PALETTE.len();
            let color = PALETTE[(k + if dashed { 3 } else { 0 }) % PALETTE.len()];
            let style = color.stroke_width(2);
            let (dash, gap) = (6, 4);
            if dashed {
                chart.draw_series(DashedLineSeries::new(pts.clone(), dash, gap, style))
            } else {
                chart.draw_series(LineSeries::new(pts.clone(), style))
            }
            .map_err(|e| plot_err(&e))?
            .label(m.name())
            .legend(move |(x, y)| {
                let ends = vec![(-12, 0), (12, 0)];
                let line: DynElement<'static, SVGBackend<'_>, (i32, i32)> = if dashed {
                    plotters::element::DashedPathElement::new(ends, dash, gap, style).into_dyn()
                } else {
                    PathElement::new(ends, style).into_dyn()
                };
                EmptyElement::at((x + 12, y)) + line + marker::<SVGBackend<'_>>(k, (0, 0), color)
            });
            chart
                .draw_series(
                    pts.iter()
                        .map(|&p| EmptyElement::at(p) + marker::<SVGBackend<'_>>(k, (0, 0), color)),
                )
                .map_err(|e| plot_err(&e))?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(WHITE.mix(0.9))
            .border_style(RGBColor(150, 150, 150))
            .label_font(("sans-serif", 14))
            .draw()
            .map_err(|e| plot_err(&e))?;
        base.present().map_err(|e| plot_err(&e))?;
    }
    crate::files::write_atomic(path, svg)
}
