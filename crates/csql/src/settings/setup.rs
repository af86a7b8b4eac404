//! A grid map prepared for a run: the map, its grid world, the feature space of the
//! paper's local sensing, and the oracles it is measured against.

use mdp::{FeatureSpace, GridWorld, Manhattan, Map, Oracle, SensedGrid, SlipperyGrid};

use crate::error::Error;
use crate::settings::values::RunSettings;

/// A prepared world: map, grid world, feature space and oracle.
///
/// ```
/// let s = csql::RunSettings::tan1991("tan8x8", csql::StrategyKind::Lazy, 1);
/// let setup = csql::Setup::new(&s).unwrap();
/// assert_eq!(setup.world.states().len(), 50);
/// ```
#[derive(Clone, Debug)]
pub struct Setup {
    /// The map.
    pub map: Map,
    /// The grid world.
    pub world: GridWorld,
    /// The features and their costs.
    pub space: FeatureSpace,
    /// The oracle for the run's gamma.
    pub oracle: Oracle,
    /// The oracle of the true model when the world slips (value iteration), else `None`
    /// ([`Setup::oracle`] is then the truth).
    pub stochastic_oracle: Option<Oracle>,
}

impl Setup {
    /// Load the map of the settings and prepare everything the run needs.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// let setup = csql::Setup::new(&s).unwrap();
    /// assert_eq!(setup.space.len(), 80);
    /// ```
    pub fn new(settings: &RunSettings) -> Result<Setup, Error> {
        let map = settings.map.resolve()?;
        Setup::for_map(map, settings)
    }

    /// Prepare a given map.
    ///
    /// ```
    /// let s = csql::RunSettings::tan1991("ignored", csql::StrategyKind::Lazy, 1);
    /// let map = mdp::Map::from_layout("strip", ".G.").unwrap();
    /// assert_eq!(csql::Setup::for_map(map, &s).unwrap().world.states().len(), 2);
    /// ```
    pub fn for_map(map: Map, settings: &RunSettings) -> Result<Setup, Error> {
        settings.validate()?;
        let world = GridWorld::new(&map);
        let mut space = FeatureSpace::new(&map, &Manhattan)?;
        if let Some(r) = settings.world.sensing_radius {
            space = space.within(f64::from(r));
        }
        let oracle = Oracle::for_grid(&world, settings.gamma.get())?;
        let slip = settings.world.slip();
        let stochastic_oracle = if slip.is_zero() {
            None
        } else {
            Some(Oracle::solve_stochastic(
                &SlipperyGrid::new(&world, slip),
                settings.gamma.get(),
            )?)
        };
        Ok(Setup {
            map,
            world,
            space,
            oracle,
            stochastic_oracle,
        })
    }

    /// The oracle of the true model: V* under the world's slip.
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// s.world.slip = Some(mdp::Slip::new(0.2).unwrap());
    /// let setup = csql::Setup::new(&s).unwrap();
    /// let here = setup.world.states()[0];
    /// assert!(setup.truth().v_star(here) < setup.oracle.v_star(here));
    /// ```
    pub fn truth(&self) -> &Oracle {
        self.stochastic_oracle.as_ref().unwrap_or(&self.oracle)
    }

    /// The grid as a [`World`](mdp::World): its local sensing and the slip of `settings`.
    ///
    /// ```
    /// use mdp::Sensors;
    /// let settings = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// let setup = csql::Setup::new(&settings).unwrap();
    /// assert_eq!(setup.sensed(&settings).num_features(), setup.space.len());
    /// ```
    pub fn sensed(&self, settings: &RunSettings) -> SensedGrid<'_> {
        SensedGrid::new(&self.world, &self.space, settings.world.slip())
    }
}
