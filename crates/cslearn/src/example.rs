//! Examples and the example library.

use crate::types::{ClassId, FeatureId, Value};

/// A sparse set of feature values plus a class label (the paper's "example": a set of
/// feature-value pairs plus a class label).
///
/// The pairs are kept sorted by feature, one value per feature, so lookups are binary
/// searches. What a missing feature means is not decided here but by the attending
/// function: for an observation it was never measured, for a rule it means "any value".
///
/// ```
/// use cslearn::{ClassId, Example, FeatureId, Value};
/// let mut e = Example::new(ClassId(1));
/// e.insert(FeatureId(4), Value(2));
/// e.insert(FeatureId(1), Value(0));
/// assert_eq!(e.get(FeatureId(4)), Some(Value(2)));
/// assert_eq!(e.get(FeatureId(3)), None);
/// assert_eq!(e.pairs()[0], (FeatureId(1), Value(0)));
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Example {
    pairs: Vec<(FeatureId, Value)>,
    class: ClassId,
}

impl Example {
    /// An example with no features.
    ///
    /// ```
    /// let e = cslearn::Example::new(cslearn::ClassId(0));
    /// assert!(e.is_empty());
    /// ```
    pub fn new(class: ClassId) -> Example {
        Example {
            pairs: Vec::new(),
            class,
        }
    }

    /// An example from pairs in any order; a later pair for the same feature wins.
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureId, Value};
    /// let e = Example::from_pairs([(FeatureId(2), Value(1)), (FeatureId(0), Value(3))], ClassId(0));
    /// assert_eq!(e.len(), 2);
    /// ```
    pub fn from_pairs(
        pairs: impl IntoIterator<Item = (FeatureId, Value)>,
        class: ClassId,
    ) -> Example {
        let mut e = Example::new(class);
        for (f, v) in pairs {
            e.insert(f, v);
        }
        e
    }

    /// The class label.
    ///
    /// ```
    /// assert_eq!(cslearn::Example::new(cslearn::ClassId(3)).class(), cslearn::ClassId(3));
    /// ```
    pub fn class(&self) -> ClassId {
        self.class
    }

    /// Change the class label.
    ///
    /// ```
    /// let mut e = cslearn::Example::new(cslearn::ClassId(3));
    /// e.set_class(cslearn::ClassId(1));
    /// assert_eq!(e.class(), cslearn::ClassId(1));
    /// ```
    pub fn set_class(&mut self, class: ClassId) {
        self.class = class;
    }

    /// The value of `feature`, if the example has it.
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureId, Value};
    /// let e = Example::from_pairs([(FeatureId(2), Value(1))], ClassId(0));
    /// assert_eq!(e.get(FeatureId(2)), Some(Value(1)));
    /// ```
    pub fn get(&self, feature: FeatureId) -> Option<Value> {
        self.pairs
            .binary_search_by_key(&feature, |&(f, _)| f)
            .ok()
            .map(|i| self.pairs[i].1)
    }

    /// Whether the example has `feature`.
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureId, Value};
    /// let e = Example::from_pairs([(FeatureId(2), Value(1))], ClassId(0));
    /// assert!(e.has(FeatureId(2)) && !e.has(FeatureId(1)));
    /// ```
    pub fn has(&self, feature: FeatureId) -> bool {
        self.get(feature).is_some()
    }

    /// Set the value of `feature`, returning the value it replaced.
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureId, Value};
    /// let mut e = Example::new(ClassId(0));
    /// assert_eq!(e.insert(FeatureId(1), Value(1)), None);
    /// assert_eq!(e.insert(FeatureId(1), Value(2)), Some(Value(1)));
    /// ```
    pub fn insert(&mut self, feature: FeatureId, value: Value) -> Option<Value> {
        match self.pairs.binary_search_by_key(&feature, |&(f, _)| f) {
            Ok(i) => Some(std::mem::replace(&mut self.pairs[i].1, value)),
            Err(i) => {
                self.pairs.insert(i, (feature, value));
                None
            }
        }
    }

    /// Remove `feature`, returning its value.
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureId, Value};
    /// let mut e = Example::from_pairs([(FeatureId(2), Value(1))], ClassId(0));
    /// assert_eq!(e.remove(FeatureId(2)), Some(Value(1)));
    /// assert!(e.is_empty());
    /// ```
    pub fn remove(&mut self, feature: FeatureId) -> Option<Value> {
        let i = self
            .pairs
            .binary_search_by_key(&feature, |&(f, _)| f)
            .ok()?;
        Some(self.pairs.remove(i).1)
    }

    /// The (feature, value) pairs, by ascending feature.
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureId, Value};
    /// let e = Example::from_pairs([(FeatureId(2), Value(1))], ClassId(0));
    /// assert_eq!(e.pairs(), &[(FeatureId(2), Value(1))]);
    /// ```
    pub fn pairs(&self) -> &[(FeatureId, Value)] {
        &self.pairs
    }

    /// The number of features the example has.
    ///
    /// ```
    /// assert_eq!(cslearn::Example::new(cslearn::ClassId(0)).len(), 0);
    /// ```
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    /// Whether the example has no features.
    ///
    /// ```
    /// assert!(cslearn::Example::new(cslearn::ClassId(0)).is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }
}

/// The example library: the learner's memory, in the order examples were added.
///
/// Examples are addressed by their index, which never changes (examples are never removed,
/// but they may be changed through [`get_mut`](Library::get_mut)).
///
/// ```
/// use cslearn::{ClassId, Example, Library};
/// let mut lib = Library::new();
/// let i = lib.push(Example::new(ClassId(1)));
/// assert_eq!(lib[i].class(), ClassId(1));
/// assert_eq!(lib.len(), 1);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Library {
    examples: Vec<Example>,
}

impl Library {
    /// An empty library.
    ///
    /// ```
    /// assert!(cslearn::Library::new().is_empty());
    /// ```
    pub fn new() -> Library {
        Library::default()
    }

    /// Add an example and return its index.
    ///
    /// ```
    /// let mut lib = cslearn::Library::new();
    /// assert_eq!(lib.push(cslearn::Example::new(cslearn::ClassId(0))), 0);
    /// ```
    pub fn push(&mut self, example: Example) -> usize {
        self.examples.push(example);
        self.examples.len() - 1
    }

    /// The example at `index`, if there is one.
    ///
    /// ```
    /// assert!(cslearn::Library::new().get(0).is_none());
    /// ```
    pub fn get(&self, index: usize) -> Option<&Example> {
        self.examples.get(index)
    }

    /// The example at `index`, to change it (csql adds features to its descriptions).
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureId, Library, Value};
    /// let mut lib = Library::from(vec![Example::new(ClassId(0))]);
    /// lib.get_mut(0).unwrap().insert(FeatureId(3), Value(1));
    /// assert!(lib[0].has(FeatureId(3)));
    /// ```
    pub fn get_mut(&mut self, index: usize) -> Option<&mut Example> {
        self.examples.get_mut(index)
    }

    /// The number of examples.
    ///
    /// ```
    /// assert_eq!(cslearn::Library::new().len(), 0);
    /// ```
    pub fn len(&self) -> usize {
        self.examples.len()
    }

    /// Whether the library is empty.
    ///
    /// ```
    /// assert!(cslearn::Library::new().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.examples.is_empty()
    }

    /// The examples, by index.
    ///
    /// ```
    /// let lib = cslearn::Library::from(vec![cslearn::Example::new(cslearn::ClassId(2))]);
    /// assert_eq!(lib.examples()[0].class(), cslearn::ClassId(2));
    /// ```
    pub fn examples(&self) -> &[Example] {
        &self.examples
    }

    /// Iterate over the examples, by index.
    ///
    /// ```
    /// let lib = cslearn::Library::from(vec![cslearn::Example::new(cslearn::ClassId(2))]);
    /// assert_eq!(lib.iter().count(), 1);
    /// ```
    pub fn iter(&self) -> std::slice::Iter<'_, Example> {
        self.examples.iter()
    }
}

impl From<Vec<Example>> for Library {
    fn from(examples: Vec<Example>) -> Library {
        Library { examples }
    }
}

impl FromIterator<Example> for Library {
    fn from_iter<I: IntoIterator<Item = Example>>(iter: I) -> Library {
        Library {
            examples: iter.into_iter().collect(),
        }
    }
}

impl std::ops::Index<usize> for Library {
    type Output = Example;
    fn index(&self, index: usize) -> &Example {
        &self.examples[index]
    }
}

impl<'a> IntoIterator for &'a Library {
    type Item = &'a Example;
    type IntoIter = std::slice::Iter<'a, Example>;
    fn into_iter(self) -> Self::IntoIter {
        self.examples.iter()
    }
}
