//! The read-only views measuring takes of a learned perception: [`Sees`] for the policy
//! quality and [`Describes`] for the report. Each perception implements them beside its
//! own type; the measuring modules (quality, report) know only these traits, so that the
//! learners never depend on the code that measures them.

use mdp::{ActionId, Reading, SensorNoise, StateId, World};
use qlearn::RowId;
use rand::Rng;

/// How a state becomes a row when the learned policy acts: the perception's view for the
/// quality measure, free of charge, through the agent's (possibly noisy) sensors.
///
/// ```
/// use csql::{Identified, Sees};
/// use rand::SeedableRng;
/// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
/// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
/// let mut p = Identified::new(&sensed, vec![0.0; 9]);
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// assert_eq!(p.sees(&sensed, mdp::StateId(0), mdp::SensorNoise::default(), &mut rng), None);
/// ```
pub trait Sees {
    /// The row the agent would use in state `s`, or `None` if it would make a new one.
    fn sees<W: World + ?Sized, R: Rng + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        noise: SensorNoise,
        rng: &mut R,
    ) -> Option<RowId>;
    /// Whether the row depends on the state alone. A perception with a memory of its own
    /// moves says `false`; its quality is then estimated by Monte Carlo, through
    /// [`Sees::begin`] and [`Sees::moved`].
    fn memoryless(&self) -> bool {
        true
    }
    /// An episode of the evaluation starts: forget the moves of the last one.
    fn begin(&mut self) {}
    /// The evaluated policy took action `a` from the state last seen.
    fn moved(&mut self, a: ActionId) {
        let _ = a;
    }
}

/// What a run's report reads from a learned perception, free of charge and without
/// changing it: its descriptions and what classifying a state costs after learning.
/// [`crate::Classify`] and the baselines' perceptions implement it.
///
/// ```
/// use csql::{Classify, Describes};
/// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
/// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
/// let mut c = Classify::new(&sensed);
/// let s = world.states()[0];
/// let d = c.classify_state(&sensed, s).description;
/// c.add_feature(&sensed, d, s);
/// assert_eq!(c.described().len(), 1);
/// assert_eq!(c.cost_after_learning(&sensed, s), 1.0);
/// ```
pub trait Describes {
    /// The descriptions, one per row that has one, in row order: the row and its
    /// features with their values.
    fn described(&self) -> Vec<(qlearn::RowId, Vec<(mdp::Feature, Reading)>)>;
    /// What classifying state `s` costs after learning.
    fn cost_after_learning<W: World + ?Sized>(&mut self, world: &W, s: mdp::StateId) -> f64;
    /// Table 1's rows 8 and 5 after learning: the mean cost per state of the cheapest
    /// classifier of the final descriptions, and of measuring a state's whole
    /// description. By default both are the mean of
    /// [`Describes::cost_after_learning`].
    fn table1_costs<W: World + ?Sized>(&mut self, world: &W) -> (f64, f64) {
        let states = world.states();
        let mean = states
            .iter()
            .map(|&s| self.cost_after_learning(world, s))
            .sum::<f64>()
            / states.len() as f64;
        (mean, mean)
    }
}
