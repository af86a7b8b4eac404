//! The oracle's audit of a predicting learner, from outside it: the number of states
//! given a description without measurement whose description was wrong, and the longest
//! run of wrong predictions of one transition between two of its measurements (the
//! bound of `predict_sensing`, at most `max_skips`).
//!
//! [`Audited`] wraps a [`Predicting`] perception for a run ([`Wraps`]: every call passes
//! through unchanged), and after each [`Perception::classify_next`] that used a transition without
//! measuring, it looks up the true description of the state reached through the free
//! view ([`Perception::lookup`], the oracle's), never charged and never shown to the
//! learner. The learner itself never calls the oracle.

use std::collections::BTreeMap;

use mdp::World;

use crate::perception::rows::Perception;
use crate::perception::sense_less::{Predicting, PredictionStats};
use crate::perception::wraps::Wraps;

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

    /// Give up the audit.
    pub(crate) fn into_inner(self) -> Predicting {
        self.inner
    }
}

impl Wraps for Audited {
    type Inner = Predicting;

    fn inner(&self) -> &Predicting {
        &self.inner
    }

    fn inner_mut(&mut self) -> &mut Predicting {
        &mut self.inner
    }

    /// After a move classified by an unmeasured use of a transition: whether the
    /// description given is the state's true one, through the oracle's free view.
    fn after_next<W: World + ?Sized>(&mut self, world: &W) {
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
    }
}
