//! `cargo xtask fit-map`: search grid layouts for the one whose Table 1 is closest to a
//! target table (the paper's by default), by the fit score of section 6.1 of the project's specification (`docs/specification.md`).
//!
//! # The score
//!
//! For a layout and a set of seeds, every strategy runs once per seed with the paper's
//! settings; rows 1, 2, 3, 4, 6 and 7 of Table 1 are averaged over the seeds per strategy,
//! and the score is `sqrt(mean over the 24 numbers of ln(ours / target)^2)`. A layout on
//! which some run does not converge within the trial cap has no score (it is never chosen).
//!
//! # The search
//!
//! Three disjoint sets of seeds keep the choice honest:
//!
//! * **search seeds** (from 100): every layout the search looks at is scored on these;
//! * **selection seeds** (from 200): the best candidates of the search are scored again
//!   on these, and the best on them is chosen;
//! * **report seeds** (from 300): the chosen layout is scored once more on seeds that took
//!   no part in any choice. This is the figure to quote; it is not a choice.
//!
//! Phases: (1) `--random` uniformly random valid layouts (the goal on a random cell, the
//! obstacles on a random subset of the others, drawn again until every free cell is
//! reachable), whose score distribution is reported; (2) local search from the best
//! `--restarts` of them (distinct random starting points): each round, every restart
//! proposes `--neighbours` moves (one obstacle moved to a free cell, or the goal moved to
//! an empty cell) and takes the best if it improves its score; (3) selection; (4) report.
//!
//! Every random choice flows from `--seed` through a named generator per restart and
//! phase, and the evaluations of a round run in parallel but are collected in a fixed
//! order, so the result does not depend on the thread count.
//!
//! # Resuming
//!
//! Each run's measures are appended to `<out>/evaluations.jsonl` as soon as a batch ends.
//! The search is deterministic, so a search that is stopped and started again with the
//! same arguments replays its choices, reads the runs it already made from that file, and
//! continues where it stopped.
//!
//! # The files
//!
//! This file holds the arguments, the score's definition, the runs (kept in the
//! evaluations file) and the search; `fit/report.rs` writes the report and the chosen
//! map, and `fit/published.rs` holds the table fitted to (the paper's, or a target CSV).

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail, ensure};
use clap::Args;
use csql::{RunSettings, Setup, StrategyKind, Table1Row};
use indicatif::{ProgressBar, ProgressStyle};
use mdp::Map;
use rand::seq::SliceRandom;
use rand::{Rng, RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use published::Target;

pub mod published;
mod report;

/// Arguments of `cargo xtask fit-map`.
#[derive(Args, Clone, Debug)]
pub struct FitArgs {
    /// Seed of the search (layouts and moves).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Interior width of the layouts.
    #[arg(long, default_value_t = 8)]
    pub width: usize,
    /// Interior height of the layouts.
    #[arg(long, default_value_t = 8)]
    pub height: usize,
    /// Obstacles in a layout (every free cell must be reachable from the goal).
    #[arg(long, default_value_t = 13)]
    pub obstacles: usize,
    /// Target table: a CSV with the header `row,resetting,lazy,random,eager` and one line
    /// for each of rows 1, 2, 3, 4, 6 and 7 (other rows are ignored). Default: the paper's.
    #[arg(long)]
    pub target: Option<PathBuf>,
    /// Random layouts scored in phase 1 (also the score distribution reported).
    #[arg(long, default_value_t = 300)]
    pub random: usize,
    /// Local searches, started from the best random layouts.
    #[arg(long, default_value_t = 6)]
    pub restarts: usize,
    /// Rounds of local moves per restart.
    #[arg(long, default_value_t = 20)]
    pub rounds: usize,
    /// Moves proposed per restart and round.
    #[arg(long, default_value_t = 6)]
    pub neighbours: usize,
    /// Candidates (best on the search seeds) re-scored on the selection seeds.
    #[arg(long, default_value_t = 12)]
    pub candidates: usize,
    /// Search seeds per strategy (seeds 100, 101, ...).
    #[arg(long, default_value_t = 12)]
    pub search_seeds: u64,
    /// Selection seeds per strategy (seeds 200, 201, ...).
    #[arg(long, default_value_t = 20)]
    pub select_seeds: u64,
    /// Report seeds per strategy (seeds 300, 301, ...), never used to choose.
    #[arg(long, default_value_t = 20)]
    pub report_seeds: u64,
    /// Trial cap of each run; a layout with a run that does not converge has no score.
    #[arg(long, default_value_t = 6000)]
    pub max_trials: u32,
    /// Worker threads (default: every core). Results do not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Output folder: evaluations (for resuming), the report and the chosen map.
    #[arg(long, default_value = "results/fit-map")]
    pub out: PathBuf,
}

impl FitArgs {
    fn validate(&self) -> Result<()> {
        ensure!(
            (1..=30).contains(&self.width) && (1..=30).contains(&self.height),
            "--width and --height must be in 1..=30"
        );
        let n = self.width * self.height;
        ensure!(
            self.obstacles + 2 <= n,
            "{} obstacles leave no room for a goal and a state in {n} cells",
            self.obstacles
        );
        ensure!(self.random >= 1, "--random must be at least 1");
        ensure!(
            self.restarts <= self.random,
            "--restarts ({}) cannot exceed --random ({})",
            self.restarts,
            self.random
        );
        ensure!(self.candidates >= 1, "--candidates must be at least 1");
        for (name, k) in [
            ("--search-seeds", self.search_seeds),
            ("--select-seeds", self.select_seeds),
            ("--report-seeds", self.report_seeds),
        ] {
            ensure!(
                (1..=100).contains(&k),
                "{name} must be in 1..=100 (the seed sets are 100 apart)"
            );
        }
        ensure!(self.max_trials >= 1, "--max-trials must be at least 1");
        Ok(())
    }
}

/// The Table 1 rows the score compares (the paper's rows 1 to 4, 6 and 7), in the order
/// of a [`Fitted`] table.
pub const FIT_ROWS: [Table1Row; 6] = [
    Table1Row::CostToSufficient,
    Table1Row::TrialsToSufficient,
    Table1Row::CostToConverge,
    Table1Row::Trials,
    Table1Row::MeanFeatures,
    Table1Row::MaxFeatures,
];

/// One value per fitted row ([`FIT_ROWS`]), reached by the row. Serialised as the array of
/// the values in [`FIT_ROWS`] order: the form of the evaluations file.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct Fitted<T>([T; 6]);

impl<T> Fitted<T> {
    /// The value of each fitted row.
    pub fn from_fn(f: impl FnMut(Table1Row) -> T) -> Fitted<T> {
        Fitted(FIT_ROWS.map(f))
    }

    /// The value of each fitted row, or `None` if some row has none.
    pub fn try_from_fn(f: impl FnMut(Table1Row) -> Option<T>) -> Option<Fitted<T>> {
        let values: Vec<T> = FIT_ROWS.into_iter().map(f).collect::<Option<_>>()?;
        values.try_into().ok().map(Fitted)
    }

    /// The value of `row`, if it is fitted.
    pub fn get(&self, row: Table1Row) -> Option<&T> {
        let i = FIT_ROWS.iter().position(|&r| r == row)?;
        Some(&self.0[i])
    }

    /// The value of `row` to change, if it is fitted.
    pub fn get_mut(&mut self, row: Table1Row) -> Option<&mut T> {
        let i = FIT_ROWS.iter().position(|&r| r == row)?;
        Some(&mut self.0[i])
    }

    /// Each fitted row with its value, in [`FIT_ROWS`] order.
    pub fn iter(&self) -> impl Iterator<Item = (Table1Row, &T)> {
        FIT_ROWS.into_iter().zip(&self.0)
    }

    /// Each fitted row with its value to change, in [`FIT_ROWS`] order.
    pub fn iter_mut(&mut self) -> impl Iterator<Item = (Table1Row, &mut T)> {
        FIT_ROWS.into_iter().zip(&mut self.0)
    }
}

/// The fitted row printed as `number` in the paper, if any (`None` for row 5, 8 and 8').
fn fitted_row(number: &str) -> Option<Table1Row> {
    FIT_ROWS.into_iter().find(|r| r.number() == number)
}

/// The fit score (`docs/specification.md`, section 6.1) of a table of means against a target.
///
/// ```text
/// score = sqrt(mean over the 24 cells of ln(ours / target)^2)
/// ```
pub fn score(means: &Fitted<[f64; 4]>, target: &Target) -> f64 {
    let mut sum = 0.0;
    for ((_, ours), (_, theirs)) in means.iter().zip(target.0.iter()) {
        for (a, b) in ours.iter().zip(theirs) {
            sum += (a / b).ln().powi(2);
        }
    }
    (sum / 24.0).sqrt()
}

/// First seed of each seed set. Disjoint from each other and from the seeds 1 to 99
/// that `cargo xtask reproduce` uses.
const SEARCH_BASE: u64 = 100;
const SELECT_BASE: u64 = 200;
const REPORT_BASE: u64 = 300;

/// Runs made between two appends to the evaluations file.
const CHUNK: usize = 256;

/// The fitted rows of one run, `None` where the run did not reach the figure.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
struct Evaluation {
    layout: String,
    strategy: StrategyKind,
    seed: u64,
    max_trials: u32,
    rows: Fitted<Option<f64>>,
}

/// The key of a run in the cache.
type Key = (String, StrategyKind, u64);

/// A layout: the interior cells, row by row, as `#`, `.` and `G`.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Layout {
    width: usize,
    cells: Vec<u8>,
}

impl Layout {
    /// The layout as one string of rows separated by `/` (the cache key).
    pub fn key(&self) -> String {
        self.cells
            .chunks(self.width)
            .map(|r| String::from_utf8_lossy(r).into_owned())
            .collect::<Vec<_>>()
            .join("/")
    }

    /// The layout as map text, rows separated by newlines.
    pub fn text(&self) -> String {
        self.key().replace('/', "\n")
    }

    /// The map of this layout.
    pub fn map(&self, name: &str) -> Result<Map> {
        Ok(Map::from_layout(name, &self.text())?)
    }

    /// Every free cell reachable from the goal (4-neighbourhood): `mdp`'s map validation
    /// refuses a layout with a free cell cut off from the goal, so a layout is connected
    /// exactly when it makes a map.
    fn connected(&self) -> bool {
        self.map("connected").is_ok()
    }

    /// A uniformly random valid layout (rejection sampling on connectivity).
    fn random<R: Rng + ?Sized>(w: usize, h: usize, obstacles: usize, rng: &mut R) -> Layout {
        let n = w * h;
        loop {
            let mut idx: Vec<usize> = (0..n).collect();
            idx.shuffle(rng);
            let mut cells = vec![b'.'; n];
            cells[idx[0]] = b'G';
            for &i in &idx[1..=obstacles] {
                cells[i] = b'#';
            }
            let l = Layout { width: w, cells };
            if l.connected() {
                return l;
            }
        }
    }

    /// A random valid neighbour: one obstacle moved to an empty cell, or (one time in
    /// four) the goal moved to an empty cell.
    fn neighbour<R: Rng + ?Sized>(&self, rng: &mut R) -> Layout {
        let of = |b: u8| -> Vec<usize> {
            (0..self.cells.len())
                .filter(|&i| self.cells[i] == b)
                .collect()
        };
        let empty = of(b'.');
        let obstacles = of(b'#');
        loop {
            let mut next = self.clone();
            let to = empty[rng.random_range(0..empty.len())];
            let from = if obstacles.is_empty() || rng.random_range(0..4) == 0 {
                self.cells.iter().position(|&c| c == b'G').expect("a goal")
            } else {
                obstacles[rng.random_range(0..obstacles.len())]
            };
            next.cells.swap(from, to);
            if next.connected() {
                return next;
            }
        }
    }
}

/// The evaluations made so far, backed by an append-only file.
struct Cache {
    runs: BTreeMap<Key, Fitted<Option<f64>>>,
    file: std::fs::File,
    max_trials: u32,
}

impl Cache {
    fn open(path: &Path, max_trials: u32) -> Result<Cache> {
        let mut runs = BTreeMap::new();
        if path.exists() {
            let text = std::fs::read_to_string(path)
                .with_context(|| format!("cannot read {}", path.display()))?;
            for (i, line) in text.lines().enumerate() {
                // A line cut short by a kill is the only one that can be bad: the last.
                let Ok(e) = serde_json::from_str::<Evaluation>(line) else {
                    eprintln!("{}:{}: skipping an unreadable line", path.display(), i + 1);
                    continue;
                };
                if e.max_trials == max_trials {
                    runs.insert((e.layout, e.strategy, e.seed), e.rows);
                }
            }
        }
        let file = crate::files::open_append(path)?;
        Ok(Cache {
            runs,
            file,
            max_trials,
        })
    }

    /// Make every run of `layouts` on `seeds` that is not cached yet, in parallel.
    fn ensure(&mut self, layouts: &[Layout], seeds: &[u64], what: &str) -> Result<()> {
        let mut todo: Vec<(Layout, StrategyKind, u64)> = Vec::new();
        let mut queued = BTreeSet::new();
        for l in layouts {
            for &k in &StrategyKind::ALL {
                for &s in seeds {
                    let key = (l.key(), k, s);
                    if !self.runs.contains_key(&key) && queued.insert(key) {
                        todo.push((l.clone(), k, s));
                    }
                }
            }
        }
        if todo.is_empty() {
            return Ok(());
        }
        let bar = ProgressBar::new(todo.len() as u64);
        bar.set_style(
            ProgressStyle::with_template(
                "{msg} [{bar:30}] {pos}/{len} runs ({elapsed}, eta {eta})",
            )
            .expect("a valid template")
            .progress_chars("=> "),
        );
        bar.set_message(what.to_string());
        let max_trials = self.max_trials;
        // In chunks, so that a stopped search loses at most one chunk of work.
        for chunk in todo.chunks(CHUNK) {
            let done: Vec<Result<Evaluation>> = chunk
                .par_iter()
                .map(|(l, k, s)| {
                    let r = evaluate(l, *k, *s, max_trials);
                    bar.inc(1);
                    r
                })
                .collect();
            let mut text = String::new();
            for e in done {
                let e = e?;
                text.push_str(&serde_json::to_string(&e)?);
                text.push('\n');
                self.runs.insert((e.layout, e.strategy, e.seed), e.rows);
            }
            self.file
                .write_all(text.as_bytes())
                .and_then(|()| self.file.flush())
                .context("cannot append to the evaluations file")?;
        }
        bar.finish_and_clear();
        Ok(())
    }

    /// Per fitted row and strategy, the mean over `seeds`; `None` if some run missed it.
    fn means(&self, l: &Layout, seeds: &[u64]) -> Option<Fitted<[f64; 4]>> {
        let mut m = Fitted::from_fn(|_| [0.0; 4]);
        for (j, &k) in StrategyKind::ALL.iter().enumerate() {
            for &s in seeds {
                let rows = self.runs.get(&(l.key(), k, s))?;
                for ((_, mean), (_, v)) in m.iter_mut().zip(rows.iter()) {
                    mean[j] += (*v)? / seeds.len() as f64;
                }
            }
        }
        Some(m)
    }

    /// The fit score of `l` on `seeds`; `None` if some run did not converge.
    fn score(&self, l: &Layout, seeds: &[u64], target: &Target) -> Option<f64> {
        self.means(l, seeds).map(|m| score(&m, target))
    }
}

/// One run of the paper's settings on a layout.
fn evaluate(l: &Layout, strategy: StrategyKind, seed: u64, max_trials: u32) -> Result<Evaluation> {
    let mut settings = RunSettings::tan1991(l.map("fit")?, strategy, seed);
    settings.max_trials = csql::TrialCap::new(max_trials)?;
    let setup = Setup::new(&settings)?;
    let t = csql::run_on(&setup, &settings)?.table1;
    Ok(Evaluation {
        layout: l.key(),
        strategy,
        seed,
        max_trials,
        rows: Fitted::from_fn(|row| row.of(&t)),
    })
}

/// A named generator for one stream of the search.
fn stream(seed: u64, id: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(seed ^ id.wrapping_mul(0x9E37_79B9_7F4A_7C15))
}

fn seeds(base: u64, n: u64) -> Vec<u64> {
    (base..base + n).collect()
}

/// `cargo xtask fit-map`.
pub fn run(args: &FitArgs) -> Result<()> {
    args.validate()?;
    let target = match &args.target {
        Some(p) => Target::parse_csv(
            &std::fs::read_to_string(p).with_context(|| format!("cannot read {}", p.display()))?,
            &p.display().to_string(),
        )?,
        None => Target::paper(),
    };
    crate::files::create_dir(&args.out)?;
    let mut cache = Cache::open(&args.out.join("evaluations.jsonl"), args.max_trials)?;
    let search = seeds(SEARCH_BASE, args.search_seeds);
    let select = seeds(SELECT_BASE, args.select_seeds);
    let report = seeds(REPORT_BASE, args.report_seeds);
    let pool = crate::files::pool(args.threads)?;
    let started = std::time::Instant::now();

    // Phase 1: random layouts.
    let mut rng = stream(args.seed, 0);
    let randoms: Vec<Layout> = (0..args.random)
        .map(|_| Layout::random(args.width, args.height, args.obstacles, &mut rng))
        .collect();
    pool.install(|| cache.ensure(&randoms, &search, "random layouts"))?;
    let random_scores: Vec<Option<f64>> = randoms
        .iter()
        .map(|l| cache.score(l, &search, &target))
        .collect();

    // Phase 2: local search from the best distinct random layouts.
    let mut ranked: Vec<(f64, &Layout)> = random_scores
        .iter()
        .zip(&randoms)
        .filter_map(|(s, l)| s.map(|s| (s, l)))
        .collect();
    ranked.sort_by(|a, b| a.0.total_cmp(&b.0).then_with(|| a.1.cmp(b.1)));
    ranked.dedup_by(|a, b| a.1 == b.1);
    ensure!(
        !ranked.is_empty(),
        "no random layout converged in every run within {} trials",
        args.max_trials
    );
    let mut current: Vec<(f64, Layout)> = ranked
        .iter()
        .take(args.restarts)
        .map(|(s, l)| (*s, (*l).clone()))
        .collect();
    let mut rngs: Vec<Xoshiro256PlusPlus> = (0..current.len())
        .map(|i| stream(args.seed, 1 + i as u64))
        .collect();
    let mut trail = String::new();
    let mut examined: BTreeSet<Layout> = randoms.iter().cloned().collect();
    for round in 1..=args.rounds {
        let proposals: Vec<Vec<Layout>> = current
            .iter()
            .zip(rngs.iter_mut())
            .map(|((_, l), rng)| (0..args.neighbours).map(|_| l.neighbour(rng)).collect())
            .collect();
        let flat: Vec<Layout> = proposals.iter().flatten().cloned().collect();
        examined.extend(flat.iter().cloned());
        pool.install(|| {
            cache.ensure(
                &flat,
                &search,
                &format!("local moves, round {round}/{}", args.rounds),
            )
        })?;
        for (i, props) in proposals.iter().enumerate() {
            for p in props {
                if let Some(s) = cache.score(p, &search, &target)
                    && s < current[i].0
                {
                    current[i] = (s, p.clone());
                }
            }
        }
        let best: Vec<String> = current.iter().map(|(s, _)| format!("{s:.3}")).collect();
        let _ = writeln!(trail, "| {round} | {} |", best.join(" | "));
    }

    // Phase 3: selection on fresh seeds among the best layouts seen on the search seeds.
    let mut seen: Vec<(f64, Layout)> = examined
        .into_iter()
        .filter_map(|l| cache.score(&l, &search, &target).map(|s| (s, l)))
        .collect();
    seen.sort_by(|a, b| a.0.total_cmp(&b.0).then_with(|| a.1.cmp(&b.1)));
    let candidates: Vec<(f64, Layout)> = seen.into_iter().take(args.candidates).collect();
    let cand_layouts: Vec<Layout> = candidates.iter().map(|c| c.1.clone()).collect();
    pool.install(|| cache.ensure(&cand_layouts, &select, "selection"))?;
    let mut chosen: Option<(f64, usize)> = None;
    for (i, l) in cand_layouts.iter().enumerate() {
        if let Some(s) = cache.score(l, &select, &target)
            && chosen.is_none_or(|(b, _)| s < b)
        {
            chosen = Some((s, i));
        }
    }
    let Some((select_score, ci)) = chosen else {
        bail!("no candidate converged in every run on the selection seeds");
    };
    let best = cand_layouts[ci].clone();

    // Phase 4: report on seeds that took no part in any choice.
    pool.install(|| cache.ensure(std::slice::from_ref(&best), &report, "report"))?;
    let elapsed = started.elapsed().as_secs_f64();
    report::write(
        args,
        &target,
        &cache,
        Found {
            search,
            select,
            report,
            random_scores,
            restarts: current.len(),
            trail,
            candidates,
            best,
            select_score,
            elapsed,
        },
    )
}

/// What a search found, for its report.
struct Found {
    /// The search seeds.
    search: Vec<u64>,
    /// The selection seeds.
    select: Vec<u64>,
    /// The report seeds.
    report: Vec<u64>,
    /// The score of each random layout on the search seeds, `None` where a run did not
    /// converge.
    random_scores: Vec<Option<f64>>,
    /// The local searches made.
    restarts: usize,
    /// The best score of each local search after each round: the rows of a table.
    trail: String,
    /// The best layouts on the search seeds, with their scores there, best first.
    candidates: Vec<(f64, Layout)>,
    /// The chosen layout: the best candidate on the selection seeds.
    best: Layout,
    /// The chosen layout's score on the selection seeds.
    select_score: f64,
    /// The seconds this invocation took.
    elapsed: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_paper_scores_zero_against_itself() {
        let t = Target::paper();
        assert_eq!(score(&t.0, &t), 0.0);
        let mut off = t.0;
        for (_, row) in off.iter_mut() {
            for v in row.iter_mut() {
                *v *= std::f64::consts::E;
            }
        }
        assert!((score(&off, &t) - 1.0).abs() < 1e-12);
        let paper = |row| t.0.get(row).copied();
        assert_eq!(
            paper(Table1Row::CostToSufficient),
            Some([467768.0, 62984.0, 37550.0, 27184.0])
        );
        assert_eq!(paper(Table1Row::MaxFeatures), Some([9.2, 10.6, 12.3, 16.8]));
        assert_eq!(paper(Table1Row::Descriptions), None);
    }

    #[test]
    fn evaluations_files_keep_their_form() {
        // A line as the evaluations file has held it since the first search: the fitted
        // rows as an array in the paper's order.
        let line = r#"{"layout":"..G","strategy":"lazy","seed":101,"max_trials":6000,"rows":[120.0,3.0,150.0,5.0,1.5,null]}"#;
        let e: Evaluation = serde_json::from_str(line).unwrap();
        assert_eq!(e.rows.get(Table1Row::CostToSufficient), Some(&Some(120.0)));
        assert_eq!(e.rows.get(Table1Row::Trials), Some(&Some(5.0)));
        assert_eq!(e.rows.get(Table1Row::MeanFeatures), Some(&Some(1.5)));
        assert_eq!(e.rows.get(Table1Row::MaxFeatures), Some(&None));
        assert_eq!(serde_json::to_string(&e).unwrap(), line);
    }

    #[test]
    fn random_layouts_and_moves_stay_valid() {
        let mut rng = stream(5, 0);
        for _ in 0..50 {
            let l = Layout::random(8, 8, 13, &mut rng);
            assert!(l.connected());
            let m = l.map("x").unwrap();
            assert_eq!((m.obstacles(), m.states().len()), (13, 50));
            let n = l.neighbour(&mut rng);
            assert_ne!(n, l);
            assert_eq!(n.map("y").unwrap().obstacles(), 13);
        }
        // A layout with a walled-in cell is not connected.
        let walled = Layout {
            width: 3,
            cells: b".#G#..#..".to_vec(),
        };
        assert!(!walled.connected());
    }

    #[test]
    fn a_tiny_search_is_deterministic_and_resumes() {
        let dir = std::env::temp_dir().join(format!("csrl-fit-test-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let args = FitArgs {
            seed: 3,
            width: 3,
            height: 3,
            obstacles: 1,
            target: None,
            random: 3,
            restarts: 1,
            rounds: 1,
            neighbours: 2,
            candidates: 2,
            search_seeds: 1,
            select_seeds: 1,
            report_seeds: 1,
            max_trials: 2000,
            threads: Some(2),
            out: dir.clone(),
        };
        run(&args).unwrap();
        let first = std::fs::read_to_string(dir.join("report.md")).unwrap();
        let lines = std::fs::read_to_string(dir.join("evaluations.jsonl"))
            .unwrap()
            .lines()
            .count();
        // Again, on one thread: nothing is run again and the choice is the same.
        let again = FitArgs {
            threads: Some(1),
            ..args
        };
        run(&again).unwrap();
        let second = std::fs::read_to_string(dir.join("report.md")).unwrap();
        let strip = |s: &str| {
            s.lines()
                .filter(|l| !l.contains(" s for this invocation"))
                .collect::<Vec<_>>()
                .join("\n")
        };
        assert_eq!(strip(&first), strip(&second));
        let after = std::fs::read_to_string(dir.join("evaluations.jsonl"))
            .unwrap()
            .lines()
            .count();
        assert_eq!(lines, after);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
