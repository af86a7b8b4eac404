//! `cargo xtask reproduce`: the paper's Table 1 and Figures 4b and 5, beside ours.
//!
//! Seeds: run `i` (from 0) of every strategy uses seed `S + i`, so the strategies are
//! compared on the same seeds and the full-sensing reference uses them too. The results
//! are collected in job order, so they do not depend on the number of threads.
//!
//! This file holds the arguments, what a reproduction computed ([`Results`]), its jobs
//! and their running; `reproduce/report.rs` writes Table 1 beside the paper's, its CSV,
//! the runs and the figures, `reproduce/published.rs` holds the paper's figures the
//! reading quotes beside ours, and `reproduce/sense.rs` writes Table 1 again at each
//! `predict_sensing` level.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::Args;
use csql::{Reference, RunReport, RunSettings, Setup, StrategyKind};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use crate::files::pool;

mod published;
mod report;
mod sense;

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

/// The committed copy of the default table.
const COMMITTED: &str = "docs/table1.md";

/// The committed copies of figures, refreshed by `--bless`.
const BLESSED_FIGURES: [&str; 7] = [
    "learning_curves.svg",
    "policy_tan8x8_lazy.svg",
    "descriptions_tan8x8_lazy.svg",
    "descriptions_tan8x8_lazy.md",
    "tree_tan8x8_resetting.svg",
    "tree_tan8x8_resetting.dot",
    "figure5_tan3x3.svg",
];

#[derive(Clone, Copy, Debug)]
enum Job {
    Csql { strategy: StrategyKind, run: u64 },
    FullSensing { run: u64 },
}

enum Outcome {
    Csql {
        report: Box<RunReport>,
        fixed: Reference,
    },
    FullSensing(Reference),
}

fn progress(len: u64, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(len);
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} runs ({elapsed})")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    bar
}

/// Run every job of a reproduction.
pub fn compute(args: &ReproduceArgs) -> Result<Results> {
    crate::files::seeds(args.seed, args.runs)?;
    if args.strategies.is_empty() {
        bail!("--strategies must name at least one strategy");
    }
    crate::files::distinct("--strategies", &args.strategies)?;
    let base = RunSettings::tan1991(&args.map, StrategyKind::Resetting, args.seed);
    let setup = Setup::new(&base)?;
    let mut jobs = Vec::new();
    for &strategy in &args.strategies {
        jobs.extend((0..args.runs).map(|run| Job::Csql { strategy, run }));
    }
    jobs.extend((0..args.runs).map(|run| Job::FullSensing { run }));
    let bar = progress(jobs.len() as u64, &format!("CS-QL on {}", setup.map.name()));
    let outcomes: Vec<Outcome> = pool(args.threads)?.install(|| {
        jobs.par_iter()
            .map(|&job| -> Result<Outcome> {
                let out = match job {
                    Job::Csql { strategy, run } => {
                        let mut settings = base.clone();
                        settings.learner = csql::LearnerSettings::cs_ql(strategy);
                        settings.seed = args.seed + run;
                        let (report, rep) = csql::run_with_representation(&setup, &settings)?;
                        let fixed = csql::fixed_representation_reference(&setup, &settings, rep);
                        Outcome::Csql {
                            report: Box::new(report),
                            fixed,
                        }
                    }
                    Job::FullSensing { run } => {
                        let mut settings = base.clone();
                        settings.seed = args.seed + run;
                        Outcome::FullSensing(csql::full_sensing_reference(&setup, &settings))
                    }
                };
                bar.inc(1);
                Ok(out)
            })
            .collect::<Result<Vec<_>>>()
    })?;
    bar.finish_and_clear();
    let mut runs: Vec<(StrategyKind, Vec<RunReport>, Vec<Reference>)> = args
        .strategies
        .iter()
        .map(|&k| (k, Vec::new(), Vec::new()))
        .collect();
    let mut full = Vec::new();
    for (job, outcome) in jobs.iter().zip(outcomes) {
        match (job, outcome) {
            (Job::Csql { strategy, .. }, Outcome::Csql { report, fixed }) => {
                let slot = runs
                    .iter_mut()
                    .find(|r| r.0 == *strategy)
                    .expect("asked for");
                slot.1.push(*report);
                slot.2.push(fixed);
            }
            (Job::FullSensing { .. }, Outcome::FullSensing(r)) => full.push(r),
            _ => unreachable!("outcomes follow their jobs"),
        }
    }
    Ok(Results {
        args: args.clone(),
        setup,
        runs,
        full,
    })
}

/// `cargo xtask reproduce`.
pub fn run(args: &ReproduceArgs) -> Result<()> {
    if args.check {
        let check = ReproduceArgs {
            runs: 5,
            seed: 1,
            map: "tan8x8".into(),
            strategies: StrategyKind::ALL.to_vec(),
            ..args.clone()
        };
        let fresh = compute(&check)?.markdown();
        let committed = std::fs::read_to_string(COMMITTED).with_context(|| {
            format!("cannot read {COMMITTED}; run `cargo xtask reproduce --bless` to write it")
        })?;
        if fresh == committed {
            crate::emit(&format!("{COMMITTED} is what the code produces today\n"))?;
            return Ok(());
        }
        for (i, (a, b)) in committed.lines().zip(fresh.lines()).enumerate() {
            if a != b {
                crate::note(&format!(
                    "{COMMITTED}:{}: differs\n  committed: {a}\n  now:       {b}",
                    i + 1
                ));
            }
        }
        if committed.lines().count() != fresh.lines().count() {
            crate::note(&format!(
                "{COMMITTED}: {} lines committed, {} produced now",
                committed.lines().count(),
                fresh.lines().count()
            ));
        }
        bail!("{COMMITTED} is out of date: run `cargo xtask reproduce --bless` and commit it");
    }
    if args.bless && !args.is_default() {
        bail!(
            "--bless refreshes the committed default table: it takes the default --map, --runs, --seed and --strategies"
        );
    }
    let res = compute(args)?;
    crate::files::create_dir(&args.out)?;
    let _lock = crate::files::OutLock::acquire(&args.out)?;
    let md = res.markdown();
    let mut written = report::write(&res, &md, &args.out)?;
    written.extend(sense::write(&res, &args.out, args.bless)?);
    if args.bless {
        // The committed copies that the README shows and `--check` compares with.
        crate::files::write_atomic(Path::new(COMMITTED), &md)?;
        written.push(PathBuf::from(COMMITTED));
        crate::files::create_dir(Path::new("docs/figures"))?;
        for name in BLESSED_FIGURES {
            let to = Path::new("docs/figures").join(name);
            let from = args.out.join(name);
            let bytes =
                std::fs::read(&from).with_context(|| format!("cannot read {}", from.display()))?;
            crate::files::write_atomic(&to, bytes)?;
            written.push(to);
        }
    }
    let mut text = format!("{md}\nWrote:\n");
    for p in written {
        let _ = writeln!(text, "  {}", p.display());
    }
    crate::emit(&text)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(threads: usize) -> ReproduceArgs {
        ReproduceArgs {
            runs: 2,
            seed: 3,
            map: "tan3x3".into(),
            strategies: vec![StrategyKind::Resetting, StrategyKind::Random],
            threads: Some(threads),
            out: PathBuf::from("unused"),
            check: false,
            bless: false,
        }
    }

    #[test]
    fn results_do_not_depend_on_the_thread_count() {
        let one = compute(&args(1)).unwrap();
        let two = compute(&args(2)).unwrap();
        assert_eq!(one.csv(), two.csv());
        assert_eq!(one.markdown(), two.markdown());
        // The table holds what the runs measured, seeds 3 and 4, in order.
        let seeds: Vec<u64> = one.runs[0].1.iter().map(|r| r.seed).collect();
        assert_eq!(seeds, [3, 4]);
        assert!(one.markdown().contains("resetting 2/2, random 2/2"));
        assert_eq!(one.csv().lines().count(), 1 + 9 * 2);
    }

    #[test]
    fn every_figure_renders_and_is_of_a_sane_size() {
        let a = ReproduceArgs {
            runs: 1,
            seed: 1,
            map: PAPERS_MAP.into(),
            strategies: vec![StrategyKind::Resetting, StrategyKind::Lazy],
            threads: Some(2),
            out: PathBuf::from("unused"),
            check: false,
            bless: false,
        };
        let res = compute(&a).unwrap();
        let dir = std::env::temp_dir().join(format!("csrl-figures-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let written = report::write_figures(&res, &dir).unwrap();
        let svgs: Vec<&PathBuf> = written
            .iter()
            .filter(|p| p.extension().is_some_and(|e| e == "svg"))
            .collect();
        // Curves, a policy and descriptions per strategy, the tree, Figure 5.
        assert_eq!(svgs.len(), 1 + 2 * 2 + 1 + 1, "{written:?}");
        for p in svgs {
            let text = std::fs::read_to_string(p).unwrap();
            let (w, h) = crate::render::check(&text, &p.display().to_string()).unwrap();
            assert!(w >= 200.0 && h >= 150.0, "{}: {w} by {h}", p.display());
            let png = crate::render::png(&text, 0.25, "figure").unwrap();
            assert!(png.starts_with(b"\x89PNG"));
        }
        // The DOT and the description table sit beside the pictures.
        assert!(
            written
                .iter()
                .any(|p| p.extension().is_some_and(|e| e == "dot"))
        );
        assert!(
            written
                .iter()
                .any(|p| p.extension().is_some_and(|e| e == "md"))
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn the_figure_check_refuses_bad_documents() {
        assert!(crate::render::check("<svg", "cut").is_err());
        let huge = r#"<svg xmlns="http://www.w3.org/2000/svg" width="4252" height="600"></svg>"#;
        let e = crate::render::check(huge, "huge").unwrap_err();
        assert!(e.to_string().contains("4252 by 600"), "{e}");
        let fine = r#"<svg xmlns="http://www.w3.org/2000/svg" width="400" height="300"><text x="10" y="20">ok</text></svg>"#;
        assert_eq!(crate::render::check(fine, "fine").unwrap(), (400.0, 300.0));
    }

    #[test]
    fn bless_needs_the_default_arguments_and_the_paper_is_shown_only_on_its_map() {
        let mut a = args(1);
        a.bless = true;
        let e = run(&a).unwrap_err();
        assert!(e.to_string().contains("--bless"), "{e}");
        // tan3x3 is not the paper's map: no paper row, no paper figures in the reading.
        let md = compute(&args(1)).unwrap().markdown();
        assert!(!md.contains(", paper |"));
        assert!(!md.contains("(the paper:"));
        assert!(md.contains("not the paper's map"));
    }

    #[test]
    fn bad_arguments_are_refused() {
        let mut a = args(1);
        a.runs = 0;
        assert!(compute(&a).is_err());
        let mut a = args(1);
        a.map = "no-such-map".into();
        assert!(compute(&a).is_err());
        // Once a panic: a strategy named twice.
        let mut a = args(1);
        a.strategies = vec![StrategyKind::Lazy, StrategyKind::Lazy];
        let err = compute(&a).err().unwrap().to_string();
        assert!(err.contains("twice"), "{err}");
        // Once wrapped around silently: seeds beyond the integer limit.
        let mut a = args(1);
        (a.seed, a.runs) = (u64::MAX, 2);
        let err = compute(&a).err().unwrap().to_string();
        assert!(err.contains("--seed"), "{err}");
        let mut a = args(1);
        a.threads = Some(1_000_000);
        assert!(compute(&a).is_err());
    }

    #[test]
    fn a_map_name_with_path_separators_stays_inside_out() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("evil.toml");
        std::fs::write(&file, "name = \"../../escaped\"\nlayout = '''\n..G\n'''\n").unwrap();
        let mut a = args(1);
        a.map = file.display().to_string();
        a.runs = 1;
        a.strategies = vec![StrategyKind::Eager];
        let res = compute(&a).unwrap();
        let out = dir.path().join("out").join("deeper");
        std::fs::create_dir_all(&out).unwrap();
        let written = report::write_figures(&res, &out).unwrap();
        for p in &written {
            assert!(
                p.starts_with(&out) && p.parent() == Some(out.as_path()),
                "{}",
                p.display()
            );
        }
        assert!(!dir.path().join("escaped_eager.svg").exists());
    }

    #[test]
    fn figure_5_of_tan3x3_is_written_only_for_the_default_map_or_tan3x3() {
        // Once: `--map my.toml` also wrote figure5_tan3x3.svg and tree_tan3x3.dot.
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("my.toml");
        std::fs::write(&file, "name = \"mine\"\nlayout = '''\n...\n..G\n'''\n").unwrap();
        let names = |map: &str| -> Vec<String> {
            let mut a = args(1);
            (a.map, a.runs, a.strategies) = (map.to_string(), 1, vec![StrategyKind::Lazy]);
            let out = dir.path().join(crate::files::safe_name(map));
            std::fs::create_dir_all(&out).unwrap();
            let written = report::write_figures(&compute(&a).unwrap(), &out).unwrap();
            written
                .iter()
                .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
                .collect()
        };
        let mine = names(&file.display().to_string());
        assert!(!mine.iter().any(|n| n.contains("tan3x3")), "{mine:?}");
        assert!(mine.contains(&"tree_mine_lazy.dot".to_string()), "{mine:?}");
        let small = names("tan3x3");
        assert!(
            small.contains(&"figure5_tan3x3.svg".to_string()),
            "{small:?}"
        );
        assert!(small.contains(&"tree_tan3x3.dot".to_string()), "{small:?}");
    }
}
