//! `cargo xtask`: repository automation for csrl.
//!
//! * `cargo xtask reproduce`: the paper's Table 1 and figures beside ours.
//! * `cargo xtask fit-map`: a layout fitted to a target Table 1 (the paper's by default).
//! * `cargo xtask png`: figures rendered to PNG (resvg), to look at them as a reader would.
//! * `cargo xtask sweep` and `cargo xtask merge`: grids of settings, sharded across
//!   machines (see `docs/sweeps.md`).
//! * `cargo xtask robustness`: CS-QL, U-Tree and full sensing beyond the paper's
//!   assumptions (see `docs/robustness.md`).
//! * `cargo xtask testcost`: the test-cost tree family on the UCI benchmark (see
//!   `docs/testcost.md`).
//! * `cargo xtask anytime`: ACT's cost against its time as its samples per branch grow.
//! * `cargo xtask budget`: accuracy against test cost, each learner swept over its cost
//!   knob (mc, a budget per object, or CEGB's tradeoff), and the area under each curve.
//! * `cargo xtask bench scale` and `cargo xtask bench throughput`: how CS-QL's cost grows
//!   with the world, and its moves per second against a plain Q-learning loop.
//! * `cargo xtask test`: every test, Rust and Python (the README's test command).
//!
//! Exit codes, the same kinds as `csrl`'s: 0 success; 1 an input that cannot be read or is
//! not valid, or another failure (`error: ...` on stderr); 2 a usage error (clap's); 4 an
//! output (a file, a folder, a lock) that cannot be written, a missing folder's parent and
//! a read-only folder alike.

/// mimalloc: the benchmarks' trees and split tries allocate and free many small vectors,
/// and the system allocator spent much of their time there. It changes no result.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

mod bench;
mod costly;
mod figures;
mod files;
mod fit;
mod pytest;
mod python;

mod render;
mod reproduce;
mod robustness;
mod shard;
mod stats;
mod sweep;
mod testcost;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "cargo xtask",
    about = "Repository automation for csrl",
    after_help = "Exit codes: 0 success; 1 an input that cannot be read or is not valid, or \
another failure; 2 a usage error; 4 an output that cannot be written."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Reproduce the paper's Table 1 and Figures 4b and 5, beside the paper's numbers.
    Reproduce(reproduce::ReproduceArgs),
    /// Search grid layouts for the best fit to a target Table 1 (the paper's by default).
    FitMap(fit::FitArgs),
    /// Render SVG figures to PNG (FILE.svg -> FILE.png), checking each is well formed.
    Png {
        /// The SVG files.
        #[arg(required = true)]
        files: Vec<std::path::PathBuf>,
        /// Scale factor; the image may have at most 100 megapixels.
        #[arg(long, default_value_t = 1.0)]
        scale: f32,
    },
    /// Run a grid of maps and strategies, optionally one shard of it.
    Sweep(sweep::SweepArgs),
    /// Merge the outputs of sweep shards into one table.
    Merge(sweep::MergeArgs),
    /// CS-QL and two baselines under slip, sensor noise and a sensing range.
    Robustness(robustness::RobustnessArgs),
    /// The active-measurement benchmark: FrozenLake with priced row and column, the
    /// costed return per episode of each learner under both sensing rules.
    Costly(costly::CostlyArgs),
    /// The test-cost tree family on the UCI benchmark of Esmeir's thesis, beside the
    /// published figures.
    Testcost(Box<testcost::TestcostArgs>),
    /// ACT's cost against its time as its samples per branch grow, on the benchmark's
    /// folds and prices.
    Anytime(testcost::anytime::AnytimeArgs),
    /// Accuracy against test cost: each learner swept over mc, a budget per object or
    /// (CEGB) its tradeoff on the benchmark's folds and prices, the area under each curve,
    /// and a figure per data set.
    Budget(testcost::curves::BudgetArgs),
    /// Write CUBE, the synthetic data set of the costly-feature literature (20 features,
    /// 8 classes, each telling its class on three features of its own), from its recipe
    /// and a seed.
    Cube(testcost::cube::CubeArgs),
    /// Benchmarks: CS-QL's growth with the world's size, and its moves per second.
    Bench(bench::BenchArgs),
    /// Every test: `cargo test --workspace`, then the Python package's tests in a virtual
    /// environment under `target/` (the README's test command).
    Test(pytest::TestArgs),
}

/// Print to stdout; a reader that has gone away (`cargo xtask ... | head`) ends the output
/// quietly instead of panicking.
pub fn emit(text: &str) -> std::io::Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => other,
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Reproduce(args) => reproduce::run(args),
        Command::FitMap(args) => fit::run(args),
        Command::Png { files, scale } => render::run(files, *scale),
        Command::Sweep(args) => sweep::sweep(args),
        Command::Merge(args) => sweep::merge(args),
        Command::Robustness(args) => robustness::robustness(args),
        Command::Costly(args) => costly::costly(args),
        Command::Testcost(args) => testcost::testcost(args),
        Command::Anytime(args) => testcost::anytime::anytime(args),
        Command::Budget(args) => testcost::curves::budget(args),
        Command::Cube(args) => testcost::cube::cube(args),
        Command::Bench(args) => bench::run(args),
        Command::Test(args) => pytest::test(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            note(&format!("error: {e:#}"));
            let cannot_write = e
                .chain()
                .any(|c| c.downcast_ref::<files::CannotWrite>().is_some());
            ExitCode::from(if cannot_write { 4 } else { 1 })
        }
    }
}

/// Print a line to stderr; a full or closed stderr loses the line instead of panicking.
pub fn note(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}
