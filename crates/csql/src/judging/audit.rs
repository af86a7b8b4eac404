//! The oracle's audit of a predicting learner, from outside it: the number of states
//! given a description without measurement whose description was wrong, and the longest
//! run of wrong predictions of one transition between two of its measurements (the
//! bound of `predict_sensing`, at most `max_skips`).
//!
//! [`Audited`] wraps a [`Predicting`] perception for a run. It passes every call through
//! unchanged, and after each [`Perception::classify_next`] that used a transition without
//! measuring, it looks up the true description of the state reached through the free
//! view ([`Perception::lookup`], the oracle's), never charged and never shown to the
//! learner. The learner itself never calls the oracle.

use std::collections::BTreeMap;

use mdp::{ActionId, Reading, SensorNoise, StateId, World};
use qlearn::{QTable, RowId};
use rand::Rng;

use crate::perception::predict::{Predicting, PredictionStats};
use crate::perception::rows::Perception;
use crate::perception::view::{Describes, Sees};

/// A [`Predicting`] perception and the oracle's count of its wrong predictions.
#[derive(Clone, Debug)]
pub(crate) struct Audited {
    inner: Predicting,
    /// Wrong unmeasured uses of each (description, action) since it was last measured,
    /// distrusted or invalidated.
    runs: BTreeMap<(u32, u32), u32>,
    wrong: u64,
    longest_wrong_run: u32,
}

impl Audited {
    /// Audit `inner` from now on.
    pub(crate) fn new(inner: Predicting) -> Audited {
        Audited {
            inner,
            runs: BTreeMap::new(),
            wrong: 0,
            longest_wrong_run: 0,
        }
    }

    /// The learner's own figures with the oracle's count of wrong predictions.
    pub(crate) fn stats(&self) -> PredictionStats {
        PredictionStats {
            wrong: self.wrong,
            longest_wrong_run: self.longest_wrong_run,
            ..self.inner.stats()
        }
    }

    /// The learner audited.
    pub(crate) fn inner_mut(&mut self) -> &mut Predicting {
        &mut self.inner
    }

    /// Give up the audit.
    pub(crate) fn into_inner(self) -> Predicting {
        self.inner
    }
}

impl Perception for Audited {
    fn classify<W: World + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        self.inner.classify(world, s, table)
    }

    fn classify_next<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        from: RowId,
        a: ActionId,
        s: StateId,
        table: &mut QTable,
        rng: &mut R,
    ) -> (RowId, f64) {
        let out = self.inner.classify_next(world, from, a, s, table, rng);
        if let Some((u, uses)) = self.inner.last_unmeasured() {
            let truth = self.inner.lookup(world, u.s);
            let run = self.runs.entry((u.from.0, u.a.0)).or_insert(0);
            // The first unmeasured use since the transition was last measured (or
            // distrusted, or invalidated) starts a new run.
            if uses == 1 {
                *run = 0;
            }
            if truth != Some(u.row) {
                *run += 1;
                self.wrong += 1;
                self.longest_wrong_run = self.longest_wrong_run.max(*run);
            }
        }
        out
    }

    fn classify_again<W: World + ?Sized>(
        &mut self,
        world: &W,
        refined: RowId,
        current: RowId,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        self.inner.classify_again(world, refined, current, s, table)
    }

    fn updated(
        &mut self,
        row: RowId,
        a: ActionId,
        reward: f64,
        next: Option<RowId>,
        table: &mut QTable,
    ) {
        self.inner.updated(row, a, reward, next, table);
    }

    fn refine<W: World + ?Sized>(&mut self, world: &W, row: RowId, s: StateId) -> Option<f64> {
        self.inner.refine(world, row, s)
    }

    fn rows(&self) -> usize {
        self.inner.rows()
    }

    fn lookup<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> Option<RowId> {
        self.inner.lookup(world, s)
    }

    fn learns_from_move(&self, ended: bool) -> bool {
        self.inner.learns_from_move(ended)
    }
}

impl Sees for Audited {
    fn sees<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        noise: SensorNoise,
        rng: &mut R,
    ) -> Option<RowId> {
        self.inner.sees(world, s, noise, rng)
    }
    fn memoryless(&self) -> bool {
        self.inner.memoryless()
    }
    fn begin(&mut self) {
        self.inner.begin();
    }
    fn moved(&mut self, a: ActionId) {
        self.inner.moved(a);
    }
}

impl Describes for Audited {
    fn described(&self) -> Vec<(RowId, Vec<(mdp::Feature, Reading)>)> {
        self.inner.described()
    }
    fn cost_after_learning<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> f64 {
        self.inner.cost_after_learning(world, s)
    }
    fn table1_costs<W: World + ?Sized>(&mut self, world: &W) -> (f64, f64) {
        self.inner.table1_costs(world)
    }
}
