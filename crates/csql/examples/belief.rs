//! Sensing by belief on the costly-sensing benchmark's lakes: the mean costed return over
//! all episodes and over the last 10%, measurements and moves per episode, success.
//!
//! ```text
//! cargo run --release -p csql --example belief [-- RUNS [K [FILTER]]]
//! ```
//!
//! RUNS (3) runs of each lake, K (7) the bound on uncertain steps, FILTER a part of
//! "WORLD DYNAMICS" to keep (e.g. `8x8 semi`); the variables `TRUST`, `PRIOR`, `MAXB` and `OPT`
//! set `trust`, `prior` and `max_beliefs` (4, 3, 5000), `OPT` the optimism (1), `BLIND`
//! `blind_plans` (0), `SHARED` `shared_moves` (0). With `RUNS_SHOWN` set, each run's line is printed too (seed, mean
//! over all episodes, over the last 10%).

use rand::SeedableRng;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let runs: u64 = args.next().map_or(Ok(3), |a| a.parse())?;
    let k: u32 = args.next().map_or(Ok(7), |a| a.parse())?;
    let filter = args.next().unwrap_or_default();
    let env = |k: &str, d: f64| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let params = csql::BeliefParams {
        max_uncertain: k,
        trust: env("TRUST", 4.0) as u32,
        prior: env("PRIOR", 3.0),
        max_beliefs: env("MAXB", 5000.0) as usize,
        optimism: env("OPT", 1.0),
        blind_plans: Some(env("BLIND", 0.0) as usize),
        shared_moves: Some(env("SHARED", 0.0) as u32),
        ..Default::default()
    };
    for (world, episodes, horizon) in [("frozenlake4x4", 1000, 100), ("frozenlake8x8", 2000, 200)] {
        for (name, slip, slide) in [
            ("deterministic", 0.0, 0.0),
            ("semi-slippery", 0.0, 0.5),
            ("slippery", 2.0 / 3.0, 0.0),
        ] {
            if !format!("{world} {name}").contains(&filter) {
                continue;
            }
            for rule in [mdp::SensingRule::WithMove, mdp::SensingRule::AfterOutcome] {
                let lake = mdp::builtin_world(
                    world,
                    &mdp::WorldOptions {
                        slip: Some(slip),
                        slide: Some(slide),
                        sensing: Some(mdp::SensingModel::Factors),
                        factor_costs: Some(vec![0.025, 0.025]),
                    },
                )?;
                let t = std::time::Instant::now();
                let mut sums = [0.0; 5];
                for seed in 0..runs {
                    let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed);
                    let run = csql::belief_planning(
                        &lake, &params, 1.0, rule, episodes, horizon, &mut rng,
                    )?;
                    let s = csql::CostlySummary::of(&run);
                    if std::env::var("RUNS_SHOWN").is_ok() {
                        println!(
                            "run {world} {name} {} {seed} {} {} {}",
                            rule.name(),
                            s.mean_all,
                            s.mean_last10,
                            s.sensing_per_episode
                        );
                    }
                    for (x, v) in sums.iter_mut().zip([
                        s.mean_all,
                        s.mean_last10,
                        s.sensing_per_episode,
                        s.steps_per_episode,
                        s.success,
                    ]) {
                        *x += v / runs as f64;
                    }
                }
                println!(
                    "{world} {name} {}: {:.3} / {:.3}, {:.2} measurements, {:.2} moves, success {:.3} ({:.1} s)",
                    rule.name(),
                    sums[0],
                    sums[1],
                    sums[2],
                    sums[3],
                    sums[4],
                    t.elapsed().as_secs_f64()
                );
            }
        }
    }
    Ok(())
}
