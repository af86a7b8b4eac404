//! Table 1 on one map: the mean of each measure over seeds 1 to N, per strategy.
//!
//! `cargo run --release -p csql --example table1 -- [MAP] [RUNS]` (default: tan8x8, 5)

use csql::{RunSettings, Setup, StrategyKind};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let map = args.next().unwrap_or_else(|| "tan8x8".to_string());
    let runs: u64 = args.next().map_or(Ok(5), |s| s.parse())?;
    println!(
        "| strategy | converged | 1 cost to sufficient | 2 trials | 3 cost to converge | 4 trials | 5 descriptions | 6 mean features | 7 max features | 8 tree cost/state | 8' description cost/state |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for k in StrategyKind::ALL {
        let mut sums = [0.0f64; 9];
        let mut converged = 0;
        for seed in 1..=runs {
            let settings = RunSettings::tan1991(&map, k, seed);
            let r = csql::run_on(&Setup::new(&settings)?, &settings);
            let t = &r.table1;
            if !r.converged {
                continue;
            }
            converged += 1;
            let row = [
                t.cost_to_sufficient.unwrap_or(f64::NAN),
                t.trials_to_sufficient.map_or(f64::NAN, f64::from),
                t.cost_to_converge.unwrap_or(f64::NAN),
                t.trials_to_converge.map_or(f64::NAN, f64::from),
                t.descriptions.map_or(f64::NAN, |x| x as f64),
                t.mean_features.unwrap_or(f64::NAN),
                t.max_features.map_or(f64::NAN, |x| x as f64),
                t.tree_cost_per_state.unwrap_or(f64::NAN),
                t.description_cost_per_state.unwrap_or(f64::NAN),
            ];
            for (s, x) in sums.iter_mut().zip(row) {
                *s += x;
            }
        }
        let n = f64::from(converged.max(1));
        println!(
            "| {k} | {converged}/{runs} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.2} | {:.1} | {:.2} | {:.2} |",
            sums[0] / n,
            sums[1] / n,
            sums[2] / n,
            sums[3] / n,
            sums[4] / n,
            sums[5] / n,
            sums[6] / n,
            sums[7] / n,
            sums[8] / n
        );
    }
    Ok(())
}
