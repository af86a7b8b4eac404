//! Library updating (Figure 2, step 4): what the library keeps of the new example.

use crate::example::{Example, Library};

/// Library updating, one of the five functions.
///
/// `example` holds every value measured on the object (missing values left out) and the
/// object's true class; `correct` says whether the prediction was right. The result is
/// the index of the library example that now stands for the object, if any: the learner
/// refines that example when it checks that the object is recognised.
///
/// | implementation | keeps |
/// |---|---|
/// | [`AppendAll`] (CS-ID3, CS-IBL, ID3) | every new example |
/// | [`AppendErrors`] | only the examples whose prediction was wrong (as IB2 does) |
///
/// ```
/// use cslearn::{AppendAll, ClassId, Example, Library, Update};
/// let mut lib = Library::new();
/// assert_eq!(AppendAll.update(&mut lib, Example::new(ClassId(0)), true), Some(0));
/// assert_eq!(lib.len(), 1);
/// ```
pub trait Update {
    /// Change `library` to reflect the new example; return the index of the example
    /// that stands for the object, if one does.
    fn update(&mut self, library: &mut Library, example: Example, correct: bool) -> Option<usize>;
}

/// Keep every new example (the paper's CS-ID3: "it adds the new example to the example
/// library").
///
/// ```
/// use cslearn::{AppendAll, ClassId, Example, Library, Update};
/// let mut lib = Library::new();
/// AppendAll.update(&mut lib, Example::new(ClassId(0)), false);
/// assert_eq!(lib[0].class(), ClassId(0));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AppendAll;

impl Update for AppendAll {
    fn update(&mut self, library: &mut Library, example: Example, _correct: bool) -> Option<usize> {
        Some(library.push(example))
    }
}

/// Keep only the examples that were predicted wrongly, so the library grows with the
/// errors rather than with the stream (the IB2 policy of Aha and Kibler).
///
/// ```
/// use cslearn::{AppendErrors, ClassId, Example, Library, Update};
/// let mut lib = Library::new();
/// assert_eq!(AppendErrors.update(&mut lib, Example::new(ClassId(0)), true), None);
/// assert!(lib.is_empty());
/// AppendErrors.update(&mut lib, Example::new(ClassId(0)), false);
/// assert_eq!(lib.len(), 1);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AppendErrors;

impl Update for AppendErrors {
    fn update(&mut self, library: &mut Library, example: Example, correct: bool) -> Option<usize> {
        (!correct).then(|| library.push(example))
    }
}
