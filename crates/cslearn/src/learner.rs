//! The incremental learner: the paper's Figure 2 cycle over the five functions.

use rand::Rng;
use serde::Serialize;

use crate::attend::{Attend, Attention, ObservationAttending, RankedAttending};
use crate::discriminate::{CheapestFirst, Discriminate, RandomOrder};
use crate::example::Library;
use crate::predict::{Decision, Nearest, Predict, Unanimous, Votes};
use crate::select::{InfoCost, MissingRule, Select};
use crate::sensing::{Ledger, Probe, Sensor};
use crate::types::{ClassId, Cost, FeatureCosts, FeatureId};
use crate::update::{AppendAll, Update};

/// The result of classifying one object: the class (none if nothing could be predicted)
/// and the cost charged for it.
///
/// ```
/// let c = cslearn::Classified { class: None, cost: cslearn::Cost::ZERO };
/// assert!(c.class.is_none());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Classified {
    /// The predicted class.
    pub class: Option<ClassId>,
    /// What the measurements cost.
    pub cost: Cost,
}

/// The result of learning one object.
///
/// ```
/// use cslearn::{ClassId, Cost, Outcome};
/// let o = Outcome { predicted: Some(ClassId(1)), class: ClassId(1), cost: Cost::ONE, measured: 1 };
/// assert!(o.correct());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Outcome {
    /// The class predicted before the true class was given (none for an empty library).
    pub predicted: Option<ClassId>,
    /// The true class.
    pub class: ClassId,
    /// Everything charged for this object, discrimination included.
    pub cost: Cost,
    /// The number of features measured on it.
    pub measured: usize,
}

impl Outcome {
    /// Whether the prediction was right.
    ///
    /// ```
    /// use cslearn::{ClassId, Cost, Outcome};
    /// let o = Outcome { predicted: None, class: ClassId(0), cost: Cost::ZERO, measured: 0 };
    /// assert!(!o.correct());
    /// ```
    pub fn correct(&self) -> bool {
        self.predicted == Some(self.class)
    }
}

/// What streaming a sequence of objects through a learner gave.
///
/// ```
/// let r = cslearn::StreamReport::default();
/// assert_eq!(r.objects, 0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct StreamReport {
    /// Objects seen.
    pub objects: usize,
    /// Wrong predictions (an object for which nothing could be predicted counts as one).
    pub errors: usize,
    /// The share of right predictions (0 for no objects).
    pub accuracy: f64,
    /// Everything charged.
    pub total_cost: f64,
    /// `total_cost` per object (0 for no objects).
    pub mean_cost: f64,
    /// The cost of measuring every feature of one object.
    pub full_cost: f64,
}

/// An incremental cost-sensitive learner: the five functions of the paper's Figure 2,
/// run for each new object.
///
/// [`learn`](Learner::learn) runs the whole cycle: attend, select, measure (charged) until
/// the prediction function settles; compare with the true class; on an error,
/// discriminate; update the library. [`classify`](Learner::classify) runs only the first
/// part. [`cs_id3`], [`cs_ibl`] and [`id3`] build the paper's instantiations.
///
/// The learner owns the price list (charging every measurement), the library, and
/// buffers reused from object to object, so classifying allocates nothing per
/// measurement once warm.
///
/// ```
/// use cslearn::{ClassId, FeatureCosts, Value};
/// let costs = FeatureCosts::from_f64(&[1.0, 50.0]).unwrap();
/// let mut learner = cslearn::cs_id3(costs);
/// // The class is feature 0; feature 1 is expensive noise.
/// let objects = [[Some(Value(0)), Some(Value(5))], [Some(Value(1)), Some(Value(6))]];
/// for round in 0..3 {
///     for (i, object) in objects.iter().enumerate() {
///         let outcome = learner.learn(&object[..], ClassId(i as u32));
///         if round > 0 {
///             assert!(outcome.correct());
///             assert_eq!(outcome.cost.get(), 1.0); // only the cheap feature
///         }
///     }
/// }
/// ```
#[derive(Clone, Debug)]
pub struct Learner<A, S, P, D, U> {
    costs: FeatureCosts,
    library: Library,
    attend: A,
    select: S,
    predict: P,
    discriminate: D,
    update: U,
    attention: Attention,
    conflicting: Attention,
    ledger: Ledger,
    recheck: bool,
}

/// CS-ID3 (specification §2): observation attending, I^2/C selection with the own-branch rule,
/// unanimous prediction, cheapest-first discrimination, every example kept.
pub type CsId3 = Learner<ObservationAttending, InfoCost, Unanimous, CheapestFirst, AppendAll>;

/// CS-IBL: ranked attending with a mismatch tolerance, I^2/C selection over the attended
/// instances, nearest-instance prediction, cheapest-first discrimination.
pub type CsIbl = Learner<RankedAttending, InfoCost, Nearest, CheapestFirst, AppendAll>;

/// Cost-blind ID3, the baseline (specification §2): CS-ID3 with every cost taken as equal in
/// selection and discrimination in a seeded random order. Real costs are still charged.
pub type Id3<R> = Learner<ObservationAttending, InfoCost, Unanimous, RandomOrder<R>, AppendAll>;

/// CS-ID3 over the features priced by `costs`.
///
/// ```
/// let learner = cslearn::cs_id3(cslearn::FeatureCosts::from_f64(&[1.0]).unwrap());
/// assert!(learner.library().is_empty());
/// ```
pub fn cs_id3(costs: FeatureCosts) -> CsId3 {
    Learner::new(
        costs,
        ObservationAttending,
        InfoCost::new(MissingRule::OwnBranch),
        Unanimous::default(),
        CheapestFirst,
        AppendAll,
    )
}

/// CS-IBL over the features priced by `costs`, tolerating up to `tolerance` wrong values
/// on an object. With `tolerance` 0 it attends as CS-ID3 does.
///
/// ```
/// let learner = cslearn::cs_ibl(cslearn::FeatureCosts::from_f64(&[1.0]).unwrap(), 1);
/// assert!(learner.library().is_empty());
/// ```
pub fn cs_ibl(costs: FeatureCosts, tolerance: u32) -> CsIbl {
    Learner::new(
        costs,
        RankedAttending { tolerance },
        InfoCost::new(MissingRule::OwnBranch),
        Nearest::default(),
        CheapestFirst,
        AppendAll,
    )
}

/// Cost-blind ID3 over the features priced by `costs`, drawing its discrimination orders
/// from `rng`.
///
/// ```
/// use rand::SeedableRng;
/// let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// let learner = cslearn::id3(cslearn::FeatureCosts::from_f64(&[1.0]).unwrap(), rng);
/// assert!(learner.library().is_empty());
/// ```
pub fn id3<R: Rng>(costs: FeatureCosts, rng: R) -> Id3<R> {
    Learner::new(
        costs,
        ObservationAttending,
        InfoCost::new(MissingRule::OwnBranch).cost_blind(),
        Unanimous::default(),
        RandomOrder::new(rng),
        AppendAll,
    )
}

impl<A, S, P, D, U> Learner<A, S, P, D, U>
where
    A: Attend,
    S: Select,
    P: Predict,
    D: Discriminate,
    U: Update,
{
    /// A learner with an empty library from the price list and the five functions.
    ///
    /// ```
    /// use cslearn::*;
    /// let learner = Learner::new(
    ///     FeatureCosts::from_f64(&[1.0, 2.0]).unwrap(),
    ///     RuleAttending,
    ///     InfoCost::new(MissingRule::C45),
    ///     Unanimous::default(),
    ///     CheapestFirst,
    ///     AppendErrors,
    /// );
    /// assert_eq!(learner.costs().len(), 2);
    /// ```
    pub fn new(
        costs: FeatureCosts,
        attend: A,
        select: S,
        predict: P,
        discriminate: D,
        update: U,
    ) -> Self {
        Learner {
            costs,
            library: Library::new(),
            attend,
            select,
            predict,
            discriminate,
            update,
            attention: Attention::new(),
            conflicting: Attention::new(),
            ledger: Ledger::default(),
            recheck: true,
        }
    }

    /// Predict the class of the object behind `sensor`, measuring (and charging) what the
    /// five functions ask for; the library is not changed. The measurements stay in
    /// [`ledger`](Learner::ledger) until the next object.
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, Value};
    /// let mut learner = cslearn::cs_id3(FeatureCosts::from_f64(&[1.0]).unwrap());
    /// assert_eq!(learner.classify(&[Some(Value(0))][..]).class, None); // nothing learned yet
    /// learner.learn(&[Some(Value(0))][..], ClassId(4));
    /// assert_eq!(learner.classify(&[Some(Value(0))][..]).class, Some(ClassId(4)));
    /// ```
    pub fn classify<T: Sensor>(&mut self, sensor: T) -> Classified {
        let class = self.run(sensor, None);
        Classified {
            class,
            cost: self.ledger.cost(),
        }
    }

    /// [`classify`](Learner::classify), with the examples the prediction went by counted
    /// by class ([`Predict::votes`]): for CS-ID3 the examples attended when it
    /// predicted, for CS-IBL the attended ones when they agree and the nearest ones
    /// otherwise. [`Votes::probabilities`] makes a distribution of them. The
    /// classification is the one `classify` makes, charges included.
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, Value};
    /// let mut learner = cslearn::cs_ibl(FeatureCosts::from_f64(&[1.0]).unwrap(), 0);
    /// for class in [0, 1, 1] {
    ///     learner.learn(&[Some(Value(class))][..], ClassId(class));
    /// }
    /// let (answer, votes) = learner.classify_with_votes(&[Some(Value(1))][..]);
    /// assert_eq!(answer.class, Some(ClassId(1)));
    /// assert_eq!(votes.count(ClassId(1)), votes.total());
    /// ```
    pub fn classify_with_votes<T: Sensor>(&mut self, sensor: T) -> (Classified, Votes) {
        let classified = self.classify(sensor);
        let votes = self.predict.votes(&self.library, &self.attention);
        (classified, votes)
    }

    /// Learn from one object whose true class is `class`: predict it (charged), then
    /// discriminate if the prediction was wrong, then update the library.
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, FeatureId, Value};
    /// let mut learner = cslearn::cs_id3(FeatureCosts::from_f64(&[1.0, 2.0]).unwrap());
    /// let first = learner.learn(&[Some(Value(0)), Some(Value(0))][..], ClassId(0));
    /// assert_eq!(first.predicted, None);
    /// let second = learner.learn(&[Some(Value(1)), Some(Value(0))][..], ClassId(1));
    /// assert_eq!(second.predicted, Some(ClassId(0)));
    /// // Discrimination measured the cheapest feature, which tells the two apart.
    /// assert_eq!(learner.library()[1].pairs(), &[(FeatureId(0), Value(1))]);
    /// ```
    pub fn learn<T: Sensor>(&mut self, sensor: T, class: ClassId) -> Outcome {
        let predicted = self.run(sensor, Some(class));
        Outcome {
            predicted,
            class,
            cost: self.ledger.cost(),
            measured: self.ledger.measured().len(),
        }
    }

    /// Learn from each (object, true class) in turn and report the errors and costs.
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, Value};
    /// let mut learner = cslearn::cs_id3(FeatureCosts::from_f64(&[1.0]).unwrap());
    /// let rows = [[Some(Value(0))], [Some(Value(0))]];
    /// let report = learner.stream(rows.iter().map(|r| (&r[..], ClassId(0))));
    /// assert_eq!((report.objects, report.errors), (2, 1));
    /// assert_eq!(report.full_cost, 1.0);
    /// ```
    pub fn stream<T: Sensor>(
        &mut self,
        objects: impl IntoIterator<Item = (T, ClassId)>,
    ) -> StreamReport {
        let full_cost = self.costs.total().get();
        stream_report(
            full_cost,
            objects.into_iter().map(|(o, c)| self.learn(o, c)),
        )
    }

    /// The cycle for one object; `label` is `Some` when learning.
    fn run<T: Sensor>(&mut self, sensor: T, label: Option<ClassId>) -> Option<ClassId> {
        let Learner {
            costs,
            library,
            attend,
            select,
            predict,
            discriminate,
            update,
            attention,
            conflicting,
            ledger,
            recheck,
        } = self;
        ledger.clear();
        let mut probe = Probe::new(sensor, &*costs, ledger);
        let mut parts = Parts {
            library,
            attend,
            select,
            predict,
            discriminate,
            attention,
            conflicting,
        };
        let predicted = parts.predict(&mut probe);
        let Some(label) = label else {
            return predicted;
        };
        // Step 2: verify. Step 3: discriminate from the examples that misled.
        let correct = predicted == Some(label);
        if !correct {
            parts.discriminate(&mut probe, label);
        }
        // Step 4: update.
        let stored = update.update(parts.library, probe.ledger().to_example(label), correct);
        if let Some(index) = stored.filter(|_| *recheck) {
            // Check that the object is now recognised, and discriminate again if not. Each
            // round either ends the check or pays for at least one more feature, so it
            // ends after at most one round per feature.
            for _ in 0..=costs.len() {
                let paid = probe.ledger().measured().len();
                probe.ledger_mut().start_pass();
                let again = parts.predict(&mut probe);
                if again != Some(label) {
                    parts.discriminate(&mut probe, label);
                }
                if let Some(example) = parts.library.get_mut(index) {
                    *example = probe.ledger().to_example(label);
                }
                // A round that paid for more has changed the example, and with it what the
                // library predicts: check again.
                if probe.ledger().measured().len() == paid {
                    break;
                }
            }
        }
        predicted
    }

    /// Whether the learner checks, after learning an object, that the object is now
    /// recognised (on by default; see [`recheck`](Learner::recheck)).
    ///
    /// ```
    /// let learner = cslearn::cs_id3(cslearn::FeatureCosts::new(Vec::new()));
    /// assert!(learner.rechecks());
    /// ```
    pub fn rechecks(&self) -> bool {
        self.recheck
    }

    /// Turn the recheck after learning on or off.
    ///
    /// With the recheck on, after the library is updated the learner classifies the
    /// object again (values already paid for are free) and, if it is not recognised,
    /// discriminates again against the examples that misled it and refines the new
    /// example, until a check pays for nothing new (a check that measured more has changed
    /// the example, so it is checked again): the object is then recognised, or nothing
    /// more can be measured. On noiseless,
    /// non-contradictory data this guarantees that an object just learned is classified
    /// correctly when it comes again; without it, the greedy selection can, rarely, prefer
    /// a feature the new example lacks once that example is in the library. On the heart
    /// data it costs almost nothing (see the crate docs).
    ///
    /// ```
    /// let learner = cslearn::cs_id3(cslearn::FeatureCosts::new(Vec::new())).recheck(false);
    /// assert!(!learner.rechecks());
    /// ```
    pub fn recheck(mut self, on: bool) -> Self {
        self.recheck = on;
        self
    }

    /// The example library.
    ///
    /// ```
    /// let learner = cslearn::cs_id3(cslearn::FeatureCosts::new(Vec::new()));
    /// assert!(learner.library().is_empty());
    /// ```
    pub fn library(&self) -> &Library {
        &self.library
    }

    /// The example library, to seed it with known examples or change it.
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureCosts};
    /// let mut learner = cslearn::cs_id3(FeatureCosts::new(Vec::new()));
    /// learner.library_mut().push(Example::new(ClassId(2)));
    /// assert_eq!(learner.classify(&[][..]).class, Some(ClassId(2)));
    /// ```
    pub fn library_mut(&mut self) -> &mut Library {
        &mut self.library
    }

    /// The price list charged.
    ///
    /// ```
    /// let learner = cslearn::cs_id3(cslearn::FeatureCosts::from_f64(&[3.0]).unwrap());
    /// assert_eq!(learner.costs().total().get(), 3.0);
    /// ```
    pub fn costs(&self) -> &FeatureCosts {
        &self.costs
    }

    /// Add a new feature (no closed world): from now on it can be measured and charged.
    ///
    /// ```
    /// let mut learner = cslearn::cs_id3(cslearn::FeatureCosts::new(Vec::new()));
    /// let f = learner.add_feature(cslearn::Cost::ONE);
    /// assert_eq!(f, cslearn::FeatureId(0));
    /// ```
    pub fn add_feature(&mut self, cost: Cost) -> FeatureId {
        self.costs.push(cost)
    }

    /// What was measured on the last object, and what it cost.
    ///
    /// ```
    /// use cslearn::{ClassId, FeatureCosts, Value};
    /// let mut learner = cslearn::cs_id3(FeatureCosts::from_f64(&[2.0]).unwrap());
    /// learner.learn(&[Some(Value(0))][..], ClassId(0));
    /// learner.learn(&[Some(Value(1))][..], ClassId(1));
    /// assert_eq!(learner.ledger().cost().get(), 2.0);
    /// ```
    pub fn ledger(&self) -> &Ledger {
        &self.ledger
    }
}

/// The parts one pass over an object needs, borrowed from the learner.
struct Parts<'a, A, S, P, D> {
    library: &'a mut Library,
    attend: &'a A,
    select: &'a mut S,
    predict: &'a mut P,
    discriminate: &'a mut D,
    attention: &'a mut Attention,
    conflicting: &'a mut Attention,
}

impl<A: Attend, S: Select, P: Predict, D: Discriminate> Parts<'_, A, S, P, D> {
    /// Figure 2, step 1: attend, select, measure, until a class can be predicted.
    fn predict<T: Sensor>(&mut self, probe: &mut Probe<'_, T>) -> Option<ClassId> {
        let library = &*self.library;
        self.attend.start(library, self.attention);
        let decision = loop {
            match self.predict.predict(library, self.attention, false) {
                Decision::Measure => {}
                settled => break settled,
            }
            let next = self
                .select
                .select(library, self.attention, probe.ledger(), probe.costs())
                // A selection that repeats itself would never end; treat it as exhausted.
                .filter(|&f| !probe.ledger().consulted(f));
            let Some(feature) = next else {
                break self.predict.predict(library, self.attention, true);
            };
            let value = probe.measure(feature);
            self.attend.attend(library, feature, value, self.attention);
        };
        match decision {
            Decision::Predict(c) => Some(c),
            Decision::Measure | Decision::Abstain => None,
        }
    }

    /// Figure 2, step 3: the conflicting examples are the attended ones of another class
    /// than `label` at the moment of prediction.
    fn discriminate<T: Sensor>(&mut self, probe: &mut Probe<'_, T>, label: ClassId) {
        let library = &*self.library;
        self.conflicting
            .copy_from(self.attention, |i| library[i].class() != label);
        self.discriminate
            .discriminate(library, self.attend, self.conflicting, probe);
    }
}

/// The report of a stream from the outcome of each object, in order: what
/// [`Learner::stream`] and the indexed learners' `stream` both return.
pub(crate) fn stream_report(
    full_cost: f64,
    outcomes: impl Iterator<Item = Outcome>,
) -> StreamReport {
    let mut report = StreamReport {
        full_cost,
        ..StreamReport::default()
    };
    let mut total = Cost::ZERO;
    for outcome in outcomes {
        report.objects += 1;
        report.errors += usize::from(!outcome.correct());
        total += outcome.cost;
    }
    report.total_cost = total.get();
    if report.objects > 0 {
        let n = report.objects as f64;
        report.accuracy = (report.objects - report.errors) as f64 / n;
        report.mean_cost = report.total_cost / n;
    }
    report
}
