//! The benchmark's report, from the job results: `costly.csv` and
//! `costly_after_outcome.csv` (one row per world, dynamics, price and learner), the
//! Markdown tables and one figure per world of the costed return against episodes.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Result, anyhow};
use mdp::SensingRule;
use plotters::prelude::*;

use super::{BLOCK, Dynamics, JobResult, Learner, PRICES, RULES, Summary, WORLDS, optimum};

/// One row of the tables: a world, dynamics, price, rule and learner over its runs.
struct Row<'a> {
    world: &'a str,
    dynamics: Dynamics,
    price: f64,
    rule: SensingRule,
    learner: Learner,
    runs: Vec<&'a JobResult>,
}

impl Row<'_> {
    /// The mean over runs of a run's figure.
    fn mean(&self, f: impl Fn(&Summary) -> f64) -> f64 {
        self.runs.iter().map(|r| f(&r.summary)).sum::<f64>() / self.runs.len() as f64
    }

    /// The half-width of the 95% interval of the mean over runs of a run's figure
    /// ([`crate::stats::ci95`]); `None` for a single run.
    fn ci95(&self, f: impl Fn(&Summary) -> f64) -> Option<f64> {
        let values: Vec<f64> = self.runs.iter().map(|r| f(&r.summary)).collect();
        crate::stats::ci95(&values)
    }

    /// The mean learning curve over runs.
    fn curve(&self) -> Vec<f64> {
        let n = self.runs.iter().map(|r| r.curve.len()).min().unwrap_or(0);
        (0..n)
            .map(|i| self.runs.iter().map(|r| r.curve[i]).sum::<f64>() / self.runs.len() as f64)
            .collect()
    }
}

fn rows(results: &[JobResult]) -> Vec<Row<'_>> {
    let mut groups: BTreeMap<(usize, Dynamics, usize, usize, Learner), Vec<&JobResult>> =
        BTreeMap::new();
    for r in results {
        let w = WORLDS
            .iter()
            .position(|w| w.0 == r.world)
            .unwrap_or(usize::MAX);
        let p = PRICES
            .iter()
            .position(|&p| p == r.price)
            .unwrap_or(usize::MAX);
        let k = RULES
            .iter()
            .position(|&k| k == r.rule)
            .unwrap_or(usize::MAX);
        groups
            .entry((w, r.dynamics, p, k, r.learner))
            .or_default()
            .push(r);
    }
    groups
        .into_values()
        .map(|runs| Row {
            world: &runs[0].world,
            dynamics: runs[0].dynamics,
            price: runs[0].price,
            rule: runs[0].rule,
            learner: runs[0].learner,
            runs,
        })
        .collect()
}

fn rule_name(rule: SensingRule) -> &'static str {
    match rule {
        SensingRule::WithMove => "sensing decided with the move (the published rule)",
        SensingRule::AfterOutcome => "sensing after the outcome",
    }
}

/// The CSV files of the two rules.
const CSV_NAMES: [(SensingRule, &str); 2] = [
    (SensingRule::WithMove, "costly.csv"),
    (SensingRule::AfterOutcome, "costly_after_outcome.csv"),
];

/// `costly.csv` and `costly_after_outcome.csv` (those of the rules run), the Markdown
/// tables and the figures (of the worlds run) into `dir`.
///
/// `joined` holds the commands of the longer runs joined in (`--with`), which the
/// page names.
pub(crate) fn write(
    results: &[JobResult],
    joined: &[String],
    dir: &Path,
    md_name: &str,
) -> Result<()> {
    let rows = rows(results);
    let optima = optimum::read(Path::new(optimum::PATH))?;
    let mut md = String::from(
        "# The active-measurement benchmark: measured\n\nWritten by `cargo xtask costly --bless` (specification 6.10 and 6.11): the costed return per episode (reward less the prices of what was sensed, in reward units), mean over runs of each run's mean over all its episodes and over its last 10%. Beside each mean, `±` the half-width of its 95% interval over the runs (Student's t with runs - 1 degrees of freedom over the runs' means; the CSV columns `ci95_all` and `ci95_last10`, empty for a single run).\n\nAMRL-Q is played two ways: `amrl-q` explores in every run, greedy in the last 10% of each run's episodes, as the method is described; `amrl-q-greedy-after-first` follows the published harness, which reuses one agent whose greedy switch stays on: its first run as `amrl-q`, every later run greedy from its first episode (`[amrl_q] greedy_share = 1`).\n\nThe last column, `optimum`, brackets the best expected costed return of any policy on the lake with its model known, the row and the column measured apart (`mdp::optimum_bounds`, kept in `docs/costly_optimum.csv` by `cargo xtask costly --optimum`; specification 6.10): one figure where its bounds meet to four places, `(open)` where the search's trials ran out before they came within 0.001. It is what a learner's last 10% could reach at most, had it known the lake from the start.\n",
    );
    if !joined.is_empty() {
        let commands: Vec<String> = joined.iter().map(|c| format!("`{c}`")).collect();
        let _ = write!(
            md,
            "\nRows joined with `--with` from other runs of the same seeds, in order: {}. A later run's rows take the place of the table's in the cells it covers (longer runs of a row, whose first runs are the row's own to the bit) or are added (a learner the table lacks). The `runs` column says how many runs each row averages.\n",
            commands.join(", then ")
        );
    }
    for (rule, csv_name) in CSV_NAMES {
        if !rows.iter().any(|r| r.rule == rule) {
            continue;
        }
        let mut csv = String::from(
            "world,dynamics,price,learner,runs,episodes,mean_all,mean_last10,sensing_per_episode,steps_per_episode,success,ci95_all,ci95_last10\n",
        );
        let _ = write!(
            md,
            "\n## {} (`{csv_name}`)\n\n| world | dynamics | price per coordinate | learner | runs | episodes | mean all | ± | mean last 10% | ± | measurements / episode | moves / episode | success | optimum |\n|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
            rule_name(rule)
        );
        for r in rows.iter().filter(|r| r.rule == rule) {
            let episodes = r.runs[0].summary.episodes;
            let means = [
                r.mean(|s| s.mean_all),
                r.mean(|s| s.mean_last10),
                r.mean(|s| s.sensing_per_episode),
                r.mean(|s| s.steps_per_episode),
                r.mean(|s| s.success),
            ];
            let ci = [r.ci95(|s| s.mean_all), r.ci95(|s| s.mean_last10)];
            let key = [
                r.world.to_string(),
                r.dynamics.name().to_string(),
                r.price.to_string(),
                r.learner.name().to_string(),
                r.runs.len().to_string(),
                episodes.to_string(),
            ];
            // The CSV at full precision; the table rounded as each column reads best.
            let exact = means.iter().map(f64::to_string);
            let exact_ci = ci
                .iter()
                .map(|c| c.map_or(String::new(), |c| c.to_string()));
            let _ = writeln!(
                csv,
                "{}",
                key.iter()
                    .cloned()
                    .chain(exact)
                    .chain(exact_ci)
                    .collect::<Vec<_>>()
                    .join(",")
            );
            let shown_ci = ci.map(|c| c.map_or("–".to_string(), |c| format!("{c:.3}")));
            let [all, last, sensing, moves, success] = means;
            let best = optima
                .get(&optimum::key(r.world, r.dynamics, r.price, r.rule))
                .map_or("–".to_string(), optimum::Bounds::text);
            let shown = [
                format!("{all:.3}"),
                shown_ci[0].clone(),
                format!("{last:.3}"),
                shown_ci[1].clone(),
                format!("{sensing:.2}"),
                format!("{moves:.2}"),
                format!("{success:.3}"),
                best,
            ];
            let _ = writeln!(
                md,
                "| {} |",
                key.into_iter().chain(shown).collect::<Vec<_>>().join(" | ")
            );
        }
        crate::files::write_atomic(&dir.join(csv_name), csv)?;
    }
    let figures = dir.join("figures");
    crate::files::create_dir(&figures)?;
    md.push_str("\n## Learning curves\n\n");
    for &(world, _, _) in &WORLDS {
        if !rows.iter().any(|r| r.world == world) {
            continue;
        }
        let name = format!("costly_{world}.svg");
        draw(&figures.join(&name), world, &rows)?;
        let _ = writeln!(md, "![the costed return on {world}](figures/{name})\n");
    }
    crate::files::write_atomic(&dir.join(md_name), md)
}

/// Whether a learner has a line in the figures: every one but AMRL-Q under the published
/// harness's protocol, whose later runs are greedy from their first episode (its figures
/// are in the tables).
fn drawn(learner: Learner) -> bool {
    learner != Learner::AmrlQGreedyAfterFirst
}

impl Learner {
    /// The learner's colour in the figures.
    fn colour(self) -> RGBColor {
        match self {
            Learner::AmrlQ => RGBColor(0, 0, 0),
            Learner::AmrlQGreedyAfterFirst => RGBColor(214, 39, 40),
            Learner::AlwaysMeasuring => RGBColor(150, 150, 150),
            Learner::CsQl => RGBColor(31, 119, 180),
            Learner::FullSensing => RGBColor(230, 120, 20),
            Learner::Belief => RGBColor(44, 160, 44),
            Learner::CsQlWeighed => RGBColor(148, 103, 189),
            Learner::BeliefBlind => RGBColor(140, 86, 75),
            Learner::BeliefApart => RGBColor(23, 190, 207),
        }
    }
}

/// One figure: a panel per dynamics, the costed return (mean over runs of each block of
/// episodes) against episodes, one line per learner and price, the published rule.
fn draw(path: &Path, world: &str, rows: &[Row<'_>]) -> Result<()> {
    crate::figures::register_font();
    let plot_err = |e: &dyn std::fmt::Display| anyhow!("drawing {}: {e}", path.display());
    let mut svg = String::new();
    let (pw, ph) = (520_u32, 380_u32);
    // The legend below the panels: a column per learner, a row per price.
    let learners: Vec<Learner> = Learner::NAMED
        .into_iter()
        .filter(|&l| drawn(l) && rows.iter().any(|r| r.world == world && r.learner == l))
        .collect();
    let legend_h = 30 + 22 * PRICES.len() as u32;
    let base = SVGBackend::with_string(&mut svg, (pw * 3, ph + 50 + legend_h)).into_drawing_area();
    base.fill(&WHITE).map_err(|e| plot_err(&e))?;
    let root = base
        .titled(
            &format!(
                "{world}: costed return per episode (mean over runs, blocks of {BLOCK} episodes; in brackets, the price per coordinate)"
            ),
            ("sans-serif", 20),
        )
        .map_err(|e| plot_err(&e))?;
    let (top, legend) = root.split_vertically(ph + 20);
    // A panel per dynamics run (a part of the table may have fewer), side by side.
    let shown: Vec<Dynamics> = Dynamics::ALL
        .into_iter()
        .filter(|&d| rows.iter().any(|r| r.world == world && r.dynamics == d))
        .collect();
    let panels = top.split_evenly((1, shown.len().max(1)));
    for (panel, &dynamics) in panels.iter().zip(&shown) {
        let lines: Vec<&Row<'_>> = rows
            .iter()
            .filter(|r| {
                r.world == world
                    && r.dynamics == dynamics
                    && r.rule == SensingRule::WithMove
                    && drawn(r.learner)
            })
            .collect();
        let episodes = lines.first().map_or(1, |r| r.runs[0].summary.episodes) as f64;
        let low = lines
            .iter()
            .flat_map(|r| r.curve())
            .fold(0.0_f64, f64::min)
            .min(-0.1)
            - 0.05;
        let mut chart = ChartBuilder::on(panel)
            .caption(dynamics.name(), ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(56)
            .build_cartesian_2d(0.0..episodes, low..1.05)
            .map_err(|e| plot_err(&e))?;
        chart
            .configure_mesh()
            .x_desc("episode")
            .y_desc("costed return")
            .axis_desc_style(("sans-serif", 15))
            .label_style(("sans-serif", 13))
            .light_line_style(WHITE)
            .bold_line_style(RGBColor(230, 230, 230))
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| format!("{:.1}", if y.abs() < 0.05 { 0.0 } else { *y }))
            .draw()
            .map_err(|e| plot_err(&e))?;
        // AMRL-Q plays its last 10% of episodes greedily.
        let greedy = episodes * 0.9;
        chart
            .draw_series(DashedLineSeries::new(
                vec![(greedy, low), (greedy, 1.05)],
                4,
                4,
                GREEDY.stroke_width(1),
            ))
            .map_err(|e| plot_err(&e))?;
        // Colour by learner, stroke by price: solid at the lower price, dashed at the
        // higher.
        for line in &lines {
            let style = line.learner.colour().stroke_width(2);
            let points: Vec<(f64, f64)> = line
                .curve()
                .iter()
                .enumerate()
                .map(|(b, &y)| (((b as f64) + 0.5) * BLOCK as f64, y))
                .collect();
            let dashed = line.price != PRICES[0];
            if dashed {
                chart.draw_series(DashedLineSeries::new(points, 6, 4, style))
            } else {
                chart.draw_series(LineSeries::new(points, style))
            }
            .map_err(|e| plot_err(&e))?;
        }
    }
    // The prices run (a part of the table may have fewer), each in its row of the legend.
    let prices: Vec<f64> = PRICES
        .into_iter()
        .filter(|&p| rows.iter().any(|r| r.world == world && r.price == p))
        .collect();
    draw_legend(&legend, &learners, &prices, pw * 3).map_err(|e| plot_err(&e))?;
    root.present().map_err(|e| plot_err(&e))?;
    drop(panels);
    drop(top);
    drop(legend);
    drop(root);
    drop(base);
    crate::files::write_atomic(path, svg)
}

/// The dashed line where AMRL-Q's greedy last tenth begins.
const GREEDY: RGBColor = RGBColor(120, 120, 120);

/// The figure's legend in `area` (`width` wide): a column per learner, a line per price
/// (solid at the lower, dashed at the higher), and the greedy tenth's marker.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    learners: &[Learner],
    prices: &[f64],
    width: u32,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let font = ("sans-serif", 14).into_font().color(&BLACK);
    let columns = learners.len() as i32 + 1;
    let column = width as i32 / columns;
    let sample = |x: i32, y: i32, colour: RGBColor, dashed: bool, width: u32| {
        let style = colour.stroke_width(width);
        if dashed {
            (0..4)
                .map(|k| PathElement::new(vec![(x + 9 * k, y), (x + 9 * k + 5, y)], style))
                .collect::<Vec<_>>()
        } else {
            vec![PathElement::new(vec![(x, y), (x + 32, y)], style)]
        }
    };
    for (c, learner) in learners.iter().enumerate() {
        let x = 40 + column * c as i32;
        for (r, price) in PRICES.iter().enumerate() {
            if !prices.contains(price) {
                continue;
            }
            let y = 14 + 22 * r as i32;
            for p in sample(x, y, learner.colour(), r > 0, 2) {
                area.draw(&p)?;
            }
            area.draw(&Text::new(
                format!("{} ({price})", learner.name()),
                (x + 42, y - 7),
                font.clone(),
            ))?;
        }
    }
    let x = 40 + column * learners.len() as i32;
    for p in sample(x, 14, GREEDY, true, 1) {
        area.draw(&p)?;
    }
    // Two short lines: the last column is the narrowest place of the legend.
    area.draw(&Text::new("AMRL-Q's greedy", (x + 42, 7), font.clone()))?;
    area.draw(&Text::new("last 10%", (x + 42, 29), font))?;
    Ok(())
}
