//! The best policy quality any CS-QL agent can reach under sensor noise with a given
//! representation: the representation a noiseless run converged to, each description
//! acting optimally (an optimal action of the states it describes), read through noisy
//! sensors. Every step's classification reads its features afresh, so a misread sends
//! the agent to another description's action; this is the ceiling of learning under
//! that noise with representations of that kind.
//!
//! For each noise level and number of reads per feature (the majority kept, as the
//! setting `extensions.reads`): the quality (exact evaluation of the noisy policy, whose
//! action probabilities come from 2000 seeded classifications per state) with exact and
//! with nearest matching, and the share of classifications that return the state's own
//! description.
//!
//! `cargo run --release -p csql --example noise_ceiling -- tan8x8 1 5`

use csql::{Classify, Matching, RunSettings, Setup, StrategyKind};
use mdp::{ActionId, Mdp, SensorNoise, SlipperyGrid};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let map = args.get(1).map_or("tan8x8", String::as_str);
    let first: u64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(1);
    let seeds: u64 = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(5);
    println!(
        "| noise | reads | matching | quality (mean over {seeds} representations) | own description read |"
    );
    println!("|---|---|---|---|---|");
    let mut reps = Vec::new();
    for seed in first..first + seeds {
        let settings = RunSettings::tan1991(map, StrategyKind::Lazy, seed);
        let setup = Setup::new(&settings)?;
        let (report, rep) = csql::run_with_representation(&setup, &settings).unwrap();
        assert!(report.converged, "seed {seed} did not converge");
        reps.push((setup, rep));
    }
    for noise in [0.01, 0.05, 0.1] {
        for reads in [1, 3, 5] {
            for matching in [Matching::Exact, Matching::Nearest] {
                let (mut quality, mut own) = (0.0, 0.0);
                for (k, (setup, rep)) in reps.iter().enumerate() {
                    let (q, o) = ceiling(setup, rep, noise, reads, matching, k as u64)?;
                    quality += q;
                    own += o;
                }
                let n = reps.len() as f64;
                println!(
                    "| {noise} | {reads} | {matching:?} | {:.3} | {:.3} |",
                    quality / n,
                    own / n
                );
            }
        }
    }
    Ok(())
}

/// The quality of the representation's optimal policy read through noisy sensors, and
/// the share of classifications that give each state its own description.
fn ceiling(
    setup: &Setup,
    rep: &csql::Representation,
    noise: f64,
    reads: u32,
    matching: Matching,
    seed: u64,
) -> Result<(f64, f64), Box<dyn std::error::Error>> {
    let world = &setup.world;
    let sensed = &mdp::SensedGrid::new(world, &setup.space, mdp::Slip::default());
    let noise = SensorNoise::new(noise)?;
    let mut classify = Classify::with_representation(sensed, rep.clone())
        .with_matching(matching)
        .with_reads(reads);
    let states = world.states();
    // Each description acts as an optimal action of the states it describes.
    let mut action = vec![ActionId(0); rep.len()];
    for &s in &states {
        if let Some(d) = classify.lookup(sensed, s) {
            action[d.index()] = setup.oracle.optimal_actions(s)[0];
        }
    }
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let samples = 2000;
    let mut policy = vec![vec![0.0; 4]; world.num_states()];
    policy[world.goal().index()][0] = 1.0;
    let mut own = 0.0;
    for &s in &states {
        let truth = classify.lookup(sensed, s);
        for _ in 0..samples {
            let seen = classify.lookup_noisy(sensed, s, noise, &mut rng);
            own += f64::from(u8::from(seen == truth));
            let a = seen.map_or(ActionId(0), |d| action[d.index()]);
            policy[s.index()][a.index()] += 1.0 / f64::from(samples);
        }
    }
    let model = SlipperyGrid::new(world, mdp::Slip::default());
    let v = mdp::evaluate_stochastic_policy(&model, setup.oracle.gamma(), &policy)?;
    let quality = states
        .iter()
        .map(|&s| v[s.index()] / setup.oracle.v_star(s))
        .sum::<f64>()
        / states.len() as f64;
    Ok((quality, own / (states.len() * samples as usize) as f64))
}
