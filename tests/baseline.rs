//! CS-QL's main loop with every state identified is plain Q-learning: with the same seed
//! it makes exactly the moves and reaches exactly the table of `qlearn::QLearner`, so the
//! paper's baseline and its CS-QL share one definition of "the same learning".

use std::ops::ControlFlow;

use csql::{Agent, Identified, LoopParams, Never, Perception, RunSettings, Setup, StrategyKind};
use mdp::Mdp;
use qlearn::{Params, QLearner, QTable, RowId, Start};
use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

#[test]
fn csql_loop_on_identified_states_is_qlearn() {
    for (map, seed) in [("tan3x3", 1), ("tan8x8", 2), ("dyna9x6", 3)] {
        let settings = RunSettings::tan1991(map, StrategyKind::Resetting, seed);
        let setup = Setup::new(&settings).unwrap();
        let world = &setup.world;
        let sensed = &setup.sensed(&settings);
        let trials = 40;

        // qlearn's plain learner.
        let mut plain = QLearner::new(world, Params::tan1991(), Start::Uniform).unwrap();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let mut plain_moves = Vec::new();
        plain.run(trials, &mut rng, |t, _| {
            plain_moves.push(t.moves);
            ControlFlow::Continue(())
        });

        // csql's main loop, one row per state, never refining.
        let mut agent = Agent::new(
            Identified::new(sensed, vec![0.0; world.num_states()]),
            Never,
            QTable::new(4).unwrap(),
            LoopParams::from(&settings),
        );
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let starts = world.states();
        let mut ours_moves = Vec::new();
        for trial in 1..=trials as u32 {
            let start = starts[rng.random_range(0..starts.len())];
            ours_moves.push(agent.run_trial(sensed, start, trial, &mut rng).moves);
        }
        assert_eq!(plain_moves, ours_moves, "{map}");
        // Same values for every state (rows are numbered differently).
        for s in world.states() {
            let (row, _) = agent.perception.classify(sensed, s, &mut agent.table);
            let table = &agent.table;
            assert_eq!(table.v(row), plain.table().v(RowId(s.0)), "{map} {s}");
            assert_eq!(
                table.q_row(row),
                plain.table().q_row(RowId(s.0)),
                "{map} {s}"
            );
        }
    }
}
