//! Value stability: for fixed seeds, the first draws of every sampling routine are
//! pinned, so that a change in a dependency (rand, rand_xoshiro) or in the draw order
//! cannot change results unnoticed. If one of these fails after an upgrade, results of
//! earlier runs are no longer reproducible: say so in the changelog and update the pins.

#[path = "../benches/support/reference.rs"]
mod reference;

use mdp::{ActionId, GridWorld, Pos};
use qlearn::{
    Discount, Epsilon, LearningRate, Params, QLearner, QTable, RowId, Start, Target, Temperature,
};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// A row with Q = [0, 0.5, 0.2, 0.5].
fn sample_table() -> QTable {
    let mut t = QTable::with_rows(4, 1).unwrap();
    let (beta, gamma) = (LearningRate::new(1.0).unwrap(), Discount::new(0.9).unwrap());
    t.update(RowId(0), ActionId(1), 0.5, Target::Terminal, beta, gamma);
    t.update(RowId(0), ActionId(2), 0.2, Target::Terminal, beta, gamma);
    t.update(RowId(0), ActionId(3), 0.5, Target::Terminal, beta, gamma);
    t
}

fn ids(v: &[ActionId]) -> Vec<u32> {
    v.iter().map(|a| a.0).collect()
}

#[test]
fn boltzmann_draws_are_pinned() {
    let mut table = sample_table();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(42);
    let t = Temperature::new(0.4).unwrap();
    let drawn: Vec<ActionId> = (0..16)
        .map(|_| table.boltzmann(RowId(0), t, &mut rng))
        .collect();
    assert_eq!(ids(&drawn), PINNED_BOLTZMANN);
}
const PINNED_BOLTZMANN: [u32; 16] = [3, 1, 3, 3, 3, 2, 1, 2, 1, 3, 2, 3, 3, 0, 1, 2];

#[test]
fn epsilon_greedy_draws_are_pinned() {
    let table = sample_table();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(42);
    let e = Epsilon::new(0.5).unwrap();
    let drawn: Vec<ActionId> = (0..16)
        .map(|_| table.epsilon_greedy(RowId(0), e, &mut rng))
        .collect();
    assert_eq!(ids(&drawn), PINNED_EPSILON);
}
const PINNED_EPSILON: [u32; 16] = [1, 3, 1, 1, 1, 2, 3, 1, 1, 1, 1, 1, 0, 1, 0, 1];

#[test]
fn uniform_starts_and_trial_lengths_are_pinned() {
    let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    let mut learner = QLearner::new(&world, Params::tan1991(), Start::Uniform).unwrap();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(42);
    let trials: Vec<(u32, u32)> = (0..8)
        .map(|_| {
            let t = learner.trial(&mut rng);
            (t.start.0, t.moves)
        })
        .collect();
    assert_eq!(trials, PINNED_TRIALS);
}
const PINNED_TRIALS: [(u32, u32); 8] = [
    (7, 30),
    (6, 11),
    (5, 1),
    (4, 17),
    (8, 6),
    (0, 2),
    (1, 5),
    (3, 20),
];

/// The throughput task of the example: the whole chain (start, selection, update) over
/// many moves, pinned through the sum of Q.
#[test]
fn the_throughput_task_is_pinned_and_matches_the_hand_written_loop() {
    let world = GridWorld::new(&mdp::builtin("open8x8").unwrap());
    let start = world.state_at(Pos::new(0, 0)).unwrap();
    for (seed, steps) in [(1991, 100_000), (7, 12_345)] {
        let mut learner = QLearner::new(&world, Params::tan1991(), Start::Fixed(start)).unwrap();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        learner.run_steps(steps, &mut rng);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let hand = reference::run(steps, &mut rng);
        // Bit for bit: same draws, same arithmetic, same trial boundaries.
        assert_eq!(learner.table().q_values(), &hand[..], "seed {seed}");
    }
    let mut learner = QLearner::new(&world, Params::tan1991(), Start::Fixed(start)).unwrap();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1991);
    learner.run_steps(10_000, &mut rng);
    let sum: f64 = learner.table().q_values().iter().sum();
    assert_eq!(format!("{sum:.6}"), PINNED_SUM_Q);
}
const PINNED_SUM_Q: &str = "122.737661";
