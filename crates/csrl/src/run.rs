//! `csrl run`: one CS-QL run.

use std::io::Write;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::{Context, Result};
use clap::Args;
use csql::{Flow, Observer, RunReport, RunSettings, Setup, StrategyKind, TracePoint};

use crate::Status;

/// Arguments of `csrl run`.
#[derive(Args)]
pub struct RunArgs {
    /// A map: a built-in name, a map file, `random:WxH:DENSITY:SEED`, or `MAP@ROW:COL`
    /// for MAP with its goal moved (default: the config's map, else tan8x8).
    #[arg(long)]
    map: Option<String>,
    /// resetting, lazy, random or eager (default: the config's, else resetting).
    #[arg(long)]
    strategy: Option<StrategyKind>,
    /// The seed of the run (default: the config's, else 1).
    #[arg(long)]
    seed: Option<u64>,
    /// A TOML file of settings that override the paper's (beta, gamma, temperature,
    /// max_moves, random_moves, tolerance, decrease_threshold, max_trials, map,
    /// strategy, seed, predict_sensing and the table `[prediction]`); flags given here
    /// override the file.
    #[arg(long)]
    config: Option<PathBuf>,
    /// off, learned or motion: predict the next description instead of sensing it
    /// (default: the config's `predict_sensing`, else off; the `[prediction]` table of
    /// the config tunes it).
    #[arg(long)]
    predict_sensing: Option<csql::PredictSensing>,
    /// Stop an unconverged run after this many trials.
    #[arg(long)]
    max_trials: Option<u32>,
    /// Exit with code 3 if the run does not converge (by default a run that reaches its
    /// trial cap is a result like any other and exits 0).
    #[arg(long)]
    require_convergence: bool,
    /// Keep the per-trial learning curve and print it as the JSON's `trace` (one point
    /// per trial, so memory grows with the run; without this flag `trace` is empty).
    #[arg(long)]
    trace: bool,
    /// Print one JSON object instead of tables.
    #[arg(long)]
    json: bool,
    /// Also draw the map with the learned policy and descriptions to this SVG file.
    #[arg(long)]
    svg: Option<PathBuf>,
}

impl RunArgs {
    fn settings(&self) -> Result<RunSettings> {
        let mut s = RunSettings::tan1991("tan8x8", StrategyKind::Resetting, 1);
        if let Some(path) = &self.config {
            s.apply_file(path)?;
        }
        if let Some(m) = &self.map {
            s.map.clone_from(m);
        }
        if let Some(k) = self.strategy {
            s.strategy = k;
        }
        if let Some(seed) = self.seed {
            s.seed = seed;
        }
        if let Some(n) = self.max_trials {
            s.max_trials = n;
        }
        if let Some(level) = self.predict_sensing {
            s.predict_sensing = level;
        }
        s.validate()?;
        Ok(s)
    }
}

/// Shows progress on a terminal (nothing otherwise), keeps the trace only when asked,
/// and stops the run when Ctrl-C was pressed.
struct Watch {
    bar: indicatif::ProgressBar,
    keep_trace: bool,
    stop: Arc<AtomicBool>,
    stopped: bool,
}

impl Observer for Watch {
    fn keep_trace(&self) -> bool {
        self.keep_trace
    }

    fn trial(&mut self, point: &TracePoint) -> Flow {
        self.bar.set_position(u64::from(point.trial));
        if point.trial.is_multiple_of(16) {
            self.bar.set_message(format!(
                "{} descriptions, sensing cost {:.0}",
                point.descriptions, point.cumulative_cost
            ));
        }
        if self.stop.load(Ordering::Relaxed) {
            self.stopped = true;
            Flow::Stop
        } else {
            Flow::Continue
        }
    }
}

/// A flag that Ctrl-C sets. If a handler cannot be installed (one already is, in tests
/// for instance), Ctrl-C keeps its default effect.
fn ctrl_c_flag() -> Arc<AtomicBool> {
    let flag = Arc::new(AtomicBool::new(false));
    let set = Arc::clone(&flag);
    let _ = ctrlc::set_handler(move || set.store(true, Ordering::Relaxed));
    flag
}

fn progress_bar(len: u32) -> indicatif::ProgressBar {
    // Drawn on standard error only when it is a terminal; hidden otherwise.
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(u64::from(len)),
        indicatif::ProgressDrawTarget::stderr(),
    );
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "trial {pos}/{len} {wide_bar} {elapsed_precise} {msg} (Ctrl-C stops with a summary)",
    ) {
        bar.set_style(style);
    }
    bar
}

/// Run `csrl run`.
pub fn run(args: &RunArgs, out: &mut dyn Write) -> Result<()> {
    let settings = args.settings()?;
    let setup = Setup::new(&settings)?;
    let mut watch = Watch {
        bar: progress_bar(settings.max_trials),
        keep_trace: args.trace,
        stop: ctrl_c_flag(),
        stopped: false,
    };
    let report = csql::run_observed(&setup, &settings, &mut watch);
    watch.bar.finish_and_clear();
    if let Some(path) = &args.svg {
        std::fs::write(path, csql::policy_svg(&setup, &report))
            .with_context(|| format!("cannot write {}", path.display()))?;
        crate::note(format_args!(
            "wrote the policy picture to {}",
            path.display()
        ));
    }
    if args.json {
        writeln!(out, "{}", serde_json::to_string(&report)?)?;
    } else {
        print_report(&report, out)?;
    }
    if watch.stopped {
        return Err(Status::interrupted(report.trials).into());
    }
    if args.require_convergence && !report.converged {
        return Err(Status::not_converged(report.trials).into());
    }
    Ok(())
}

fn fmt_opt<T: std::fmt::Display>(x: Option<T>) -> String {
    x.map_or_else(|| "not reached".to_string(), |v| v.to_string())
}

fn print_report(r: &RunReport, out: &mut dyn Write) -> std::io::Result<()> {
    writeln!(
        out,
        "CS-QL on {} with the {} strategy, seed {}: {} after {} trials ({} moves, sensing cost {:.0})",
        r.map,
        r.strategy,
        r.seed,
        if r.converged {
            "converged"
        } else {
            "did NOT converge"
        },
        r.trials,
        r.moves,
        r.total_cost
    )?;
    let t = &r.table1;
    let rows = [
        (
            "1 sensing cost to a sufficient representation",
            fmt_opt(t.cost_to_sufficient),
        ),
        (
            "2 trials to a sufficient representation",
            fmt_opt(t.trials_to_sufficient),
        ),
        ("3 sensing cost to convergence", fmt_opt(t.cost_to_converge)),
        ("4 trials to convergence", fmt_opt(t.trials_to_converge)),
        ("5 descriptions", fmt_opt(t.descriptions)),
        (
            "6 mean features per description",
            fmt_opt(t.mean_features.map(|x| format!("{x:.2}"))),
        ),
        ("7 max features in a description", fmt_opt(t.max_features)),
        (
            "8 tree sensing cost per state",
            fmt_opt(t.tree_cost_per_state.map(|x| format!("{x:.2}"))),
        ),
        (
            "8' description sensing cost per state",
            fmt_opt(t.description_cost_per_state.map(|x| format!("{x:.2}"))),
        ),
    ];
    table(out, ("Table 1 row", "value"), &rows)?;
    if let (Some(cost), Some(success)) = (r.navigation_cost_per_move, r.navigation_success) {
        writeln!(
            out,
            "Navigation after learning ({}): sensing cost {cost:.2} per move, {:.1}% of trials by an optimal path",
            r.settings.predict_sensing,
            100.0 * success
        )?;
    }
    Ok(())
}

/// A two-column table whose columns are as wide as their widest cell.
fn table(out: &mut dyn Write, head: (&str, &str), rows: &[(&str, String)]) -> std::io::Result<()> {
    let width = |s: &str| s.chars().count();
    let left = rows
        .iter()
        .map(|(n, _)| width(n))
        .chain([width(head.0)])
        .max()
        .unwrap_or(0);
    let right = rows
        .iter()
        .map(|(_, v)| width(v))
        .chain([width(head.1)])
        .max()
        .unwrap_or(0);
    writeln!(out)?;
    writeln!(out, "{:<left$}  {:>right$}", head.0, head.1)?;
    for (name, value) in rows {
        writeln!(out, "{name:<left$}  {value:>right$}")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn table_columns_line_up_whatever_the_cells() {
        let rows = [
            ("a long label of many words", "1".to_string()),
            ("short", "not reached".to_string()),
        ];
        let mut out = Vec::new();
        super::table(&mut out, ("row", "value"), &rows).unwrap();
        let text = String::from_utf8(out).unwrap();
        let ends: Vec<usize> = text.lines().skip(1).map(|l| l.chars().count()).collect();
        assert!(ends.windows(2).all(|w| w[0] == w[1]), "{text}");
    }
}
