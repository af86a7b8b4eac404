//! Example discrimination (Figure 2, step 3): after a wrong prediction, measure more of
//! the object until the new example is told apart from the examples that misled.

use rand::Rng;
use rand::seq::SliceRandom;

use crate::attend::{Attend, Attention};
use crate::example::Library;
use crate::sensing::{Probe, Sensor};
use crate::types::{FeatureCosts, FeatureId};

/// Example discrimination, one of the five functions.
///
/// `conflicting` holds the examples that contributed the error: the attended examples of
/// another class than the true one, at the moment of prediction. An implementation
/// measures unmeasured features of the object through `probe` (charged), updating
/// `conflicting` with the learner's own attending function, until no conflicting example
/// is attended any more or no feature is left. Reusing the attending function is what
/// makes "told apart" mean the same thing here as in classification.
///
/// | implementation | order of the extra measurements |
/// |---|---|
/// | [`CheapestFirst`] (CS-ID3, CS-IBL) | ascending cost, then ascending id |
/// | [`RandomOrder`] (cost-blind ID3) | a fresh seeded random order for each object |
///
/// ```
/// use cslearn::{Attend, Attention, CheapestFirst, ClassId, Discriminate, Example, FeatureCosts};
/// use cslearn::{FeatureId, Ledger, Library, ObservationAttending, Probe, Value};
/// let lib = Library::from(vec![Example::from_pairs([(FeatureId(1), Value(0))], ClassId(0))]);
/// let costs = FeatureCosts::from_f64(&[5.0, 1.0]).unwrap();
/// let object = [Some(Value(3)), Some(Value(1))];
/// let mut conflicting = Attention::new();
/// ObservationAttending.start(&lib, &mut conflicting);
/// let mut ledger = Ledger::default();
/// let mut probe = Probe::new(&object[..], &costs, &mut ledger);
/// CheapestFirst.discriminate(&lib, &ObservationAttending, &mut conflicting, &mut probe);
/// // Feature 1 is cheapest and already tells the object apart.
/// assert_eq!(ledger.measured(), &[(FeatureId(1), Some(Value(1)))]);
/// assert!(conflicting.attended().is_empty());
/// ```
pub trait Discriminate {
    /// Measure the object until the conflicting examples are no longer attended.
    fn discriminate<A: Attend + ?Sized, S: Sensor>(
        &mut self,
        library: &Library,
        attend: &A,
        conflicting: &mut Attention,
        probe: &mut Probe<'_, S>,
    );

    /// The order in which [`discriminate`](Discriminate::discriminate) measures features
    /// when something conflicts, if that order does not depend on the examples; drawn as
    /// `discriminate` would draw it (so ask only where it would measure something), and
    /// `None` (the default) otherwise. A learner that keeps counts per sequence of
    /// measurements, as the indexed ones do, then discriminates by walking down its index
    /// instead of filtering the conflicting examples one by one.
    ///
    /// ```
    /// use cslearn::{CheapestFirst, Discriminate, FeatureCosts, FeatureId};
    /// let costs = FeatureCosts::from_f64(&[5.0, 1.0]).unwrap();
    /// assert_eq!(CheapestFirst.order(&costs), Some(&[FeatureId(1), FeatureId(0)][..]));
    /// ```
    fn order<'a>(&'a mut self, costs: &'a FeatureCosts) -> Option<&'a [FeatureId]> {
        let _ = costs;
        None
    }
}

/// Measure features in `order`, skipping those the current pass has seen, until nothing
/// conflicts. A feature paid for in an earlier pass is replayed free but still attended.
fn measure_until_apart<A: Attend + ?Sized, S: Sensor>(
    order: &[FeatureId],
    library: &Library,
    attend: &A,
    conflicting: &mut Attention,
    probe: &mut Probe<'_, S>,
) {
    for &feature in order {
        if conflicting.attended().is_empty() {
            return;
        }
        if probe.ledger().consulted(feature) {
            continue;
        }
        let value = probe.measure(feature);
        attend.attend(library, feature, value, conflicting);
    }
}

/// CS-ID3's discrimination (the paper's "next cheapest feature"; specification §2): the unmeasured
/// features in ascending cost, then ascending id.
///
/// ```
/// use cslearn::{Attention, CheapestFirst, Discriminate, FeatureCosts, Ledger, Library};
/// use cslearn::{ObservationAttending, Probe, Value};
/// let costs = FeatureCosts::from_f64(&[1.0]).unwrap();
/// let object = [Some(Value(0))];
/// let mut ledger = Ledger::default();
/// let mut probe = Probe::new(&object[..], &costs, &mut ledger);
/// // Nothing conflicts: nothing is measured.
/// CheapestFirst.discriminate(&Library::new(), &ObservationAttending, &mut Attention::new(), &mut probe);
/// assert!(ledger.measured().is_empty());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CheapestFirst;

impl Discriminate for CheapestFirst {
    fn discriminate<A: Attend + ?Sized, S: Sensor>(
        &mut self,
        library: &Library,
        attend: &A,
        conflicting: &mut Attention,
        probe: &mut Probe<'_, S>,
    ) {
        measure_until_apart(probe.costs().order(), library, attend, conflicting, probe);
    }

    fn order<'a>(&'a mut self, costs: &'a FeatureCosts) -> Option<&'a [FeatureId]> {
        Some(costs.order())
    }
}

/// Cost-blind discrimination for the ID3 baseline (specification §2): the unmeasured features in a
/// random order drawn afresh for each object from the owned, seeded generator, so that no
/// cost information enters (the column order of a data set may follow its costs).
///
/// ```
/// use cslearn::{Attend, Attention, ClassId, Discriminate, Example, FeatureCosts, FeatureId};
/// use cslearn::{Ledger, Library, ObservationAttending, Probe, RandomOrder, Value};
/// use rand::SeedableRng;
/// let lib = Library::from(vec![Example::new(ClassId(0))]);
/// let costs = FeatureCosts::from_f64(&[1.0, 1.0, 1.0]).unwrap();
/// let object = [Some(Value(0)), Some(Value(0)), Some(Value(0))];
/// let mut conflicting = Attention::new();
/// ObservationAttending.start(&lib, &mut conflicting);
/// let mut ledger = Ledger::default();
/// let mut probe = Probe::new(&object[..], &costs, &mut ledger);
/// let mut order = RandomOrder::new(rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(7));
/// order.discriminate(&lib, &ObservationAttending, &mut conflicting, &mut probe);
/// assert_eq!(ledger.measured().len(), 1); // the empty example is dropped at once
/// ```
#[derive(Clone, Debug)]
pub struct RandomOrder<R> {
    rng: R,
    order: Vec<FeatureId>,
}

impl<R: Rng> RandomOrder<R> {
    /// A discrimination that draws its orders from `rng`.
    ///
    /// ```
    /// use rand::SeedableRng;
    /// let _ = cslearn::RandomOrder::new(rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1));
    /// ```
    pub fn new(rng: R) -> RandomOrder<R> {
        RandomOrder {
            rng,
            order: Vec::new(),
        }
    }
}

impl<R: Rng> Discriminate for RandomOrder<R> {
    fn discriminate<A: Attend + ?Sized, S: Sensor>(
        &mut self,
        library: &Library,
        attend: &A,
        conflicting: &mut Attention,
        probe: &mut Probe<'_, S>,
    ) {
        if conflicting.attended().is_empty() {
            // Drawing nothing keeps the generator's stream independent of lucky objects.
            return;
        }
        self.draw(probe.costs());
        measure_until_apart(&self.order, library, attend, conflicting, probe);
    }

    /// A fresh order from the generator, exactly as [`discriminate`](Discriminate::discriminate)
    /// draws it.
    ///
    /// ```
    /// use cslearn::{Discriminate, FeatureCosts, RandomOrder};
    /// use rand::SeedableRng;
    /// let costs = FeatureCosts::from_f64(&[1.0, 1.0, 1.0]).unwrap();
    /// let mut order = RandomOrder::new(rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(7));
    /// assert_eq!(order.order(&costs).unwrap().len(), 3);
    /// ```
    fn order<'a>(&'a mut self, costs: &'a FeatureCosts) -> Option<&'a [FeatureId]> {
        self.draw(costs);
        Some(&self.order)
    }
}

impl<R: Rng> RandomOrder<R> {
    fn draw(&mut self, costs: &FeatureCosts) {
        self.order.clear();
        self.order.extend((0..costs.len() as u32).map(FeatureId));
        self.order.shuffle(&mut self.rng);
    }
}
