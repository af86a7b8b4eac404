//! Grid worlds: a [`Map`] turned into a deterministic MDP with four moves.

use std::fmt;

use serde::{Deserialize, Serialize};

use crate::error::MdpError;
use crate::geometry::{Cell, Offset, Pos};
use crate::map::Map;
use crate::process::{ActionId, Mdp, StateId, Step};
use crate::tabular::{NegativeRewards, TabularMdp};

/// The four moves of a grid world, with action ids 0 to 3 in this order.
///
/// ```
/// use mdp::Action;
/// assert_eq!(Action::from_id(Action::Left.id()), Some(Action::Left));
/// assert_eq!(Action::Up.name(), "up");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Action {
    /// Towards row 0 (dy = +1).
    Up,
    /// Away from row 0 (dy = -1).
    Down,
    /// Towards column 0 (dx = -1).
    Left,
    /// Away from column 0 (dx = +1).
    Right,
}

impl Action {
    /// All four, in id order.
    ///
    /// ```
    /// assert_eq!(mdp::Action::ALL[3], mdp::Action::Right);
    /// ```
    pub const ALL: [Action; 4] = [Action::Up, Action::Down, Action::Left, Action::Right];

    /// The action's id.
    ///
    /// ```
    /// assert_eq!(mdp::Action::Down.id(), mdp::ActionId(1));
    /// ```
    pub fn id(self) -> ActionId {
        ActionId(self as u32)
    }

    /// The action of an id, if it is one of the four.
    ///
    /// ```
    /// assert_eq!(mdp::Action::from_id(mdp::ActionId(4)), None);
    /// ```
    pub fn from_id(id: ActionId) -> Option<Action> {
        Action::ALL.get(id.index()).copied()
    }

    /// The move as a Cartesian offset (`dx` right, `dy` up).
    ///
    /// ```
    /// assert_eq!(mdp::Action::Up.offset(), mdp::Offset::new(0, 1));
    /// ```
    pub fn offset(self) -> Offset {
        match self {
            Action::Up => Offset::new(0, 1),
            Action::Down => Offset::new(0, -1),
            Action::Left => Offset::new(-1, 0),
            Action::Right => Offset::new(1, 0),
        }
    }

    /// Lowercase name: `up`, `down`, `left`, `right`.
    ///
    /// ```
    /// assert_eq!(mdp::Action::Right.name(), "right");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Action::Up => "up",
            Action::Down => "down",
            Action::Left => "left",
            Action::Right => "right",
        }
    }

    /// An arrow character for text renderings.
    ///
    /// ```
    /// assert_eq!(mdp::Action::Left.arrow(), '<');
    /// ```
    pub fn arrow(self) -> char {
        match self {
            Action::Up => '^',
            Action::Down => 'v',
            Action::Left => '<',
            Action::Right => '>',
        }
    }
}

impl fmt::Display for Action {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What a move into an obstacle or the boundary does.
///
/// ```
/// assert_eq!(mdp::Blocked::default(), mdp::Blocked::Stay);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Blocked {
    /// The robot stays where it is and receives the step reward (the paper's setting).
    #[default]
    Stay,
}

/// Settings of a grid world.
///
/// The default is the paper's: blocked moves stay, reward 1 for entering the goal, 0 for
/// every other move, negative rewards refused.
///
/// ```
/// let o = mdp::GridOptions::default();
/// assert_eq!((o.goal_reward, o.step_reward), (1.0, 0.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GridOptions {
    /// What a blocked move does.
    pub blocked: Blocked,
    /// Reward for a move that enters the goal.
    pub goal_reward: f64,
    /// Reward for every other move.
    pub step_reward: f64,
    /// What to do if a reward is negative.
    pub negative_rewards: NegativeRewards,
}

impl Default for GridOptions {
    fn default() -> Self {
        GridOptions {
            blocked: Blocked::Stay,
            goal_reward: 1.0,
            step_reward: 0.0,
            negative_rewards: NegativeRewards::Refuse,
        }
    }
}

/// A grid world: every free cell (empty or goal) is a state, numbered in row-major order;
/// the goal is the one terminal state.
///
/// ```
/// use mdp::{Action, GridWorld, Mdp, Pos};
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let s = world.state_at(Pos::new(0, 1)).unwrap();
/// let step = world.step(s, Action::Right.id());
/// assert_eq!(world.pos(step.next), Pos::new(0, 2));
/// assert!(step.terminated && step.reward == 1.0);
/// // Bumping into the boundary stays in place.
/// assert_eq!(world.step(s, Action::Up.id()).next, s);
/// ```
#[derive(Clone, Debug)]
pub struct GridWorld {
    map: Map,
    options: GridOptions,
    positions: Vec<Pos>,
    state_of: Vec<Option<StateId>>,
    goal: StateId,
    table: TabularMdp,
}

impl GridWorld {
    /// The grid world of a map with the paper's settings.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan8x8").unwrap());
    /// assert_eq!(mdp::Mdp::num_states(&w), 51);
    /// ```
    #[cfg_attr(
        not(test),
        expect(
            clippy::expect_used,
            reason = "the default options have non-negative, finite rewards, the only thing with_options refuses"
        )
    )]
    pub fn new(map: &Map) -> GridWorld {
        GridWorld::with_options(map, GridOptions::default())
            .expect("the default options have no negative reward")
    }

    /// The grid world of a map with explicit settings; fails only on a negative or
    /// non-finite reward that is not to be shifted.
    ///
    /// ```
    /// use mdp::{GridOptions, GridWorld, NegativeRewards};
    /// let map = mdp::builtin("tan3x3").unwrap();
    /// let costly = GridOptions { step_reward: -0.1, ..GridOptions::default() };
    /// assert!(GridWorld::with_options(&map, costly).is_err());
    /// let shifted = GridOptions { negative_rewards: NegativeRewards::Shift, ..costly };
    /// assert!(GridWorld::with_options(&map, shifted).is_ok());
    /// ```
    pub fn with_options(map: &Map, options: GridOptions) -> Result<GridWorld, MdpError> {
        let mut positions = Vec::new();
        let mut state_of = vec![None; map.width() * map.height()];
        for (p, c) in map.cells() {
            if c.is_free() {
                state_of[p.row * map.width() + p.col] = Some(StateId(positions.len() as u32));
                positions.push(p);
            }
        }
        #[cfg_attr(
            not(test),
            expect(
                clippy::expect_used,
                reason = "a valid map's goal is a free cell, and every free cell got a state above"
            )
        )]
        let goal = state_of[map.goal().row * map.width() + map.goal().col].expect("goal is free");
        let n = positions.len();
        let mut next = Vec::with_capacity(n * 4);
        let mut reward = Vec::with_capacity(n * 4);
        for &p in &positions {
            for a in Action::ALL {
                let o = a.offset();
                let (r, c) = (p.row as i64 - o.dy as i64, p.col as i64 + o.dx as i64);
                let target = match map.cell_at(r, c) {
                    Cell::Obstacle => match options.blocked {
                        Blocked::Stay => p,
                    },
                    _ => Pos::new(r as usize, c as usize),
                };
                #[cfg_attr(
                    not(test),
                    expect(
                        clippy::expect_used,
                        reason = "a move lands on a free cell: the target if free, else the robot's own cell"
                    )
                )]
                let t = state_of[target.row * map.width() + target.col].expect("free");
                next.push(t.0);
                reward.push(if t == goal && p != map.goal() {
                    options.goal_reward
                } else {
                    options.step_reward
                });
            }
        }
        let terminal = (0..n).map(|i| i == goal.index()).collect();
        let table = TabularMdp::new(n, 4, next, reward, terminal, options.negative_rewards)?;
        Ok(GridWorld {
            map: map.clone(),
            options,
            positions,
            state_of,
            goal,
            table,
        })
    }

    /// The map.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// assert_eq!(w.map().name(), "tan3x3");
    /// ```
    pub fn map(&self) -> &Map {
        &self.map
    }

    /// The settings.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// assert_eq!(w.options().goal_reward, 1.0);
    /// ```
    pub fn options(&self) -> &GridOptions {
        &self.options
    }

    /// The goal state.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// assert_eq!(w.pos(w.goal()), mdp::Pos::new(0, 2));
    /// ```
    pub fn goal(&self) -> StateId {
        self.goal
    }

    /// The position of a state.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// assert_eq!(w.pos(mdp::StateId(0)), mdp::Pos::new(0, 0));
    /// ```
    pub fn pos(&self, s: StateId) -> Pos {
        self.positions[s.index()]
    }

    /// The state at a position, if the cell is free.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan8x8-maze").unwrap());
    /// assert!(w.state_at(mdp::Pos::new(0, 5)).is_none()); // an obstacle
    /// ```
    pub fn state_at(&self, p: Pos) -> Option<StateId> {
        if p.row < self.map.height() && p.col < self.map.width() {
            self.state_of[p.row * self.map.width() + p.col]
        } else {
            None
        }
    }

    /// The states: the non-goal free cells, in id order (row-major), where trials start.
    /// The same cells, in the same order, as [`Map::states`] gives as positions; the MDP's
    /// [`num_states`](Mdp::num_states) also counts the goal.
    ///
    /// ```
    /// let w = mdp::GridWorld::new(&mdp::builtin("tan8x8").unwrap());
    /// assert_eq!(w.states().len(), 50);
    /// ```
    pub fn states(&self) -> Vec<StateId> {
        self.non_terminal_states()
    }

    /// The condition of the cell at Cartesian offset `o` from state `s` (`dx` right,
    /// `dy` up). Cells beyond the interior read as obstacles, so every offset is defined.
    ///
    /// ```
    /// use mdp::{Cell, GridWorld, Offset, Pos};
    /// let w = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let s = w.state_at(Pos::new(0, 1)).unwrap();
    /// assert_eq!(w.sense(s, Offset::new(1, 0)), Cell::Goal);
    /// assert_eq!(w.sense(s, Offset::new(0, 1)), Cell::Obstacle);
    /// ```
    #[inline]
    pub fn sense(&self, s: StateId, o: Offset) -> Cell {
        let p = self.positions[s.index()];
        self.map
            .cell_at(p.row as i64 - o.dy as i64, p.col as i64 + o.dx as i64)
    }
}

impl Mdp for GridWorld {
    #[inline]
    fn num_states(&self) -> usize {
        self.positions.len()
    }
    #[inline]
    fn num_actions(&self) -> usize {
        4
    }
    #[inline]
    fn is_terminal(&self, s: StateId) -> bool {
        s == self.goal
    }
    #[inline]
    fn step(&self, s: StateId, a: ActionId) -> Step {
        self.table.step(s, a)
    }
}
