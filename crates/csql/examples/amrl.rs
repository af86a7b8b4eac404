//! AMRL-Q on the active-measurement benchmark: FrozenLake 4x4 and 8x8, deterministic,
//! semi-slippery (`slide = 0.5`) and slippery (`slip = 2/3`), the whole state measured at
//! 0.05 (0.025 per coordinate) and at 0.1 (0.05 per coordinate), under both sensing rules
//! (specification 6.10). Five seeded runs of 1000 episodes (4x4) or 2000 (8x8), at most
//! 100 (4x4) or 200 (8x8) moves each, as Gymnasium caps FrozenLake's episodes.
//!
//! ```text
//! cargo run --release -p csql --example amrl [-- --runs 5 --seed 1]
//! ```

use csql::{AmrlParams, CostlySummary, Episode, SensingRule, amrl_q};
use mdp::{SensingModel, WorldOptions};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

fn arg(name: &str, default: u64) -> u64 {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .map(|v| {
            v.parse()
                .unwrap_or_else(|_| panic!("{name} takes a whole number"))
        })
        .unwrap_or(default)
}

fn main() -> Result<(), mdp::WorldError> {
    let (runs, seed) = (arg("--runs", 5), arg("--seed", 1));
    println!(
        "| world | dynamics | price per coordinate | rule | mean all | mean last 10% | measurements / episode | steps / episode | success |"
    );
    println!("|---|---|---:|---|---:|---:|---:|---:|---:|");
    for (world, episodes, max_moves) in [("frozenlake4x4", 1000, 100), ("frozenlake8x8", 2000, 200)]
    {
        for (dynamics, slip, slide) in [
            ("deterministic", 0.0, 0.0),
            ("semi-slippery", 0.0, 0.5),
            ("slippery", 2.0 / 3.0, 0.0),
        ] {
            let options = WorldOptions {
                slip,
                slide,
                sensing: Some(SensingModel::Factors),
                factor_costs: None,
            };
            let lake = mdp::builtin_world(world, &options)?;
            for coordinate in [0.025, 0.05] {
                // AMRL-Q measures the whole state: both coordinates at once.
                let price = 2.0 * coordinate;
                for rule in [SensingRule::WithTheMove, SensingRule::AfterTheOutcome] {
                    let mut all: Vec<Episode> = Vec::new();
                    let mut means = Vec::new();
                    for run in 0..runs {
                        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed + run);
                        let episodes = amrl_q(
                            &lake,
                            &AmrlParams::default(),
                            price,
                            rule,
                            episodes,
                            max_moves,
                            &mut rng,
                        );
                        means.push(CostlySummary::of(&episodes));
                        all.extend(episodes);
                    }
                    // The mean of the runs' means (every run has as many episodes).
                    let avg = |f: &dyn Fn(&CostlySummary) -> f64| {
                        means.iter().map(f).sum::<f64>() / means.len() as f64
                    };
                    println!(
                        "| {world} | {dynamics} | {coordinate} | {} | {:.3} | {:.3} | {:.2} | {:.2} | {:.3} |",
                        match rule {
                            SensingRule::WithTheMove => "with the move",
                            SensingRule::AfterTheOutcome => "after the outcome",
                        },
                        avg(&|s| s.mean_all),
                        avg(&|s| s.mean_last10),
                        avg(&|s| s.sensing_per_episode),
                        avg(&|s| s.steps_per_episode),
                        CostlySummary::of(&all).success,
                    );
                }
            }
        }
    }
    Ok(())
}
