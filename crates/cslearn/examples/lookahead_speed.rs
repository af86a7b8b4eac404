//! ACT's and CVT's time per tree against EG2's, in one process, on the data sets of the
//! test-cost benchmark; and, with `--check`, every pinned tree of
//! `tests/pins/lookahead.txt` grown again and compared (the cases too slow for the
//! unoptimised `cargo test` included; ACT's on one thread and on two).
//!
//! Each data set grows one tree per learner: the training part of fold 0 of a 10-fold
//! split (seed 1), random prices uniform in [1, 100] (seed 1), mc 500, listed selection
//! prices (the benchmark's), seed 1. The times are wall times of this single-threaded
//! process; read the ratios, which compare runs of the same moment, not the milliseconds.
//!
//! ```text
//! cargo run --release -p cslearn --example lookahead_speed [-- DATASET,...|all [LEARNER,...]]
//! cargo run --release -p cslearn --example lookahead_speed -- --check
//! cargo run --release -p cslearn --example lookahead_speed -- --each [DATASET,...|all [LEARNER,...]]
//! ```
//!
//! `--file CSV TARGET [LEARNER,...]` grows one tree per learner on every object of a CSV
//! file, every test priced 1, mc 100, ACT and CVT on one thread and on two, VOI looking
//! one, two and three tests ahead (the Spambase measurements of `docs/testcost.md`: `--
//! --file data/uci/spambase/spambase.csv Outcome`, and `... Outcome eg2,voi`), and prints
//! each tree's fingerprint, to compare two builds tree for tree.
//!
//! `--each` grows each learner's trees at the benchmark's four costs (mc 100, 500, 1000
//! and 5000) one by one with `fit`, then all at once with `fit_each`, checks that they are
//! the same trees, and prints both times, and (where EG2 ran first) the time per tree of
//! all at once over EG2's, the benchmark's measure: a learner whose tree depends on the
//! costs grows four trees, EG2 one tree that serves the four.
//!
//! LEARNER is any of the family's names (default `eg2,act,cvt`); the columns give each
//! learner's time over EG2's and over ACT's, where those ran before it.
//!
//! Built with `--features work-counts` (`cargo run --release -p cslearn --features
//! work-counts --example lookahead_speed -- ...`), every mode but `--check` also gives the
//! work of each tree apart from the machine: the objects of the nodes whose split
//! statistics were computed (each read once per feature), and that over EG2's. Time over
//! EG2's may sit below work over EG2's: a greedy tree's time also holds what the count
//! leaves out (the root's sorted orders, the pruning), and a small node costs less per
//! object than the root. `--each` also gives the nodes split per node scored.

#[path = "../tests/support/lookahead.rs"]
#[expect(dead_code, reason = "the pin test's parts this example does not use")]
mod lookahead;

use std::time::Instant;

use cslearn::testcost::{
    FamilyParams, Frame, FrameSpec, Method, MisclassCosts, SelectionPrices, TestPrices, VoiParams,
    fit, fit_each, folds, random_prices,
};
use lookahead::{Case, catalogue, fingerprint, pins};

/// mimalloc, as the benchmark (`cargo xtask testcost`) runs with: split tries allocate
/// and free many small vectors.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The work this process has counted so far: the nodes whose split statistics were
/// computed, their objects, and the nodes split, where the build counts them
/// (`--features work-counts`).
#[cfg(feature = "work-counts")]
fn counted() -> Option<(u64, u64, u64)> {
    let work = cslearn::testcost::Work::now();
    Some((work.nodes, work.objects, work.splits))
}

/// Nothing: the build does not count (`--features work-counts` does).
#[cfg(not(feature = "work-counts"))]
fn counted() -> Option<(u64, u64, u64)> {
    None
}

/// The work counted since the reading `before`.
fn since(before: Option<(u64, u64, u64)>) -> Option<(u64, u64, u64)> {
    let ((n0, o0, s0), (n1, o1, s1)) = before.zip(counted())?;
    Some((n1 - n0, o1 - o0, s1 - s0))
}

/// `value / base` to one decimal, or `-` where either is unknown.
fn over(value: Option<f64>, base: Option<f64>) -> String {
    value
        .zip(base)
        .map_or("-".into(), |(v, b)| format!("{:.1}", v / b))
}

fn check() -> Result<(), Box<dyn std::error::Error>> {
    let catalogue = catalogue();
    let mut failed = 0;
    for (case, print) in pins() {
        let loaded = catalogue.load(&case.dataset)?;
        let start = Instant::now();
        let tree = case.grow(&loaded);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let mut got = fingerprint(&tree);
        // ACT's also on two threads: the same tree.
        if case.learner == Method::Act {
            let threaded = fingerprint(&case.grow_on(&loaded, 2));
            if threaded != got {
                got = format!("{got}, on two threads {threaded}");
            }
        }
        let verdict = if got == print { "same" } else { "CHANGED" };
        failed += usize::from(got != print);
        println!("{:<52} {ms:>10.1} ms  {verdict}", case.key());
    }
    if failed > 0 {
        return Err(format!("{failed} pinned trees changed").into());
    }
    println!("every pinned tree grown again, the same");
    Ok(())
}

/// `--each`: one by one against all at once, on fold 0's training part (listed selection
/// prices, random prices of seed 1, seed 1).
fn each(names: &[String], learners: &[Method]) -> Result<(), Box<dyn std::error::Error>> {
    let catalogue = catalogue();
    println!(
        "dataset        learner   one by one ms   all at once ms   ratio   x EG2   scored/tree  work x EG2   splits"
    );
    for name in names {
        let loaded = catalogue.load(name)?;
        let frame = &loaded.frame;
        let prices = random_prices(frame.feature_count(), 1.0, 100.0, 1);
        let mcs: Vec<MisclassCosts> = [100.0, 500.0, 1000.0, 5000.0]
            .into_iter()
            .map(|m| MisclassCosts::uniform(frame.class_count(), m))
            .collect::<Result<_, _>>()?;
        let test = &folds(frame, 10, 1)[0];
        let train: Vec<usize> = (0..frame.len())
            .filter(|r| test.binary_search(r).is_err())
            .collect();
        let params = FamilyParams {
            selection_prices: SelectionPrices::Listed,
            ..FamilyParams::default()
        };
        // EG2's time and work per tree, where it ran first.
        let mut eg2: Option<(f64, Option<f64>)> = None;
        for &learner in learners {
            let start = Instant::now();
            let alone: Vec<_> = mcs
                .iter()
                .map(|mc| fit(learner, frame, &train, &prices, mc, &params, 1))
                .collect();
            let one_by_one = start.elapsed().as_secs_f64() * 1e3;
            let before = counted();
            let start = Instant::now();
            let together = fit_each(learner, frame, &train, &prices, &mcs, &params, 1);
            let at_once = start.elapsed().as_secs_f64() * 1e3;
            let done = since(before);
            let work = done.map(|(_, objects, _)| objects as f64);
            // Nodes split per node scored.
            let splits = done
                .map(|(nodes, _, splits)| format!("{:.2}", splits as f64 / nodes.max(1) as f64));
            // Per tree, as the benchmark's `timing.csv` counts them.
            let trees = if learner.depends_on_mc() {
                mcs.len()
            } else {
                1
            } as f64;
            let (per_tree, work) = (at_once / trees, work.map(|w| w / trees));
            if alone != together {
                return Err(format!("{name} {}: fit_each grew other trees", learner.name()).into());
            }
            println!(
                "{name:<14} {:<7} {one_by_one:>15.1} {at_once:>16.1} {:>7.2} {:>7} {:>13} {:>11} {:>8}",
                learner.name(),
                at_once / one_by_one,
                over(Some(per_tree), eg2.map(|(t, _)| t)),
                work.map_or("-".into(), |w| format!("{w:.0}")),
                over(work, eg2.and_then(|(_, w)| w)),
                splits.unwrap_or_else(|| "-".into()),
            );
            if learner == Method::Eg2 {
                eg2 = Some((per_tree, work));
            }
        }
    }
    Ok(())
}

/// `--file`: one tree per learner on every object of a CSV file, every price 1, mc 100.
fn file(path: &str, target: &str, learners: &[Method]) -> Result<(), Box<dyn std::error::Error>> {
    let frame = Frame::read_csv(std::path::Path::new(path), &FrameSpec::new(target), None)?;
    let prices = TestPrices::flat(&vec![1.0; frame.feature_count()])?;
    let mc = MisclassCosts::uniform(frame.class_count(), 100.0)?;
    let rows: Vec<usize> = (0..frame.len()).collect();
    let params = FamilyParams::default();
    println!(
        "{path}: {} objects, {} tests priced 1, mc 100",
        frame.len(),
        frame.feature_count()
    );
    println!("learner  threads        ms  nodes   x EG2     scored  work x EG2  fingerprint");
    // One untimed tree first, as in the table of data sets.
    fit(Method::Eg2, &frame, &rows, &prices, &mc, &params, 1);
    let mut eg2 = None;
    for &learner in learners {
        // ACT and CVT on one thread and on two: the same tree. VOI looking one, two and
        // three tests ahead: its work grows as the features to that power.
        let settings: Vec<(usize, Option<usize>)> = match learner {
            Method::Act | Method::Cvt => vec![(1, None), (2, None)],
            Method::Voi => (1..=3).map(|d| (1, Some(d))).collect(),
            _ => vec![(1, None)],
        };
        let mut trees = Vec::new();
        for &(t, lookahead) in &settings {
            let params = FamilyParams {
                act: params.act.with_threads(t),
                cvt: params.cvt.with_threads(t),
                voi: VoiParams {
                    lookahead: lookahead.or(params.voi.lookahead),
                    ..params.voi
                },
                ..params
            };
            let before = counted();
            let start = Instant::now();
            let tree = fit(learner, &frame, &rows, &prices, &mc, &params, 1).tree;
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let work = since(before).map(|(_, objects, _)| objects as f64);
            let name = match lookahead {
                Some(d) => format!("{}-{d}", learner.name()),
                None => learner.name().to_string(),
            };
            println!(
                "{name:<7} {t:>8} {ms:>9.1} {:>6} {:>7} {:>10} {:>11}  {}",
                tree.len(),
                over(Some(ms), eg2.map(|(b, _)| b)),
                work.map_or("-".into(), |w| w.to_string()),
                over(work, eg2.and_then(|(_, w)| w)),
                fingerprint(&tree),
            );
            if lookahead.is_some() {
                // Each lookahead grows a tree of its own.
                continue;
            }
            if learner == Method::Eg2 {
                eg2 = Some((ms, work));
            }
            trees.push(tree);
        }
        if trees.windows(2).any(|w| w[0] != w[1]) {
            return Err(format!("{}: another tree on more threads", learner.name()).into());
        }
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--check") {
        return check();
    }
    if args.first().map(String::as_str) == Some("--file") {
        let (Some(path), Some(target)) = (args.get(1), args.get(2)) else {
            return Err("--file needs a CSV file and its class column".into());
        };
        let learners: Vec<Method> = match args.get(3) {
            Some(list) => list
                .split(',')
                .map(Method::parse)
                .collect::<Result<_, _>>()?,
            None => vec![Method::Eg2, Method::Act, Method::Cvt],
        };
        return file(path, target, &learners);
    }
    let sweep = args.first().map(String::as_str) == Some("--each");
    if sweep {
        args.remove(0);
    }
    let catalogue = catalogue();
    let names: Vec<String> = match args.first() {
        Some(list) if list != "all" => list.split(',').map(String::from).collect(),
        _ => catalogue.benchmark().map(|s| s.name.clone()).collect(),
    };
    let learners: Vec<Method> = match args.get(1) {
        Some(list) => list
            .split(',')
            .map(Method::parse)
            .collect::<Result<_, _>>()?,
        None if sweep => vec![Method::Act, Method::Cvt],
        None => vec![Method::Eg2, Method::Act, Method::Cvt],
    };
    if sweep {
        return each(&names, &learners);
    }
    println!(
        "dataset        learner   ms/tree  nodes   x EG2   x ACT     scored  work x EG2  fingerprint"
    );
    for name in &names {
        let loaded = catalogue.load(name)?;
        let (mut eg2, mut act, mut eg2_work) = (None, None, None);
        // One untimed tree first: the process's first allocations and page faults would
        // otherwise be charged to the first learner timed.
        let warm_up = Case {
            dataset: name.clone(),
            learner: Method::Eg2,
            prices: "random".into(),
            selection: SelectionPrices::Listed,
            mc: 500.0,
            objects: 0,
        };
        warm_up.grow(&loaded);
        for &learner in &learners {
            let case = Case {
                dataset: name.clone(),
                learner,
                prices: "random".into(),
                selection: SelectionPrices::Listed,
                mc: 500.0,
                objects: 0,
            };
            let before = counted();
            let start = Instant::now();
            let tree = case.grow(&loaded);
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let work = since(before).map(|(_, objects, _)| objects as f64);
            println!(
                "{name:<14} {:<7} {ms:>9.2} {:>6} {:>7} {:>7} {:>10} {:>11}  {}",
                learner.name(),
                tree.len(),
                over(Some(ms), eg2),
                over(Some(ms), act),
                work.map_or("-".into(), |w| w.to_string()),
                over(work, eg2_work),
                fingerprint(&tree)
            );
            match learner {
                Method::Eg2 => (eg2, eg2_work) = (Some(ms), work),
                Method::Act => act = Some(ms),
                _ => {}
            }
        }
    }
    Ok(())
}
