//! The oracle: optimal distances, utilities and actions, for measuring and testing only.
//! A learner never sees it.

use std::collections::VecDeque;

use petgraph::graph::{DiGraph, NodeIndex};

use crate::error::MdpError;
use crate::grid::GridWorld;
use crate::process::{ActionId, Mdp, StateId};
use crate::stochastic::{StochasticMdp, backup};

/// Relative tolerance under which two action values count as equally optimal.
const TIE: f64 = 1e-9;

/// Optimal utilities `V*`, the optimal actions of every state and, for grid worlds, the
/// shortest distance to the goal.
///
/// For a grid world with reward 1 on entering the goal and 0 otherwise,
/// `V*(s) = gamma^(d(s) - 1)` where `d(s)` is the number of moves to the goal.
///
/// ```
/// use mdp::{GridWorld, Oracle, Pos};
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let oracle = Oracle::for_grid(&world, 0.9).unwrap();
/// let s = world.state_at(Pos::new(2, 0)).unwrap();
/// assert_eq!(oracle.distance(s), Some(4));
/// assert!((oracle.v_star(s) - 0.9f64.powi(3)).abs() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Oracle {
    actions: usize,
    gamma: f64,
    v_star: Vec<f64>,
    optimal: Vec<bool>,
    distance: Option<Vec<Option<u32>>>,
}

fn check_gamma(gamma: f64) -> Result<(), MdpError> {
    if (0.0..1.0).contains(&gamma) {
        Ok(())
    } else {
        Err(MdpError::InvalidDiscount { gamma })
    }
}

impl Oracle {
    /// The oracle of a grid world, from breadth-first distances to the goal.
    ///
    /// Utilities use the world's goal reward (`V* = goal_reward * gamma^(d-1)`); a world
    /// with a non-zero step reward is solved by [`Oracle::solve`] instead, and the
    /// distances are kept.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan8x8").unwrap());
    /// let oracle = mdp::Oracle::for_grid(&world, 0.9).unwrap();
    /// assert_eq!(oracle.distance(world.goal()), Some(0));
    /// ```
    pub fn for_grid(world: &GridWorld, gamma: f64) -> Result<Oracle, MdpError> {
        check_gamma(gamma)?;
        let distance = grid_distances(world);
        if world.options().step_reward != 0.0 {
            let mut o = Oracle::solve(world, gamma)?;
            o.distance = Some(distance);
            return Ok(o);
        }
        let n = Mdp::num_states(world);
        let r = world.options().goal_reward;
        let v_star: Vec<f64> = distance
            .iter()
            .enumerate()
            .map(|(s, d)| match d {
                _ if s == world.goal().index() => 0.0,
                Some(d) => r * gamma.powi(*d as i32 - 1),
                None => 0.0,
            })
            .collect();
        let mut optimal = vec![false; n * 4];
        for s in 0..n {
            if s == world.goal().index() {
                continue;
            }
            let Some(d) = distance[s] else { continue };
            for a in 0..4 {
                let next = world.step(StateId(s as u32), ActionId(a as u32)).next;
                optimal[s * 4 + a] = distance[next.index()] == Some(d - 1);
            }
        }
        Ok(Oracle {
            actions: 4,
            gamma,
            v_star,
            optimal,
            distance: Some(distance),
        })
    }

    /// The oracle of any deterministic MDP with non-negative rewards, by value iteration
    /// to machine precision. Terminal states have utility 0.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let a = mdp::Oracle::solve(&world, 0.9).unwrap();
    /// let b = mdp::Oracle::for_grid(&world, 0.9).unwrap();
    /// for s in world.states() { assert!((a.v_star(s) - b.v_star(s)).abs() < 1e-9); }
    /// ```
    pub fn solve<M: Mdp + ?Sized>(mdp: &M, gamma: f64) -> Result<Oracle, MdpError> {
        check_gamma(gamma)?;
        let (n, na) = (mdp.num_states(), mdp.num_actions());
        let q = |v: &[f64], s: usize, a: usize| {
            let step = mdp.step(StateId(s as u32), ActionId(a as u32));
            step.reward
                + if step.terminated {
                    0.0
                } else {
                    gamma * v[step.next.index()]
                }
        };
        let mut v = vec![0.0; n];
        // Deterministic Bellman backups contract by gamma; stop when nothing moves.
        loop {
            let mut change: f64 = 0.0;
            for s in 0..n {
                if mdp.is_terminal(StateId(s as u32)) {
                    continue;
                }
                let best = (0..na)
                    .map(|a| q(&v, s, a))
                    .fold(f64::NEG_INFINITY, f64::max);
                change = change.max((best - v[s]).abs());
                v[s] = best;
            }
            if change <= f64::EPSILON * v.iter().fold(1.0, |m: f64, x| m.max(x.abs())) {
                break;
            }
        }
        let mut optimal = vec![false; n * na];
        for s in 0..n {
            if mdp.is_terminal(StateId(s as u32)) {
                continue;
            }
            for a in 0..na {
                optimal[s * na + a] = q(&v, s, a) >= v[s] - TIE * v[s].abs();
            }
        }
        Ok(Oracle {
            actions: na,
            gamma,
            v_star: v,
            optimal,
            distance: None,
        })
    }

    /// The oracle of a stochastic MDP (for example a [`crate::SlipperyGrid`]) by value
    /// iteration on its true model, until no value changes by more than 1e-13. Terminal
    /// states have utility 0; there are no distances. On a deterministic world it agrees
    /// with [`Oracle::solve`].
    ///
    /// ```
    /// use mdp::{GridWorld, Oracle, Slip, SlipperyGrid};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let o = Oracle::solve_stochastic(&SlipperyGrid::new(&world, Slip::new(0.1).unwrap()), 0.9).unwrap();
    /// let next_to_goal = world.state_at(mdp::Pos::new(0, 1)).unwrap();
    /// // Right reaches the goal unless it slips (up stays, down moves away).
    /// assert!(o.v_star(next_to_goal) < 1.0 && o.v_star(next_to_goal) > 0.9);
    /// assert_eq!(o.distance(next_to_goal), None);
    /// ```
    pub fn solve_stochastic<M: StochasticMdp + ?Sized>(
        mdp: &M,
        gamma: f64,
    ) -> Result<Oracle, MdpError> {
        check_gamma(gamma)?;
        let (n, na) = (mdp.num_states(), mdp.num_actions());
        let mut v = vec![0.0; n];
        let mut out = Vec::new();
        let q = |v: &[f64], s: usize, a: usize, out: &mut Vec<_>| {
            mdp.outcomes(StateId(s as u32), ActionId(a as u32), out);
            backup(out, v, gamma)
        };
        loop {
            let mut change: f64 = 0.0;
            for s in 0..n {
                if mdp.is_terminal(StateId(s as u32)) {
                    continue;
                }
                let best = (0..na)
                    .map(|a| q(&v, s, a, &mut out))
                    .fold(f64::NEG_INFINITY, f64::max);
                change = change.max((best - v[s]).abs());
                v[s] = best;
            }
            if change <= 1e-13 {
                break;
            }
        }
        let mut optimal = vec![false; n * na];
        for s in 0..n {
            if mdp.is_terminal(StateId(s as u32)) {
                continue;
            }
            for a in 0..na {
                optimal[s * na + a] = q(&v, s, a, &mut out) >= v[s] - 1e-9 * v[s].abs();
            }
        }
        Ok(Oracle {
            actions: na,
            gamma,
            v_star: v,
            optimal,
            distance: None,
        })
    }

    /// How many actions the world has.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// assert_eq!(mdp::Oracle::for_grid(&w, 0.5).unwrap().num_actions(), 4);
    /// ```
    pub fn num_actions(&self) -> usize {
        self.actions
    }

    /// The actions, in id order.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let o = mdp::Oracle::for_grid(&w, 0.9).unwrap();
    /// assert_eq!(o.actions().count(), 4);
    /// ```
    pub fn actions(&self) -> impl Iterator<Item = ActionId> + use<> {
        (0..self.actions as u32).map(ActionId)
    }

    /// The discount the oracle was built with.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// assert_eq!(mdp::Oracle::for_grid(&w, 0.5).unwrap().gamma(), 0.5);
    /// ```
    pub fn gamma(&self) -> f64 {
        self.gamma
    }

    /// The optimal utility of a state (0 for terminal states).
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let o = mdp::Oracle::for_grid(&w, 0.9).unwrap();
    /// assert_eq!(o.v_star(w.state_at(mdp::Pos::new(0, 1)).unwrap()), 1.0);
    /// ```
    pub fn v_star(&self, s: StateId) -> f64 {
        self.v_star[s.index()]
    }

    /// Whether action `a` is optimal in state `s` (never, in a terminal state).
    ///
    /// ```
    /// use mdp::{Action, Pos};
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let o = mdp::Oracle::for_grid(&w, 0.9).unwrap();
    /// let s = w.state_at(Pos::new(0, 1)).unwrap();
    /// assert!(o.is_optimal(s, Action::Right.id()));
    /// assert!(!o.is_optimal(s, Action::Left.id()));
    /// ```
    pub fn is_optimal(&self, s: StateId, a: ActionId) -> bool {
        self.optimal[s.index() * self.actions + a.index()]
    }

    /// The optimal actions of a state, in id order.
    ///
    /// ```
    /// use mdp::{Action, Pos};
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let o = mdp::Oracle::for_grid(&w, 0.9).unwrap();
    /// let s = w.state_at(Pos::new(1, 1)).unwrap();
    /// assert_eq!(o.optimal_actions(s), vec![Action::Up.id(), Action::Right.id()]);
    /// ```
    pub fn optimal_actions(&self, s: StateId) -> Vec<ActionId> {
        (0..self.actions)
            .filter(|&a| self.optimal[s.index() * self.actions + a])
            .map(|a| ActionId(a as u32))
            .collect()
    }

    /// Moves to the goal from a state (grid oracles only; `None` otherwise or if the goal
    /// cannot be reached).
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan8x8").unwrap());
    /// let o = mdp::Oracle::for_grid(&w, 0.9).unwrap();
    /// assert!(w.states().iter().all(|&s| o.distance(s).unwrap() >= 1));
    /// ```
    pub fn distance(&self, s: StateId) -> Option<u32> {
        self.distance.as_ref().and_then(|d| d[s.index()])
    }
}

/// Breadth-first distances to the goal over the reversed transition graph.
fn grid_distances(world: &GridWorld) -> Vec<Option<u32>> {
    let n = Mdp::num_states(world);
    let mut graph: DiGraph<(), ()> = DiGraph::with_capacity(n, n * 4);
    for _ in 0..n {
        graph.add_node(());
    }
    for s in 0..n {
        if s == world.goal().index() {
            continue;
        }
        for a in 0..4 {
            let next = world.step(StateId(s as u32), ActionId(a)).next;
            if next.index() != s {
                graph.add_edge(NodeIndex::new(next.index()), NodeIndex::new(s), ());
            }
        }
    }
    let mut distance = vec![None; n];
    distance[world.goal().index()] = Some(0);
    let mut queue = VecDeque::from([NodeIndex::new(world.goal().index())]);
    while let Some(u) = queue.pop_front() {
        #[cfg_attr(
            not(test),
            expect(
                clippy::expect_used,
                reason = "a node is queued only after its distance is set"
            )
        )]
        let d = distance[u.index()].expect("queued nodes have a distance");
        for v in graph.neighbors(u) {
            if distance[v.index()].is_none() {
                distance[v.index()] = Some(d + 1);
                queue.push_back(v);
            }
        }
    }
    distance
}
