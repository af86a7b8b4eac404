//! Built-in worlds beyond grid maps, as Gymnasium defines them: `frozenlake4x4`,
//! `frozenlake8x8`, `taxi` (Taxi-v3) and `cliffwalking`, each a [`FiniteWorld`] with a
//! choice of sensing ([`SensingModel`]).
//!
//! The worlds, their options and their sensing are documented on [`builtin_world`].

use serde::{Deserialize, Serialize};

use crate::finite::{FeatureSpec, FiniteWorld, OutcomeSpec, StatesSpec, WorldError, WorldSpec};
use crate::geometry::Offset;

/// How the agent of a built-in world senses where it is.
///
/// ```
/// let s: mdp::SensingModel = serde_json::from_str("\"factors\"").unwrap();
/// assert_eq!(s, mdp::SensingModel::Factors);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SensingModel {
    /// The cells around the agent, priced by distance (grid-like worlds only).
    Local,
    /// The factors of the state (row, column, ...), each one feature.
    Factors,
}

/// Settings of a built-in world. The default is Gymnasium's deterministic world with the
/// world's default sensing.
///
/// ```
/// let o = mdp::WorldOptions { slip: Some(2.0 / 3.0), ..Default::default() };
/// let lake = mdp::builtin_world("frozenlake4x4", &o).unwrap();
/// assert_eq!(lake.name(), "frozenlake4x4");
/// let bad = mdp::WorldOptions { slip: Some(1.5), ..Default::default() };
/// assert!(mdp::builtin_world("frozenlake4x4", &bad).is_err());
/// // Taxi reads no slip: given at all, even at 0, it is refused.
/// let taxi = mdp::WorldOptions { slip: Some(0.0), ..Default::default() };
/// assert!(mdp::builtin_world("taxi", &taxi).is_err());
/// ```
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WorldOptions {
    /// The probability that a move goes sideways (in `[0, 1]`; `None`: 0). Not for
    /// Taxi, which refuses it given at all.
    pub slip: Option<f64>,
    /// The probability of sliding one more cell (in `[0, 1]`; `None`: 0). Not for Taxi,
    /// which refuses it given at all.
    pub slide: Option<f64>,
    /// The sensing; `None` is the world's default (factors for Taxi, local otherwise).
    pub sensing: Option<SensingModel>,
    /// The prices of the factors, in factor order (factors sensing only; `None`: 1 each).
    pub factor_costs: Option<Vec<f64>>,
}

const NAMES: &[&str] = &["frozenlake4x4", "frozenlake8x8", "taxi", "cliffwalking"];

/// What a built-in world asks of a run's settings to be learned from its defaults, as
/// plain data (each `None`: the paper's value). A learner's crate applies it where the
/// settings do not give the key (`csql` does, for `csrl run --world NAME`, the settings
/// file's `map` and Python's `csrl.run`), and `csrl world show NAME` prints it.
///
/// The rule behind the values: Boltzmann's temperature is 0.4 times the world's largest
/// reward in size (the paper's 0.4 is for rewards of size 1); where one state of a
/// description pays a penalty for an action that the others do not, the penalty lowers
/// that action's Q, not V, so the detector is `action` (a fall of a tried action's Q,
/// specification 1.11); the trial cap is at least twice the most trials any CS-QL
/// strategy needed in the deterministic world on seeds 1 to 5 (`docs/worlds.md`); and
/// sensing by belief learns a lake's moves over every cell and may stop measuring
/// (`shared_moves`, `blind_plans`), which the active-measurement benchmark found at least
/// as good on every lake (`docs/costly.md`).
///
/// ```
/// let taxi = mdp::builtin_world_settings("taxi").unwrap();
/// assert_eq!((taxi.temperature, taxi.detector, taxi.max_trials), (Some(8.0), Some("action"), Some(200_000)));
/// assert!(mdp::builtin_world_settings("taxi").unwrap().belief_shared_moves.is_none());
/// assert!(mdp::builtin_world_settings("tan8x8").is_none()); // a map, not a built-in world
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct WorldSettings {
    /// Boltzmann's temperature on the world's reward scale (`temperature`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub temperature: Option<f64>,
    /// The detector of inconsistent descriptions, by its setting's value (`[extensions]
    /// detector`: `decrease`, `statistical` or `action`), for CS-QL in the deterministic
    /// world with beta 1.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detector: Option<&'static str>,
    /// The trial cap (`max_trials`) of the learners judged over trials.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_trials: Option<u32>,
    /// Sensing by belief's shared moves (`[belief] shared_moves`: tries of an action
    /// before it is trusted), where the world is sensed by its own state variables and
    /// those read exactly (then its states are a grid of their readings, and a move a
    /// shift of them).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub belief_shared_moves: Option<u32>,
    /// Sensing by belief's open-loop plans a step (`[belief] blind_plans`), where
    /// [`WorldSettings::belief_shared_moves`] applies.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub belief_blind_plans: Option<usize>,
    /// Why, in a sentence or two.
    pub why: &'static str,
}

impl WorldSettings {
    /// Whether the world asks for nothing beyond the paper's settings.
    ///
    /// ```
    /// assert!(!mdp::builtin_world_settings("cliffwalking").unwrap().is_paper());
    /// assert!(!mdp::builtin_world_settings("frozenlake4x4").unwrap().is_paper());
    /// ```
    pub fn is_paper(&self) -> bool {
        self.temperature.is_none()
            && self.detector.is_none()
            && self.max_trials.is_none()
            && self.belief_shared_moves.is_none()
            && self.belief_blind_plans.is_none()
    }
}

/// The settings built-in world `name` asks of a run ([`WorldSettings`]), or `None` if
/// `name` is not a built-in world.
///
/// ```
/// let cliff = mdp::builtin_world_settings("cliffwalking").unwrap();
/// assert_eq!((cliff.temperature, cliff.detector, cliff.max_trials), (Some(40.0), Some("action"), None));
/// assert_eq!(mdp::builtin_world_settings("frozenlake8x8").unwrap().max_trials, Some(200_000));
/// ```
pub fn builtin_world_settings(name: &str) -> Option<WorldSettings> {
    let paper = WorldSettings {
        temperature: None,
        detector: None,
        max_trials: None,
        belief_shared_moves: None,
        belief_blind_plans: None,
        why: "",
    };
    // Measured in the active-measurement benchmark (`cargo xtask costly`): at or above
    // the pairs learned apart, without open-loop plans, on every lake, price and rule.
    let lake = WorldSettings {
        belief_shared_moves: Some(48),
        belief_blind_plans: Some(64),
        ..paper
    };
    macro_rules! lake_why {
        ($why:literal) => {
            concat!(
                $why,
                "; sensed by its row and column, sensing by belief learns each move once for \
                 every cell and may stop measuring, at least as good as each cell apart on \
                 every lake of the active-measurement benchmark"
            )
        };
    }
    Some(match name {
        "frozenlake4x4" => WorldSettings {
            why: lake_why!(
                "rewards of 0 and 1, the paper's scale: its settings learn the lake with every \
                 strategy"
            ),
            ..lake
        },
        "frozenlake8x8" => WorldSettings {
            max_trials: Some(200_000),
            why: lake_why!(
                "rewards of 0 and 1, the paper's scale; the resetting strategy starts every Q \
                 again at each refinement and needs 70000 to 80000 trials on this lake, past \
                 the paper's cap of 20000"
            ),
            ..lake
        },
        "taxi" => WorldSettings {
            temperature: Some(8.0),
            detector: Some("action"),
            max_trials: Some(200_000),
            why: "rewards from -10 to 20: at the paper's temperature (0.4, for rewards of size 1) \
                  Boltzmann selection never tries an action again once it paid -10, and an \
                  illegal pick-up or drop-off lowers that action's Q while V, the maximum, \
                  stays, so the paper's detector never fires; the resetting strategy needs \
                  61000 to 66000 trials",
            ..paper
        },
        "cliffwalking" => WorldSettings {
            temperature: Some(40.0),
            detector: Some("action"),
            why: "rewards from -100 to -1: at the paper's temperature (0.4, for rewards of size \
                  1) Boltzmann selection never tries a move again once it fell off the cliff, \
                  and the fall lowers that move's Q while V, the maximum, stays, so the \
                  paper's detector never fires",
            ..paper
        },
        _ => return None,
    })
}

/// The names of the built-in worlds, in a fixed order.
///
/// ```
/// assert_eq!(mdp::builtin_world_names(), ["frozenlake4x4", "frozenlake8x8", "taxi", "cliffwalking"]);
/// ```
pub fn builtin_world_names() -> &'static [&'static str] {
    NAMES
}

/// A built-in world by name, with options.
///
/// # The worlds
///
/// * **FrozenLake** (`SFFF/FHFH/FFFH/HFFG`, and the 8 by 8 map): state `row * ncol +
///   col` for every cell; holes and the goal are terminal. Actions 0 left, 1 down,
///   2 right, 3 up; a move off the map stays. Entering the goal pays 1, everything else
///   0; trials start on `S`.
/// * **CliffWalking** (4 by 12): state `row * 12 + col`; start (3,0), goal (3,11), the
///   cliff (3,1) to (3,10). Actions 0 up, 1 right, 2 down, 3 left. Every move pays -1;
///   a move into the cliff pays -100 and returns to the start without ending the trial;
///   entering the goal ends it. Cliff cells are states no trial reaches.
/// * **Taxi** (Taxi-v3): state `((row * 5 + col) * 5 + passenger) * 4 + destination`,
///   passenger 0 to 3 at stand R, G, Y, B and 4 in the taxi; actions 0 south, 1 north,
///   2 east, 3 west, 4 pickup, 5 dropoff, east and west blocked by the map's walls.
///   Every step pays -1; a pickup where the passenger waits takes them in, any other
///   pickup pays -10; a drop-off at the destination with the passenger aboard pays 20
///   and ends the trial, at another stand leaves the passenger there (-1), anywhere else
///   pays -10. States with the passenger at the destination are terminal. Trials start
///   uniformly over the 300 states with the passenger at a stand other than the
///   destination.
///
/// # Slips and slides (FrozenLake and CliffWalking)
///
/// With slip `p > 0` a move goes in its intended direction with probability `1 - p` and
/// in each perpendicular direction with `p / 2` (`p = 2/3` is Gymnasium's slippery lake,
/// a third each). The outcomes are listed in Gymnasium's order: the direction whose id is
/// one less (modulo 4), the intended one, the one whose id is one more. With slip 0 the
/// intended move is the only outcome.
///
/// With slide `q > 0`, after the one-cell move, unless the cell reached ends the move (a
/// hole, the cliff or the goal), the agent moves one more cell in the same direction
/// with probability `q` (clamped at the edges, so at an edge the slide stays). Each
/// direction's outcome is then split in two, listed as "no slide" (`1 - q`) then "slide"
/// (`q`), even when both land on the same cell; outcomes are never merged. The reward is
/// that of the cell finally reached (on CliffWalking a slide still costs -1 a move).
///
/// # Sensing
///
/// * [`SensingModel::Local`] (FrozenLake and CliffWalking, the default there): the cells
///   around the agent at every offset of the bordered grid, as [`crate::FeatureSpace::new`]
///   builds them for a map of that size (`|dx| <= width + 1`, `|dy| <= height + 1`, not
///   `(0, 0)`; Cartesian, `dx` right and `dy` up), priced by Manhattan distance and ordered
///   by price then clockwise from straight up ([`crate::Offset::clockwise_cmp`]). Readings:
///   0 `empty` (frozen or start), 1 `obstacle` (outside the map), 2 `goal`, 3 `hole` or
///   `cliff`.
/// * [`SensingModel::Factors`] (the default for Taxi, the only one it has): features
///   `row` and `col` (and for Taxi `passenger` and `destination`), each reading its value
///   (passenger readings named R, G, Y, B, taxi; destination readings R, G, Y, B), priced
///   by [`WorldOptions::factor_costs`] (1 each by default), ties in that order.
///
/// # Example
///
/// ```
/// use mdp::{SensingModel, StochasticMdp, World, WorldOptions};
/// let taxi = mdp::builtin_world("taxi", &WorldOptions::default()).unwrap();
/// assert_eq!((taxi.num_states(), taxi.num_actions()), (500, 6));
/// assert_eq!(taxi.start_distribution().len(), 300);
/// let local = WorldOptions { sensing: Some(SensingModel::Local), ..Default::default() };
/// let err = mdp::builtin_world("taxi", &local).unwrap_err().to_string();
/// assert!(err.contains("passenger"), "{err}");
/// assert!(mdp::builtin_world("chess", &WorldOptions::default()).is_err());
/// ```
pub fn builtin_world(name: &str, options: &WorldOptions) -> Result<FiniteWorld, WorldError> {
    let bad = |option: &'static str, reason: String| WorldError::BadOption {
        world: name.to_string(),
        option,
        reason,
    };
    let given = [("slip", options.slip), ("slide", options.slide)];
    for (option, p) in given.iter().filter_map(|&(o, p)| Some((o, p?))) {
        if !(0.0..=1.0).contains(&p) {
            return Err(bad(option, format!("{p} is not a probability in [0, 1]")));
        }
    }
    let is_taxi = name == "taxi";
    let sensing = options.sensing.unwrap_or(if is_taxi {
        SensingModel::Factors
    } else {
        SensingModel::Local
    });
    if is_taxi {
        if sensing == SensingModel::Local {
            return Err(bad(
                "sensing",
                "local sensing is refused for taxi: the passenger and the destination are \
                 not cells around the taxi, so states that differ only in them would read \
                 alike (use factors)"
                    .to_string(),
            ));
        }
        if let Some((option, p)) = given.iter().find_map(|&(o, p)| Some((o, p?))) {
            return Err(bad(
                option,
                format!(
                    "{p}: Taxi-v3 is deterministic and reads no {option}; slips and slides are for the grid worlds"
                ),
            ));
        }
    }
    let factors = if is_taxi { 4 } else { 2 };
    let costs = match (&options.factor_costs, sensing) {
        (Some(_), SensingModel::Local) => {
            return Err(bad(
                "factor_costs",
                "factor costs apply to factors sensing only; local features are priced by distance"
                    .to_string(),
            ));
        }
        (Some(c), SensingModel::Factors) => {
            if c.len() != factors {
                return Err(bad(
                    "factor_costs",
                    format!("{} costs given, but {name} has {factors} factors", c.len()),
                ));
            }
            if let Some((i, x)) = c
                .iter()
                .enumerate()
                .find(|(_, x)| !(x.is_finite() && **x >= 0.0))
            {
                return Err(bad(
                    "factor_costs",
                    format!("cost {i} is {x}; costs must be finite and >= 0"),
                ));
            }
            if let Some((i, x)) = c.iter().enumerate().find(|(_, x)| **x > crate::MAX_PRICE) {
                return Err(bad(
                    "factor_costs",
                    format!(
                        "cost {i} is {x:e}; costs must be at most {:e} (mdp::MAX_PRICE, so \
                         that a run's total cost stays finite)",
                        crate::MAX_PRICE
                    ),
                ));
            }
            c.clone()
        }
        (None, _) => vec![1.0; factors],
    };
    let sensing = match sensing {
        SensingModel::Local => Sensing::Local,
        SensingModel::Factors => Sensing::Factors(costs),
    };
    match name {
        "frozenlake4x4" => grid_world(name, LAKE4, Kind::Lake, options, &sensing),
        "frozenlake8x8" => grid_world(name, LAKE8, Kind::Lake, options, &sensing),
        "cliffwalking" => grid_world(name, CLIFF, Kind::Cliff, options, &sensing),
        "taxi" => taxi(&sensing),
        _ => Err(WorldError::UnknownWorld {
            name: name.to_string(),
            known: NAMES.join(", "),
        }),
    }
}

enum Sensing {
    Local,
    Factors(Vec<f64>),
}

const LAKE4: &[&str] = &["SFFF", "FHFH", "FFFH", "HFFG"];
const LAKE8: &[&str] = &[
    "SFFFFFFF", "FFFFFFFF", "FFFHFFFF", "FFFFFHFF", "FFFHFFFF", "FHHFFFHF", "FHFFHFHF", "FFFHFFFG",
];
const CLIFF: &[&str] = &[
    "FFFFFFFFFFFF",
    "FFFFFFFFFFFF",
    "FFFFFFFFFFFF",
    "SCCCCCCCCCCG",
];

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Lake,
    Cliff,
}

impl Kind {
    /// Action names and (row, column) moves, in id order.
    fn actions(self) -> [(&'static str, i64, i64); 4] {
        match self {
            Kind::Lake => [
                ("left", 0, -1),
                ("down", 1, 0),
                ("right", 0, 1),
                ("up", -1, 0),
            ],
            Kind::Cliff => [
                ("up", -1, 0),
                ("right", 0, 1),
                ("down", 1, 0),
                ("left", 0, -1),
            ],
        }
    }
    /// The name of reading 3.
    fn danger(self) -> &'static str {
        match self {
            Kind::Lake => "hole",
            Kind::Cliff => "cliff",
        }
    }
}

fn label(r: usize, c: usize) -> String {
    format!("({r},{c})")
}

fn spec(
    name: &str,
    labels: Vec<String>,
    actions: &[&str],
    start: Vec<(f64, u32)>,
    terminal: Vec<u32>,
    transitions: Vec<(u32, u32, Vec<OutcomeSpec>)>,
    (features, readings): (Vec<FeatureSpec>, Vec<Vec<u32>>),
) -> WorldSpec {
    WorldSpec {
        format: crate::finite::WORLD_FORMAT.to_string(),
        version: crate::finite::WORLD_VERSION,
        name: name.to_string(),
        states: StatesSpec::Labels(labels),
        actions: actions.iter().map(|a| a.to_string()).collect(),
        start,
        terminal,
        transitions,
        features,
        readings,
    }
}

/// FrozenLake or CliffWalking from its rows.
fn grid_world(
    name: &str,
    rows: &[&str],
    kind: Kind,
    options: &WorldOptions,
    sensing: &Sensing,
) -> Result<FiniteWorld, WorldError> {
    let grid: Vec<&[u8]> = rows.iter().map(|r| r.as_bytes()).collect();
    let (h, w) = (grid.len(), grid.first().map_or(0, |r| r.len()));
    let id = |r: usize, c: usize| (r * w + c) as u32;
    let cells = || (0..h).flat_map(|r| (0..w).map(move |c| (r, c)));
    let at = |(r, c): (usize, usize)| grid[r][c];
    let start = cells()
        .find(|&p| at(p) == b'S')
        .ok_or_else(|| invalid_builtin(name, "no start cell"))?;
    let ends = |ch: u8| match kind {
        Kind::Lake => ch == b'H' || ch == b'G',
        Kind::Cliff => ch == b'C' || ch == b'G',
    };
    let terminal_cell = |ch: u8| match kind {
        Kind::Lake => ch == b'H' || ch == b'G',
        Kind::Cliff => ch == b'G',
    };
    let actions = kind.actions();
    let step = |(r, c): (usize, usize), d: usize| {
        let (_, dr, dc) = actions[d];
        let nr = (r as i64 + dr).clamp(0, h as i64 - 1) as usize;
        let nc = (c as i64 + dc).clamp(0, w as i64 - 1) as usize;
        (nr, nc)
    };
    // Where a move that ends on `p` leaves the agent: (next, reward, terminated).
    let land = |p: (usize, usize)| -> (u32, f64, bool) {
        let ch = at(p);
        match kind {
            Kind::Lake => (id(p.0, p.1), if ch == b'G' { 1.0 } else { 0.0 }, ends(ch)),
            Kind::Cliff if ch == b'C' => (id(start.0, start.1), -100.0, false),
            Kind::Cliff => (id(p.0, p.1), -1.0, ch == b'G'),
        }
    };
    let (p, q) = (options.slip.unwrap_or(0.0), options.slide.unwrap_or(0.0));
    let mut transitions = Vec::new();
    for pos in cells() {
        if terminal_cell(at(pos)) {
            continue;
        }
        for a in 0..4 {
            let directions = if p == 0.0 {
                vec![(a, 1.0)]
            } else {
                vec![((a + 3) % 4, p / 2.0), (a, 1.0 - p), ((a + 1) % 4, p / 2.0)]
            };
            let mut outs = Vec::new();
            for (d, pd) in directions {
                let first = step(pos, d);
                let mut push = |prob: f64, cell| {
                    let (next, reward, terminated) = land(cell);
                    outs.push((prob, next, reward, terminated));
                };
                if q == 0.0 || ends(at(first)) {
                    push(pd, first);
                } else {
                    push(pd * (1.0 - q), first);
                    push(pd * q, step(first, d));
                }
            }
            transitions.push((id(pos.0, pos.1), a as u32, outs));
        }
    }
    let terminal = cells()
        .filter(|&p| terminal_cell(at(p)))
        .map(|(r, c)| id(r, c))
        .collect();
    let features = match sensing {
        Sensing::Local => {
            let read = |(r, c): (usize, usize), o: Offset| {
                let (rr, cc) = (r as i64 - o.dy as i64, c as i64 + o.dx as i64);
                if rr < 0 || cc < 0 || rr >= h as i64 || cc >= w as i64 {
                    return 1;
                }
                match grid[rr as usize][cc as usize] {
                    b'G' => 2,
                    b'H' | b'C' => 3,
                    _ => 0,
                }
            };
            local_features(w, h, kind.danger(), |s, o| read((s / w, s % w), o))
        }
        Sensing::Factors(costs) => {
            factor_features(&[("row", &[]), ("col", &[])], costs, h * w, |s, f| {
                [s / w, s % w][f] as u32
            })
        }
    };
    let names: Vec<&str> = actions.iter().map(|a| a.0).collect();
    FiniteWorld::new(spec(
        name,
        cells().map(|(r, c)| label(r, c)).collect(),
        &names,
        vec![(1.0, id(start.0, start.1))],
        terminal,
        transitions,
        features,
    ))
}

fn invalid_builtin(name: &str, problem: &str) -> WorldError {
    WorldError::Invalid {
        at: format!("built-in world {name}"),
        problem: problem.to_string(),
    }
}

/// The local features of a `w` by `h` grid: every offset of the bordered grid, priced by
/// Manhattan distance, ordered by price then clockwise from straight up.
fn local_features(
    w: usize,
    h: usize,
    danger: &str,
    read: impl Fn(usize, Offset) -> u32,
) -> (Vec<FeatureSpec>, Vec<Vec<u32>>) {
    let (hw, hh) = (w as i32 + 1, h as i32 + 1);
    let mut offsets: Vec<Offset> = (-hh..=hh)
        .flat_map(|dy| (-hw..=hw).map(move |dx| Offset::new(dx, dy)))
        .filter(|o| (o.dx, o.dy) != (0, 0))
        .collect();
    let cost = |o: &Offset| o.dx.unsigned_abs() + o.dy.unsigned_abs();
    offsets.sort_by(|a, b| cost(a).cmp(&cost(b)).then_with(|| a.clockwise_cmp(b)));
    let names: Vec<String> = ["empty", "obstacle", "goal", danger]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let features = offsets
        .iter()
        .map(|o| FeatureSpec {
            name: format!("({:+},{:+})", o.dx, o.dy).replace("+0", "0"),
            price: cost(o) as f64,
            readings: names.clone(),
        })
        .collect();
    let readings = (0..w * h)
        .map(|s| offsets.iter().map(|&o| read(s, o)).collect())
        .collect();
    (features, readings)
}

/// One feature per factor, each reading its value.
fn factor_features(
    factors: &[(&str, &[&str])],
    costs: &[f64],
    n: usize,
    value: impl Fn(usize, usize) -> u32,
) -> (Vec<FeatureSpec>, Vec<Vec<u32>>) {
    let features = factors
        .iter()
        .zip(costs)
        .map(|(&(name, readings), &price)| FeatureSpec {
            name: name.to_string(),
            price,
            readings: readings.iter().map(|s| s.to_string()).collect(),
        })
        .collect();
    let readings = (0..n)
        .map(|s| (0..factors.len()).map(|f| value(s, f)).collect())
        .collect();
    (features, readings)
}

const TAXI_MAP: &[&str] = &[
    "+---------+",
    "|R: | : :G|",
    "| : | : : |",
    "| : : : : |",
    "| | : | : |",
    "|Y| : |B: |",
    "+---------+",
];
const STANDS: [(usize, usize); 4] = [(0, 0), (0, 4), (4, 0), (4, 3)];
const STAND_NAMES: [&str; 5] = ["R", "G", "Y", "B", "taxi"];

/// Taxi-v3, exactly as Gymnasium builds its table.
fn taxi(sensing: &Sensing) -> Result<FiniteWorld, WorldError> {
    let costs = match sensing {
        Sensing::Factors(c) => c,
        Sensing::Local => return Err(invalid_builtin("taxi", "local sensing")),
    };
    let desc: Vec<&[u8]> = TAXI_MAP.iter().map(|r| r.as_bytes()).collect();
    let encode = |row: usize, col: usize, pass: usize, dest: usize| {
        (((row * 5 + col) * 5 + pass) * 4 + dest) as u32
    };
    let decode = |s: usize| (s / 100, (s / 20) % 5, (s / 4) % 5, s % 4);
    let mut transitions = Vec::new();
    let mut start = Vec::new();
    let mut terminal = Vec::new();
    for s in 0..500 {
        let (row, col, pass, dest) = decode(s);
        if pass == dest {
            terminal.push(s as u32);
            continue;
        }
        if pass < 4 {
            start.push(s as u32);
        }
        for a in 0..6u32 {
            let (mut r, mut c, mut p) = (row, col, pass);
            let mut reward = -1.0;
            let mut done = false;
            match a {
                0 => r = (row + 1).min(4),
                1 => r = row.saturating_sub(1),
                2 if desc[1 + row][2 * col + 2] == b':' => c = (col + 1).min(4),
                3 if desc[1 + row][2 * col] == b':' => c = col.saturating_sub(1),
                4 => {
                    if pass < 4 && (row, col) == STANDS[pass] {
                        p = 4;
                    } else {
                        reward = -10.0;
                    }
                }
                5 => {
                    let here = STANDS.iter().position(|&x| x == (row, col));
                    if pass == 4 && (row, col) == STANDS[dest] {
                        p = dest;
                        done = true;
                        reward = 20.0;
                    } else if let (Some(i), 4) = (here, pass) {
                        p = i;
                    } else {
                        reward = -10.0;
                    }
                }
                _ => {}
            }
            transitions.push((
                s as u32,
                a,
                vec![(1.0, encode(r, c, p, dest), reward, done)],
            ));
        }
    }
    let k = start.len() as f64;
    let labels = (0..500)
        .map(|s| {
            let (r, c, p, d) = decode(s);
            format!("({r},{c},{},{})", STAND_NAMES[p], STAND_NAMES[d])
        })
        .collect();
    let features = factor_features(
        &[
            ("row", &[]),
            ("col", &[]),
            ("passenger", &STAND_NAMES),
            ("destination", &STAND_NAMES[..4]),
        ],
        costs,
        500,
        |s, f| {
            let (r, c, p, d) = decode(s);
            [r, c, p, d][f] as u32
        },
    );
    FiniteWorld::new(spec(
        "taxi",
        labels,
        &["south", "north", "east", "west", "pickup", "dropoff"],
        start.into_iter().map(|s| (1.0 / k, s)).collect(),
        terminal,
        transitions,
        features,
    ))
}
