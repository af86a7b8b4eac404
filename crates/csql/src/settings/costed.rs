//! The parameters of the learners played on costed episodes: AMRL-Q's ([`AmrlParams`],
//! the settings file's table `[amrl_q]`) and sensing by belief's ([`BeliefParams`], the
//! table `[belief]`), with the bounds a run's settings hold them to. The learners
//! themselves are [`crate::amrl_q`] and [`crate::belief_planning`].

use qlearn::{Discount, Epsilon, LearningRate};
use serde::{Deserialize, Serialize};

use crate::error::Error;

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
    pub fn validate(&self) -> Result<(), Error> {
        if !(-MAX_BIAS..=MAX_BIAS).contains(&self.measure_bias) {
            return Err(Error::InvalidSetting {
                value: format!("amrl_q.measure_bias = {:?}", self.measure_bias),
                expected: "a number of at most 1e9 in size (csql::MAX_BIAS): a larger one drowns the world's rewards in the values' rounding",
            });
        }
        if !(0.0..=1.0).contains(&self.greedy_share) {
            return Err(Error::InvalidSetting {
                value: format!("amrl_q.greedy_share = {}", self.greedy_share),
                expected: "a share from 0 to 1",
            });
        }
        Ok(())
    }
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

/// The settings of [`crate::belief_planning`], and of the learner `belief` (the settings file's
/// table `[belief]`). The price of sensing is not one of them: a run's is `[costly]
/// price`, given to [`crate::belief_planning`] beside these.
///
/// ```
/// let p = csql::BeliefParams::default();
/// assert_eq!((p.max_uncertain, p.trust, p.prior, p.optimism), (7, 4, 3.0, 1.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BeliefParams {
    /// `K`: the most steps in a row after which the agent may be uncertain of its state (7).
    pub max_uncertain: u32,
    /// Tries of a pair after which it may be taken without measuring what follows, if it
    /// has shown two outcomes; twice as many if it has shown one (4).
    pub trust: u32,
    /// The weight of the optimistic outcome against a pair's tries (3).
    pub prior: f64,
    /// The reward of the optimistic outcome, in reward units (1, FrozenLake's goal; at
    /// most [`crate::MAX_BIAS`] in size).
    pub optimism: f64,
    /// Measure the whole state at once (the sum of the prices) rather than features apart.
    pub whole_state: bool,
    /// The most beliefs a plan may have; a plan that would have more is built with a
    /// lower `K`, kept for the rest of the run (5,000).
    pub max_beliefs: usize,
    /// A price per move in the plan, in reward units, so that it does not wander between
    /// choices of equal value (1e-6).
    pub move_cost: f64,
    /// With more than 0, the plan may stop measuring for the rest of the episode at any
    /// belief where the agent is to move, and follow the best open-loop plan over its
    /// model from that belief, at most this many plans kept a step
    /// ([`mdp::PlanOptions::blind_plans`]); 0: no such choice. `None` (the default):
    /// the world's own where a run's settings are built ([`crate::WorldDefaults`]: 64
    /// on FrozenLake sensed by row and column), 0 otherwise, and for
    /// [`crate::belief_planning`]; left out of the settings' echo.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub blind_plans: Option<usize>,
    /// With more than 0, what each action does is learned over every state at once (a
    /// shift of the readings, the same everywhere; specification 6.13) in place of each
    /// pair apart, an action trusted after this many tries from a known state; the
    /// world's states must then be every combination of their readings (a grid, as the
    /// lakes' row and column), else the run is refused. 0: each pair learned apart.
    /// `None` (the default): the world's own where a run's settings are built (48 on
    /// FrozenLake sensed by row and column), 0 otherwise, and for
    /// [`crate::belief_planning`]; left out of the settings' echo.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shared_moves: Option<u32>,
}

impl Default for BeliefParams {
    fn default() -> BeliefParams {
        BeliefParams {
            max_uncertain: 7,
            trust: 4,
            prior: 3.0,
            optimism: 1.0,
            whole_state: false,
            max_beliefs: 5_000,
            move_cost: 1e-6,
            blind_plans: None,
            shared_moves: None,
        }
    }
}

/// The largest `max_uncertain` a run's settings take ([`BeliefParams::validate`]): a plan
/// over more beliefs than `max_beliefs` is rebuilt with `K` one lower, so a larger bound
/// would only be lowered again, plan after plan.
///
/// ```
/// let p = csql::BeliefParams { max_uncertain: csql::MAX_BELIEF_UNCERTAIN + 1, ..Default::default() };
/// assert!(p.validate().unwrap_err().to_string().contains("belief.max_uncertain = 65"));
/// ```
pub const MAX_BELIEF_UNCERTAIN: u32 = 64;

/// The most open-loop plans a step `[belief] blind_plans` takes
/// ([`BeliefParams::validate`]): each plan is rebuilt with them, and their work grows
/// with the square of their number.
///
/// ```
/// let p = csql::BeliefParams { blind_plans: Some(csql::MAX_BLIND_PLANS + 1), ..Default::default() };
/// assert!(p.validate().unwrap_err().to_string().contains("belief.blind_plans = 4097"));
/// ```
pub const MAX_BLIND_PLANS: usize = 4096;

impl BeliefParams {
    /// Whether every setting of `[belief]` is at its default: for the settings echo,
    /// which leaves the table out then.
    ///
    /// ```
    /// let p = csql::BeliefParams::default();
    /// assert!(p.is_default());
    /// assert!(!csql::BeliefParams { trust: 2, ..p }.is_default());
    /// ```
    pub fn is_default(&self) -> bool {
        *self == BeliefParams::default()
    }

    /// The open-loop plans a step: [`BeliefParams::blind_plans`], 0 where not given.
    ///
    /// ```
    /// let p = csql::BeliefParams::default();
    /// assert_eq!(p.blind_plans(), 0);
    /// assert_eq!(csql::BeliefParams { blind_plans: Some(64), ..p }.blind_plans(), 64);
    /// ```
    pub fn blind_plans(&self) -> usize {
        self.blind_plans.unwrap_or(0)
    }

    /// The tries before a shared move is trusted: [`BeliefParams::shared_moves`], 0 (each
    /// pair apart) where not given.
    ///
    /// ```
    /// let p = csql::BeliefParams::default();
    /// assert_eq!(p.shared_moves(), 0);
    /// assert_eq!(csql::BeliefParams { shared_moves: Some(48), ..p }.shared_moves(), 48);
    /// ```
    pub fn shared_moves(&self) -> u32 {
        self.shared_moves.unwrap_or(0)
    }

    /// Check the settings as a run's settings take them, each refused with its key in
    /// `[belief]` and what is accepted: what [`crate::belief_planning`] refuses, and the bounds
    /// that keep a plan's size and its rebuilding finite (`max_uncertain` at most
    /// [`MAX_BELIEF_UNCERTAIN`], `max_beliefs` at most [`mdp::DEFAULT_MAX_BELIEFS`]).
    ///
    /// # Errors
    /// [`Error::InvalidSetting`], naming the key.
    ///
    /// ```
    /// assert!(csql::BeliefParams::default().validate().is_ok());
    /// let p = csql::BeliefParams { trust: 0, ..Default::default() };
    /// assert!(p.validate().unwrap_err().to_string().contains("belief.trust = 0"));
    /// ```
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |key: &str, value: String, expected: &'static str| {
            Err(Error::InvalidSetting {
                value: format!("belief.{key} = {value}"),
                expected,
            })
        };
        if self.max_uncertain > MAX_BELIEF_UNCERTAIN {
            return bad(
                "max_uncertain",
                self.max_uncertain.to_string(),
                "at most 64 uncertain steps in a row (csql::MAX_BELIEF_UNCERTAIN)",
            );
        }
        if self.trust == 0 {
            return bad("trust", "0".into(), "at least 1 try");
        }
        if !(self.prior.is_finite() && self.prior > 0.0) {
            return bad(
                "prior",
                self.prior.to_string(),
                "a finite weight greater than 0",
            );
        }
        if !(-MAX_BIAS..=MAX_BIAS).contains(&self.optimism) {
            return bad(
                "optimism",
                format!("{:?}", self.optimism),
                "a reward of at most 1e9 in size (csql::MAX_BIAS): a larger one drowns the world's rewards in the plan's rounding",
            );
        }
        if !(self.move_cost.is_finite() && self.move_cost >= 0.0) {
            return bad(
                "move_cost",
                self.move_cost.to_string(),
                "a finite price of at least 0 reward units",
            );
        }
        if self.blind_plans() > MAX_BLIND_PLANS {
            return bad(
                "blind_plans",
                self.blind_plans().to_string(),
                "at most 4096 open-loop plans a step (csql::MAX_BLIND_PLANS)",
            );
        }
        if !(1..=mdp::DEFAULT_MAX_BELIEFS).contains(&self.max_beliefs) {
            return bad(
                "max_beliefs",
                self.max_beliefs.to_string(),
                "1 to 1000000 beliefs (mdp::DEFAULT_MAX_BELIEFS)",
            );
        }
        Ok(())
    }
}
