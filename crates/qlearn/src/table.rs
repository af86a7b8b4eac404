//! The Q/V table: dense rows of action values, the update of equation 2, and action
//! selection.

use std::fmt;

use mdp::ActionId;
use rand::{Rng, RngExt};

use crate::error::Error;
use crate::params::{Discount, Epsilon, LearningRate, Temperature};

/// A row of a [`QTable`]: the learner's name for a state, or for a state description
/// that several states share. Rows are numbered from 0 in the order they were added.
///
/// ```
/// let mut table = qlearn::QTable::new(2).unwrap();
/// let row = table.add_row();
/// assert_eq!(row, qlearn::RowId(0));
/// assert_eq!(row.index(), 0);
/// ```
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize,
)]
pub struct RowId(pub u32);

impl RowId {
    /// The id as an index into dense per-row storage.
    ///
    /// ```
    /// assert_eq!(qlearn::RowId(5).index(), 5);
    /// ```
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl fmt::Display for RowId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "row{}", self.0)
    }
}

/// Where the target of an update comes from.
///
/// A transition into a terminal state (the goal) has nothing after it: the target is
/// the reward alone. Any other transition, including the last move of a trial that was
/// cut off by a move cap, bootstraps from the utility `V` of the row of the next state.
///
/// ```
/// use qlearn::{RowId, Target};
/// let t = Target::Bootstrap(RowId(3));
/// assert_ne!(t, Target::Terminal);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// The transition ended in a terminal state: target `r`.
    Terminal,
    /// The transition reached a state described by this row: target `r + gamma * V(row)`.
    Bootstrap(RowId),
}

/// The utility `V` of the updated row before and after an update.
///
/// Theorem 1 says that with consistent rows and non-negative rewards this never
/// decreases; CS-QL takes a decrease as the sign of an inconsistent (aliased) row.
///
/// ```
/// let c = qlearn::VChange { before: 0.9, after: 0.81 };
/// assert!(c.decreased());
/// assert!(!c.increased());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VChange {
    /// `V(row)` before the update.
    pub before: f64,
    /// `V(row)` after the update.
    pub after: f64,
}

impl VChange {
    /// Whether `V` went down.
    ///
    /// ```
    /// assert!(!qlearn::VChange { before: 1.0, after: 1.0 }.decreased());
    /// ```
    #[inline]
    pub fn decreased(&self) -> bool {
        self.after < self.before
    }

    /// Whether `V` went up.
    ///
    /// ```
    /// assert!(qlearn::VChange { before: 0.0, after: 1.0 }.increased());
    /// ```
    #[inline]
    pub fn increased(&self) -> bool {
        self.after > self.before
    }
}

/// A table of action values `Q(row, a)` and utilities `V(row) = max_a Q(row, a)` over a
/// growable set of rows and a fixed number of actions, every value starting at 0.
///
/// Storage is dense and row-major, indexed by [`RowId`] and [`ActionId`]: no hashing, and
/// neither [`update`](QTable::update) nor the selection methods allocate.
///
/// Rows are whatever the caller says they are. Plain Q-learning gives every state its
/// own row; CS-QL gives one row to each state description, which several states share.
/// The table never assumes that a row is one state.
///
/// Boltzmann selection keeps each row's weights `exp((Q - max) / T)` and their sum
/// between calls and recomputes them only after that row's `Q` changed (or `T` did), so
/// that a row that is visited again and again without change costs no `exp`. The
/// cache is invisible: results are bit for bit those of a fresh computation.
///
/// ```
/// use mdp::ActionId;
/// use qlearn::{Discount, LearningRate, QTable, Target};
///
/// let mut table = QTable::new(2).unwrap();
/// let x = table.add_row();
/// let y = table.add_row();
/// let (beta, gamma) = (LearningRate::new(1.0).unwrap(), Discount::new(0.9).unwrap());
/// // Reaching the goal from y pays 1; moving from x to y pays nothing.
/// table.update(y, ActionId(1), 1.0, Target::Terminal, beta, gamma);
/// let change = table.update(x, ActionId(0), 0.0, Target::Bootstrap(y), beta, gamma);
/// assert_eq!((change.before, change.after), (0.0, 0.9));
/// assert_eq!(table.greedy(x), ActionId(0));
/// ```
#[derive(Clone, Debug)]
pub struct QTable {
    actions: usize,
    /// `Q`, row-major: `q[row * actions + a]`.
    q: Vec<f64>,
    /// `V(row)`, always the maximum of the row's `Q` (equation 1).
    v: Vec<f64>,
    /// Boltzmann weights `exp((Q - max) / cached_t)`, laid out like `q`.
    weights: Vec<f64>,
    /// The sum of each row's weights, or 0 when the row's weights are stale. A valid sum
    /// is at least 1 (the maximum's weight is `exp(0)`), so 0 is free to mean "stale".
    totals: Vec<f64>,
    /// The temperature the cached weights were computed for (NaN before the first use).
    cached_t: f64,
    /// What every `Q` and `V` starts at (and returns to on [`QTable::reset`]).
    initial: f64,
}

impl QTable {
    /// An empty table for `actions` actions.
    ///
    /// ```
    /// assert!(qlearn::QTable::new(4).is_ok());
    /// assert_eq!(qlearn::QTable::new(0).unwrap_err(), qlearn::Error::NoActions { actions: 0 });
    /// ```
    pub fn new(actions: usize) -> Result<QTable, Error> {
        QTable::with_rows(actions, 0)
    }

    /// A table for `actions` actions with `rows` rows already added (ids `0..rows`), as
    /// plain Q-learning wants: one row per state.
    ///
    /// ```
    /// let t = qlearn::QTable::with_rows(4, 64).unwrap();
    /// assert_eq!(t.rows(), 64);
    /// ```
    pub fn with_rows(actions: usize, rows: usize) -> Result<QTable, Error> {
        if actions == 0 {
            return Err(Error::NoActions { actions });
        }
        if u32::try_from(rows).is_err() {
            return Err(Error::TooManyStates { states: rows });
        }
        let n = rows * actions;
        Ok(QTable {
            actions,
            q: vec![0.0; n],
            v: vec![0.0; rows],
            // All-zero rows have weight exp(0) = 1 for every action at any temperature.
            weights: vec![1.0; n],
            totals: vec![actions as f64; rows],
            cached_t: f64::NAN,
            initial: 0.0,
        })
    }

    /// The same table with every `Q` and `V` starting at `initial` instead of 0, for rows
    /// already there, rows added later and after [`QTable::reset`]. Starting at a lower
    /// bound of the return (`r_min / (1 - gamma)` in a world with negative rewards) keeps
    /// utilities from decreasing while learning a deterministic world, as they do from 0
    /// when rewards are never negative (Theorem 1).
    ///
    /// ```
    /// let mut t = qlearn::QTable::with_rows(2, 1).unwrap().starting_at(-10.0).unwrap();
    /// assert_eq!(t.v(qlearn::RowId(0)), -10.0);
    /// let r = t.add_row();
    /// assert_eq!(t.q_row(r), &[-10.0, -10.0]);
    /// assert!(qlearn::QTable::new(2).unwrap().starting_at(f64::NAN).is_err());
    /// ```
    pub fn starting_at(mut self, initial: f64) -> Result<QTable, Error> {
        if !initial.is_finite() {
            return Err(Error::BadInitialValue { value: initial });
        }
        self.initial = initial;
        self.q.fill(initial);
        self.v.fill(initial);
        Ok(self)
    }

    /// Add a row with every `Q` and `V` at 0 and return its id (ids count up from 0).
    ///
    /// # Panics
    ///
    /// If the table already has `u32::MAX + 1` rows (memory runs out long before).
    ///
    /// ```
    /// let mut t = qlearn::QTable::new(3).unwrap();
    /// assert_eq!(t.add_row(), qlearn::RowId(0));
    /// assert_eq!(t.add_row(), qlearn::RowId(1));
    /// assert_eq!(t.q_row(qlearn::RowId(1)), &[0.0, 0.0, 0.0]);
    /// ```
    pub fn add_row(&mut self) -> RowId {
        #[cfg_attr(
            not(test),
            expect(
                clippy::expect_used,
                reason = "2^32 rows of Q-values would need far more memory than any machine has"
            )
        )]
        let id = RowId(u32::try_from(self.v.len()).expect("at most 2^32 rows"));
        self.q
            .extend(std::iter::repeat_n(self.initial, self.actions));
        self.weights.extend(std::iter::repeat_n(1.0, self.actions));
        self.v.push(self.initial);
        self.totals.push(self.actions as f64);
        id
    }

    /// The number of rows.
    ///
    /// ```
    /// assert_eq!(qlearn::QTable::new(2).unwrap().rows(), 0);
    /// ```
    #[inline]
    pub fn rows(&self) -> usize {
        self.v.len()
    }

    /// The number of actions.
    ///
    /// ```
    /// assert_eq!(qlearn::QTable::new(2).unwrap().num_actions(), 2);
    /// ```
    #[inline]
    pub fn num_actions(&self) -> usize {
        self.actions
    }

    /// `Q(row, action)`.
    ///
    /// # Panics
    ///
    /// If `row` or `action` is out of range.
    ///
    /// ```
    /// let t = qlearn::QTable::with_rows(2, 1).unwrap();
    /// assert_eq!(t.q(qlearn::RowId(0), mdp::ActionId(1)), 0.0);
    /// ```
    #[inline]
    pub fn q(&self, row: RowId, action: ActionId) -> f64 {
        self.q_row(row)[action.index()]
    }

    /// The `Q` values of a row, in action order.
    ///
    /// # Panics
    ///
    /// If `row` is out of range.
    ///
    /// ```
    /// let t = qlearn::QTable::with_rows(2, 1).unwrap();
    /// assert_eq!(t.q_row(qlearn::RowId(0)).len(), 2);
    /// ```
    #[inline]
    pub fn q_row(&self, row: RowId) -> &[f64] {
        let base = row.index() * self.actions;
        &self.q[base..base + self.actions]
    }

    /// `V(row)`, the largest `Q` of the row (equation 1).
    ///
    /// # Panics
    ///
    /// If `row` is out of range.
    ///
    /// ```
    /// let t = qlearn::QTable::with_rows(2, 1).unwrap();
    /// assert_eq!(t.v(qlearn::RowId(0)), 0.0);
    /// ```
    #[inline]
    pub fn v(&self, row: RowId) -> f64 {
        self.v[row.index()]
    }

    /// Every `Q`, row-major (`row * num_actions() + action`).
    ///
    /// ```
    /// let t = qlearn::QTable::with_rows(4, 3).unwrap();
    /// assert_eq!(t.q_values().len(), 12);
    /// assert_eq!(t.q_values().iter().sum::<f64>(), 0.0);
    /// ```
    #[inline]
    pub fn q_values(&self) -> &[f64] {
        &self.q
    }

    /// Every `V`, in row order.
    ///
    /// ```
    /// let t = qlearn::QTable::with_rows(4, 3).unwrap();
    /// assert_eq!(t.v_values(), &[0.0, 0.0, 0.0]);
    /// ```
    #[inline]
    pub fn v_values(&self) -> &[f64] {
        &self.v
    }

    /// Set every `Q` and `V` to 0, keeping the rows (CS-QL's resetting strategy).
    ///
    /// ```
    /// use mdp::ActionId;
    /// use qlearn::{Discount, LearningRate, QTable, RowId, Target};
    /// let mut t = QTable::with_rows(2, 1).unwrap();
    /// let (beta, gamma) = (LearningRate::new(1.0).unwrap(), Discount::new(0.9).unwrap());
    /// t.update(RowId(0), ActionId(0), 1.0, Target::Terminal, beta, gamma);
    /// t.reset();
    /// assert_eq!((t.rows(), t.v(RowId(0))), (1, 0.0));
    /// ```
    pub fn reset(&mut self) {
        self.q.fill(self.initial);
        self.v.fill(self.initial);
        // Zero rows have known weights at any temperature, so the cache stays warm.
        self.weights.fill(1.0);
        self.totals.fill(self.actions as f64);
    }

    /// The update of equation 2 followed by equation 1:
    /// `Q(row, a) += beta * (target - Q(row, a))`, then `V(row) = max_b Q(row, b)`, where
    /// the target is `reward` for [`Target::Terminal`] and `reward + gamma * V(y)` for
    /// [`Target::Bootstrap(y)`](Target::Bootstrap). Returns `V(row)` before and after.
    ///
    /// `y` may be `row` itself (a move that stays); `V(y)` is read before the update.
    /// With `beta = 1` the new `Q` is the target exactly; otherwise it is clamped so
    /// that rounding never carries it past the target (the exact result always lies
    /// between the old `Q` and the target). Without that, a one-ulp overshoot could
    /// later show as a one-ulp decrease of `V`, which Theorem 1 rules out.
    /// Rewards should be finite; a NaN or infinite reward is stored as given and never
    /// makes selection panic.
    ///
    /// # Panics
    ///
    /// If `row`, `action` or the bootstrap row is out of range.
    ///
    /// ```
    /// use mdp::ActionId;
    /// use qlearn::{Discount, LearningRate, QTable, RowId, Target};
    /// let mut t = QTable::with_rows(1, 1).unwrap();
    /// let (beta, gamma) = (LearningRate::new(0.5).unwrap(), Discount::new(0.9).unwrap());
    /// let c = t.update(RowId(0), ActionId(0), 1.0, Target::Terminal, beta, gamma);
    /// assert_eq!((c.before, c.after), (0.0, 0.5));
    /// // A self-loop bootstraps from the row's own V.
    /// let c = t.update(RowId(0), ActionId(0), 0.0, Target::Bootstrap(RowId(0)), beta, gamma);
    /// assert_eq!(c.after, 0.5 + 0.5 * (0.9 * 0.5 - 0.5));
    /// assert!(c.decreased());
    /// ```
    #[inline]
    pub fn update(
        &mut self,
        row: RowId,
        action: ActionId,
        reward: f64,
        target: Target,
        beta: LearningRate,
        gamma: Discount,
    ) -> VChange {
        let target = match target {
            Target::Terminal => reward,
            Target::Bootstrap(next) => reward + gamma.get() * self.v[next.index()],
        };
        let r = row.index();
        let base = r * self.actions;
        let q_row = &mut self.q[base..base + self.actions];
        let old = q_row[action.index()];
        let beta = beta.get();
        // Equation 2 moves Q towards the target and never past it, but rounding can
        // overshoot by an ulp (even with beta = 1: `old + (target - old)` need not be
        // `target`); the next update towards the same target would then lower V by an
        // ulp, a decrease Theorem 1 rules out and CS-QL would act on. So beta = 1 takes
        // the target exactly, and any other beta is clamped to it.
        let new = if beta == 1.0 {
            target
        } else {
            let step = old + beta * (target - old);
            if target >= old {
                step.min(target)
            } else {
                step.max(target)
            }
        };
        let before = self.v[r];
        // Skipping an update that changes nothing keeps the row's Boltzmann weights
        // valid; once values settle, most updates are of this kind.
        if new.to_bits() != old.to_bits() {
            q_row[action.index()] = new;
            self.v[r] = row_max(q_row);
            self.totals[r] = 0.0;
        }
        VChange {
            before,
            after: self.v[r],
        }
    }

    /// The greedy action of a row: the lowest-numbered action whose `Q` equals the row's
    /// maximum (ties go to the lowest id).
    ///
    /// # Panics
    ///
    /// If `row` is out of range.
    ///
    /// ```
    /// let t = qlearn::QTable::with_rows(4, 1).unwrap();
    /// assert_eq!(t.greedy(qlearn::RowId(0)), mdp::ActionId(0)); // all tied at 0
    /// ```
    #[inline]
    pub fn greedy(&self, row: RowId) -> ActionId {
        self.greedy_actions(row).next().unwrap_or(ActionId(0))
    }

    /// Every action whose `Q` equals the row's maximum exactly, in id order. With
    /// finite values there is at least one; a row holding NaN may have none.
    ///
    /// # Panics
    ///
    /// If `row` is out of range.
    ///
    /// ```
    /// use mdp::ActionId;
    /// use qlearn::{Discount, LearningRate, QTable, RowId, Target};
    /// let mut t = QTable::with_rows(3, 1).unwrap();
    /// let (beta, gamma) = (LearningRate::new(1.0).unwrap(), Discount::new(0.9).unwrap());
    /// t.update(RowId(0), ActionId(0), 1.0, Target::Terminal, beta, gamma);
    /// t.update(RowId(0), ActionId(2), 1.0, Target::Terminal, beta, gamma);
    /// let best: Vec<ActionId> = t.greedy_actions(RowId(0)).collect();
    /// assert_eq!(best, [ActionId(0), ActionId(2)]);
    /// ```
    pub fn greedy_actions(&self, row: RowId) -> impl Iterator<Item = ActionId> + '_ {
        let max = self.v(row);
        self.q_row(row)
            .iter()
            .enumerate()
            .filter(move |&(_, &q)| q == max)
            .map(|(a, _)| ActionId(a as u32))
    }

    /// Draw an action from the Boltzmann distribution of Figure 1, step 2:
    /// `P(a) = exp(Q(row, a) / T) / sum_b exp(Q(row, b) / T)`.
    ///
    /// Computed as `w_a = exp((Q(row, a) - V(row)) / T)`, which is the same distribution
    /// but cannot overflow: the largest weight is exactly 1, so the sum lies in
    /// `[1, num_actions()]` for any `T > 0` and any finite `Q`.
    ///
    /// Exactly one value is drawn from `rng`: `u = rng.random::<f64>()` (uniform in
    /// `[0, 1)`), and the action is the first `a` whose running sum `w_0 + ... + w_a`
    /// exceeds `u * sum`. Should rounding leave `u * sum` at the sum, the last action of
    /// positive weight is taken; a row whose weights are not numbers (NaN rewards) falls
    /// back to [`greedy`](QTable::greedy). Never panics for a valid row.
    ///
    /// The weights are cached per row (see the type's docs), hence `&mut self`.
    ///
    /// # Panics
    ///
    /// If `row` is out of range.
    ///
    /// ```
    /// use rand::SeedableRng;
    /// use qlearn::{QTable, RowId, Temperature};
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
    /// let mut t = QTable::with_rows(4, 1).unwrap();
    /// let a = t.boltzmann(RowId(0), Temperature::new(0.4).unwrap(), &mut rng);
    /// assert!(a.index() < 4);
    /// ```
    #[inline]
    pub fn boltzmann<R: Rng + ?Sized>(
        &mut self,
        row: RowId,
        temperature: Temperature,
        rng: &mut R,
    ) -> ActionId {
        let t = temperature.get();
        if t.to_bits() != self.cached_t.to_bits() {
            self.retune(t);
        }
        let r = row.index();
        let base = r * self.actions;
        let mut total = self.totals[r];
        // A NaN sum is not fresh either, and is then recomputed each time.
        let fresh = total > 0.0;
        if !fresh {
            total = self.refresh(r, t);
        }
        let u = rng.random::<f64>() * total;
        let weights = &self.weights[base..base + self.actions];
        let mut acc = 0.0;
        for (a, &w) in weights.iter().enumerate() {
            acc += w;
            if u < acc {
                return ActionId(a as u32);
            }
        }
        self.boltzmann_fallback(row)
    }

    /// The rare end of [`boltzmann`](QTable::boltzmann), kept out of line.
    #[cold]
    fn boltzmann_fallback(&self, row: RowId) -> ActionId {
        let base = row.index() * self.actions;
        self.weights[base..base + self.actions]
            .iter()
            .rposition(|&w| w > 0.0)
            .map_or_else(|| self.greedy(row), |a| ActionId(a as u32))
    }

    /// The Boltzmann probabilities of a row's actions, computed afresh (no cache), for
    /// inspection and tests.
    ///
    /// # Panics
    ///
    /// If `row` is out of range.
    ///
    /// ```
    /// use qlearn::{QTable, RowId, Temperature};
    /// let t = QTable::with_rows(4, 1).unwrap();
    /// let p = t.boltzmann_probabilities(RowId(0), Temperature::new(0.4).unwrap());
    /// assert_eq!(p, [0.25; 4]);
    /// ```
    pub fn boltzmann_probabilities(&self, row: RowId, temperature: Temperature) -> Vec<f64> {
        let mut w = vec![0.0; self.actions];
        let total = boltzmann_weights(self.q_row(row), temperature.get(), &mut w);
        w.iter_mut().for_each(|x| *x /= total);
        w
    }

    /// Epsilon-greedy selection: with probability epsilon an action drawn uniformly,
    /// otherwise [`greedy`](QTable::greedy).
    ///
    /// Draws `u = rng.random::<f64>()` first; if `u < epsilon` it draws the action with
    /// `rng.random_range(0..num_actions())`. So one draw when exploiting, two when
    /// exploring.
    ///
    /// # Panics
    ///
    /// If `row` is out of range.
    ///
    /// ```
    /// use rand::SeedableRng;
    /// use qlearn::{Epsilon, QTable, RowId};
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
    /// let t = QTable::with_rows(4, 1).unwrap();
    /// let a = t.epsilon_greedy(RowId(0), Epsilon::new(0.0).unwrap(), &mut rng);
    /// assert_eq!(a, t.greedy(RowId(0)));
    /// ```
    #[inline]
    pub fn epsilon_greedy<R: Rng + ?Sized>(
        &self,
        row: RowId,
        epsilon: Epsilon,
        rng: &mut R,
    ) -> ActionId {
        if rng.random::<f64>() < epsilon.get() {
            ActionId(rng.random_range(0..self.actions as u32))
        } else {
            self.greedy(row)
        }
    }

    /// Mark every row's weights stale because the temperature changed.
    #[cold]
    fn retune(&mut self, t: f64) {
        self.totals.fill(0.0);
        self.cached_t = t;
    }

    /// Recompute one row's weights; returns their sum.
    fn refresh(&mut self, r: usize, t: f64) -> f64 {
        let base = r * self.actions;
        let total = boltzmann_weights(
            &self.q[base..base + self.actions],
            t,
            &mut self.weights[base..base + self.actions],
        );
        self.totals[r] = total;
        total
    }
}

/// The largest value of a row. NaN entries are skipped by `f64::max`.
#[inline]
fn row_max(q: &[f64]) -> f64 {
    q.iter().copied().fold(f64::NEG_INFINITY, f64::max)
}

/// Fill `out` with `exp((q - max) / t)` and return the sum, in action order. Every
/// Boltzmann number in this crate comes from here, so cached and fresh weights agree bit
/// for bit.
#[inline]
fn boltzmann_weights(q: &[f64], t: f64, out: &mut [f64]) -> f64 {
    let max = row_max(q);
    let mut total = 0.0;
    for (w, &x) in out.iter_mut().zip(q) {
        *w = ((x - max) / t).exp();
        total += *w;
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_xoshiro::Xoshiro256PlusPlus;

    fn rates(beta: f64, gamma: f64) -> (LearningRate, Discount) {
        (
            LearningRate::new(beta).unwrap(),
            Discount::new(gamma).unwrap(),
        )
    }

    /// The cache must equal a fresh computation for every row it claims to hold.
    fn assert_cache_fresh(t: &QTable) {
        for r in 0..t.rows() {
            if t.totals[r] > 0.0 {
                let base = r * t.actions;
                let mut w = vec![0.0; t.actions];
                let total = boltzmann_weights(&t.q[base..base + t.actions], t.cached_t, &mut w);
                assert_eq!(t.totals[r].to_bits(), total.to_bits(), "row {r} total");
                for (a, (&c, &f)) in t.weights[base..base + t.actions].iter().zip(&w).enumerate() {
                    assert_eq!(c.to_bits(), f.to_bits(), "row {r} action {a}");
                }
            }
        }
    }

    #[test]
    fn cache_matches_fresh_computation_after_updates_reset_and_retune() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
        let mut table = QTable::with_rows(4, 6).unwrap();
        let (beta, gamma) = rates(0.7, 0.9);
        let temps = [0.4, 0.4, 0.05, 3.0].map(|t| Temperature::new(t).unwrap());
        let mut refreshed = 0;
        for (round, &t) in temps.iter().enumerate() {
            for _ in 0..500 {
                let row = RowId(rng.random_range(0..6));
                let a = table.boltzmann(row, t, &mut rng);
                refreshed += usize::from(table.totals[row.index()] > 0.0);
                let target = if rng.random_bool(0.2) {
                    Target::Terminal
                } else {
                    Target::Bootstrap(RowId(rng.random_range(0..6)))
                };
                table.update(row, a, rng.random::<f64>(), target, beta, gamma);
                assert_cache_fresh(&table);
            }
            if round == 1 {
                table.reset();
                assert_cache_fresh(&table);
                assert!(table.q_values().iter().all(|&q| q == 0.0));
                // Zero rows are valid without recomputation.
                assert!(table.totals.iter().all(|&s| s == 4.0));
            }
            table.add_row();
            assert_cache_fresh(&table);
        }
        assert!(refreshed > 0, "the cache was never used");
    }

    #[test]
    fn a_cached_draw_equals_a_draw_from_fresh_weights() {
        let t = Temperature::new(0.3).unwrap();
        let (beta, gamma) = rates(1.0, 0.9);
        let mut table = QTable::with_rows(4, 2).unwrap();
        table.update(RowId(0), ActionId(2), 0.5, Target::Terminal, beta, gamma);
        table.update(RowId(0), ActionId(1), 0.2, Target::Terminal, beta, gamma);
        let mut cached = Xoshiro256PlusPlus::seed_from_u64(3);
        let mut fresh = cached.clone();
        for _ in 0..1000 {
            let a = table.boltzmann(RowId(0), t, &mut cached);
            // Reference: an uncached draw from the same stream.
            let p = table.boltzmann_probabilities(RowId(0), t);
            let u = fresh.random::<f64>();
            let mut acc = 0.0;
            let b = p
                .iter()
                .position(|&x| {
                    acc += x;
                    u < acc
                })
                .unwrap_or(3);
            // Probabilities are normalised, weights are not: the draws may only differ
            // where rounding puts u on a boundary, which this seed never does.
            assert_eq!(a.index(), b);
        }
    }

    #[test]
    fn extreme_temperatures_and_values_never_give_nan() {
        let (beta, gamma) = rates(1.0, 0.0);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
        let mut table = QTable::with_rows(4, 1).unwrap();
        table.update(RowId(0), ActionId(1), 1e6, Target::Terminal, beta, gamma);
        table.update(
            RowId(0),
            ActionId(3),
            1e6 - 1e-3,
            Target::Terminal,
            beta,
            gamma,
        );
        for t in [1e-6, 1e-300, 0.4, 1e6, f64::MAX] {
            let t = Temperature::new(t).unwrap();
            let p = table.boltzmann_probabilities(RowId(0), t);
            assert!(p.iter().all(|x| x.is_finite() && *x >= 0.0), "{p:?}");
            assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            for _ in 0..100 {
                assert!(table.boltzmann(RowId(0), t, &mut rng).index() < 4);
            }
        }
        let tiny = Temperature::new(1e-6).unwrap();
        for _ in 0..100 {
            assert_eq!(table.boltzmann(RowId(0), tiny, &mut rng), ActionId(1));
        }
    }

    #[test]
    fn nan_rewards_do_not_panic_selection() {
        let (beta, gamma) = rates(1.0, 0.9);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
        let mut table = QTable::with_rows(2, 1).unwrap();
        table.update(
            RowId(0),
            ActionId(0),
            f64::NAN,
            Target::Terminal,
            beta,
            gamma,
        );
        let t = Temperature::new(0.4).unwrap();
        for _ in 0..10 {
            assert!(table.boltzmann(RowId(0), t, &mut rng).index() < 2);
        }
        table.update(
            RowId(0),
            ActionId(1),
            f64::INFINITY,
            Target::Terminal,
            beta,
            gamma,
        );
        for _ in 0..10 {
            assert!(table.boltzmann(RowId(0), t, &mut rng).index() < 2);
        }
    }

    #[test]
    fn unchanged_updates_keep_the_cache_and_changed_ones_drop_it() {
        let (beta, gamma) = rates(1.0, 0.9);
        let t = Temperature::new(0.4).unwrap();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
        let mut table = QTable::with_rows(2, 1).unwrap();
        table.update(RowId(0), ActionId(0), 1.0, Target::Terminal, beta, gamma);
        table.boltzmann(RowId(0), t, &mut rng);
        assert!(table.totals[0] > 0.0);
        table.update(RowId(0), ActionId(0), 1.0, Target::Terminal, beta, gamma);
        assert!(
            table.totals[0] > 0.0,
            "an update to the same value dropped the cache"
        );
        table.update(RowId(0), ActionId(1), 0.5, Target::Terminal, beta, gamma);
        assert_eq!(table.totals[0], 0.0);
    }

    #[test]
    fn greedy_breaks_ties_by_lowest_id() {
        let (beta, gamma) = rates(1.0, 0.9);
        let mut table = QTable::with_rows(4, 1).unwrap();
        table.update(RowId(0), ActionId(3), 1.0, Target::Terminal, beta, gamma);
        table.update(RowId(0), ActionId(1), 1.0, Target::Terminal, beta, gamma);
        assert_eq!(table.greedy(RowId(0)), ActionId(1));
        let all: Vec<_> = table.greedy_actions(RowId(0)).collect();
        assert_eq!(all, [ActionId(1), ActionId(3)]);
    }

    #[test]
    fn epsilon_one_explores_uniformly_and_zero_never_does() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(9);
        let (beta, gamma) = rates(1.0, 0.9);
        let mut table = QTable::with_rows(4, 1).unwrap();
        table.update(RowId(0), ActionId(2), 1.0, Target::Terminal, beta, gamma);
        let mut counts = [0u32; 4];
        for _ in 0..4000 {
            let a = table.epsilon_greedy(RowId(0), Epsilon::new(1.0).unwrap(), &mut rng);
            counts[a.index()] += 1;
        }
        assert!(
            counts.iter().all(|&c| (850..1150).contains(&c)),
            "{counts:?}"
        );
        for _ in 0..100 {
            let a = table.epsilon_greedy(RowId(0), Epsilon::new(0.0).unwrap(), &mut rng);
            assert_eq!(a, ActionId(2));
        }
    }
}
