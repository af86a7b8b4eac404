//! Plans over beliefs for costly sensing: the finite graph of beliefs an agent reaches
//! when at most `K` steps in a row leave it uncertain of the state, and the best choice
//! (a move, what to measure) at each of them, found by finite-horizon value iteration.
//!
//! The model is a [`CostlyModel`]: a world's dynamics, rewards and readings read once
//! ([`CostlyModel::of`]), or tables an agent has learned ([`CostlyModel::from_parts`]).
//! [`best_sensing`](crate::best_sensing) and [`sensing_ceiling`](crate::sensing_ceiling)
//! value the start of a world's model; a [`BeliefPlan`] keeps the whole graph, so that an
//! agent can follow it step by step: [`BeliefPlan::point`] for a known state,
//! [`BeliefPlan::decide`] for the best choice, [`BeliefPlan::follow`] for the belief the
//! readings lead to (specification 6.13).
//!
//! ```
//! use mdp::{BeliefPlan, CostlyModel, Decision, PlanOptions, SensingMenu, StateId};
//! let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
//! let model = CostlyModel::of(&lake).unwrap();
//! let opts = PlanOptions { menu: SensingMenu::Whole { price: 0.05 }, ..PlanOptions::default() };
//! let plan = BeliefPlan::build(&model, &opts, &[StateId(0)]).unwrap();
//! let start = plan.point(StateId(0)).unwrap();
//! assert!((plan.value(start) - 1.0).abs() < 1e-12); // deterministic: never measure
//! let (_, Decision::Move { measure, .. }) = plan.decide(start).unwrap() else { panic!() };
//! assert_eq!(measure, 0);
//! ```

use std::collections::BTreeMap;

use crate::costly::{
    BELIEF_QUANTUM, MAX_MENU_FEATURES, PlanSize, ReferenceError, ReferenceOptions, SensingMenu,
    SensingRule, bad, check_horizon, check_menu,
};
use crate::process::{ActionId, StateId};
use crate::sensing::Feature;
use crate::world::World;

/// How far a pair's next-state probabilities may sum above 1 (rounding).
const SUM_TOLERANCE: f64 = 1e-9;

/// A model for costly sensing: for every non-terminal state and action the expected
/// reward and the non-terminal next states with their probabilities (the rest of the
/// mass ends the episode), what each feature reads in each state and its price (reward
/// units), the start distribution, and the pairs after which an agent must measure
/// every feature.
///
/// ```
/// let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
/// let m = mdp::CostlyModel::of(&lake).unwrap();
/// assert_eq!((m.num_states(), m.num_actions()), (16, 4));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CostlyModel {
    pub(crate) n: usize,
    pub(crate) na: usize,
    pub(crate) terminal: Vec<bool>,
    /// Expected reward of `(s, a)`, at `s * na + a`.
    pub(crate) reward: Vec<f64>,
    /// Non-terminal next states of `(s, a)` with their probabilities, sorted by state.
    pub(crate) next: Vec<Vec<(u32, f64)>>,
    /// Whether `(s, a)` may be taken only with `s` known, every feature measured after.
    pub(crate) must_measure: Vec<bool>,
    pub(crate) prices: Vec<f64>,
    /// What feature `f` reads in state `s`, at `s * nf + f`.
    pub(crate) readings: Vec<u32>,
    pub(crate) start: Vec<(f64, u32)>,
}

/// The tables of a [`CostlyModel`] given by hand ([`CostlyModel::from_parts`]); pairs are
/// indexed `s * num_actions + a`.
///
/// ```
/// // One state, one action that ends the episode with reward 1.
/// let parts = mdp::ModelParts {
///     num_actions: 1,
///     terminal: vec![false],
///     reward: vec![1.0],
///     next: vec![vec![]],
///     must_measure: vec![false],
///     prices: vec![0.5],
///     readings: vec![0],
///     start: vec![(1.0, 0)],
/// };
/// assert!(mdp::CostlyModel::from_parts(parts).is_ok());
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ModelParts {
    /// Actions in every state.
    pub num_actions: usize,
    /// Whether each state is terminal (its length is the number of states).
    pub terminal: Vec<bool>,
    /// The expected reward of each pair (ignored for terminal states).
    pub reward: Vec<f64>,
    /// Each pair's non-terminal next states `(state, probability)`, sorted by state, the
    /// probabilities summing to at most 1 (the rest ends the episode).
    pub next: Vec<Vec<(u32, f64)>>,
    /// The pairs an agent may take only from the state known for certain, and after
    /// which it measures every feature (pairs it has not learned yet).
    pub must_measure: Vec<bool>,
    /// Each feature's price, in reward units.
    pub prices: Vec<f64>,
    /// What feature `f` reads in state `s`, at `s * prices.len() + f`.
    pub readings: Vec<u32>,
    /// The start distribution `(probability, state)`.
    pub start: Vec<(f64, u32)>,
}

impl CostlyModel {
    /// The model of a world: its outcomes merged, rewards averaged, readings and prices.
    ///
    /// ```
    /// let w = mdp::builtin_world("frozenlake8x8", &mdp::WorldOptions::default()).unwrap();
    /// assert_eq!(mdp::CostlyModel::of(&w).unwrap().num_states(), 64);
    /// ```
    pub fn of<W: World>(world: &W) -> Result<CostlyModel, ReferenceError> {
        let n = world.num_states();
        let na = world.num_actions();
        if n == 0 || na == 0 {
            return Err(ReferenceError::BadWorld(
                "it has no states or no actions".to_string(),
            ));
        }
        let terminal: Vec<bool> = (0..n)
            .map(|s| world.is_terminal(StateId(s as u32)))
            .collect();
        let mut reward = vec![0.0; n * na];
        let mut next = vec![Vec::new(); n * na];
        let mut out = Vec::new();
        for s in 0..n {
            if terminal[s] {
                continue;
            }
            for a in 0..na {
                world.outcomes(StateId(s as u32), ActionId(a as u32), &mut out);
                let mut merged: BTreeMap<u32, f64> = BTreeMap::new();
                let mut r = 0.0;
                for (p, step) in &out {
                    if !(p.is_finite() && *p >= 0.0 && step.reward.is_finite()) {
                        return Err(ReferenceError::BadWorld(format!(
                            "state {s}, action {a}: an outcome has probability {p} and reward {}",
                            step.reward
                        )));
                    }
                    if step.next.index() >= n {
                        return Err(ReferenceError::BadWorld(format!(
                            "state {s}, action {a} leads to state {}, which does not exist",
                            step.next
                        )));
                    }
                    r += p * step.reward;
                    if !step.terminated && !terminal[step.next.index()] && *p > 0.0 {
                        *merged.entry(step.next.0).or_insert(0.0) += p;
                    }
                }
                reward[s * na + a] = r;
                next[s * na + a] = merged.into_iter().collect();
            }
        }
        let nf = world.num_features();
        let prices: Vec<f64> = (0..nf).map(|f| world.price(Feature(f as u32))).collect();
        let mut readings = Vec::with_capacity(n * nf);
        for s in 0..n {
            for f in 0..nf {
                readings.push(world.read(StateId(s as u32), Feature(f as u32)).0);
            }
        }
        let start = world
            .start_distribution()
            .into_iter()
            .map(|(p, s)| (p, s.0))
            .collect();
        CostlyModel::from_parts(ModelParts {
            num_actions: na,
            terminal,
            reward,
            next,
            must_measure: vec![false; n * na],
            prices,
            readings,
            start,
        })
    }

    /// A model from its tables, each checked: lengths, probabilities, prices, states.
    ///
    /// ```
    /// let bad = mdp::ModelParts { num_actions: 1, terminal: vec![false], ..Default::default() };
    /// let err = mdp::CostlyModel::from_parts(bad).unwrap_err();
    /// assert!(err.to_string().contains("reward"), "{err}");
    /// ```
    pub fn from_parts(parts: ModelParts) -> Result<CostlyModel, ReferenceError> {
        let ModelParts {
            num_actions: na,
            terminal,
            reward,
            next,
            must_measure,
            prices,
            readings,
            start,
        } = parts;
        let n = terminal.len();
        let world = |text: String| ReferenceError::BadWorld(text);
        if n == 0 || na == 0 {
            return Err(world("it has no states or no actions".to_string()));
        }
        let pairs = n * na;
        for (name, len) in [
            ("reward", reward.len()),
            ("next", next.len()),
            ("must_measure", must_measure.len()),
        ] {
            if len != pairs {
                return Err(world(format!(
                    "{name} has {len} entries for {pairs} pairs of a state and an action"
                )));
            }
        }
        if readings.len() != n * prices.len() {
            return Err(world(format!(
                "readings has {} entries for {n} states and {} features",
                readings.len(),
                prices.len()
            )));
        }
        if let Some((f, p)) = prices
            .iter()
            .enumerate()
            .find(|(_, p)| !(p.is_finite() && **p >= 0.0))
        {
            return Err(world(format!(
                "feature {f} has price {p}; prices must be finite and >= 0"
            )));
        }
        for i in 0..pairs {
            let (s, a) = (i / na, i % na);
            if terminal[s] {
                continue;
            }
            if !reward[i].is_finite() {
                return Err(world(format!(
                    "state {s}, action {a}: reward {}",
                    reward[i]
                )));
            }
            let mut sum = 0.0;
            let mut last = None;
            for &(t, p) in &next[i] {
                if t as usize >= n || terminal[t as usize] {
                    return Err(world(format!(
                        "state {s}, action {a} goes on to state {t}, which is not a non-terminal state"
                    )));
                }
                if !(p.is_finite() && p > 0.0) || last.is_some_and(|l| l >= t) {
                    return Err(world(format!(
                        "state {s}, action {a}: next states must be sorted, each once, with probabilities > 0 (state {t}, {p})"
                    )));
                }
                last = Some(t);
                sum += p;
            }
            if sum > 1.0 + SUM_TOLERANCE {
                return Err(world(format!(
                    "state {s}, action {a}: next-state probabilities sum to {sum} > 1"
                )));
            }
        }
        let mut kept = Vec::new();
        for (p, s) in start {
            if s as usize >= n || terminal[s as usize] || !(p.is_finite() && p >= 0.0) {
                return Err(world(format!(
                    "the start distribution has ({p}, {s}): a start must be a non-terminal state with a probability"
                )));
            }
            if p > 0.0 {
                kept.push((p, s));
            }
        }
        if kept.is_empty() {
            return Err(world("the start distribution is empty".to_string()));
        }
        Ok(CostlyModel {
            n,
            na,
            terminal,
            reward,
            next,
            must_measure,
            prices,
            readings,
            start: kept,
        })
    }

    /// Its states.
    ///
    /// ```
    /// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
    /// assert_eq!(mdp::CostlyModel::of(&w).unwrap().num_states(), 16);
    /// ```
    pub fn num_states(&self) -> usize {
        self.n
    }

    /// Its actions.
    ///
    /// ```
    /// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
    /// assert_eq!(mdp::CostlyModel::of(&w).unwrap().num_actions(), 4);
    /// ```
    pub fn num_actions(&self) -> usize {
        self.na
    }

    pub(crate) fn pair(&self, s: u32, a: usize) -> usize {
        s as usize * self.na + a
    }

    /// The expected value over the start distribution of a per-state value.
    pub(crate) fn at_start(&self, v: impl Fn(u32) -> f64) -> f64 {
        self.start.iter().map(|&(p, s)| p * v(s)).sum()
    }

    /// What action `a` does from belief `b`: `reward` plus its expected reward, whether
    /// some pair of it must be measured, and the sub-distribution of the non-terminal
    /// states it leads to (sorted by state, no zeros; its mass is the chance the episode
    /// goes on).
    pub(crate) fn successor(
        &self,
        b: &[(u32, f64)],
        a: usize,
        mut reward: f64,
    ) -> (f64, bool, Belief) {
        let mut forced = false;
        let mut next: BTreeMap<u32, f64> = BTreeMap::new();
        for &(s, p) in b {
            let pair = self.pair(s, a);
            reward += p * self.reward[pair];
            forced |= self.must_measure[pair];
            for &(t, q) in &self.next[pair] {
                *next.entry(t).or_insert(0.0) += p * q;
            }
        }
        let next: Belief = next.into_iter().filter(|x| x.1 > 0.0).collect();
        (reward, forced, next)
    }

    /// [`probes`](CostlyModel::probes) for a search under `rule`: with the move every
    /// subset of them is a choice, so more than [`MAX_MENU_FEATURES`] are refused.
    pub(crate) fn probes_under(
        &self,
        menu: SensingMenu,
        rule: SensingRule,
    ) -> Result<Vec<Probe>, ReferenceError> {
        let probes = self.probes(menu);
        if rule == SensingRule::WithMove && probes.len() > MAX_MENU_FEATURES {
            return Err(bad(
                "sensing menu",
                format!(
                    "{} features; with the move at most {MAX_MENU_FEATURES} are tried in every subset (measure the whole state instead)",
                    probes.len()
                ),
            ));
        }
        Ok(probes)
    }

    pub(crate) fn probes(&self, menu: SensingMenu) -> Vec<Probe> {
        match menu {
            SensingMenu::Whole { price } => vec![Probe {
                price,
                feature: None,
            }],
            SensingMenu::Features => (0..self.prices.len())
                .map(|f| Probe {
                    price: self.prices[f],
                    feature: Some(f),
                })
                .collect(),
        }
    }
}

/// A belief: `(state, probability)` sorted by state, summing to 1.
pub(crate) type Belief = Vec<(u32, f64)>;
/// A belief's key: probabilities rounded to multiples of [`BELIEF_QUANTUM`].
type Key = Vec<(u32, u64)>;

fn key(b: &[(u32, f64)]) -> Key {
    b.iter()
        .map(|&(s, p)| (s, (p / BELIEF_QUANTUM).round() as u64))
        .collect()
}

/// Normalise a sub-distribution sorted by state; its mass.
pub(crate) fn normalise(mut b: Belief) -> (f64, Belief) {
    let total: f64 = b.iter().map(|x| x.1).sum();
    for x in &mut b {
        x.1 /= total;
    }
    (total, b)
}

/// A probe: one thing that can be measured, with its price and what each state reads.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Probe {
    pub(crate) price: f64,
    /// `None`: the state itself (the whole state).
    pub(crate) feature: Option<usize>,
}

impl Probe {
    pub(crate) fn read(&self, m: &CostlyModel, s: u32) -> u32 {
        match self.feature {
            None => s,
            Some(f) => m.readings[s as usize * m.prices.len() + f],
        }
    }
}

/// The probes of a bit set over the menu ([`EVERY_PROBE`]: all of them, however many).
pub(crate) fn members(mask: u32, probes: usize) -> impl Iterator<Item = usize> {
    (0..probes).filter(move |&j| mask == EVERY_PROBE || (j < 32 && mask >> j & 1 == 1))
}

/// The bit set of [`Decision::Move`] that stands for every probe of the menu, however
/// many there are.
///
/// ```
/// assert_eq!(mdp::EVERY_PROBE, u32::MAX);
/// ```
pub const EVERY_PROBE: u32 = u32::MAX;

/// Split a sub-distribution (sorted by state) by what the probes in `set` read: the
/// parts' masses (of the whole) and normalised beliefs, in the order of the readings.
pub(crate) fn split(
    m: &CostlyModel,
    probes: &[Probe],
    set: &[usize],
    b: &[(u32, f64)],
) -> Vec<(f64, Belief)> {
    if set.is_empty() {
        return vec![normalise(b.to_vec())];
    }
    let mut parts: BTreeMap<Vec<u32>, Belief> = BTreeMap::new();
    for &(s, p) in b {
        let r: Vec<u32> = set.iter().map(|&j| probes[j].read(m, s)).collect();
        parts.entry(r).or_default().push((s, p));
    }
    parts.into_values().map(normalise).collect()
}

/// What an agent does at a node of a [`BeliefPlan`].
///
/// ```
/// let d = mdp::Decision::Move { action: mdp::ActionId(2), measure: 0b11 };
/// assert_ne!(d, mdp::Decision::Act);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Decision {
    /// Make this move. Under [`SensingRule::WithMove`], measure the probes of the bit set
    /// `measure` with it (bit `j` is probe `j` of the menu: feature `j`, or the whole
    /// state for [`SensingMenu::Whole`]); [`EVERY_PROBE`] when the pair must be measured.
    /// Under [`SensingRule::AfterOutcome`], `measure` is 0, or [`EVERY_PROBE`] when the
    /// pair must be measured (then every probe is read if the episode goes on).
    Move {
        /// The action.
        action: ActionId,
        /// The probes measured, as a bit set over the menu.
        measure: u32,
    },
    /// Under [`SensingRule::AfterOutcome`]: measure probe `j` now.
    Measure(usize),
    /// Under [`SensingRule::AfterOutcome`]: measure nothing more and choose a move.
    Act,
    /// Measure nothing for the rest of the episode: make the moves of
    /// [`BeliefPlan::blind_moves`], an open-loop plan from the node's belief (a choice of
    /// every node where the agent is to move, with [`PlanOptions::blind_plans`]).
    Blind,
}

/// One choice at a node: what it is, an immediate reward (net of prices) and weighted
/// children.
struct Choice {
    decision: Decision,
    reward: f64,
    children: Vec<(f64, usize)>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Kind {
    /// The agent chooses a move (and, under the rule with the move, what to measure).
    Act,
    /// Under the rule after the outcome: the agent chooses to measure one more probe or
    /// to stop and act.
    Sense,
}

pub(crate) struct Graph {
    keys: BTreeMap<(Kind, Key, u32), usize>,
    /// The beliefs (an expanded one is emptied unless they are kept).
    beliefs: Vec<Belief>,
    /// A state of each belief, which stands for its readings.
    first: Vec<u32>,
    /// How many states each belief has.
    sizes: Vec<usize>,
    kinds: Vec<Kind>,
    counts: Vec<u32>,
    choices: Vec<Vec<Choice>>,
    cap: usize,
    /// What the graph holds so far, and the most bytes it may be counted at.
    size: PlanSize,
    max_bytes: usize,
    k_text: String,
}

impl Graph {
    /// The node of a belief with its count of uncertain steps (0 if certain).
    fn node(&mut self, kind: Kind, b: Belief, count: u32) -> Result<usize, ReferenceError> {
        let count = if b.len() == 1 { 0 } else { count };
        let k = (kind, key(&b), count);
        if let Some(&i) = self.keys.get(&k) {
            return Ok(i);
        }
        if self.beliefs.len() >= self.cap {
            return Err(ReferenceError::TooManyBeliefs {
                cap: self.cap,
                k: self.k_text.clone(),
            });
        }
        self.size.beliefs += 1;
        self.size.belief_states += b.len();
        self.check_bytes()?;
        let i = self.beliefs.len();
        self.keys.insert(k, i);
        self.sizes.push(b.len());
        self.first.push(b[0].0);
        self.beliefs.push(b);
        self.kinds.push(kind);
        self.counts.push(count);
        self.choices.push(Vec::new());
        Ok(i)
    }

    /// Refuse to grow past [`ReferenceOptions::max_bytes`].
    fn check_bytes(&self) -> Result<(), ReferenceError> {
        if self.size.bytes() > self.max_bytes {
            return Err(ReferenceError::TooLarge {
                max_bytes: self.max_bytes,
                size: self.size,
                k: self.k_text.clone(),
            });
        }
        Ok(())
    }
}

/// The graph of beliefs reachable from the point beliefs of `roots` and its values.
pub(crate) struct Solved {
    pub(crate) graph: Graph,
    pub(crate) roots: Vec<usize>,
    pub(crate) values: Vec<f64>,
    /// The expected probes of the best policy from each node, when they were counted
    /// ([`solve_counted`]); empty otherwise.
    pub(crate) probes: Vec<f64>,
    pub(crate) converged_at: u32,
    /// The open-loop plans of [`Decision::Blind`], with [`PlanOptions::blind_plans`].
    pub(crate) blind: Option<Blind>,
}

/// How many beliefs [`BeliefPlan::build_unless`] expands between two questions to its
/// `stop`: a few milliseconds of work on the largest plans.
///
/// ```
/// assert_eq!(mdp::STOP_CHECK_BELIEFS, 1024);
/// ```
pub const STOP_CHECK_BELIEFS: usize = 1024;

/// Build the graph of beliefs from `roots` and solve it (see
/// [`best_sensing`](crate::best_sensing)); with `reveal`, the relaxation of
/// [`sensing_ceiling`](crate::sensing_ceiling). With `keep`, every belief stays in the
/// graph (for a [`BeliefPlan`]). `stop` is asked every [`STOP_CHECK_BELIEFS`] beliefs
/// expanded and every step of value iteration; a yes ends the work with
/// [`ReferenceError::Stopped`].
pub(crate) fn solve(
    m: &CostlyModel,
    plan: &PlanOptions,
    roots: &[u32],
    (reveal, keep): (bool, bool),
    stop: &mut dyn FnMut() -> bool,
) -> Result<Solved, ReferenceError> {
    solve_counted(m, plan, roots, (reveal, keep, false), stop)
}

/// [`solve`]; with `count`, also the expected number of probes the best policy measures
/// from each node in the horizon's moves ([`Solved::probes`]), its choices the first best
/// of each node at each number of moves left. Values and choices are those of [`solve`]:
/// only the iteration goes on past the values' convergence, up to the horizon or until
/// the counts stop changing too.
pub(crate) fn solve_counted(
    m: &CostlyModel,
    plan: &PlanOptions,
    roots: &[u32],
    (reveal, keep, count): (bool, bool, bool),
    stop: &mut dyn FnMut() -> bool,
) -> Result<Solved, ReferenceError> {
    let PlanOptions {
        menu,
        rule,
        search: ref options,
        move_cost,
        tolerance,
        blind_plans,
    } = *plan;
    check_horizon(options)?;
    check_menu(menu)?;
    if blind_plans > 0 && options.horizon > MAX_BLIND_HORIZON {
        // The open-loop plans keep one level per move: judged before any is made.
        return Err(bad(
            "horizon",
            format!(
                "{} moves with open-loop plans; at most {MAX_BLIND_HORIZON} (one level of \
                 plans is kept per move)",
                options.horizon
            ),
        ));
    }
    for (what, v) in [("move_cost", move_cost), ("tolerance", tolerance)] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(bad(what, format!("{v}; it must be finite and >= 0")));
        }
    }
    if options.max_beliefs == 0 {
        return Err(bad("max_beliefs", "0; at least one belief is needed"));
    }
    let probes = m.probes_under(menu, rule)?;
    // With the move at most MAX_MENU_FEATURES probes, so every subset is a number.
    let subsets_end: u32 = if probes.len() < 32 {
        (1u32 << probes.len()) - 1
    } else {
        EVERY_PROBE
    };
    let all_price: f64 = probes.iter().map(|p| p.price).sum();
    let every: Vec<usize> = (0..probes.len()).collect();
    // No run has more uncertain steps in a row than moves.
    let k_max = options
        .max_uncertain
        .unwrap_or(u32::MAX)
        .min(options.horizon);
    let mut g = Graph {
        keys: BTreeMap::new(),
        beliefs: Vec::new(),
        first: Vec::new(),
        sizes: Vec::new(),
        kinds: Vec::new(),
        counts: Vec::new(),
        choices: Vec::new(),
        cap: options.max_beliefs,
        size: PlanSize::default(),
        max_bytes: options.max_bytes,
        k_text: options
            .max_uncertain
            .map_or("unbounded".to_string(), |k| k.to_string()),
    };
    // Every subset of the probes, with the move only (at most MAX_MENU_FEATURES of them).
    let subsets: Vec<u32> = match rule {
        SensingRule::WithMove => (0..=subsets_end).collect(),
        SensingRule::AfterOutcome => Vec::new(),
    };
    let blind = (blind_plans > 0).then(|| Blind::of(m, options.horizon, blind_plans, move_cost));
    let mut starts = Vec::new();
    for &s in roots {
        if s as usize >= m.n || m.terminal[s as usize] {
            return Err(ReferenceError::BadWorld(format!(
                "state {s} cannot be a root: it is not a non-terminal state"
            )));
        }
        starts.push(g.node(Kind::Act, vec![(s, 1.0)], 0)?);
    }
    let mut i = 0;
    while i < g.beliefs.len() {
        if i % STOP_CHECK_BELIEFS == 0 && stop() {
            return Err(ReferenceError::Stopped);
        }
        let b = std::mem::take(&mut g.beliefs[i]);
        let count = g.counts[i];
        let next_count = count.saturating_add(1);
        let mut choices = Vec::new();
        match g.kinds[i] {
            Kind::Act => {
                if let Some(blind) = &blind {
                    let (_, value) = blind.best(&b);
                    if value.is_finite() {
                        choices.push(Choice {
                            decision: Decision::Blind,
                            reward: value,
                            children: Vec::new(),
                        });
                    }
                }
                for a in 0..m.na {
                    let (reward, forced, next) = m.successor(&b, a, -move_cost);
                    let action = ActionId(a as u32);
                    if forced && b.len() > 1 {
                        continue; // such a pair is taken from a known state only
                    }
                    if forced {
                        // Every probe is read after the move (under the other rule, if
                        // the episode goes on).
                        let mut children = Vec::new();
                        let mut going_on = 0.0;
                        if !next.is_empty() {
                            for (w, part) in split(m, &probes, &every, &next) {
                                going_on += w;
                                children.push((w, g.node(Kind::Act, part, next_count)?));
                            }
                        }
                        let price = match rule {
                            SensingRule::WithMove => all_price,
                            SensingRule::AfterOutcome => going_on * all_price,
                        };
                        choices.push(Choice {
                            decision: Decision::Move {
                                action,
                                measure: EVERY_PROBE,
                            },
                            reward: reward - price,
                            children,
                        });
                        continue;
                    }
                    match rule {
                        SensingRule::WithMove => {
                            'subset: for &set in &subsets {
                                let members: Vec<usize> = members(set, probes.len()).collect();
                                let price: f64 = members.iter().map(|&j| probes[j].price).sum();
                                let mut children = Vec::new();
                                if !next.is_empty() {
                                    for (w, part) in split(m, &probes, &members, &next) {
                                        if part.len() > 1 && count >= k_max {
                                            if !reveal {
                                                continue 'subset;
                                            }
                                            // The relaxation: the state is told, free.
                                            for &(s, p) in &part {
                                                let point = g.node(Kind::Act, vec![(s, 1.0)], 0)?;
                                                children.push((w * p, point));
                                            }
                                            continue;
                                        }
                                        children.push((w, g.node(Kind::Act, part, next_count)?));
                                    }
                                }
                                choices.push(Choice {
                                    decision: Decision::Move {
                                        action,
                                        measure: set,
                                    },
                                    reward: reward - price,
                                    children,
                                });
                            }
                        }
                        SensingRule::AfterOutcome => {
                            let mut children = Vec::new();
                            if !next.is_empty() {
                                let (w, part) = normalise(next);
                                children.push((w, g.node(Kind::Sense, part, next_count)?));
                            }
                            choices.push(Choice {
                                decision: Decision::Move { action, measure: 0 },
                                reward,
                                children,
                            });
                        }
                    }
                }
            }
            Kind::Sense => {
                // Stop and act: allowed when certain or within the bound.
                if b.len() == 1 || count <= k_max {
                    let act = g.node(Kind::Act, b.clone(), count)?;
                    choices.push(Choice {
                        decision: Decision::Act,
                        reward: 0.0,
                        children: vec![(1.0, act)],
                    });
                } else if reveal {
                    // The relaxation: past the bound the state is told, free.
                    let mut children = Vec::new();
                    for &(s, p) in &b {
                        children.push((p, g.node(Kind::Act, vec![(s, 1.0)], 0)?));
                    }
                    choices.push(Choice {
                        decision: Decision::Act,
                        reward: 0.0,
                        children,
                    });
                }
                for (j, probe) in probes.iter().enumerate() {
                    let parts = split(m, &probes, &[j], &b);
                    if parts.len() < 2 {
                        continue; // reads alike on every state of the belief: no news
                    }
                    let mut children = Vec::new();
                    for (w, part) in parts {
                        children.push((w, g.node(Kind::Sense, part, count)?));
                    }
                    choices.push(Choice {
                        decision: Decision::Measure(j),
                        reward: -probe.price,
                        children,
                    });
                }
            }
        }
        g.size.choices += choices.len();
        g.size.edges += choices.iter().map(|c| c.children.len()).sum::<usize>();
        g.check_bytes()?;
        g.choices[i] = choices;
        if keep {
            g.beliefs[i] = b;
        }
        i += 1;
    }
    let n = g.beliefs.len();
    // Sense nodes in order of support size, so that a probe's parts (smaller) come first.
    let mut sense_order: Vec<usize> = (0..n).filter(|&i| g.kinds[i] == Kind::Sense).collect();
    sense_order.sort_by_key(|&i| (g.sizes[i], i));
    let act_nodes: Vec<usize> = (0..n).filter(|&i| g.kinds[i] == Kind::Act).collect();
    // prev: values with h - 1 moves left (0 moves left: 0 everywhere, nothing sensed).
    let mut prev = vec![0.0; n];
    let mut cur = vec![0.0; n];
    // The expected probes of the best policy, with h - 1 and h moves left.
    let (mut probes_prev, mut probes_cur) = if count {
        (vec![0.0; n], vec![0.0; n])
    } else {
        (Vec::new(), Vec::new())
    };
    let per_probe = probes.len();
    let mut converged_at = options.horizon;
    let mut values_converged = false;
    for h in 1..=options.horizon {
        if stop() {
            return Err(ReferenceError::Stopped);
        }
        if count {
            for &i in &act_nodes {
                (cur[i], probes_cur[i]) =
                    best_counted(&g.choices[i], &prev, &probes_prev, (per_probe, rule));
            }
        } else {
            for &i in &act_nodes {
                cur[i] = best_of(&g.choices[i], &prev);
            }
        }
        if rule == SensingRule::AfterOutcome {
            // A sense node with h moves left acts now (an act node at h) or probes (sense
            // nodes at h). Act nodes read sense nodes with h - 1 moves left, so `cur`
            // must hold them: act values were computed from `prev`, now sense values.
            for &i in &sense_order {
                if count {
                    (cur[i], probes_cur[i]) =
                        best_counted(&g.choices[i], &cur, &probes_cur, (per_probe, rule));
                } else {
                    cur[i] = best_of(&g.choices[i], &cur);
                }
            }
        }
        let same = if tolerance == 0.0 {
            cur == prev
        } else {
            cur.iter()
                .zip(&prev)
                .all(|(a, b)| a == b || (a - b).abs() <= tolerance)
        };
        let probes_same = probes_cur == probes_prev;
        std::mem::swap(&mut prev, &mut cur);
        std::mem::swap(&mut probes_prev, &mut probes_cur);
        if same && !values_converged {
            converged_at = h;
            values_converged = true;
        }
        if same && (!count || probes_same) {
            break;
        }
    }
    Ok(Solved {
        graph: g,
        roots: starts,
        values: prev,
        probes: probes_prev,
        converged_at,
        blind,
    })
}

/// How many probes a choice measures (of a menu of `per_probe`): those of its bit set
/// with the move; every probe after a move that must be measured (under the rule after
/// the outcome only if the episode goes on, the mass of its children); one for a probe
/// after the outcome; none to act.
fn probes_of(c: &Choice, per_probe: usize, rule: SensingRule) -> f64 {
    match c.decision {
        Decision::Move {
            measure: EVERY_PROBE,
            ..
        } => match rule {
            SensingRule::WithMove => per_probe as f64,
            SensingRule::AfterOutcome => {
                c.children.iter().map(|&(w, _)| w).sum::<f64>() * per_probe as f64
            }
        },
        Decision::Move { measure, .. } => f64::from(measure.count_ones()),
        Decision::Measure(_) => 1.0,
        Decision::Act | Decision::Blind => 0.0,
    }
}

/// The best value of the choices (`-inf` for none), as [`best_of`] gives it, and the
/// expected probes of the first choice that reaches it (`probes`: of each node, with the
/// moves left that `v` has).
fn best_counted(
    cs: &[Choice],
    v: &[f64],
    probes: &[f64],
    (per_probe, rule): (usize, SensingRule),
) -> (f64, f64) {
    let mut best = f64::NEG_INFINITY;
    let mut counted = 0.0;
    for c in cs {
        let q = value_of(c, v);
        if q > best {
            best = q;
            counted = probes_of(c, per_probe, rule)
                + c.children.iter().map(|&(w, j)| w * probes[j]).sum::<f64>();
        }
    }
    (best, counted)
}

/// The open-loop plans of [`Decision::Blind`]: built backwards over value vectors as
/// [`open_loop`](crate::open_loop) builds them, each plan of `h` moves an action followed
/// by a plan of `h - 1`, a pair that must be measured worth `-inf` (never in a plan).
pub(crate) struct Blind {
    /// The vectors of the plans of the horizon's length: each one's expected return from
    /// every state (0 at terminal states).
    top: Vec<Vec<f64>>,
    /// The plans of `h` moves at `levels[h - 1]`: the first move and the index of the
    /// rest among the plans of `h - 1` moves.
    levels: Vec<Vec<(u32, u32)>>,
}

impl Blind {
    fn of(m: &CostlyModel, horizon: u32, max_plans: usize, move_cost: f64) -> Blind {
        let mut plans: Vec<Vec<f64>> = vec![vec![0.0; m.n]];
        let mut levels = Vec::with_capacity(horizon as usize);
        for _ in 0..horizon {
            let mut candidates = Vec::with_capacity(plans.len() * m.na);
            for a in 0..m.na {
                for (j, alpha) in plans.iter().enumerate() {
                    let v: Vec<f64> = (0..m.n)
                        .map(|s| {
                            if m.terminal[s] {
                                return 0.0;
                            }
                            let i = m.pair(s as u32, a);
                            if m.must_measure[i] {
                                return f64::NEG_INFINITY;
                            }
                            m.reward[i] - move_cost
                                + m.next[i]
                                    .iter()
                                    .map(|&(t, p)| p * alpha[t as usize])
                                    .sum::<f64>()
                        })
                        .collect();
                    candidates.push(((a as u32, j as u32), v));
                }
            }
            let mut kept = undominated_tagged(candidates);
            kept.truncate(max_plans);
            levels.push(kept.iter().map(|k| k.0).collect());
            plans = kept.into_iter().map(|k| k.1).collect();
        }
        Blind { top: plans, levels }
    }

    /// The best plan from a belief, and its expected return (`-inf` if every plan takes a
    /// pair that must be measured from a state of the belief).
    fn best(&self, b: &[(u32, f64)]) -> (usize, f64) {
        let mut best = (0, f64::NEG_INFINITY);
        for (j, alpha) in self.top.iter().enumerate() {
            let v: f64 = b.iter().map(|&(s, p)| p * alpha[s as usize]).sum();
            if v > best.1 {
                best = (j, v);
            }
        }
        best
    }

    /// The moves of plan `j` of the horizon's length, in order.
    fn moves(&self, mut j: usize) -> Vec<ActionId> {
        let mut out = Vec::with_capacity(self.levels.len());
        for level in self.levels.iter().rev() {
            let (a, rest) = level[j];
            out.push(ActionId(a));
            j = rest as usize;
        }
        out
    }
}

/// The vectors no other is at least as large as everywhere (within [`BLIND_TOLERANCE`]),
/// as the open loop of [`open_loop`](crate::open_loop) keeps them, each with its tag, for
/// vectors that may hold `-inf`; ranked by decreasing sum, ties by the vectors' order.
fn undominated_tagged<T: Copy>(candidates: Vec<(T, Vec<f64>)>) -> Vec<(T, Vec<f64>)> {
    let (tags, vectors): (Vec<T>, Vec<Vec<f64>>) = candidates.into_iter().unzip();
    // Ranked by their sums, a `-inf` (a pair that must be measured) counted as -1e6.
    let sums: Vec<f64> = vectors
        .iter()
        .map(|v| {
            v.iter()
                .map(|&x| if x.is_finite() { x } else { -1e6 })
                .sum()
        })
        .collect();
    let mut order: Vec<usize> = (0..vectors.len()).collect();
    order.sort_by(|&i, &j| {
        sums[j].total_cmp(&sums[i]).then_with(|| {
            vectors[i]
                .iter()
                .zip(&vectors[j])
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        })
    });
    let mut kept: Vec<(T, Vec<f64>)> = Vec::new();
    for i in order {
        let v = &vectors[i];
        let dominated = kept
            .iter()
            .any(|(_, k)| k.iter().zip(v).all(|(a, b)| *a >= *b - BLIND_TOLERANCE));
        if !dominated {
            kept.push((tags[i], v.clone()));
        }
    }
    kept
}

/// How much lower a vector may be somewhere and still count as dominated (rounding), as
/// in the open loop.
const BLIND_TOLERANCE: f64 = 1e-12;

fn value_of(c: &Choice, v: &[f64]) -> f64 {
    c.reward + c.children.iter().map(|&(w, j)| w * v[j]).sum::<f64>()
}

/// The best value of the choices (`-inf` for none).
fn best_of(cs: &[Choice], v: &[f64]) -> f64 {
    cs.iter()
        .map(|c| value_of(c, v))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// What a [`BeliefPlan`] is built for: the sensing menu and rule, the search's bounds,
/// and a price per move.
///
/// ```
/// let o = mdp::PlanOptions::default();
/// assert_eq!((o.menu, o.rule, o.move_cost, o.tolerance), (mdp::SensingMenu::Features, mdp::SensingRule::WithMove, 0.0, 0.0));
/// assert_eq!(o.blind_plans, 0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanOptions {
    /// What may be measured.
    pub menu: SensingMenu,
    /// When sensing is decided.
    pub rule: SensingRule,
    /// The horizon, the bound `K` on uncertain steps in a row, the cap on beliefs.
    pub search: ReferenceOptions,
    /// A price per move, in reward units (finite, at least 0): a small one makes the
    /// plan end an episode sooner where that costs nothing else, so that a plan followed
    /// step by step does not wander between choices of equal value.
    pub move_cost: f64,
    /// When value iteration stops before the horizon: 0 (exact) when a step leaves every
    /// value unchanged bit for bit; otherwise when it changes none by more than this.
    pub tolerance: f64,
    /// With more than 0: every node where the agent is to move may also stop measuring
    /// for the rest of the episode ([`Decision::Blind`]) and follow the best of the
    /// open-loop plans of the horizon's length over the model, at most this many kept a
    /// step (the undominated ones, as [`open_loop`](crate::open_loop) keeps them; a pair
    /// that must be measured is never in one); valued as that plan's expected return
    /// from the belief. 0: no such choice (the plans of before).
    pub blind_plans: usize,
}

/// The longest horizon [`PlanOptions::blind_plans`] may plan over: its open-loop plans
/// keep one level per move (up to 4096 plans each), so a horizon of 4294967295 moves once
/// asked for 103 GB.
///
/// ```
/// let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
/// let model = mdp::CostlyModel::of(&lake).unwrap();
/// let mut options = mdp::PlanOptions { blind_plans: 4, ..Default::default() };
/// options.search.horizon = mdp::MAX_BLIND_HORIZON + 1;
/// let Err(err) = mdp::BeliefPlan::build(&model, &options, &[mdp::StateId(0)]) else { panic!() };
/// assert!(err.to_string().contains("at most 10000"), "{err}");
/// ```
pub const MAX_BLIND_HORIZON: u32 = 10_000;

impl Default for PlanOptions {
    fn default() -> PlanOptions {
        PlanOptions {
            menu: SensingMenu::Features,
            rule: SensingRule::WithMove,
            search: ReferenceOptions::default(),
            move_cost: 0.0,
            tolerance: 0.0,
            blind_plans: 0,
        }
    }
}

/// A node of a [`BeliefPlan`]: a belief, whether the agent is to move or to sense, and
/// its count of uncertain steps in a row.
///
/// ```
/// let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
/// let model = mdp::CostlyModel::of(&lake).unwrap();
/// let plan = mdp::BeliefPlan::build(&model, &Default::default(), &[mdp::StateId(0)]).unwrap();
/// let node: mdp::NodeId = plan.point(mdp::StateId(0)).unwrap();
/// assert_eq!(plan.belief(node), &[(mdp::StateId(0), 1.0)]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct NodeId(pub usize);

/// The best policy within `K` uncertain steps in a row over a [`CostlyModel`], from a
/// set of known states: every belief it reaches, with its value and best choice.
///
/// Values are those of the finite-horizon problem of [`ReferenceOptions::horizon`] moves
/// (the stationary choice of an episode's first move); ties between choices go to the
/// first in the order of the actions, then of the probe sets as numbers.
pub struct BeliefPlan {
    solved: Solved,
    states: Vec<(StateId, f64)>,
    /// Offsets of each node's belief in `states`.
    offsets: Vec<usize>,
    /// The point node of each root state.
    points: BTreeMap<u32, usize>,
    probe_features: Vec<Option<usize>>,
    /// The model's readings, `s * features + f`.
    readings: Vec<u32>,
    features: usize,
}

impl BeliefPlan {
    /// The plan from the point beliefs of `roots` (each must be a non-terminal state).
    ///
    /// # Errors
    /// Those of [`best_sensing`](crate::best_sensing): a bad setting, a root that cannot
    /// be one, more beliefs than [`ReferenceOptions::max_beliefs`], a graph counted at
    /// more bytes than [`ReferenceOptions::max_bytes`] ([`ReferenceError::TooLarge`]).
    ///
    /// ```
    /// use mdp::{BeliefPlan, CostlyModel, PlanOptions, ReferenceOptions, SensingMenu, StateId};
    /// let o = mdp::WorldOptions { slide: Some(0.5), ..Default::default() };
    /// let lake = mdp::builtin_world("frozenlake4x4", &o).unwrap();
    /// let m = CostlyModel::of(&lake).unwrap();
    /// let search = ReferenceOptions { max_uncertain: Some(2), ..Default::default() };
    /// let opts = PlanOptions { menu: SensingMenu::Whole { price: 0.05 }, search, ..PlanOptions::default() };
    /// let plan = BeliefPlan::build(&m, &opts, &[StateId(0)]).unwrap();
    /// assert!((plan.value(plan.point(StateId(0)).unwrap()) - 0.90).abs() < 1e-9);
    /// ```
    pub fn build(
        model: &CostlyModel,
        options: &PlanOptions,
        roots: &[StateId],
    ) -> Result<BeliefPlan, ReferenceError> {
        BeliefPlan::build_unless(model, options, roots, &mut || false)
    }

    /// [`BeliefPlan::build`], asking `stop` every [`STOP_CHECK_BELIEFS`] beliefs expanded
    /// and every step of value iteration whether to give up (a large plan takes minutes):
    /// a yes ends the work with [`ReferenceError::Stopped`].
    ///
    /// ```
    /// use mdp::{BeliefPlan, CostlyModel, ReferenceError, StateId};
    /// # let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
    /// let model = CostlyModel::of(&lake).unwrap();
    /// let mut asked = 0;
    /// let built = BeliefPlan::build_unless(&model, &Default::default(), &[StateId(0)], &mut || {
    ///     asked += 1;
    ///     true
    /// });
    /// assert!(matches!(built, Err(ReferenceError::Stopped)) && asked == 1);
    /// ```
    pub fn build_unless(
        model: &CostlyModel,
        options: &PlanOptions,
        roots: &[StateId],
        stop: &mut dyn FnMut() -> bool,
    ) -> Result<BeliefPlan, ReferenceError> {
        let roots: Vec<u32> = roots.iter().map(|s| s.0).collect();
        let solved = solve(model, options, &roots, (false, true), stop)?;
        let menu = options.menu;
        let mut states = Vec::new();
        let mut offsets = Vec::with_capacity(solved.graph.beliefs.len() + 1);
        for b in &solved.graph.beliefs {
            offsets.push(states.len());
            states.extend(b.iter().map(|&(s, p)| (StateId(s), p)));
        }
        offsets.push(states.len());
        let points = roots
            .iter()
            .zip(&solved.roots)
            .map(|(&s, &i)| (s, i))
            .collect();
        Ok(BeliefPlan {
            probe_features: model.probes(menu).iter().map(|p| p.feature).collect(),
            solved,
            states,
            offsets,
            points,
            readings: model.readings.clone(),
            features: model.prices.len(),
        })
    }

    /// The node of a root state known for certain (`None` if it was not a root).
    ///
    /// ```
    /// # let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
    /// # let model = mdp::CostlyModel::of(&lake).unwrap();
    /// let plan = mdp::BeliefPlan::build(&model, &Default::default(), &[mdp::StateId(0)]).unwrap();
    /// assert!(plan.point(mdp::StateId(1)).is_none());
    /// ```
    pub fn point(&self, s: StateId) -> Option<NodeId> {
        self.points.get(&s.0).map(|&i| NodeId(i))
    }

    /// What the plan holds, and the bytes it is counted at ([`PlanSize::bytes`]).
    ///
    /// ```
    /// # let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
    /// # let model = mdp::CostlyModel::of(&lake).unwrap();
    /// let plan = mdp::BeliefPlan::build(&model, &Default::default(), &[mdp::StateId(0)]).unwrap();
    /// assert_eq!(plan.size().beliefs, 11);
    /// ```
    pub fn size(&self) -> PlanSize {
        self.solved.graph.size
    }

    /// How many nodes the plan has.
    ///
    /// ```
    /// # let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
    /// # let model = mdp::CostlyModel::of(&lake).unwrap();
    /// let plan = mdp::BeliefPlan::build(&model, &Default::default(), &[mdp::StateId(0)]).unwrap();
    /// assert_eq!(plan.nodes(), 11);
    /// ```
    pub fn nodes(&self) -> usize {
        self.solved.values.len()
    }

    /// The belief of a node: `(state, probability)`, sorted by state.
    ///
    /// ```
    /// # let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
    /// # let model = mdp::CostlyModel::of(&lake).unwrap();
    /// # let plan = mdp::BeliefPlan::build(&model, &Default::default(), &[mdp::StateId(0)]).unwrap();
    /// let start = plan.point(mdp::StateId(0)).unwrap();
    /// assert_eq!(plan.belief(start).len(), 1);
    /// ```
    pub fn belief(&self, node: NodeId) -> &[(StateId, f64)] {
        &self.states[self.offsets[node.0]..self.offsets[node.0 + 1]]
    }

    /// The expected costed return of the plan from a node.
    ///
    /// ```
    /// # let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
    /// # let model = mdp::CostlyModel::of(&lake).unwrap();
    /// let plan = mdp::BeliefPlan::build(&model, &Default::default(), &[mdp::StateId(14)]).unwrap();
    /// assert_eq!(plan.value(plan.point(mdp::StateId(14)).unwrap()), 1.0); // the goal is next door
    /// ```
    pub fn value(&self, node: NodeId) -> f64 {
        self.solved.values[node.0]
    }

    /// The best choice at a node (its index among the node's choices, and what it is);
    /// `None` when the node has no choice (no probe tells its states apart and the bound
    /// forbids acting uncertain).
    ///
    /// ```
    /// # let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
    /// # let model = mdp::CostlyModel::of(&lake).unwrap();
    /// let opts = mdp::PlanOptions { move_cost: 1e-6, ..Default::default() };
    /// let plan = mdp::BeliefPlan::build(&model, &opts, &[mdp::StateId(14)]).unwrap();
    /// let (_, d) = plan.decide(plan.point(mdp::StateId(14)).unwrap()).unwrap();
    /// assert_eq!(d, mdp::Decision::Move { action: mdp::ActionId(2), measure: 0 }); // right
    /// ```
    pub fn decide(&self, node: NodeId) -> Option<(usize, Decision)> {
        let v = &self.solved.values;
        let mut best: Option<(usize, f64)> = None;
        for (c, choice) in self.solved.graph.choices[node.0].iter().enumerate() {
            let q = value_of(choice, v);
            if best.is_none_or(|(_, b)| q > b) {
                best = Some((c, q));
            }
        }
        best.map(|(c, _)| (c, self.solved.graph.choices[node.0][c].decision))
    }

    /// The moves of the open-loop plan [`Decision::Blind`] follows from a node: the best
    /// for its belief among the plans of [`PlanOptions::blind_plans`], the horizon's
    /// length of them; `None` when the plan was built without them or every one of them
    /// takes a pair that must be measured.
    ///
    /// ```
    /// use mdp::{BeliefPlan, CostlyModel, Decision, PlanOptions, StateId};
    /// # let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
    /// let model = CostlyModel::of(&lake).unwrap();
    /// let opts = PlanOptions { blind_plans: 8, move_cost: 1e-6, ..PlanOptions::default() };
    /// let plan = BeliefPlan::build(&model, &opts, &[StateId(0)]).unwrap();
    /// let start = plan.point(StateId(0)).unwrap();
    /// // Deterministic: the open loop reaches the goal, worth as much as the best plan
    /// // (each paying the same price per move on the same shortest way).
    /// let moves = plan.blind_moves(start).unwrap();
    /// assert_eq!(moves.len(), 100);
    /// assert!(matches!(plan.decide(start).unwrap().1, Decision::Blind | Decision::Move { measure: 0, .. }));
    /// ```
    pub fn blind_moves(&self, node: NodeId) -> Option<Vec<ActionId>> {
        let blind = self.solved.blind.as_ref()?;
        let b: Vec<(u32, f64)> = self.belief(node).iter().map(|&(s, p)| (s.0, p)).collect();
        let (j, value) = blind.best(&b);
        value.is_finite().then(|| blind.moves(j))
    }

    /// The node a choice leads to, given what the probes it measured read in the state
    /// reached (`read(probe)`: feature `j`'s reading, or for the whole state its index).
    /// `None` when no belief of the plan agrees with the readings (the model was wrong),
    /// or the choice ends every episode.
    ///
    /// ```
    /// use mdp::{Decision, StateId};
    /// # let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() }).unwrap();
    /// # let model = mdp::CostlyModel::of(&lake).unwrap();
    /// let plan = mdp::BeliefPlan::build(&model, &Default::default(), &[StateId(0)]).unwrap();
    /// let start = plan.point(StateId(0)).unwrap();
    /// let (c, _) = plan.decide(start).unwrap();
    /// let next = plan.follow(start, c, |_| unreachable!("nothing measured")).unwrap();
    /// assert_eq!(plan.belief(next).len(), 1);
    /// ```
    pub fn follow(
        &self,
        node: NodeId,
        choice: usize,
        mut read: impl FnMut(Option<Feature>) -> u32,
    ) -> Option<NodeId> {
        let choice = self.solved.graph.choices[node.0].get(choice)?;
        let mask = match choice.decision {
            Decision::Move { measure, .. } => measure,
            Decision::Measure(j) => 1 << j,
            Decision::Act | Decision::Blind => 0,
        };
        if mask == 0 {
            // Nothing read: one belief, unless the episode ends.
            return choice.children.first().map(|&(_, j)| NodeId(j));
        }
        let probes: Vec<usize> = members(mask, self.probe_features.len()).collect();
        let wanted: Vec<u32> = probes
            .iter()
            .map(|&j| read(self.probe_features[j].map(|f| Feature(f as u32))))
            .collect();
        choice.children.iter().find_map(|&(_, j)| {
            let s = self.solved.graph.first[j];
            let agree = probes
                .iter()
                .zip(&wanted)
                .all(|(&p, &w)| match self.probe_features[p] {
                    None => s == w,
                    Some(f) => self.readings[s as usize * self.features + f] == w,
                });
            agree.then_some(NodeId(j))
        })
    }
}
