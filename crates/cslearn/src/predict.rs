//! Class prediction (Figure 2, the "until" of step 1): whether the attended examples
//! settle the object's class yet.

use crate::attend::Attention;
use crate::example::Library;
use crate::types::ClassId;

/// What a prediction function says after each measurement.
///
/// ```
/// use cslearn::{ClassId, Decision};
/// assert_ne!(Decision::Predict(ClassId(1)), Decision::Measure);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Decision {
    /// Not settled: measure another feature.
    Measure,
    /// The class to predict.
    Predict(ClassId),
    /// Nothing to go by (an empty library): no class can be predicted.
    Abstain,
}

/// Class prediction, one of the five functions.
///
/// `exhausted` says that no feature is left to measure, so the function must decide now;
/// [`Decision::Measure`] is then read as [`Decision::Abstain`].
///
/// | implementation | predicts when |
/// |---|---|
/// | [`Unanimous`] (CS-ID3) | all attended examples share a class; their majority when exhausted; the majority of the last non-empty attended set when none is left |
/// | [`Nearest`] (CS-IBL) | all attended examples share a class; else the majority of the fewest-mismatch examples when exhausted or when none is attended |
///
/// Majority ties go to the lowest [`ClassId`].
///
/// ```
/// use cslearn::{Attend, Attention, ClassId, Decision, Example, Library, ObservationAttending, Predict, Unanimous};
/// let lib = Library::from(vec![Example::new(ClassId(2)), Example::new(ClassId(2))]);
/// let mut a = Attention::new();
/// ObservationAttending.start(&lib, &mut a);
/// assert_eq!(Unanimous::default().predict(&lib, &a, false), Decision::Predict(ClassId(2)));
/// ```
pub trait Predict {
    /// The decision for the current attention.
    fn predict(&mut self, library: &Library, attention: &Attention, exhausted: bool) -> Decision;

    /// The classes of the examples a decision for `attention` went by, counted: what
    /// [`Learner::classify_with_votes`](crate::Learner::classify_with_votes) reads a
    /// distribution from. By default the attended examples, or the last non-empty
    /// attended set when none is attended ([`Unanimous`]'s rule); a prediction function
    /// that decides from other examples says which.
    ///
    /// ```
    /// use cslearn::{Attend, Attention, ClassId, Example, Library, ObservationAttending, Predict, Unanimous};
    /// let lib = Library::from(vec![Example::new(ClassId(0)), Example::new(ClassId(1)), Example::new(ClassId(1))]);
    /// let mut a = Attention::new();
    /// ObservationAttending.start(&lib, &mut a);
    /// let votes = Unanimous::default().votes(&lib, &a);
    /// assert_eq!((votes.count(ClassId(0)), votes.count(ClassId(1))), (1, 2));
    /// ```
    fn votes(&mut self, library: &Library, attention: &Attention) -> Votes {
        Votes::of(
            attention
                .last_nonempty()
                .iter()
                .map(|&i| library[i].class()),
        )
    }
}

/// The stored examples a prediction went by, counted by class: the distribution an
/// incremental learner's answer comes from.
///
/// [`probabilities`](Votes::probabilities) smooths the counts by Laplace's rule, as the
/// test-cost trees smooth their leaves' weights: one added to each class's count, then
/// normalised; so a prediction settled by one example is not a certainty, and one
/// settled by no example (an empty library) is uniform. CS-ID3 predicts the majority of
/// its votes (their one class when they agree) and CS-IBL the majority of its nearest
/// examples, which are its votes when they disagree; so the class predicted is a class of
/// largest probability, up to ties.
///
/// ```
/// use cslearn::{ClassId, Votes};
/// let votes = Votes::of([ClassId(1), ClassId(1), ClassId(1)]);
/// assert_eq!(votes.total(), 3);
/// // (0 + 1) / (3 + 3), (3 + 1) / (3 + 3), (0 + 1) / (3 + 3) over three classes.
/// let p = votes.probabilities(3);
/// assert!((p[1] - 4.0 / 6.0).abs() < 1e-15 && (p[0] - 1.0 / 6.0).abs() < 1e-15);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Votes {
    /// Examples per class id.
    counts: Vec<u32>,
}

impl Votes {
    /// The votes of examples of these classes.
    ///
    /// ```
    /// let votes = cslearn::Votes::of([cslearn::ClassId(2)]);
    /// assert_eq!(votes.count(cslearn::ClassId(2)), 1);
    /// ```
    pub fn of(classes: impl IntoIterator<Item = ClassId>) -> Votes {
        let mut counts: Vec<u32> = Vec::new();
        for class in classes {
            let c = class.0 as usize;
            if counts.len() <= c {
                counts.resize(c + 1, 0);
            }
            counts[c] += 1;
        }
        Votes { counts }
    }

    /// The examples of `class` among the votes.
    ///
    /// ```
    /// assert_eq!(cslearn::Votes::default().count(cslearn::ClassId(0)), 0);
    /// ```
    pub fn count(&self, class: ClassId) -> u32 {
        self.counts.get(class.0 as usize).copied().unwrap_or(0)
    }

    /// The number of examples voting.
    ///
    /// ```
    /// assert_eq!(cslearn::Votes::default().total(), 0);
    /// ```
    pub fn total(&self) -> u32 {
        self.counts.iter().sum()
    }

    /// The probability of each class `0..classes` (more if a vote is for a higher class
    /// id), by Laplace's rule: `(count + 1) / (total + number of classes)`.
    ///
    /// ```
    /// assert_eq!(cslearn::Votes::default().probabilities(2), vec![0.5, 0.5]);
    /// ```
    pub fn probabilities(&self, classes: usize) -> Vec<f64> {
        let k = classes.max(self.counts.len());
        let total = f64::from(self.total()) + k as f64;
        (0..k)
            .map(|c| (f64::from(self.counts.get(c).copied().unwrap_or(0)) + 1.0) / total)
            .collect()
    }
}

/// Counts classes with a reusable buffer.
#[derive(Clone, Debug, Default)]
struct Tally {
    classes: Vec<ClassId>,
}

impl Tally {
    /// The most frequent class, ties to the lowest id; `None` for no examples.
    fn majority(&mut self, classes: impl Iterator<Item = ClassId>) -> Option<ClassId> {
        self.classes.clear();
        self.classes.extend(classes);
        self.classes.sort_unstable();
        let mut best: Option<(usize, ClassId)> = None;
        for run in self.classes.chunk_by(|a, b| a == b) {
            // Strictly more only: a later (higher) class never wins a tie.
            if best.is_none_or(|(n, _)| run.len() > n) {
                best = Some((run.len(), run[0]));
            }
        }
        best.map(|(_, c)| c)
    }
}

/// The shared class if every example has the same one.
fn unanimous(mut classes: impl Iterator<Item = ClassId>) -> Option<ClassId> {
    let first = classes.next()?;
    classes.all(|c| c == first).then_some(first)
}

/// CS-ID3's prediction (specification §2): the class of the attended examples once they agree;
/// their majority when no feature is left; the majority of the last non-empty attended
/// set when a measurement leaves none attended.
///
/// ```
/// use cslearn::{Attend, Attention, ClassId, Decision, Example, Library, ObservationAttending, Predict, Unanimous};
/// let lib = Library::from(vec![Example::new(ClassId(0)), Example::new(ClassId(1)), Example::new(ClassId(1))]);
/// let mut a = Attention::new();
/// ObservationAttending.start(&lib, &mut a);
/// let mut p = Unanimous::default();
/// assert_eq!(p.predict(&lib, &a, false), Decision::Measure);
/// assert_eq!(p.predict(&lib, &a, true), Decision::Predict(ClassId(1)));
/// a.retain(|_| false);
/// assert_eq!(p.predict(&lib, &a, false), Decision::Predict(ClassId(1)));
/// ```
#[derive(Clone, Debug, Default)]
pub struct Unanimous {
    tally: Tally,
}

impl Predict for Unanimous {
    fn predict(&mut self, library: &Library, attention: &Attention, exhausted: bool) -> Decision {
        let class_of = |&i: &usize| library[i].class();
        let attended = attention.attended();
        if attended.is_empty() {
            return self
                .tally
                .majority(attention.last_nonempty().iter().map(class_of))
                .map_or(Decision::Abstain, Decision::Predict);
        }
        if let Some(c) = unanimous(attended.iter().map(class_of)) {
            Decision::Predict(c)
        } else if exhausted {
            self.tally
                .majority(attended.iter().map(class_of))
                .map_or(Decision::Abstain, Decision::Predict)
        } else {
            Decision::Measure
        }
    }
}

/// CS-IBL's prediction: the class of the attended examples (those within the tolerance)
/// once they agree; otherwise, when no feature is left or none is attended, the majority
/// class of the nearest examples (the fewest mismatches among the attended ones, or among
/// the whole library when none is attended).
///
/// ```
/// use cslearn::{Attend, Attention, ClassId, Decision, Example, FeatureId, Library};
/// use cslearn::{Nearest, Predict, RankedAttending, Value};
/// let lib = Library::from(vec![
///     Example::from_pairs([(FeatureId(0), Value(0))], ClassId(0)),
///     Example::from_pairs([(FeatureId(0), Value(1))], ClassId(1)),
/// ]);
/// let ranked = RankedAttending { tolerance: 1 };
/// let mut a = Attention::new();
/// ranked.start(&lib, &mut a);
/// ranked.attend(&lib, FeatureId(0), Some(Value(1)), &mut a);
/// // Both are within one mismatch; the one with none is nearest.
/// assert_eq!(Nearest::default().predict(&lib, &a, true), Decision::Predict(ClassId(1)));
/// ```
#[derive(Clone, Debug, Default)]
pub struct Nearest {
    tally: Tally,
}

impl Nearest {
    fn nearest(&mut self, library: &Library, attention: &Attention, pool: &[usize]) -> Decision {
        let counts = attention.mismatches();
        let distance = |i: usize| counts.get(i).copied().unwrap_or(0);
        let all = 0..library.len();
        let min = if pool.is_empty() {
            all.clone().map(distance).min()
        } else {
            pool.iter().map(|&i| distance(i)).min()
        };
        let Some(min) = min else {
            return Decision::Abstain;
        };
        let class_of = |i: usize| library[i].class();
        let majority = if pool.is_empty() {
            self.tally
                .majority(all.filter(|&i| distance(i) == min).map(class_of))
        } else {
            self.tally.majority(
                pool.iter()
                    .copied()
                    .filter(|&i| distance(i) == min)
                    .map(class_of),
            )
        };
        majority.map_or(Decision::Abstain, Decision::Predict)
    }
}

impl Nearest {
    /// The nearest examples of `pool` (of the whole library when it is empty): those of
    /// fewest mismatches.
    fn nearest_of<'a>(
        library: &'a Library,
        attention: &'a Attention,
        pool: &'a [usize],
    ) -> impl Iterator<Item = usize> + 'a {
        let counts = attention.mismatches();
        let distance = move |i: usize| counts.get(i).copied().unwrap_or(0);
        let all: Vec<usize> = if pool.is_empty() {
            (0..library.len()).collect()
        } else {
            pool.to_vec()
        };
        let min = all.iter().map(|&i| distance(i)).min();
        all.into_iter().filter(move |&i| Some(distance(i)) == min)
    }
}

impl Predict for Nearest {
    /// The attended examples when they agree (what settled the class); otherwise the
    /// nearest ones, whose majority is the answer.
    fn votes(&mut self, library: &Library, attention: &Attention) -> Votes {
        let attended = attention.attended();
        let class_of = |i: usize| library[i].class();
        if !attended.is_empty() && unanimous(attended.iter().map(|&i| class_of(i))).is_some() {
            return Votes::of(attended.iter().map(|&i| class_of(i)));
        }
        Votes::of(Nearest::nearest_of(library, attention, attended).map(class_of))
    }

    fn predict(&mut self, library: &Library, attention: &Attention, exhausted: bool) -> Decision {
        let attended = attention.attended();
        if attended.is_empty() {
            return self.nearest(library, attention, &[]);
        }
        if let Some(c) = unanimous(attended.iter().map(|&i| library[i].class())) {
            Decision::Predict(c)
        } else if exhausted {
            self.nearest(library, attention, attended)
        } else {
            Decision::Measure
        }
    }
}
