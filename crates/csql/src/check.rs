//! The oracle's verdict on a perception and a Q table, at the end of a trial.
//!
//! Nothing here is charged and nothing here reaches the learner: it only decides when a
//! run has found a sufficient representation and when it has converged.

use mdp::{GridWorld, Oracle};
use qlearn::{QTable, RowId};
use serde::Serialize;

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
        let states = world.states();
        let unmatched = rows.iter().filter(|m| m.is_none()).count();
        let mut members: Vec<Vec<mdp::StateId>> = vec![Vec::new(); table.rows()];
        for (&s, m) in states.iter().zip(rows) {
            if let Some(r) = m {
                members[r.index()].push(s);
            }
        }
        let mut inconsistent = 0;
        let mut literal = true;
        for group in &members {
            let Some((&first, rest)) = group.split_first() else {
                continue;
            };
            let v0 = oracle.v_star(first);
            let same_v = rest
                .iter()
                .all(|&s| (oracle.v_star(s) - v0).abs() <= 1e-12 * v0.abs().max(1.0));
            let shared_action = mdp::Action::ALL
                .iter()
                .any(|a| group.iter().all(|&s| oracle.is_optimal(s, a.id())));
            if !(same_v && shared_action) {
                inconsistent += 1;
            }
            let first_set = oracle.optimal_actions(first);
            literal &= rest.iter().all(|&s| oracle.optimal_actions(s) == first_set);
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
