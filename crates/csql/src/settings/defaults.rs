//! The defaults of a run in the world it names: the paper's, except where a built-in
//! world asks for settings of its own ([`mdp::builtin_world_settings`]): a temperature on
//! its reward scale, the detector that works with its penalties, a trial cap.
//!
//! A world's setting is a default like the paper's: it fills a key the settings do not
//! give ([`crate::SettingsDraft::build`]), and a key given, in a file, by a flag or from
//! Python, always wins. The report's settings echo what the run used, the world's
//! defaults included, and build again to the same settings.

use qlearn::Temperature;

use crate::settings::costed::BeliefParams;
use crate::settings::extensions::{DetectorKind, WorldExtras};
use crate::settings::learner::StrategyKind;
use crate::settings::values::{MapSource, RunSettings, TrialCap};

/// What a run in a world defaults to, where the settings do not say: the paper's values
/// (temperature 0.4, the paper's detector `decrease`, a cap of 20000 trials), or those a
/// built-in world asks for ([`mdp::WorldSettings`]); `csrl world show` prints them.
///
/// ```
/// use csql::{DetectorKind, WorldDefaults};
/// let taxi = WorldDefaults::of("taxi");
/// assert_eq!((taxi.temperature.get(), taxi.detector, taxi.max_trials.get()), (8.0, DetectorKind::Action, 200_000));
/// assert!(taxi.world.is_some());
/// let map = WorldDefaults::of("tan8x8");
/// assert_eq!((map.temperature.get(), map.detector, map.max_trials.get()), (0.4, DetectorKind::Decrease, 20_000));
/// assert!(map.world.is_none());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldDefaults {
    /// Boltzmann's temperature (`temperature`).
    pub temperature: Temperature,
    /// CS-QL's detector (`[extensions] detector`) in the world as built in, with beta 1
    /// ([`WorldDefaults::detector_for`]).
    pub detector: DetectorKind,
    /// The trial cap of the learners judged over trials (`max_trials`; AMRL-Q and
    /// sensing by belief play the paper's 20000 episodes unless told).
    pub max_trials: TrialCap,
    /// The built-in world's own settings and why it asks for them, if the map names a
    /// built-in world (`None`: a grid map or a world file, at the paper's values).
    pub world: Option<mdp::WorldSettings>,
}

impl WorldDefaults {
    /// The paper's defaults, for every world that asks for nothing else.
    ///
    /// ```
    /// assert_eq!(csql::WorldDefaults::paper().max_trials.get(), 20_000);
    /// ```
    pub fn paper() -> WorldDefaults {
        // The paper's preset, whatever its map: only its numbers are read.
        let paper =
            RunSettings::tan1991(MapSource::Named(String::new()), StrategyKind::Resetting, 1);
        WorldDefaults {
            temperature: paper.temperature,
            detector: DetectorKind::default(),
            max_trials: paper.max_trials,
            world: None,
        }
    }

    /// The defaults of the world `map` names: a built-in world's own where it has them,
    /// the paper's otherwise.
    ///
    /// ```
    /// assert_eq!(csql::WorldDefaults::of("cliffwalking").temperature.get(), 40.0);
    /// assert_eq!(csql::WorldDefaults::of("frozenlake8x8").max_trials.get(), 200_000);
    /// assert_eq!(csql::WorldDefaults::of("frozenlake4x4").temperature.get(), 0.4);
    /// ```
    pub fn of(map: &str) -> WorldDefaults {
        let paper = WorldDefaults::paper();
        let Some(asked) = mdp::builtin_world_settings(map) else {
            return paper;
        };
        WorldDefaults {
            temperature: asked
                .temperature
                .and_then(|t| Temperature::new(t).ok())
                .unwrap_or(paper.temperature),
            detector: asked
                .detector
                .and_then(detector_named)
                .unwrap_or(paper.detector),
            max_trials: asked
                .max_trials
                .and_then(|n| TrialCap::new(n).ok())
                .unwrap_or(paper.max_trials),
            world: Some(asked),
        }
    }

    /// The defaults of a run's map: a named built-in world's own, the paper's for
    /// anything else (a map given as a value is a grid map).
    ///
    /// ```
    /// use csql::{MapSource, WorldDefaults};
    /// assert_eq!(WorldDefaults::of_source(&MapSource::from("taxi")), WorldDefaults::of("taxi"));
    /// let mine = mdp::Map::from_layout("taxi", ".G.").unwrap(); // a grid, whatever its name
    /// assert_eq!(WorldDefaults::of_source(&MapSource::from(mine)), WorldDefaults::paper());
    /// ```
    pub fn of_source(map: &MapSource) -> WorldDefaults {
        match map {
            MapSource::Named(name) => WorldDefaults::of(name),
            MapSource::Given(_) => WorldDefaults::paper(),
        }
    }

    /// CS-QL's detector where `[extensions] detector` is not given: the world's, where it
    /// applies (the world as built in, deterministic, and beta 1: a fall of a tried
    /// action's Q proves an inconsistent description only there), the paper's otherwise.
    ///
    /// ```
    /// use csql::{DetectorKind, WorldDefaults, WorldExtras};
    /// let taxi = WorldDefaults::of("cliffwalking");
    /// let plain = WorldExtras::default();
    /// assert_eq!(taxi.detector_for(1.0, &plain), DetectorKind::Action);
    /// assert_eq!(taxi.detector_for(0.5, &plain), DetectorKind::Decrease);
    /// let slippery = WorldExtras { slip: Some(mdp::Slip::new(0.1).unwrap()), ..Default::default() };
    /// assert_eq!(taxi.detector_for(1.0, &slippery), DetectorKind::Decrease);
    /// ```
    pub fn detector_for(&self, beta: f64, world: &WorldExtras) -> DetectorKind {
        if self.detector == DetectorKind::Action && (beta != 1.0 || world.departs_from_the_paper())
        {
            DetectorKind::default()
        } else {
            self.detector
        }
    }

    /// Sensing by belief's settings, with what `params` leaves to the world filled: the
    /// world's shared moves and open-loop plans ([`mdp::WorldSettings::belief_shared_moves`],
    /// [`mdp::WorldSettings::belief_blind_plans`]) where it asks for them, is sensed by its
    /// own state variables (`[world] sensing = "factors"`) read without noise, and an
    /// episode of `max_moves` moves fits the open-loop plans ([`mdp::MAX_BLIND_HORIZON`]).
    /// A key `params` gives (0 included) stays as given; the others stay unset, which
    /// is off.
    ///
    /// ```
    /// use csql::{BeliefParams, WorldDefaults, WorldExtras};
    /// let factors = WorldExtras { sensing: Some(mdp::SensingModel::Factors), ..Default::default() };
    /// let lake = WorldDefaults::of("frozenlake8x8").belief_for(BeliefParams::default(), &factors, 200);
    /// assert_eq!((lake.shared_moves, lake.blind_plans), (Some(48), Some(64)));
    /// // A key given stays; the lake sensed cell by cell around the agent is no grid.
    /// let apart = BeliefParams { shared_moves: Some(0), ..Default::default() };
    /// let given = WorldDefaults::of("frozenlake8x8").belief_for(apart, &factors, 200);
    /// assert_eq!((given.shared_moves, given.blind_plans), (Some(0), Some(64)));
    /// let local = WorldDefaults::of("frozenlake8x8").belief_for(BeliefParams::default(), &WorldExtras::default(), 200);
    /// assert!(local.is_default());
    /// assert!(WorldDefaults::of("taxi").belief_for(BeliefParams::default(), &factors, 200).is_default());
    /// ```
    pub fn belief_for(
        &self,
        params: BeliefParams,
        world: &WorldExtras,
        max_moves: u32,
    ) -> BeliefParams {
        let applies = world.sensing == Some(mdp::SensingModel::Factors)
            && world.sensor_noise().is_zero()
            && max_moves <= mdp::MAX_BLIND_HORIZON;
        let asked = self.world.filter(|_| applies);
        BeliefParams {
            shared_moves: params
                .shared_moves
                .or(asked.and_then(|w| w.belief_shared_moves)),
            blind_plans: params
                .blind_plans
                .or(asked.and_then(|w| w.belief_blind_plans)),
            ..params
        }
    }
}

/// The detector a setting's value names.
fn detector_named(name: &str) -> Option<DetectorKind> {
    [
        DetectorKind::Decrease,
        DetectorKind::Statistical,
        DetectorKind::Action,
    ]
    .into_iter()
    .find(|d| d.name() == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_world_asks_for_settings_csql_has() {
        for &name in mdp::builtin_world_names() {
            let asked = mdp::builtin_world_settings(name).unwrap();
            if let Some(t) = asked.temperature {
                assert!(Temperature::new(t).is_ok(), "{name}");
            }
            if let Some(d) = asked.detector {
                assert!(detector_named(d).is_some(), "{name}: {d}");
            }
            if let Some(n) = asked.max_trials {
                assert!(TrialCap::new(n).is_ok(), "{name}");
            }
        }
    }
}
