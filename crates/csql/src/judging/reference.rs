//! The two reference points of the paper's discussion of Table 1.
//!
//! * Plain Q-learning with every state identified, charged at every classification for
//!   sensing the whole bordered world from the robot's cell: what CS-QL saves.
//! * Q-learning given the final representation from the start (charged as CLASSIFY
//!   charges): the paper's "76 trials and 38545 sensing cost" comparison, which says how
//!   much of a heuristic strategy's cost was spent learning the representation.

use mdp::{FeatureSpace, GridWorld, Mdp, StateId};
use qlearn::QTable;
use serde::Serialize;

use crate::agent::main_loop::{Agent, LoopParams};
use crate::agent::strategy::Never;
use crate::judging::trials::{Scene, learn};
use crate::observe::KeepTrace;
use crate::perception::classify::Classify;
use crate::perception::grid::bordered_features;
use crate::perception::representation::Representation;
use crate::perception::rows::{Identified, Perception};
use crate::settings::setup::Setup;
use crate::settings::values::RunSettings;

/// What a reference learner needed to converge.
///
/// ```
/// let r = csql::Reference { converged: false, trials: 3, cost: 10.0, cost_per_classification: None };
/// assert!(!r.converged);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Reference {
    /// Whether it converged before the trial cap.
    pub converged: bool,
    /// Trials run (to convergence, if it converged).
    pub trials: u32,
    /// Sensing cost charged.
    pub cost: f64,
    /// The fixed price of one classification, where there is one (mean over states).
    pub cost_per_classification: Option<f64>,
}

/// The summed cost of sensing, from state `s`, every cell within `margin` cells of the
/// interior.
fn sensing_cost(world: &GridWorld, space: &FeatureSpace, s: StateId, margin: i64) -> f64 {
    bordered_features(world, space, s, margin)
        .map(|f| space.cost(f))
        .sum()
}

/// The cost of sensing every cell of the bordered world (the interior and its boundary)
/// from state `s`: the price of identifying a state by brute force.
///
/// ```
/// use mdp::{FeatureSpace, GridWorld, Manhattan};
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
/// // From the centre of a 5 by 5 bordered world: 4 cells at 1, 8 at 2, 8 at 3, 4 at 4.
/// let centre = world.state_at(mdp::Pos::new(1, 1)).unwrap();
/// assert_eq!(csql::whole_world_cost(&world, &space, centre), 4.0 + 16.0 + 24.0 + 16.0);
/// ```
pub fn whole_world_cost(world: &GridWorld, space: &FeatureSpace, s: StateId) -> f64 {
    sensing_cost(world, space, s, 1)
}

/// The cost of sensing only the interior cells from the cheapest state: the paper's
/// "sensing the whole grid world just once will cost at least" figure.
///
/// ```
/// use mdp::{FeatureSpace, GridWorld, Manhattan};
/// let world = GridWorld::new(&mdp::builtin("open8x8").unwrap());
/// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
/// assert_eq!(csql::cheapest_interior_cost(&world, &space), 256.0);
/// ```
pub fn cheapest_interior_cost(world: &GridWorld, space: &FeatureSpace) -> f64 {
    world
        .states()
        .iter()
        .map(|&s| sensing_cost(world, space, s, 0))
        .fold(f64::INFINITY, f64::min)
}

/// Learn on a fixed perception with the run's settings until convergence.
fn reference<P: Perception + crate::perception::view::Sees>(
    setup: &Setup,
    settings: &RunSettings,
    perception: P,
    table: QTable,
    cost_per_classification: Option<f64>,
) -> Reference {
    let mut agent = Agent::new(perception, Never, table, LoopParams::from(settings));
    let sensed = setup.sensed(settings);
    let scene = Scene::new(&sensed, &setup.oracle, setup.truth(), setup.map.name());
    let learned = learn(&scene, settings, &mut agent, &mut KeepTrace);
    Reference {
        converged: learned.first_converged.is_some(),
        trials: learned.trials,
        cost: learned.cost,
        cost_per_classification,
    }
}

/// Plain Q-learning with every state identified, charged [`whole_world_cost`] per
/// classification, with the run's settings and seed.
///
/// ```
/// use csql::{RunSettings, Setup, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Resetting, 1);
/// let r = csql::full_sensing_reference(&Setup::new(&settings).unwrap(), &settings);
/// assert!(r.converged && r.cost > 0.0);
/// ```
pub fn full_sensing_reference(setup: &Setup, settings: &RunSettings) -> Reference {
    let cost: Vec<f64> = (0..mdp::Mdp::num_states(&setup.world) as u32)
        .map(|s| whole_world_cost(&setup.world, &setup.space, StateId(s)))
        .collect();
    let states = setup.world.states();
    let mean = states.iter().map(|s| cost[s.index()]).sum::<f64>() / states.len() as f64;
    let perception = Identified::new(&setup.sensed(settings), cost);
    reference(
        setup,
        settings,
        perception,
        QTable::new(setup.world.num_actions()).expect("grid worlds have four actions"),
        Some(mean),
    )
}

/// Q-learning from zero on a fixed representation (for example the one a run ended
/// with), classifying with CLASSIFY and charged as it charges.
///
/// ```
/// use csql::{RunSettings, Setup, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Resetting, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let (report, rep) = csql::run_with_representation(&setup, &settings).unwrap();
/// let r = csql::fixed_representation_reference(&setup, &settings, rep);
/// assert!(report.converged && r.converged);
/// ```
pub fn fixed_representation_reference(
    setup: &Setup,
    settings: &RunSettings,
    rep: Representation,
) -> Reference {
    let table = QTable::with_rows(setup.world.num_actions(), rep.len())
        .expect("grid worlds have four actions");
    let perception = Classify::with_representation(&setup.sensed(settings), rep);
    reference(setup, settings, perception, table, None)
}
