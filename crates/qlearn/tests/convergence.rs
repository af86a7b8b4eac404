//! Convergence: plain Q-learning's values reach V* computed by value iteration (written
//! in `common`, independent of the learner), and its greedy actions are optimal.

mod common;

use std::ops::ControlFlow;

use mdp::{ActionId, GridWorld, Mdp, NegativeRewards, StateId, TabularMdp};
use proptest::prelude::*;
use qlearn::{
    Discount, LearningRate, MoveCap, Params, QLearner, QTable, RowId, Start, Temperature, TrialEnd,
};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// Whether every non-terminal state's V is within `tol` of V* and every greedy action
/// is optimal within `tol`.
fn converged<M: Mdp>(mdp: &M, table: &QTable, v_star: &[f64], gamma: f64, tol: f64) -> bool {
    mdp.non_terminal_states().into_iter().all(|s| {
        let row = RowId(s.0);
        (table.v(row) - v_star[s.index()]).abs() <= tol
            && table
                .greedy_actions(row)
                .all(|a| common::q_value(mdp, v_star, s, a, gamma) >= v_star[s.index()] - tol)
    })
}

/// Learn until converged (checked after each trial) or `max_trials`; the trials used.
fn learn<M: Mdp>(mdp: &M, params: Params, seed: u64, max_trials: u64, tol: f64) -> Option<u64> {
    let gamma = params.discount.get();
    let v_star = common::value_iteration(mdp, gamma);
    let mut learner = QLearner::new(mdp, params, Start::Uniform).unwrap();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let summary = learner.run(max_trials, &mut rng, |_, table| {
        if converged(mdp, table, &v_star, gamma, tol) {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    });
    summary.stopped.then_some(summary.trials)
}

fn params(beta: f64, gamma: f64, t: f64, moves: u64) -> Params {
    Params {
        learning_rate: LearningRate::new(beta).unwrap(),
        discount: Discount::new(gamma).unwrap(),
        temperature: Temperature::new(t).unwrap(),
        max_moves: MoveCap::new(moves).unwrap(),
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 128,
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::Direct("proptest-regressions/convergence.txt"),
        )),
        ..ProptestConfig::default()
    })]

    /// Random small MDPs (rewards 0, 0.5 or 1; some terminal states; cycles allowed):
    /// with beta 1 and a temperature high enough to keep trying every action, V reaches
    /// V* to 1e-9.
    #[test]
    fn q_learning_reaches_v_star_on_small_mdps(
        mdp in common::small_mdp(5),
        gamma in prop_oneof![Just(0.0), Just(0.5), Just(0.8)],
        seed in any::<u64>(),
    ) {
        prop_assume!(!mdp.non_terminal_states().is_empty());
        let trials = learn(&mdp, params(1.0, gamma, 1.0, 30), seed, 20_000, 1e-9);
        prop_assert!(trials.is_some(), "not converged after 20000 trials");
    }
}

/// The paper's setting on the paper's 3 by 3 world and on the open 8 by 8 room: V
/// reaches gamma^(d-1) exactly enough, and the greedy policy is a shortest path.
#[test]
fn the_papers_setting_converges_on_grid_worlds() {
    for (name, seed) in [("tan3x3", 1), ("open8x8", 2), ("tan8x8", 3)] {
        let world = GridWorld::new(&mdp::builtin(name).unwrap());
        let trials = learn(&world, Params::tan1991(), seed, 50_000, 1e-12);
        assert!(trials.is_some(), "{name}: not converged");
    }
}

/// A learning rate below 1 approaches V* geometrically rather than in one step.
#[test]
fn a_smaller_learning_rate_converges_too() {
    let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    let trials = learn(&world, params(0.5, 0.9, 0.4, 100), 4, 50_000, 1e-6);
    assert!(trials.is_some());
}

/// A trial cut off by the move cap bootstraps its last update: a state that loops on
/// itself for reward 1 learns 1, then 1 + 0.9, and so on, one move per trial. Were the
/// cut treated as terminal, Q would stay at 1.
#[test]
fn truncation_bootstraps_and_termination_does_not() {
    let looping = TabularMdp::new(
        2,
        1,
        vec![0, 1],
        vec![1.0, 0.0],
        vec![false, true],
        NegativeRewards::Refuse,
    )
    .unwrap();
    let mut learner =
        QLearner::new(&looping, params(1.0, 0.9, 0.4, 1), Start::Fixed(StateId(0))).unwrap();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(0);
    let first = learner.trial(&mut rng);
    assert_eq!((first.moves, first.end), (1, TrialEnd::MoveCap));
    assert_eq!(learner.table().v(RowId(0)), 1.0);
    learner.trial(&mut rng);
    assert_eq!(learner.table().v(RowId(0)), 1.0 + 0.9 * 1.0);

    let ending = TabularMdp::new(
        2,
        1,
        vec![1, 1],
        vec![1.0, 0.0],
        vec![false, true],
        NegativeRewards::Refuse,
    )
    .unwrap();
    let mut learner =
        QLearner::new(&ending, params(1.0, 0.9, 0.4, 5), Start::Fixed(StateId(0))).unwrap();
    for _ in 0..3 {
        let t = learner.trial(&mut rng);
        assert_eq!((t.moves, t.end, t.reward), (1, TrialEnd::Terminated, 1.0));
    }
    // The terminal state's row is never updated, and the target is the reward alone.
    assert_eq!(learner.table().v(RowId(0)), 1.0);
    assert_eq!(learner.table().q(RowId(1), ActionId(0)), 0.0);
}

/// Invalid starts are errors, not panics.
#[test]
fn invalid_starts_are_refused() {
    let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    let p = Params::tan1991();
    assert_eq!(
        QLearner::new(&world, p, Start::Fixed(StateId(9))).unwrap_err(),
        qlearn::Error::StartOutOfRange {
            state: StateId(9),
            states: 9
        }
    );
    let all_terminal = TabularMdp::new(
        1,
        1,
        vec![0],
        vec![0.0],
        vec![true],
        NegativeRewards::Refuse,
    )
    .unwrap();
    assert_eq!(
        QLearner::new(&all_terminal, p, Start::Uniform).unwrap_err(),
        qlearn::Error::NoStartState
    );
}
