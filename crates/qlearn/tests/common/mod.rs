//! Helpers shared by the integration tests: random small MDPs and value iteration.

#![allow(
    dead_code,
    reason = "shared by several test programs, each of which uses only some of it (an expectation would fail in those that use all)"
)]

use mdp::{ActionId, Mdp, NegativeRewards, StateId, TabularMdp};
use proptest::prelude::*;

/// A small deterministic MDP with non-negative rewards: 2 to `max_states` states, 1 to
/// 3 actions, rewards drawn from a few values (0 most often), some states terminal.
pub fn small_mdp(max_states: usize) -> impl Strategy<Value = TabularMdp> {
    (2..=max_states, 1..=3usize).prop_flat_map(|(n, a)| {
        (
            Just(n),
            Just(a),
            prop::collection::vec(0..n as u32, n * a),
            prop::collection::vec(prop::sample::select(vec![0.0, 0.0, 0.0, 0.5, 1.0]), n * a),
            prop::collection::vec(prop::bool::weighted(0.25), n),
        )
            .prop_map(|(n, a, next, reward, terminal)| {
                TabularMdp::new(n, a, next, reward, terminal, NegativeRewards::Refuse).unwrap()
            })
    })
}

/// Optimal utilities by value iteration, written independently of the learner:
/// `V(s) = max_a r(s, a) + (0 if the step terminates, else gamma * V(next))`, and 0 for
/// terminal states, iterated until nothing changes.
pub fn value_iteration<M: Mdp>(mdp: &M, gamma: f64) -> Vec<f64> {
    let n = mdp.num_states();
    let mut v = vec![0.0f64; n];
    for _ in 0..100_000 {
        let mut next_v = vec![0.0f64; n];
        for (s, value) in next_v.iter_mut().enumerate() {
            let s_id = StateId(s as u32);
            if mdp.is_terminal(s_id) {
                continue;
            }
            *value = (0..mdp.num_actions())
                .map(|a| q_value(mdp, &v, s_id, ActionId(a as u32), gamma))
                .fold(f64::NEG_INFINITY, f64::max);
        }
        if next_v == v {
            break;
        }
        v = next_v;
    }
    v
}

/// One Bellman backup of `Q(s, a)` from utilities `v`.
pub fn q_value<M: Mdp>(mdp: &M, v: &[f64], s: StateId, a: ActionId, gamma: f64) -> f64 {
    let step = mdp.step(s, a);
    step.reward
        + if step.terminated {
            0.0
        } else {
            gamma * v[step.next.index()]
        }
}
