//! The weighed level (`predict_sensing = "weighed"`): after a move, the frequencies the
//! model measured give the descriptions the agent may now have, with their
//! probabilities; the agent weighs acting on that belief against the price of measuring
//! (specification 6.14, `docs/predict_sensing.md`).
//!
//! The choice is made with the move, before its outcome: it depends only on the belief
//! before the move, the action and the model.
//!
//! * The belief after the move is the belief before it pushed through the model's
//!   frequencies. It exists only when every description it starts from has a trusted
//!   transition for the action (measured at least `confirmations` times, never found
//!   wrong); otherwise the agent classifies in full, as the paper does.
//! * Acting on the belief means acting as its most likely description: the loss is the
//!   expected shortfall of that description's greedy action,
//!   `sum_d b(d) (max_a Q(d, a) - Q(d, a*))`. The belief is carried to the next move, so
//!   the uncertainty a skip leaves is weighed again, grown, at the next choice; the
//!   main loop learns nothing from a move from or to a state given the most likely of
//!   several descriptions ([`crate::Perception::learns_from_move`]).
//! * Measuring costs at least: with one likely description, its features (what
//!   classifying a state of it reads); with several, the cheapest feature two of them
//!   read differently. Both at the price in reward units.
//! * The agent skips when the loss is below that price; otherwise, with several likely
//!   descriptions, it measures only what tells them apart (CLASSIFY's rule restricted to
//!   them, [`Classify::classify_among`]), and with one it classifies in full.
//!
//! At a price of 0 the agent never skips or narrows and classifies again after a
//! refinement, so a run is the paper's, move for move. No more than `max_skips` moves
//! pass without a classification in full, no transition is used more than `max_skips`
//! times in a row without its outcome classified in full, and a use chosen to skip or
//! narrow is re-checked in full with probability `recheck` (one draw, only then).

use mdp::{ActionId, StateId, World};
use qlearn::{QTable, RowId};
use rand::{Rng, RngExt};

use super::{Choice, Known, Predicting};
use crate::perception::classify::Classify;
use crate::perception::representation::DescriptionId;

impl Predicting {
    /// What the weighed level chooses after action `a` from row `from`, before the
    /// outcome.
    pub(super) fn choose(&self, from: RowId, a: ActionId, table: &QTable) -> Choice {
        let price = self.price.unwrap_or(0.0);
        if price <= 0.0
            || self.blind >= self.max_skips
            || self.model.unmeasured_uses(from, a) >= self.max_skips
        {
            return Choice::Classify;
        }
        let before: Vec<(RowId, f64)> = match &self.known {
            Known::Measured | Known::Trusted => vec![(from, 1.0)],
            Known::Spread(b) => b.clone(),
            Known::Lost => return Choice::Classify,
        };
        let mut after: Vec<(RowId, f64)> = Vec::new();
        for (d, p) in before {
            let Some((next, n)) = self.model.frequencies(d, a) else {
                return Choice::Classify;
            };
            for (r, c) in next {
                let q = p * f64::from(c) / f64::from(n);
                match after.iter_mut().find(|(x, _)| *x == r) {
                    Some((_, w)) => *w += q,
                    None => after.push((r, q)),
                }
            }
        }
        // The most likely description, the first of equals in the order first seen.
        let Some(&(likely, _)) =
            after
                .iter()
                .fold(None, |best: Option<&(RowId, f64)>, x| match best {
                    Some(b) if b.1 >= x.1 => Some(b),
                    _ => Some(x),
                })
        else {
            return Choice::Classify;
        };
        let act = table.greedy(likely);
        let loss: f64 = after
            .iter()
            .map(|&(d, p)| p * (table.q(d, table.greedy(d)) - table.q(d, act)))
            .sum();
        let rows: Vec<RowId> = after.iter().map(|&(d, _)| d).collect();
        if loss < price * self.least_to_measure(&rows) {
            Choice::Skip(likely, after)
        } else if after.len() >= 2 {
            Choice::Narrow(after)
        } else {
            Choice::Classify
        }
    }

    /// The least that measuring a state of one of `rows` costs: the features of the one
    /// description, or the cheapest feature two of them read differently.
    fn least_to_measure(&self, rows: &[RowId]) -> f64 {
        let rep = self.inner.representation();
        let prices = self.inner.prices();
        if let [only] = rows {
            return rep
                .get(DescriptionId(only.0))
                .features()
                .map(|(f, _)| prices[f.index()])
                .sum();
        }
        let mut least = f64::INFINITY;
        for (i, &d) in rows.iter().enumerate() {
            for (f, v) in rep.get(DescriptionId(d.0)).features() {
                let differs = rows[i + 1..]
                    .iter()
                    .any(|&e| rep.get(DescriptionId(e.0)).value(f).is_some_and(|w| w != v));
                if differs {
                    least = least.min(prices[f.index()]);
                }
            }
        }
        if least.is_finite() { least } else { 0.0 }
    }

    /// The weighed level's [`Perception::classify_next`].
    pub(super) fn next_by_belief<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        from: RowId,
        a: ActionId,
        s: StateId,
        table: &mut QTable,
        rng: &mut R,
    ) -> (RowId, f64) {
        self.previous = self.current.take();
        self.left_guessed = self.known.guessed();
        let choice = self.choose(from, a, table);
        let likely: Vec<RowId> = match &choice {
            Choice::Classify => return self.classify_in_full(world, from, a, s, table),
            Choice::Skip(_, b) | Choice::Narrow(b) => b.iter().map(|&(d, _)| d).collect(),
        };
        // One draw per use chosen to skip or narrow.
        let draw: f64 = rng.random();
        if draw < self.recheck {
            self.stats.rechecks += 1;
            let (row, cost) = self.classify_in_full(world, from, a, s, table);
            if !likely.contains(&row) {
                self.stats.caught += 1;
            }
            return (row, cost);
        }
        match choice {
            Choice::Skip(row, belief) => {
                self.stats.skipped += 1;
                self.unmeasured(from, a, s, row);
                self.blind += 1;
                self.known = if belief.len() == 1 {
                    Known::Trusted
                } else {
                    Known::Spread(belief)
                };
                (row, 0.0)
            }
            _ => {
                let (found, partial) = self.read_apart(world, s, &likely);
                if let Some(d) = found {
                    self.stats.narrowed += 1;
                    self.unmeasured(from, a, s, d.row());
                    self.blind += 1;
                    self.known = Known::Trusted;
                    return (d.row(), partial);
                }
                // None of the likely descriptions: the model was wrong where it started.
                self.stats.caught += 1;
                self.distrust_before(from, a);
                let (row, cost) = self.classify_in_full(world, from, a, s, table);
                (row, partial + cost)
            }
        }
    }

    /// Which of `rows` state `s` has, reading only what tells them apart (charged), and
    /// what was read.
    fn read_apart<W: World + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        rows: &[RowId],
    ) -> (Option<DescriptionId>, f64) {
        let candidates: Vec<DescriptionId> = rows.iter().map(|&r| DescriptionId(r.0)).collect();
        let found = self.inner.classify_among(world, s, &candidates);
        (found, self.charge(self.inner.last_cost()))
    }

    /// Distrust every transition the belief before the move used.
    fn distrust_before(&mut self, from: RowId, a: ActionId) {
        match &self.known {
            Known::Spread(b) => {
                for d in b.iter().map(|&(d, _)| d).collect::<Vec<_>>() {
                    self.model.distrust(d, a);
                }
            }
            _ => self.model.distrust(from, a),
        }
    }

    /// Classify `s` in full (charged); the transition is learned when the state left
    /// was classified in full too.
    fn classify_in_full<W: World + ?Sized>(
        &mut self,
        world: &W,
        from: RowId,
        a: ActionId,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        let (row, cost) = self.measure(world, s, table);
        if self.known == Known::Measured {
            self.model.observe(from, a, row);
        } else {
            self.model.measured_unobserved(from, a);
        }
        self.known = Known::Measured;
        self.blind = 0;
        (row, cost)
    }

    /// After a refinement of `row`: forget the transitions it may have made wrong, and
    /// the belief if it held `row`.
    pub(super) fn refined_belief(&mut self, row: RowId) {
        self.model.invalidate_outcome(row);
        if let Known::Spread(b) = &self.known
            && b.iter().any(|&(d, _)| d == row)
        {
            self.known = Known::Lost;
        }
    }

    /// What the weighed level would read on `s` reached by `a` from `from`, learning
    /// nothing: the charge of a move that ends an episode when sensing is chosen with
    /// the move.
    pub(crate) fn would_read_by_belief<W: World + ?Sized>(
        &mut self,
        world: &W,
        from: RowId,
        a: ActionId,
        s: StateId,
        table: &QTable,
    ) -> f64 {
        let choice = self
            .chosen
            .take()
            .unwrap_or_else(|| self.choose(from, a, table));
        match choice {
            Choice::Skip(..) => 0.0,
            Choice::Narrow(b) => {
                let rows: Vec<RowId> = b.iter().map(|&(d, _)| d).collect();
                self.read_apart(world, s, &rows).1
            }
            Choice::Classify => Classify::lookup_cost(&mut self.inner, world, s),
        }
    }

    /// Choose, before the outcome of action `a` from `from`, what the weighed level
    /// will measure after it (the rule "with the move").
    pub(crate) fn choose_with_move(&mut self, from: RowId, a: ActionId, table: &QTable) {
        if self.price.is_some() {
            self.chosen = Some(self.choose(from, a, table));
        }
    }

    /// A new trial: the start is classified in full.
    pub(super) fn restart_belief(&mut self) {
        self.known = Known::Measured;
        self.blind = 0;
        self.left_guessed = false;
        self.chosen = None;
    }
}

#[cfg(test)]
mod tests {
    use mdp::{Cell, Feature, Reading};
    use qlearn::{Discount, LearningRate, Target};

    use super::*;
    use crate::perception::representation::Representation;
    use crate::perception::sense_less::level::PredictionParams;

    /// A level at `price` whose model has seen action 0 from row 0 lead to rows 1 and 2
    /// twice each (told apart by feature 0), and a table where row 1 prefers action 0
    /// and row 2 prefers action 1 by `gap` (row 2 is the most likely by one count).
    fn level(price: f64, gap: f64) -> (Predicting, QTable) {
        let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
        let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
        let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
        let (wall, free) = (Reading::from(Cell::Obstacle), Reading::from(Cell::Empty));
        let mut rep = Representation::default();
        rep.push(&[]);
        rep.push(&[(Feature(0), wall), (Feature(1), free)]);
        rep.push(&[(Feature(0), free), (Feature(1), free)]);
        let classify = Classify::with_representation(&sensed, rep);
        let mut p = Predicting::weighed(classify, &PredictionParams::default(), 4, price);
        for to in [1, 2, 2, 1, 2] {
            p.model.observe(RowId(0), ActionId(0), RowId(to));
        }
        let mut table = QTable::with_rows(4, 3).unwrap();
        let (beta, gamma) = (LearningRate::new(1.0).unwrap(), Discount::new(0.9).unwrap());
        table.update(RowId(1), ActionId(0), 1.0, Target::Terminal, beta, gamma);
        table.update(RowId(2), ActionId(0), 1.0, Target::Terminal, beta, gamma);
        table.update(
            RowId(2),
            ActionId(1),
            1.0 + gap,
            Target::Terminal,
            beta,
            gamma,
        );
        (p, table)
    }

    #[test]
    fn the_choice_weighs_the_loss_against_the_price() {
        // Acting as row 2 (greedy: action 1) loses `gap` in row 1's 2 cases of 5.
        let (p, table) = level(0.01, 0.0);
        match p.choose(RowId(0), ActionId(0), &table) {
            Choice::Skip(row, belief) => {
                assert_eq!(row, RowId(2));
                assert_eq!(belief, [(RowId(1), 0.4), (RowId(2), 0.6)]);
            }
            other => panic!("{other:?}"),
        }
        // A loss of 0.4 * gap against 0.01 times the one feature that tells them apart.
        let (p, table) = level(0.01, 0.1);
        assert!(matches!(
            p.choose(RowId(0), ActionId(0), &table),
            Choice::Narrow(_)
        ));
        let (p, table) = level(1.0, 0.1);
        assert!(matches!(
            p.choose(RowId(0), ActionId(0), &table),
            Choice::Skip(..)
        ));
        // Free measuring, an untrusted transition, or the bound reached: classify.
        let (p, table) = level(0.0, 0.0);
        assert_eq!(p.choose(RowId(0), ActionId(0), &table), Choice::Classify);
        let (p, table) = level(0.01, 0.0);
        assert_eq!(p.choose(RowId(0), ActionId(1), &table), Choice::Classify);
        let (mut p, table) = level(0.01, 0.0);
        p.blind = p.max_skips;
        assert_eq!(p.choose(RowId(0), ActionId(0), &table), Choice::Classify);
    }

    #[test]
    fn a_carried_belief_is_pushed_through_every_description_it_holds() {
        let (mut p, table) = level(0.01, 0.0);
        // From rows 1 and 2 with action 0 nothing is known: the state is classified.
        p.known = Known::Spread(vec![(RowId(1), 0.5), (RowId(2), 0.5)]);
        assert_eq!(p.choose(RowId(2), ActionId(0), &table), Choice::Classify);
        for _ in 0..3 {
            p.model.observe(RowId(1), ActionId(0), RowId(1));
            p.model.observe(RowId(2), ActionId(0), RowId(1));
        }
        match p.choose(RowId(2), ActionId(0), &table) {
            Choice::Skip(row, belief) => {
                assert_eq!((row, belief), (RowId(1), vec![(RowId(1), 1.0)]))
            }
            other => panic!("{other:?}"),
        }
        // Where the one likely description reads nothing, measuring is free: classify.
        p.model.observe(RowId(1), ActionId(2), RowId(0));
        p.model.observe(RowId(1), ActionId(2), RowId(0));
        p.model.observe(RowId(1), ActionId(2), RowId(0));
        p.model.observe(RowId(2), ActionId(2), RowId(0));
        p.model.observe(RowId(2), ActionId(2), RowId(0));
        p.model.observe(RowId(2), ActionId(2), RowId(0));
        assert_eq!(p.choose(RowId(2), ActionId(2), &table), Choice::Classify);
        // A refinement of a description the belief holds loses it.
        p.refined_belief(RowId(1));
        assert_eq!(p.known, Known::Lost);
        assert_eq!(p.choose(RowId(2), ActionId(0), &table), Choice::Classify);
    }
}
