//! AMRL-Q (Bellinger et al., 2021): Q-learning over a state and a pair (action, measure
//! or not), the baseline of the active-measurement literature (specification 6.11).
//!
//! The agent knows its start state. At every step it chooses an action and whether to
//! measure the whole state at once (at one price, in reward units), greedily on
//! `Q(s, a, m)` with probability `1 - epsilon` and uniformly otherwise. Measured, the
//! state reached is known and counted in a model of transitions; unmeasured, the agent
//! takes the model's most likely next state for the truth. Both `Q(s, a, 0)` and
//! `Q(s, a, 1)` learn from every step, toward `r + gamma max Q(s', .)` (0 after a
//! terminal move), the second less the price; `Q(s, a, 1)` starts at the measuring bias.
//! The last share of episodes is greedy.
//!
//! ```
//! use rand::SeedableRng;
//! let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
//! let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
//! let run = csql::amrl_q(&lake, &csql::AmrlParams::default(), 0.05, mdp::SensingRule::WithMove, 300, 100, &mut rng);
//! assert_eq!(run.len(), 300);
//! let s = csql::CostlySummary::of(&run);
//! assert!(s.mean_last10 > 0.8, "{s:?}"); // greedy at the end: few measurements, the goal
//! ```

use mdp::{ActionId, SensingRule, StateId, World};
use qlearn::{Discount, LearningRate, QTable, RowId, Target};
use rand::{Rng, RngExt};
use serde::Serialize;

use crate::observe::{KeepTrace, Observer, told_to_stop};
use crate::settings::costed::{AmrlParams, MAX_EPISODES, Measuring};

/// What one episode of a run with priced sensing gave, in reward units.
///
/// ```
/// let e = csql::Episode { reward: 1.0, sensing: 0.1, measurements: 2, steps: 6, reached_goal: true };
/// assert!((e.costed_return() - 0.9).abs() < 1e-12);
/// assert_eq!(csql::Episode::default().costed_return(), 0.0); // before its first move
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Episode {
    /// The undiscounted reward of the episode.
    pub reward: f64,
    /// The prices of what was sensed in the episode.
    pub sensing: f64,
    /// How many measurements were made.
    pub measurements: u32,
    /// How many moves were made.
    pub steps: u32,
    /// Whether the episode ended on a terminal move with a positive reward (FrozenLake's
    /// goal).
    pub reached_goal: bool,
}

impl Episode {
    /// The costed return: the undiscounted reward less the prices of what was sensed.
    ///
    /// ```
    /// let e = csql::Episode { reward: 0.0, sensing: 0.05, measurements: 1, steps: 1, reached_goal: false };
    /// assert_eq!(e.costed_return(), -0.05);
    /// ```
    pub fn costed_return(&self) -> f64 {
        self.reward - self.sensing
    }
}

/// A run's episodes summed up as the active-measurement benchmark reports them.
///
/// ```
/// let e = |r: f64| csql::Episode { reward: r, sensing: 0.0, measurements: 0, steps: 3, reached_goal: r > 0.0 };
/// let s = csql::CostlySummary::of(&[e(0.0), e(0.0), e(1.0), e(1.0)]);
/// assert_eq!((s.mean_all, s.mean_last10, s.success), (0.5, 1.0, 0.5));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CostlySummary {
    /// Episodes.
    pub episodes: usize,
    /// The mean costed return over every episode, learning included.
    pub mean_all: f64,
    /// The mean costed return over the last 10% of episodes (at least one).
    pub mean_last10: f64,
    /// Measurements per episode.
    pub sensing_per_episode: f64,
    /// Moves per episode.
    pub steps_per_episode: f64,
    /// The share of episodes that reached the goal.
    pub success: f64,
}

impl CostlySummary {
    /// The summary of `episodes` (all zero for none).
    ///
    /// ```
    /// assert_eq!(csql::CostlySummary::of(&[]).episodes, 0);
    /// ```
    pub fn of(episodes: &[Episode]) -> CostlySummary {
        let n = episodes.len();
        let mean = |xs: &[Episode], f: &dyn Fn(&Episode) -> f64| {
            if xs.is_empty() {
                0.0
            } else {
                xs.iter().map(f).sum::<f64>() / xs.len() as f64
            }
        };
        let last = &episodes[n - n.div_ceil(10)..];
        CostlySummary {
            episodes: n,
            mean_all: mean(episodes, &Episode::costed_return),
            mean_last10: mean(last, &Episode::costed_return),
            sensing_per_episode: mean(episodes, &|e| f64::from(e.measurements)),
            steps_per_episode: mean(episodes, &|e| f64::from(e.steps)),
            success: mean(episodes, &|e| f64::from(u8::from(e.reached_goal))),
        }
    }
}

/// Measuring or not, the second half of AMRL-Q's pair.
const PAIRS: usize = 2;

/// AMRL-Q's tables: `Q(s, a, m)` as a [`QTable`] with a row per state and a column per
/// pair (`2a + m`), and the counts of measured transitions.
struct Tables {
    q: QTable,
    actions: usize,
    states: usize,
    /// `counts[(s * actions + a) * states + s']`.
    counts: Vec<u32>,
}

/// A learning rate of 1: an update that sets its target exactly.
fn exactly() -> LearningRate {
    LearningRate::new(1.0).expect("1 is a learning rate")
}

impl Tables {
    fn new(states: usize, actions: usize, bias: f64, discount: Discount) -> Tables {
        let mut q =
            QTable::with_rows(actions * PAIRS, states).expect("a world has at least one action");
        for s in 0..states {
            for a in 0..actions {
                q.update(
                    row(StateId(s as u32)),
                    pair(a, true),
                    bias,
                    Target::Terminal,
                    exactly(),
                    discount,
                );
            }
        }
        Tables {
            q,
            actions,
            states,
            counts: vec![0; states * actions * states],
        }
    }

    /// The greedy (action, measure) pair: the first maximum, actions first.
    fn greedy(&self, s: StateId) -> (usize, bool) {
        let best = self.q.greedy(row(s)).index();
        (best / PAIRS, best % PAIRS == 1)
    }

    /// The greedy action among the measuring halves: the first maximum.
    fn greedy_measured(&self, s: StateId) -> usize {
        let q = self.q.q_row(row(s));
        let mut best = 0;
        for a in 1..self.actions {
            if q[a * PAIRS + 1] > q[best * PAIRS + 1] {
                best = a;
            }
        }
        best
    }

    /// The most often measured outcome of `(s, a)`, the lowest state first among equals
    /// (the lowest state when none was measured, as a uniform prior's first maximum).
    fn likely(&self, s: StateId, a: usize) -> StateId {
        let at = (s.index() * self.actions + a) * self.states;
        let row = &self.counts[at..at + self.states];
        let mut best = 0;
        for (i, &c) in row.iter().enumerate() {
            if c > row[best] {
                best = i;
            }
        }
        StateId(best as u32)
    }

    fn count(&mut self, s: StateId, a: usize, next: StateId) {
        self.counts[(s.index() * self.actions + a) * self.states + next.index()] += 1;
    }

    /// Both halves of `(s, a)` learn from one step toward `target`, the measuring half
    /// less `price`.
    fn learn(&mut self, s: StateId, a: usize, target: f64, price: f64, p: &AmrlParams) {
        for (measure, goal) in [(false, target), (true, target - price)] {
            self.q.update(
                row(s),
                pair(a, measure),
                goal,
                Target::Terminal,
                p.learning_rate,
                p.discount,
            );
        }
    }
}

/// The table's row of state `s`.
fn row(s: StateId) -> RowId {
    RowId(s.0)
}

/// The table's column of action `a` measured or not.
fn pair(a: usize, measure: bool) -> ActionId {
    ActionId((a * PAIRS + usize::from(measure)) as u32)
}

/// Run AMRL-Q for `episodes` episodes of at most `max_moves` moves in `world`, measuring
/// the whole state at `price` (reward units) under `rule`, every random choice drawn from
/// `rng`.
///
/// ```
/// use rand::SeedableRng;
/// let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
/// let run = |seed| {
///     let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed);
///     csql::amrl_q(&lake, &Default::default(), 0.05, mdp::SensingRule::WithMove, 50, 100, &mut rng)
/// };
/// assert_eq!(run(4), run(4)); // the seed decides everything
/// ```
pub fn amrl_q<W: World + ?Sized, R: Rng + ?Sized>(
    world: &W,
    params: &AmrlParams,
    price: f64,
    rule: SensingRule,
    episodes: u32,
    max_moves: u32,
    rng: &mut R,
) -> Vec<Episode> {
    let play = Episodes {
        episodes,
        max_moves,
    };
    amrl_q_observed(world, params, price, rule, play, rng, &mut KeepTrace)
}

/// How many episodes a learner on costed episodes plays, and the move cap of each.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Episodes {
    pub(crate) episodes: u32,
    pub(crate) max_moves: u32,
}

/// [`amrl_q`], asking `observer` before every episode and every
/// [`crate::STOP_CHECK_MOVES`] moves within one whether to go on ([`Observer::keep_going`]): a
/// no ends the episode there, as the move cap would, and the run after it.
pub(crate) fn amrl_q_observed<W: World + ?Sized, R: Rng + ?Sized>(
    world: &W,
    params: &AmrlParams,
    price: f64,
    rule: SensingRule,
    Episodes {
        episodes,
        max_moves,
    }: Episodes,
    rng: &mut R,
    observer: &mut dyn Observer,
) -> Vec<Episode> {
    let actions = world.num_actions();
    let mut t = Tables::new(
        world.num_states(),
        actions,
        params.measure_bias,
        params.discount,
    );
    let greedy_share = params.greedy_share.clamp(0.0, 1.0);
    let greedy_from = episodes - (f64::from(episodes) * greedy_share).round() as u32;
    let mut out = Vec::with_capacity(episodes.min(MAX_EPISODES) as usize);
    for episode in 0..episodes {
        if !observer.keep_going() {
            break;
        }
        let greedy = episode >= greedy_from;
        // The truth, and what the agent takes for it.
        let mut truth = world.sample_start(rng);
        let mut believed = truth;
        let mut e = Episode::default();
        for moves in 0..max_moves {
            if told_to_stop(observer, moves) {
                break;
            }
            let exploit = greedy || !rng.random_bool(params.epsilon.get());
            let (a, measure) = match (params.measuring, exploit) {
                (Measuring::Choose, true) => t.greedy(believed),
                (Measuring::Choose, false) => (rng.random_range(0..actions), rng.random_bool(0.5)),
                (Measuring::Always, true) => (t.greedy_measured(believed), true),
                (Measuring::Always, false) => (rng.random_range(0..actions), true),
            };
            let step = world.sample(truth, ActionId(a as u32), rng);
            e.steps += 1;
            e.reward += step.reward;
            // Under the second rule a move that ends the episode is followed by no
            // measurement, and the measuring half learns that nothing was paid.
            let ended_first = rule == SensingRule::AfterOutcome && step.terminated;
            let measured = measure && !ended_first;
            let charged = if ended_first { 0.0 } else { price };
            if measured {
                e.sensing += price;
                e.measurements += 1;
            }
            let next = if measured {
                t.count(believed, a, step.next);
                step.next
            } else {
                t.likely(believed, a)
            };
            let future = if step.terminated {
                0.0
            } else {
                params.discount.get() * t.q.v(row(next))
            };
            t.learn(believed, a, step.reward + future, charged, params);
            truth = step.next;
            believed = next;
            if step.terminated {
                e.reached_goal = step.reward > 0.0;
                break;
            }
        }
        out.push(e);
    }
    out
}
