//! ACT's and CVT's time per tree against EG2's, in one process, on the data sets of the
//! test-cost benchmark; and, with `--check`, every pinned tree of
//! `tests/pins/lookahead.txt` grown again and compared (the cases too slow for the
//! unoptimised `cargo test` included).
//!
//! Each data set grows one tree per learner: the training part of fold 0 of a 10-fold
//! split (seed 1), random prices uniform in [1, 100] (seed 1), mc 500, listed selection
//! prices (the benchmark's), seed 1. The times are wall times of this single-threaded
//! process; read the ratios, which compare runs of the same moment, not the milliseconds.
//!
//! ```text
//! cargo run --release -p cslearn --example lookahead_speed [-- DATASET,...|all [LEARNER,...]]
//! cargo run --release -p cslearn --example lookahead_speed -- --check
//! ```
//!
//! LEARNER is any of the family's names (default `eg2,act,cvt`); the columns give each
//! learner's time over EG2's and over ACT's, where those ran before it.

#[path = "../tests/support/lookahead.rs"]
#[allow(dead_code)] // the pin test's parts this example does not use
mod lookahead;

use cslearn::testcost::{Method, SelectionPrices};
use lookahead::{Case, catalogue, fingerprint, pins};

fn check() -> Result<(), Box<dyn std::error::Error>> {
    let catalogue = catalogue();
    let mut failed = 0;
    for (case, print) in pins() {
        let loaded = catalogue.load(&case.dataset)?;
        let (tree, ms) = case.grow(&loaded);
        let got = fingerprint(&tree);
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

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--check") {
        return check();
    }
    let catalogue = catalogue();
    let names: Vec<String> = match args.first() {
        Some(list) if list != "all" => list.split(',').map(String::from).collect(),
        _ => catalogue.sources().iter().map(|s| s.name.clone()).collect(),
    };
    let learners: Vec<Method> = match args.get(1) {
        Some(list) => list
            .split(',')
            .map(Method::parse)
            .collect::<Result<_, _>>()?,
        None => vec![Method::Eg2, Method::Act, Method::Cvt],
    };
    println!("dataset        learner   ms/tree  nodes   x EG2   x ACT  fingerprint");
    for name in &names {
        let loaded = catalogue.load(name)?;
        let (mut eg2, mut act) = (None, None);
        for &learner in &learners {
            let case = Case {
                dataset: name.clone(),
                learner,
                prices: "random".into(),
                selection: SelectionPrices::Listed,
                mc: 500.0,
                objects: 0,
            };
            let (tree, ms) = case.grow(&loaded);
            let ratio = |base: Option<f64>| base.map_or("-".into(), |b| format!("{:.1}", ms / b));
            println!(
                "{name:<14} {:<7} {ms:>9.2} {:>6} {:>7} {:>7}  {}",
                learner.name(),
                tree.len(),
                ratio(eg2),
                ratio(act),
                fingerprint(&tree)
            );
            match learner {
                Method::Eg2 => eg2 = Some(ms),
                Method::Act => act = Some(ms),
                _ => {}
            }
        }
    }
    Ok(())
}
