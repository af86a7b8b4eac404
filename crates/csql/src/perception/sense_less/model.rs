//! The learned transition model at the level of descriptions: (description, action) ->
//! next description, trusted after a run of equal measurements ([`TransitionModel`]).
//! It knows nothing of worlds, sensing or the oracle.

use mdp::ActionId;
use qlearn::RowId;

/// What the model knows of one (description, action).
#[derive(Clone, Debug, Default)]
struct Entry {
    /// The last next description measured.
    next: Option<RowId>,
    /// Every next description measured, in the order first seen.
    successors: Vec<RowId>,
    /// How often each of `successors` was measured (the weighed level's frequencies).
    counts: Vec<u32>,
    /// Measurements since the entry was last invalidated.
    measured: u32,
    /// Whether a use of the transition was found wrong (set by [`TransitionModel::distrust`]).
    distrusted: bool,
    /// Measurements in a row that gave `next`.
    agree: u32,
    /// Whether two measurements disagreed since the entry was last invalidated.
    conflicted: bool,
    /// Unmeasured uses since the last measurement.
    unmeasured: u32,
}

/// The learned transition model at the level of descriptions: (description, action) ->
/// next description, with the confidence rule of [`PredictionParams::confirmations`](crate::PredictionParams::confirmations).
///
/// ```
/// use csql::TransitionModel;
/// use mdp::ActionId;
/// use qlearn::RowId;
/// let mut m = TransitionModel::new(4, 2);
/// let (d, e) = (RowId(0), RowId(1));
/// m.observe(d, ActionId(1), e);
/// assert_eq!(m.trusted(d, ActionId(1)), None); // one measurement is not enough
/// m.observe(d, ActionId(1), e);
/// assert_eq!(m.trusted(d, ActionId(1)), Some(e));
/// m.invalidate(e); // refining e invalidates what leads to it
/// assert_eq!(m.trusted(d, ActionId(1)), None);
/// ```
#[derive(Clone, Debug)]
pub struct TransitionModel {
    actions: usize,
    confirmations: u32,
    entries: Vec<Entry>,
}

impl TransitionModel {
    /// An empty model for `actions` actions that trusts a transition after
    /// `confirmations` equal measurements.
    ///
    /// ```
    /// let m = csql::TransitionModel::new(4, 3);
    /// assert_eq!(m.trusted(qlearn::RowId(7), mdp::ActionId(0)), None);
    /// ```
    pub fn new(actions: usize, confirmations: u32) -> TransitionModel {
        TransitionModel {
            actions,
            confirmations,
            entries: Vec::new(),
        }
    }

    fn index(&self, from: RowId, a: ActionId) -> usize {
        from.index() * self.actions + a.index()
    }

    fn entry(&self, from: RowId, a: ActionId) -> Option<&Entry> {
        self.entries.get(self.index(from, a))
    }

    /// Unmeasured uses of a transition since it was last measured, distrusted or
    /// invalidated.
    pub(crate) fn unmeasured_uses(&self, from: RowId, a: ActionId) -> u32 {
        self.entry(from, a).map_or(0, |e| e.unmeasured)
    }

    /// The transition's outcome was classified in full from a state whose description
    /// was not: its run of unmeasured uses ends, and nothing is learned.
    pub(crate) fn measured_unobserved(&mut self, from: RowId, a: ActionId) {
        self.entry_mut(from, a).unmeasured = 0;
    }

    /// The transition was used without a measurement.
    pub(crate) fn used_unmeasured(&mut self, from: RowId, a: ActionId) {
        self.entry_mut(from, a).unmeasured += 1;
    }

    fn entry_mut(&mut self, from: RowId, a: ActionId) -> &mut Entry {
        let i = self.index(from, a);
        if i >= self.entries.len() {
            self.entries.resize(i + 1, Entry::default());
        }
        &mut self.entries[i]
    }

    /// The predicted next description, if the transition is trusted.
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 1);
    /// let (d, a) = (qlearn::RowId(0), mdp::ActionId(0));
    /// m.observe(d, a, qlearn::RowId(2));
    /// assert_eq!(m.trusted(d, a), Some(qlearn::RowId(2)));
    /// m.observe(d, a, qlearn::RowId(3)); // disagrees: distrusted for good
    /// m.observe(d, a, qlearn::RowId(3));
    /// assert_eq!(m.trusted(d, a), None);
    /// ```
    pub fn trusted(&self, from: RowId, a: ActionId) -> Option<RowId> {
        self.entry(from, a)
            .filter(|e| !e.conflicted && e.agree >= self.confirmations)
            .and_then(|e| e.next)
    }

    /// Record a measured transition; returns whether it agreed with what the model held
    /// (true for the first measurement).
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 2);
    /// let (d, a) = (qlearn::RowId(0), mdp::ActionId(3));
    /// assert!(m.observe(d, a, qlearn::RowId(1)));
    /// assert!(!m.observe(d, a, qlearn::RowId(2)));
    /// ```
    pub fn observe(&mut self, from: RowId, a: ActionId, to: RowId) -> bool {
        let e = self.entry_mut(from, a);
        e.unmeasured = 0;
        e.measured = e.measured.saturating_add(1);
        match e.successors.iter().position(|&r| r == to) {
            Some(i) => e.counts[i] = e.counts[i].saturating_add(1),
            None => {
                e.successors.push(to);
                e.counts.push(1);
            }
        }
        match e.next {
            Some(n) if n == to => {
                e.agree = e.agree.saturating_add(1);
                true
            }
            Some(_) => {
                e.next = Some(to);
                e.agree = 1;
                e.conflicted = true;
                false
            }
            None => {
                e.next = Some(to);
                e.agree = 1;
                true
            }
        }
    }

    /// Never trust a transition again until it is invalidated (a prediction of it was
    /// found wrong).
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 1);
    /// let (d, a) = (qlearn::RowId(0), mdp::ActionId(0));
    /// m.observe(d, a, qlearn::RowId(1));
    /// m.distrust(d, a);
    /// assert_eq!(m.trusted(d, a), None);
    /// ```
    pub fn distrust(&mut self, from: RowId, a: ActionId) {
        let e = self.entry_mut(from, a);
        e.conflicted = true;
        e.distrusted = true;
        e.unmeasured = 0;
    }

    /// The measured frequencies of a transition's next descriptions, once it has been
    /// measured at least `confirmations` times and never found wrong since it was last
    /// invalidated (the weighed level's trust): `(description, count)` in the order first
    /// seen, and the number of measurements.
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 2);
    /// let (d, a) = (qlearn::RowId(0), mdp::ActionId(0));
    /// m.observe(d, a, qlearn::RowId(4));
    /// assert!(m.frequencies(d, a).is_none()); // one measurement is not enough
    /// m.observe(d, a, qlearn::RowId(2));
    /// let (next, n) = m.frequencies(d, a).unwrap();
    /// assert_eq!((next.count(), n), (2, 2));
    /// m.distrust(d, a);
    /// assert!(m.frequencies(d, a).is_none());
    /// ```
    pub fn frequencies(
        &self,
        from: RowId,
        a: ActionId,
    ) -> Option<(impl Iterator<Item = (RowId, u32)> + '_, u32)> {
        self.entry(from, a)
            .filter(|e| !e.distrusted && e.measured >= self.confirmations)
            .map(|e| {
                (
                    e.successors.iter().copied().zip(e.counts.iter().copied()),
                    e.measured,
                )
            })
    }

    /// Forget what a refinement of `row` may have made wrong, for a model whose
    /// transitions may have several next descriptions: the transitions that leave `row`
    /// and every one that has led to it.
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 1);
    /// let a = mdp::ActionId(0);
    /// m.observe(qlearn::RowId(0), a, qlearn::RowId(1));
    /// m.observe(qlearn::RowId(0), a, qlearn::RowId(2));
    /// m.invalidate_outcome(qlearn::RowId(1)); // not the last outcome, but one of them
    /// assert!(m.frequencies(qlearn::RowId(0), a).is_none());
    /// ```
    pub fn invalidate_outcome(&mut self, row: RowId) {
        self.forget(row, |e| e.successors.contains(&row));
    }

    /// Every next description measured for a transition since it was last invalidated,
    /// in the order first seen: the edges of the reduced map.
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 1);
    /// let (d, a) = (qlearn::RowId(0), mdp::ActionId(0));
    /// m.observe(d, a, qlearn::RowId(4));
    /// m.observe(d, a, qlearn::RowId(2));
    /// m.observe(d, a, qlearn::RowId(4));
    /// assert_eq!(m.successors(d, a), [qlearn::RowId(4), qlearn::RowId(2)]);
    /// ```
    pub fn successors(&self, from: RowId, a: ActionId) -> &[RowId] {
        self.entry(from, a).map_or(&[], |e| &e.successors)
    }

    /// Forget what a refinement of `row` may have made wrong: the transitions that leave
    /// it and those that lead to it.
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 1);
    /// let a = mdp::ActionId(0);
    /// m.observe(qlearn::RowId(0), a, qlearn::RowId(1));
    /// m.observe(qlearn::RowId(2), a, qlearn::RowId(3));
    /// m.invalidate(qlearn::RowId(0));
    /// assert_eq!(m.trusted(qlearn::RowId(0), a), None);
    /// assert_eq!(m.trusted(qlearn::RowId(2), a), Some(qlearn::RowId(3))); // untouched
    /// ```
    pub fn invalidate(&mut self, row: RowId) {
        self.forget(row, |e| e.next == Some(row));
    }

    /// Forget the transitions that leave `row`, and those `leads` says lead to it.
    fn forget(&mut self, row: RowId, leads: impl Fn(&Entry) -> bool) {
        let actions = self.actions;
        for (i, e) in self.entries.iter_mut().enumerate() {
            if i / actions == row.index() || leads(e) {
                *e = Entry::default();
            }
        }
    }

    /// How many transitions gave two different answers since they were last invalidated
    /// (the reduced map is deterministic everywhere else).
    ///
    /// ```
    /// let mut m = csql::TransitionModel::new(4, 1);
    /// m.observe(qlearn::RowId(0), mdp::ActionId(0), qlearn::RowId(0));
    /// assert_eq!(m.conflicts(), 0);
    /// ```
    pub fn conflicts(&self) -> usize {
        self.entries.iter().filter(|e| e.conflicted).count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_disagreement_distrusts_until_invalidated() {
        let mut m = TransitionModel::new(4, 2);
        let (d, a) = (RowId(3), ActionId(2));
        for _ in 0..5 {
            m.observe(d, a, RowId(1));
        }
        assert_eq!(m.trusted(d, a), Some(RowId(1)));
        m.observe(d, a, RowId(2));
        for _ in 0..5 {
            m.observe(d, a, RowId(2));
        }
        assert_eq!(m.trusted(d, a), None);
        assert_eq!(m.conflicts(), 1);
        m.invalidate(RowId(2));
        assert_eq!(m.conflicts(), 0);
        m.observe(d, a, RowId(2));
        m.observe(d, a, RowId(2));
        assert_eq!(m.trusted(d, a), Some(RowId(2)));
    }

    #[test]
    fn invalidation_touches_only_the_refined_row() {
        let mut m = TransitionModel::new(4, 1);
        for from in 0..5u32 {
            for a in 0..4u32 {
                m.observe(RowId(from), ActionId(a), RowId((from + a) % 5));
            }
        }
        m.invalidate(RowId(2));
        for from in 0..5u32 {
            for a in 0..4u32 {
                let to = (from + a) % 5;
                let kept = from != 2 && to != 2;
                assert_eq!(
                    m.trusted(RowId(from), ActionId(a)).is_some(),
                    kept,
                    "{from} {a}"
                );
            }
        }
    }
}
