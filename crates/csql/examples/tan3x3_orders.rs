//! Can the 3 by 3 world give the paper's 7 descriptions (Figure 5)?
//!
//! Runs every strategy on every placement of the goal in the 3 by 3 world with no
//! obstacles, over several seeds, and counts the descriptions at convergence.
//!
//! Tie orders of the features need no separate loop: the 8 symmetries of the square
//! (rotations and reflections) preserve the Manhattan cost, so sensing a world with the
//! features of equal cost taken clockwise or counter-clockwise from any side is the same
//! as sensing a rotated or reflected world with the fixed order (clockwise from up).
//! A rotated or reflected empty 3 by 3 world is the same world with the goal moved, so
//! the 9 goal placements under the fixed order cover every (goal, tie order) pair. Only
//! the labels of the actions differ, which changes which random draws pick which move, so
//! the seeds are varied too.
//!
//! ```text
//! cargo run --release -p csql --example tan3x3_orders [SEEDS]
//! ```

use std::collections::BTreeMap;

use csql::{RunSettings, Setup, StrategyKind};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let seeds: u64 = match std::env::args().nth(1) {
        Some(s) => s.parse()?,
        None => 10,
    };
    println!("goal (row, col) | strategy | descriptions at convergence over seeds 1..={seeds}");
    let mut overall: BTreeMap<usize, usize> = BTreeMap::new();
    for row in 0..3 {
        for col in 0..3 {
            let mut layout = [['.'; 3]; 3];
            layout[row][col] = 'G';
            let text: Vec<String> = layout.iter().map(|r| r.iter().collect()).collect();
            let map = mdp::Map::from_layout("tan3x3-goal", &text.join("\n"))?;
            for strategy in StrategyKind::ALL {
                let mut counts: BTreeMap<usize, usize> = BTreeMap::new();
                for seed in 1..=seeds {
                    let settings = RunSettings::tan1991("tan3x3-goal", strategy, seed);
                    let setup = Setup::for_map(map.clone(), &settings)?;
                    let report = csql::run_on(&setup, &settings).unwrap();
                    let n = report.table1.descriptions.ok_or("a run did not converge")?;
                    *counts.entry(n).or_default() += 1;
                    *overall.entry(n).or_default() += 1;
                }
                let shown: Vec<String> = counts
                    .iter()
                    .map(|(n, times)| format!("{n} descriptions x{times}"))
                    .collect();
                println!("({row}, {col}) | {strategy} | {}", shown.join(", "));
            }
        }
    }
    let shown: Vec<String> = overall
        .iter()
        .map(|(n, times)| format!("{n}: {times} runs"))
        .collect();
    println!("all placements, strategies and seeds: {}", shown.join(", "));
    Ok(())
}
