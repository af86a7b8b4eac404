//! The oracle's verdict on a perception and a Q table, at the end of a trial.
//!
//! Nothing here is charged and nothing here reaches the learner: it only decides when a
//! run has found a sufficient representation and when it has converged.

use mdp::{GridWorld, Oracle};
use qlearn::{QTable, RowId};
use serde::Serialize;

use crate::perception::Perception;

/// What the oracle sees at one moment.
///
/// * A row (a description) is *consistent* when all the states it describes share `V*`
///   and at least one optimal action. (The paper's "same utility and best actions" read
///   as equal sets of optimal actions can be unreachable: two states whose optimal sets
///   overlap but differ never make their description's V decrease, so nothing would split
///   them. That literal reading is reported as `consistent_literal`; it never stops a run.)
/// * The representation is *sufficient* when every state has a row and every row is
///   consistent.
/// * The run has *converged* when it is sufficient and, for every state, `V` of its row is
///   within the tolerance of `V*` and every greedy action of its row is optimal for it.
///
/// ```
/// use csql::Verdict;
/// use mdp::{GridWorld, Oracle};
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let oracle = Oracle::for_grid(&world, 0.9).unwrap();
/// let mut table = qlearn::QTable::new(4).unwrap();
/// let one = table.add_row();
/// // One row for every state: not consistent.
/// let rows = vec![Some(one); world.states().len()];
/// let v = Verdict::judge(&world, &oracle, &table, &rows, 1e-9);
/// assert!(!v.sufficient && !v.converged);
/// assert_eq!(v.inconsistent, 1);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Verdict {
    /// States that have no row.
    pub unmatched: usize,
    /// Rows that are not consistent.
    pub inconsistent: usize,
    /// Every state has a consistent row.
    pub sufficient: bool,
    /// Sufficient, and the states of every row also have equal sets of optimal actions.
    pub consistent_literal: bool,
    /// Sufficient, with optimal utilities and only optimal greedy actions.
    pub converged: bool,
}

impl Verdict {
    /// Judge a mapping from states to rows: `rows[i]` is the row of `world.states()[i]`.
    ///
    /// ```
    /// use csql::Verdict;
    /// use mdp::{GridWorld, Oracle};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let oracle = Oracle::for_grid(&world, 0.9).unwrap();
    /// let mut table = qlearn::QTable::new(4).unwrap();
    /// // One row per state: sufficient, but nothing learned yet.
    /// let rows: Vec<_> = world.states().iter().map(|_| Some(table.add_row())).collect();
    /// let v = Verdict::judge(&world, &oracle, &table, &rows, 1e-9);
    /// assert!(v.sufficient && v.consistent_literal && !v.converged);
    /// ```
    pub fn judge(
        world: &GridWorld,
        oracle: &Oracle,
        table: &QTable,
        rows: &[Option<RowId>],
        tolerance: f64,
    ) -> Verdict {
        Judge::default().judge(world, oracle, table, rows, tolerance)
    }
}

/// The oracle's judge, with the buffers it reuses from one trial to the next: judging
/// costs a pass over the states (and over each state's actions) and allocates nothing
/// once warm. A perception is judged through its free view ([`Perception::lookup`]),
/// never through anything the learner pays for or sees.
///
/// ```
/// use csql::{Classify, Judge, Perception};
/// use mdp::{FeatureSpace, GridWorld, Manhattan, Oracle};
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
/// let oracle = Oracle::for_grid(&world, 0.9).unwrap();
/// let mut classify = Classify::new(&space);
/// let mut table = qlearn::QTable::new(4).unwrap();
/// classify.classify(&world, world.states()[0], &mut table); // the empty description
/// let v = Judge::default().judge_perception(&world, &oracle, &mut classify, &table, 1e-6);
/// assert_eq!((v.unmatched, v.inconsistent, v.sufficient), (0, 1, false));
/// ```
#[derive(Clone, Debug, Default)]
pub struct Judge {
    rows: Vec<Option<RowId>>,
    /// Indices into the states, grouped by row.
    order: Vec<u32>,
    /// Where each row's group starts in `order` (one more entry than rows).
    starts: Vec<u32>,
    /// Where the next state of each row goes while grouping.
    cursor: Vec<u32>,
}

impl Judge {
    /// Judge a perception and a table: every state's row comes from the perception's
    /// free view.
    ///
    /// ```
    /// use csql::{Identified, Judge};
    /// use mdp::{GridWorld, Mdp, Oracle};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let oracle = Oracle::for_grid(&world, 0.9).unwrap();
    /// let mut p = Identified::new(&world, vec![0.0; world.num_states()]);
    /// let table = qlearn::QTable::new(4).unwrap();
    /// // Nothing classified yet: no state has a row.
    /// let v = Judge::default().judge_perception(&world, &oracle, &mut p, &table, 1e-6);
    /// assert_eq!(v.unmatched, 8);
    /// ```
    pub fn judge_perception<P: Perception + ?Sized>(
        &mut self,
        world: &GridWorld,
        oracle: &Oracle,
        perception: &mut P,
        table: &QTable,
        tolerance: f64,
    ) -> Verdict {
        let mut rows = std::mem::take(&mut self.rows);
        rows.clear();
        rows.extend(world.states().iter().map(|&s| perception.lookup(world, s)));
        let verdict = self.judge(world, oracle, table, &rows, tolerance);
        self.rows = rows;
        verdict
    }

    /// Judge a mapping from states to rows: `rows[i]` is the row of `world.states()[i]`
    /// (as [`Verdict::judge`], reusing this judge's buffers).
    ///
    /// ```
    /// use csql::Judge;
    /// use mdp::{GridWorld, Oracle};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let oracle = Oracle::for_grid(&world, 0.9).unwrap();
    /// let table = qlearn::QTable::new(4).unwrap();
    /// let v = Judge::default().judge(&world, &oracle, &table, &vec![None; 8], 1e-6);
    /// assert!(!v.sufficient && v.unmatched == 8);
    /// ```
    pub fn judge(
        &mut self,
        world: &GridWorld,
        oracle: &Oracle,
        table: &QTable,
        rows: &[Option<RowId>],
        tolerance: f64,
    ) -> Verdict {
        let states = world.states();
        let unmatched = rows.iter().filter(|m| m.is_none()).count();
        // Group the states by row (a counting sort, stable in state order).
        self.starts.clear();
        self.starts.resize(table.rows() + 1, 0);
        for r in rows.iter().flatten() {
            self.starts[r.index() + 1] += 1;
        }
        for i in 1..self.starts.len() {
            self.starts[i] += self.starts[i - 1];
        }
        self.order.clear();
        self.order.resize(rows.len() - unmatched, 0);
        self.cursor.clone_from(&self.starts);
        for (i, r) in rows.iter().enumerate() {
            if let Some(r) = r {
                self.order[self.cursor[r.index()] as usize] = i as u32;
                self.cursor[r.index()] += 1;
            }
        }
        let mut inconsistent = 0;
        let mut literal = true;
        for w in self.starts.windows(2) {
            let group = &self.order[w[0] as usize..w[1] as usize];
            let Some((&first, rest)) = group.split_first() else {
                continue;
            };
            let first = states[first as usize];
            let v0 = oracle.v_star(first);
            let same_v = rest.iter().all(|&i| {
                (oracle.v_star(states[i as usize]) - v0).abs() <= 1e-12 * v0.abs().max(1.0)
            });
            let shared_action = mdp::Action::ALL.iter().any(|a| {
                group
                    .iter()
                    .all(|&i| oracle.is_optimal(states[i as usize], a.id()))
            });
            if !(same_v && shared_action) {
                inconsistent += 1;
            }
            literal &= rest.iter().all(|&i| {
                mdp::Action::ALL.iter().all(|a| {
                    oracle.is_optimal(states[i as usize], a.id())
                        == oracle.is_optimal(first, a.id())
                })
            });
        }
        let sufficient = unmatched == 0 && inconsistent == 0;
        let converged = sufficient
            && states.iter().zip(rows).all(|(&s, m)| {
                let row = m.expect("sufficient: every state has a row");
                (table.v(row) - oracle.v_star(s)).abs() <= tolerance
                    && table.greedy_actions(row).all(|a| oracle.is_optimal(s, a))
            });
        Verdict {
            unmatched,
            inconsistent,
            sufficient,
            consistent_literal: sufficient && literal,
            converged,
        }
    }
}
