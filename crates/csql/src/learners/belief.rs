//! Sensing by belief (specification 6.13): an agent that learns a model of the world from
//! what it measures, plans over the beliefs that model lets it reach, and after each move
//! senses nothing, or only the features that separate the states it may be in, when the
//! plan says that is worth its price.
//!
//! * **The model.** Counts of the transitions from a known state: the next state when
//!   what was read tells it among the states the pair may lead to (its outcomes so far
//!   once trusted, every state before; a state inferred with nothing read is not
//!   counted, it would only confirm the model), or the end of the episode and its reward. A pair tried `n` times has the empirical
//!   outcomes with weight `n / (n + prior)` and, with the rest, an optimistic outcome
//!   that ends the episode with reward `optimism` (so untried pairs are worth trying);
//!   once trusted, the empirical outcomes alone. A pair is trusted after `trust` tries
//!   if it has shown two outcomes or more, after `2 trust` if it has shown one.
//! * **The plan.** An [`mdp::BeliefPlan`] over that model from every state known so far:
//!   the best choice of a move and of the features to measure (each at its price, in
//!   reward units) at every belief reachable with at most `max_uncertain` uncertain
//!   steps in a row. A pair not yet trusted is taken from a known state only and
//!   followed by a measurement of every feature, so that the agent learns it. The plan is rebuilt,
//!   when the agent knows its state, after the model has changed enough (a pair's count
//!   reached a power of two or `trust`, a state was seen for the first time, or a pair
//!   lost its trust), or when it lacks the state.
//! * **A wrong belief.** When something happens that the model gives probability zero (a
//!   reading no state of the belief gives, an end of episode it did not allow, or none
//!   where it foresaw one), every pair used since the agent last knew its state must be
//!   measured again `trust` times; the agent then measures every feature with its next
//!   move (or at once, when sensing follows the outcome) and moves on from what it read.
//!   So a wrong belief lasts until the first observation that contradicts it.
//!
//! ```
//! use rand::SeedableRng;
//! let o = mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), factor_costs: Some(vec![0.025, 0.025]), ..Default::default() };
//! let lake = mdp::builtin_world("frozenlake4x4", &o).unwrap();
//! let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
//! let run = csql::belief_planning(&lake, &csql::BeliefParams::default(), 1.0, mdp::SensingRule::WithMove, 200, 100, &mut rng).unwrap();
//! let s = csql::CostlySummary::of(&run);
//! assert_eq!(s.mean_last10, 1.0); // the goal, and nothing measured
//! ```

use std::collections::BTreeMap;

use mdp::{
    ActionId, BeliefPlan, CostlyModel, Decision, EVERY_PROBE, Feature, ModelParts, NodeId,
    PlanOptions, ReferenceError, ReferenceOptions, SensingMenu, SensingRule, StateId, World,
};
use rand::Rng;

use crate::learners::amrl::{Episode, Episodes};

mod moves;
use crate::observe::{KeepTrace, Observer};
use crate::settings::costed::{BeliefParams, MAX_EPISODES};
use moves::Moves;

/// Value iteration of a plan stops when a step changes no value by more than this (reward
/// units): far below any price, and far fewer steps on lakes where the values creep.
const PLAN_TOLERANCE: f64 = 1e-9;

/// What the agent has counted of one pair (a state and an action).
#[derive(Clone, Debug, Default)]
struct Counts {
    tries: u32,
    /// Tries that went on, by next state.
    next: BTreeMap<u32, u32>,
    /// The sum of the rewards of every try.
    reward: f64,
    /// Tries from which on the pair may go unmeasured, once it has shown two outcomes.
    trusted_at: u32,
}

impl Counts {
    /// How many different outcomes it has shown (an end of the episode is one).
    fn outcomes(&self) -> usize {
        self.next.len() + usize::from(self.next.values().sum::<u32>() < self.tries)
    }

    /// Whether it may go unmeasured: `trusted_at` tries, `trust` more while it has shown
    /// one outcome only (a pair of two even outcomes shows one in `trust` tries with
    /// probability `2^(1 - trust)`; in `2 trust`, `2^(1 - 2 trust)`).
    fn trusted(&self, trust: u32) -> bool {
        let extra = if self.outcomes() < 2 { trust } else { 0 };
        self.tries >= self.trusted_at.saturating_add(extra)
    }
}

struct Planner<'w, W: World + ?Sized> {
    world: &'w W,
    params: BeliefParams,
    rule: SensingRule,
    max_moves: u32,
    counts: Vec<Counts>,
    known: Vec<bool>,
    /// Whether the model changed enough since the plan was built.
    stale: bool,
    plan: Option<BeliefPlan>,
    prices: Vec<f64>,
    /// What each state reads on each feature, at `s * features + f` (as
    /// [`ModelParts::readings`]): the world's readings, read once.
    readings: Vec<u32>,
    /// The bound `K` of the plans, lowered for the rest of the run when a plan passes
    /// the cap on beliefs.
    k: u32,
    /// The most bytes a plan may be counted at ([`mdp::PlanSize::bytes`]).
    max_bytes: usize,
    /// The moves learned over every state (`[belief] shared_moves`), in place of the
    /// pairs' counts in the model.
    moves: Option<Moves>,
}

/// Run `episodes` episodes of sensing by belief (specification 6.13) and return what
/// each gave; a feature is priced at its cost times `price` reward units (a run's
/// `[costly] price`; 1 when the world's costs are its prices), and `max_moves` caps an
/// episode (and is the plan's horizon).
///
/// # Errors
/// A world or a setting the plan cannot use ([`ReferenceError`]), such as more than
/// [`mdp::MAX_MENU_FEATURES`] features measured apart.
///
/// ```
/// use rand::SeedableRng;
/// let o = mdp::WorldOptions { slide: Some(0.5), sensing: Some(mdp::SensingModel::Factors), factor_costs: Some(vec![0.025, 0.025]), ..Default::default() };
/// let lake = mdp::builtin_world("frozenlake4x4", &o).unwrap();
/// let run = |seed| {
///     let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed);
///     csql::belief_planning(&lake, &Default::default(), 1.0, mdp::SensingRule::WithMove, 30, 100, &mut rng).unwrap()
/// };
/// assert_eq!(run(3), run(3)); // the seed decides everything
/// ```
pub fn belief_planning<W: World + ?Sized, R: Rng + ?Sized>(
    world: &W,
    params: &BeliefParams,
    price: f64,
    rule: SensingRule,
    episodes: u32,
    max_moves: u32,
    rng: &mut R,
) -> Result<Vec<Episode>, ReferenceError> {
    let play = Episodes {
        episodes,
        max_moves,
    };
    belief_planning_observed(world, params, price, rule, play, rng, &mut KeepTrace)
}

/// [`belief_planning`], asking `observer` before every episode whether to go on
/// ([`Observer::keep_going`]): a no ends the run there. A plan is bounded at
/// [`mdp::DEFAULT_MAX_PLAN_BYTES`]: one that would pass it ends the run with an error
/// that names `[belief] max_uncertain` and `max_beliefs`.
pub(crate) fn belief_planning_observed<W: World + ?Sized, R: Rng + ?Sized>(
    world: &W,
    params: &BeliefParams,
    price: f64,
    rule: SensingRule,
    play: Episodes,
    rng: &mut R,
    observer: &mut dyn Observer,
) -> Result<Vec<Episode>, ReferenceError> {
    let bounded = (price, rule, mdp::DEFAULT_MAX_PLAN_BYTES);
    belief_planning_bounded(world, params, bounded, play, rng, observer)
}

/// [`belief_planning_observed`] with each plan bounded at `max_bytes`.
fn belief_planning_bounded<W: World + ?Sized, R: Rng + ?Sized>(
    world: &W,
    params: &BeliefParams,
    (price, rule, max_bytes): (f64, SensingRule, usize),
    Episodes {
        episodes,
        max_moves,
    }: Episodes,
    rng: &mut R,
    observer: &mut dyn Observer,
) -> Result<Vec<Episode>, ReferenceError> {
    check(params, price, max_moves)?;
    let n = world.num_states();
    let na = world.num_actions();
    let prices: Vec<f64> = (0..world.num_features())
        .map(|f| world.price(Feature(f as u32)) * price)
        .collect();
    let nf = world.num_features();
    let mut readings = Vec::with_capacity(n * nf);
    for s in 0..n {
        for f in 0..nf {
            readings.push(world.read(StateId(s as u32), Feature(f as u32)).0);
        }
    }
    let moves = if params.shared_moves() > 0 {
        let terminal: Vec<bool> = (0..n)
            .map(|s| world.is_terminal(StateId(s as u32)))
            .collect();
        Some(Moves::new(
            &readings,
            nf,
            &terminal,
            na,
            params.shared_moves(),
        )?)
    } else {
        None
    };
    let mut l = Planner {
        moves,
        world,
        params: *params,
        rule,
        max_moves,
        counts: vec![
            Counts {
                trusted_at: params.trust,
                ..Counts::default()
            };
            n * na
        ],
        known: vec![false; n],
        stale: true,
        plan: None,
        prices,
        readings,
        k: params.max_uncertain,
        max_bytes,
    };
    for (_, s) in world.start_distribution() {
        l.known[s.index()] = true;
    }
    let mut out = Vec::with_capacity(episodes.min(MAX_EPISODES) as usize);
    for _ in 0..episodes {
        if !observer.keep_going() {
            break;
        }
        // A plan being built asks the observer too: a no ends the run there, with the
        // episodes played before this one.
        match l.episode(rng, observer) {
            Ok(e) => out.push(e),
            Err(ReferenceError::Stopped) => break,
            Err(e) => return Err(e),
        }
    }
    Ok(out)
}

fn check(p: &BeliefParams, price: f64, max_moves: u32) -> Result<(), ReferenceError> {
    let bad = |what: &'static str, problem: String| ReferenceError::BadSetting { what, problem };
    if max_moves == 0 {
        return Err(bad("max_moves", "0; an episode needs a move".into()));
    }
    if p.blind_plans() > 0 && max_moves > mdp::MAX_BLIND_HORIZON {
        return Err(bad(
            "max_moves",
            format!(
                "{max_moves} with [belief] blind_plans = {}: the open-loop plans keep one \
                 level per move, so at most {} moves (mdp::MAX_BLIND_HORIZON)",
                p.blind_plans(),
                mdp::MAX_BLIND_HORIZON
            ),
        ));
    }
    if p.trust == 0 {
        return Err(bad(
            "trust",
            "0; a pair is trusted after at least one try".into(),
        ));
    }
    for (what, v) in [
        ("prior", p.prior),
        ("price", price),
        ("move_cost", p.move_cost),
    ] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(bad(what, format!("{v}; it must be finite and >= 0")));
        }
    }
    if p.prior == 0.0 {
        return Err(bad(
            "prior",
            "0; the optimistic outcome needs a weight".into(),
        ));
    }
    if !p.optimism.is_finite() {
        return Err(bad(
            "optimism",
            format!("{}; it must be finite", p.optimism),
        ));
    }
    if p.max_beliefs == 0 {
        return Err(bad("max_beliefs", "0; a plan needs a belief".into()));
    }
    Ok(())
}

/// Where the agent is in its plan.
enum Place {
    /// At a node of the plan.
    Node(NodeId),
    /// Off the plan: the states that agree with what it last read (or every state).
    Lost(Vec<u32>),
}

impl<W: World + ?Sized> Planner<'_, W> {
    fn na(&self) -> usize {
        self.world.num_actions()
    }

    /// The model the counts give.
    fn model(&self) -> Result<CostlyModel, ReferenceError> {
        let w = self.world;
        let n = w.num_states();
        let p = &self.params;
        let mut reward = Vec::with_capacity(self.counts.len());
        let mut next = Vec::with_capacity(self.counts.len());
        let mut must_measure = Vec::with_capacity(self.counts.len());
        let na = self.na();
        for (i, c) in self.counts.iter().enumerate() {
            // Each pair from the shared moves where they are learned, else from its counts.
            let (on, r, measure) = match &self.moves {
                Some(m) => {
                    let (s, a) = ((i / na) as u32, i % na);
                    let (on, r) = m.pair(s, a, p.prior, p.optimism);
                    (on, r, !m.trusted(a))
                }
                None => {
                    let tries = f64::from(c.tries);
                    let (weight, rest) = if c.trusted(p.trust) {
                        (1.0 / tries, 0.0)
                    } else {
                        (1.0 / (tries + p.prior), p.prior / (tries + p.prior))
                    };
                    let on = c.next.iter().map(|(&t, &k)| (t, f64::from(k) * weight));
                    (
                        on.collect(),
                        c.reward * weight + rest * p.optimism,
                        !c.trusted(p.trust),
                    )
                }
            };
            reward.push(r);
            next.push(on);
            must_measure.push(measure);
        }
        CostlyModel::from_parts(ModelParts {
            num_actions: na,
            terminal: (0..n).map(|s| w.is_terminal(StateId(s as u32))).collect(),
            reward,
            next,
            must_measure,
            prices: self.prices.clone(),
            readings: self.readings.clone(),
            start: w
                .start_distribution()
                .into_iter()
                .map(|(q, s)| (q, s.0))
                .collect(),
        })
    }

    /// Rebuild the plan from every known state, lowering `K` until it fits the cap on
    /// beliefs; a plan that passes the bound on bytes ends the run with an error naming
    /// the settings that size it.
    fn replan(&mut self, observer: &mut dyn Observer) -> Result<(), ReferenceError> {
        // The plan it replaces goes first: one plan at a time is held.
        self.plan = None;
        if let Some(m) = &mut self.moves {
            m.fit();
        }
        let model = self.model()?;
        let roots: Vec<StateId> = (0..self.known.len())
            .filter(|&s| self.known[s])
            .map(|s| StateId(s as u32))
            .collect();
        let menu = if self.params.whole_state {
            SensingMenu::Whole {
                price: self.prices.iter().sum(),
            }
        } else {
            SensingMenu::Features
        };
        loop {
            let k = self.k;
            let options = PlanOptions {
                menu,
                rule: self.rule,
                search: ReferenceOptions {
                    horizon: self.max_moves,
                    max_uncertain: Some(k),
                    max_beliefs: self.params.max_beliefs,
                    max_bytes: self.max_bytes,
                    ..ReferenceOptions::default()
                },
                move_cost: self.params.move_cost,
                tolerance: PLAN_TOLERANCE,
                blind_plans: self.params.blind_plans(),
            };
            match BeliefPlan::build_unless(&model, &options, &roots, &mut || !observer.keep_going())
            {
                Ok(plan) => {
                    self.plan = Some(plan);
                    self.stale = false;
                    return Ok(());
                }
                Err(ReferenceError::TooManyBeliefs { .. }) if k > 0 => self.k -= 1,
                Err(ReferenceError::TooLarge {
                    max_bytes, size, ..
                }) => {
                    return Err(ReferenceError::BadSetting {
                        what: "belief.max_uncertain and belief.max_beliefs",
                        problem: format!(
                            "{k} uncertain steps in a row and {} beliefs: a plan of {} beliefs over {} states with {} edges passed the bound of {max_bytes} bytes on a plan's memory (mdp::DEFAULT_MAX_PLAN_BYTES); lower max_uncertain or max_beliefs",
                            self.params.max_beliefs, size.beliefs, size.belief_states, size.edges
                        ),
                    });
                }
                Err(e) => return Err(e),
            }
        }
    }

    fn pair(&self, s: u32, a: ActionId) -> usize {
        s as usize * self.na() + a.index()
    }

    /// Count a try of `(s, a)`: the next state (`None`: the episode ended) and reward.
    fn count(&mut self, s: u32, a: ActionId, next: Option<u32>, reward: f64) {
        let i = self.pair(s, a);
        let trust = self.params.trust;
        let c = &mut self.counts[i];
        let was = c.trusted(trust);
        c.tries = c.tries.saturating_add(1);
        c.reward += reward;
        if let Some(t) = next {
            *c.next.entry(t).or_insert(0) += 1;
        }
        // With shared moves the pairs' counts are not the model: only the moves' tries
        // make it stale.
        if (c.tries.is_power_of_two() || c.trusted(trust) != was) && self.moves.is_none() {
            self.stale = true;
        }

        if let Some(t) = next
            && !self.known[t as usize]
        {
            self.known[t as usize] = true;
            self.stale = true;
        }
    }

    /// Every pair used since the agent last knew its state (from every state it may
    /// have been in) must be measured again.
    fn distrust(&mut self, path: &[(Vec<u32>, ActionId)]) {
        for (states, a) in path {
            if let Some(m) = &mut self.moves {
                m.distrust(a.index(), self.params.trust);
                self.stale = true;
            }
            for &s in states {
                let i = self.pair(s, *a);
                let c = &mut self.counts[i];
                c.trusted_at = c.tries.saturating_add(self.params.trust);
                self.stale = true;
            }
        }
    }

    /// The states the agent may be in at a place.
    fn states(&self, place: &Place) -> Vec<u32> {
        match place {
            Place::Node(n) => self
                .plan
                .as_ref()
                .expect("a node is of a plan")
                .belief(*n)
                .iter()
                .map(|x| x.0.0)
                .collect(),
            Place::Lost(states) => states.clone(),
        }
    }

    /// Whether what was read (the readings `truth` gives on `read`) tells the state `t`
    /// the agent believes it reached, among the states `(s, a)` may lead to: its outcomes
    /// so far once it is trusted, every state before.
    fn told(&self, s: u32, a: ActionId, t: u32, truth: StateId, read: &[usize]) -> bool {
        if read.is_empty() {
            return false;
        }
        let c = &self.counts[self.pair(s, a)];
        let trusted = c.trusted(self.params.trust);
        let agreeing = self.agreeing(truth, read);
        let mut possible = agreeing
            .iter()
            .filter(|x| !trusted || c.next.contains_key(x));
        possible.next() == Some(&t) && possible.next().is_none()
    }

    /// The states that read as `truth` does on every feature.
    fn agreeing(&self, truth: StateId, features: &[usize]) -> Vec<u32> {
        let w = self.world;
        let nf = self.prices.len();
        let reads = |s: usize, f: usize| self.readings[s * nf + f];
        (0..w.num_states() as u32)
            .filter(|&s| !w.is_terminal(StateId(s)))
            .filter(|&s| {
                features
                    .iter()
                    .all(|&f| reads(s as usize, f) == reads(truth.index(), f))
            })
            .collect()
    }

    fn all_features(&self) -> Vec<usize> {
        (0..self.prices.len()).collect()
    }

    /// The price of a set of probes of the plan's menu, and the features they read.
    fn probes(&self, mask: u32) -> (f64, Vec<usize>) {
        if mask == 0 {
            (0.0, Vec::new())
        } else if self.params.whole_state || mask == EVERY_PROBE {
            (self.prices.iter().sum(), self.all_features())
        } else {
            let f: Vec<usize> = (0..self.prices.len().min(32))
                .filter(|j| mask >> j & 1 == 1)
                .collect();
            (f.iter().map(|&j| self.prices[j]).sum(), f)
        }
    }

    /// Off the plan: the move that is best on average over `states` by the values of
    /// their points (0 where a state has none).
    fn fallback(&self, states: &[u32]) -> ActionId {
        let plan = self.plan.as_ref();
        let value = |s: u32| {
            plan.and_then(|p| p.point(StateId(s)).map(|n| p.value(n)))
                .unwrap_or(0.0)
        };
        let mut best = (ActionId(0), f64::NEG_INFINITY);
        for a in 0..self.na() {
            let a = ActionId(a as u32);
            let q: f64 = states
                .iter()
                .map(|&s| {
                    let c = &self.counts[self.pair(s, a)];
                    if c.tries == 0 {
                        return self.params.optimism;
                    }
                    let on: f64 = c.next.iter().map(|(&t, &k)| f64::from(k) * value(t)).sum();
                    (c.reward + on) / f64::from(c.tries)
                })
                .sum();
            if q > best.1 {
                best = (a, q);
            }
        }
        best.0
    }

    /// Where a known state puts the agent (rebuilding the plan if it is stale).
    fn at(&mut self, s: u32, observer: &mut dyn Observer) -> Result<Place, ReferenceError> {
        let missing = self
            .plan
            .as_ref()
            .is_none_or(|p| p.point(StateId(s)).is_none());
        if missing || self.stale {
            self.known[s as usize] = true;
            self.replan(observer)?;
        }
        let plan = self.plan.as_ref().expect("just built");
        Ok(match plan.point(StateId(s)) {
            Some(n) => Place::Node(n),
            None => Place::Lost(vec![s]),
        })
    }

    fn episode<R: Rng + ?Sized>(
        &mut self,
        rng: &mut R,
        observer: &mut dyn Observer,
    ) -> Result<Episode, ReferenceError> {
        let w = self.world;
        let mut e = Episode::default();
        let mut truth = w.sample_start(rng);
        let mut place = self.at(truth.0, observer)?;
        // The moves since the agent last knew its state, from that state.
        let mut path: Vec<(Vec<u32>, ActionId)> = Vec::new();
        let mut from: Option<u32> = Some(truth.0);
        while e.steps < self.max_moves {
            // Choose: a node of the plan's choice, or off the plan a fallback move that
            // measures every feature.
            let (action, mask, choice) = match &place {
                Place::Node(node) => {
                    let plan = self.plan.as_ref().expect("a node is of a plan");
                    match plan.decide(*node) {
                        Some((c, Decision::Move { action, measure })) => (action, measure, Some(c)),
                        Some((_, Decision::Blind)) => {
                            if let Some(moves) = plan.blind_moves(*node) {
                                let belief: Vec<(u32, f64)> =
                                    plan.belief(*node).iter().map(|&(s, p)| (s.0, p)).collect();
                                self.blind(moves, (truth, belief), &mut e, rng);
                                return Ok(e);
                            }
                            (self.fallback(&self.states(&place)), EVERY_PROBE, None)
                        }
                        _ => (self.fallback(&self.states(&place)), EVERY_PROBE, None),
                    }
                }
                Place::Lost(states) => (self.fallback(states), EVERY_PROBE, None),
            };
            let step = w.sample(truth, action, rng);
            e.steps += 1;
            e.reward += step.reward;
            let ended = step.terminated || w.is_terminal(step.next);
            path.push((self.states(&place), action));
            // What is read: with the move, whatever happens; after it, only if it goes on.
            let (price, features) = self.probes(mask);
            let read_now = match self.rule {
                SensingRule::WithMove => true,
                SensingRule::AfterOutcome => !ended && (mask != 0),
            };
            if read_now && !features.is_empty() {
                e.sensing += price;
                e.measurements += match self.rule {
                    SensingRule::WithMove => 1,
                    SensingRule::AfterOutcome => features.len() as u32,
                };
            }
            let from_state = from;
            if ended {
                if let Some(s) = from_state {
                    self.count(s, action, None, step.reward);
                    if let Some(m) = &mut self.moves
                        && m.record(s, action.index(), None, step.reward)
                    {
                        self.stale = true;
                    }
                }
                // Did the model allow the end? (Counted above, so less one try.)
                if let Place::Node(_) = place {
                    let trust = self.params.trust;
                    let may_end = self.states(&place).iter().any(|&s| {
                        if let Some(m) = &self.moves {
                            return m.may_end(s, action.index());
                        }
                        let c = &self.counts[self.pair(s, action)];
                        let before = c.tries - u32::from(from_state == Some(s));
                        !c.trusted(trust) || c.next.values().sum::<u32>() < before
                    });
                    if !may_end {
                        self.distrust(&path);
                    }
                }
                e.reached_goal = step.reward > 0.0;
                return Ok(e);
            }
            truth = step.next;
            // Where the move and the readings put the agent.
            let followed = match (&place, choice) {
                (Place::Node(node), Some(c)) => {
                    let plan = self.plan.as_ref().expect("a node is of a plan");
                    plan.follow(*node, c, |f| match f {
                        None => truth.0,
                        Some(f) => w.read(truth, f).0,
                    })
                }
                _ => None,
            };
            let mut next_place = match followed {
                Some(n) => Place::Node(n),
                None => {
                    if choice.is_some() {
                        // The model gave what happened probability zero.
                        self.distrust(&path);
                    }
                    Place::Lost(self.agreeing(truth, if read_now { &features } else { &[] }))
                }
            };
            // The features read in this step.
            let mut read: Vec<usize> = if read_now { features } else { Vec::new() };
            // After the outcome: measure one probe at a time while the plan says so.
            if self.rule == SensingRule::AfterOutcome {
                next_place = self.sense_after(next_place, truth, &mut e, &path, &mut read);
            }
            if let Some(s) = from_state
                && let Some(m) = &mut self.moves
            {
                let seen = read
                    .iter()
                    .map(|&f| (f, w.read(truth, Feature(f as u32)).0))
                    .collect();
                if m.record(s, action.index(), Some(seen), step.reward) {
                    self.stale = true;
                }
            }
            // Certain now?
            let certain = match &next_place {
                Place::Node(n) => {
                    let b = self.plan.as_ref().expect("a node is of a plan").belief(*n);
                    (b.len() == 1).then(|| b[0].0.0)
                }
                Place::Lost(states) => (states.len() == 1).then(|| states[0]),
            };
            match certain {
                Some(t) => {
                    // Counted only when something was read and the readings tell the
                    // state among those the pair may lead to (every state until it is
                    // trusted): a state inferred from the model alone would only
                    // confirm the model.
                    if let Some(s) = from_state
                        && self.told(s, action, t, truth, &read)
                    {
                        self.count(s, action, Some(t), step.reward);
                    }
                    from = Some(t);
                    path.clear();
                    place = self.at(t, observer)?;
                }
                None => {
                    from = None;
                    place = next_place;
                }
            }
        }
        Ok(e)
    }

    /// The rest of an episode without measuring: `moves` in order from the state `truth`
    /// (the agent's belief `belief`), until the episode ends or reaches its cap. Nothing
    /// is read; with shared moves, an end teaches the reward of the terminal states the
    /// belief, carried along the moves by the model, may have landed on.
    fn blind<R: Rng + ?Sized>(
        &mut self,
        moves: Vec<ActionId>,
        (mut truth, mut belief): (StateId, Vec<(u32, f64)>),
        e: &mut Episode,
        rng: &mut R,
    ) {
        let w = self.world;
        for action in moves {
            if e.steps >= self.max_moves {
                return;
            }
            let step = w.sample(truth, action, rng);
            e.steps += 1;
            e.reward += step.reward;
            if step.terminated || w.is_terminal(step.next) {
                e.reached_goal = step.reward > 0.0;
                if let Some(m) = &mut self.moves
                    && m.end_blind(&belief, action.index(), step.reward)
                {
                    self.stale = true;
                }
                return;
            }
            if let Some(m) = &self.moves {
                belief = m.carry(&belief, action.index());
            }
            truth = step.next;
        }
    }

    /// Under the rule after the outcome: follow the plan's sense nodes, reading one probe
    /// at a time; off the plan (or on a contradiction), read every feature at once.
    fn sense_after(
        &mut self,
        mut place: Place,
        truth: StateId,
        e: &mut Episode,
        path: &[(Vec<u32>, ActionId)],
        read: &mut Vec<usize>,
    ) -> Place {
        let w = self.world;
        if let Place::Lost(states) = &place
            && states.len() == 1
        {
            return place;
        }
        while let Place::Node(node) = place {
            let plan = self.plan.as_ref().expect("a node is of a plan");
            match plan.decide(node) {
                Some((c, Decision::Act)) => match plan.follow(node, c, |_| 0) {
                    Some(n) => return Place::Node(n),
                    None => break,
                },
                Some((c, Decision::Measure(j))) => {
                    let (price, features) = self.probes(1 << j);
                    e.sensing += price;
                    e.measurements += features.len() as u32;
                    read.extend(&features);
                    match plan.follow(node, c, |f| match f {
                        None => truth.0,
                        Some(f) => w.read(truth, f).0,
                    }) {
                        Some(n) => place = Place::Node(n),
                        None => {
                            self.distrust(path);
                            break;
                        }
                    }
                }
                // An act node (reached after a forced measurement) or no choice.
                Some((_, Decision::Move { .. } | Decision::Blind)) => return Place::Node(node),
                None => break,
            }
        }
        // Lost: read every feature now.
        let all = self.all_features();
        e.sensing += self.prices.iter().sum::<f64>();
        e.measurements += all.len() as u32;
        let lost = Place::Lost(self.agreeing(truth, &all));
        read.extend(all);
        lost
    }
}

#[cfg(test)]
mod tests {
    use rand::SeedableRng;

    use super::*;

    /// A plan that would pass its bound on bytes ends the run with an error that names the
    /// settings that size it and the numbers; under the bound the run is the same.
    #[test]
    fn a_plan_past_its_bound_on_bytes_is_refused_by_name() {
        let o = mdp::WorldOptions {
            slip: Some(2.0 / 3.0),
            sensing: Some(mdp::SensingModel::Factors),
            factor_costs: Some(vec![0.025, 0.025]),
            ..Default::default()
        };
        let lake = mdp::builtin_world("frozenlake4x4", &o).unwrap();
        let params = BeliefParams::default();
        let play = Episodes {
            episodes: 20,
            max_moves: 100,
        };
        let run = |max_bytes| {
            let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(2);
            let bounded = (1.0, SensingRule::WithMove, max_bytes);
            belief_planning_bounded(&lake, &params, bounded, play, &mut rng, &mut KeepTrace)
        };
        let err = run(20_000).unwrap_err().to_string();
        assert!(
            err.starts_with("belief.max_uncertain and belief.max_beliefs: 7 uncertain steps in a row and 5000 beliefs: a plan of")
                && err.contains("passed the bound of 20000 bytes"),
            "{err}"
        );
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(2);
        let default = belief_planning(
            &lake,
            &params,
            1.0,
            SensingRule::WithMove,
            20,
            100,
            &mut rng,
        )
        .unwrap();
        assert_eq!(run(mdp::DEFAULT_MAX_PLAN_BYTES).unwrap(), default);
        assert_eq!(default.len(), 20);
    }
}
