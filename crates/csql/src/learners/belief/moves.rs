//! Shared moves (`[belief] shared_moves`, specification 6.13): what an action does,
//! learned over every state at once.
//!
//! On a world whose states are every combination of their readings (a grid of cells read
//! by row and column, say), an action moves the agent by a displacement of the readings
//! drawn from a distribution of its own, the same in every state: a walk of one reading
//! step at a time, feature by feature, held within each reading's range (a step into a
//! wall stays) and stopped by the first terminal state on its way. Every try of an action
//! from a known state teaches that one distribution, whatever was read after it: each
//! counts for the displacements that agree with what it read (all those that go on, when
//! nothing was read; those that land on a terminal state, when it ended the episode), and
//! the distribution is the one of greatest likelihood over every try kept
//! (expectation-maximisation). What to read is decided before the outcome, or from what
//! was read already, so that likelihood is the right one. The reward of landing on a
//! terminal state is learned from the ends attributed to it, by the likelihood or, for an
//! end met without measuring, by the belief the model carried along the moves; until a
//! state has taken an end's worth of attribution its reward is the optimistic one.

use std::collections::BTreeMap;

use mdp::ReferenceError;

/// Rounds of expectation-maximisation a fit runs.
const ROUNDS: usize = 40;

/// The weight of ends a terminal state must be attributed before its reward counts as
/// known.
const KNOWN: f64 = 0.5;

/// The most displacements the model keeps (a try's consistent ones are a bit set).
const MAX_SUPPORT: usize = 64;

/// What a try of an action from a known state showed: the state it was tried from and
/// what was read after it (feature and reading; `None`: it ended the episode). Tries that
/// showed the same are kept once, with their number and the sum of their rewards.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Try {
    from: u32,
    seen: Option<Vec<(usize, u32)>>,
}

/// The shared model of moves.
#[derive(Clone, Debug)]
pub(super) struct Moves {
    features: usize,
    /// Each feature's least and greatest reading.
    lo: Vec<i64>,
    hi: Vec<i64>,
    /// Each state's readings.
    readings: Vec<i64>,
    /// The state of each combination of readings (row-major over the features' ranges).
    cell: Vec<u32>,
    terminal: Vec<bool>,
    /// The displacements seen whole, in the order first seen.
    support: Vec<Vec<i64>>,
    /// Where each displacement takes each state, at `s * support.len() + k`.
    lands: Vec<u32>,
    /// Per action: its tries by the set of displacements they agree with.
    sets: Vec<BTreeMap<u64, f64>>,
    /// Per action: its tries (how many of each, the sum of their rewards), their number,
    /// and the probability of each displacement of `support`.
    tries: Vec<BTreeMap<Try, (f64, f64)>>,
    count: Vec<u32>,
    p: Vec<Vec<f64>>,
    /// Per action: tries from which on it may go unmeasured.
    trusted_at: Vec<u32>,
    /// Per terminal state: the reward attributed to landing on it, and the weight of the
    /// ends attributed.
    landing: Vec<(f64, f64)>,
    /// Ends met without measuring: each terminal state's share of the end (as the belief
    /// carried by the model then had it) and the end's reward.
    blind_ends: Vec<(Vec<(u32, f64)>, f64)>,
    /// Per state: the weight of ends attributed to it since the last fit, as the model
    /// then had it (to tell when an end makes a terminal state's reward known).
    pending: Vec<f64>,
    /// The rewards of the tries that went on, and how many.
    step_reward: (f64, u32),
}

impl Moves {
    /// The model of a world of `n` states read by `features` features (`readings` at
    /// `s * features + f`), `na` actions, each action trusted after `trust` tries.
    ///
    /// # Errors
    /// [`ReferenceError::BadSetting`] if the states are not every combination of their
    /// readings, each once.
    pub(super) fn new(
        readings: &[u32],
        features: usize,
        terminal: &[bool],
        na: usize,
        trust: u32,
    ) -> Result<Moves, ReferenceError> {
        let n = terminal.len();
        let bad = |problem: String| ReferenceError::BadSetting {
            what: "belief.shared_moves",
            problem,
        };
        if features == 0 || n == 0 {
            return Err(bad(
                "the world has no states or no features to read a move by".into(),
            ));
        }
        let readings: Vec<i64> = readings.iter().map(|&r| i64::from(r)).collect();
        let mut lo = vec![i64::MAX; features];
        let mut hi = vec![i64::MIN; features];
        for s in 0..n {
            for f in 0..features {
                let r = readings[s * features + f];
                lo[f] = lo[f].min(r);
                hi[f] = hi[f].max(r);
            }
        }
        let combinations = lo
            .iter()
            .zip(&hi)
            .try_fold(1usize, |acc, (l, h)| acc.checked_mul((h - l + 1) as usize));
        if combinations != Some(n) {
            return Err(bad(format!(
                "its {n} states are not every combination of their readings (a grid), so a \
                 move cannot be read as a shift of the readings; leave shared_moves off"
            )));
        }
        let mut cell = vec![u32::MAX; n];
        let mut moves = Moves {
            features,
            lo,
            hi,
            readings,
            cell: Vec::new(),
            terminal: terminal.to_vec(),
            support: Vec::new(),
            lands: Vec::new(),
            sets: vec![BTreeMap::new(); na],
            tries: vec![BTreeMap::new(); na],
            count: vec![0; na],
            p: vec![Vec::new(); na],
            trusted_at: vec![trust; na],
            landing: vec![(0.0, 0.0); n],
            blind_ends: Vec::new(),
            pending: vec![0.0; n],
            step_reward: (0.0, 0),
        };
        for s in 0..n {
            let i = moves.index(&moves.readings[s * features..(s + 1) * features]);
            if cell[i] != u32::MAX {
                return Err(bad(format!(
                    "states {} and {s} read alike, so a move cannot be read as a shift of \
                     the readings; leave shared_moves off",
                    cell[i]
                )));
            }
            cell[i] = s as u32;
        }
        moves.cell = cell;
        Ok(moves)
    }

    /// The index of a combination of readings (each within its range).
    fn index(&self, r: &[i64]) -> usize {
        (self.lo.iter().zip(&self.hi).zip(r)).fold(0usize, |i, ((lo, hi), x)| {
            i * (hi - lo + 1) as usize + (x - lo) as usize
        })
    }

    fn reads(&self, s: u32) -> &[i64] {
        let f = self.features;
        &self.readings[s as usize * f..(s as usize + 1) * f]
    }

    /// Where the `k`-th displacement takes state `s`.
    fn land(&self, s: u32, k: usize) -> u32 {
        self.lands[s as usize * self.support.len() + k]
    }

    /// A new displacement: every landing and every try's set of agreeing displacements
    /// computed again.
    fn widen(&mut self, d: Vec<i64>) {
        self.support.push(d);
        let n = self.terminal.len();
        self.lands = (0..n as u32)
            .flat_map(|s| self.support.iter().map(move |d| (s, d)))
            .map(|(s, d)| self.walk(s, d))
            .collect();
        for a in 0..self.tries.len() {
            let mut sets = BTreeMap::new();
            for (t, &(n, _)) in &self.tries[a] {
                let set = self.consistent(t);
                if set != 0 {
                    *sets.entry(set).or_insert(0.0) += n;
                }
            }
            self.sets[a] = sets;
        }
    }

    /// Where displacement `d` takes state `s`: a walk of one reading step at a time,
    /// feature by feature in order, each reading held within its range (a step into a
    /// wall stays), that stops on the first terminal state it meets.
    fn walk(&self, s: u32, d: &[i64]) -> u32 {
        let mut at: Vec<i64> = self.reads(s).to_vec();
        let mut state = s;
        for f in 0..self.features {
            let step = d[f].signum();
            for _ in 0..d[f].abs() {
                let r = (at[f] + step).clamp(self.lo[f], self.hi[f]);
                if r == at[f] {
                    break;
                }
                at[f] = r;
                state = self.cell[self.index(&at)];
                if self.terminal[state as usize] {
                    return state;
                }
            }
        }
        state
    }

    /// Keep a try of action `a` from the known state `s`: the readings `seen` of what
    /// followed (`None`: the episode ended; empty: nothing was read) and its reward.
    /// Whether the model may have changed enough to plan again: a new displacement, a
    /// try count at a power of two or at trust, or an end that may have landed where the
    /// reward is not known yet.
    pub(super) fn record(
        &mut self,
        s: u32,
        a: usize,
        seen: Option<Vec<(usize, u32)>>,
        reward: f64,
    ) -> bool {
        let was = self.trusted(a);
        let mut stale = false;
        match &seen {
            Some(read) => {
                // Every feature read: the displacement is seen whole.
                if read.len() == self.features && self.support.len() < MAX_SUPPORT {
                    let mut to = vec![0i64; self.features];
                    for &(f, r) in read {
                        to[f] = i64::from(r);
                    }
                    let d: Vec<i64> = to.iter().zip(self.reads(s)).map(|(x, y)| x - y).collect();
                    if !self.support.contains(&d) {
                        self.widen(d);
                        stale = true;
                    }
                }
                self.step_reward.0 += reward;
                self.step_reward.1 += 1;
            }
            None => {
                let shares = self.shares(&[(s, 1.0)], a);
                stale |= self.learns(&shares);
            }
        }
        let t = Try { from: s, seen };
        let set = self.consistent(&t);
        if set != 0 {
            *self.sets[a].entry(set).or_insert(0.0) += 1.0;
        }
        let kept = self.tries[a].entry(t).or_insert((0.0, 0.0));
        kept.0 += 1.0;
        kept.1 += reward;
        self.count[a] = self.count[a].saturating_add(1);
        let n = self.count[a];
        stale || n.is_power_of_two() || self.trusted(a) != was
    }

    /// Whether action `a` may go unmeasured.
    pub(super) fn trusted(&self, a: usize) -> bool {
        self.count[a] >= self.trusted_at[a]
    }

    /// Action `a` must be measured `trust` more times.
    pub(super) fn distrust(&mut self, a: usize, trust: u32) {
        let again = self.count[a].saturating_add(trust);
        self.trusted_at[a] = self.trusted_at[a].max(again);
    }

    /// The displacements of `support` a try is consistent with, as a bit set: those
    /// that land where it read what it read, or (an end) on a terminal state.
    fn consistent(&self, t: &Try) -> u64 {
        let mut set = 0u64;
        for k in 0..self.support.len() {
            let land = self.land(t.from, k);
            let fits = match &t.seen {
                None => self.terminal[land as usize],
                Some(read) => {
                    !self.terminal[land as usize]
                        && read.iter().all(|&(f, r)| {
                            self.readings[land as usize * self.features + f] == i64::from(r)
                        })
                }
            };
            if fits {
                set |= 1 << k;
            }
        }
        set
    }

    /// Fit every action's distribution to its tries (greatest likelihood), then the
    /// rewards of landing on terminal states.
    pub(super) fn fit(&mut self) {
        let k = self.support.len();
        self.landing.iter_mut().for_each(|l| *l = (0.0, 0.0));
        self.pending.iter_mut().for_each(|w| *w = 0.0);
        let bits = |set: u64| (0..k).filter(move |j| set >> j & 1 == 1);
        for a in 0..self.tries.len() {
            if self.sets[a].is_empty() {
                self.p[a] = vec![0.0; k];
                continue;
            }
            let mut p = vec![1.0 / k as f64; k];
            let mut mass = vec![0.0; k];
            for _ in 0..ROUNDS {
                mass.iter_mut().for_each(|m| *m = 0.0);
                for (&set, &n) in &self.sets[a] {
                    let z: f64 = bits(set).map(|j| p[j]).sum();
                    for j in bits(set) {
                        mass[j] += n * p[j] / z;
                    }
                }
                let total: f64 = mass.iter().sum();
                for (x, m) in p.iter_mut().zip(&mass) {
                    *x = m / total;
                }
            }
            for (t, &(n, reward)) in self.tries[a].iter().filter(|(t, _)| t.seen.is_none()) {
                let set = self.consistent(t);
                let z: f64 = bits(set).map(|j| p[j]).sum();
                if z > 0.0 {
                    for j in bits(set) {
                        let land = self.land(t.from, j) as usize;
                        self.landing[land].0 += p[j] / z * reward;
                        self.landing[land].1 += p[j] / z * n;
                    }
                }
            }
            self.p[a] = p;
        }
        for (shares, reward) in &self.blind_ends {
            for &(t, w) in shares {
                self.landing[t as usize].0 += w * reward;
                self.landing[t as usize].1 += w;
            }
        }
    }

    /// Action `a` from `s` as the model has it: the states it goes on to with their
    /// probabilities, its expected reward, and the share of its tries (`n / (n + prior)`
    /// until trusted, with the rest an optimistic end of reward `optimism`).
    pub(super) fn pair(
        &self,
        s: u32,
        a: usize,
        prior: f64,
        optimism: f64,
    ) -> (Vec<(u32, f64)>, f64) {
        let n = f64::from(self.count[a]);
        let weight = if self.trusted(a) {
            1.0
        } else {
            n / (n + prior)
        };
        let step = if self.step_reward.1 > 0 {
            self.step_reward.0 / f64::from(self.step_reward.1)
        } else {
            0.0
        };
        let mut next: BTreeMap<u32, f64> = BTreeMap::new();
        let mut reward = (1.0 - weight) * optimism;
        for (k, &q) in self.p[a].iter().enumerate() {
            if q <= 0.0 {
                continue;
            }
            let t = self.land(s, k);
            let q = q * weight;
            if self.terminal[t as usize] {
                let (sum, w) = self.landing[t as usize];
                reward += q * if w >= KNOWN { sum / w } else { optimism };
            } else {
                *next.entry(t).or_insert(0.0) += q;
                reward += q * step;
            }
        }
        // No displacement fitted yet: all of it optimistic.
        if self.p[a].iter().all(|&q| q <= 0.0) {
            reward = optimism;
        }
        (next.into_iter().collect(), reward)
    }

    /// Where action `a` takes `belief` as the model has it, among the terminal states
    /// (`ended`) or the others, normalised (empty where it goes to none of them).
    fn spread(&self, belief: &[(u32, f64)], a: usize, ended: bool) -> Vec<(u32, f64)> {
        let mut to: BTreeMap<u32, f64> = BTreeMap::new();
        for &(s, b) in belief {
            for (k, &q) in self.p[a].iter().enumerate() {
                let t = self.land(s, k);
                if q > 0.0 && self.terminal[t as usize] == ended {
                    *to.entry(t).or_insert(0.0) += b * q;
                }
            }
        }
        let total: f64 = to.values().sum();
        if total <= 0.0 {
            return Vec::new();
        }
        to.into_iter().map(|(t, x)| (t, x / total)).collect()
    }

    /// The belief after action `a` from `belief`, given that the episode went on (the
    /// same belief where the model says it cannot).
    pub(super) fn carry(&self, belief: &[(u32, f64)], a: usize) -> Vec<(u32, f64)> {
        let next = self.spread(belief, a, false);
        if next.is_empty() {
            belief.to_vec()
        } else {
            next
        }
    }

    /// Each terminal state's share of an end of action `a` from `belief`, as the model
    /// has it (none where the model allows no end).
    fn shares(&self, belief: &[(u32, f64)], a: usize) -> Vec<(u32, f64)> {
        self.spread(belief, a, true)
    }

    /// Count `shares` as pending; whether they make a terminal state's reward known.
    fn learns(&mut self, shares: &[(u32, f64)]) -> bool {
        let mut learned = false;
        for &(t, w) in shares {
            let t = t as usize;
            let before = self.landing[t].1 + self.pending[t];
            self.pending[t] += w;
            learned |= before < KNOWN && before + w >= KNOWN;
        }
        learned
    }

    /// Keep an end met without measuring, by action `a` from `belief`, of reward
    /// `reward`: each terminal state the model says the action may have landed on takes
    /// its share. Whether that makes a terminal state's reward known.
    pub(super) fn end_blind(&mut self, belief: &[(u32, f64)], a: usize, reward: f64) -> bool {
        let shares = self.shares(belief, a);
        if shares.is_empty() {
            return false;
        }
        let learned = self.learns(&shares);
        self.blind_ends.push((shares, reward));
        learned
    }

    /// Whether action `a` from `s` may end the episode, as the model has it.
    pub(super) fn may_end(&self, s: u32, a: usize) -> bool {
        !self.trusted(a)
            || (self.p[a].iter().enumerate())
                .any(|(k, q)| *q > 0.0 && self.terminal[self.land(s, k) as usize])
    }
}

#[cfg(test)]
mod tests {
    use rand::{RngExt, SeedableRng};

    use super::*;

    /// The readings of a `rows` x `cols` grid, state `r * cols + c` reading (r, c).
    fn grid(rows: u32, cols: u32) -> Vec<u32> {
        (0..rows)
            .flat_map(|r| (0..cols).flat_map(move |c| [r, c]))
            .collect()
    }

    #[test]
    fn a_world_that_is_not_a_grid_is_refused() {
        // Three cells of a 2 x 2 grid: one combination missing.
        let e = Moves::new(&[0, 0, 0, 1, 1, 0], 2, &[false; 3], 4, 8).unwrap_err();
        assert!(
            e.to_string()
                .contains("its 3 states are not every combination"),
            "{e}"
        );
        // Two states that read alike (and so one combination missing).
        let e = Moves::new(&[0, 0, 0, 0], 2, &[false; 2], 4, 8).unwrap_err();
        assert!(e.to_string().contains("belief.shared_moves"), "{e}");
        assert!(Moves::new(&grid(2, 2), 2, &[false; 4], 4, 8).is_ok());
    }

    #[test]
    fn a_walk_stops_on_the_first_terminal_state_and_at_walls() {
        // A corridor of five cells read by (0, column), the middle one terminal.
        let mut terminal = [false; 5];
        terminal[2] = true;
        let mut m = Moves::new(&grid(1, 5), 2, &terminal, 1, 8).unwrap();
        m.widen(vec![0, 3]);
        m.widen(vec![0, -3]);
        assert_eq!((m.land(0, 0), m.land(3, 0), m.land(4, 0)), (2, 4, 4));
        assert_eq!((m.land(4, 1), m.land(1, 1)), (2, 0));
    }

    /// Tries of one action on an open 6 x 6 grid from random cells, its outcome drawn from
    /// a slip (right 1/2, up 1/4, down 1/4) and held by the walls; a third of them read
    /// whole, a third only the column, a third nothing: the likelihood finds the slip.
    #[test]
    fn the_likelihood_finds_the_slip_through_walls_and_partial_readings() {
        let mut m = Moves::new(&grid(6, 6), 2, &[false; 36], 1, 8).unwrap();
        let slip = [(vec![0, 1], 0.5), (vec![-1, 0], 0.25), (vec![1, 0], 0.25)];
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(3);
        for i in 0..6000 {
            let s: u32 = rng.random_range(0..36);
            let u: f64 = rng.random();
            let d = if u < 0.5 {
                &slip[0].0
            } else if u < 0.75 {
                &slip[1].0
            } else {
                &slip[2].0
            };
            let (r, c) = (i64::from(s / 6), i64::from(s % 6));
            let to = [(r + d[0]).clamp(0, 5) as u32, (c + d[1]).clamp(0, 5) as u32];
            let seen = match i % 3 {
                0 => vec![(0, to[0]), (1, to[1])],
                1 => vec![(1, to[1])],
                _ => Vec::new(),
            };
            m.record(s, 0, Some(seen), 0.0);
        }
        m.fit();
        for (d, p) in &slip {
            let k = m.support.iter().position(|x| x == d).unwrap();
            assert!(
                (m.p[0][k] - p).abs() < 0.03,
                "{d:?}: {} against {p}",
                m.p[0][k]
            );
        }
        // A stay seen through a wall is a displacement too, with next to no weight.
        let stay = m.support.iter().position(|x| x == &vec![0, 0]).unwrap();
        assert!(m.p[0][stay] < 0.01, "{}", m.p[0][stay]);
        assert!(m.trusted(0));
    }

    /// Ends met without measuring teach the reward of the terminal state the belief
    /// carried by the model lands on; until then that state is worth the optimism.
    #[test]
    fn ends_met_blind_teach_the_reward_of_where_they_land() {
        // A corridor of three cells, the last one terminal; one action, always right.
        let mut terminal = [false; 3];
        terminal[2] = true;
        let mut m = Moves::new(&grid(1, 3), 2, &terminal, 1, 2).unwrap();
        for _ in 0..2 {
            m.record(0, 0, Some(vec![(0, 0), (1, 1)]), 0.0);
        }
        m.fit();
        assert_eq!(m.pair(1, 0, 3.0, 1.0), (vec![], 1.0));
        let after = m.carry(&[(0, 1.0)], 0);
        assert_eq!(after, vec![(1, 1.0)]);
        assert!(m.end_blind(&after, 0, 0.25));
        m.fit();
        assert_eq!(m.pair(1, 0, 3.0, 1.0), (vec![], 0.25));
        assert_eq!(m.pair(0, 0, 3.0, 1.0), (vec![(1, 1.0)], 0.0));
    }
}
