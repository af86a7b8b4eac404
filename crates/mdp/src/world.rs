//! The seam under every learner: a finite world whose states are sensed through priced
//! features.
//!
//! A [`World`] is three things a learner needs and nothing about learning:
//!
//! * its dynamics and true model ([`StochasticMdp`]: states, actions, a sampled step that
//!   keeps `terminated` and `truncated` apart, and the outcomes with their probabilities,
//!   which only the oracle and the measures read);
//! * its features ([`Sensors`]): a finite list, each with a price, and what each reads
//!   in each state as a small integer ([`Reading`]);
//! * where trials start, and names for states, actions, features and readings, so that
//!   reports speak the world's language.
//!
//! Feature ids are in the order a cost-sensitive learner takes "the next cheapest
//! feature": ascending price, ties in an order the world documents (for grids,
//! clockwise from straight up; for factored worlds, the order of the factors).
//!
//! Grid maps with the paper's local sensing are one world ([`SensedGrid`]); tabular
//! worlds from files and the built-in worlds beyond grids are another.

use rand::{Rng, RngExt};

use crate::geometry::Cell;
use crate::grid::{Action, GridWorld};
use crate::process::{ActionId, StateId, Step};
use crate::sensing::{Feature, FeatureSpace, Reading};
use crate::stochastic::{SlipperyGrid, StochasticMdp};

/// A finite list of features, each with a price, and what each reads in each state.
///
/// Reading is free and exact here: this is the world's truth. What a learner pays, and
/// whether its sensors err, is the learner's business (csql charges [`Sensors::price`]
/// per measurement and wraps readings in noise when asked).
///
/// ```
/// use mdp::{FeatureSpace, GridWorld, Manhattan, Sensors, SensedGrid, Slip};
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
/// let sensed = SensedGrid::new(&world, &space, Slip::default());
/// assert_eq!(sensed.num_features(), space.len());
/// assert_eq!(sensed.price(mdp::Feature(0)), 1.0);
/// assert_eq!(sensed.feature_name(mdp::Feature(0)), "(0,+1)");
/// ```
pub trait Sensors {
    /// How many features there are; ids are `0..num_features()`, cheapest first.
    fn num_features(&self) -> usize;
    /// The price of measuring feature `f` once (finite, at least 0).
    fn price(&self, f: Feature) -> f64;
    /// What feature `f` reads in state `s`, exactly.
    fn read(&self, s: StateId, f: Feature) -> Reading;
    /// How many readings feature `f` has: it reads one of `0..readings(f)` (a wrong read
    /// of a noisy sensor is drawn among the others).
    fn readings(&self, f: Feature) -> u32;
    /// A short name for feature `f`.
    fn feature_name(&self, f: Feature) -> String;
    /// A short name for reading `v` of feature `f`.
    fn reading_name(&self, f: Feature, v: Reading) -> String;
}

/// A finite world with priced features: the one thing CS-QL, its baselines, the oracle
/// and the reports work through.
///
/// ```
/// use mdp::{FeatureSpace, GridWorld, Manhattan, SensedGrid, Slip, World};
/// use rand::SeedableRng;
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
/// let sensed = SensedGrid::new(&world, &space, Slip::default());
/// assert_eq!(sensed.states(), world.states());
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// let s = sensed.sample_start(&mut rng);
/// assert!(world.states().contains(&s));
/// assert!(sensed.grid().is_some());
/// ```
pub trait World: StochasticMdp + Sensors {
    /// The non-terminal states a trial may visit, in id order: the states every measure
    /// (consistency, sufficiency, policy quality, the decision tree) ranges over.
    fn states(&self) -> Vec<StateId>;
    /// Where trials start, with probabilities that sum to 1.
    fn start_distribution(&self) -> Vec<(f64, StateId)>;
    /// Draw a trial's start state.
    fn sample_start<R: Rng + ?Sized>(&self, rng: &mut R) -> StateId;
    /// A short label of state `s` (a position, or the world's own name for it).
    fn state_label(&self, s: StateId) -> String {
        s.to_string()
    }
    /// A short name of action `a`.
    fn action_name(&self, a: ActionId) -> String {
        a.to_string()
    }
    /// The grid underneath, for the parts that only make sense on a grid (figures, the
    /// paper's reference points, dead reckoning); `None` for every other world.
    fn grid(&self) -> Option<&GridWorld> {
        None
    }
    /// The grid's feature space (offsets around the robot), where [`World::grid`] is one.
    fn local_space(&self) -> Option<&FeatureSpace> {
        None
    }
}

/// A grid map sensed as the paper senses it: the cells at offsets around the robot,
/// priced by a [`FeatureSpace`], with moves that may slip. Trials start uniformly at the
/// free cells other than the goal (one `random_range` draw, as every run has drawn).
///
/// ```
/// use mdp::{FeatureSpace, GridWorld, Manhattan, Reading, SensedGrid, Sensors, Slip};
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
/// let sensed = SensedGrid::new(&world, &space, Slip::default());
/// let s = world.states()[0];
/// let f = mdp::Feature(0);
/// assert_eq!(sensed.read(s, f), Reading::from(space.measure(&world, s, f)));
/// ```
#[derive(Clone, Copy, Debug)]
pub struct SensedGrid<'w> {
    dynamics: SlipperyGrid<'w>,
    space: &'w FeatureSpace,
}

impl<'w> SensedGrid<'w> {
    /// A grid world, its feature space and its slip.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let g = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// assert_eq!(g.world().map().name(), "tan3x3");
    /// ```
    pub fn new(world: &'w GridWorld, space: &'w FeatureSpace, slip: crate::Slip) -> Self {
        SensedGrid {
            dynamics: SlipperyGrid::new(world, slip),
            space,
        }
    }

    /// The grid world.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// assert_eq!(mdp::SensedGrid::new(&world, &space, mdp::Slip::default()).world().goal(), world.goal());
    /// ```
    pub fn world(&self) -> &'w GridWorld {
        self.dynamics.world()
    }

    /// The feature space.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// assert_eq!(mdp::SensedGrid::new(&world, &space, mdp::Slip::default()).space().len(), space.len());
    /// ```
    pub fn space(&self) -> &'w FeatureSpace {
        self.space
    }

    /// The slippery dynamics.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let g = mdp::SensedGrid::new(&world, &space, mdp::Slip::new(0.1).unwrap());
    /// assert_eq!(g.dynamics().slip().get(), 0.1);
    /// ```
    pub fn dynamics(&self) -> &SlipperyGrid<'w> {
        &self.dynamics
    }
}

impl StochasticMdp for SensedGrid<'_> {
    #[inline]
    fn num_states(&self) -> usize {
        self.dynamics.num_states()
    }
    #[inline]
    fn num_actions(&self) -> usize {
        4
    }
    #[inline]
    fn is_terminal(&self, s: StateId) -> bool {
        self.dynamics.is_terminal(s)
    }
    fn outcomes(&self, s: StateId, a: ActionId, out: &mut Vec<(f64, Step)>) {
        self.dynamics.outcomes(s, a, out)
    }
    #[inline]
    fn sample<R: Rng + ?Sized>(&self, s: StateId, a: ActionId, rng: &mut R) -> Step {
        self.dynamics.sample(s, a, rng)
    }
}

impl Sensors for SensedGrid<'_> {
    #[inline]
    fn num_features(&self) -> usize {
        self.space.len()
    }
    #[inline]
    fn price(&self, f: Feature) -> f64 {
        self.space.cost(f)
    }
    #[inline]
    fn read(&self, s: StateId, f: Feature) -> Reading {
        Reading::from(self.space.measure(self.dynamics.world(), s, f))
    }
    #[inline]
    fn readings(&self, _f: Feature) -> u32 {
        Cell::ALL.len() as u32
    }
    fn feature_name(&self, f: Feature) -> String {
        let o = self.space.offset(f);
        format!("({:+},{:+})", o.dx, o.dy).replace("+0", "0")
    }
    fn reading_name(&self, _f: Feature, v: Reading) -> String {
        match Cell::try_from(v) {
            Ok(c) => cell_name(c).to_string(),
            Err(r) => r.0.to_string(),
        }
    }
}

/// The name a cell has in reports (`empty`, `obstacle`, `goal`), as serde writes it.
fn cell_name(c: Cell) -> &'static str {
    match c {
        Cell::Empty => "empty",
        Cell::Obstacle => "obstacle",
        Cell::Goal => "goal",
    }
}

impl World for SensedGrid<'_> {
    fn states(&self) -> Vec<StateId> {
        self.world().states()
    }
    fn start_distribution(&self) -> Vec<(f64, StateId)> {
        let states = self.world().states();
        let p = 1.0 / states.len() as f64;
        states.into_iter().map(|s| (p, s)).collect()
    }
    fn sample_start<R: Rng + ?Sized>(&self, rng: &mut R) -> StateId {
        // The states are every id but the goal's, in order: the i-th without a list.
        let goal = self.world().goal().0;
        let i = rng.random_range(0..self.num_states() as u32 - 1);
        StateId(if i < goal { i } else { i + 1 })
    }
    fn state_label(&self, s: StateId) -> String {
        let p = self.world().pos(s);
        format!("({},{})", p.row, p.col)
    }
    fn action_name(&self, a: ActionId) -> String {
        Action::from_id(a).map_or_else(|| a.to_string(), |a| a.name().to_string())
    }
    fn grid(&self) -> Option<&GridWorld> {
        Some(self.world())
    }
    fn local_space(&self) -> Option<&FeatureSpace> {
        Some(self.space)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Manhattan;

    #[test]
    fn feature_names_show_offsets() {
        let world = GridWorld::new(&crate::builtin("tan3x3").unwrap());
        let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
        let g = SensedGrid::new(&world, &space, crate::Slip::default());
        let names: Vec<String> = (0..4).map(|i| g.feature_name(Feature(i))).collect();
        assert_eq!(names, ["(0,+1)", "(+1,0)", "(0,-1)", "(-1,0)"]);
        assert_eq!(g.reading_name(Feature(0), Reading(1)), "obstacle");
        assert_eq!(g.reading_name(Feature(0), Reading(7)), "7");
    }
}
