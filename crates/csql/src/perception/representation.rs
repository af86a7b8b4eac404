//! State descriptions and the internal representation that holds them.
//!
//! A description is a rule: a sparse set of (feature, value) pairs. A state matches it
//! when the state has every listed value; a feature the description lacks may have any
//! value (unlike an example in an ordinary cslearn library, where a missing feature was
//! simply never measured: see [`cslearn::Semantics`]). The representation is a
//! [`cslearn::Library`] whose examples are the descriptions, each its own class (its
//! unique label): features are grid features ([`mdp::Feature`] indices) and values are
//! cell codes ([`mdp::Cell::code`]).
//!
//! The representation starts empty and only grows: descriptions are added by CLASSIFY
//! and refined (given one more feature) by the strategies, never removed. Any two
//! descriptions conflict on some feature, so a state matches at most one.

use cslearn::{AppendAll, ClassId, Example, FeatureId, Library, Update, Value};
use mdp::{Feature, Reading, Sensors, StateId};
use serde::Serialize;

/// The id of a description: its index in the representation, which is also its row in
/// the Q table and its unique label.
///
/// ```
/// assert_eq!(csql::DescriptionId(3).index(), 3);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub struct DescriptionId(pub u32);

impl DescriptionId {
    /// The id as an index.
    ///
    /// ```
    /// assert_eq!(csql::DescriptionId(0).index(), 0);
    /// ```
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }

    /// The description's row in the Q table.
    ///
    /// ```
    /// assert_eq!(csql::DescriptionId(2).row(), qlearn::RowId(2));
    /// ```
    #[inline]
    pub fn row(self) -> qlearn::RowId {
        qlearn::RowId(self.0)
    }
}

/// A grid feature as a cslearn feature.
#[inline]
pub(crate) fn feature_id(f: Feature) -> FeatureId {
    FeatureId(f.0)
}

/// A cell as a cslearn value.
#[inline]
pub(crate) fn value_of(r: Reading) -> Value {
    Value(r.0)
}

/// A borrowed view of one description, in grid terms.
///
/// ```
/// use mdp::{Cell, Feature, Reading};
/// let mut rep = csql::Representation::default();
/// let id = rep.push(&[(Feature(0), Reading::from(Cell::Empty))]);
/// let d = rep.get(id);
/// assert_eq!(d.features().collect::<Vec<_>>(), vec![(Feature(0), Reading::from(Cell::Empty))]);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Description<'a>(&'a Example);

impl<'a> Description<'a> {
    /// The pairs, in the feature order.
    ///
    /// ```
    /// let mut rep = csql::Representation::default();
    /// let id = rep.push(&[]);
    /// assert_eq!(rep.get(id).features().count(), 0);
    /// ```
    pub fn features(self) -> impl Iterator<Item = (Feature, Reading)> + 'a {
        self.0
            .pairs()
            .iter()
            .map(|&(f, v)| (Feature(f.0), Reading(v.0)))
    }

    /// The number of features.
    ///
    /// ```
    /// let mut rep = csql::Representation::default();
    /// let id = rep.push(&[(mdp::Feature(3), mdp::Reading::from(mdp::Cell::Goal))]);
    /// assert_eq!(rep.get(id).len(), 1);
    /// ```
    pub fn len(self) -> usize {
        self.0.len()
    }

    /// Whether the description has no feature (it matches every state).
    ///
    /// ```
    /// let mut rep = csql::Representation::default();
    /// let id = rep.push(&[]);
    /// assert!(rep.get(id).is_empty());
    /// ```
    pub fn is_empty(self) -> bool {
        self.0.is_empty()
    }

    /// The value the description requires for a feature, if any.
    ///
    /// ```
    /// let mut rep = csql::Representation::default();
    /// let id = rep.push(&[(mdp::Feature(3), mdp::Reading::from(mdp::Cell::Goal))]);
    /// assert_eq!(rep.get(id).value(mdp::Feature(3)), Some(mdp::Reading::from(mdp::Cell::Goal)));
    /// assert_eq!(rep.get(id).value(mdp::Feature(0)), None);
    /// ```
    pub fn value(self, f: Feature) -> Option<Reading> {
        self.0.get(feature_id(f)).map(|v| Reading(v.0))
    }

    /// The first feature in the feature order that the description lacks.
    ///
    /// ```
    /// use mdp::{Cell, Feature, Reading};
    /// let mut rep = csql::Representation::default();
    /// let id = rep.push(&[(Feature(0), Reading::from(Cell::Empty)), (Feature(2), Reading::from(Cell::Empty))]);
    /// assert_eq!(rep.get(id).next_missing(10), Some(Feature(1)));
    /// ```
    pub fn next_missing(self, universe: usize) -> Option<Feature> {
        (0..universe as u32)
            .map(Feature)
            .find(|&f| !self.0.has(feature_id(f)))
    }

    /// Whether a state matches: every listed feature has the listed value there. Sensing
    /// here is free: it is for the oracle and tests, not for the learner.
    ///
    /// ```
    /// use mdp::{Cell, Feature, FeatureSpace, GridWorld, Manhattan, Pos, Reading};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut rep = csql::Representation::default();
    /// let id = rep.push(&[(Feature(0), Reading::from(Cell::Obstacle))]); // a wall above
    /// assert!(rep.get(id).matches(&sensed, world.state_at(Pos::new(0, 0)).unwrap()));
    /// ```
    pub fn matches<W: Sensors + ?Sized>(self, world: &W, s: StateId) -> bool {
        self.features().all(|(f, v)| world.read(s, f) == v)
    }

    /// The summed cost of the description's features.
    ///
    /// ```
    /// use mdp::{Cell, Feature, FeatureSpace, Manhattan, Reading};
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut rep = csql::Representation::default();
    /// let id = rep.push(&[(Feature(0), Reading::from(Cell::Empty)), (Feature(4), Reading::from(Cell::Empty))]);
    /// assert_eq!(rep.get(id).cost(&sensed), 3.0);
    /// ```
    pub fn cost<W: Sensors + ?Sized>(self, world: &W) -> f64 {
        self.features().map(|(f, _)| world.price(f)).sum()
    }
}

/// The internal representation: every description, indexed by [`DescriptionId`].
///
/// ```
/// use csql::Representation;
/// let mut r = Representation::default();
/// let id = r.push(&[]);
/// assert_eq!((id.0, r.len()), (0, 1));
/// ```
#[derive(Clone, Debug, Default)]
pub struct Representation {
    library: Library,
    version: u64,
}

impl Representation {
    /// Add a description with the given pairs; its id (and label) is the next index.
    ///
    /// ```
    /// let mut r = csql::Representation::default();
    /// r.push(&[]);
    /// assert_eq!(r.push(&[(mdp::Feature(0), mdp::Reading::from(mdp::Cell::Empty))]).0, 1);
    /// ```
    pub fn push(&mut self, pairs: &[(Feature, Reading)]) -> DescriptionId {
        let id = DescriptionId(self.library.len() as u32);
        let example = Example::from_pairs(
            pairs.iter().map(|&(f, v)| (feature_id(f), value_of(v))),
            ClassId(id.0),
        );
        // CLASSIFY's library updating (Figure 3, step 4) is cslearn's: keep every new one.
        AppendAll.update(&mut self.library, example, false);
        self.version += 1;
        id
    }

    /// Add a feature to a description.
    ///
    /// ```
    /// let mut r = csql::Representation::default();
    /// let id = r.push(&[]);
    /// r.refine(id, mdp::Feature(0), mdp::Reading::from(mdp::Cell::Empty));
    /// assert_eq!(r.get(id).len(), 1);
    /// ```
    pub fn refine(&mut self, id: DescriptionId, f: Feature, v: Reading) {
        self.library
            .get_mut(id.index())
            .expect("a description of this representation")
            .insert(feature_id(f), value_of(v));
        self.version += 1;
    }

    /// A description.
    ///
    /// ```
    /// let mut r = csql::Representation::default();
    /// let id = r.push(&[]);
    /// assert!(r.get(id).is_empty());
    /// ```
    pub fn get(&self, id: DescriptionId) -> Description<'_> {
        Description(&self.library.examples()[id.index()])
    }

    /// Every description in id order.
    ///
    /// ```
    /// let mut r = csql::Representation::default();
    /// r.push(&[]);
    /// assert_eq!(r.iter().count(), 1);
    /// ```
    pub fn iter(&self) -> impl Iterator<Item = (DescriptionId, Description<'_>)> + '_ {
        self.library
            .examples()
            .iter()
            .enumerate()
            .map(|(i, e)| (DescriptionId(i as u32), Description(e)))
    }

    /// The descriptions as a cslearn library (each description its own class).
    ///
    /// ```
    /// let mut r = csql::Representation::default();
    /// r.push(&[]);
    /// assert_eq!(r.library().len(), 1);
    /// ```
    pub fn library(&self) -> &Library {
        &self.library
    }

    /// The number of descriptions.
    ///
    /// ```
    /// assert_eq!(csql::Representation::default().len(), 0);
    /// ```
    pub fn len(&self) -> usize {
        self.library.len()
    }

    /// Whether there is no description yet.
    ///
    /// ```
    /// assert!(csql::Representation::default().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.library.is_empty()
    }

    /// A counter that changes whenever the representation does (for caches).
    ///
    /// ```
    /// let mut r = csql::Representation::default();
    /// let v = r.version();
    /// r.push(&[]);
    /// assert_ne!(r.version(), v);
    /// ```
    pub fn version(&self) -> u64 {
        self.version
    }

    /// The description a state matches, found for free (oracle and tests only).
    ///
    /// ```
    /// use mdp::{FeatureSpace, GridWorld, Manhattan};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut r = csql::Representation::default();
    /// let id = r.push(&[]);
    /// assert_eq!(r.matching(&sensed, world.states()[0]), Some(id));
    /// ```
    pub fn matching<W: Sensors + ?Sized>(&self, world: &W, s: StateId) -> Option<DescriptionId> {
        self.iter()
            .find(|(_, d)| d.matches(world, s))
            .map(|(id, _)| id)
    }
}
