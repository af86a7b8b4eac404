//! The reproduction's rows for `predict_sensing`: Table 1 again at the levels `learned`
//! and `motion` (one row block per level), with navigation after learning, and the
//! learning curves of every level. Written beside `table1.md` as `prediction.md` and
//! `learning_curves_prediction.svg`, so that the paper's table (and `--check`) stay as
//! they are.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use csql::{PredictSensing, RunReport, StrategyKind};
use rayon::prelude::*;

use super::Results;
use crate::figures;
use crate::stats::{Summary, rows, summary};

/// The levels beyond the paper, in order.
const LEVELS: [PredictSensing; 2] = [PredictSensing::Learned, PredictSensing::Motion];

/// Run every strategy of `res` at both levels (same seeds) and write the rows and the
/// curves to `out`, and for the default reproduction also to `docs/` (committed copies;
/// `--check` compares only `table1.md`).
pub fn write(res: &Results, out: &Path, to_docs: bool) -> Result<Vec<PathBuf>> {
    let args = &res.args;
    let jobs: Vec<(PredictSensing, StrategyKind, u64)> = LEVELS
        .iter()
        .flat_map(|&l| {
            args.strategies
                .iter()
                .flat_map(move |&k| (0..args.runs).map(move |i| (l, k, i)))
        })
        .collect();
    let reports: Vec<RunReport> = crate::files::pool(args.threads)?.install(|| {
        jobs.par_iter()
            .map(|&(level, strategy, i)| {
                let mut s = csql::RunSettings::tan1991(&args.map, strategy, args.seed + i);
                if let Some(q) = s.cs_ql_mut() {
                    q.predict_sensing = level;
                }
                csql::run_on(&res.setup, &s)
            })
            .collect::<Result<Vec<_>, _>>()
    })?;
    let block = |level: PredictSensing, k: StrategyKind| -> Vec<&RunReport> {
        jobs.iter()
            .zip(&reports)
            .filter(|((l, s, _), _)| *l == level && *s == k)
            .map(|(_, r)| r)
            .collect()
    };
    let mean_cost = |runs: &[&RunReport]| {
        let v: Vec<f64> = runs
            .iter()
            .filter_map(|r| r.table1.cost_to_converge)
            .collect();
        Summary::of(&v).map(|s| s.mean)
    };
    let best_off = res
        .runs
        .iter()
        .filter_map(|(_, runs, _)| mean_cost(&runs.iter().collect::<Vec<_>>()))
        .fold(f64::INFINITY, f64::min);
    let mut md = String::new();
    let _ = writeln!(md, "# Sensing less: Table 1 with prediction\n");
    let _ = writeln!(
        md,
        "`cargo xtask reproduce` on `{}`, seeds {} to {}, the paper's parameters and the \
         default `[prediction]` settings. The level `off` is `table1.md`; the best of its \
         strategies costs {best_off:.0} to convergence. Mean ± standard deviation [min–max].\n",
        res.setup.map.name(),
        args.seed,
        args.seed + args.runs - 1
    );
    let mut curves = Vec::new();
    for (k, runs, _) in &res.runs {
        curves.push(figures::Curve::of(format!("{k}, off"), runs));
    }
    for level in LEVELS {
        let _ = writeln!(md, "## predict_sensing = \"{level}\"\n");
        let _ = write!(md, "| row |");
        for k in &args.strategies {
            let _ = write!(md, " {k} |");
        }
        let _ = write!(md, "\n|---|");
        for _ in &args.strategies {
            let _ = write!(md, "---|");
        }
        let _ = writeln!(md);
        let blocks: Vec<Vec<&RunReport>> =
            args.strategies.iter().map(|&k| block(level, k)).collect();
        let mut line = |name: &str, cell: &dyn Fn(&[&RunReport]) -> String| {
            let _ = write!(md, "| {name} |");
            for b in &blocks {
                let _ = write!(md, " {} |", cell(b));
            }
            let _ = writeln!(md);
        };
        line("converged", &|b| {
            format!("{}/{}", b.iter().filter(|r| r.converged).count(), b.len())
        });
        for (name, decimals, row) in rows() {
            line(&name, &|b| {
                summary(b, row).map_or("–".into(), |s| s.show(decimals))
            });
        }
        line("3 / best of the paper's four at level off", &|b| {
            mean_cost(b).map_or("–".into(), |c| format!("{:.3}", c / best_off))
        });
        line("navigation sensing cost per move", &|b| {
            let v: Vec<f64> = b
                .iter()
                .filter_map(|r| r.navigation_cost_per_move)
                .collect();
            Summary::of(&v).map_or("–".into(), |s| s.show(2))
        });
        line("navigation success (optimal paths)", &|b| {
            let v: Vec<f64> = b.iter().filter_map(|r| r.navigation_success).collect();
            Summary::of(&v).map_or("–".into(), |s| s.show(3))
        });
        line("wrong predictions (most in a row)", &|b| {
            let stats: Vec<_> = b.iter().filter_map(|r| r.prediction).collect();
            let wrong: u64 = stats.iter().map(|p| p.wrong).sum();
            let run = stats.iter().map(|p| p.longest_wrong_run).max().unwrap_or(0);
            format!("{:.0} ({run})", wrong as f64 / b.len().max(1) as f64)
        });
        let _ = writeln!(md);
        for (&k, b) in args.strategies.iter().zip(&blocks) {
            curves.push(figures::Curve::of(format!("{k}, {level}"), b));
        }
    }
    let md_path = out.join("prediction.md");
    crate::files::write_atomic(&md_path, &md)?;
    let svg = out.join("learning_curves_prediction.svg");
    figures::learning_curves(
        &svg,
        &format!(
            "CS-QL on {}: cumulative sensing cost by strategy and predict_sensing level",
            crate::files::safe_name(res.setup.map.name())
        ),
        &curves,
    )?;
    let mut written = vec![md_path, svg.clone()];
    if to_docs {
        let md_doc = PathBuf::from("docs/prediction.md");
        crate::files::write_atomic(&md_doc, &md)?;
        let svg_doc = PathBuf::from("docs/figures/learning_curves_prediction.svg");
        let bytes =
            std::fs::read(&svg).with_context(|| format!("cannot read {}", svg.display()))?;
        crate::files::write_atomic(&svg_doc, bytes)?;
        written.extend([md_doc, svg_doc]);
    }
    Ok(written)
}
