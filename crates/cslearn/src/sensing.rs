//! Sensing: measuring one feature of the current object, and the ledger of what it cost.

use crate::example::Example;
use crate::types::{ClassId, Cost, Costs, FeatureId, Value};

/// Measures one feature of the current object (the paper's step 1(c) of Figure 2).
///
/// `None` is a missing value: the feature was measured but gave nothing. A sensor never
/// charges; whoever calls it through a [`Probe`] does. Implemented for a dense row
/// (`&[Option<Value>]`, feature `i` at index `i`), for `&Example` (a feature it lacks reads
/// as missing) and for `&mut S` of any sensor `S`.
///
/// ```
/// use cslearn::{FeatureId, Sensor, Value};
/// let row = [Some(Value(1)), None];
/// let mut object = &row[..];
/// assert_eq!(object.measure(FeatureId(0)), Some(Value(1)));
/// assert_eq!(object.measure(FeatureId(1)), None);
/// assert_eq!(object.measure(FeatureId(9)), None);
/// ```
pub trait Sensor {
    /// The value of `feature` on the current object, or `None` if it is missing.
    fn measure(&mut self, feature: FeatureId) -> Option<Value>;
}

impl Sensor for &[Option<Value>] {
    fn measure(&mut self, feature: FeatureId) -> Option<Value> {
        self.get(feature.index()).copied().flatten()
    }
}

impl Sensor for &Example {
    fn measure(&mut self, feature: FeatureId) -> Option<Value> {
        self.get(feature)
    }
}

impl<S: Sensor + ?Sized> Sensor for &mut S {
    fn measure(&mut self, feature: FeatureId) -> Option<Value> {
        (**self).measure(feature)
    }
}

/// What was measured on one object, in order, and what it cost: the learner's ledger.
///
/// A missing value is recorded too (it was paid for, and measuring again would not help).
/// A feature is paid for once per object: the learner may look at the object more than
/// once (a *pass*: after learning it checks that the object is now recognised), and a
/// later pass reads the values already paid for free. [`consulted`](Ledger::consulted)
/// tells which features the current pass has looked at.
///
/// ```
/// use cslearn::{Cost, FeatureCosts, FeatureId, Ledger, Probe, Value};
/// let costs = FeatureCosts::from_f64(&[1.0, 2.5]).unwrap();
/// let row = [Some(Value(0)), None];
/// let mut ledger = Ledger::default();
/// let mut probe = Probe::new(&row[..], &costs, &mut ledger);
/// probe.measure(FeatureId(1));
/// probe.measure(FeatureId(0));
/// assert_eq!(ledger.cost().get(), 3.5);
/// assert_eq!(ledger.measured(), &[(FeatureId(1), None), (FeatureId(0), Some(Value(0)))]);
/// assert!(ledger.is_measured(FeatureId(1)));
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Ledger {
    measured: Vec<(FeatureId, Option<Value>)>,
    cost: Cost,
    /// Indices into `measured` of the features looked at in the current pass.
    pass: Vec<usize>,
}

impl Ledger {
    /// Forget everything, keeping the buffer.
    ///
    /// ```
    /// let mut ledger = cslearn::Ledger::default();
    /// ledger.clear();
    /// assert_eq!(ledger.cost(), cslearn::Cost::ZERO);
    /// ```
    pub fn clear(&mut self) {
        self.measured.clear();
        self.pass.clear();
        self.cost = Cost::ZERO;
    }

    /// Start a new pass over the same object: nothing is consulted yet, everything paid
    /// for stays paid for.
    ///
    /// ```
    /// use cslearn::{Cost, FeatureId, Ledger};
    /// let mut ledger = Ledger::default();
    /// ledger.record(FeatureId(0), None, Cost::ONE);
    /// ledger.start_pass();
    /// assert!(ledger.is_measured(FeatureId(0)) && !ledger.consulted(FeatureId(0)));
    /// ```
    pub fn start_pass(&mut self) {
        self.pass.clear();
    }

    /// Whether the current pass has looked at `feature`.
    ///
    /// ```
    /// use cslearn::{Cost, FeatureId, Ledger};
    /// let mut ledger = Ledger::default();
    /// ledger.record(FeatureId(0), None, Cost::ONE);
    /// assert!(ledger.consulted(FeatureId(0)));
    /// ```
    pub fn consulted(&self, feature: FeatureId) -> bool {
        self.pass.iter().any(|&i| self.measured[i].0 == feature)
    }

    /// Look at `feature` in the current pass if it was paid for: its value, free.
    fn replay(&mut self, feature: FeatureId) -> Option<Option<Value>> {
        let i = self.measured.iter().position(|&(f, _)| f == feature)?;
        if !self.pass.contains(&i) {
            self.pass.push(i);
        }
        Some(self.measured[i].1)
    }

    /// Record a measurement and its price; it counts as consulted in the current pass.
    ///
    /// ```
    /// use cslearn::{Cost, FeatureId, Ledger, Value};
    /// let mut ledger = Ledger::default();
    /// ledger.record(FeatureId(2), Some(Value(1)), Cost::ONE);
    /// assert_eq!(ledger.value(FeatureId(2)), Some(Some(Value(1))));
    /// ```
    pub fn record(&mut self, feature: FeatureId, value: Option<Value>, cost: Cost) {
        self.pass.push(self.measured.len());
        self.measured.push((feature, value));
        self.cost += cost;
    }

    /// The measurements in the order they were made.
    ///
    /// ```
    /// assert!(cslearn::Ledger::default().measured().is_empty());
    /// ```
    pub fn measured(&self) -> &[(FeatureId, Option<Value>)] {
        &self.measured
    }

    /// Whether `feature` has been measured (paid for) on this object.
    ///
    /// ```
    /// assert!(!cslearn::Ledger::default().is_measured(cslearn::FeatureId(0)));
    /// ```
    pub fn is_measured(&self, feature: FeatureId) -> bool {
        // A linear scan: an object's ledger holds a handful of entries, and a scan needs
        // no second structure to keep in step.
        self.measured.iter().any(|&(f, _)| f == feature)
    }

    /// The measured value of `feature`: `None` if not measured, `Some(None)` if missing.
    ///
    /// ```
    /// assert_eq!(cslearn::Ledger::default().value(cslearn::FeatureId(0)), None);
    /// ```
    pub fn value(&self, feature: FeatureId) -> Option<Option<Value>> {
        self.measured
            .iter()
            .find(|&&(f, _)| f == feature)
            .map(|&(_, v)| v)
    }

    /// The total charged.
    ///
    /// ```
    /// assert_eq!(cslearn::Ledger::default().cost(), cslearn::Cost::ZERO);
    /// ```
    pub fn cost(&self) -> Cost {
        self.cost
    }

    /// The new example the measurements make, with class `class`: every value measured,
    /// missing ones left out (an example lacking a feature does not know its value).
    ///
    /// ```
    /// use cslearn::{ClassId, Cost, FeatureId, Ledger, Value};
    /// let mut ledger = Ledger::default();
    /// ledger.record(FeatureId(2), Some(Value(1)), Cost::ONE);
    /// ledger.record(FeatureId(0), None, Cost::ONE);
    /// let e = ledger.to_example(ClassId(1));
    /// assert_eq!(e.pairs(), &[(FeatureId(2), Value(1))]);
    /// ```
    pub fn to_example(&self, class: ClassId) -> Example {
        Example::from_pairs(
            self.measured.iter().filter_map(|&(f, v)| v.map(|v| (f, v))),
            class,
        )
    }
}

/// A sensor, the price list and a ledger together: every measurement through a probe is
/// charged and recorded.
///
/// ```
/// use cslearn::{FeatureCosts, FeatureId, Ledger, Probe, Value};
/// let costs = FeatureCosts::from_f64(&[4.0]).unwrap();
/// let row = [Some(Value(7))];
/// let mut ledger = Ledger::default();
/// let mut probe = Probe::new(&row[..], &costs, &mut ledger);
/// assert_eq!(probe.measure(FeatureId(0)), Some(Value(7)));
/// assert_eq!(probe.ledger().cost().get(), 4.0);
/// ```
#[derive(Debug)]
pub struct Probe<'a, S, C: ?Sized = crate::types::FeatureCosts> {
    sensor: S,
    costs: &'a C,
    ledger: &'a mut Ledger,
}

impl<'a, S: Sensor, C: Costs + ?Sized> Probe<'a, S, C> {
    /// A probe that charges `costs` into `ledger`, which it does not clear.
    ///
    /// ```
    /// let costs = cslearn::FeatureCosts::new(Vec::new());
    /// let mut ledger = cslearn::Ledger::default();
    /// let row: [Option<cslearn::Value>; 0] = [];
    /// let probe = cslearn::Probe::new(&row[..], &costs, &mut ledger);
    /// assert!(probe.ledger().measured().is_empty());
    /// ```
    pub fn new(sensor: S, costs: &'a C, ledger: &'a mut Ledger) -> Self {
        Probe {
            sensor,
            costs,
            ledger,
        }
    }

    /// Measure `feature`, charge its cost and record it; a feature already paid for on
    /// this object is read from the ledger, free. A feature without a price is charged
    /// nothing (no part of this crate measures one).
    ///
    /// ```
    /// use cslearn::{FeatureCosts, FeatureId, Ledger, Probe, Value};
    /// let costs = FeatureCosts::from_f64(&[4.0]).unwrap();
    /// let mut ledger = Ledger::default();
    /// let row = [Some(Value(7))];
    /// Probe::new(&row[..], &costs, &mut ledger).measure(FeatureId(0));
    /// assert_eq!(ledger.measured().len(), 1);
    /// ```
    pub fn measure(&mut self, feature: FeatureId) -> Option<Value> {
        if let Some(value) = self.ledger.replay(feature) {
            return value;
        }
        let value = self.sensor.measure(feature);
        let cost = self.costs.cost(feature).unwrap_or(Cost::ZERO);
        self.ledger.record(feature, value, cost);
        value
    }

    /// The ledger so far, to start a new pass.
    ///
    /// ```
    /// let costs = cslearn::FeatureCosts::new(Vec::new());
    /// let mut ledger = cslearn::Ledger::default();
    /// let row: [Option<cslearn::Value>; 0] = [];
    /// let mut probe = cslearn::Probe::new(&row[..], &costs, &mut ledger);
    /// probe.ledger_mut().start_pass();
    /// ```
    pub fn ledger_mut(&mut self) -> &mut Ledger {
        self.ledger
    }

    /// The ledger so far.
    ///
    /// ```
    /// let costs = cslearn::FeatureCosts::new(Vec::new());
    /// let mut ledger = cslearn::Ledger::default();
    /// let row: [Option<cslearn::Value>; 0] = [];
    /// let probe = cslearn::Probe::new(&row[..], &costs, &mut ledger);
    /// assert_eq!(probe.ledger().cost(), cslearn::Cost::ZERO);
    /// ```
    pub fn ledger(&self) -> &Ledger {
        self.ledger
    }

    /// The price list charged.
    ///
    /// ```
    /// let costs = cslearn::FeatureCosts::from_f64(&[1.0]).unwrap();
    /// let mut ledger = cslearn::Ledger::default();
    /// let row: [Option<cslearn::Value>; 0] = [];
    /// let probe = cslearn::Probe::new(&row[..], &costs, &mut ledger);
    /// assert_eq!(probe.costs().len(), 1);
    /// ```
    pub fn costs(&self) -> &'a C {
        self.costs
    }
}
