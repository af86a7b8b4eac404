//! What costly sensing is, for the reference points and the belief plan alike: what an
//! agent may measure and at what price ([`SensingMenu`]), when it decides
//! ([`SensingRule`]), the settings of a search over beliefs ([`ReferenceOptions`]) and
//! why one cannot be made ([`ReferenceError`]). It depends on the world's traits only, so
//! that `belief` and `reference` both use it and neither uses the other's terms.

use crate::sensing::Feature;
use crate::world::Sensors;

/// The rounding of belief probabilities for telling beliefs apart: `2^-40`.
pub const BELIEF_QUANTUM: f64 = 1.0 / 1_099_511_627_776.0;
/// The default cap on the beliefs of [`best_sensing`](crate::best_sensing) (nodes of its
/// graph). On the 4x4 slippery lake 685,436 beliefs (K = 8) take 1.1 GB and a minute on
/// one core.
pub const DEFAULT_MAX_BELIEFS: usize = 1_000_000;
/// The default cap on the plans [`open_loop`](crate::open_loop) keeps at each step.
pub const DEFAULT_MAX_PLANS: usize = 2_000;
/// The most features [`SensingMenu::Features`] takes under [`SensingRule::WithMove`] (it
/// tries every subset of them with every move).
pub const MAX_MENU_FEATURES: usize = 12;

/// What an agent may measure, and at what price (reward units).
///
/// ```
/// let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions {
///     sensing: Some(mdp::SensingModel::Factors),
///     factor_costs: Some(vec![0.025, 0.025]),
///     ..Default::default()
/// }).unwrap();
/// assert_eq!(mdp::SensingMenu::whole(&lake), mdp::SensingMenu::Whole { price: 0.05 });
/// assert_eq!(mdp::SensingMenu::whole(&lake).whole_price(&lake), 0.05);
/// assert_eq!(mdp::SensingMenu::Features.whole_price(&lake), 0.05);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SensingMenu {
    /// One measurement reveals the state, at this price.
    Whole {
        /// The price of one measurement (finite, at least 0).
        price: f64,
    },
    /// Any set of the world's features, each at its price; the whole state is all of them.
    Features,
}

impl SensingMenu {
    /// The whole state at the sum of the world's feature prices.
    ///
    /// ```
    /// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions {
    ///     sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
    /// assert_eq!(mdp::SensingMenu::whole(&w), mdp::SensingMenu::Whole { price: 2.0 });
    /// ```
    pub fn whole<W: Sensors>(world: &W) -> SensingMenu {
        let price = (0..world.num_features())
            .map(|f| world.price(Feature(f as u32)))
            .sum();
        SensingMenu::Whole { price }
    }

    /// What measuring the whole state costs: the price of [`SensingMenu::Whole`], or the
    /// sum of the feature prices.
    ///
    /// ```
    /// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
    /// assert_eq!(mdp::SensingMenu::Whole { price: 0.5 }.whole_price(&w), 0.5);
    /// ```
    pub fn whole_price<W: Sensors>(&self, world: &W) -> f64 {
        match *self {
            SensingMenu::Whole { price } => price,
            SensingMenu::Features => match SensingMenu::whole(world) {
                SensingMenu::Whole { price } => price,
                SensingMenu::Features => 0.0,
            },
        }
    }
}

/// When the decision to sense is taken (see [`reference_points`](crate::reference_points)).
///
/// ```
/// assert_ne!(mdp::SensingRule::WithMove, mdp::SensingRule::AfterOutcome);
/// assert_eq!(mdp::SensingRule::WithMove.name(), "with-move");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SensingRule {
    /// Chosen with the move, before its outcome; paid even when the move ends the episode.
    WithMove,
    /// Chosen after the outcome, one measurement at a time; nothing once the episode ended.
    AfterOutcome,
}

impl SensingRule {
    /// A short name: `with-move` or `after-outcome`.
    ///
    /// ```
    /// assert_eq!(mdp::SensingRule::AfterOutcome.name(), "after-outcome");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            SensingRule::WithMove => "with-move",
            SensingRule::AfterOutcome => "after-outcome",
        }
    }
}

/// The settings of the reference points.
///
/// ```
/// let o = mdp::ReferenceOptions::default();
/// assert_eq!((o.horizon, o.max_uncertain), (100, Some(3)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReferenceOptions {
    /// `H`: the most moves an episode has (at least 1); it is truncated after them.
    pub horizon: u32,
    /// `K`: the most steps in a row after which the agent may be uncertain of the state
    /// (its belief has more than one state); `None` is no bound but the horizon, and then
    /// the search is exact over every policy but may well pass the cap on beliefs. A step after which the agent is certain (it measured,
    /// or the move could lead to one state only) resets the count.
    pub max_uncertain: Option<u32>,
    /// The most beliefs [`best_sensing`](crate::best_sensing) may visit before it refuses.
    pub max_beliefs: usize,
    /// The most plans [`open_loop`](crate::open_loop) keeps at each step; beyond it the value is a lower
    /// bound ([`OpenLoop::exact`](crate::OpenLoop::exact) is false).
    pub max_plans: usize,
}

impl Default for ReferenceOptions {
    fn default() -> Self {
        ReferenceOptions {
            horizon: 100,
            max_uncertain: Some(3),
            max_beliefs: DEFAULT_MAX_BELIEFS,
            max_plans: DEFAULT_MAX_PLANS,
        }
    }
}

/// Why a reference point could not be computed.
///
/// ```
/// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
/// let o = mdp::ReferenceOptions { horizon: 0, ..Default::default() };
/// let err = mdp::open_loop(&w, &o).unwrap_err();
/// assert!(err.to_string().contains("horizon"), "{err}");
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ReferenceError {
    /// A setting out of its range.
    #[error("{what}: {problem}")]
    BadSetting {
        /// Which setting.
        what: &'static str,
        /// What is wrong.
        problem: String,
    },
    /// Something of the world the computation cannot use.
    #[error("the world: {0}")]
    BadWorld(String),
    /// The belief graph grew past its cap.
    #[error(
        "more than {cap} beliefs are reachable with at most {k} uncertain steps in a row; lower the bound or raise the cap"
    )]
    TooManyBeliefs {
        /// The cap.
        cap: usize,
        /// The bound on uncertain steps, as text (`unbounded` for none).
        k: String,
    },
    /// No policy keeps within the bound on uncertain steps.
    #[error(
        "no policy keeps the agent uncertain for at most {k} steps in a row (measuring every feature does not tell some states apart)"
    )]
    Infeasible {
        /// The bound.
        k: u32,
    },
    /// The caller asked to stop ([`BeliefPlan::build_unless`](crate::BeliefPlan::build_unless)).
    #[error("stopped from outside while the plan was built")]
    Stopped,
}

/// A setting that cannot be used, and why.
pub(crate) fn bad(what: &'static str, problem: impl Into<String>) -> ReferenceError {
    ReferenceError::BadSetting {
        what,
        problem: problem.into(),
    }
}

/// Refuse a horizon of 0 moves.
pub(crate) fn check_horizon(options: &ReferenceOptions) -> Result<(), ReferenceError> {
    if options.horizon == 0 {
        return Err(bad("horizon", "0 moves; an episode needs at least one"));
    }
    Ok(())
}

/// Refuse a whole-state price that is not a finite number of at least 0.
pub(crate) fn check_menu(menu: SensingMenu) -> Result<(), ReferenceError> {
    if let SensingMenu::Whole { price } = menu
        && !(price.is_finite() && price >= 0.0)
    {
        return Err(bad("price", format!("{price} is not a finite number >= 0")));
    }
    Ok(())
}
