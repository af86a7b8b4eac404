//! Theorem 1 (Tan 1991): with every row consistent, non-negative rewards and Q = 0 at
//! the start, no V ever decreases under equation 2, whatever beta in (0, 1], gamma in
//! [0, 1) and sequence of actions. And the converse check: the same test does see a
//! decrease when two inconsistent states share a row, so it cannot pass vacuously.

mod common;

use std::ops::ControlFlow;

use mdp::{ActionId, Mdp, NegativeRewards, StateId, TabularMdp};
use proptest::prelude::*;
use qlearn::{
    Discount, LearningRate, MoveCap, Params, QLearner, QTable, RowId, Start, Target, Temperature,
    VChange,
};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// Apply the updates of `moves` (state, action) to a table whose row of state `s` is
/// `row_of[s]`, and return the first update that decreased some V: the update's own
/// report, and also any row's V compared with a snapshot, so that an update that touched
/// another row could not hide. `None` if no V ever decreased.
fn first_decrease<M: Mdp>(
    mdp: &M,
    row_of: &[u32],
    beta: LearningRate,
    gamma: Discount,
    moves: &[(StateId, ActionId)],
) -> Option<(usize, VChange)> {
    let rows = row_of.iter().max().map_or(0, |&r| r as usize + 1);
    let mut table = QTable::with_rows(mdp.num_actions(), rows).unwrap();
    let mut before = table.v_values().to_vec();
    for (i, &(s, a)) in moves.iter().enumerate() {
        let step = mdp.step(s, a);
        let target = if step.terminated {
            Target::Terminal
        } else {
            Target::Bootstrap(RowId(row_of[step.next.index()]))
        };
        let change = table.update(
            RowId(row_of[s.index()]),
            a,
            step.reward,
            target,
            beta,
            gamma,
        );
        if change.decreased() {
            return Some((i, change));
        }
        for (r, (&old, &new)) in before.iter().zip(table.v_values()).enumerate() {
            assert!(new >= old, "row {r} fell from {old} to {new} unreported");
        }
        before.copy_from_slice(table.v_values());
    }
    None
}

fn beta() -> impl Strategy<Value = LearningRate> {
    // (0, 1], with the end point 1 (the paper's value) drawn often.
    prop_oneof![Just(1.0), 1e-3..=1.0f64].prop_map(|b| LearningRate::new(b).unwrap())
}

fn gamma() -> impl Strategy<Value = Discount> {
    prop_oneof![Just(0.0), Just(0.9), 0.0..1.0f64].prop_map(|g| Discount::new(g).unwrap())
}

/// Non-terminal (state, action) pairs, drawn as raw numbers and folded into range.
fn moves(mdp: &TabularMdp, raw: &[(u32, u32)]) -> Vec<(StateId, ActionId)> {
    let live = mdp.non_terminal_states();
    let actions = mdp.num_actions() as u32;
    if live.is_empty() {
        return Vec::new();
    }
    raw.iter()
        .map(|&(s, a)| (live[s as usize % live.len()], ActionId(a % actions)))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 256,
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::Direct("proptest-regressions/theorem1.txt"),
        )),
        ..ProptestConfig::default()
    })]

    /// Every state its own row: any update sequence keeps every V non-decreasing.
    #[test]
    fn no_v_decreases_with_every_state_identified(
        mdp in common::small_mdp(6),
        beta in beta(),
        gamma in gamma(),
        raw in prop::collection::vec((any::<u32>(), any::<u32>()), 0..200),
    ) {
        let identity: Vec<u32> = (0..mdp.num_states() as u32).collect();
        let moves = moves(&mdp, &raw);
        prop_assert_eq!(first_decrease(&mdp, &identity, beta, gamma, &moves), None);
    }

    /// The same through the trial loop with Boltzmann selection: no trial reports a
    /// decrease.
    #[test]
    fn no_trial_of_plain_q_learning_reports_a_decrease(
        mdp in common::small_mdp(6),
        beta in beta(),
        gamma in gamma(),
        t in prop_oneof![Just(0.4), 1e-3..10.0f64],
        seed in any::<u64>(),
    ) {
        prop_assume!(!mdp.non_terminal_states().is_empty());
        let params = Params {
            learning_rate: beta,
            discount: gamma,
            temperature: Temperature::new(t).unwrap(),
            max_moves: MoveCap::new(20).unwrap(),
        };
        let mut learner = QLearner::new(&mdp, params, Start::Uniform).unwrap();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let mut decreases = 0;
        learner.run(20, &mut rng, |trial, _| {
            decreases += trial.decreases;
            ControlFlow::Continue(())
        });
        prop_assert_eq!(decreases, 0);
    }

    /// Two inconsistent states in one row: state 0 reaches the goal for reward 1, state 1
    /// loops on itself for nothing. Updating 0 then 1 lowers the shared V for every
    /// beta and gamma, and the check above sees it.
    #[test]
    fn the_check_sees_a_decrease_when_inconsistent_states_share_a_row(
        beta in beta(),
        gamma in gamma(),
    ) {
        // States: 0 and 1 (aliased in row 0), 2 the terminal goal (row 1).
        let mdp = TabularMdp::new(
            3, 1, vec![2, 1, 2], vec![1.0, 0.0, 0.0], vec![false, false, true],
            NegativeRewards::Refuse,
        ).unwrap();
        let moves = [(StateId(0), ActionId(0)), (StateId(1), ActionId(0))];
        let aliased = [0, 0, 1];
        let found = first_decrease(&mdp, &aliased, beta, gamma, &moves);
        let (at, change) = found.expect("an aliased row must lose value");
        prop_assert_eq!(at, 1);
        prop_assert_eq!(change.before, beta.get());
        // With each state in its own row the same moves decrease nothing.
        prop_assert_eq!(first_decrease(&mdp, &[0, 1, 2], beta, gamma, &moves), None);
    }
}

/// A second aliased case, on a corridor: a row shared by two states whose V* differ
/// loses value as soon as the farther state moves along the corridor.
#[test]
fn a_shared_row_in_a_corridor_decreases() {
    // A corridor 0 - 1 - 2 - G with actions left (0) and right (1); states 0 and 2 share
    // a row although V*(0) = 0.81 and V*(2) = 1.
    let mdp = TabularMdp::new(
        4,
        2,
        vec![0, 1, 0, 2, 1, 3, 3, 3],
        vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0],
        vec![false, false, false, true],
        NegativeRewards::Refuse,
    )
    .unwrap();
    let (beta, gamma) = (LearningRate::new(1.0).unwrap(), Discount::new(0.9).unwrap());
    let moves: Vec<_> = [(2, 1), (0, 1)]
        .iter()
        .map(|&(s, a)| (StateId(s), ActionId(a)))
        .collect();
    assert!(first_decrease(&mdp, &[0, 1, 0, 2], beta, gamma, &moves).is_some());
    assert!(first_decrease(&mdp, &[0, 1, 2, 3], beta, gamma, &moves).is_none());
}
