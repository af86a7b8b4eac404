//! What a memory of recent steps can and cannot tell apart under a sensing radius.
//!
//! A history of K steps is what an agent with `memory = K` could know at a state: the
//! views within the radius and the actions of its last K moves, ending with the view of
//! the state itself. A history is ambiguous when the states that can end it have no
//! optimal action in common: no policy that acts on that history is optimal at all of
//! them. A state needs more than K steps when some full K-step history ending at it is
//! ambiguous. At a trial's start there is no history at all: there, only the view
//! counts, whatever K is.
//!
//! Prints, per radius and K, the share of (state, full K-step history) pairs whose history
//! is ambiguous, and whose history is shared with a state of another V* (Q-learning on a
//! row needs one value: the paper's Theorem 2 asks for descriptions whose states agree),
//! and the shares of states whose view alone is so (the first move of a trial).
//!
//! `cargo run --release -p csql --example memory_limits -- tan8x8`

use std::collections::{BTreeMap, BTreeSet};

use csql::{RunSettings, Setup, StrategyKind};
use mdp::{ActionId, Cell, Mdp, StateId};

type View = Vec<Cell>;
/// A history: views and actions, oldest first, ending with the current view.
type History = (Vec<(View, u32)>, View);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let map = args.get(1).map_or("tan8x8", String::as_str);
    println!(
        "| radius | K | share of (state, K-step history) pairs: ambiguous | shared with another V* | share of states: ambiguous view (a trial's first move) | view shared with another V* |"
    );
    println!("|---|---|---|---|---|---|");
    for radius in [1u32, 2] {
        let mut settings = RunSettings::tan1991(map, StrategyKind::Lazy, 1);
        settings.world.sensing_radius = Some(radius);
        let setup = Setup::new(&settings)?;
        let world = &setup.world;
        let states = world.states();
        let view = |s: StateId| -> View {
            setup
                .space
                .features()
                .map(|f| setup.space.measure(world, s, f))
                .collect()
        };
        let best: BTreeMap<StateId, BTreeSet<ActionId>> = states
            .iter()
            .map(|&s| (s, setup.oracle.optimal_actions(s).iter().copied().collect()))
            .collect();
        // The states of a group have no optimal action in common.
        let ambiguous = |group: &[StateId]| {
            let mut common = best[&group[0]].clone();
            for s in &group[1..] {
                common = common.intersection(&best[s]).copied().collect();
            }
            common.is_empty()
        };
        // The states of a group differ in V*: Q-learning on one row cannot fit them all.
        let mixed = |group: &[StateId]| {
            let v = setup.oracle.v_star(group[0]);
            group[1..]
                .iter()
                .any(|&s| (setup.oracle.v_star(s) - v).abs() > 1e-9)
        };
        // Predecessors: (s', a) with a non-terminal step from s' to s.
        let mut into: BTreeMap<StateId, Vec<(StateId, u32)>> = BTreeMap::new();
        for &s in &states {
            for a in 0..4u32 {
                let step = world.step(s, ActionId(a));
                if !step.terminated {
                    into.entry(step.next).or_default().push((s, a));
                }
            }
        }
        let by_view: Vec<(StateId, View)> = states.iter().map(|&s| (s, view(s))).collect();
        let mut groups: BTreeMap<&View, Vec<StateId>> = BTreeMap::new();
        for (s, v) in &by_view {
            groups.entry(v).or_default().push(*s);
        }
        let alone: usize = groups.values().filter(|g| ambiguous(g)).map(Vec::len).sum();
        let mixed_view: usize = groups.values().filter(|g| mixed(g)).map(Vec::len).sum();
        // Full K-step histories ending at each state.
        let mut full: BTreeMap<StateId, BTreeSet<History>> = states
            .iter()
            .map(|&s| (s, BTreeSet::from([(Vec::new(), view(s))])))
            .collect();
        for k in 1..=3usize {
            let mut next: BTreeMap<StateId, BTreeSet<History>> = BTreeMap::new();
            for &s in &states {
                let mut hs = BTreeSet::new();
                for &(p, a) in into.get(&s).map_or(&[][..], Vec::as_slice) {
                    for (past, last) in &full[&p] {
                        let mut steps = past.clone();
                        steps.push((last.clone(), a));
                        hs.insert((steps, view(s)));
                    }
                }
                next.insert(s, hs);
            }
            full = next;
            // The states at the end of an ambiguous full history.
            let mut owners: BTreeMap<&History, Vec<StateId>> = BTreeMap::new();
            for (s, hs) in &full {
                for h in hs {
                    owners.entry(h).or_default().push(*s);
                }
            }
            // The share of (state, full history) pairs whose history is bad.
            let pairs: usize = owners.values().map(Vec::len).sum();
            let share = |bad: &dyn Fn(&[StateId]) -> bool| -> f64 {
                let n: usize = owners.values().filter(|ss| bad(ss)).map(Vec::len).sum();
                n as f64 / pairs as f64
            };
            println!(
                "| {radius} | {k} | {:.2} | {:.2} | {:.2} | {:.2} |",
                share(&ambiguous),
                share(&mixed),
                alone as f64 / states.len() as f64,
                mixed_view as f64 / states.len() as f64
            );
        }
    }
    Ok(())
}
