//! `csrl._csrl.Rng`: the generator a world's starts and outcomes are drawn from.

use pyo3::prelude::*;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use crate::PyAgent;

/// Where a [`PyRng`]'s draws come from.
enum Source {
    /// A generator of its own, seeded by the caller.
    Own(Box<Xoshiro256PlusPlus>),
    /// A `CsQlAgent`'s generator: the world's draws and the agent's come from one stream,
    /// as `csrl.run`'s do.
    Agent(Py<PyAgent>),
}

/// A seeded generator for `World.sample_start` and `World.sample`: `Rng(seed)` draws from
/// a generator of its own (the one a run seeds with its seed), `CsQlAgent.rng` from the
/// agent's.
#[pyclass(module = "csrl._csrl", name = "Rng")]
pub struct PyRng {
    source: Source,
}

impl PyRng {
    /// The generator of an agent (`CsQlAgent.rng`).
    pub(crate) fn of_agent(agent: Py<PyAgent>) -> PyRng {
        PyRng {
            source: Source::Agent(agent),
        }
    }

    /// Draw with `draw` from the generator.
    pub(crate) fn draw<T>(
        &mut self,
        py: Python<'_>,
        draw: impl FnOnce(&mut Xoshiro256PlusPlus) -> T,
    ) -> PyResult<T> {
        match &mut self.source {
            Source::Own(rng) => Ok(draw(rng)),
            Source::Agent(agent) => Ok(draw(agent.bind(py).try_borrow_mut()?.stepper.rng())),
        }
    }
}

#[pymethods]
impl PyRng {
    /// A generator of its own, seeded with `seed` (0 to 2**64 - 1).
    #[new]
    fn new(seed: u64) -> PyRng {
        PyRng {
            source: Source::Own(Box::new(Xoshiro256PlusPlus::seed_from_u64(seed))),
        }
    }

    /// Whether it draws from an agent's generator.
    #[getter]
    fn shared(&self) -> bool {
        matches!(self.source, Source::Agent(_))
    }

    fn __repr__(&self) -> String {
        match self.source {
            Source::Own(_) => "csrl.Rng(a generator of its own)".to_string(),
            Source::Agent(_) => "csrl.Rng(a CsQlAgent's generator)".to_string(),
        }
    }
}
