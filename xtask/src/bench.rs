//! `cargo xtask bench`: how CS-QL's cost grows with the world, and how fast it moves
//! against a plain Q-learning loop.
//!
//! * `bench scale`: CS-QL on `random:WxW:0.2:S` for growing W, every run in a process of
//!   its own (so that CPU time and peak memory are the run's alone), with the fitted
//!   exponent of time against states.
//! * `bench throughput`: moves per CPU second of every strategy on `tan8x8`, against the
//!   hand-written Q-learning loop of qlearn's throughput example, in the same process.

use std::process::Command;
use std::time::Duration;

use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand};
use csql::{RunSettings, StrategyKind};
use serde::{Deserialize, Serialize};

#[path = "../../crates/qlearn/benches/support/reference.rs"]
mod reference;

/// Arguments of `cargo xtask bench`.
#[derive(Args)]
pub struct BenchArgs {
    #[command(subcommand)]
    what: What,
}

#[derive(Subcommand)]
enum What {
    /// CS-QL's CPU time, moves and peak memory on random W x W maps, and the exponent of
    /// time against states.
    Scale(ScaleArgs),
    /// Moves per CPU second of each strategy on tan8x8 against a hand-written Q-learning
    /// loop.
    Throughput(ThroughputArgs),
    /// One run, measured in this process (used by `scale`; prints one JSON line).
    #[command(hide = true)]
    One(OneArgs),
}

#[derive(Args)]
struct ScaleArgs {
    /// Map sides W (maps are `random:WxW:0.2:S`).
    #[arg(long, value_delimiter = ',', default_values_t = [8, 12, 16, 24, 32, 48, 64])]
    sizes: Vec<u32>,
    /// Strategies.
    #[arg(long, value_delimiter = ',', default_values_t = [StrategyKind::Lazy, StrategyKind::Random])]
    strategies: Vec<StrategyKind>,
    /// Map seeds S (every run uses seed 1, as `csrl run` does by default).
    #[arg(long, value_delimiter = ',', default_values_t = [1, 2])]
    seeds: Vec<u64>,
    /// The trial cap, high enough for the largest maps to converge.
    #[arg(long, default_value_t = 1_000_000)]
    max_trials: u32,
    /// Fit the exponents over sides at least this large.
    #[arg(long, default_value_t = 12)]
    fit_from: u32,
}

#[derive(Args)]
struct ThroughputArgs {
    /// Seeds per strategy (1 to N).
    #[arg(long, default_value_t = 20)]
    runs: u64,
    /// Moves of the hand-written reference loop.
    #[arg(long, default_value_t = 20_000_000)]
    reference_moves: u64,
}

#[derive(Args)]
struct OneArgs {
    #[arg(long)]
    map: String,
    #[arg(long)]
    strategy: StrategyKind,
    #[arg(long)]
    max_trials: u32,
}

/// What one measured run prints.
#[derive(Serialize, Deserialize)]
struct Measured {
    states: usize,
    converged: bool,
    trials: u32,
    moves: u64,
    /// Sensing cost charged in the whole run: the work CLASSIFY does.
    cost: f64,
    cpu_seconds: f64,
    peak_mib: f64,
}

/// Run `cargo xtask bench`.
pub fn run(args: &BenchArgs) -> Result<()> {
    match &args.what {
        What::Scale(a) => scale(a),
        What::Throughput(a) => throughput(a),
        What::One(a) => one(a),
    }
}

/// CPU time of this process so far and its peak resident memory in MiB, read from
/// Linux's `/proc` (elsewhere: zero and NaN, and the tables say so by their figures).
fn usage() -> (Duration, f64) {
    let cpu = std::fs::read_to_string("/proc/self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<u64>().ok())
        .map_or(Duration::ZERO, Duration::from_nanos);
    let peak = std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
            line.split_whitespace().nth(1)?.parse::<f64>().ok()
        })
        .map_or(f64::NAN, |kib| kib / 1024.0);
    (cpu, peak)
}

fn one(a: &OneArgs) -> Result<()> {
    let mut settings = RunSettings::tan1991(&a.map, a.strategy, 1);
    settings.max_trials = csql::TrialCap::new(a.max_trials)?;
    let (before, _) = usage();
    let report = csql::run(&settings)?;
    let (after, peak) = usage();
    let m = Measured {
        states: report.states.len(),
        converged: report.converged,
        trials: report.trials,
        moves: report.moves,
        cost: report.total_cost,
        cpu_seconds: (after - before).as_secs_f64(),
        peak_mib: peak,
    };
    crate::emit(&format!("{}\n", serde_json::to_string(&m)?))?;
    Ok(())
}

/// Least-squares slope of ln y against ln x.
fn exponent(points: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.0 > 0.0 && p.1 > 0.0)
        .map(|&(x, y)| (x.ln(), y.ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

fn scale(a: &ScaleArgs) -> Result<()> {
    if a.sizes.is_empty() || a.strategies.is_empty() || a.seeds.is_empty() {
        bail!("--sizes, --strategies and --seeds each need at least one value");
    }
    let exe = std::env::current_exe().context("cannot find the xtask program")?;
    crate::emit(&format!(
        "CS-QL on random:WxW:0.2:S (run seed 1, trial cap {}), one process per run\n\n\
         | strategy | W | S | states | converged | trials | moves | sensing cost | CPU s | moves per CPU s | CPU ns per unit of sensing | peak MiB |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
        a.max_trials
    ))?;
    let mut fits = Vec::new();
    for &k in &a.strategies {
        let (mut time_pts, mut move_pts, mut cost_pts) = (Vec::new(), Vec::new(), Vec::new());
        for &w in &a.sizes {
            for &seed in &a.seeds {
                let map = format!("random:{w}x{w}:0.2:{seed}");
                let out = Command::new(&exe)
                    .args(["bench", "one", "--map", &map, "--strategy", k.name()])
                    .args(["--max-trials", &a.max_trials.to_string()])
                    .output()
                    .with_context(|| format!("cannot run {}", exe.display()))?;
                if !out.status.success() {
                    bail!(
                        "the run on {map} ({k}) failed: {}",
                        String::from_utf8_lossy(&out.stderr).trim()
                    );
                }
                let m: Measured = serde_json::from_slice(&out.stdout)
                    .with_context(|| format!("unreadable measurement for {map} ({k})"))?;
                crate::emit(&format!(
                    "| {k} | {w} | {seed} | {} | {} | {} | {} | {:.0} | {:.3} | {:.0} | {:.1} | {:.1} |\n",
                    m.states,
                    if m.converged { "yes" } else { "no" },
                    m.trials,
                    m.moves,
                    m.cost,
                    m.cpu_seconds,
                    m.moves as f64 / m.cpu_seconds.max(1e-9),
                    m.cpu_seconds * 1e9 / m.cost.max(1.0),
                    m.peak_mib
                ))?;
                if w >= a.fit_from {
                    time_pts.push((m.states as f64, m.cpu_seconds));
                    move_pts.push((m.states as f64, m.moves as f64));
                    cost_pts.push((m.states as f64, m.cost));
                }
            }
        }
        fits.push((
            k,
            exponent(&time_pts),
            exponent(&move_pts),
            exponent(&cost_pts),
        ));
    }
    crate::emit(&format!(
        "\nFitted over W >= {} (least squares of ln y against ln states):\n\n\
         | strategy | CPU time ~ states^x | moves ~ states^x | sensing cost ~ states^x |\n|---|---|---|---|\n",
        a.fit_from
    ))?;
    let show = |x: Option<f64>| x.map_or_else(|| "-".to_string(), |x| format!("{x:.2}"));
    for (k, t, m, c) in fits {
        crate::emit(&format!(
            "| {k} | {} | {} | {} |\n",
            show(t),
            show(m),
            show(c)
        ))?;
    }
    Ok(())
}

fn throughput(a: &ThroughputArgs) -> Result<()> {
    use rand::SeedableRng;
    if a.runs == 0 || a.reference_moves == 0 {
        bail!("--runs and --reference-moves must be at least 1");
    }
    let (before, _) = usage();
    let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1991);
    let q = reference::run(a.reference_moves, &mut rng);
    let (after, _) = usage();
    std::hint::black_box(q);
    let reference = a.reference_moves as f64 / (after - before).as_secs_f64().max(1e-9);
    crate::emit(&format!(
        "hand-written Q-learning loop (qlearn's throughput example, open8x8): {reference:.0} moves per CPU s\n\n\
         | strategy | runs | moves | CPU s | moves per CPU s | against the loop |\n|---|---|---|---|---|---|\n"
    ))?;
    for k in StrategyKind::ALL {
        let mut moves = 0;
        let (before, _) = usage();
        for seed in 1..=a.runs {
            let settings = RunSettings::tan1991("tan8x8", k, seed);
            moves += csql::run(&settings)?.moves;
        }
        let (after, _) = usage();
        let secs = (after - before).as_secs_f64().max(1e-9);
        let rate = moves as f64 / secs;
        crate::emit(&format!(
            "| {k} | {} | {moves} | {secs:.3} | {rate:.0} | {:.3}x |\n",
            a.runs,
            rate / reference
        ))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::exponent;

    #[test]
    fn the_exponent_of_a_power_law_is_its_power() {
        let pts: Vec<(f64, f64)> = [1.0, 2.0, 5.0, 10.0]
            .iter()
            .map(|&x: &f64| (x, 3.0 * x.powf(1.7)))
            .collect();
        assert!((exponent(&pts).unwrap() - 1.7).abs() < 1e-9);
        assert_eq!(exponent(&pts[..1]), None);
    }
}
