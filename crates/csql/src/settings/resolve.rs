//! What a run's settings name: a grid map (the paper's world, sensed around the robot) or
//! a world beyond grids (a built-in world or a world file), each with the oracle the run
//! is measured against.
//!
//! The setting `map` names either. A built-in world's name (`frozenlake4x4`, `taxi`, ...)
//! or a path ending in `.json` is a world beyond grids; anything else is resolved as a map
//! (a built-in map, a map file, `random:...`, `MAP@ROW:COL`). Settings that only make
//! sense for one kind are refused on the other with a message naming both.

use std::path::Path;

use mdp::{ActionId, FiniteWorld, Oracle, StateId, StochasticMdp};

use crate::error::Error;
use crate::settings::setup::Setup;
use crate::settings::values::RunSettings;

/// A world resolved from settings, ready to run.
///
/// ```
/// let settings = csql::RunSettings::tan1991("frozenlake4x4", csql::StrategyKind::Lazy, 1);
/// match csql::Resolved::new(&settings).unwrap() {
///     csql::Resolved::Finite { world, .. } => assert_eq!(world.name(), "frozenlake4x4"),
///     csql::Resolved::Grid(_) => unreachable!(),
/// }
/// let grid = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
/// assert!(matches!(csql::Resolved::new(&grid).unwrap(), csql::Resolved::Grid(_)));
/// ```
#[derive(Clone, Debug)]
#[expect(clippy::large_enum_variant, reason = "built once per run")]
pub enum Resolved {
    /// A grid map with the paper's local sensing.
    Grid(Setup),
    /// A world beyond grids, with the oracle of its true model.
    Finite {
        /// The world.
        world: FiniteWorld,
        /// Its oracle (value iteration on the true model, at the run's discount).
        oracle: Oracle,
    },
}

impl Resolved {
    /// Resolve the world the settings name and check the settings against it.
    ///
    /// ```
    /// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
    /// s.apply_toml("[world]\nslide = 0.5", "x.toml").unwrap();
    /// let err = csql::Resolved::new(&s).unwrap_err().to_string();
    /// assert!(err.contains("slide"), "{err}");
    /// // A grid map reads no slide: given at its default, it is refused all the same.
    /// s.apply_toml("[world]\nslide = 0.0", "x.toml").unwrap();
    /// let err = csql::Resolved::new(&s).unwrap_err().to_string();
    /// assert!(err.contains("[world] slide = 0"), "{err}");
    /// ```
    pub fn new(settings: &RunSettings) -> Result<Resolved, Error> {
        settings.validate()?;
        let name = settings.map.name();
        let world = &settings.world;
        if is_world_name(name) {
            let world = if mdp::builtin_world_names().contains(&name) {
                mdp::builtin_world(name, &world.world_options())?
            } else {
                carries_its_own(settings, "a world file")?;
                FiniteWorld::read(Path::new(name))?
            };
            return Resolved::finite(world, settings);
        }
        let grid_only = |setting: &str| Error::Conflict {
            first: format!("the grid map {name}"),
            second: setting.to_string(),
            why: "grid maps sense the cells around the robot and move one cell at a time; use a built-in world (csrl world list) for these",
        };
        // A grid map reads none of these: given at all, at any value, they are refused.
        if let Some(p) = world.slide {
            return Err(grid_only(&format!("[world] slide = {}", p.get())));
        }
        if let Some(m) = world.sensing {
            let m = format!("{m:?}").to_lowercase();
            return Err(grid_only(&format!("[world] sensing = \"{m}\"")));
        }
        if world.factor_costs.is_some() {
            return Err(grid_only("[world] factor_costs"));
        }
        check_with_world(settings, true, true)?;
        let setup = Setup::new(settings)?;
        check_size(settings, &setup.sensed(settings))?;
        Ok(Resolved::Grid(setup))
    }
}

impl Resolved {
    /// A world built in code (a [`FiniteWorld`] from arrays, or read and changed), with
    /// the settings checked against it and its oracle solved at the run's discount. The
    /// world carries its own dynamics, features and prices, so the `[world]` settings
    /// that would change them are refused, as they are for a world file; the settings'
    /// `map` is not read (the report names the world).
    ///
    /// ```
    /// let lake = mdp::builtin_world("frozenlake4x4", &Default::default()).unwrap();
    /// let s = csql::RunSettings::tan1991("tan8x8", csql::StrategyKind::Lazy, 1);
    /// let resolved = csql::Resolved::given(lake.clone(), &s).unwrap();
    /// let report = csql::run_resolved(&resolved, &s, &mut csql::KeepTrace).unwrap();
    /// assert_eq!(report.trials().unwrap().map, "frozenlake4x4");
    /// let mut slipping = s.clone();
    /// slipping.world.slip = Some(mdp::Slip::new(0.1).unwrap());
    /// let err = csql::Resolved::given(lake.clone(), &slipping).unwrap_err().to_string();
    /// assert!(err.contains("slip"), "{err}");
    /// slipping.world.slip = Some(mdp::Slip::default()); // given at 0: refused all the same
    /// assert!(csql::Resolved::given(lake, &slipping).is_err());
    /// ```
    pub fn given(world: FiniteWorld, settings: &RunSettings) -> Result<Resolved, Error> {
        settings.validate()?;
        carries_its_own(
            settings,
            &format!("the world {} given to the run", world.name()),
        )?;
        Resolved::finite(world, settings)
    }

    /// A world beyond grids with the settings checked against it, and its oracle.
    fn finite(world: FiniteWorld, settings: &RunSettings) -> Result<Resolved, Error> {
        if settings.world.sensing_radius.is_some() {
            return Err(Error::GridOnly {
                what: "[world] sensing_radius (offsets around a robot on a grid)",
            });
        }
        check_with_world(settings, is_deterministic(&world), false)?;
        check_size(settings, &world)?;
        let oracle = Oracle::solve_stochastic(&world, settings.gamma.get())?;
        Ok(Resolved::Finite { world, oracle })
    }
}

/// Refuses the `[world]` settings that would change a world's dynamics, features or
/// prices, for a world that carries its own (`what`: a world file, or one given): each
/// given at all, at any value (a world that carries its own reads none of them).
fn carries_its_own(settings: &RunSettings, what: &str) -> Result<(), Error> {
    let w = &settings.world;
    let given = [
        ("slip", w.slip.is_some()),
        ("slide", w.slide.is_some()),
        ("sensing", w.sensing.is_some()),
        ("factor_costs", w.factor_costs.is_some()),
    ];
    if let Some((key, _)) = given.iter().find(|(_, given)| *given) {
        return Err(Error::Conflict {
            first: what.to_string(),
            second: format!("[world] {key}"),
            why: "it carries its own dynamics, features and prices (give them when building it)",
        });
    }
    Ok(())
}

/// Settings that mean nothing in the world they are run in, refused once the world is
/// known: how long the quality must hold where the oracle judges (a deterministic world,
/// in the paper's setting: the oracle's convergence ends such a run, and the quality is
/// only measured, on its schedule `quality_every`), and a memory of recent steps on a grid
/// sensed without a radius, where every state is told apart by its surroundings and no
/// description runs out of features to add.
///
/// ```
/// let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
/// s.judge.quality_patience = 3;
/// let err = csql::Resolved::new(&s).unwrap_err().to_string();
/// assert!(err.contains("quality_patience"), "{err}");
/// s.judge.quality_patience = 20;
/// s.judge.quality_every = 11; // the quality is measured in every run
/// assert!(csql::Resolved::new(&s).is_ok());
/// ```
pub(crate) fn check_with_world(
    settings: &RunSettings,
    deterministic: bool,
    grid: bool,
) -> Result<(), Error> {
    let e = settings.extensions();
    let defaults = crate::settings::values::JudgeSettings::default();
    if !settings.judged_by_quality(deterministic)
        && settings.judge.quality_patience != defaults.quality_patience
    {
        return Err(Error::Conflict {
            first: "judge.quality_patience".to_string(),
            second: "a run the oracle judges (a deterministic world, the paper's setting)"
                .to_string(),
            why: "the oracle's convergence ends such a run; the quality is measured there, every quality_every trials, but judges only runs beyond the paper (slip, slide, noise, a sensing range, an extension, or judge_by_quality = true)",
        });
    }
    if grid && e.memory > 0 && settings.world.sensing_radius.is_none() {
        return Err(Error::Conflict {
            first: format!("extensions.memory = {}", e.memory),
            second: "a grid map sensed without [world] sensing_radius".to_string(),
            why: "memory refines a description whose features have run out, and on a grid every state is told apart by its surroundings unless a radius limits them",
        });
    }
    Ok(())
}

/// Whether a `map` setting names a world beyond grids: a built-in world, or a file whose
/// name ends in `.json`.
///
/// ```
/// assert!(csql::is_world_name("taxi"));
/// assert!(csql::is_world_name("worlds/my.json"));
/// assert!(!csql::is_world_name("tan8x8"));
/// ```
pub fn is_world_name(name: &str) -> bool {
    mdp::builtin_world_names().contains(&name) || name.ends_with(".json")
}

/// Runs whose memory would exceed a documented bound, refused before they start with
/// the estimate: full sensing keeps every state's whole view ([`crate::FullView`]). And
/// runs priced by `[costly] price` whose costed returns could add up to more than
/// [`crate::MAX_COSTED_TOTAL`] in size (every feature charged, and the largest reward
/// earned, at every move of every trial), whose sums would not be true.
///
/// ```
/// let s = csql::RunSettings::tan1991("random:256x256:0.2:1", csql::StrategyKind::Lazy, 1)
///     .with_learner(csql::LearnerKind::FullSensing);
/// let err = csql::Resolved::new(&s).unwrap_err().to_string();
/// assert!(err.contains("over the limit"), "{err}");
/// ```
pub(crate) fn check_size<W: mdp::World + ?Sized>(
    settings: &RunSettings,
    world: &W,
) -> Result<(), Error> {
    if settings.learner == crate::LearnerSettings::FullSensing {
        let needed = crate::FullView::readings_needed(world);
        if needed > crate::FULL_VIEW_LIMIT {
            return Err(Error::TooLarge {
                what: format!(
                    "full sensing of {} ({} states, each with its whole view)",
                    settings.map,
                    world.states().len()
                ),
                needed,
                limit: crate::FULL_VIEW_LIMIT,
                hint: "run it on a smaller world, or with a sensing radius",
            });
        }
    }
    if let Some(c) = settings.costly {
        // The most a run's costed returns could add up to in size: every feature
        // charged, and the largest reward earned, at every move of every trial. Their
        // sums (an episode's, the means over episodes) stay finite below the bound.
        let whole: f64 = (0..world.num_features() as u32)
            .map(|f| world.price(mdp::Feature(f)))
            .sum();
        let mut outcomes = Vec::new();
        let mut reward = 0.0f64;
        for s in world.states() {
            for a in 0..world.num_actions() as u32 {
                world.outcomes(s, mdp::ActionId(a), &mut outcomes);
                for o in &outcomes {
                    reward = reward.max(o.1.reward.abs());
                }
            }
        }
        let most = (c.price * whole + reward)
            * f64::from(settings.max_moves.get())
            * f64::from(settings.max_trials.get());
        if !(0.0..=crate::MAX_COSTED_TOTAL).contains(&most) {
            return Err(Error::InvalidSetting {
                value: format!(
                    "costly.price = {:?} in {} (feature costs summing to {whole:?}, rewards of up to {reward:?} in size)",
                    c.price, settings.map
                ),
                expected: "costed returns that can be summed: the price times the summed feature costs, plus the largest reward, times max_moves and max_trials, at most 1e300 (csql::MAX_COSTED_TOTAL)",
            });
        }
    }
    Ok(())
}

/// Whether every action of every non-terminal state has a single outcome: who judges a
/// run ([`crate::Judging`]), and which settings it refuses, depend on it.
pub(crate) fn is_deterministic<W: StochasticMdp + ?Sized>(world: &W) -> bool {
    let mut out = Vec::new();
    (0..world.num_states() as u32)
        .map(StateId)
        .filter(|&s| !world.is_terminal(s))
        .all(|s| {
            (0..world.num_actions() as u32).map(ActionId).all(|a| {
                world.outcomes(s, a, &mut out);
                out.len() == 1
            })
        })
}
