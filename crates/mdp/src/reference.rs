//! Exact reference points for costly sensing: what the best policies of three kinds
//! score, computed from a world's model.
//!
//! An agent acts in a [`World`] whose state it sees only when it pays for a measurement.
//! Its score is the **costed return** of an episode: the undiscounted sum of the rewards
//! minus the prices of everything it sensed in that episode, in reward units. The start
//! state is known to the agent (a start distribution is averaged over, each start known).
//!
//! What can be measured ([`SensingMenu`]): the whole state at one price, or any set of the
//! world's features, each at its [`Sensors::price`]. Measuring feature `f` and reading `v`
//! narrows the belief to its states that read `v` on `f`, renormalised.
//!
//! When the decision to sense is taken ([`SensingRule`]):
//!
//! * [`SensingRule::WithMove`] (the rule of the active-measurement literature): the agent
//!   chooses the move and what to measure together, before the move's outcome is seen;
//!   the price is paid even when the move ends the episode, and the readings describe the
//!   state the move leads to.
//! * [`SensingRule::AfterOutcome`]: the agent moves, sees whether the episode ended, and
//!   only if it goes on decides what to measure, one feature (or the whole state) at a
//!   time, each decided after the readings before it. Nothing is sensed once the episode
//!   has ended (by a terminal state or by the horizon).
//!
//! Both rules see when an episode ends: a belief after a move is conditioned on the
//! episode going on.
//!
//! The three reference points ([`reference_points`]), below the ceiling of free sensing
//! ([`free_sensing`]: the state known after every move at no price):
//!
//! * **always measuring** ([`always_measuring`]): the best policy that measures the whole
//!   state after every move (under [`SensingRule::WithMove`] every move pays; under
//!   [`SensingRule::AfterOutcome`] every move the episode survives pays);
//! * **open loop** ([`open_loop`]): the best plan, a sequence of actions fixed at the start
//!   and never revised by a measurement;
//! * **best sensing** ([`best_sensing`]): the best policy that may measure or not at each
//!   step, found by value iteration over the finite graph of beliefs reachable when at most
//!   `K` steps in a row leave the agent uncertain of the state ([`ReferenceOptions::max_uncertain`]).
//!
//! Each is the value of some policy, so the best of them is a lower bound of the optimum
//! over every policy. [`sensing_ceiling`] is an upper bound (the same search with the
//! state told for free past `K` uncertain steps); where the two meet, the optimum is found.
//!
//! Episodes are capped at a horizon of `H` moves ([`ReferenceOptions::horizon`]): every
//! value here is the exact optimum of the `H`-move problem (finite-horizon backward
//! induction; it stops early, exactly, when a step leaves every value unchanged bit for
//! bit, since the values of longer horizons are then the same).
//!
//! # Beliefs and their keys
//!
//! A belief is a list of `(state, probability)` pairs sorted by state, without zeros,
//! summing to 1. Two beliefs are the same node of the graph when they have the same states
//! and each probability rounds to the same multiple of [`BELIEF_QUANTUM`] (`2^-40`, about
//! `9.1e-13`); the first one reached stands for both. Rounding only ever merges beliefs
//! that agree to that tolerance, so a value differs from the unrounded one by at most
//! about `H * BELIEF_QUANTUM` times the largest return.
//!
//! # Example
//!
//! ```
//! use mdp::{ReferenceOptions, SensingMenu, SensingModel, SensingRule, WorldOptions};
//! let options = WorldOptions {
//!     slide: Some(0.5),
//!     sensing: Some(SensingModel::Factors),
//!     factor_costs: Some(vec![0.025, 0.025]),
//!     ..Default::default()
//! };
//! let lake = mdp::builtin_world("frozenlake4x4", &options).unwrap();
//! let opts = ReferenceOptions { max_uncertain: Some(2), ..ReferenceOptions::default() };
//! let whole = mdp::reference_points(&lake, SensingMenu::whole(&lake), SensingRule::WithMove, &opts).unwrap();
//! assert!((whole.always_measuring - 0.7375).abs() < 1e-9);
//! assert!((whole.best_sensing.value - 0.90).abs() < 1e-9);
//! let apart = mdp::best_sensing(&lake, SensingMenu::Features, SensingRule::WithMove, &opts).unwrap();
//! assert!((apart.value - 0.95).abs() < 1e-9);
//! ```

use crate::belief::{CostlyModel, PlanOptions, solve_counted};
use crate::costly::{
    ReferenceError, ReferenceOptions, SensingMenu, SensingRule, bad, check_horizon, check_menu,
};
use crate::world::World;

/// The value of the best open-loop plan.
///
/// ```
/// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
/// let o = mdp::open_loop(&w, &mdp::ReferenceOptions::default()).unwrap();
/// assert!(o.exact && (o.value - 1.0).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenLoop {
    /// The expected return of the best plan (nothing is sensed).
    pub value: f64,
    /// Whether it is the optimum; false when the plans kept were capped (and the value
    /// is below [`free_sensing`]), and then `value` is the return of a plan, so a lower
    /// bound of the optimum.
    pub exact: bool,
    /// The most plans (undominated value vectors) kept at one step.
    pub plans: usize,
}

/// The value of the best policy that may measure or not at each step.
///
/// ```
/// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
/// let menu = mdp::SensingMenu::Whole { price: 0.05 };
/// let b = mdp::best_sensing(&w, menu, mdp::SensingRule::WithMove, &mdp::ReferenceOptions::default()).unwrap();
/// assert!((b.value - 1.0).abs() < 1e-12);
/// assert!(b.beliefs >= 1);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BestSensing {
    /// The expected costed return of the best policy.
    pub value: f64,
    /// How many beliefs (nodes of the graph) the search visited.
    pub beliefs: usize,
    /// The horizon at which the values stopped changing (`H` if they never did).
    pub converged_at: u32,
    /// The expected number of probes the policy measures in an episode: coordinates
    /// (features) with [`SensingMenu::Features`], whole states with
    /// [`SensingMenu::Whole`]; of the best choices, the first in the order of
    /// [`BeliefPlan::decide`](crate::BeliefPlan::decide) where several are best. For
    /// [`sensing_ceiling`], the probes the relaxed policy pays for (not the states it is
    /// told).
    pub sensing: f64,
}

/// The three reference points of a world, one sensing menu and one rule.
///
/// ```
/// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
/// let menu = mdp::SensingMenu::Whole { price: 0.05 };
/// let r = mdp::reference_points(&w, menu, mdp::SensingRule::WithMove, &Default::default()).unwrap();
/// assert!((r.always_measuring - 0.7).abs() < 1e-12); // six moves at 0.05
/// assert_eq!(r.open_loop.value, 1.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferencePoints {
    /// [`free_sensing`]: the ceiling of the others.
    pub free_sensing: f64,
    /// [`always_measuring`].
    pub always_measuring: f64,
    /// [`always_measuring_sensing`]: what the always-measuring policy measures in an
    /// episode (the open loop measures nothing; the best policy's is
    /// [`BestSensing::sensing`]).
    pub always_measuring_sensing: f64,
    /// [`open_loop`].
    pub open_loop: OpenLoop,
    /// [`best_sensing`].
    pub best_sensing: BestSensing,
}

/// Exact reference points for costly sensing: what the best policies of three kinds
/// score, computed from a world's model.
///
/// An agent acts in a [`World`] whose state it sees only when it pays for a measurement.
/// Its score is the **costed return** of an episode: the undiscounted sum of the rewards
/// minus the prices of everything it sensed in that episode, in reward units. The start
/// state is known to the agent (a start distribution is averaged over, each start known).
///
/// What can be measured ([`SensingMenu`]): the whole state at one price, or any set of the
/// world's features, each at its [`Sensors::price`](crate::Sensors::price). Measuring feature `f` and reading `v`
/// narrows the belief to its states that read `v` on `f`, renormalised.
///
/// When the decision to sense is taken ([`SensingRule`]):
///
/// * [`SensingRule::WithMove`] (the rule of the active-measurement literature): the agent
///   chooses the move and what to measure together, before the move's outcome is seen;
///   the price is paid even when the move ends the episode, and the readings describe the
///   state the move leads to.
/// * [`SensingRule::AfterOutcome`]: the agent moves, sees whether the episode ended, and
///   only if it goes on decides what to measure, one feature (or the whole state) at a
///   time, each decided after the readings before it. Nothing is sensed once the episode
///   has ended (by a terminal state or by the horizon).
///
/// Both rules see when an episode ends: a belief after a move is conditioned on the
/// episode going on.
///
/// The three reference points ([`reference_points`]), below the ceiling of free sensing
/// ([`free_sensing`]: the state known after every move at no price):
///
/// * **always measuring** ([`always_measuring`]): the best policy that measures the whole
///   state after every move (under [`SensingRule::WithMove`] every move pays; under
///   [`SensingRule::AfterOutcome`] every move the episode survives pays);
/// * **open loop** ([`open_loop`]): the best plan, a sequence of actions fixed at the start
///   and never revised by a measurement;
/// * **best sensing** ([`best_sensing`]): the best policy that may measure or not at each
///   step, found by value iteration over the finite graph of beliefs reachable when at most
///   `K` steps in a row leave the agent uncertain of the state ([`ReferenceOptions::max_uncertain`]).
///
/// Each is the value of some policy, so the best of them is a lower bound of the optimum
/// over every policy. [`sensing_ceiling`] is an upper bound (the same search with the
/// state told for free past `K` uncertain steps); where the two meet, the optimum is found.
///
/// Episodes are capped at a horizon of `H` moves ([`ReferenceOptions::horizon`]): every
/// value here is the exact optimum of the `H`-move problem (finite-horizon backward
/// induction; it stops early, exactly, when a step leaves every value unchanged bit for
/// bit, since the values of longer horizons are then the same).
///
/// # Beliefs and their keys
///
/// A belief is a list of `(state, probability)` pairs sorted by state, without zeros,
/// summing to 1. Two beliefs are the same node of the graph when they have the same states
/// and each probability rounds to the same multiple of [`BELIEF_QUANTUM`](crate::BELIEF_QUANTUM) (`2^-40`, about
/// `9.1e-13`); the first one reached stands for both. Rounding only ever merges beliefs
/// that agree to that tolerance, so a value differs from the unrounded one by at most
/// about `H * BELIEF_QUANTUM` times the largest return.
///
/// # Example
///
/// ```
/// use mdp::{ReferenceOptions, SensingMenu, SensingModel, SensingRule, WorldOptions};
/// let options = WorldOptions {
///     slide: Some(0.5),
///     sensing: Some(SensingModel::Factors),
///     factor_costs: Some(vec![0.025, 0.025]),
///     ..Default::default()
/// };
/// let lake = mdp::builtin_world("frozenlake4x4", &options).unwrap();
/// let opts = ReferenceOptions { max_uncertain: Some(2), ..ReferenceOptions::default() };
/// let whole = mdp::reference_points(&lake, SensingMenu::whole(&lake), SensingRule::WithMove, &opts).unwrap();
/// assert!((whole.always_measuring - 0.7375).abs() < 1e-9);
/// assert!((whole.best_sensing.value - 0.90).abs() < 1e-9);
/// let apart = mdp::best_sensing(&lake, SensingMenu::Features, SensingRule::WithMove, &opts).unwrap();
/// assert!((apart.value - 0.95).abs() < 1e-9);
/// ```
///
/// # Another example
///
/// ```
/// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
/// let r = mdp::reference_points(&w, mdp::SensingMenu::Whole { price: 0.0 },
///     mdp::SensingRule::AfterOutcome, &Default::default()).unwrap();
/// assert_eq!(r.always_measuring, 1.0);
/// ```
pub fn reference_points<W: World>(
    world: &W,
    menu: SensingMenu,
    rule: SensingRule,
    options: &ReferenceOptions,
) -> Result<ReferencePoints, ReferenceError> {
    Ok(ReferencePoints {
        free_sensing: free_sensing(world, options)?,
        always_measuring: always_measuring(world, menu, rule, options)?,
        always_measuring_sensing: always_measuring_sensing(world, menu, rule, options)?,
        open_loop: open_loop(world, options)?,
        best_sensing: best_sensing(world, menu, rule, options)?,
    })
}

/// The best expected costed return of a policy that measures the whole state after every
/// move, at [`SensingMenu::whole_price`]: backward induction over the states for
/// `H` moves.
///
/// ```
/// use mdp::{SensingMenu, SensingRule};
/// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
/// let o = mdp::ReferenceOptions::default();
/// let m = SensingMenu::Whole { price: 0.05 };
/// // Six moves; after the last one the episode has ended, so the other rule pays five.
/// assert!((mdp::always_measuring(&w, m, SensingRule::WithMove, &o).unwrap() - 0.70).abs() < 1e-12);
/// assert!((mdp::always_measuring(&w, m, SensingRule::AfterOutcome, &o).unwrap() - 0.75).abs() < 1e-12);
/// ```
pub fn always_measuring<W: World>(
    world: &W,
    menu: SensingMenu,
    rule: SensingRule,
    options: &ReferenceOptions,
) -> Result<f64, ReferenceError> {
    let (m, c, _) = measuring_every_move(world, menu, options)?;
    Ok(measured(&m, c, rule, options.horizon))
}

/// The model of `world`, what measuring its whole state costs with `menu`, and what one
/// such measurement counts in probes (one whole state, or every feature), for the policy
/// that measures after every move.
fn measuring_every_move<W: World>(
    world: &W,
    menu: SensingMenu,
    options: &ReferenceOptions,
) -> Result<(CostlyModel, f64, f64), ReferenceError> {
    check_horizon(options)?;
    check_menu(menu)?;
    let m = CostlyModel::of(world)?;
    let (c, per_measure) = match menu {
        SensingMenu::Whole { price } => (price, 1.0),
        SensingMenu::Features => (m.prices.iter().sum(), m.prices.len() as f64),
    };
    Ok((m, c, per_measure))
}

/// The expected number of probes the policy of [`always_measuring`] measures in an
/// episode: the whole state after every move (under [`SensingRule::AfterOutcome`], after
/// every move the episode survives but the horizon's last), counted as one whole state
/// with [`SensingMenu::Whole`] and as every feature with [`SensingMenu::Features`]; of
/// the best moves, the first where several are best.
///
/// ```
/// use mdp::{SensingMenu, SensingRule};
/// let lake = mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), factor_costs: Some(vec![0.025, 0.025]), ..Default::default() };
/// let w = mdp::builtin_world("frozenlake4x4", &lake).unwrap();
/// let o = mdp::ReferenceOptions::default();
/// let whole = SensingMenu::Whole { price: 0.05 };
/// // Six moves, each measured, the last one too under the published rule.
/// assert_eq!(mdp::always_measuring_sensing(&w, whole, SensingRule::WithMove, &o).unwrap(), 6.0);
/// assert_eq!(mdp::always_measuring_sensing(&w, whole, SensingRule::AfterOutcome, &o).unwrap(), 5.0);
/// // The row and the column of every state reached.
/// let apart = SensingMenu::Features;
/// assert_eq!(mdp::always_measuring_sensing(&w, apart, SensingRule::WithMove, &o).unwrap(), 12.0);
/// ```
pub fn always_measuring_sensing<W: World>(
    world: &W,
    menu: SensingMenu,
    rule: SensingRule,
    options: &ReferenceOptions,
) -> Result<f64, ReferenceError> {
    let (m, c, per_measure) = measuring_every_move(world, menu, options)?;
    Ok(measured_counted(&m, c, rule, options.horizon, Some(per_measure)).1)
}

/// The best expected return when the state is known after every move for free: a
/// ceiling of every reference point (no policy that senses less, or pays, does better).
///
/// ```
/// // On the semi-slippery lake a policy that knows the state always reaches the goal.
/// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { slide: Some(0.5), ..Default::default() }).unwrap();
/// let v = mdp::free_sensing(&w, &mdp::ReferenceOptions::default()).unwrap();
/// assert!((v - 1.0).abs() < 1e-12);
/// ```
pub fn free_sensing<W: World>(
    world: &W,
    options: &ReferenceOptions,
) -> Result<f64, ReferenceError> {
    check_horizon(options)?;
    let m = CostlyModel::of(world)?;
    Ok(measured(&m, 0.0, SensingRule::WithMove, options.horizon))
}

/// Backward induction over the states, the state measured at `c` after every move.
fn measured(m: &CostlyModel, c: f64, rule: SensingRule, horizon: u32) -> f64 {
    measured_counted(m, c, rule, horizon, None).0
}

/// [`measured`], and with `per_measure` (what one measurement counts) the expected count
/// of measurements of the first best move of each state at each number of moves left;
/// the values are [`measured`]'s, the iteration going on past their convergence until
/// the counts stop changing too (or the horizon).
fn measured_counted(
    m: &CostlyModel,
    c: f64,
    rule: SensingRule,
    horizon: u32,
    per_measure: Option<f64>,
) -> (f64, f64) {
    // v[s]: the value with h moves left, from a known state s; n[s] its measurements.
    let mut v = vec![0.0; m.n];
    let mut w = vec![0.0; m.n];
    let mut n = vec![0.0; m.n];
    let mut n_next = vec![0.0; m.n];
    let per = per_measure.unwrap_or(0.0);
    for h in 1..=horizon {
        measured_step(m, (c, per), rule, h, (&v, &n), (&mut w, &mut n_next));
        let counts_same = per_measure.is_none() || n_next == n;
        if w == v && counts_same {
            break;
        }
        std::mem::swap(&mut v, &mut w);
        std::mem::swap(&mut n, &mut n_next);
    }
    (m.at_start(|s| v[s as usize]), m.at_start(|s| n[s as usize]))
}

/// One step of [`measured_counted`]'s backward induction: from the values `v` (and
/// counts `n`) with `h - 1` moves left, those with `h` moves left into `w` (and `n_next`),
/// the state measured at `c` after every move, each measurement counting `per`; of the
/// best moves the first gives the count. Terminal states are left as they are.
pub(crate) fn measured_step(
    m: &CostlyModel,
    (c, per): (f64, f64),
    rule: SensingRule,
    h: u32,
    (v, n): (&[f64], &[f64]),
    (w, n_next): (&mut [f64], &mut [f64]),
) {
    // Under the other rule a move that leaves the episode going measures, unless it
    // was the last move of the horizon.
    let after_price = if h > 1 { c } else { 0.0 };
    let after_count = if h > 1 { per } else { 0.0 };
    for (s, ws) in w.iter_mut().enumerate() {
        if m.terminal[s] {
            continue;
        }
        let mut best = f64::NEG_INFINITY;
        let mut counted = 0.0;
        for a in 0..m.na {
            let i = m.pair(s as u32, a);
            let mut q = m.reward[i];
            let mut k = 0.0;
            for &(t, p) in &m.next[i] {
                q += p * v[t as usize];
                k += p * n[t as usize];
                if rule == SensingRule::AfterOutcome {
                    q -= p * after_price;
                    k += p * after_count;
                }
            }
            if rule == SensingRule::WithMove {
                q -= c;
                k += per;
            }
            if q > best {
                counted = k;
            }
            best = best.max(q);
        }
        *ws = best;
        n_next[s] = counted;
    }
}

/// The best expected return of an open-loop plan: `H` actions fixed at the start (which
/// is known), nothing sensed after it.
///
/// Computed backwards over value vectors: each plan of `h` moves has a vector of its
/// expected returns from every state, the plans of `h + 1` moves are each action followed
/// by a plan of `h`, and a plan whose vector is nowhere above another's is dropped (it is
/// never better from any belief). That is exact. When more than
/// [`ReferenceOptions::max_plans`] vectors remain, the ones with the largest sum are
/// kept: every vector kept is still a plan's, so the value is then a lower bound
/// ([`OpenLoop::exact`] false), unless it reaches the ceiling [`free_sensing`].
///
/// ```
/// let o = mdp::WorldOptions { slide: Some(0.5), ..Default::default() };
/// let lake = mdp::builtin_world("frozenlake8x8", &o).unwrap();
/// let o = mdp::ReferenceOptions { horizon: 20, max_plans: 100, ..Default::default() };
/// let r = mdp::open_loop(&lake, &o).unwrap();
/// assert!(r.exact && (r.value - 1.0).abs() < 1e-12); // right to the edge, then down
/// ```
pub fn open_loop<W: World>(
    world: &W,
    options: &ReferenceOptions,
) -> Result<OpenLoop, ReferenceError> {
    check_horizon(options)?;
    if options.max_plans == 0 {
        return Err(bad("max_plans", "0; at least one plan must be kept"));
    }
    let m = CostlyModel::of(world)?;
    let live: Vec<u32> = (0..m.n as u32)
        .filter(|&s| !m.terminal[s as usize])
        .collect();
    let mut index = vec![usize::MAX; m.n];
    for (i, &s) in live.iter().enumerate() {
        index[s as usize] = i;
    }
    let d = live.len();
    let mut plans: Vec<Vec<f64>> = vec![vec![0.0; d]];
    let mut exact = true;
    let mut most = 1;
    for _ in 0..options.horizon {
        let mut candidates: Vec<Vec<f64>> = Vec::with_capacity(plans.len() * m.na);
        for a in 0..m.na {
            for alpha in &plans {
                let v: Vec<f64> = live
                    .iter()
                    .map(|&s| {
                        let i = m.pair(s, a);
                        m.reward[i]
                            + m.next[i]
                                .iter()
                                .map(|&(t, p)| p * alpha[index[t as usize]])
                                .sum::<f64>()
                    })
                    .collect();
                candidates.push(v);
            }
        }
        let mut kept = undominated(candidates);
        if kept.len() > options.max_plans {
            kept.truncate(options.max_plans);
            exact = false;
        }
        most = most.max(kept.len());
        let same = kept == plans;
        plans = kept;
        if same {
            break;
        }
    }
    let value = m.at_start(|s| {
        plans
            .iter()
            .map(|alpha| alpha[index[s as usize]])
            .fold(f64::NEG_INFINITY, f64::max)
    });
    // A capped search that reaches the ceiling of free sensing is exact all the same.
    let ceiling = measured(&m, 0.0, SensingRule::WithMove, options.horizon);
    let exact = exact || value >= ceiling - DOMINANCE_TOLERANCE;
    Ok(OpenLoop {
        value,
        exact,
        plans: most,
    })
}

/// The vectors no other is at least as large as everywhere, by decreasing sum (ties by
/// the vectors' order, so the result is deterministic); of equal vectors one is kept.
fn undominated(mut candidates: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    let sums: Vec<f64> = candidates.iter().map(|v| v.iter().sum()).collect();
    let mut order: Vec<usize> = (0..candidates.len()).collect();
    order.sort_by(|&i, &j| {
        sums[j]
            .total_cmp(&sums[i])
            .then_with(|| compare(&candidates[i], &candidates[j]))
    });
    let mut kept: Vec<Vec<f64>> = Vec::new();
    for i in order {
        let v = std::mem::take(&mut candidates[i]);
        let dominated = kept.iter().any(|k| {
            k.iter()
                .zip(&v)
                .all(|(a, b)| *a >= *b - DOMINANCE_TOLERANCE)
        });
        if !dominated {
            kept.push(v);
        }
    }
    kept
}

/// How much lower a vector may be somewhere and still count as dominated (rounding).
const DOMINANCE_TOLERANCE: f64 = 1e-12;

fn compare(a: &[f64], b: &[f64]) -> std::cmp::Ordering {
    a.iter()
        .zip(b)
        .map(|(x, y)| x.total_cmp(y))
        .find(|o| o.is_ne())
        .unwrap_or(std::cmp::Ordering::Equal)
}

/// The best expected costed return of a policy that may measure or not at each step,
/// with at most [`ReferenceOptions::max_uncertain`] uncertain steps in a row: value
/// iteration over the beliefs such policies reach (see [`reference_points`]).
///
/// Under [`SensingRule::WithMove`] a choice is a move and a set of probes (with
/// [`SensingMenu::Whole`]: nothing or the whole state; with [`SensingMenu::Features`]:
/// any subset of the features, at most [`MAX_MENU_FEATURES`](crate::MAX_MENU_FEATURES) of them). Under
/// [`SensingRule::AfterOutcome`] a move is followed, if the episode goes on, by probes one
/// at a time, each chosen after the readings before it.
///
/// ```
/// use mdp::{ReferenceOptions, SensingMenu, SensingRule};
/// let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { slide: Some(0.5), ..Default::default() }).unwrap();
/// let menu = SensingMenu::Whole { price: 0.05 };
/// let o = ReferenceOptions { max_uncertain: Some(3), ..Default::default() };
/// let with = mdp::best_sensing(&lake, menu, SensingRule::WithMove, &o).unwrap();
/// let after = mdp::best_sensing(&lake, menu, SensingRule::AfterOutcome, &o).unwrap();
/// assert!(after.value >= with.value);
/// let tiny = ReferenceOptions { max_beliefs: 3, ..o };
/// assert!(mdp::best_sensing(&lake, menu, SensingRule::WithMove, &tiny).is_err());
/// ```
pub fn best_sensing<W: World>(
    world: &W,
    menu: SensingMenu,
    rule: SensingRule,
    options: &ReferenceOptions,
) -> Result<BestSensing, ReferenceError> {
    search(world, menu, rule, options, false)
}

/// An upper bound of the best expected costed return of **every** policy, with no bound
/// on uncertain steps: the optimum of a relaxed problem in which, whenever a step would
/// leave the agent uncertain for more than [`ReferenceOptions::max_uncertain`] steps in a
/// row, the state is told to it at no price. Every policy of the real problem runs
/// unchanged in the relaxed one (it may ignore what it is told), so none scores more than
/// this; with [`best_sensing`] below it, the two bracket the optimum, and where they meet
/// it is found. The search is [`best_sensing`]'s over the same beliefs.
///
/// ```
/// use mdp::{ReferenceOptions, SensingMenu, SensingRule};
/// let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { slide: Some(0.5), ..Default::default() }).unwrap();
/// let menu = SensingMenu::Whole { price: 0.05 };
/// let o = ReferenceOptions { max_uncertain: Some(4), ..Default::default() };
/// let low = mdp::best_sensing(&lake, menu, SensingRule::WithMove, &o).unwrap().value;
/// let high = mdp::sensing_ceiling(&lake, menu, SensingRule::WithMove, &o).unwrap().value;
/// assert!(low <= high + 1e-12 && high <= 1.0);
/// ```
pub fn sensing_ceiling<W: World>(
    world: &W,
    menu: SensingMenu,
    rule: SensingRule,
    options: &ReferenceOptions,
) -> Result<BestSensing, ReferenceError> {
    search(world, menu, rule, options, true)
}

/// The search of [`best_sensing`]; with `reveal`, that of [`sensing_ceiling`]: the graph
/// of beliefs from the start states, valued at the start.
fn search<W: World>(
    world: &W,
    menu: SensingMenu,
    rule: SensingRule,
    options: &ReferenceOptions,
    reveal: bool,
) -> Result<BestSensing, ReferenceError> {
    check_horizon(options)?;
    check_menu(menu)?;
    let m = CostlyModel::of(world)?;
    let roots: Vec<u32> = m.start.iter().map(|&(_, s)| s).collect();
    let plan = PlanOptions {
        menu,
        rule,
        search: *options,
        move_cost: 0.0,
        tolerance: 0.0,
        blind_plans: 0,
    };
    let solved = solve_counted(&m, &plan, &roots, (reveal, false, true), &mut || false)?;
    let value: f64 = m
        .start
        .iter()
        .zip(&solved.roots)
        .map(|(&(p, _), &i)| p * solved.values[i])
        .sum();
    if value == f64::NEG_INFINITY || value.is_nan() {
        let k_max = options
            .max_uncertain
            .unwrap_or(u32::MAX)
            .min(options.horizon);
        return Err(ReferenceError::Infeasible { k: k_max });
    }
    let sensing = m
        .start
        .iter()
        .zip(&solved.roots)
        .map(|(&(p, _), &i)| p * solved.probes[i])
        .sum();
    Ok(BestSensing {
        value,
        beliefs: solved.values.len(),
        converged_at: solved.converged_at,
        sensing,
    })
}
