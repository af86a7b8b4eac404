//! `csrl run`: one CS-QL run.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use csql::{RunReport, RunSettings, Setup, StrategyKind};

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
    /// strategy, seed); flags given here override the file.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Stop an unconverged run after this many trials.
    #[arg(long)]
    max_trials: Option<u32>,
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
        s.validate()?;
        Ok(s)
    }
}

/// Run `csrl run`.
pub fn run(args: &RunArgs, out: &mut dyn Write) -> Result<()> {
    let settings = args.settings()?;
    let setup = Setup::new(&settings)?;
    let report = csql::run_on(&setup, &settings);
    if let Some(path) = &args.svg {
        std::fs::write(path, csql::policy_svg(&setup, &report))
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    if args.json {
        writeln!(out, "{}", serde_json::to_string(&report)?)?;
    } else {
        print_report(&report, out)?;
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
    writeln!(out)?;
    writeln!(out, "{:<42} {:>12}", "Table 1 row", "value")?;
    for (name, value) in rows {
        writeln!(out, "{name:<42} {value:>12}")?;
    }
    Ok(())
}
