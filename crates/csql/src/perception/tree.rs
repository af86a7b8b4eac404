//! The cost-sensitive decision tree over the final descriptions (the paper's Figure 5d),
//! built with cslearn's tree and classifying states of the grid.

use cslearn::{ClassId, Cost, DecisionTree, FeatureId, Labels, Sensor, TreeOptions, Value};
use mdp::{Cell, Feature, FeatureSpace, Reading, StateId, World};

use crate::perception::representation::{DescriptionId, Representation};

/// A state being sensed through a grid's feature space, for cslearn's sensing trait.
///
/// ```
/// use cslearn::{FeatureId, Sensor, Value};
/// use mdp::{FeatureSpace, GridWorld, Manhattan, SensedGrid, Slip};
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
/// let sensed = SensedGrid::new(&world, &space, Slip::default());
/// let mut sensor = csql::StateSensor { world: &sensed, state: world.states()[0] };
/// assert_eq!(sensor.measure(FeatureId(0)), Some(Value(mdp::Cell::Obstacle.code())));
/// ```
#[derive(Clone, Copy, Debug)]
pub struct StateSensor<'a, W: ?Sized> {
    /// The world.
    pub world: &'a W,
    /// The state sensed.
    pub state: StateId,
}

impl<W: World + ?Sized> Sensor for StateSensor<'_, W> {
    fn measure(&mut self, feature: FeatureId) -> Option<Value> {
        let f = Feature(feature.0);
        (f.index() < self.world.num_features()).then(|| Value(self.world.read(self.state, f).0))
    }
}

/// Names features by offset, values by cell and classes by description label.
struct GridLabels<'a>(&'a FeatureSpace);

impl Labels for GridLabels<'_> {
    fn feature(&self, feature: FeatureId) -> String {
        let o = self.0.offset(Feature(feature.0));
        format!("({}, {})", o.dx, o.dy)
    }
    fn value(&self, _feature: FeatureId, value: Value) -> String {
        Cell::from_code(value.0).map_or_else(|| value.0.to_string(), |c| c.name().to_string())
    }
    fn class(&self, class: ClassId) -> String {
        format!("d{}", class.0)
    }
}

/// Labels in the world's own words, for worlds that are not grids.
struct WorldLabels<'a, W: ?Sized>(&'a W);

impl<W: World + ?Sized> Labels for WorldLabels<'_, W> {
    fn feature(&self, feature: FeatureId) -> String {
        self.0.feature_name(Feature(feature.0))
    }
    fn value(&self, feature: FeatureId, value: Value) -> String {
        self.0.reading_name(Feature(feature.0), Reading(value.0))
    }
    fn class(&self, class: ClassId) -> String {
        format!("d{}", class.0)
    }
}

/// A decision tree that maps states to descriptions, built greedily by I^2/C over the
/// descriptions as rules (a description lacking the split feature follows every branch).
///
/// ```
/// use csql::{RunSettings, Setup, StateTree, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 2);
/// let setup = Setup::new(&settings).unwrap();
/// let (report, rep) = csql::run_with_representation(&setup, &settings).unwrap();
/// let world = setup.sensed(&settings);
/// let tree = StateTree::build(&rep, setup.space.costs());
/// for s in setup.world.states() {
///     let (d, _cost) = tree.classify(&world, s);
///     assert_eq!(d, rep.matching(&world, s));
/// }
/// assert!(tree.to_dot(&world).starts_with("digraph"));
/// ```
#[derive(Clone, Debug)]
pub struct StateTree {
    tree: DecisionTree,
}

impl StateTree {
    /// Build the tree over a representation.
    ///
    /// ```
    /// use mdp::{Cell, Feature, FeatureSpace, Manhattan, Reading};
    /// let space = FeatureSpace::new(&mdp::builtin("tan3x3").unwrap(), &Manhattan).unwrap();
    /// let mut rep = csql::Representation::default();
    /// rep.push(&[(Feature(0), Reading::from(Cell::Empty))]);
    /// rep.push(&[(Feature(0), Reading::from(Cell::Obstacle))]);
    /// assert_eq!(csql::StateTree::build(&rep, space.costs()).tree().depth(), 1);
    /// ```
    pub fn build(rep: &Representation, prices: &[f64]) -> StateTree {
        #[cfg_attr(
            not(test),
            expect(
                clippy::expect_used,
                reason = "a world's prices are finite and at least 0, the rule of Cost::new"
            )
        )]
        let costs: Vec<Cost> = prices
            .iter()
            .map(|&c| Cost::new(c).expect("feature spaces hold valid costs"))
            .collect();
        StateTree {
            tree: DecisionTree::build(rep.library(), &costs[..], TreeOptions::rules()),
        }
    }

    /// The description the tree gives a state, and the sensing cost of getting there.
    ///
    /// ```
    /// use mdp::{Cell, Feature, FeatureSpace, GridWorld, Manhattan, Pos, Reading};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut rep = csql::Representation::default();
    /// let open = rep.push(&[(Feature(0), Reading::from(Cell::Empty))]);
    /// rep.push(&[(Feature(0), Reading::from(Cell::Obstacle))]);
    /// let tree = csql::StateTree::build(&rep, space.costs());
    /// let below = world.state_at(Pos::new(1, 1)).unwrap();
    /// assert_eq!(tree.classify(&sensed, below), (Some(open), 1.0));
    /// ```
    pub fn classify<W: World + ?Sized>(
        &self,
        world: &W,
        s: StateId,
    ) -> (Option<DescriptionId>, f64) {
        let out = self.tree.classify(StateSensor { world, state: s });
        (out.class.map(|c| DescriptionId(c.0)), out.cost.get())
    }

    /// The tree as Graphviz DOT, with features named by offset `(dx, dy)`.
    ///
    /// ```
    /// use mdp::{Cell, Feature, FeatureSpace, Manhattan, Reading};
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut rep = csql::Representation::default();
    /// rep.push(&[(Feature(0), Reading::from(Cell::Empty))]);
    /// rep.push(&[(Feature(0), Reading::from(Cell::Obstacle))]);
    /// assert!(csql::StateTree::build(&rep, space.costs()).to_dot(&sensed).contains("(0, 1)"));
    /// ```
    pub fn to_dot<W: World + ?Sized>(&self, world: &W) -> String {
        match world.local_space() {
            Some(space) => self.tree.to_dot(&GridLabels(space)),
            None => self.tree.to_dot(&WorldLabels(world)),
        }
    }

    /// The underlying cslearn tree.
    ///
    /// ```
    /// let space = mdp::FeatureSpace::new(&mdp::builtin("tan3x3").unwrap(), &mdp::Manhattan).unwrap();
    /// let mut rep = csql::Representation::default();
    /// rep.push(&[]);
    /// assert_eq!(csql::StateTree::build(&rep, space.costs()).tree().len(), 1);
    /// ```
    pub fn tree(&self) -> &DecisionTree {
        &self.tree
    }
}
