//! `csrl._csrl.CsQlAgent`: CS-QL stepped from Python ([`csql::Stepper`]), its sensors
//! Python callables.

use csql::{Moment, StepError, Stepper};
use mdp::{Feature, Reading};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::{AgentError, SensorError, run_error};

/// CS-QL driven one move at a time: `act(sensor)`, then `update(...)`.
#[pyclass(module = "csrl._csrl", name = "CsQlAgent")]
pub struct PyAgent {
    pub(crate) stepper: Stepper,
    /// The sensor of the state the agent is in (the last one given): asked again, as the
    /// sensor of the state left, when the move from there refines.
    here: Option<Py<PyAny>>,
    /// An update given without a sensor: learned from at the next `act`, whose sensor
    /// reads the state it reached.
    waiting: Option<(f64, bool, bool)>,
    /// How many readings each feature has (the caller's numbering).
    arities: Vec<u32>,
}

/// The Python sensors of one call: `now` reads the state the agent is in, `left` the
/// state its move left. The first error is kept (and every later read answers 0): the
/// call then fails with it.
struct PySense<'a, 'py> {
    now: Option<&'a Bound<'py, PyAny>>,
    left: Option<&'a Bound<'py, PyAny>>,
    arities: &'a [u32],
    error: Option<PyErr>,
}

impl PySense<'_, '_> {
    fn read_py(&mut self, at: Moment, f: Feature) -> PyResult<Reading> {
        let sensor = match at {
            Moment::Now => self.now,
            Moment::Left => self.left,
        }
        .ok_or_else(|| {
            AgentError::new_err(format!(
                "feature {} was to be read {}, with no sensor of it",
                f.0,
                match at {
                    Moment::Now => "in the state reached",
                    Moment::Left => "in the state left",
                }
            ))
        })?;
        let value = sensor.call1((f.0,))?;
        let last = self.arities[f.index()] - 1;
        let out_of_range = |shown: String| {
            SensorError::new_err(format!(
                "the sensor read {shown} for feature {}, which reads 0 to {last}",
                f.0
            ))
        };
        if value.is_instance_of::<pyo3::types::PyBool>() {
            return Err(SensorError::new_err(format!(
                "the sensor returned a bool for feature {}, not an int",
                f.0
            )));
        }
        match value.extract::<i128>() {
            Ok(v) if (0..=i128::from(last)).contains(&v) => Ok(Reading(v as u32)),
            Ok(v) => Err(out_of_range(v.to_string())),
            Err(_) => Err(SensorError::new_err(format!(
                "the sensor returned {} for feature {}, not an int",
                value
                    .repr()
                    .map(|r| r.to_string())
                    .unwrap_or_else(|_| "a value".into()),
                f.0
            ))),
        }
    }
}

impl csql::Sense for PySense<'_, '_> {
    fn read(&mut self, at: Moment, f: Feature) -> Reading {
        if self.error.is_some() {
            return Reading(0);
        }
        self.read_py(at, f).unwrap_or_else(|e| {
            self.error = Some(e);
            Reading(0)
        })
    }
}

/// The Python exception for an error of the stepper.
fn step_error(e: &StepError) -> PyErr {
    match e {
        StepError::Reading { .. } => SensorError::new_err(e.to_string()),
        StepError::Reward(_) => PyValueError::new_err(e.to_string()),
        StepError::OutOfOrder { .. } | StepError::Stopped(_) => AgentError::new_err(e.to_string()),
    }
}

impl PyAgent {
    /// After a call of the stepper: the sensor's error first (the stepper then stops: its
    /// learning holds a reading that was never made), else the stepper's.
    fn settle(&mut self, error: Option<PyErr>, out: Result<(), StepError>) -> PyResult<()> {
        if let Some(e) = error {
            self.stepper.stop(format!("its sensor failed: {e}"));
            return Err(e);
        }
        out.map_err(|e| step_error(&e))
    }

    fn check_stopped(&self) -> PyResult<()> {
        match self.stepper.stopped() {
            Some(why) => Err(step_error(&StepError::Stopped(why.to_string()))),
            None => Ok(()),
        }
    }

    /// Learn from a move, `now` reading the state reached.
    fn learn(
        &mut self,
        py: Python<'_>,
        (reward, terminated, truncated): (f64, bool, bool),
        now: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let left = self.here.as_ref().map(|h| h.bind(py).clone());
        let mut sense = PySense {
            now,
            left: left.as_ref(),
            arities: &self.arities,
            error: None,
        };
        let out = self
            .stepper
            .update(reward, terminated, truncated, &mut sense);
        let error = sense.error.take();
        self.here = now.map(|n| n.clone().unbind());
        self.settle(error, out)
    }
}

#[pymethods]
impl PyAgent {
    /// A CS-QL agent for features of prices `feature_costs`, each reading one of
    /// `0..feature_values[i]`, in an environment of `num_actions` actions. `settings` is
    /// the text of a TOML settings file, read as `csrl run` reads it (then `strategy` and
    /// `seed` over it; the keys of a run the agent does not read are refused,
    /// `csql::NOT_READ_BY_A_STEPPER`); `refine_from` is `"left"` or `"next"`; Q and V start at
    /// `initial_value`.
    #[new]
    #[pyo3(signature = (feature_costs, feature_values, num_actions, strategy=None, seed=None, settings=None, refine_from="left", initial_value=0.0))]
    #[expect(
        clippy::too_many_arguments,
        reason = "keywords in Python, one per choice of the agent"
    )]
    fn new(
        feature_costs: Vec<f64>,
        feature_values: Vec<u32>,
        num_actions: usize,
        strategy: Option<&str>,
        seed: Option<u64>,
        settings: Option<&str>,
        refine_from: &str,
        initial_value: f64,
    ) -> PyResult<PyAgent> {
        let from = match refine_from {
            "left" => csql::RefineFrom::StateLeft,
            "next" => csql::RefineFrom::NextSensed,
            other => {
                return Err(crate::SettingsError::new_err(format!(
                    "refine_from = {other:?}: expected \"left\" or \"next\""
                )));
            }
        };
        let args = crate::settings::RunArgs {
            world: None,
            strategy,
            seed,
            learner: None,
            settings,
            max_trials: None,
            episodes: None,
            predict_sensing: None,
        };
        let s = args
            .draft()?
            .build_for_stepper()
            .map_err(|e| run_error(&e))?;
        let stepper = Stepper::new(&feature_costs, &feature_values, num_actions, &s)
            .and_then(|st| st.starting_at(initial_value))
            .map_err(|e| run_error(&e))?
            .refining_from(from);
        Ok(PyAgent {
            stepper,
            here: None,
            waiting: None,
            arities: feature_values,
        })
    }

    /// Classify the state `sensor` reads if a trial starts here (or learn from the last
    /// move, if its update came without a sensor) and choose an action.
    fn act(&mut self, sensor: &Bound<'_, PyAny>) -> PyResult<u32> {
        self.check_stopped()?;
        if let Some(w) = self.waiting.take() {
            self.learn(sensor.py(), w, Some(sensor))?;
        }
        let mut sense = PySense {
            now: Some(sensor),
            left: None,
            arities: &self.arities,
            error: None,
        };
        let out = self.stepper.act(&mut sense);
        let error = sense.error.take();
        self.here = Some(sensor.clone().unbind());
        match out {
            Ok(a) => {
                self.settle(error, Ok(()))?;
                Ok(a.0)
            }
            Err(e) => self.settle(error, Err(e)).map(|()| 0),
        }
    }

    /// The outcome of the action `act` returned; `sensor` reads the state reached.
    #[pyo3(signature = (reward, terminated, truncated, sensor=None))]
    fn update(
        &mut self,
        py: Python<'_>,
        reward: f64,
        terminated: bool,
        truncated: bool,
        sensor: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        self.check_stopped()?;
        if self.waiting.is_some() || !self.stepper.acted() {
            return Err(step_error(&StepError::OutOfOrder {
                called: "update",
                expected: "act",
            }));
        }
        if !(reward.is_finite() && reward.abs() <= mdp::MAX_REWARD) {
            return Err(step_error(&StepError::Reward(reward)));
        }
        match sensor {
            Some(_) => self.learn(py, (reward, terminated, truncated), sensor),
            None if terminated => self.learn(py, (reward, terminated, truncated), None),
            None if truncated => Err(AgentError::new_err(
                "update: a truncated move needs the sensor of the state reached (the move is learned from it: the move cap does not change the target); pass sensor=",
            )),
            None => {
                self.waiting = Some((reward, terminated, truncated));
                Ok(())
            }
        }
    }

    /// The agent's generator as a `csrl.Rng`: a world that draws its starts and outcomes
    /// from it (`World.sample_start`, `World.sample`) shares the agent's one stream, in
    /// `csrl.run`'s order.
    #[getter]
    fn rng(slf: Py<Self>) -> crate::rng::PyRng {
        crate::rng::PyRng::borrowed(Box::new(AgentRng(slf)))
    }

    /// Trials started.
    #[getter]
    fn trials(&self) -> u32 {
        self.stepper.trials()
    }

    /// Moves learned from (an update waiting for its sensor is not yet one).
    #[getter]
    fn moves(&self) -> u64 {
        self.stepper.moves()
    }

    /// Sensing cost charged so far.
    #[getter]
    fn sensing_cost(&self) -> f64 {
        self.stepper.cost()
    }

    /// `"left"` or `"next"`.
    #[getter]
    fn refine_from(&self) -> &'static str {
        match self.stepper.refine_from() {
            csql::RefineFrom::StateLeft => "left",
            csql::RefineFrom::NextSensed => "next",
        }
    }

    /// The descriptions, in id order: `(feature, value)` pairs, in the order added.
    fn descriptions(&self) -> Vec<Vec<(u32, u32)>> {
        self.stepper.descriptions()
    }

    /// Q of every description, one row each.
    fn q_table(&self) -> Vec<Vec<f64>> {
        let t = self.stepper.table();
        (0..t.rows())
            .map(|r| t.q_row(qlearn::RowId(r as u32)).to_vec())
            .collect()
    }

    /// V of every description.
    fn values(&self) -> Vec<f64> {
        self.stepper.table().v_values().to_vec()
    }

    /// The greedy action of every description (the lowest among ties).
    fn policy(&self) -> Vec<u32> {
        let t = self.stepper.table();
        (0..t.rows())
            .map(|r| t.greedy(qlearn::RowId(r as u32)).0)
            .collect()
    }

    /// The last trial that ended, or the one in progress: `(trial, moves, reached_goal,
    /// cost, decreases, refinements, resets)`.
    #[pyo3(signature = (current=false))]
    fn trial(&self, current: bool) -> Option<(u32, u32, bool, f64, u32, u32, u32)> {
        let t = if current {
            self.stepper.current_trial()
        } else {
            self.stepper.last_trial()
        }?;
        Some((
            t.trial,
            t.moves,
            t.reached_goal,
            t.cost,
            t.decreases,
            t.refinements,
            t.resets,
        ))
    }
}

/// An agent lending its generator to a `csrl.Rng`.
struct AgentRng(Py<PyAgent>);

impl crate::rng::Lender for AgentRng {
    fn lend(
        &self,
        py: Python<'_>,
        draw: &mut dyn FnMut(&mut rand_xoshiro::Xoshiro256PlusPlus),
    ) -> PyResult<()> {
        draw(self.0.bind(py).try_borrow_mut()?.stepper.rng());
        Ok(())
    }
}
