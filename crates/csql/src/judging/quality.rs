//! The policy quality of specification §6: how good the learned greedy policy is, acting through the
//! learned representation in the true world, as a share of the optimum.
//!
//! The policy is the greedy action (ties: lowest action id) of the description CLASSIFY
//! gives a state (action 0 where it would create a new description, whose Q values are
//! all 0). Its value from each non-goal free state on the true model (slip included) is
//! divided by that state's V* on the same model, and the ratios are averaged. Without
//! sensor noise, and for a perception without a memory of its moves, classification is a
//! function of the state and the value is computed exactly by policy evaluation
//! ([`mdp::evaluate_policy`]). Under sensor noise, a memoryless policy is a stochastic
//! policy: in each state, each action has the probability that a noisy classification
//! leads to it. Those probabilities are estimated from [`POLICY_SAMPLES`] seeded
//! classifications per state (drawn from the evaluation's own generator), and the
//! stochastic policy is evaluated exactly ([`mdp::evaluate_stochastic_policy`]); the
//! standard error comes from the spread of [`POLICY_BATCHES`] batches. A perception with
//! a memory ([`Sees::memoryless`] false: [`crate::Remembering`], [`crate::UTree`])
//! acts on its path, not on its state: without slip and noise one simulated episode
//! from every state gives its exact value; otherwise the value is a seeded Monte Carlo
//! estimate: rounds of one episode from every state (the noise and the slips drawn from
//! the evaluation's own generator, at most [`MC_MAX_MOVES`] moves an episode), until the
//! standard error of the mean over rounds is below 0.005 (after at least
//! [`MC_MIN_ROUNDS`] rounds, at most [`MC_MAX_ROUNDS`]). The
//! measure is never charged and the learner never sees it.

use mdp::{ActionId, Oracle, SensorNoise, StateId, World};
use qlearn::{QTable, RowId};
use rand::Rng;
use serde::Serialize;

use crate::agent::main_loop::value_floor;
use crate::perception::view::Sees;
use crate::settings::resolve::is_deterministic;

/// Moves an episode of the Monte Carlo estimate may make (gamma^200 is below 1e-9 at the
/// paper's gamma).
///
/// ```
/// assert_eq!(csql::MC_MAX_MOVES, 200);
/// ```
pub const MC_MAX_MOVES: u32 = 200;
/// Fewest rounds of the Monte Carlo estimate.
///
/// ```
/// assert_eq!(csql::MC_MIN_ROUNDS, 30);
/// ```
pub const MC_MIN_ROUNDS: u32 = 30;
/// Most rounds of the Monte Carlo estimate.
///
/// ```
/// assert_eq!(csql::MC_MAX_ROUNDS, 4000);
/// ```
pub const MC_MAX_ROUNDS: u32 = 4000;

/// How a quality figure was obtained.
///
/// ```
/// assert_eq!(serde_json::to_string(&csql::QualityMethod::Exact).unwrap(), "\"exact\"");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum QualityMethod {
    /// Exact policy evaluation on the true model.
    Exact,
    /// A seeded Monte Carlo estimate of episodes (for a perception with a memory, in a
    /// world with slip or sensor noise).
    MonteCarlo,
    /// Under sensor noise, without a memory: the noisy policy's probability of each
    /// action in each state, estimated from [`POLICY_SAMPLES`] seeded classifications
    /// per state, then evaluated exactly on the true model.
    SampledPolicy,
}

impl QualityMethod {
    /// The method's name, as in the JSON.
    ///
    /// ```
    /// assert_eq!(csql::QualityMethod::SampledPolicy.name(), "sampled_policy");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            QualityMethod::Exact => "exact",
            QualityMethod::MonteCarlo => "monte_carlo",
            QualityMethod::SampledPolicy => "sampled_policy",
        }
    }
}

/// Classifications per state that estimate a noisy policy's action probabilities
/// ([`QualityMethod::SampledPolicy`]), in [`POLICY_BATCHES`] batches whose spread gives
/// the standard error.
///
/// ```
/// assert_eq!(csql::POLICY_SAMPLES, 400);
/// ```
pub const POLICY_SAMPLES: usize = 400;
/// Batches of [`POLICY_SAMPLES`].
///
/// ```
/// assert_eq!(csql::POLICY_BATCHES, 4);
/// ```
pub const POLICY_BATCHES: usize = 4;

/// One evaluation of the policy quality.
///
/// ```
/// let q = csql::QualityEstimate { quality: 1.0, method: csql::QualityMethod::Exact, standard_error: 0.0, episodes: 0 };
/// assert!(q.quality >= 0.95);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct QualityEstimate {
    /// Mean over non-goal states of the policy's value divided by V*.
    pub quality: f64,
    /// Exact or Monte Carlo.
    pub method: QualityMethod,
    /// The estimate's standard error (0 when exact).
    pub standard_error: f64,
    /// Episodes simulated (0 when exact).
    pub episodes: u64,
}

/// The policy quality of an agent over a run (see the module docs), with what one
/// evaluation can hand the next: the floor of the world's returns, computed once, and the
/// last exact evaluation, which is reused, bit for bit, while the policy is the same.
#[derive(Clone, Debug)]
pub(crate) struct QualityMeter<'a, R> {
    /// The oracle of the true model.
    truth: &'a Oracle,
    /// The world's sensor noise, which the evaluated policy acts through.
    noise: SensorNoise,
    /// The evaluation's own generator, drawn from only under noise.
    rng: R,
    /// Value a deterministic policy by following its paths ([`mdp::follow_policy`]),
    /// linear in the states, where it has no loop; otherwise by sweeping its Bellman
    /// equation.
    follow: bool,
    floor: Option<f64>,
    /// The last memoryless, noise-free policy evaluated, and its quality.
    last: Option<(Vec<ActionId>, f64)>,
}

impl<'a, R: Rng> QualityMeter<'a, R> {
    /// A meter of the policy quality against `truth`, through sensors with `noise`,
    /// drawing from `rng` (the evaluation's own generator); it follows deterministic
    /// policies' paths (`follow`) or sweeps.
    pub(crate) fn new(truth: &'a Oracle, noise: SensorNoise, rng: R, follow: bool) -> Self {
        QualityMeter {
            truth,
            noise,
            rng,
            follow,
            floor: None,
            last: None,
        }
    }

    /// One evaluation of the policy quality. `rows`, when given, are the rows of
    /// `world.states()` as the oracle's judge found them at the end of this trial (the
    /// perception's free view of each state, for a perception without a memory): the
    /// same rows [`Sees::sees`] would give, without walking to them again.
    pub(crate) fn evaluate<W: World + ?Sized, P: Sees>(
        &mut self,
        world: &W,
        perception: &mut P,
        table: &QTable,
        rows: Option<&[Option<RowId>]>,
    ) -> QualityEstimate {
        let (truth, noise, rng) = (self.truth, self.noise, &mut self.rng);
        let gamma = truth.gamma();
        let floor = *self.floor.get_or_insert_with(|| value_floor(world, gamma));
        if !perception.memoryless() {
            return episode_quality(world, truth, floor, perception, table, noise, rng);
        }
        if !noise.is_zero() {
            return sampled_policy_quality(world, truth, floor, perception, table, noise, rng);
        }
        let states = world.states();
        let act = |row: Option<RowId>| row.map_or(ActionId(0), |r| table.greedy(r));
        let mut policy = vec![ActionId(0); world.num_states()];
        match rows {
            Some(rows) => {
                for (&s, &row) in states.iter().zip(rows) {
                    policy[s.index()] = act(row);
                }
            }
            None => {
                for &s in &states {
                    policy[s.index()] = act(perception.sees(world, s, noise, rng));
                }
            }
        }
        let quality = match &self.last {
            Some((last, q)) if *last == policy => *q,
            _ => {
                let followed = if self.follow {
                    mdp::follow_policy(world, gamma, &policy).ok().flatten()
                } else {
                    None
                };
                let values = match followed {
                    Some(v) => Ok(v),
                    None => mdp::evaluate_policy(world, gamma, &policy),
                };
                let q = match values {
                    Ok(v) => ratio_mean(&states, truth, floor, |s| v[s.index()]),
                    Err(_) => 0.0,
                };
                self.last = Some((policy, q));
                q
            }
        };
        QualityEstimate {
            quality,
            method: QualityMethod::Exact,
            standard_error: 0.0,
            episodes: 0,
        }
    }
}

/// The policy quality of a perception with a memory, from episodes (see the module
/// docs); `floor` is the world's [`value_floor`].
fn episode_quality<W: World + ?Sized, P: Sees, R: Rng + ?Sized>(
    world: &W,
    truth: &Oracle,
    floor: f64,
    perception: &mut P,
    table: &QTable,
    noise: SensorNoise,
    rng: &mut R,
) -> QualityEstimate {
    let states = world.states();
    let gamma = truth.gamma();
    let act = |row: Option<RowId>| row.map_or(ActionId(0), |r| table.greedy(r));
    // Without slip and noise, an episode is a function of its start: one round is the
    // exact value (up to MC_MAX_MOVES moves, beyond which nothing is left to earn).
    let deterministic = noise.is_zero() && is_deterministic(world);
    let mut rounds: Vec<f64> = Vec::new();
    let mut returns = vec![0.0; world.num_states()];
    let mut se = f64::INFINITY;
    while rounds.len() < MC_MAX_ROUNDS as usize {
        for &s in &states {
            let mut x = s;
            let mut g = 0.0;
            let mut discount = 1.0;
            perception.begin();
            for _ in 0..MC_MAX_MOVES {
                let a = act(perception.sees(world, x, noise, rng));
                perception.moved(a);
                let step = world.sample(x, a, rng);
                g += discount * step.reward;
                discount *= gamma;
                if step.terminated {
                    break;
                }
                x = step.next;
            }
            returns[s.index()] = g;
        }
        rounds.push(ratio_mean(&states, truth, floor, |s| returns[s.index()]));
        if deterministic {
            return QualityEstimate {
                quality: rounds[0],
                method: QualityMethod::Exact,
                standard_error: 0.0,
                episodes: states.len() as u64,
            };
        }
        if rounds.len() >= MC_MIN_ROUNDS as usize {
            se = standard_error(&rounds);
            if se < 0.005 {
                break;
            }
        }
    }
    let n = rounds.len() as f64;
    QualityEstimate {
        quality: rounds.iter().sum::<f64>() / n,
        method: QualityMethod::MonteCarlo,
        standard_error: se,
        episodes: rounds.len() as u64 * states.len() as u64,
    }
}

/// The quality of a memoryless policy under sensor noise ([`QualityMethod::SampledPolicy`]).
fn sampled_policy_quality<W: World + ?Sized, P: Sees, R: Rng + ?Sized>(
    world: &W,
    truth: &Oracle,
    floor: f64,
    perception: &mut P,
    table: &QTable,
    noise: SensorNoise,
    rng: &mut R,
) -> QualityEstimate {
    let states = world.states();
    let n = world.num_states();
    let mut measured = vec![false; n];
    for &s in &states {
        measured[s.index()] = true;
    }
    let actions = table.num_actions();
    let per_batch = POLICY_SAMPLES / POLICY_BATCHES;
    // counts[b][s][a]: how often batch b's classifications of s led to action a.
    let mut counts = vec![vec![vec![0u32; actions]; n]; POLICY_BATCHES];
    for &s in &states {
        for batch in counts.iter_mut() {
            for _ in 0..per_batch {
                let a = perception
                    .sees(world, s, noise, rng)
                    .map_or(ActionId(0), |r| table.greedy(r));
                batch[s.index()][a.index()] += 1;
            }
        }
    }
    let quality_of = |batches: &[Vec<Vec<u32>>]| -> f64 {
        let total = (batches.len() * per_batch) as f64;
        let policy: Vec<Vec<f64>> = (0..n)
            .map(|s| {
                if !measured[s] {
                    // Terminal (or never visited): any action, the first.
                    let mut p = vec![0.0; actions];
                    p[0] = 1.0;
                    return p;
                }
                (0..actions)
                    .map(|a| batches.iter().map(|b| b[s][a]).sum::<u32>() as f64 / total)
                    .collect()
            })
            .collect();
        match mdp::evaluate_stochastic_policy(world, truth.gamma(), &policy) {
            Ok(v) => ratio_mean(&states, truth, floor, |s| v[s.index()]),
            Err(_) => 0.0,
        }
    };
    let quality = quality_of(&counts);
    let parts: Vec<f64> = (0..POLICY_BATCHES)
        .map(|b| quality_of(&counts[b..=b]))
        .collect();
    QualityEstimate {
        quality,
        method: QualityMethod::SampledPolicy,
        // The spread of the batch estimates, scaled to the whole sample.
        standard_error: standard_error(&parts),
        episodes: 0,
    }
}

/// The standard error of the mean of `xs` (sample variance over `n`), for `n >= 2`.
fn standard_error(xs: &[f64]) -> f64 {
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|q| (q - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (var / n).sqrt()
}

/// Mean over states with a positive V* of value / V*.
/// The mean over states of `(value(s) - floor) / (V*(s) - floor)`, over the states where
/// `V*(s) > floor` (1 if there is none), with `floor` the [`value_floor`]: 1 for an
/// optimal policy, 0 for one no better than the worst state's best reward forever
/// (below 0 for a worse one). Where no reward is negative the floor is 0 and this is the
/// ratio `value / V*`.
fn ratio_mean(
    states: &[StateId],
    truth: &Oracle,
    floor: f64,
    value: impl Fn(StateId) -> f64,
) -> f64 {
    let (sum, n) = states
        .iter()
        .filter(|&&s| truth.v_star(s) > floor)
        .fold((0.0, 0usize), |(sum, n), &s| {
            (sum + (value(s) - floor) / (truth.v_star(s) - floor), n + 1)
        });
    if n == 0 { 1.0 } else { sum / n as f64 }
}
