//! `csrl._csrl`: the compiled part of the `csrl` Python package.
//!
//! The Python modules beside it (`crates/csrl-py/python/csrl`) give the public names; this
//! module holds what has to run in Rust:
//!
//! * `run`: one run, by the path `csrl run` takes (settings from the paper's preset,
//!   then a TOML settings table, then the arguments, then `csql::run_resolved`), its
//!   report given to Python as Python objects (pythonize); `dumps` writes it as the text
//!   `csrl run --json` prints, byte for byte. The GIL is released while it runs, and the
//!   run checks for Ctrl-C after every trial.
//! * [`PyWorld`]: a finite world with priced features (`mdp::FiniteWorld`), built from a
//!   name (the same resolution as `csrl run --world`) or from a world file's JSON.
//! * [`PyAgent`]: CS-QL stepped from Python ([`csql::Stepper`]), its sensors Python
//!   callables.
//! * `Rng`: the seeded generator a world's starts and outcomes are drawn from, its own
//!   or an agent's.
//! * [`Classifier`]: CS-ID3 or CS-IBL over integer-coded objects, for the scikit-learn
//!   estimators.
//! * [`TestCostTree`]: a tree of the test-cost family (`cslearn::testcost`: ID3, C4.5,
//!   IDX, batch CS-ID3, EG2, DTMC, ICET) over numeric and nominal columns, for the
//!   scikit-learn estimators of that family.
//!
//! Every error of the Rust crates becomes a Python exception with the same message
//! (`SettingsError` and `WorldError`, both `ValueError`s; `DataError` for the
//! classifiers), never a panic.

mod agent;
mod classifier;
mod rng;
mod settings;
mod testcost;
mod world;

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

pub use agent::PyAgent;
pub use classifier::Classifier;
pub use testcost::TestCostTree;
pub use world::PyWorld;

create_exception!(
    csrl,
    SettingsError,
    PyValueError,
    "Settings that cannot be used: unknown keys, values out of range, or settings that mean nothing together (the message names them)."
);
create_exception!(
    csrl,
    WorldError,
    PyValueError,
    "A world or map that cannot be read or built (the message says what and where)."
);
create_exception!(
    csrl,
    AgentError,
    pyo3::exceptions::PyRuntimeError,
    "A CsQlAgent called out of order (act and update alternate), or stopped at an earlier error of its sensor."
);
create_exception!(
    csrl,
    SensorError,
    PyValueError,
    "A sensor's reading that is not an int in its feature's range (the message names the feature)."
);
create_exception!(
    csrl,
    DataError,
    PyValueError,
    "Data a classifier cannot learn from (the message says what and where)."
);

/// The error and its causes, each said once (as `csrl` prints them): a cause whose text
/// the message so far already holds is left out.
pub(crate) fn message(e: &(dyn std::error::Error + 'static)) -> String {
    let mut text = e.to_string().trim_end().to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        let part = c.to_string();
        let part = part.trim_end();
        if !text.contains(part) {
            text.push_str(": ");
            text.push_str(part);
        }
        cause = c.source();
    }
    text
}

/// The Python exception for an error of a run.
pub(crate) fn run_error(e: &csql::Error) -> PyErr {
    match e {
        csql::Error::Map(_)
        | csql::Error::World(_)
        | csql::Error::Cost(_)
        | csql::Error::WorldFile(_) => WorldError::new_err(message(e)),
        _ => SettingsError::new_err(message(e)),
    }
}

/// The Python exception for an error of a world.
pub(crate) fn world_error(e: &(dyn std::error::Error + 'static)) -> PyErr {
    WorldError::new_err(message(e))
}

/// Stops the run when Python has a signal to handle (Ctrl-C), keeping the error that the
/// signal's handler raised; keeps the trace only when asked.
struct Signals {
    keep_trace: bool,
    raised: Option<PyErr>,
}

impl csql::Observer for Signals {
    fn keep_trace(&self) -> bool {
        self.keep_trace
    }

    fn trial(&mut self, _point: &csql::TracePoint) -> csql::Flow {
        if self.keep_going() {
            csql::Flow::Continue
        } else {
            csql::Flow::Stop
        }
    }

    fn keep_going(&mut self) -> bool {
        if self.raised.is_some() {
            return false;
        }
        // The GIL is released during the run: take it for the check only.
        match Python::attach(|py| py.check_signals()) {
            Ok(()) => true,
            Err(e) => {
                self.raised = Some(e);
                false
            }
        }
    }
}

/// One run, its report as Python objects: the dict of the JSON object `csrl run --json`
/// prints (converted by pythonize, key for key in the report's order).
///
/// `world` is a name or path as `--world` takes it, or a `World`; `settings` is the text
/// of a TOML settings file (as `--config` reads it); the other arguments are the flags
/// of the same names.
#[pyfunction]
#[pyo3(signature = (world=None, strategy=None, seed=None, learner=None, settings=None, max_trials=None, episodes=None, predict_sensing=None, trace=false))]
#[expect(
    clippy::too_many_arguments,
    reason = "one argument per flag of `csrl run`, all keywords in Python"
)]
fn run<'py>(
    py: Python<'py>,
    world: Option<&Bound<'py, PyAny>>,
    strategy: Option<&str>,
    seed: Option<u64>,
    learner: Option<&str>,
    settings: Option<&str>,
    max_trials: Option<u32>,
    episodes: Option<u32>,
    predict_sensing: Option<&str>,
    trace: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let object: Option<PyRef<'_, PyWorld>> = match world {
        Some(w) if w.is_instance_of::<PyWorld>() => Some(w.extract()?),
        _ => None,
    };
    let name: Option<String> = match (world, &object) {
        (Some(_), Some(_)) | (None, _) => None,
        (Some(w), None) => Some(w.extract().map_err(|_| {
            SettingsError::new_err(
                "world must be a name, a path or a csrl.World, found another type",
            )
        })?),
    };
    let args = settings::RunArgs {
        world: name,
        strategy,
        seed,
        learner,
        settings,
        max_trials,
        episodes,
        predict_sensing,
    };
    let mut settings = args.settings()?;
    if let Some(w) = &object {
        // The report names the world given.
        settings.map = w.world.name().into();
    }
    if trace && settings.learner.kind().on_episodes() {
        return Err(run_error(&csql::Error::Conflict {
            first: "trace".to_string(),
            second: format!("learner = {}", settings.learner.kind()),
            why: "the learner plays a fixed number of episodes, scored by the costed return: its every episode is already in the report",
        }));
    }
    let mut signals = Signals {
        keep_trace: trace,
        raised: None,
    };
    // Resolving a world solves its true model (value iteration), which takes time on
    // large worlds: everything from here runs without the GIL.
    let world = object.as_ref().map(|w| &w.world);
    let report = py
        .detach(|| {
            let resolved = match world {
                None => csql::Resolved::new(&settings)?,
                Some(world) => csql::Resolved::given(world.clone(), &settings)?,
            };
            csql::run_resolved(&resolved, &settings, &mut signals)
        })
        .map_err(|e| run_error(&e))?;
    if let Some(e) = signals.raised {
        return Err(e);
    }
    Ok(pythonize::pythonize(py, &report)?)
}

/// The settings of a run as `csrl run` would resolve them, as Python objects (the
/// report's `settings` dict), without running: to check settings before a long run.
#[pyfunction]
#[pyo3(signature = (world=None, strategy=None, seed=None, learner=None, settings=None, max_trials=None, episodes=None, predict_sensing=None))]
#[expect(
    clippy::too_many_arguments,
    reason = "one argument per flag of `csrl run`, all keywords in Python"
)]
fn resolve_settings<'py>(
    py: Python<'py>,
    world: Option<&str>,
    strategy: Option<&str>,
    seed: Option<u64>,
    learner: Option<&str>,
    settings: Option<&str>,
    max_trials: Option<u32>,
    episodes: Option<u32>,
    predict_sensing: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    let args = settings::RunArgs {
        world: world.map(str::to_string),
        strategy,
        seed,
        learner,
        settings,
        max_trials,
        episodes,
        predict_sensing,
    };
    let s = args.settings()?;
    Ok(pythonize::pythonize(py, &s)?)
}

/// A Python settings mapping as the text of a TOML settings file.
#[pyfunction]
fn settings_toml(settings: &Bound<'_, PyAny>) -> PyResult<String> {
    settings::to_toml(settings)
}

/// A report (any JSON value as Python holds it) as serde_json writes it, keys in the
/// mapping's order: `dumps(run(...))` is the text `csrl run --json` prints for the same
/// arguments (without its final newline).
#[pyfunction]
fn dumps(obj: &Bound<'_, PyAny>) -> PyResult<String> {
    let mut out = String::new();
    settings::write_json(obj, &mut out)?;
    Ok(out)
}

/// The names of the built-in maps.
#[pyfunction]
fn map_names() -> Vec<&'static str> {
    mdp::builtin_names().to_vec()
}

/// The names of the built-in worlds beyond grid maps.
#[pyfunction]
fn world_names() -> Vec<&'static str> {
    mdp::builtin_world_names().to_vec()
}

/// Where `csrl.run` starts Q and V in `world` at discount `gamma` (0 without negative
/// rewards): `csql::value_floor`. A discount outside [0, 1) is refused: the floor sums
/// the worst reward forever, which only a discount below 1 keeps finite.
#[pyfunction]
fn value_floor(world: PyRef<'_, PyWorld>, gamma: f64) -> PyResult<f64> {
    if !(0.0..1.0).contains(&gamma) {
        return Err(SettingsError::new_err(format!(
            "gamma {gamma}: the discount of value_floor must be at least 0 and below 1"
        )));
    }
    Ok(csql::value_floor(&world.world, gamma))
}

/// The compiled part of the `csrl` package.
#[pymodule]
fn _csrl(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SettingsError", py.get_type::<SettingsError>())?;
    m.add("WorldError", py.get_type::<WorldError>())?;
    m.add("DataError", py.get_type::<DataError>())?;
    m.add("AgentError", py.get_type::<AgentError>())?;
    m.add("SensorError", py.get_type::<SensorError>())?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(resolve_settings, m)?)?;
    m.add_function(wrap_pyfunction!(settings_toml, m)?)?;
    m.add_function(wrap_pyfunction!(dumps, m)?)?;
    m.add_function(wrap_pyfunction!(map_names, m)?)?;
    m.add_function(wrap_pyfunction!(world_names, m)?)?;
    m.add_class::<PyWorld>()?;
    m.add_class::<Classifier>()?;
    m.add_class::<TestCostTree>()?;
    m.add_class::<PyAgent>()?;
    m.add_class::<rng::PyRng>()?;
    m.add_function(wrap_pyfunction!(value_floor, m)?)?;
    // The limits of a world, so that the Python side checks sizes before building one.
    m.add("MAX_STATES", mdp::MAX_STATES)?;
    m.add("MAX_ACTIONS", mdp::MAX_ACTIONS)?;
    m.add("MAX_FEATURES", mdp::MAX_FEATURES)?;
    m.add("MAX_READING", mdp::MAX_READING)?;
    m.add("MAX_REWARD", mdp::MAX_REWARD)?;
    m.add("MAX_PRICE", mdp::MAX_PRICE)?;
    m.add("MAX_TOTAL_COST", cslearn::MAX_TOTAL_COST)?;
    m.add(
        "MAX_CLASSES",
        cslearn::testcost::FrameSpec::DEFAULT_MAX_CLASSES,
    )?;
    m.add(
        "MAX_LOOKAHEAD_FEATURES",
        cslearn::testcost::FamilyParams::DEFAULT_MAX_LOOKAHEAD_FEATURES,
    )?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
