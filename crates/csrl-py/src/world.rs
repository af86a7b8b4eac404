//! `csrl._csrl.World`: a finite world with priced features.

use std::path::PathBuf;

use mdp::{FiniteWorld, Sensors, StochasticMdp, World as _};
use pyo3::prelude::*;

use crate::rng::PyRng;
use crate::{run_error, world_error};

/// A finite world with priced features (a `csrl-world` world file in memory).
#[pyclass(frozen, module = "csrl._csrl", name = "World")]
pub struct PyWorld {
    pub(crate) world: FiniteWorld,
}

#[pymethods]
impl PyWorld {
    /// A world by name as `csrl run --world` resolves it (a built-in world, a built-in
    /// map, a map or world file, `random:...`), with `settings` the text of a TOML
    /// settings file whose `[world]` table sets its options. A grid map becomes the
    /// finite world `csrl world export` writes.
    #[staticmethod]
    #[pyo3(signature = (name, settings=None))]
    fn load(name: &str, settings: Option<&str>) -> PyResult<PyWorld> {
        let mut s = csql::RunSettings::tan1991(name, csql::StrategyKind::Lazy, 1);
        if let Some(text) = settings {
            s.apply_toml(text, "world options")
                .map_err(|e| run_error(&e))?;
            s.map = name.into();
        }
        let world = match csql::Resolved::new(&s).map_err(|e| run_error(&e))? {
            csql::Resolved::Grid(setup) => FiniteWorld::from_grid(&setup.sensed(&s)),
            csql::Resolved::Finite { world, .. } => world,
        };
        Ok(PyWorld { world })
    }

    /// A world from the JSON text of a world file (format `csrl-world`, version 1).
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<PyWorld> {
        let world = FiniteWorld::from_json(text).map_err(|e| world_error(&e))?;
        Ok(PyWorld { world })
    }

    /// A world from a world file.
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<PyWorld> {
        let world = FiniteWorld::read(&path).map_err(|e| world_error(&e))?;
        Ok(PyWorld { world })
    }

    /// The world as the JSON text of a world file.
    fn to_json(&self) -> String {
        self.world.to_json()
    }

    /// The world's name.
    #[getter]
    fn name(&self) -> String {
        self.world.name().to_string()
    }

    /// The number of states (terminal ones included).
    #[getter]
    fn num_states(&self) -> usize {
        self.world.num_states()
    }

    /// The number of actions.
    #[getter]
    fn num_actions(&self) -> usize {
        self.world.num_actions()
    }

    /// The number of features.
    #[getter]
    fn num_features(&self) -> usize {
        self.world.num_features()
    }

    /// The non-terminal states a trial can reach, in id order.
    fn states(&self) -> Vec<u32> {
        self.world.states().into_iter().map(|s| s.0).collect()
    }

    /// Whether each state is terminal.
    fn terminal(&self) -> Vec<bool> {
        (0..self.world.num_states() as u32)
            .map(|s| self.world.is_terminal(mdp::StateId(s)))
            .collect()
    }

    /// The features' names, cheapest first.
    fn feature_names(&self) -> Vec<String> {
        (0..self.world.num_features() as u32)
            .map(|f| self.world.feature_name(mdp::Feature(f)))
            .collect()
    }

    /// The features' prices, cheapest first.
    fn prices(&self) -> Vec<f64> {
        (0..self.world.num_features() as u32)
            .map(|f| self.world.price(mdp::Feature(f)))
            .collect()
    }

    /// How many readings each feature has.
    fn arities(&self) -> Vec<u32> {
        (0..self.world.num_features() as u32)
            .map(|f| self.world.readings(mdp::Feature(f)))
            .collect()
    }

    /// The actions' names.
    fn action_names(&self) -> Vec<String> {
        (0..self.world.num_actions() as u32)
            .map(|a| self.world.action_name(mdp::ActionId(a)))
            .collect()
    }

    /// The states' labels.
    fn state_labels(&self) -> Vec<String> {
        (0..self.world.num_states() as u32)
            .map(|s| self.world.state_label(mdp::StateId(s)))
            .collect()
    }

    /// What every feature reads in every state: one row per state, cheapest feature first.
    fn readings(&self) -> Vec<Vec<u32>> {
        let nf = self.world.num_features() as u32;
        (0..self.world.num_states() as u32)
            .map(|s| {
                (0..nf)
                    .map(|f| self.world.read(mdp::StateId(s), mdp::Feature(f)).0)
                    .collect()
            })
            .collect()
    }

    /// The outcomes of action `a` in state `s`: `(probability, next, reward, terminated)`.
    fn outcomes(&self, s: u32, a: u32) -> PyResult<Vec<(f64, u32, f64, bool)>> {
        if s as usize >= self.world.num_states() || a as usize >= self.world.num_actions() {
            return Err(crate::WorldError::new_err(format!(
                "state {s}, action {a}: the world has {} states and {} actions",
                self.world.num_states(),
                self.world.num_actions()
            )));
        }
        let mut out = Vec::new();
        self.world
            .outcomes(mdp::StateId(s), mdp::ActionId(a), &mut out);
        Ok(out
            .into_iter()
            .map(|(p, step)| (p, step.next.0, step.reward, step.terminated))
            .collect())
    }

    /// Where trials start: `(probability, state)` pairs.
    fn start(&self) -> Vec<(f64, u32)> {
        self.world
            .start_distribution()
            .into_iter()
            .map(|(p, s)| (p, s.0))
            .collect()
    }

    /// The optimal state values of the world at discount `gamma` (value iteration on its
    /// true model), one per state.
    fn optimal_values(&self, gamma: f64) -> PyResult<Vec<f64>> {
        let oracle =
            mdp::Oracle::solve_stochastic(&self.world, gamma).map_err(|e| world_error(&e))?;
        Ok((0..self.world.num_states() as u32)
            .map(|s| oracle.v_star(mdp::StateId(s)))
            .collect())
    }

    /// Draw a trial's start state from `rng` (a `csrl.Rng`: `Rng(seed)`, or an agent's
    /// `CsQlAgent.rng`, whose draws and the world's then come from one stream, in
    /// `csrl.run`'s order).
    fn sample_start(&self, py: Python<'_>, rng: &Bound<'_, PyRng>) -> PyResult<u32> {
        rng.try_borrow_mut()?
            .draw(py, |r| self.world.sample_start(r).0)
    }

    /// Draw an outcome of action `a` in state `s` from `rng` (see `sample_start`):
    /// `(next, reward, terminated)`.
    fn sample(
        &self,
        py: Python<'_>,
        s: u32,
        a: u32,
        rng: &Bound<'_, PyRng>,
    ) -> PyResult<(u32, f64, bool)> {
        let n = self.world.num_states();
        if s as usize >= n
            || a as usize >= self.world.num_actions()
            || self.world.is_terminal(mdp::StateId(s))
        {
            return Err(crate::WorldError::new_err(format!(
                "state {s}, action {a}: the world has {n} states (sampled only where not terminal) and {} actions",
                self.world.num_actions()
            )));
        }
        let step = rng.try_borrow_mut()?.draw(py, |r| {
            self.world.sample(mdp::StateId(s), mdp::ActionId(a), r)
        })?;
        Ok((step.next.0, step.reward, step.terminated))
    }

    fn __repr__(&self) -> String {
        format!(
            "csrl.World({:?}: {} states, {} actions, {} features)",
            self.world.name(),
            self.world.num_states(),
            self.world.num_actions(),
            self.world.num_features()
        )
    }
}
