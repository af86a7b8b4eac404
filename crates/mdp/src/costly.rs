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
    /// The most bytes a belief graph ([`best_sensing`](crate::best_sensing),
    /// [`BeliefPlan`](crate::BeliefPlan)) may be counted at ([`PlanSize::bytes`]):
    /// one that would pass it stops with [`ReferenceError::TooLarge`]
    /// ([`DEFAULT_MAX_PLAN_BYTES`] by default).
    pub max_bytes: usize,
}

/// The most bytes a belief graph may be counted at by default: 1.5 GB, so that with what
/// else a process holds no plan takes it past 2 GB (`docs/costly.md`, "The memory of a
/// plan", measures what a plan takes against what it is counted at).
///
/// ```
/// assert_eq!(mdp::ReferenceOptions::default().max_bytes, mdp::DEFAULT_MAX_PLAN_BYTES);
/// ```
pub const DEFAULT_MAX_PLAN_BYTES: usize = 1_500_000_000;

impl Default for ReferenceOptions {
    fn default() -> Self {
        ReferenceOptions {
            horizon: 100,
            max_uncertain: Some(3),
            max_beliefs: DEFAULT_MAX_BELIEFS,
            max_plans: DEFAULT_MAX_PLANS,
            max_bytes: DEFAULT_MAX_PLAN_BYTES,
        }
    }
}

/// What a belief graph holds, counted as it is built ([`BeliefPlan::size`](crate::BeliefPlan::size)): the measure
/// its memory is bounded in ([`ReferenceOptions::max_bytes`]).
///
/// ```
/// let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
/// let model = mdp::CostlyModel::of(&lake).unwrap();
/// let plan = mdp::BeliefPlan::build(&model, &Default::default(), &[mdp::StateId(0)]).unwrap();
/// let size = plan.size();
/// assert_eq!(size.beliefs, plan.nodes());
/// assert!(size.edges > 0 && size.bytes() > size.beliefs * mdp::PlanSize::BYTES_PER_BELIEF);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PlanSize {
    /// The beliefs (nodes of the graph).
    pub beliefs: usize,
    /// The states of every belief, summed (a belief over three states counts three).
    pub belief_states: usize,
    /// The choices of every node, summed.
    pub choices: usize,
    /// The edges: the weighted children of every choice, summed.
    pub edges: usize,
}

impl PlanSize {
    /// The bytes a belief is counted at, beside its states, choices and edges: its entry
    /// in the index of beliefs, its slots in the per-node tables, its values in value
    /// iteration and the plan's copy (measured: `docs/costly.md`, "The memory of a plan").
    pub const BYTES_PER_BELIEF: usize = 300;
    /// The bytes a state of a belief is counted at: its probability, its key in the
    /// index and its place in the plan's copy.
    pub const BYTES_PER_BELIEF_STATE: usize = 64;
    /// The bytes a choice is counted at (the choice and its list of children).
    pub const BYTES_PER_CHOICE: usize = 48;
    /// The bytes an edge (a weighted child of a choice) is counted at.
    pub const BYTES_PER_EDGE: usize = 24;

    /// The bytes the graph is counted at: each belief, state, choice and edge at its
    /// `BYTES_PER_*` (saturating).
    ///
    /// ```
    /// let s = mdp::PlanSize { beliefs: 1, belief_states: 1, choices: 0, edges: 0 };
    /// assert_eq!(s.bytes(), mdp::PlanSize::BYTES_PER_BELIEF + mdp::PlanSize::BYTES_PER_BELIEF_STATE);
    /// ```
    pub fn bytes(&self) -> usize {
        [
            (self.beliefs, Self::BYTES_PER_BELIEF),
            (self.belief_states, Self::BYTES_PER_BELIEF_STATE),
            (self.choices, Self::BYTES_PER_CHOICE),
            (self.edges, Self::BYTES_PER_EDGE),
        ]
        .iter()
        .fold(0usize, |sum, &(n, b)| {
            sum.saturating_add(n.saturating_mul(b))
        })
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
    /// The belief graph would be counted at more bytes than its bound
    /// ([`ReferenceOptions::max_bytes`]).
    #[error(
        "the belief graph would pass {max_bytes} bytes ({} beliefs over {} states, {} choices, {} edges so far, with at most {k} uncertain steps in a row); lower the bound on uncertain steps or the cap on beliefs",
        size.beliefs,
        size.belief_states,
        size.choices,
        size.edges
    )]
    TooLarge {
        /// The bound.
        max_bytes: usize,
        /// What the graph held when it passed it.
        size: PlanSize,
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
