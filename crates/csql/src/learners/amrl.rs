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
use qlearn::{Discount, Epsilon, LearningRate, QTable, RowId, Target};
use rand::{Rng, RngExt};
use serde::{Deserialize, Serialize};

use crate::observe::{KeepTrace, Observer, told_to_stop};

/// AMRL-Q's parameters; the defaults are those the active-measurement benchmark runs it
/// with.
///
/// ```
/// let p = csql::AmrlParams::default();
/// assert_eq!((p.learning_rate.get(), p.epsilon.get(), p.discount.get()), (0.3, 0.1, 0.95));
/// assert_eq!((p.measure_bias, p.greedy_share), (0.1, 0.1));
/// assert_eq!(p.measuring, csql::Measuring::Choose);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AmrlParams {
    /// The learning rate of the Q update (0.3).
    pub learning_rate: LearningRate,
    /// The probability of a uniformly random (action, measure) pair (0.1).
    pub epsilon: Epsilon,
    /// The discount of the Q update (0.95).
    pub discount: Discount,
    /// The initial value of every `Q(s, a, measure)`; `Q(s, a, no measure)` starts at 0
    /// (0.1).
    pub measure_bias: f64,
    /// The share of the last episodes played greedily (0.1; taken within `[0, 1]`).
    pub greedy_share: f64,
    /// Whether the agent chooses to measure (AMRL-Q) or measures at every step.
    pub measuring: Measuring,
}

impl AmrlParams {
    /// Whether every parameter is the default (for serde's `skip_serializing_if`).
    ///
    /// ```
    /// assert!(csql::AmrlParams::default().is_default());
    /// ```
    pub fn is_default(&self) -> bool {
        *self == AmrlParams::default()
    }

    /// Check the parameters their types do not: a finite measuring bias, a greedy share
    /// within `[0, 1]` (the settings file's table `[amrl_q]` names them in errors).
    ///
    /// ```
    /// let mut p = csql::AmrlParams::default();
    /// assert!(p.validate().is_ok());
    /// p.greedy_share = 1.5;
    /// assert!(p.validate().unwrap_err().to_string().contains("amrl_q.greedy_share"));
    /// ```
    pub fn validate(&self) -> Result<(), crate::Error> {
        if !(-MAX_BIAS..=MAX_BIAS).contains(&self.measure_bias) {
            return Err(crate::Error::InvalidSetting {
                value: format!("amrl_q.measure_bias = {:?}", self.measure_bias),
                expected: "a number of at most 1e9 in size (csql::MAX_BIAS): a larger one drowns the world's rewards in the values' rounding",
            });
        }
        if !(0.0..=1.0).contains(&self.greedy_share) {
            return Err(crate::Error::InvalidSetting {
                value: format!("amrl_q.greedy_share = {}", self.greedy_share),
                expected: "a share from 0 to 1",
            });
        }
        Ok(())
    }
}

/// The most episodes a learner on costed episodes may play (`episodes` of
/// `learner = "amrl-q"` or `"belief"`, and [`crate::costed_episodes`]): every episode is
/// kept in the report, with its costed return.
///
/// ```
/// let s = csql::SettingsDraft::from_toml("learner = \"amrl-q\"\nepisodes = 1000001\n[costly]\nprice = 0.1", "f").unwrap();
/// assert!(s.build().unwrap_err().to_string().contains("at most 1000000 episodes"));
/// assert_eq!(csql::MAX_EPISODES, 1_000_000);
/// ```
pub const MAX_EPISODES: u32 = 1_000_000;

/// The largest size of a value the learners on costed episodes add to the world's
/// rewards (`[belief] optimism`, `[amrl_q] measure_bias`): beyond it, rewards of the
/// size of FrozenLake's drown in the rounding of the values.
///
/// ```
/// let p = csql::BeliefParams { optimism: 1e20, ..Default::default() };
/// assert!(p.validate().unwrap_err().to_string().contains("belief.optimism = 1e20"));
/// let a = csql::AmrlParams { measure_bias: -1e308, ..Default::default() };
/// assert!(a.validate().unwrap_err().to_string().contains("measure_bias = -1e308"));
/// assert_eq!(csql::MAX_BIAS, 1e9);
/// ```
pub const MAX_BIAS: f64 = 1e9;

/// Whether the agent chooses to measure.
///
/// ```
/// assert_eq!(csql::Measuring::default(), csql::Measuring::Choose);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Measuring {
    /// AMRL-Q: the pair (action, measure or not) is chosen at every step.
    #[default]
    Choose,
    /// The whole state is measured at every step, and only the action is chosen (over
    /// `Q(s, a, measure)`): Q-learning on the true state, paying for it every step, the
    /// benchmark's always-measuring learner.
    Always,
}

impl Default for AmrlParams {
    fn default() -> AmrlParams {
        AmrlParams {
            learning_rate: LearningRate::new(0.3).expect("in (0, 1]"),
            epsilon: Epsilon::new(0.1).expect("in [0, 1]"),
            discount: Discount::new(0.95).expect("in [0, 1)"),
            measure_bias: 0.1,
            greedy_share: 0.1,
            measuring: Measuring::Choose,
        }
    }
}

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
