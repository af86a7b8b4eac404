//! Deterministic finite MDPs and grid worlds, with a priced sensing model and an oracle.
//!
//! # Quick start
//!
//! Add to `Cargo.toml` (the `rand` and `rand_xoshiro` versions are the ones this
//! workspace's examples and tests use):
//!
//! ```toml
//! [dependencies]
//! mdp = "0.1.0"
//! rand = { version = "0.10.0", default-features = false, features = ["std"] }
//! rand_xoshiro = "0.8.0"
//! ```
//!
//! Then walk a built-in grid world and read what the robot senses:
//!
//! ```
//! use mdp::Mdp;
//! let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
//! let s = world.state_at(mdp::Pos::new(0, 1)).unwrap();
//! let step = world.step(s, mdp::Action::Right.id());
//! assert!(step.terminated); // the goal is one move to the right
//! assert_eq!(step.reward, 1.0);
//! ```
//!
//! This crate is the environment side of cost-sensitive reinforcement learning (Tan,
//! AAAI-91, section "Experiments in a Navigation Domain"). It knows nothing of learning:
//!
//! * [`Mdp`]: a deterministic MDP over dense [`StateId`]s and [`ActionId`]s whose
//!   [`Step`] keeps `terminated` (the goal: do not bootstrap) and `truncated` (a move cap:
//!   bootstrap) apart. [`TabularMdp`] is an explicit one; rewards must be non-negative for
//!   the paper's theorems, or shifted on request ([`NegativeRewards`]).
//! * [`Map`]: a validated grid read from a TOML file ([`Map::load`]), compiled in
//!   ([`builtin`]: `tan3x3`, `tan8x8`, `tan8x8-maze`, `dyna9x6`, `open8x8`,
//!   `corridors9x5`) or drawn at
//!   random ([`RandomMap`]). [`GridWorld`] turns a map into an MDP with four moves
//!   ([`Action`]): a blocked move stays, entering the goal pays 1 and ends the trial.
//! * [`FeatureSpace`]: the sensing model. A feature is the condition ([`Cell`]) of the
//!   cell at a Cartesian [`Offset`] from the robot (`dx` right, `dy` up); cells beyond the
//!   boundary read as obstacles. Costs come from a pluggable [`CostModel`] ([`Manhattan`]
//!   by default) and features are numbered in one fixed order: ascending cost, then
//!   clockwise from straight up.
//! * [`Oracle`]: distances to the goal, `V*` and the optimal actions, for measuring and
//!   testing; a learner never sees it.
//! * Beyond the paper's assumptions ([`SlipperyGrid`], [`SensorNoise`],
//!   [`FeatureSpace::within`]): moves that slip sideways with probability [`Slip`], sensors
//!   that misread with probability [`SensorNoise`], and a sensing range; a
//!   [`StochasticMdp`] lists outcomes for [`Oracle::solve_stochastic`] and
//!   [`evaluate_policy`] and samples them with an RNG passed in.
//! * [`render_text`] and [`render_svg`]: pictures of a map with an [`Overlay`].
//! * [`World`]: the seam every learner works through (dynamics, priced features, starts).
//!   [`SensedGrid`] is a grid map with the paper's sensing; [`FiniteWorld`] is an
//!   explicit finite world read from a JSON world file ([`FiniteWorld::read`]), exported
//!   from a grid ([`FiniteWorld::from_grid`]) or built in ([`builtin_world`]:
//!   `frozenlake4x4`, `frozenlake8x8`, `taxi`, `cliffwalking`, as Gymnasium defines them).
//! * [`reference_points`]: what the best policies score when sensing is priced in reward
//!   units (always measuring, the best open-loop plan, the best policy that measures only
//!   when it pays), computed exactly from a world's model; [`optimum_bounds`]: the best
//!   of every policy, bracketed between a policy's value and an upper bound to a gap.
//!
//! # Example
//!
//! ```
//! use mdp::{Action, FeatureSpace, GridWorld, Manhattan, Mdp, Oracle, Pos};
//!
//! let map = mdp::builtin("tan8x8").unwrap();
//! let world = GridWorld::new(&map);
//! let oracle = Oracle::for_grid(&world, 0.9).unwrap();
//! let space = FeatureSpace::new(&map, &Manhattan).unwrap();
//!
//! let s = world.state_at(Pos::new(7, 0)).unwrap();
//! let best = oracle.optimal_actions(s);
//! let step = world.step(s, best[0]);
//! assert_eq!(oracle.distance(step.next), Some(oracle.distance(s).unwrap() - 1));
//! // The cheapest feature senses the cell above the robot.
//! assert_eq!(space.cost(mdp::Feature(0)), 1.0);
//! println!("{}", mdp::render_text(&map, &mdp::Overlay::default()));
//! ```
//!
//! # Choices where the paper is silent
//!
//! * `tan8x8` is a reconstruction: the paper's Figure 4a is not in its text. It keeps the
//!   figures the paper gives (8 by 8, 13 obstacles, 50 states), and its layout is the one
//!   whose Table 1 is closest to the paper's, found by `cargo xtask fit-map` (the README
//!   gives the command and the scores). A layout that fits the numbers is not the paper's
//!   layout. `tan8x8-maze` is the earlier hand-made maze, kept under its own name.
//! * `tan3x3` puts the goal in the top-right corner.
//! * Maps are limited to [`MAX_SIDE`] cells a side and files to [`MAX_FILE_BYTES`].
//! * A move from a terminal state stays there with reward 0 (trials end before it).

#![deny(missing_docs)]
#![cfg_attr(not(test), warn(clippy::unwrap_used, clippy::expect_used))]

mod belief;
mod builtin;
mod costly;
mod error;
mod finite;
mod format;
mod geometry;
mod grid;
mod map;
mod optimum;
mod oracle;
mod process;
mod random;
mod reference;
mod render;
mod sensing;
mod spec;
mod stochastic;
mod tabular;
mod world;
mod worlds;

pub use belief::{
    BeliefPlan, CostlyModel, Decision, EVERY_PROBE, MAX_BLIND_HORIZON, ModelParts, NodeId,
    PlanOptions, STOP_CHECK_BELIEFS,
};
pub use builtin::{builtin, builtin_names};
pub use costly::{
    BELIEF_QUANTUM, DEFAULT_MAX_BELIEFS, DEFAULT_MAX_PLAN_BYTES, DEFAULT_MAX_PLANS,
    MAX_MENU_FEATURES, PlanSize, ReferenceError, ReferenceOptions, SensingMenu, SensingRule,
};
pub use error::{MapError, MdpError, Position};
pub use finite::{
    Aliasing, FeatureSpec, FiniteWorld, MAX_ACTIONS, MAX_ALIASED_LISTED, MAX_FEATURES, MAX_READING,
    MAX_READINGS, MAX_REWARD, MAX_STATES, OutcomeSpec, PROBABILITY_TOLERANCE, StatesSpec,
    TransitionSpec, WORLD_FORMAT, WORLD_VERSION, WorldError, WorldSpec,
};
pub use format::MAX_FILE_BYTES;
pub use geometry::{Cell, Offset, Pos};
pub use grid::{Action, Blocked, GridOptions, GridWorld};
pub use map::{MAX_SIDE, Map};
pub use optimum::{BoundOptions, OptimumBounds, optimum_bounds};
pub use oracle::Oracle;
pub use process::{ActionId, Mdp, StateId, Step};
pub use random::RandomMap;
pub use reference::{
    BestSensing, OpenLoop, ReferencePoints, always_measuring, always_measuring_sensing,
    best_sensing, free_sensing, open_loop, reference_points, sensing_ceiling,
};
pub use render::{Overlay, render_svg, render_text};
pub use sensing::{BadCost, CostModel, Feature, FeatureSpace, MAX_PRICE, Manhattan, Reading};
pub use spec::{MAX_GOAL_MOVES, resolve};
pub use stochastic::{
    SensorNoise, Slip, SlipperyGrid, StochasticMdp, evaluate_policy, evaluate_stochastic_policy,
    follow_policy,
};
pub use tabular::{NegativeRewards, TabularMdp};
pub use world::{SensedGrid, Sensors, World};
pub use worlds::{
    SensingModel, WorldOptions, WorldSettings, builtin_world, builtin_world_names,
    builtin_world_settings,
};
