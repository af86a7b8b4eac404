//! What a reproduction is asked for and what it computed: shared by `reproduce` (Table 1
//! and the figures) and `sense` (Table 1 at each `predict_sensing` level), so that neither
//! needs the other's module.

use std::path::PathBuf;

use clap::Args;
use csql::{Reference, RunReport, Setup, StrategyKind};

/// Arguments of `cargo xtask reproduce`.
#[derive(Args, Clone, Debug)]
pub struct ReproduceArgs {
    /// Runs per strategy (the paper: 5).
    #[arg(long, default_value_t = 5)]
    pub runs: u64,
    /// Base seed: run i uses seed S + i.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// The map: a built-in name or a map file.
    #[arg(long, default_value = "tan8x8")]
    pub map: String,
    /// Strategies, comma-separated, each named once.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "resetting,lazy,random,eager"
    )]
    pub strategies: Vec<StrategyKind>,
    /// Worker threads, at most 256 (default or 0: every core). Results do not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Output folder.
    #[arg(long, default_value = "results")]
    pub out: PathBuf,
    /// Recompute the default table and compare it with the committed docs/table1.md,
    /// failing on any difference; writes nothing.
    #[arg(long, conflicts_with = "bless")]
    pub check: bool,
    /// Also refresh the committed docs/table1.md and docs/figures/ (only with the default
    /// map, runs, seed and strategies). Without it, nothing outside `--out` is written.
    #[arg(long)]
    pub bless: bool,
}

impl ReproduceArgs {
    pub(crate) fn is_default(&self) -> bool {
        self.runs == 5
            && self.seed == 1
            && self.map == PAPERS_MAP
            && self.strategies == StrategyKind::ALL
    }

    /// The paper's numbers are shown beside ours only on our reconstruction of its map.
    pub(crate) fn on_papers_map(&self) -> bool {
        self.map == PAPERS_MAP
    }
}

/// The built-in map that stands for the paper's (fitted to its Table 1).
pub(crate) const PAPERS_MAP: &str = "tan8x8";

/// Everything the table and the figures are made of.
pub struct Results {
    pub args: ReproduceArgs,
    pub setup: Setup,
    /// Per strategy (in the order asked), its runs and the Q-learning-on-the-final-
    /// representation reference of each run.
    pub runs: Vec<(StrategyKind, Vec<RunReport>, Vec<Reference>)>,
    pub full: Vec<Reference>,
}
