//! Explicit finite worlds with priced features, and the JSON world file that describes
//! them.
//!
//! A [`FiniteWorld`] lists everything: its states, actions, start distribution, terminal
//! states, the outcomes of every action in every non-terminal state, and its features
//! with their prices and what each state reads on each. It is a [`World`], so every
//! learner, the oracle and the reports work on it as on a grid. Grid maps export to one
//! ([`FiniteWorld::from_grid`]), and the built-in worlds beyond grids
//! ([`crate::builtin_world`]) are ones.
//!
//! The file format is documented on [`WorldSpec`].

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use rand::{Rng, RngExt};
use serde::{Deserialize, Serialize};

use crate::error::MdpError;
use crate::format::{MAX_FILE_BYTES, ReadFailure, read_regular_file};
use crate::grid::Action;
use crate::oracle::Oracle;
use crate::process::{ActionId, Mdp, StateId, Step};
use crate::sensing::{Feature, MAX_PRICE, Reading};
use crate::stochastic::{StochasticMdp, perpendicular};
use crate::world::{SensedGrid, Sensors, World};

/// The `format` of a world file.
pub const WORLD_FORMAT: &str = "csrl-world";
/// The `version` of the world file this crate reads and writes.
pub const WORLD_VERSION: u32 = 1;
/// The most states a world may have.
pub const MAX_STATES: usize = 65_536;
/// The most actions a world may have.
pub const MAX_ACTIONS: usize = 64;
/// The most features a world may have.
pub const MAX_FEATURES: usize = 4_096;
/// The most readings (states times features) a world may have.
pub const MAX_READINGS: usize = 16_777_216;
/// The largest reading a feature may have in a state: a feature reads one of
/// `0..=MAX_READING`, so that its number of readings (one more than its largest) is a
/// `u32`.
pub const MAX_READING: u32 = u32::MAX - 1;
/// The largest size a reward may have. Every sum of rewards a run makes stays far below
/// `f64::MAX`: a return over at most 2^64 moves, a value discounted by a `gamma` below 1
/// (at most 2^53 rewards' worth), their differences and ratios (the policy quality).
/// Larger rewards are refused rather than summed to infinity.
///
/// ```
/// assert_eq!(mdp::MAX_REWARD, 1e200);
/// ```
pub const MAX_REWARD: f64 = 1e200;
/// How far a list of probabilities may sum from 1 (absolute).
pub const PROBABILITY_TOLERANCE: f64 = 1e-9;
/// The most aliased pairs [`FiniteWorld::aliased`] lists (it counts them all).
pub const MAX_ALIASED_LISTED: usize = 100;

/// Why a world could not be read, built or chosen.
///
/// ```
/// let err = mdp::FiniteWorld::from_json("{\"format\": \"csrl-world\", \"version\": 7}").unwrap_err();
/// assert!(matches!(err, mdp::WorldError::Version { found: 7, .. }));
/// assert!(err.to_string().contains("version 7"));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum WorldError {
    /// An error in a file, with the file's path.
    #[error("{path}: {error}")]
    InFile {
        /// The file.
        path: String,
        /// What is wrong with it.
        error: Box<WorldError>,
    },
    /// The file could not be read.
    #[error("cannot read: {0}")]
    Io(String),
    /// The path is a directory or another non-file.
    #[error("not a regular file")]
    NotAFile,
    /// The file is larger than a world file may be.
    #[error("file is {bytes} bytes, more than the {max} a world file may have")]
    FileTooLarge {
        /// Its size.
        bytes: u64,
        /// The limit.
        max: u64,
    },
    /// The file is not UTF-8 text.
    #[error("not UTF-8 text (first bad byte at offset {offset})")]
    NotUtf8 {
        /// The byte offset of the first invalid byte.
        offset: usize,
    },
    /// Not JSON, or missing, unknown or mistyped keys.
    #[error("line {line}, column {column}: {message}")]
    Json {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// The `format` key is missing or not `csrl-world`.
    #[error("not a csrl world file: `format` is {found}, expected \"csrl-world\"")]
    Format {
        /// What the file has (`missing` if nothing).
        found: String,
    },
    /// A `version` this crate does not read.
    #[error("world file version {found} is not supported (this reader reads version {supported})")]
    Version {
        /// The file's version.
        found: u64,
        /// The version this crate reads.
        supported: u32,
    },
    /// A count beyond a limit.
    #[error("{what}: {found}, more than the limit of {max}")]
    TooLarge {
        /// What was counted.
        what: &'static str,
        /// How many there are.
        found: u64,
        /// The limit.
        max: u64,
    },
    /// A value of the world that breaks a rule; `at` says where.
    #[error("{at}: {problem}")]
    Invalid {
        /// Where: a key, an index in a list, a state, an action, a feature.
        at: String,
        /// What is wrong.
        problem: String,
    },
    /// No built-in world of that name.
    #[error("no built-in world named `{name}` (built-in worlds: {known})")]
    UnknownWorld {
        /// What was asked for.
        name: String,
        /// The built-in names, comma-separated.
        known: String,
    },
    /// An option a built-in world refuses.
    #[error("world `{world}`, option `{option}`: {reason}")]
    BadOption {
        /// The world.
        world: String,
        /// The option.
        option: &'static str,
        /// Why.
        reason: String,
    },
}

fn invalid(at: impl Into<String>, problem: impl Into<String>) -> WorldError {
    WorldError::Invalid {
        at: at.into(),
        problem: problem.into(),
    }
}

/// The states of a world file: a count, or one label per state.
///
/// ```
/// let n: mdp::StatesSpec = serde_json::from_str("3").unwrap();
/// assert_eq!(n.len(), 3);
/// let l: mdp::StatesSpec = serde_json::from_str("[\"a\", \"b\"]").unwrap();
/// assert_eq!(l, mdp::StatesSpec::Labels(vec!["a".into(), "b".into()]));
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged, expecting = "a number of states or a list of state labels")]
pub enum StatesSpec {
    /// This many states, labelled `s0`, `s1`, ...
    Count(u64),
    /// One label per state.
    Labels(Vec<String>),
}

impl StatesSpec {
    /// The number of states.
    ///
    /// ```
    /// assert_eq!(mdp::StatesSpec::Count(4).len(), 4);
    /// ```
    pub fn len(&self) -> u64 {
        match self {
            StatesSpec::Count(n) => *n,
            StatesSpec::Labels(l) => l.len() as u64,
        }
    }

    /// Whether there are no states.
    ///
    /// ```
    /// assert!(mdp::StatesSpec::Labels(vec![]).is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// One feature of a world file: its name, its price and optionally names of its readings.
///
/// ```
/// let f: mdp::FeatureSpec = serde_json::from_str(r#"{"name": "row", "price": 1.0}"#).unwrap();
/// assert!(f.readings.is_empty());
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeatureSpec {
    /// A short name.
    pub name: String,
    /// The price of measuring it once (finite, at least 0).
    pub price: f64,
    /// Names of its readings, by value (empty: readings are named by their number).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub readings: Vec<String>,
}

/// One outcome in a world file: `[probability, next, reward, terminated]`.
pub type OutcomeSpec = (f64, u32, f64, bool);

/// The outcomes of one action in one state in a world file: `[state, action, outcomes]`.
pub type TransitionSpec = (u32, u32, Vec<OutcomeSpec>);

/// A world file's contents, before validation; [`FiniteWorld::new`] validates it.
///
/// # The world file (format `csrl-world`, version 1)
///
/// A world file is JSON, the serialisation of a [`WorldSpec`]:
///
/// ```json
/// {
///   "format": "csrl-world",
///   "version": 1,
///   "name": "two-rooms",
///   "states": ["hall", "kitchen", "exit"],
///   "actions": ["stay", "go"],
///   "start": [[1.0, 0]],
///   "terminal": [2],
///   "transitions": [
///     [0, 0, [[1.0, 0, 0.0, false]]],
///     [0, 1, [[0.9, 1, 0.0, false], [0.1, 0, 0.0, false]]],
///     [1, 0, [[1.0, 1, 0.0, false]]],
///     [1, 1, [[1.0, 2, 1.0, true]]]
///   ],
///   "features": [
///     {"name": "light", "price": 1.0, "readings": ["off", "on"]},
///     {"name": "smell", "price": 0.5}
///   ],
///   "readings": [[0, 0], [1, 1], [1, 0]]
/// }
/// ```
///
/// * `format` is `"csrl-world"` and `version` is `1`; both are checked before anything
///   else, so a file of another format or version is refused as such.
/// * `states` is the number of states (labelled `s0`, `s1`, ...) or the list of their
///   labels. State ids are `0..states`.
/// * `actions` names the actions; action ids are their positions.
/// * `start` lists `[probability, state]` pairs: where trials start.
/// * `terminal` lists the terminal states (in any order; repeats are harmless).
/// * `transitions` lists `[state, action, outcomes]`, one entry for every action of every
///   non-terminal state (in any order) and none for terminal states; each outcome is
///   `[probability, next, reward, terminated]`, and `terminated` must be true exactly
///   when `next` is terminal. Outcomes are kept in the given order (sampling depends on
///   it, see [`FiniteWorld`]).
/// * `features` lists the features with their price and, optionally, names of their
///   readings (reading `i` is named `readings[i]`; without names a reading is named by
///   its number, and with names every reading must have one).
/// * `readings` has one row per state (terminal ones too), one reading per feature in
///   the order of `features`, each at most [`MAX_READING`].
/// * Names are distinct: no two state labels, no two actions, no two features and no two
///   readings of one feature have the same name (reports and policies name them).
///
/// Every probability must be finite and in `[0, 1]`, and every list of probabilities
/// must sum to 1 within an absolute tolerance of [`PROBABILITY_TOLERANCE`] (1e-9).
/// Rewards must be finite and at most [`MAX_REWARD`] in size, prices finite, at least 0
/// and at most [`MAX_PRICE`] (so that every sum a run makes stays finite). Unknown keys are
/// refused. A
/// world has at most [`MAX_STATES`] states, [`MAX_ACTIONS`] actions, [`MAX_FEATURES`]
/// features and [`MAX_READINGS`] readings (states times features); a file has at most
/// [`crate::MAX_FILE_BYTES`] bytes. Errors say what is wrong and where: the state, the
/// action, the feature, the index in the list, or the line and column of a JSON error.
///
/// Features are stored cheapest first: [`FiniteWorld::new`] sorts them by price, stably
/// (features of equal price keep the file's order), and permutes the readings with them,
/// so [`FiniteWorld::to_json`] writes them sorted.
///
/// ```
/// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
/// let spec = w.to_spec();
/// assert_eq!(spec.format, "csrl-world");
/// assert_eq!(mdp::FiniteWorld::new(spec).unwrap(), w);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorldSpec {
    /// Always `"csrl-world"`.
    pub format: String,
    /// Always 1.
    pub version: u32,
    /// The world's name.
    pub name: String,
    /// The number of states, or their labels.
    pub states: StatesSpec,
    /// The names of the actions.
    pub actions: Vec<String>,
    /// `[probability, state]` pairs: where trials start.
    pub start: Vec<(f64, u32)>,
    /// The terminal states.
    pub terminal: Vec<u32>,
    /// `[state, action, outcomes]` for every action of every non-terminal state.
    pub transitions: Vec<TransitionSpec>,
    /// The features, with prices.
    pub features: Vec<FeatureSpec>,
    /// One row per state, one reading per feature.
    pub readings: Vec<Vec<u32>>,
}

/// An explicit finite world with priced features.
///
/// Rules, checked by [`FiniteWorld::new`]:
///
/// * A transition's `terminated` equals whether its next state is terminal. Terminal
///   states have no outcomes of their own: an action there stays with reward 0 and
///   `terminated` set (trials end before it), and [`StochasticMdp::sample`] draws nothing.
/// * [`StochasticMdp::outcomes`] gives the outcomes as they were given, in that order.
/// * [`StochasticMdp::sample`]: one outcome draws nothing from the generator; several
///   draw exactly one `rng.random::<f64>()` and take the first outcome whose cumulative
///   probability exceeds it (the last one if rounding leaves none).
/// * [`World::sample_start`]: if all start probabilities are equal, exactly one
///   `rng.random_range(0..k)` over the `k` start states in the listed order (even when
///   `k = 1`); otherwise one `random::<f64>()` and the cumulative rule above.
/// * [`World::states`]: the non-terminal states reachable from a start state through
///   outcomes of positive probability, in id order.
/// * Features are cheapest first (see [`WorldSpec`]).
///
/// ```
/// use mdp::{FiniteWorld, Sensors, StochasticMdp, World};
/// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
/// assert_eq!((w.num_states(), w.num_actions()), (16, 4));
/// assert_eq!(w.start_distribution(), vec![(1.0, mdp::StateId(0))]);
/// assert_eq!(w.price(mdp::Feature(0)), 1.0);
/// let back = FiniteWorld::from_json(&w.to_json()).unwrap();
/// assert_eq!(back, w);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct FiniteWorld {
    name: String,
    labels: Option<Vec<String>>,
    actions: Vec<String>,
    start: Vec<(f64, StateId)>,
    uniform_start: bool,
    terminal: Vec<bool>,
    /// Outcomes of `(s, a)` are `outcomes[first[s * na + a]..first[s * na + a + 1]]`.
    first: Vec<usize>,
    outcomes: Vec<(f64, Step)>,
    features: Vec<FeatureSpec>,
    /// `readings[s * nf + f]`.
    readings: Vec<u32>,
    /// How many readings each feature has: its named readings, or one more than the
    /// largest it reads in any state.
    arity: Vec<u32>,
    states: Vec<StateId>,
}

/// Sum probabilities and check each one and the total.
fn check_probabilities(
    ps: impl Iterator<Item = f64>,
    at: &dyn Fn(usize) -> String,
    whole: &str,
) -> Result<(), WorldError> {
    let mut sum = 0.0;
    for (i, p) in ps.enumerate() {
        if !(p.is_finite() && (0.0..=1.0).contains(&p)) {
            return Err(invalid(
                at(i),
                format!("probability {p} is not a finite number in [0, 1]"),
            ));
        }
        sum += p;
    }
    if (sum - 1.0).abs() > PROBABILITY_TOLERANCE {
        return Err(invalid(
            whole,
            format!("probabilities sum to {sum}, not to 1 (tolerance {PROBABILITY_TOLERANCE})"),
        ));
    }
    Ok(())
}

fn limit(what: &'static str, found: usize, max: usize) -> Result<(), WorldError> {
    if found > max {
        return Err(WorldError::TooLarge {
            what,
            found: found as u64,
            max: max as u64,
        });
    }
    Ok(())
}

impl FiniteWorld {
    /// Validate a world file's contents and build the world (features sorted by price,
    /// stably, readings permuted with them).
    ///
    /// ```
    /// let text = r#"{"format": "csrl-world", "version": 1, "name": "coin",
    ///   "states": 2, "actions": ["flip"], "start": [[1.0, 0]], "terminal": [1],
    ///   "transitions": [[0, 0, [[0.5, 0, 0.0, false], [0.5, 1, 1.0, true]]]],
    ///   "features": [], "readings": [[], []]}"#;
    /// let spec: mdp::WorldSpec = serde_json::from_str(text).unwrap();
    /// let w = mdp::FiniteWorld::new(spec.clone()).unwrap();
    /// assert_eq!(w.name(), "coin");
    /// let mut bad = spec;
    /// bad.transitions[0].2[0].0 = 0.4;
    /// let err = mdp::FiniteWorld::new(bad).unwrap_err().to_string();
    /// assert!(err.contains("state 0, action 0") && err.contains("sum to 0.9"), "{err}");
    /// ```
    pub fn new(spec: WorldSpec) -> Result<FiniteWorld, WorldError> {
        if spec.format != WORLD_FORMAT {
            return Err(WorldError::Format {
                found: format!("{:?}", spec.format),
            });
        }
        if spec.version != WORLD_VERSION {
            return Err(WorldError::Version {
                found: spec.version.into(),
                supported: WORLD_VERSION,
            });
        }
        validate(&spec)?;
        Ok(assemble(spec))
    }

    /// Read a world from the text of a world file.
    ///
    /// `format` and `version` are checked first; JSON errors give the line and column.
    ///
    /// ```
    /// let err = mdp::FiniteWorld::from_json("{\"format\": \"csrl-world\",\n \"version\": 1,").unwrap_err();
    /// assert!(err.to_string().starts_with("line 2"), "{err}");
    /// let err = mdp::FiniteWorld::from_json("{\"format\": \"gym\"}").unwrap_err();
    /// assert!(err.to_string().contains("\"gym\""));
    /// ```
    pub fn from_json(text: &str) -> Result<FiniteWorld, WorldError> {
        #[derive(Deserialize)]
        #[serde(expecting = "a csrl world file (a JSON object)")]
        struct Header {
            format: Option<serde_json::Value>,
            version: Option<serde_json::Value>,
        }
        let json_error = |e: serde_json::Error| WorldError::Json {
            line: e.line(),
            column: e.column(),
            message: strip_position(&e.to_string()),
        };
        let header: Header = serde_json::from_str(text).map_err(json_error)?;
        match &header.format {
            Some(serde_json::Value::String(f)) if f == WORLD_FORMAT => {}
            Some(other) => {
                return Err(WorldError::Format {
                    found: other.to_string(),
                });
            }
            None => {
                return Err(WorldError::Format {
                    found: "missing".to_string(),
                });
            }
        }
        match &header.version {
            Some(v) if v.as_u64() == Some(WORLD_VERSION.into()) => {}
            Some(v) => {
                return Err(match v.as_u64() {
                    Some(found) => WorldError::Version {
                        found,
                        supported: WORLD_VERSION,
                    },
                    None => invalid("`version`", format!("{v} is not a version number")),
                });
            }
            None => {
                return Err(invalid(
                    "`version`",
                    "missing (this reader reads version 1)",
                ));
            }
        }
        let spec: WorldSpec = serde_json::from_str(text).map_err(json_error)?;
        FiniteWorld::new(spec)
    }

    /// Read a world file: regular files only, at most [`MAX_FILE_BYTES`] bytes. Errors
    /// name the file.
    ///
    /// ```
    /// let dir = std::env::temp_dir().join("mdp-doc-world-read");
    /// std::fs::create_dir_all(&dir).unwrap();
    /// let path = dir.join("lake.json");
    /// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
    /// std::fs::write(&path, w.to_json()).unwrap();
    /// assert_eq!(mdp::FiniteWorld::read(&path).unwrap(), w);
    /// let err = mdp::FiniteWorld::read(&dir).unwrap_err().to_string();
    /// assert!(err.contains("not a regular file"));
    /// ```
    pub fn read(path: &Path) -> Result<FiniteWorld, WorldError> {
        let in_file = |error: WorldError| WorldError::InFile {
            path: path.display().to_string(),
            error: Box::new(error),
        };
        let bytes = read_regular_file(path, MAX_FILE_BYTES).map_err(|e| {
            in_file(match e {
                ReadFailure::Io(e) => WorldError::Io(e.to_string()),
                ReadFailure::NotAFile => WorldError::NotAFile,
                ReadFailure::TooLarge { bytes } => WorldError::FileTooLarge {
                    bytes,
                    max: MAX_FILE_BYTES,
                },
            })
        })?;
        let text = std::str::from_utf8(&bytes).map_err(|e| {
            in_file(WorldError::NotUtf8 {
                offset: e.valid_up_to(),
            })
        })?;
        FiniteWorld::from_json(text).map_err(in_file)
    }

    /// The world as a [`WorldSpec`] that [`FiniteWorld::new`] builds back into it.
    ///
    /// ```
    /// let w = mdp::builtin_world("cliffwalking", &mdp::WorldOptions::default()).unwrap();
    /// assert_eq!(w.to_spec().states, mdp::StatesSpec::Labels(
    ///     (0..48).map(|s| format!("({},{})", s / 12, s % 12)).collect()));
    /// ```
    pub fn to_spec(&self) -> WorldSpec {
        let (n, na) = (self.terminal.len(), self.actions.len());
        let nf = self.features.len();
        let mut transitions = Vec::new();
        for s in 0..n {
            if self.terminal[s] {
                continue;
            }
            for a in 0..na {
                let outs = &self.outcomes[self.first[s * na + a]..self.first[s * na + a + 1]];
                transitions.push((
                    s as u32,
                    a as u32,
                    outs.iter()
                        .map(|(p, st)| (*p, st.next.0, st.reward, st.terminated))
                        .collect(),
                ));
            }
        }
        WorldSpec {
            format: WORLD_FORMAT.to_string(),
            version: WORLD_VERSION,
            name: self.name.clone(),
            states: match &self.labels {
                Some(l) => StatesSpec::Labels(l.clone()),
                None => StatesSpec::Count(n as u64),
            },
            actions: self.actions.clone(),
            start: self.start.iter().map(|(p, s)| (*p, s.0)).collect(),
            terminal: (0..n as u32)
                .filter(|&s| self.terminal[s as usize])
                .collect(),
            transitions,
            features: self.features.clone(),
            readings: (0..n)
                .map(|s| self.readings[s * nf..(s + 1) * nf].to_vec())
                .collect(),
        }
    }

    /// The world file: pretty, one transition and one readings row a line, the same text
    /// for the same world; [`FiniteWorld::from_json`] reads it back into the same world.
    ///
    /// ```
    /// let w = mdp::builtin_world("taxi", &mdp::WorldOptions::default()).unwrap();
    /// let text = w.to_json();
    /// assert!(text.starts_with("{\n  \"format\": \"csrl-world\",\n  \"version\": 1,"));
    /// assert_eq!(mdp::FiniteWorld::from_json(&text).unwrap().to_json(), text);
    /// ```
    pub fn to_json(&self) -> String {
        let spec = self.to_spec();
        let j = |v: &dyn erased::Json| v.json();
        let mut out = String::new();
        let _ = writeln!(out, "{{");
        let _ = writeln!(out, "  \"format\": {},", j(&spec.format));
        let _ = writeln!(out, "  \"version\": {},", spec.version);
        let _ = writeln!(out, "  \"name\": {},", j(&spec.name));
        let _ = writeln!(out, "  \"states\": {},", j(&spec.states));
        let _ = writeln!(out, "  \"actions\": {},", j(&spec.actions));
        let _ = writeln!(out, "  \"start\": {},", j(&spec.start));
        let _ = writeln!(out, "  \"terminal\": {},", j(&spec.terminal));
        write_lines(&mut out, "transitions", &spec.transitions, true);
        write_lines(&mut out, "features", &spec.features, true);
        write_lines(&mut out, "readings", &spec.readings, false);
        let _ = writeln!(out, "}}");
        out
    }

    /// The world's name.
    ///
    /// ```
    /// let w = mdp::builtin_world("taxi", &mdp::WorldOptions::default()).unwrap();
    /// assert_eq!(w.name(), "taxi");
    /// ```
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The export of a grid map with its local sensing: the same state ids, the four
    /// moves named as [`Action::name`] names them, trials starting uniformly over the
    /// grid's states, the goal terminal, and the features, prices and readings of
    /// [`SensedGrid`]'s [`Sensors`].
    ///
    /// The outcomes are ordered so that sampling draws exactly as
    /// [`crate::SlipperyGrid`] does: with slip 0 one outcome; with slip `p > 0`
    /// `[(p/2, first perpendicular), (p/2, second perpendicular), (1 - p, intended)]`.
    /// The export is not checked against the file limits: a very large map exports to a
    /// world whose file [`FiniteWorld::from_json`] refuses.
    ///
    /// ```
    /// use mdp::{FeatureSpace, FiniteWorld, GridWorld, Manhattan, SensedGrid, Slip, World};
    /// let grid = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(grid.map(), &Manhattan).unwrap();
    /// let sensed = SensedGrid::new(&grid, &space, Slip::new(0.2).unwrap());
    /// let w = FiniteWorld::from_grid(&sensed);
    /// assert_eq!(w.states(), sensed.states());
    /// assert_eq!(w.action_name(mdp::ActionId(3)), "right");
    /// ```
    pub fn from_grid(grid: &SensedGrid<'_>) -> FiniteWorld {
        let world = grid.world();
        let n = Mdp::num_states(world);
        let p = grid.dynamics().slip().get();
        let states = world.states();
        let k = states.len() as f64;
        let mut transitions = Vec::new();
        for s in 0..n as u32 {
            let sid = StateId(s);
            if Mdp::is_terminal(world, sid) {
                continue;
            }
            for act in Action::ALL {
                let outcome = |q: f64, a: Action| {
                    let st = world.step(sid, a.id());
                    (q, st.next.0, st.reward, st.terminated)
                };
                let outs = if p == 0.0 {
                    vec![outcome(1.0, act)]
                } else {
                    let [first, second] = perpendicular(act);
                    vec![
                        outcome(p / 2.0, first),
                        outcome(p / 2.0, second),
                        outcome(1.0 - p, act),
                    ]
                };
                transitions.push((s, act.id().0, outs));
            }
        }
        let nf = grid.num_features();
        let features = (0..nf as u32)
            .map(|f| {
                let f = Feature(f);
                FeatureSpec {
                    name: grid.feature_name(f),
                    price: grid.price(f),
                    readings: (0..3).map(|v| grid.reading_name(f, Reading(v))).collect(),
                }
            })
            .collect();
        let readings = (0..n as u32)
            .map(|s| {
                (0..nf as u32)
                    .map(|f| grid.read(StateId(s), Feature(f)).0)
                    .collect()
            })
            .collect();
        assemble(WorldSpec {
            format: WORLD_FORMAT.to_string(),
            version: WORLD_VERSION,
            name: world.map().name().to_string(),
            states: StatesSpec::Labels(
                (0..n as u32)
                    .map(|s| grid.state_label(StateId(s)))
                    .collect(),
            ),
            actions: Action::ALL.iter().map(|a| a.name().to_string()).collect(),
            start: states.iter().map(|s| (1.0 / k, s.0)).collect(),
            terminal: vec![world.goal().0],
            transitions,
            features,
            readings,
        })
    }

    /// The pairs of reachable non-terminal states ([`World::states`]) that read the same
    /// on every feature but are not equivalent: their optimal values (by
    /// [`Oracle::solve_stochastic`] with discount `gamma`) differ by more than 1e-9
    /// relative, or they share no optimal action. Such a pair breaks the paper's
    /// assumption that every state is told apart from non-equivalent ones by some set of
    /// features.
    ///
    /// Every pair is counted; the first [`MAX_ALIASED_LISTED`] in id order (by first
    /// state, then second) are listed. Fails only on a discount outside `[0, 1)`.
    ///
    /// ```
    /// let w = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
    /// let a = w.aliased(0.9).unwrap();
    /// assert_eq!((a.count, a.pairs.len()), (0, 0));
    /// ```
    pub fn aliased(&self, gamma: f64) -> Result<Aliasing, MdpError> {
        let oracle = Oracle::solve_stochastic(self, gamma)?;
        let nf = self.features.len();
        let mut groups: BTreeMap<&[u32], Vec<StateId>> = BTreeMap::new();
        for &s in &self.states {
            groups
                .entry(&self.readings[s.index() * nf..(s.index() + 1) * nf])
                .or_default()
                .push(s);
        }
        let distinct = |s: StateId, t: StateId| {
            let (a, b) = (oracle.v_star(s), oracle.v_star(t));
            (a - b).abs() > 1e-9 * a.abs().max(b.abs())
                || !(0..self.actions.len() as u32)
                    .any(|a| oracle.is_optimal(s, ActionId(a)) && oracle.is_optimal(t, ActionId(a)))
        };
        let mut pairs = Vec::new();
        let mut count = 0u64;
        for group in groups.values() {
            // A group's pairs come in id order: its first few are all the merge can keep.
            let mut listed = 0;
            for (i, &s) in group.iter().enumerate() {
                for &t in &group[i + 1..] {
                    if distinct(s, t) {
                        count += 1;
                        if listed < MAX_ALIASED_LISTED {
                            listed += 1;
                            pairs.push((s, t));
                        }
                    }
                }
            }
            pairs.sort_unstable();
            pairs.truncate(MAX_ALIASED_LISTED);
        }
        Ok(Aliasing { pairs, count })
    }

    fn slice(&self, s: StateId, a: ActionId) -> &[(f64, Step)] {
        let i = s.index() * self.actions.len() + a.index();
        &self.outcomes[self.first[i]..self.first[i + 1]]
    }
}

/// What [`FiniteWorld::aliased`] finds.
///
/// ```
/// let a = mdp::Aliasing::default();
/// assert!(a.pairs.is_empty() && a.count == 0);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Aliasing {
    /// The first pairs in id order, at most [`MAX_ALIASED_LISTED`].
    pub pairs: Vec<(StateId, StateId)>,
    /// How many pairs there are in all.
    pub count: u64,
}

/// Serialise to compact JSON; for the writer of [`FiniteWorld::to_json`].
mod erased {
    pub(super) trait Json {
        fn json(&self) -> String;
    }
    impl<T: serde::Serialize> Json for T {
        fn json(&self) -> String {
            // The world's values are strings, integers, booleans and finite numbers,
            // which always serialise.
            serde_json::to_string(self).unwrap_or_default()
        }
    }
}

/// Write `"key": [` then one compact item a line, then `],` (or `]` for the last key).
fn write_lines<T: Serialize>(out: &mut String, key: &str, items: &[T], comma: bool) {
    use erased::Json;
    let end = if comma { "," } else { "" };
    if items.is_empty() {
        let _ = writeln!(out, "  \"{key}\": []{end}");
        return;
    }
    let _ = writeln!(out, "  \"{key}\": [");
    for (i, item) in items.iter().enumerate() {
        let sep = if i + 1 < items.len() { "," } else { "" };
        let _ = writeln!(out, "    {}{sep}", item.json());
    }
    let _ = writeln!(out, "  ]{end}");
}

/// serde_json's message without its trailing " at line L column C".
fn strip_position(message: &str) -> String {
    match message.rfind(" at line ") {
        Some(i) => message[..i].to_string(),
        None => message.to_string(),
    }
}

/// Check every rule of [`WorldSpec`] except `format` and `version`.
fn validate(spec: &WorldSpec) -> Result<(), WorldError> {
    let n64 = spec.states.len();
    if n64 > MAX_STATES as u64 {
        return Err(WorldError::TooLarge {
            what: "states",
            found: n64,
            max: MAX_STATES as u64,
        });
    }
    let n = n64 as usize;
    let na = spec.actions.len();
    let nf = spec.features.len();
    limit("actions", na, MAX_ACTIONS)?;
    limit("features", nf, MAX_FEATURES)?;
    limit("readings (states times features)", n * nf, MAX_READINGS)?;
    if n == 0 {
        return Err(invalid("`states`", "a world needs at least one state"));
    }
    if na == 0 {
        return Err(invalid("`actions`", "a world needs at least one action"));
    }
    if let StatesSpec::Labels(labels) = &spec.states {
        distinct("`states`", "state label", labels.iter())?;
    }
    distinct("`actions`", "action name", spec.actions.iter())?;
    distinct(
        "`features`",
        "feature name",
        spec.features.iter().map(|f| &f.name),
    )?;
    for (f, feature) in spec.features.iter().enumerate() {
        distinct(
            &format!("`features`[{f}] `{}` `readings`", feature.name),
            "reading name",
            feature.readings.iter(),
        )?;
    }
    let state = |at: &str, s: u32| -> Result<usize, WorldError> {
        if (s as usize) < n {
            Ok(s as usize)
        } else {
            Err(invalid(
                at,
                format!(
                    "state {s} does not exist (there are {n} states, 0 to {})",
                    n - 1
                ),
            ))
        }
    };
    let mut terminal = vec![false; n];
    for (i, &s) in spec.terminal.iter().enumerate() {
        terminal[state(&format!("`terminal`[{i}]"), s)?] = true;
    }
    if spec.start.is_empty() {
        return Err(invalid("`start`", "the start distribution is empty"));
    }
    for (i, &(_, s)) in spec.start.iter().enumerate() {
        let at = format!("`start`[{i}]");
        if terminal[state(&at, s)?] {
            return Err(invalid(
                at,
                format!("state {s} is terminal; trials cannot start there"),
            ));
        }
    }
    check_probabilities(
        spec.start.iter().map(|x| x.0),
        &|i| format!("`start`[{i}]"),
        "`start`",
    )?;
    let mut given: Vec<Option<usize>> = vec![None; n * na];
    for (i, (s, a, outs)) in spec.transitions.iter().enumerate() {
        let at = format!("`transitions`[{i}]");
        let s = state(&at, *s)?;
        let a = *a as usize;
        if a >= na {
            return Err(invalid(
                at,
                format!(
                    "action {a} does not exist (there are {na} actions, 0 to {})",
                    na - 1
                ),
            ));
        }
        let at = format!("`transitions`[{i}] (state {s}, action {a})");
        if terminal[s] {
            return Err(invalid(
                at,
                format!("state {s} is terminal; a terminal state has no transitions"),
            ));
        }
        if let Some(first) = given[s * na + a] {
            return Err(invalid(
                at,
                format!("given twice (first at `transitions`[{first}])"),
            ));
        }
        given[s * na + a] = Some(i);
        if outs.is_empty() {
            return Err(invalid(at, "no outcomes"));
        }
        check_probabilities(
            outs.iter().map(|o| o.0),
            &|j| format!("{at}, outcome {j}"),
            &at,
        )?;
        for (j, &(_, next, reward, terminated)) in outs.iter().enumerate() {
            let at = format!("{at}, outcome {j}");
            let next = state(&at, next)?;
            if !reward.is_finite() {
                return Err(invalid(at, format!("reward {reward} is not finite")));
            }
            if reward.abs() > MAX_REWARD {
                return Err(invalid(
                    at,
                    format!(
                        "reward {reward:e} is larger in size than {MAX_REWARD:e} (mdp::MAX_REWARD, \
                         so that its sums over a run stay finite)"
                    ),
                ));
            }
            if terminated != terminal[next] {
                return Err(invalid(
                    at,
                    format!(
                        "`terminated` is {terminated} but state {next} is {}",
                        if terminal[next] {
                            "terminal"
                        } else {
                            "not terminal"
                        }
                    ),
                ));
            }
        }
    }
    for s in 0..n {
        if terminal[s] {
            continue;
        }
        if let Some(a) = (0..na).find(|&a| given[s * na + a].is_none()) {
            return Err(invalid(
                format!("state {s}, action {a}"),
                "no transition given (every action of a non-terminal state needs one)",
            ));
        }
    }
    for (f, feature) in spec.features.iter().enumerate() {
        if !(feature.price.is_finite() && feature.price >= 0.0) {
            return Err(invalid(
                format!("`features`[{f}] `{}`", feature.name),
                format!("price {} is not a finite number >= 0", feature.price),
            ));
        }
        if feature.price > MAX_PRICE {
            return Err(invalid(
                format!("`features`[{f}] `{}`", feature.name),
                format!(
                    "price {:e} is more than {MAX_PRICE:e} (mdp::MAX_PRICE, so that a run's \
                     total cost stays finite)",
                    feature.price
                ),
            ));
        }
    }
    if spec.readings.len() != n {
        return Err(invalid(
            "`readings`",
            format!("{} rows, but there are {n} states", spec.readings.len()),
        ));
    }
    for (s, row) in spec.readings.iter().enumerate() {
        if row.len() != nf {
            return Err(invalid(
                format!("`readings`[{s}]"),
                format!("{} readings, but there are {nf} features", row.len()),
            ));
        }
        for (f, (&v, feature)) in row.iter().zip(&spec.features).enumerate() {
            if v > MAX_READING {
                return Err(invalid(
                    format!("`readings`[{s}][{f}]"),
                    format!(
                        "state {s} reads {v} on feature `{}`, more than the largest reading \
                         a feature may have ({MAX_READING})",
                        feature.name
                    ),
                ));
            }
            if !feature.readings.is_empty() && v as usize >= feature.readings.len() {
                return Err(invalid(
                    format!("`readings`[{s}][{f}]"),
                    format!(
                        "state {s} reads {v} on feature `{}`, which names only {} readings",
                        feature.name,
                        feature.readings.len()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Refuse a name given twice in the list `list` (its items are `what`s), naming both
/// places.
fn distinct<'a>(
    list: &str,
    what: &str,
    names: impl Iterator<Item = &'a String>,
) -> Result<(), WorldError> {
    let mut seen: BTreeMap<&str, usize> = BTreeMap::new();
    for (i, name) in names.enumerate() {
        if let Some(first) = seen.insert(name, i) {
            return Err(invalid(
                format!("{list}[{i}]"),
                format!(
                    "{what} {name:?} is also {list}[{first}]'s: names must differ, or reports \
                     and policies would be ambiguous"
                ),
            ));
        }
    }
    Ok(())
}

/// Build the world from a spec that satisfies the rules (or a grid export).
fn assemble(spec: WorldSpec) -> FiniteWorld {
    let n = spec.states.len() as usize;
    let na = spec.actions.len();
    let nf = spec.features.len();
    let mut terminal = vec![false; n];
    for &s in &spec.terminal {
        terminal[s as usize] = true;
    }
    let mut by_pair: Vec<Option<&Vec<OutcomeSpec>>> = vec![None; n * na];
    for (s, a, outs) in &spec.transitions {
        by_pair[*s as usize * na + *a as usize] = Some(outs);
    }
    let mut first = Vec::with_capacity(n * na + 1);
    let mut outcomes = Vec::new();
    for outs in &by_pair {
        first.push(outcomes.len());
        for &(p, next, reward, terminated) in outs.map(|v| v.as_slice()).unwrap_or(&[]) {
            outcomes.push((
                p,
                Step {
                    next: StateId(next),
                    reward,
                    terminated,
                    truncated: false,
                },
            ));
        }
    }
    first.push(outcomes.len());
    let mut order: Vec<usize> = (0..nf).collect();
    // Prices are finite, so `partial_cmp` is total; unlike `total_cmp` it ties -0 and 0.
    order.sort_by(|&a, &b| {
        spec.features[a]
            .price
            .partial_cmp(&spec.features[b].price)
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let features: Vec<FeatureSpec> = order.iter().map(|&f| spec.features[f].clone()).collect();
    let mut readings = Vec::with_capacity(n * nf);
    for row in &spec.readings {
        readings.extend(order.iter().map(|&f| row[f]));
    }
    let start: Vec<(f64, StateId)> = spec.start.iter().map(|&(p, s)| (p, StateId(s))).collect();
    let uniform_start = start.iter().all(|&(p, _)| p == start[0].0);
    let labels = match spec.states {
        StatesSpec::Count(_) => None,
        StatesSpec::Labels(l) => Some(l),
    };
    let arity = (0..nf)
        .map(|f| {
            let named = features_named(&features, f);
            let largest = (0..n)
                .map(|s| readings[s * nf + f])
                .max()
                // At most `MAX_READING` (checked), so the count is a `u32`.
                .map_or(0, |m| m.saturating_add(1));
            named.max(largest)
        })
        .collect();
    let mut world = FiniteWorld {
        name: spec.name,
        labels,
        actions: spec.actions,
        start,
        uniform_start,
        terminal,
        first,
        outcomes,
        features,
        readings,
        arity,
        states: Vec::new(),
    };
    world.states = reachable(&world);
    world
}

/// How many readings feature `f` names.
fn features_named(features: &[FeatureSpec], f: usize) -> u32 {
    features[f].readings.len() as u32
}

/// The non-terminal states reachable from a start state, in id order.
fn reachable(w: &FiniteWorld) -> Vec<StateId> {
    let na = w.actions.len();
    let mut seen = vec![false; w.terminal.len()];
    let mut stack: Vec<StateId> = Vec::new();
    for &(p, s) in &w.start {
        if p > 0.0 && !seen[s.index()] {
            seen[s.index()] = true;
            stack.push(s);
        }
    }
    while let Some(s) = stack.pop() {
        if w.terminal[s.index()] {
            continue;
        }
        for a in 0..na {
            for (p, step) in w.slice(s, ActionId(a as u32)) {
                if *p > 0.0 && !seen[step.next.index()] {
                    seen[step.next.index()] = true;
                    stack.push(step.next);
                }
            }
        }
    }
    (0..w.terminal.len() as u32)
        .map(StateId)
        .filter(|s| seen[s.index()] && !w.terminal[s.index()])
        .collect()
}

/// The first entry whose cumulative probability exceeds `u` (the last if none does).
fn pick<T>(items: &[T], prob: impl Fn(&T) -> f64, u: f64) -> usize {
    let mut cum = 0.0;
    for (i, item) in items.iter().enumerate() {
        cum += prob(item);
        if cum > u {
            return i;
        }
    }
    items.len().saturating_sub(1)
}

impl StochasticMdp for FiniteWorld {
    fn num_states(&self) -> usize {
        self.terminal.len()
    }
    fn num_actions(&self) -> usize {
        self.actions.len()
    }
    fn is_terminal(&self, s: StateId) -> bool {
        self.terminal[s.index()]
    }
    fn outcomes(&self, s: StateId, a: ActionId, out: &mut Vec<(f64, Step)>) {
        out.clear();
        if self.terminal[s.index()] {
            out.push((1.0, terminal_step(s)));
        } else {
            out.extend_from_slice(self.slice(s, a));
        }
    }
    fn sample<R: Rng + ?Sized>(&self, s: StateId, a: ActionId, rng: &mut R) -> Step {
        if self.terminal[s.index()] {
            return terminal_step(s);
        }
        let outs = self.slice(s, a);
        if outs.len() == 1 {
            return outs[0].1;
        }
        let u = rng.random::<f64>();
        outs[pick(outs, |o| o.0, u)].1
    }
}

/// What an action does in a terminal state: stay, reward 0.
fn terminal_step(s: StateId) -> Step {
    Step {
        next: s,
        reward: 0.0,
        terminated: true,
        truncated: false,
    }
}

impl Sensors for FiniteWorld {
    fn num_features(&self) -> usize {
        self.features.len()
    }
    fn price(&self, f: Feature) -> f64 {
        self.features[f.index()].price
    }
    fn read(&self, s: StateId, f: Feature) -> Reading {
        Reading(self.readings[s.index() * self.features.len() + f.index()])
    }
    fn readings(&self, f: Feature) -> u32 {
        self.arity[f.index()]
    }
    fn feature_name(&self, f: Feature) -> String {
        self.features[f.index()].name.clone()
    }
    fn reading_name(&self, f: Feature, v: Reading) -> String {
        self.features[f.index()]
            .readings
            .get(v.0 as usize)
            .cloned()
            .unwrap_or_else(|| v.0.to_string())
    }
}

impl World for FiniteWorld {
    fn states(&self) -> Vec<StateId> {
        self.states.clone()
    }
    fn start_distribution(&self) -> Vec<(f64, StateId)> {
        self.start.clone()
    }
    fn sample_start<R: Rng + ?Sized>(&self, rng: &mut R) -> StateId {
        if self.uniform_start {
            self.start[rng.random_range(0..self.start.len())].1
        } else {
            let u = rng.random::<f64>();
            self.start[pick(&self.start, |x| x.0, u)].1
        }
    }
    fn state_label(&self, s: StateId) -> String {
        match &self.labels {
            Some(l) => l[s.index()].clone(),
            None => s.to_string(),
        }
    }
    fn action_name(&self, a: ActionId) -> String {
        self.actions[a.index()].clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pick_takes_the_first_cumulative_above_and_the_last_on_rounding() {
        let ps = [0.25, 0.25, 0.5];
        assert_eq!(pick(&ps, |p| *p, 0.0), 0);
        assert_eq!(pick(&ps, |p| *p, 0.25), 1);
        assert_eq!(pick(&ps, |p| *p, 0.4999), 1);
        assert_eq!(pick(&ps, |p| *p, 0.5), 2);
        assert_eq!(pick(&[0.3, 0.3], |p| *p, 0.9), 1);
    }

    #[test]
    fn strip_position_keeps_the_message() {
        assert_eq!(
            strip_position("EOF while parsing at line 2 column 3"),
            "EOF while parsing"
        );
        assert_eq!(strip_position("plain"), "plain");
    }
}
