//! `csrl._csrl.Rng`: the generator a world's starts and outcomes are drawn from.

use pyo3::prelude::*;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// An object that lends its generator to a [`PyRng`] for one draw (a `CsQlAgent`, whose
/// draws and the world's then come from one stream, as `csrl.run`'s do).
pub(crate) trait Lender: Send + Sync {
    /// Call `draw` once with the generator.
    fn lend(&self, py: Python<'_>, draw: &mut dyn FnMut(&mut Xoshiro256PlusPlus)) -> PyResult<()>;
}

/// Where a [`PyRng`]'s draws come from.
enum Source {
    /// A generator of its own, seeded by the caller.
    Own(Box<Xoshiro256PlusPlus>),
    /// Another object's generator.
    Borrowed(Box<dyn Lender>),
}

/// A seeded generator for `World.sample_start` and `World.sample`: `Rng(seed)` draws from
/// a generator of its own (the one a run seeds with its seed), `CsQlAgent.rng` from the
/// agent's.
#[pyclass(module = "csrl._csrl", name = "Rng")]
pub struct PyRng {
    source: Source,
}

impl PyRng {
    /// The generator another object lends (`CsQlAgent.rng`).
    pub(crate) fn borrowed(from: Box<dyn Lender>) -> PyRng {
        PyRng {
            source: Source::Borrowed(from),
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
            Source::Borrowed(from) => {
                let mut draw = Some(draw);
                let mut out = None;
                from.lend(py, &mut |rng| {
                    if let Some(d) = draw.take() {
                        out = Some(d(rng));
                    }
                })?;
                out.ok_or_else(|| {
                    pyo3::exceptions::PyRuntimeError::new_err("the generator was not lent")
                })
            }
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
        matches!(self.source, Source::Borrowed(_))
    }

    fn __repr__(&self) -> String {
        match self.source {
            Source::Own(_) => "csrl.Rng(a generator of its own)".to_string(),
            Source::Borrowed(_) => "csrl.Rng(a CsQlAgent's generator)".to_string(),
        }
    }
}
