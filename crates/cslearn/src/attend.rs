//! Example attending (Figure 2, step 1(a)): which stored examples are still relevant,
//! given the values measured on the object so far.

use crate::example::{Example, Library};
use crate::types::{FeatureId, Value};

/// What a feature that an example lacks means.
///
/// The difference matters in attending and in building trees. Library examples are
/// observations (specification §2); csql's state descriptions are rules (specification §4).
///
/// ```
/// use cslearn::{ClassId, Example, FeatureId, Semantics, Value};
/// let e = Example::new(ClassId(0)); // lacks every feature
/// assert!(!Semantics::Observation.keeps(&e, FeatureId(1), Value(2)));
/// assert!(Semantics::Rule.keeps(&e, FeatureId(1), Value(2)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Semantics {
    /// The feature was never measured, so the example cannot be said to match: an example
    /// lacking a measured feature is dropped (CS-ID3).
    Observation,
    /// The feature is "any value": a description lacking it matches every value (CS-QL).
    Rule,
}

impl Semantics {
    /// Whether `example` agrees with an object whose `feature` reads `value`.
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureId, Semantics, Value};
    /// let e = Example::from_pairs([(FeatureId(1), Value(2))], ClassId(0));
    /// assert!(Semantics::Observation.keeps(&e, FeatureId(1), Value(2)));
    /// assert!(!Semantics::Rule.keeps(&e, FeatureId(1), Value(3)));
    /// ```
    pub fn keeps(self, example: &Example, feature: FeatureId, value: Value) -> bool {
        match (self, example.get(feature)) {
            (_, Some(v)) => v == value,
            (Semantics::Observation, None) => false,
            (Semantics::Rule, None) => true,
        }
    }
}

/// The attended examples of one classification, as indices into the library, with the
/// buffers the attending functions reuse (so attending allocates nothing once warm).
///
/// Besides the attended set it remembers the last non-empty attended set (CS-ID3 predicts
/// its majority when a measurement leaves nothing attended) and, for ranking attenders,
/// each library example's number of mismatches so far.
///
/// ```
/// use cslearn::Attention;
/// let mut a = Attention::new();
/// a.attend_all(3);
/// a.retain(|i| i != 1);
/// assert_eq!(a.attended(), &[0, 2]);
/// a.retain(|_| false);
/// assert!(a.attended().is_empty());
/// assert_eq!(a.last_nonempty(), &[0, 2]);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Attention {
    attended: Vec<usize>,
    previous: Vec<usize>,
    scratch: Vec<usize>,
    mismatches: Vec<u32>,
}

impl Attention {
    /// An empty attention (nothing attended).
    ///
    /// ```
    /// assert!(cslearn::Attention::new().attended().is_empty());
    /// ```
    pub fn new() -> Attention {
        Attention::default()
    }

    /// Attend every one of `len` examples, with no mismatches and no history.
    ///
    /// ```
    /// let mut a = cslearn::Attention::new();
    /// a.attend_all(2);
    /// assert_eq!(a.attended(), &[0, 1]);
    /// assert_eq!(a.mismatches(), &[0, 0]);
    /// ```
    pub fn attend_all(&mut self, len: usize) {
        self.attended.clear();
        self.attended.extend(0..len);
        self.previous.clear();
        self.mismatches.clear();
        self.mismatches.resize(len, 0);
    }

    /// Attend exactly `indices` (ascending), with no mismatches and no history: what
    /// [`copy_from`](Attention::copy_from) leaves for observation attending, without a
    /// whole attention to copy from.
    pub(crate) fn attend_only(&mut self, indices: impl IntoIterator<Item = usize>) {
        self.attended.clear();
        self.attended.extend(indices);
        self.previous.clear();
        self.mismatches.clear();
    }

    /// The attended examples, by ascending index.
    ///
    /// ```
    /// assert!(cslearn::Attention::new().attended().is_empty());
    /// ```
    pub fn attended(&self) -> &[usize] {
        &self.attended
    }

    /// The attended examples if there are any, otherwise the last non-empty attended set.
    ///
    /// ```
    /// let mut a = cslearn::Attention::new();
    /// a.attend_all(1);
    /// assert_eq!(a.last_nonempty(), &[0]);
    /// ```
    pub fn last_nonempty(&self) -> &[usize] {
        if self.attended.is_empty() {
            &self.previous
        } else {
            &self.attended
        }
    }

    /// The number of mismatches of each library example so far (all zero unless a
    /// ranking attender such as [`RankedAttending`] counts them).
    ///
    /// ```
    /// assert!(cslearn::Attention::new().mismatches().is_empty());
    /// ```
    pub fn mismatches(&self) -> &[u32] {
        &self.mismatches
    }

    /// Keep only the attended examples for which `keep` holds. If none is kept, the set
    /// before this call becomes the last non-empty set.
    ///
    /// ```
    /// let mut a = cslearn::Attention::new();
    /// a.attend_all(4);
    /// a.retain(|i| i % 2 == 0);
    /// assert_eq!(a.attended(), &[0, 2]);
    /// ```
    pub fn retain(&mut self, mut keep: impl FnMut(usize) -> bool) {
        self.scratch.clear();
        self.scratch
            .extend(self.attended.iter().copied().filter(|&i| keep(i)));
        if self.scratch.is_empty() && !self.attended.is_empty() {
            std::mem::swap(&mut self.previous, &mut self.attended);
        }
        std::mem::swap(&mut self.attended, &mut self.scratch);
    }

    /// Become a copy of `other` restricted to the attended examples for which `keep`
    /// holds (mismatch counts are copied whole). Discrimination uses this to attend only
    /// the conflicting examples.
    ///
    /// ```
    /// let mut all = cslearn::Attention::new();
    /// all.attend_all(3);
    /// let mut some = cslearn::Attention::new();
    /// some.copy_from(&all, |i| i > 0);
    /// assert_eq!(some.attended(), &[1, 2]);
    /// ```
    pub fn copy_from(&mut self, other: &Attention, mut keep: impl FnMut(usize) -> bool) {
        self.attended.clear();
        self.attended
            .extend(other.attended.iter().copied().filter(|&i| keep(i)));
        self.previous.clear();
        self.mismatches.clone_from(&other.mismatches);
    }
}

/// Example attending: which examples stay relevant as values are measured.
///
/// | implementation | a measured value drops an example that |
/// |---|---|
/// | [`ObservationAttending`] (CS-ID3) | lacks the feature or has another value |
/// | [`RuleAttending`] (CS-QL's CLASSIFY) | has the feature with another value |
/// | [`RankedAttending`] (CS-IBL) | has more than `tolerance` mismatches so far |
///
/// In every implementation a missing value on the object drops nothing.
///
/// ```
/// use cslearn::{Attend, Attention, ClassId, Example, FeatureId, Library, ObservationAttending, Value};
/// let lib = Library::from(vec![
///     Example::from_pairs([(FeatureId(0), Value(1))], ClassId(0)),
///     Example::from_pairs([(FeatureId(0), Value(2))], ClassId(1)),
/// ]);
/// let mut a = Attention::new();
/// ObservationAttending.start(&lib, &mut a);
/// ObservationAttending.attend(&lib, FeatureId(0), Some(Value(2)), &mut a);
/// assert_eq!(a.attended(), &[1]);
/// ```
pub trait Attend {
    /// Attend the examples to consider before anything is measured.
    fn start(&self, library: &Library, attention: &mut Attention) {
        attention.attend_all(library.len());
    }

    /// Update `attention` after `feature` was measured on the object as `value`.
    fn attend(
        &self,
        library: &Library,
        feature: FeatureId,
        value: Option<Value>,
        attention: &mut Attention,
    );
}

/// CS-ID3's attending (specification §2): an example stays only if it has the measured feature with
/// the same value. See [`Semantics::Observation`].
///
/// ```
/// use cslearn::{Attend, Attention, ClassId, Example, FeatureId, Library, ObservationAttending, Value};
/// let lib = Library::from(vec![Example::new(ClassId(0))]);
/// let mut a = Attention::new();
/// ObservationAttending.start(&lib, &mut a);
/// ObservationAttending.attend(&lib, FeatureId(0), None, &mut a); // missing: keeps all
/// assert_eq!(a.attended(), &[0]);
/// ObservationAttending.attend(&lib, FeatureId(0), Some(Value(1)), &mut a);
/// assert!(a.attended().is_empty());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ObservationAttending;

/// Rule attending (specification §4, CS-QL's CLASSIFY): an example that lacks the measured feature
/// means "any value" and stays. See [`Semantics::Rule`].
///
/// ```
/// use cslearn::{Attend, Attention, ClassId, Example, FeatureId, Library, RuleAttending, Value};
/// let lib = Library::from(vec![Example::new(ClassId(0))]);
/// let mut a = Attention::new();
/// RuleAttending.start(&lib, &mut a);
/// RuleAttending.attend(&lib, FeatureId(0), Some(Value(1)), &mut a);
/// assert_eq!(a.attended(), &[0]);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RuleAttending;

fn filter(
    semantics: Semantics,
    library: &Library,
    f: FeatureId,
    v: Option<Value>,
    a: &mut Attention,
) {
    if let Some(v) = v {
        a.retain(|i| semantics.keeps(&library[i], f, v));
    }
}

impl Attend for ObservationAttending {
    fn attend(&self, library: &Library, f: FeatureId, v: Option<Value>, a: &mut Attention) {
        filter(Semantics::Observation, library, f, v, a);
    }
}

impl Attend for RuleAttending {
    fn attend(&self, library: &Library, f: FeatureId, v: Option<Value>, a: &mut Attention) {
        filter(Semantics::Rule, library, f, v, a);
    }
}

/// CS-IBL's attending: every library example is ranked by its number of mismatches on
/// the measured features (lacking a measured feature counts as a mismatch, as it drops
/// the example in CS-ID3), and the attended examples are those with at most `tolerance`
/// mismatches.
///
/// With `tolerance` 0 this attends exactly what [`ObservationAttending`] attends. With
/// `tolerance` t, an example stays attended through t wrong values on the object, which is
/// how CS-IBL tolerates noisy sensing.
///
/// ```
/// use cslearn::{Attend, Attention, ClassId, Example, FeatureId, Library, RankedAttending, Value};
/// let lib = Library::from(vec![
///     Example::from_pairs([(FeatureId(0), Value(1)), (FeatureId(1), Value(1))], ClassId(0)),
/// ]);
/// let ranked = RankedAttending { tolerance: 1 };
/// let mut a = Attention::new();
/// ranked.start(&lib, &mut a);
/// ranked.attend(&lib, FeatureId(0), Some(Value(9)), &mut a); // one wrong value: kept
/// assert_eq!(a.attended(), &[0]);
/// ranked.attend(&lib, FeatureId(1), Some(Value(9)), &mut a); // a second: dropped
/// assert!(a.attended().is_empty());
/// assert_eq!(a.mismatches(), &[2]);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RankedAttending {
    /// The most mismatches an attended example may have.
    pub tolerance: u32,
}

impl Attend for RankedAttending {
    fn attend(&self, library: &Library, f: FeatureId, v: Option<Value>, a: &mut Attention) {
        let Some(v) = v else { return };
        // Every example is counted, attended or not: the nearest examples overall are
        // the fallback when nothing is left within the tolerance.
        for (count, example) in a.mismatches.iter_mut().zip(library) {
            if !Semantics::Observation.keeps(example, f, v) {
                *count += 1;
            }
        }
        let tolerance = self.tolerance;
        // `retain` borrows the whole attention, so the counts move out while it runs.
        let counts = std::mem::take(&mut a.mismatches);
        a.retain(|i| counts[i] <= tolerance);
        a.mismatches = counts;
    }
}
