//! The optimum of costly sensing over every policy, bracketed from both sides: a lower
//! bound that is the value of a policy and an upper bound that no policy passes, brought
//! together until they are at most a stated gap apart.
//!
//!
//! The search and its terms are described at [`optimum_bounds`].

use std::collections::BTreeMap;

use crate::belief::{Belief, CostlyModel, Probe, members, split};
use crate::costly::{ReferenceError, SensingMenu, SensingRule, bad, check_menu};
use crate::reference::measured_step;
use crate::world::World;

/// The settings of [`optimum_bounds`].
///
/// ```
/// let o = mdp::BoundOptions::default();
/// assert_eq!((o.horizon, o.gap), (100, 1e-3));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundOptions {
    /// `H`: the most moves an episode has (at least 1), as [`ReferenceOptions::horizon`](crate::ReferenceOptions::horizon).
    pub horizon: u32,
    /// The search stops when the upper bound at the start is at most this above the lower
    /// bound (finite, at least 0).
    pub gap: f64,
    /// The most trials; past it the bounds are returned as they are
    /// ([`OptimumBounds::converged`] false).
    pub max_trials: usize,
    /// The most vectors and points of the lower and upper bounds kept in all, those the
    /// lower bound starts with included (about `8 * states` bytes a vector, `16` a state
    /// of a point's belief): past it the bounds are returned as they are. A horizon
    /// whose starting vectors (with the informed bound's) alone pass it is refused.
    pub max_entries: usize,
}

impl Default for BoundOptions {
    fn default() -> Self {
        BoundOptions {
            horizon: 100,
            gap: 1e-3,
            max_trials: 100_000,
            max_entries: 1_000_000,
        }
    }
}

/// The bounds of the optimum of every policy, and what finding them took.
///
/// ```
/// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
/// let menu = mdp::SensingMenu::Whole { price: 0.05 };
/// let b = mdp::optimum_bounds(&w, menu, mdp::SensingRule::WithMove, &Default::default()).unwrap();
/// assert!(b.converged && b.lower <= b.upper && b.upper - b.lower <= 1e-3);
/// assert!((b.lower - 1.0).abs() < 1e-9); // six moves, nothing measured
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OptimumBounds {
    /// The expected costed return of a policy (the best of the vectors at the start).
    pub lower: f64,
    /// A value no policy's expected costed return passes.
    pub upper: f64,
    /// Whether `upper - lower` reached [`BoundOptions::gap`] (else a budget stopped it).
    pub converged: bool,
    /// The trials run.
    pub trials: usize,
    /// The beliefs backed up (each counted once per backup).
    pub backups: usize,
    /// The vectors of the lower bound kept, over every number of moves left (the
    /// informed bound's, a few per number of moves left and fixed, not counted).
    pub vectors: usize,
    /// The beliefs with a value of the upper bound kept, over every number of moves
    /// left (the states' values, `states * H` of them, not counted).
    pub points: usize,
    /// The states of those beliefs, summed (their memory: about 16 bytes each).
    pub point_states: usize,
}

/// Bounds of the best expected costed return of **every** policy of a world with `menu`
/// and `rule`, `H` moves an episode: a lower bound that is the value of a policy, and an
/// upper bound no policy passes, searched until they are at most [`BoundOptions::gap`]
/// apart or a budget is spent.
///
/// The problem is the one of [`reference_points`](crate::reference_points): a world's
/// model known, the costed return of an `H`-move episode (undiscounted), a
/// [`SensingMenu`] and a [`SensingRule`]. Seen from the agent it is a partially
/// observable MDP whose hidden state is the world's state and whose observations are
/// deterministic: a measurement reads a feature of the state (or the whole state), and
/// the agent always sees whether the episode goes on. Its optimum with `h` moves left is
/// a convex, piecewise linear function of the belief (`V_h`), and the search bounds it at
/// every `h` separately (the problem is finite-horizon, so the best choice depends on the
/// moves left):
///
/// * **lower bound**: a set of vectors per number of moves left, each the expected
///   costed return from every state of a policy (a conditional plan); the bound at a
///   belief is the best of them there. It starts from policies that never measure (one
///   action repeated) and, where measuring every probe tells every state apart, from
///   measuring everything after every move ([`always_measuring`](crate::always_measuring)),
///   and grows by point backups: at a belief, each choice followed, for each reading, by
///   the best vector of the moves left after it. The value at the start is therefore the
///   value of a policy;
/// * **upper bound**: per number of moves left, the lower of two upper bounds. One is
///   the *informed bound* (Hauskrecht, "Value-function approximations for partially
///   observable Markov decision processes", JAIR 13, 2000: the fast informed bound),
///   computed once from `h = 1` up: the optimum of a relaxed problem in which the state
///   a move leaves is told one move later for free, a few vectors per number of moves
///   left. The other is a value at each state (a belief certain of it), at first the
///   lower of [`free_sensing`](crate::free_sensing)'s (the state told after every move
///   at no price) and the informed bound's, and values at some beliefs, interpolated by
///   the sawtooth rule (same paper: by convexity, the value at a belief is at most the
///   states' values mixed, corrected by the kept belief it holds the most of). A backup
///   at a belief takes the best choice's value under the upper bound of what follows,
///   so every value kept stays an upper bound.
///
/// The beliefs backed up are those heuristic search value iteration visits (Smith and
/// Simmons, "Heuristic search value iteration for POMDPs", UAI 2004): trials from the
/// start, each following the choice best under the upper bound and the reading whose
/// gap, weighted by its probability, is largest, down to a belief whose two bounds are
/// within half the gap (or the horizon), then backing up every belief of the path from
/// the last to the first; they stop when the bounds at the start are within the gap.
/// Half the gap is the same at every depth (there is no discount). Nothing
/// is random; ties go to the first choice (the actions in order, then the probe sets as
/// numbers, then the probes) and the first reading (in the order of the readings).
///
/// Under [`SensingRule::WithMove`] a choice is a move with a set of probes, the price
/// paid whatever the outcome, and its readings come with the belief after the move.
/// Under [`SensingRule::AfterOutcome`] the bounds are of the value after a move the
/// episode survives, before sensing (the start, certain, is the same): a choice is a
/// move, or one probe that tells the belief's states apart, read now at its price, its
/// readings leading to beliefs with the same moves left.
///
/// Beliefs are `(state, probability)` lists sorted by state, as in
/// [`BeliefPlan`](crate::BeliefPlan); they are never rounded or merged here.
///
/// # Errors
/// [`ReferenceError::BadSetting`] for a horizon of 0, a gap that is not a finite number
/// of at least 0, a price that is not one, more than [`MAX_MENU_FEATURES`](crate::MAX_MENU_FEATURES) features with
/// the move, or starting vectors past [`BoundOptions::max_entries`];
/// [`ReferenceError::BadWorld`] for a world without a usable model.
///
/// ```
/// use mdp::{BoundOptions, SensingMenu, SensingModel, SensingRule, WorldOptions};
/// let options = WorldOptions {
///     slide: Some(0.5),
///     sensing: Some(SensingModel::Factors),
///     factor_costs: Some(vec![0.025, 0.025]),
///     ..Default::default()
/// };
/// let lake = mdp::builtin_world("frozenlake4x4", &options).unwrap();
/// let o = BoundOptions { horizon: 40, gap: 1e-6, ..Default::default() };
/// let b = mdp::optimum_bounds(&lake, SensingMenu::Features, SensingRule::WithMove, &o).unwrap();
/// assert!(b.converged && b.upper - b.lower <= 1e-6);
/// // Coordinates apart at 0.025 each: the published 0.95 is the optimum (to 1e-4 in 40
/// // moves; the horizon's truncation takes the rest).
/// assert!((b.lower - 0.95).abs() < 1e-4, "{b:?}");
/// let bad = BoundOptions { gap: f64::NAN, ..o };
/// assert!(mdp::optimum_bounds(&lake, SensingMenu::Features, SensingRule::WithMove, &bad).is_err());
/// ```
pub fn optimum_bounds<W: World>(
    world: &W,
    menu: SensingMenu,
    rule: SensingRule,
    options: &BoundOptions,
) -> Result<OptimumBounds, ReferenceError> {
    if options.horizon == 0 {
        return Err(bad("horizon", "0 moves; an episode needs at least one"));
    }
    if !(options.gap.is_finite() && options.gap >= 0.0) {
        return Err(bad(
            "gap",
            format!("{}; it must be finite and >= 0", options.gap),
        ));
    }
    check_menu(menu)?;
    let m = CostlyModel::of(world)?;
    let probes = m.probes_under(menu, rule)?;
    let mut search = Search::new(&m, probes, rule, options)?;
    Ok(search.run(options))
}

/// A set of probes read together, and how it splits the states: what each state reads
/// on it, as the index of its group (`usize::MAX` for terminal states).
struct ProbeSet {
    members: Vec<usize>,
    price: f64,
    group: Vec<usize>,
    groups: usize,
}

/// The bounds with a number of moves left.
struct Stage {
    /// The lower bound: vectors over the states (0 at terminal ones).
    alphas: Vec<Vec<f64>>,
    /// The upper bound at each state known for certain.
    corners: Vec<f64>,
    /// The upper bound at beliefs of two states or more, each with how far it is below
    /// the states' values mixed (`value - corners . belief`, kept up to date as the
    /// states' values fall).
    points: Vec<(Belief, f64)>,
    /// The states of each point, as a bit set of [`Search::words`] words a point, so
    /// that the points a belief covers are found without reading them.
    masks: Vec<u64>,
    /// The informed bound: vectors whose best at a belief is an upper bound there.
    informed: Vec<Vec<f64>>,
}

/// A choice at a belief: a move with the probes of a set (under the rule after the
/// outcome, the empty set), or the probes of a set alone (after the outcome, one probe).
#[derive(Clone, Copy)]
enum Choice {
    Move { action: usize, set: usize },
    Probe { set: usize },
}

/// A choice at a belief with its immediate reward (net of prices) and what follows it:
/// each reading's probability and belief, with `after` moves left.
struct Expanded {
    choice: Choice,
    reward: f64,
    after: usize,
    children: Vec<(f64, Belief)>,
}

/// The share of [`BoundOptions::gap`] a trial narrows each belief to: below 1, so that
/// the last belief of a trial is narrowed by a good part of the gap (at the gap itself a
/// trial could end at a belief just above it whose backup gains less than
/// [`IMPROVEMENT`], and the next trial follow the same path).
const TRIAL_GAP: f64 = 0.5;

/// How much a new vector or point must improve a bound at its belief to be kept.
const IMPROVEMENT: f64 = 1e-12;

/// The search: the model, the probe sets its choices read, the bounds for every number
/// of moves left (index `h`, 0 to the horizon), and what it has done so far.
struct Search<'a> {
    m: &'a CostlyModel,
    rule: SensingRule,
    probes: Vec<Probe>,
    /// With the move: every subset of the probes, as numbers. After the outcome: the
    /// empty set, then each probe alone.
    sets: Vec<ProbeSet>,
    stages: Vec<Stage>,
    gap: f64,
    backups: usize,
    entries: usize,
    /// The words of a bit set of states.
    words: usize,
}

impl<'a> Search<'a> {
    fn new(
        m: &'a CostlyModel,
        probes: Vec<Probe>,
        rule: SensingRule,
        options: &BoundOptions,
    ) -> Result<Search<'a>, ReferenceError> {
        let masks: Vec<Vec<usize>> = match rule {
            SensingRule::WithMove => (0..1u32 << probes.len())
                .map(|mask| members(mask, probes.len()).collect())
                .collect(),
            SensingRule::AfterOutcome => std::iter::once(Vec::new())
                .chain((0..probes.len()).map(|j| vec![j]))
                .collect(),
        };
        let sets: Vec<ProbeSet> = masks
            .into_iter()
            .map(|members| probe_set(m, &probes, members))
            .collect();
        // Whether measuring every probe tells every state apart: then measuring after
        // every move is a policy whose vectors can start the lower bound.
        let everything = probe_set(m, &probes, (0..probes.len()).collect());
        let identifies = everything.groups == m.terminal.iter().filter(|t| !**t).count();
        let h_max = options.horizon as usize;
        let per_stage = m.na + if identifies { m.na } else { 0 };
        // The informed bound's vectors: one a move and probe set, and one for sensing.
        let informed_per_stage = match rule {
            SensingRule::WithMove => m.na.saturating_mul(sets.len()),
            SensingRule::AfterOutcome => m.na + 1,
        };
        let starting = h_max
            .saturating_mul(per_stage.saturating_add(informed_per_stage))
            .saturating_add(2);
        if starting > options.max_entries {
            return Err(bad(
                "horizon",
                format!(
                    "{} moves start the bounds with {starting} vectors, more than max_entries ({})",
                    options.horizon, options.max_entries
                ),
            ));
        }
        let free = measured_stages(m, 0.0, rule, options.horizon);
        let all_price: f64 = probes.iter().map(|p| p.price).sum();
        let measuring = identifies.then(|| measured_stages(m, all_price, rule, options.horizon));
        let mut stages = Vec::with_capacity(h_max + 1);
        stages.push(Stage {
            alphas: vec![vec![0.0; m.n]],
            corners: vec![0.0; m.n],
            points: Vec::new(),
            masks: Vec::new(),
            informed: vec![vec![0.0; m.n]],
        });
        let cheapest = sets
            .iter()
            .filter(|set| !set.members.is_empty())
            .map(|set| set.price)
            .fold(f64::INFINITY, f64::min);
        for h in 1..=h_max {
            let mut alphas = Vec::with_capacity(per_stage);
            // One action repeated, nothing measured.
            for a in 0..m.na {
                // The first vectors of each stage are these, in the order of the actions
                // (stage 0 has the one vector 0).
                let then = &stages[h - 1].alphas;
                alphas.push(one_move(m, a, 0.0, &then[a.min(then.len() - 1)]));
            }
            if let Some(w) = &measuring {
                match rule {
                    // A move with every probe, then measuring after every move.
                    SensingRule::WithMove => {
                        for a in 0..m.na {
                            alphas.push(one_move(m, a, all_price, &w[h - 1]));
                        }
                    }
                    // Every probe now, then measuring after every move that goes on.
                    SensingRule::AfterOutcome => alphas.push(
                        (0..m.n)
                            .map(|s| {
                                if m.terminal[s] {
                                    0.0
                                } else {
                                    w[h][s] - all_price
                                }
                            })
                            .collect(),
                    ),
                }
            }
            let informed = informed_bound(m, rule, &sets, &stages[h - 1].informed, cheapest);
            // The states' values: free sensing's, or the informed bound's where lower.
            let corners = (0..m.n)
                .map(|s| {
                    let best = informed
                        .iter()
                        .map(|v| v[s])
                        .fold(f64::NEG_INFINITY, f64::max);
                    free[h][s].min(best)
                })
                .collect();
            stages.push(Stage {
                alphas,
                corners,
                points: Vec::new(),
                masks: Vec::new(),
                informed,
            });
        }
        let entries = stages.iter().map(|s| s.alphas.len()).sum();
        Ok(Search {
            m,
            rule,
            probes,
            sets,
            stages,
            gap: options.gap,
            backups: 0,
            entries,
            words: m.n.div_ceil(64),
        })
    }

    fn run(&mut self, options: &BoundOptions) -> OptimumBounds {
        let h = options.horizon as usize;
        let starts: Vec<(f64, Belief)> = self
            .m
            .start
            .iter()
            .map(|&(p, s)| (p, vec![(s, 1.0)]))
            .collect();
        for (_, b) in &starts {
            self.backup(b, h);
        }
        let mut trials = 0;
        let converged = loop {
            let widths: Vec<f64> = starts
                .iter()
                .map(|(p, b)| p * (self.upper(h, b) - self.lower(h, b)))
                .collect();
            if widths.iter().sum::<f64>() <= self.gap {
                break true;
            }
            if trials >= options.max_trials || self.entries >= options.max_entries {
                break false;
            }
            let root = first_max(&widths);
            self.trial(starts[root].1.clone(), h);
            trials += 1;
        };
        let lower: f64 = starts.iter().map(|(p, b)| p * self.lower(h, b)).sum();
        let upper: f64 = starts.iter().map(|(p, b)| p * self.upper(h, b)).sum();
        // Where the two meet, rounding may leave the upper a bit below a policy's value,
        // which is a lower bound of the optimum: the larger of the two is an upper bound.
        let upper = upper.max(lower);
        OptimumBounds {
            lower,
            upper,
            converged,
            trials,
            backups: self.backups,
            vectors: self.stages.iter().map(|s| s.alphas.len()).sum(),
            points: self.stages.iter().map(|s| s.points.len()).sum(),
            point_states: self
                .stages
                .iter()
                .flat_map(|s| &s.points)
                .map(|(b, _)| b.len())
                .sum(),
        }
    }

    /// One trial from `b` with `h` moves left: down while the bounds are more than the
    /// gap apart, then a backup at every belief of the path, the last first.
    fn trial(&mut self, mut b: Belief, mut h: usize) {
        let mut path = Vec::new();
        let gap = self.gap * TRIAL_GAP;
        while h > 0 && self.upper(h, &b) - self.lower(h, &b) > gap {
            let expanded = self.expand(&b, h);
            let Some((best, value)) = self.best_upper(&expanded) else {
                break;
            };
            self.keep_point(h, &b, value);
            let e = &expanded[best];
            let excess: Vec<f64> = e
                .children
                .iter()
                .map(|(w, c)| w * (self.upper(e.after, c) - self.lower(e.after, c) - gap))
                .collect();
            let next = first_max(&excess);
            let step = (excess.get(next).is_some_and(|x| *x > 0.0))
                .then(|| (e.children[next].1.clone(), e.after));
            path.push((b, h));
            match step {
                Some((c, after)) => (b, h) = (c, after),
                None => break,
            }
        }
        for (b, h) in path.into_iter().rev() {
            self.backup(&b, h);
        }
    }

    /// Both bounds backed up at `b` with `h` moves left.
    fn backup(&mut self, b: &[(u32, f64)], h: usize) {
        self.backups += 1;
        let expanded = self.expand(b, h);
        let mut best: Option<(f64, Vec<f64>)> = None;
        for e in &expanded {
            let alpha = self.alpha(e);
            let v = dot(&alpha, b);
            if best.as_ref().is_none_or(|(x, _)| v > *x) {
                best = Some((v, alpha));
            }
        }
        if let Some((v, alpha)) = best
            && v > self.lower(h, b) + IMPROVEMENT
        {
            // A vector nowhere above the new one is never the best again.
            let terminal = &self.m.terminal;
            let stage = &mut self.stages[h];
            let before = stage.alphas.len();
            stage.alphas.retain(|old| {
                !old.iter()
                    .zip(&alpha)
                    .zip(terminal)
                    .all(|((o, n), t)| *t || o <= n)
            });
            self.entries -= before - stage.alphas.len();
            stage.alphas.push(alpha);
            self.entries += 1;
        }
        if let Some((_, value)) = self.best_upper(&expanded) {
            self.keep_point(h, b, value);
        }
    }

    /// Every choice at `b` with `h` moves left.
    fn expand(&self, b: &[(u32, f64)], h: usize) -> Vec<Expanded> {
        let mut out = Vec::new();
        let moves = match self.rule {
            SensingRule::WithMove => 0..self.sets.len(),
            SensingRule::AfterOutcome => 0..1,
        };
        for action in 0..self.m.na {
            for set in moves.clone() {
                let price = self.sets[set].price;
                let (reward, _, next) = self.m.successor(b, action, -price);
                let children = if next.is_empty() {
                    Vec::new()
                } else {
                    split(self.m, &self.probes, &self.sets[set].members, &next)
                };
                out.push(Expanded {
                    choice: Choice::Move { action, set },
                    reward,
                    after: h - 1,
                    children,
                });
            }
        }
        if self.rule == SensingRule::AfterOutcome {
            for set in 1..self.sets.len() {
                let children = split(self.m, &self.probes, &self.sets[set].members, b);
                if children.len() > 1 {
                    out.push(Expanded {
                        choice: Choice::Probe { set },
                        reward: -self.sets[set].price,
                        after: h,
                        children,
                    });
                }
            }
        }
        out
    }

    /// The choice best under the upper bound, the first of the best, and its value. A
    /// choice is worth at most its reward plus what follows at the states' values mixed
    /// (the points and the informed bound only lower that), so the choices are valued in
    /// the order of that estimate until none left can reach the best found.
    fn best_upper(&self, expanded: &[Expanded]) -> Option<(usize, f64)> {
        let estimates: Vec<f64> = expanded
            .iter()
            .map(|e| {
                let corners = &self.stages[e.after].corners;
                e.reward
                    + e.children
                        .iter()
                        .map(|(w, c)| w * dot(corners, c))
                        .sum::<f64>()
            })
            .collect();
        let mut order: Vec<usize> = (0..expanded.len()).collect();
        order.sort_by(|&i, &j| estimates[j].total_cmp(&estimates[i]).then(i.cmp(&j)));
        let mut best: Option<(usize, f64)> = None;
        for i in order {
            if best.is_some_and(|(_, v)| estimates[i] < v) {
                break;
            }
            let v = self.upper_of(&expanded[i]);
            if best.is_none_or(|(k, b)| v > b || (v == b && i < k)) {
                best = Some((i, v));
            }
        }
        best
    }

    /// The value of a choice under the upper bound of what follows it.
    fn upper_of(&self, e: &Expanded) -> f64 {
        e.reward
            + e.children
                .iter()
                .map(|(w, c)| w * self.upper(e.after, c))
                .sum::<f64>()
    }

    /// The vector of the policy that makes the choice, then follows for each reading the
    /// vector (of the moves left after it) best at that reading's belief; a reading no
    /// state of the belief gives (it may come from other states) follows the vector best
    /// for its states weighted alike.
    fn alpha(&self, e: &Expanded) -> Vec<f64> {
        let m = self.m;
        let (set, price) = match e.choice {
            Choice::Move { set, .. } | Choice::Probe { set } => (set, self.sets[set].price),
        };
        let set = &self.sets[set];
        let gamma = &self.stages[e.after].alphas;
        let mut weights = vec![0.0; m.n];
        for (w, part) in &e.children {
            for &(t, p) in part {
                weights[t as usize] += w * p;
            }
        }
        let mut mass = vec![0.0; set.groups];
        for (t, w) in weights.iter().enumerate() {
            if set.group[t] != usize::MAX {
                mass[set.group[t]] += w;
            }
        }
        for (t, w) in weights.iter_mut().enumerate() {
            let g = set.group[t];
            if g != usize::MAX && mass[g] == 0.0 {
                *w = 1.0;
            }
        }
        let mut best = vec![(f64::NEG_INFINITY, 0usize); set.groups];
        let mut score = vec![0.0; set.groups];
        for (k, alpha) in gamma.iter().enumerate() {
            score.iter_mut().for_each(|x| *x = 0.0);
            for (t, w) in weights.iter().enumerate() {
                if *w != 0.0 {
                    score[set.group[t]] += w * alpha[t];
                }
            }
            for (g, x) in score.iter().enumerate() {
                if *x > best[g].0 {
                    best[g] = (*x, k);
                }
            }
        }
        let follow = |t: usize| gamma[best[set.group[t]].1][t];
        (0..m.n)
            .map(|s| {
                if m.terminal[s] {
                    return 0.0;
                }
                match e.choice {
                    Choice::Move { action, .. } => {
                        let i = m.pair(s as u32, action);
                        m.reward[i] - price
                            + m.next[i]
                                .iter()
                                .map(|&(t, p)| p * follow(t as usize))
                                .sum::<f64>()
                    }
                    Choice::Probe { .. } => follow(s) - price,
                }
            })
            .collect()
    }

    /// The lower bound at `b` with `h` moves left: the best vector there.
    fn lower(&self, h: usize, b: &[(u32, f64)]) -> f64 {
        self.stages[h]
            .alphas
            .iter()
            .map(|a| dot(a, b))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// The upper bound at `b` with `h` moves left: the sawtooth interpolation of the
    /// states' values and the beliefs' values kept.
    fn upper(&self, h: usize, b: &[(u32, f64)]) -> f64 {
        let stage = &self.stages[h];
        let base = dot(&stage.corners, b);
        let mut correction = 0.0f64;
        if b.len() > 1 && !stage.points.is_empty() {
            let mask = self.mask(b);
            // Points with a state outside the belief are skipped (one word: the lakes).
            let outside = |i: usize| match mask.as_slice() {
                [q] => stage.masks[i] & !q != 0,
                _ => {
                    let words = &stage.masks[i * self.words..(i + 1) * self.words];
                    words.iter().zip(&mask).any(|(p, q)| p & !q != 0)
                }
            };
            for (i, (point, v)) in stage.points.iter().enumerate() {
                if !outside(i) {
                    correction = correction.min(covered(b, point) * v);
                }
            }
        }
        let informed = stage
            .informed
            .iter()
            .map(|v| dot(v, b))
            .fold(f64::NEG_INFINITY, f64::max);
        (base + correction).min(informed)
    }

    /// The states of a belief as a bit set.
    fn mask(&self, b: &[(u32, f64)]) -> Vec<u64> {
        let mut mask = vec![0u64; self.words];
        for &(s, _) in b {
            mask[s as usize / 64] |= 1 << (s % 64);
        }
        mask
    }

    /// Keep `v` as the upper bound at `b` with `h` moves left, where it is lower.
    fn keep_point(&mut self, h: usize, b: &[(u32, f64)], v: f64) {
        if h == 0 {
            return;
        }
        if let [(s, _)] = b {
            let stage = &mut self.stages[h];
            let s = *s as usize;
            let fall = stage.corners[s] - v;
            if fall > 0.0 {
                stage.corners[s] = v;
                // Each point holding the state is that much less below the mixture.
                let (word, bit) = (s / 64, 1u64 << (s % 64));
                for (i, (point, below)) in stage.points.iter_mut().enumerate() {
                    if stage.masks[i * self.words + word] & bit != 0
                        && let Ok(k) = point.binary_search_by_key(&(s as u32), |x| x.0)
                    {
                        *below += fall * point[k].1;
                    }
                }
            }
        } else if v < self.upper(h, b) - IMPROVEMENT {
            let mask = self.mask(b);
            let words = self.words;
            let stage = &mut self.stages[h];
            let below = v - dot(&stage.corners, b);
            // A point holding `r` of the new one and no more than `r` times as far below
            // the mixture gives no belief a lower bound than the new one does.
            let keep: Vec<bool> = stage
                .points
                .iter()
                .enumerate()
                .map(|(i, (point, old))| {
                    let theirs = &stage.masks[i * words..(i + 1) * words];
                    let holds = mask.iter().zip(theirs).all(|(q, p)| q & !p == 0);
                    !(holds && covered(point, b) * below <= *old)
                })
                .collect();
            let before = stage.points.len();
            let mut i = 0;
            stage.points.retain(|_| {
                i += 1;
                keep[i - 1]
            });
            let mut i = 0;
            stage.masks.retain(|_| {
                i += 1;
                keep[(i - 1) / words]
            });
            self.entries -= before - stage.points.len();
            stage.points.push((b.to_vec(), below));
            stage.masks.extend(mask);
            self.entries += 1;
        }
    }
}

/// The probes of `members` with what splits the non-terminal states by their readings.
fn probe_set(m: &CostlyModel, probes: &[Probe], members: Vec<usize>) -> ProbeSet {
    let mut index: BTreeMap<Vec<u32>, usize> = BTreeMap::new();
    let group = (0..m.n)
        .map(|s| {
            if m.terminal[s] {
                return usize::MAX;
            }
            let reading: Vec<u32> = members
                .iter()
                .map(|&j| probes[j].read(m, s as u32))
                .collect();
            let next = index.len();
            *index.entry(reading).or_insert(next)
        })
        .collect();
    ProbeSet {
        price: members.iter().map(|&j| probes[j].price).sum(),
        members,
        group,
        groups: index.len(),
    }
}

/// The vector of one move `a` (with probes at `price`), then the policy of `then`.
fn one_move(m: &CostlyModel, a: usize, price: f64, then: &[f64]) -> Vec<f64> {
    (0..m.n)
        .map(|s| {
            if m.terminal[s] {
                return 0.0;
            }
            let i = m.pair(s as u32, a);
            let after: f64 = m.next[i].iter().map(|&(t, p)| p * then[t as usize]).sum();
            m.reward[i] - price + after
        })
        .collect()
}

/// The values from each known state with `0..=horizon` moves left, the state measured
/// at `price` after every move under `rule` (at 0, the values of free sensing).
fn measured_stages(m: &CostlyModel, price: f64, rule: SensingRule, horizon: u32) -> Vec<Vec<f64>> {
    let zeros = vec![0.0; m.n];
    let mut counts = vec![0.0; m.n];
    let mut stages = vec![zeros.clone()];
    for h in 1..=horizon {
        let mut w = vec![0.0; m.n];
        measured_step(
            m,
            (price, 0.0),
            rule,
            h,
            (&stages[h as usize - 1], &zeros),
            (&mut w, &mut counts),
        );
        stages.push(w);
    }
    stages
}

/// The expected value of a vector over a belief.
fn dot(alpha: &[f64], b: &[(u32, f64)]) -> f64 {
    b.iter().map(|&(s, p)| p * alpha[s as usize]).sum()
}

/// The largest `r` such that `b - r * point` has no negative entry, for a point whose
/// states are all in `b`: how much of `point` the belief holds.
fn covered(b: &[(u32, f64)], point: &[(u32, f64)]) -> f64 {
    let mut ratio = f64::INFINITY;
    let mut i = 0;
    for &(s, q) in point {
        while b[i].0 < s {
            i += 1;
        }
        ratio = ratio.min(b[i].1 / q);
    }
    ratio
}

/// The informed bound with `h` moves left from the one with `h - 1` (`then`): the
/// state a move leaves told one move late, for free. With the move, a vector for each move and probe set:
/// its reward, less the set's price, and for each reading the best vector of `then` over
/// the states that read so. After the outcome, a vector for each move, the best vector
/// of `then` over the states it leads to; and, for sensing, the best of those at each
/// state less the cheapest probe (as if a probe told the state).
fn informed_bound(
    m: &CostlyModel,
    rule: SensingRule,
    sets: &[ProbeSet],
    then: &[Vec<f64>],
    cheapest: f64,
) -> Vec<Vec<f64>> {
    let moves = match rule {
        SensingRule::WithMove => sets.len(),
        SensingRule::AfterOutcome => 1,
    };
    let mut out = Vec::new();
    let mut sums = Vec::new();
    for a in 0..m.na {
        for set in &sets[..moves] {
            let vector = (0..m.n)
                .map(|s| {
                    if m.terminal[s] {
                        return 0.0;
                    }
                    let i = m.pair(s as u32, a);
                    sums.clear();
                    sums.resize(set.groups * then.len(), 0.0);
                    for &(t, p) in &m.next[i] {
                        let g = set.group[t as usize];
                        for (k, beta) in then.iter().enumerate() {
                            sums[g * then.len() + k] += p * beta[t as usize];
                        }
                    }
                    let after: f64 = sums
                        .chunks(then.len())
                        .map(|c| c.iter().copied().fold(f64::NEG_INFINITY, f64::max))
                        .sum();
                    m.reward[i] - set.price + after
                })
                .collect();
            out.push(vector);
        }
    }
    if rule == SensingRule::AfterOutcome && cheapest.is_finite() {
        let sensed = (0..m.n)
            .map(|s| {
                let best = out
                    .iter()
                    .map(|v: &Vec<f64>| v[s])
                    .fold(f64::NEG_INFINITY, f64::max);
                if m.terminal[s] { 0.0 } else { best - cheapest }
            })
            .collect();
        out.push(sensed);
    }
    out
}

/// The index of the first largest value (0 for none).
fn first_max(values: &[f64]) -> usize {
    let mut best = 0;
    for (i, v) in values.iter().enumerate() {
        if *v > values[best] {
            best = i;
        }
    }
    best
}
