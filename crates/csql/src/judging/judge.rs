//! The oracle's verdict on a perception and a Q table, at the end of a trial.
//!
//! Nothing here is charged and nothing here reaches the learner: it only decides when a
//! run has found a sufficient representation and when it has converged.

use mdp::{ActionId, Oracle, SensorNoise, StateId, World};
use qlearn::{QTable, RowId};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::Serialize;

use crate::agent::main_loop::Agent;
use crate::perception::rows::Perception;
use crate::perception::view::Sees;

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
/// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
/// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
/// let oracle = Oracle::for_grid(&world, 0.9).unwrap();
/// let mut table = qlearn::QTable::new(4).unwrap();
/// let one = table.add_row();
/// // One row for every state: not consistent.
/// let rows = vec![Some(one); world.states().len()];
/// let v = Verdict::judge(&sensed, &oracle, &table, &rows, 1e-9);
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
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let oracle = Oracle::for_grid(&world, 0.9).unwrap();
    /// let mut table = qlearn::QTable::new(4).unwrap();
    /// // One row per state: sufficient, but nothing learned yet.
    /// let rows: Vec<_> = world.states().iter().map(|_| Some(table.add_row())).collect();
    /// let v = Verdict::judge(&sensed, &oracle, &table, &rows, 1e-9);
    /// assert!(v.sufficient && v.consistent_literal && !v.converged);
    /// ```
    pub fn judge<W: World + ?Sized>(
        world: &W,
        oracle: &Oracle,
        table: &QTable,
        rows: &[Option<RowId>],
        tolerance: f64,
    ) -> Verdict {
        let situations: Vec<(StateId, Option<RowId>)> = world
            .states()
            .into_iter()
            .zip(rows.iter().copied())
            .collect();
        Verdict::of_situations(oracle, table, &situations, tolerance)
    }

    /// Judge the situations a learner can act in: each is a state and the row the
    /// learner uses there (`None`: it would make a new one). A perception without a memory
    /// has one situation per state; one that remembers its last move (U-Tree) has one per
    /// state and way of arriving there, so that a state may have several rows, each of
    /// which must be consistent and converged for it.
    ///
    /// ```
    /// use csql::Verdict;
    /// use mdp::{GridWorld, Oracle, StateId};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let oracle = Oracle::for_grid(&world, 0.9).unwrap();
    /// let mut table = qlearn::QTable::new(4).unwrap();
    /// let (a, b) = (table.add_row(), table.add_row());
    /// let s = world.states()[0];
    /// // One state in two rows: each row is consistent on its own.
    /// let v = Verdict::of_situations(&oracle, &table, &[(s, Some(a)), (s, Some(b))], 1e-9);
    /// assert!(v.sufficient && !v.converged);
    /// // A situation without a row is not sufficient.
    /// assert!(!Verdict::of_situations(&oracle, &table, &[(s, None)], 1e-9).sufficient);
    /// ```
    pub fn of_situations(
        oracle: &Oracle,
        table: &QTable,
        situations: &[(StateId, Option<RowId>)],
        tolerance: f64,
    ) -> Verdict {
        let unmatched = situations.iter().filter(|(_, m)| m.is_none()).count();
        let mut members: Vec<Vec<StateId>> = vec![Vec::new(); table.rows()];
        for &(s, m) in situations {
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
            let shared_action = oracle
                .actions()
                .any(|a| group.iter().all(|&s| oracle.is_optimal(s, a)));
            if !(same_v && shared_action) {
                inconsistent += 1;
            }
            let first_set = oracle.optimal_actions(first);
            literal &= rest.iter().all(|&s| oracle.optimal_actions(s) == first_set);
        }
        let sufficient = unmatched == 0 && inconsistent == 0;
        let converged = sufficient
            && situations.iter().all(|&(s, m)| {
                let row = m.expect("sufficient: every situation has a row");
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

/// The situations a learned perception acts in, through its free view ([`Sees`], noise
/// off): for a perception without a memory, every measured state at a trial's start; for
/// one with a memory of its last move, every state a trial may start in (arrived at by
/// no move) and every state an action leads to from a non-terminal state (arrived at by
/// that action, where the world is deterministic).
pub(crate) fn situations<W: World + ?Sized, P: Sees>(
    world: &W,
    perception: &mut P,
) -> Vec<(StateId, Option<RowId>)> {
    // Nothing is drawn without noise; the generator only fills the signature.
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(0);
    let noise = SensorNoise::default();
    let mut out = Vec::new();
    if perception.memoryless() {
        for s in world.states() {
            perception.begin();
            out.push((s, perception.sees(world, s, noise, &mut rng)));
        }
        return out;
    }
    for (_, s) in world.start_distribution() {
        perception.begin();
        out.push((s, perception.sees(world, s, noise, &mut rng)));
    }
    let mut outcomes = Vec::new();
    for x in world.states() {
        for a in (0..world.num_actions() as u32).map(ActionId) {
            world.outcomes(x, a, &mut outcomes);
            for &(_, step) in &outcomes {
                if !step.terminated {
                    perception.begin();
                    perception.moved(a);
                    out.push((
                        step.next,
                        perception.sees(world, step.next, noise, &mut rng),
                    ));
                }
            }
        }
    }
    out
}

/// The oracle's judge of one agent through its run, at the end of every trial.
///
/// It re-examines only what the agent changed since it last looked (the agent keeps a
/// journal for it, which the agent itself never reads): the states of refined rows and
/// the states that had no row (when rows were added) are looked up again through the
/// perception's free view ([`Perception::lookup`]), and a row's verdicts (consistent,
/// consistent in the literal reading, converged) are recomputed only when its states or
/// its Q values changed. The verdict is exactly [`Verdict::judge`]'s on the whole mapping
/// (`tests/judge.rs` checks it at every trial), at a cost proportional to the changes
/// instead of the number of states.
///
/// This relies on the contract of [`Perception`]: a state's row changes only when that
/// row is refined, or when a state without a row gets one.
///
/// ```
/// use csql::{Agent, Classify, Judge, Lazy, LoopParams, RunSettings, Setup, StrategyKind};
/// use rand::SeedableRng;
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let table = qlearn::QTable::new(4).unwrap();
/// let world = setup.sensed(&settings);
/// let mut agent = Agent::new(Classify::new(&world), Lazy::default(), table, LoopParams::from(&settings));
/// let mut judge = Judge::default();
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// agent.run_trial(&world, setup.world.states()[0], 1, &mut rng);
/// let v = judge.judge(&world, &setup.oracle, &mut agent, 1e-6);
/// assert!(!v.converged);
/// ```
#[derive(Clone, Debug, Default)]
pub struct Judge {
    started: bool,
    states: Vec<StateId>,
    /// Per state (index into `states`): its row.
    row_of: Vec<Option<RowId>>,
    /// Per row: its states, ascending.
    members: Vec<Vec<u32>>,
    /// States with no row.
    unmatched: Vec<u32>,
    /// Rows the perception had when last looked at.
    rows_seen: usize,
    /// Per row: consistent, literally consistent, converged (all true for no states).
    flags: Vec<[bool; 3]>,
    /// Rows failing each flag.
    failing: [usize; 3],
    /// Rows whose flags must be recomputed.
    dirty: Vec<u32>,
    is_dirty: Vec<bool>,
}

impl Judge {
    /// Judge an agent at the end of a trial.
    pub fn judge<W: World + ?Sized, P: Perception, S>(
        &mut self,
        world: &W,
        oracle: &Oracle,
        agent: &mut Agent<P, S>,
        tolerance: f64,
    ) -> Verdict {
        let journal = agent.take_journal();
        let perception = &mut agent.perception;
        if !self.started {
            self.started = true;
            self.states = world.states();
            self.row_of = vec![None; self.states.len()];
            self.unmatched = (0..self.states.len() as u32).collect();
            self.rows_seen = usize::MAX;
        }
        let rows = perception.rows();
        if self.members.len() < rows {
            self.members.resize_with(rows, Vec::new);
            self.flags.resize(rows, [true; 3]);
            self.is_dirty.resize(rows, false);
        }
        for &r in &journal.refined {
            let moved = std::mem::take(&mut self.members[r.index()]);
            self.mark(r);
            for i in moved {
                let found = perception.lookup(world, self.states[i as usize]);
                self.place(i, found);
            }
        }
        if rows != self.rows_seen {
            self.rows_seen = rows;
            for i in std::mem::take(&mut self.unmatched) {
                let found = perception.lookup(world, self.states[i as usize]);
                self.place(i, found);
            }
        }
        if journal.reset {
            for r in 0..rows {
                self.mark(RowId(r as u32));
            }
        } else {
            for &r in &journal.updated {
                self.mark(r);
            }
        }
        let table = &agent.table;
        for r in std::mem::take(&mut self.dirty) {
            self.is_dirty[r as usize] = false;
            let new = self.row_flags(oracle, table, RowId(r), tolerance);
            let old = std::mem::replace(&mut self.flags[r as usize], new);
            for k in 0..3 {
                if old[k] != new[k] {
                    if new[k] {
                        self.failing[k] -= 1;
                    } else {
                        self.failing[k] += 1;
                    }
                }
            }
        }
        let sufficient = self.unmatched.is_empty() && self.failing[0] == 0;
        Verdict {
            unmatched: self.unmatched.len(),
            inconsistent: self.failing[0],
            sufficient,
            consistent_literal: sufficient && self.failing[1] == 0,
            converged: sufficient && self.failing[2] == 0,
        }
    }

    /// The row of each of the world's states (in the order of `World::states`) as of the
    /// last judgement; empty before the first.
    pub(crate) fn rows(&self) -> &[Option<RowId>] {
        &self.row_of
    }

    /// Give state `i` its row (or none).
    fn place(&mut self, i: u32, row: Option<RowId>) {
        self.row_of[i as usize] = row;
        match row {
            Some(r) => {
                let m = &mut self.members[r.index()];
                let at = m.partition_point(|&j| j < i);
                m.insert(at, i);
                self.mark(r);
            }
            None => self.unmatched.push(i),
        }
    }

    fn mark(&mut self, r: RowId) {
        if !std::mem::replace(&mut self.is_dirty[r.index()], true) {
            self.dirty.push(r.0);
        }
    }

    /// A row's verdicts from its states: consistent (shared `V*` and an optimal action
    /// in common), literally consistent (equal sets of optimal actions), converged (`V`
    /// within the tolerance of every state's `V*` and only optimal greedy actions).
    fn row_flags(&self, oracle: &Oracle, table: &QTable, r: RowId, tolerance: f64) -> [bool; 3] {
        let group = &self.members[r.index()];
        let Some((&first, rest)) = group.split_first() else {
            return [true; 3];
        };
        let states = &self.states;
        let first = states[first as usize];
        let v0 = oracle.v_star(first);
        let same_v = rest
            .iter()
            .all(|&i| (oracle.v_star(states[i as usize]) - v0).abs() <= 1e-12 * v0.abs().max(1.0));
        let shared_action = oracle.actions().any(|a| {
            group
                .iter()
                .all(|&i| oracle.is_optimal(states[i as usize], a))
        });
        let literal = rest.iter().all(|&i| {
            oracle
                .actions()
                .all(|a| oracle.is_optimal(states[i as usize], a) == oracle.is_optimal(first, a))
        });
        let settled = group.iter().all(|&i| {
            let s = states[i as usize];
            (table.v(r) - oracle.v_star(s)).abs() <= tolerance
                && table.greedy_actions(r).all(|a| oracle.is_optimal(s, a))
        });
        [same_v && shared_action, literal, settled]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mdp::StochasticMdp;

    /// A perception whose row is the last move (row 0 before any), as a tree split on
    /// the previous action everywhere would be.
    #[derive(Default)]
    struct LastMove {
        previous: Option<ActionId>,
        memoryless: bool,
    }

    impl Sees for LastMove {
        fn sees<W: World + ?Sized, R: rand::Rng + ?Sized>(
            &mut self,
            _world: &W,
            _s: StateId,
            _noise: SensorNoise,
            _rng: &mut R,
        ) -> Option<RowId> {
            Some(RowId(self.previous.map_or(0, |a| a.0 + 1)))
        }
        fn memoryless(&self) -> bool {
            self.memoryless
        }
        fn begin(&mut self) {
            self.previous = None;
        }
        fn moved(&mut self, a: ActionId) {
            self.previous = Some(a);
        }
    }

    #[test]
    fn situations_are_the_states_and_how_they_were_reached() {
        let grid = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
        let space = mdp::FeatureSpace::new(grid.map(), &mdp::Manhattan).unwrap();
        let world = mdp::SensedGrid::new(&grid, &space, mdp::Slip::default());
        let states = world.states();
        // Without a memory: one situation per state, seen with no move.
        let mut plain = LastMove {
            memoryless: true,
            ..LastMove::default()
        };
        let got = situations(&world, &mut plain);
        assert_eq!(got.len(), states.len());
        assert!(got.iter().all(|&(_, r)| r == Some(RowId(0))));
        // With one: every start with no move, and every state an action leads to (the
        // goal aside) with that action.
        let mut memory = LastMove::default();
        let got = situations(&world, &mut memory);
        let mut want: Vec<(StateId, Option<RowId>)> = world
            .start_distribution()
            .into_iter()
            .map(|(_, s)| (s, Some(RowId(0))))
            .collect();
        for &x in &states {
            for a in 0..4 {
                let step = world.sample(x, ActionId(a), &mut Xoshiro256PlusPlus::seed_from_u64(0));
                if !step.terminated {
                    want.push((step.next, Some(RowId(a + 1))));
                }
            }
        }
        assert_eq!(got, want);
        assert!(got.len() > states.len());
        // Each state must be right in each of its rows: a table that is right only for
        // row 0 is not converged over the situations.
        let oracle = mdp::Oracle::for_grid(&grid, 0.9).unwrap();
        let mut table = QTable::new(4).unwrap();
        for _ in 0..5 {
            table.add_row();
        }
        let v = Verdict::of_situations(&oracle, &table, &got, 1e-9);
        assert!(!v.sufficient, "one row holds states of different values");
    }
}
