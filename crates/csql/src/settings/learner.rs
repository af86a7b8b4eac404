//! Which learner a run uses (the run setting `learner`), with its own settings: CS-QL, the paper's method and the
//! default, one of two baselines that share its sensing model and its charges, or one of
//! two learners played on episodes of the costed return.
//!
//! | `learner` | perception | type |
//! |---|---|---|
//! | `cs-ql` | CLASSIFY over descriptions refined on a decrease of V | [`crate::Classify`] |
//! | `u-tree` | a tree split by a Kolmogorov-Smirnov test on future discounted returns | [`crate::UTree`] |
//! | `full-sensing` | every sensable feature measured at every step | [`crate::FullView`] |
//! | `amrl-q` | the believed state, measured whole when the learner chooses to (not a learner of [`crate::run`]; `csrl run` plays it for a fixed number of episodes) | [`crate::AmrlParams`] |
//! | `belief` | a belief over the states a learned model allows, the features that separate them measured when a plan says it is worth their price (not a learner of [`crate::run`]; `csrl run` plays it for a fixed number of episodes) | [`crate::BeliefParams`] |
//!
//! Every learner of [`crate::run`] is judged the same way ([`crate::Judging`]): by the oracle's verdicts
//! where the world is deterministic and the run in the paper's setting (for U-Tree, whose
//! rows may depend on the last move, over every state and way of arriving there), by the
//! policy quality otherwise (specification §6); every run also reports the cost and trials
//! until the quality reached 0.95 and stayed there.
//!
//! CS-QL's strategy is a setting by name ([`StrategyKind`]); the strategy it builds
//! ([`StrategyKind::build`]) is the agent's.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::perception::sense_less::level::{PredictSensing, PredictionParams};
use crate::settings::extensions::Extensions;

/// The learner of a run with the settings that are its own: CS-QL's strategy, prediction
/// and extensions, or U-Tree's parameters. A setting of one learner cannot be given to
/// another: the settings file's keys of CS-QL with a baseline, or `[u_tree]` with CS-QL,
/// are refused when the file is read ([`crate::SettingsDraft::build`]).
///
/// ```
/// use csql::{LearnerSettings, LearnerKind, StrategyKind};
/// let l = LearnerSettings::cs_ql(StrategyKind::Eager);
/// assert_eq!(l.kind(), LearnerKind::CsQl);
/// assert_eq!(l.strategy(), Some(StrategyKind::Eager));
/// assert_eq!(LearnerSettings::from(LearnerKind::UTree).strategy(), None);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum LearnerSettings {
    /// CS-QL, the paper's method.
    CsQl(CsQlSettings),
    /// A U-Tree-like statistical splitter ([`crate::UTree`]).
    UTree(UTreeParams),
    /// Q-learning on the whole sensable view ([`crate::FullView`]).
    FullSensing,
    /// AMRL-Q ([`crate::amrl_q`]): Q-learning over the state and whether to measure it
    /// whole, played for a fixed number of episodes on the costed return (specification
    /// 6.11). `csrl run` plays it; [`crate::run`] refuses it.
    AmrlQ(crate::AmrlParams),
    /// Sensing by belief ([`crate::belief_planning`]): a learned model, a plan over
    /// beliefs, features measured when the plan says so, played for a fixed number of
    /// episodes on the costed return (specification 6.13), its features priced at the
    /// settings' `[costly] price`. `csrl run` plays it; [`crate::run`] refuses it.
    Belief(crate::BeliefParams),
}

impl LearnerSettings {
    /// CS-QL with `strategy` and otherwise the paper's settings ([`CsQlSettings::new`]).
    ///
    /// ```
    /// let l = csql::LearnerSettings::cs_ql(csql::StrategyKind::Random);
    /// assert_eq!(l.strategy(), Some(csql::StrategyKind::Random));
    /// ```
    pub fn cs_ql(strategy: StrategyKind) -> LearnerSettings {
        LearnerSettings::CsQl(CsQlSettings::new(strategy))
    }

    /// Which learner this is.
    ///
    /// ```
    /// assert_eq!(csql::LearnerSettings::FullSensing.kind(), csql::LearnerKind::FullSensing);
    /// ```
    pub fn kind(&self) -> LearnerKind {
        match self {
            LearnerSettings::CsQl(_) => LearnerKind::CsQl,
            LearnerSettings::UTree(_) => LearnerKind::UTree,
            LearnerSettings::FullSensing => LearnerKind::FullSensing,
            LearnerSettings::AmrlQ(_) => LearnerKind::AmrlQ,
            LearnerSettings::Belief(_) => LearnerKind::Belief,
        }
    }

    /// CS-QL's strategy; `None` for a baseline, which refines by none.
    ///
    /// ```
    /// assert_eq!(csql::LearnerSettings::FullSensing.strategy(), None);
    /// ```
    pub fn strategy(&self) -> Option<StrategyKind> {
        match self {
            LearnerSettings::CsQl(q) => Some(q.strategy),
            _ => None,
        }
    }
}

/// Each learner with its defaults; CS-QL with the resetting strategy, as `csrl run` has
/// it when no strategy is given.
///
/// ```
/// use csql::{LearnerSettings, LearnerKind, StrategyKind};
/// assert_eq!(LearnerSettings::from(LearnerKind::CsQl), LearnerSettings::cs_ql(StrategyKind::Resetting));
/// assert_eq!(LearnerSettings::from(LearnerKind::UTree), LearnerSettings::UTree(csql::UTreeParams::default()));
/// ```
impl From<LearnerKind> for LearnerSettings {
    fn from(kind: LearnerKind) -> LearnerSettings {
        match kind {
            LearnerKind::CsQl => LearnerSettings::cs_ql(StrategyKind::Resetting),
            LearnerKind::UTree => LearnerSettings::UTree(UTreeParams::default()),
            LearnerKind::FullSensing => LearnerSettings::FullSensing,
            LearnerKind::AmrlQ => LearnerSettings::AmrlQ(crate::AmrlParams::default()),
            LearnerKind::Belief => LearnerSettings::Belief(crate::BeliefParams::default()),
        }
    }
}

/// CS-QL's own settings: how it refines (the strategy), whether it predicts instead of
/// sensing, and its remedies beyond the paper.
///
/// ```
/// let q = csql::CsQlSettings::new(csql::StrategyKind::Lazy);
/// assert_eq!(q.random_moves, 20);
/// assert!(q.predict_sensing.is_off() && q.extensions == csql::Extensions::default());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CsQlSettings {
    /// How decreases are handled.
    pub strategy: StrategyKind,
    /// Random moves after each refinement, for the random strategy (the paper: 20; another
    /// value is refused with another strategy).
    pub random_moves: u32,
    /// Whether, and with what knowledge, the agent predicts instead of sensing (`off`,
    /// the paper's procedure, by default; see [`crate::Predicting`]).
    pub predict_sensing: PredictSensing,
    /// The confidence rule, re-check rates and navigation trials of prediction (the
    /// TOML table `[prediction]`; only with `predict_sensing` other than `off`).
    pub prediction: PredictionParams,
    /// CS-QL's remedies beyond the paper (the TOML table `[extensions]`).
    pub extensions: Extensions,
}

/// The paper's random moves after a refinement, and the default of `random_moves`.
pub(crate) const PAPER_RANDOM_MOVES: u32 = 20;

impl CsQlSettings {
    /// The paper's CS-QL with `strategy`: 20 random moves after a refinement (random
    /// strategy), no prediction, no extension.
    ///
    /// ```
    /// let q = csql::CsQlSettings::new(csql::StrategyKind::Eager);
    /// assert_eq!(q.strategy, csql::StrategyKind::Eager);
    /// ```
    pub fn new(strategy: StrategyKind) -> CsQlSettings {
        CsQlSettings {
            strategy,
            random_moves: PAPER_RANDOM_MOVES,
            predict_sensing: PredictSensing::Off,
            prediction: PredictionParams::default(),
            extensions: Extensions::default(),
        }
    }
}

/// The learner of a run.
///
/// ```
/// use csql::LearnerKind;
/// assert_eq!(LearnerKind::default(), LearnerKind::CsQl);
/// assert_eq!("u-tree".parse::<LearnerKind>().unwrap(), LearnerKind::UTree);
/// assert_eq!(LearnerKind::FullSensing.to_string(), "full-sensing");
/// assert_eq!("belief".parse::<LearnerKind>().unwrap(), LearnerKind::Belief);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LearnerKind {
    /// CS-QL (the paper's method; the default).
    #[default]
    CsQl,
    /// A U-Tree-like statistical splitter (McCallum, 1995), charged as CLASSIFY is.
    UTree,
    /// Q-learning on the whole sensable view, charged every feature at every step.
    FullSensing,
    /// AMRL-Q, measuring the whole state or not at each step, on the costed return
    /// (not a learner of [`crate::run`]: `csrl run` plays it for `episodes` episodes).
    AmrlQ,
    /// Sensing by belief, measuring what a plan over a learned model says is worth its
    /// price, on the costed return (not a learner of [`crate::run`]: `csrl run` plays it
    /// for `episodes` episodes).
    Belief,
}

impl LearnerKind {
    /// The three learners of [`crate::run`], in order (AMRL-Q and sensing by belief,
    /// played on episodes of the costed return, are not among them).
    ///
    /// ```
    /// assert_eq!(csql::LearnerKind::ALL.len(), 3);
    /// ```
    pub const ALL: [LearnerKind; 3] = [
        LearnerKind::CsQl,
        LearnerKind::UTree,
        LearnerKind::FullSensing,
    ];

    /// The setting's value: `cs-ql`, `u-tree`, `full-sensing`, `amrl-q` or `belief`.
    ///
    /// ```
    /// assert_eq!(csql::LearnerKind::CsQl.name(), "cs-ql");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            LearnerKind::CsQl => "cs-ql",
            LearnerKind::UTree => "u-tree",
            LearnerKind::FullSensing => "full-sensing",
            LearnerKind::AmrlQ => "amrl-q",
            LearnerKind::Belief => "belief",
        }
    }

    /// Whether this learner is played on episodes of the costed return (`amrl-q`,
    /// `belief`): for a fixed number of episodes, with `[costly] price`, reported by
    /// [`crate::costed_report`] rather than run by [`crate::run`].
    ///
    /// ```
    /// use csql::LearnerKind;
    /// assert!(LearnerKind::Belief.on_episodes() && LearnerKind::AmrlQ.on_episodes());
    /// assert!(!LearnerKind::CsQl.on_episodes());
    /// ```
    pub fn on_episodes(self) -> bool {
        matches!(self, LearnerKind::AmrlQ | LearnerKind::Belief)
    }

    /// Whether this is CS-QL (for serde's `skip_serializing_if`).
    ///
    /// ```
    /// assert!(csql::LearnerKind::CsQl.is_cs_ql());
    /// ```
    pub fn is_cs_ql(&self) -> bool {
        *self == LearnerKind::CsQl
    }
}

impl std::fmt::Display for LearnerKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for LearnerKind {
    type Err = Error;
    fn from_str(s: &str) -> Result<LearnerKind, Error> {
        LearnerKind::ALL
            .into_iter()
            .chain([LearnerKind::AmrlQ, LearnerKind::Belief])
            .find(|k| k.name() == s)
            .ok_or_else(|| Error::InvalidSetting {
                value: s.to_string(),
                expected: "cs-ql, u-tree, full-sensing, amrl-q or belief",
            })
    }
}

/// The U-Tree learner's parameters (the TOML table `[u_tree]`; see [`crate::UTree`]).
///
/// ```
/// let p = csql::UTreeParams::default();
/// assert_eq!((p.fringe, p.window, p.test_every, p.min_group, p.patience), (4, 2000, 25, 5, 1000));
/// assert_eq!(p.alpha, 0.01);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct UTreeParams {
    /// Candidate features of a leaf (its fringe): the cheapest ones its path lacks. They
    /// are measured, and charged, at every visit of a leaf that still collects.
    pub fringe: usize,
    /// Significance of the Kolmogorov-Smirnov test, before the Bonferroni correction for
    /// the tests made together.
    pub alpha: f64,
    /// Instances a leaf keeps (the most recent).
    pub window: usize,
    /// New instances between two tests of a leaf.
    pub test_every: usize,
    /// Fewest instances on each side of a comparison.
    pub min_group: usize,
    /// Tests after which a leaf that never split stops collecting (and measuring its
    /// fringe).
    pub patience: u32,
}

impl Default for UTreeParams {
    fn default() -> UTreeParams {
        UTreeParams {
            fringe: 4,
            alpha: 0.01,
            window: 2000,
            test_every: 25,
            min_group: 5,
            patience: 1000,
        }
    }
}

impl UTreeParams {
    /// Whether every parameter is the default (for serde's `skip_serializing_if`).
    ///
    /// ```
    /// assert!(csql::UTreeParams::default().is_default());
    /// ```
    pub fn is_default(&self) -> bool {
        *self == UTreeParams::default()
    }

    pub(crate) fn validate(&self) -> Result<(), Error> {
        let bad = |name: &str, value: String, expected: &'static str| {
            Err(Error::InvalidSetting {
                value: format!("u_tree.{name} = {value}"),
                expected,
            })
        };
        if !(1..=16).contains(&self.fringe) {
            return bad("fringe", self.fringe.to_string(), "1 to 16");
        }
        if !(self.alpha > 0.0 && self.alpha < 1.0) {
            return bad("alpha", self.alpha.to_string(), "a number in (0, 1)");
        }
        if !(2..=100_000).contains(&self.window) {
            return bad("window", self.window.to_string(), "2 to 100000");
        }
        if self.test_every == 0 {
            return bad("test_every", "0".into(), "at least 1");
        }
        if self.min_group == 0 || 2 * self.min_group > self.window {
            return bad(
                "min_group",
                self.min_group.to_string(),
                "at least 1 and at most half the window",
            );
        }
        if self.patience == 0 {
            return bad("patience", "0".into(), "at least 1");
        }
        Ok(())
    }
}

/// The four strategies of the paper by name, as read from settings and the command line.
///
/// ```
/// use csql::StrategyKind;
/// let k: StrategyKind = "lazy".parse().unwrap();
/// assert_eq!(k, StrategyKind::Lazy);
/// assert_eq!(k.to_string(), "lazy");
/// assert!("greedy".parse::<StrategyKind>().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StrategyKind {
    /// [`crate::Resetting`].
    Resetting,
    /// [`crate::Lazy`].
    Lazy,
    /// [`crate::RandomMoves`].
    Random,
    /// [`crate::Eager`].
    Eager,
}

impl StrategyKind {
    /// All four, in the paper's column order.
    ///
    /// ```
    /// assert_eq!(csql::StrategyKind::ALL.len(), 4);
    /// ```
    pub const ALL: [StrategyKind; 4] = [
        StrategyKind::Resetting,
        StrategyKind::Lazy,
        StrategyKind::Random,
        StrategyKind::Eager,
    ];

    /// The name used in settings, on the command line and in reports.
    ///
    /// ```
    /// assert_eq!(csql::StrategyKind::Random.name(), "random");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            StrategyKind::Resetting => "resetting",
            StrategyKind::Lazy => "lazy",
            StrategyKind::Random => "random",
            StrategyKind::Eager => "eager",
        }
    }
}

impl fmt::Display for StrategyKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A strategy name that is not one of the four.
///
/// ```
/// let err = "x".parse::<csql::StrategyKind>().unwrap_err();
/// assert!(err.to_string().contains("resetting"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown strategy `{0}` (expected resetting, lazy, random or eager)")]
pub struct UnknownStrategy(pub String);

impl FromStr for StrategyKind {
    type Err = UnknownStrategy;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        StrategyKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| UnknownStrategy(s.to_string()))
    }
}
