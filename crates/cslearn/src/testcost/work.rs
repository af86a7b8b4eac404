//! What the split tries of this process have computed, counted for measurement (the
//! `work-counts` feature; without it nothing is counted and this module is absent).
//!
//! Every learner of the family spends its time in a split trie's statistics: one pass
//! per feature over a node's objects, for every node whose statistics are not already
//! remembered. The count of those nodes and of the objects they held measures a
//! learner's work apart from the machine, so that two learners, or two versions of
//! one, can be compared by what they had to compute as well as by how long it took.
//! The counts are process-wide and taken by every thread, so read them around work
//! done on one thread at a time.
//!
//! ```
//! # #[cfg(feature = "work-counts")] {
//! use cslearn::testcost::{fit, Column, FamilyParams, Frame, Method, MisclassCosts, TestPrices, Work};
//! let frame = Frame::new(vec!["x".into()], vec![Column::Numeric((0..20).map(f64::from).collect())],
//!     (0..20).map(|i| u32::from(i >= 10)).collect(), vec!["a".into(), "b".into()]).unwrap();
//! let prices = TestPrices::flat(&[5.0]).unwrap();
//! let mc = MisclassCosts::uniform(2, 100.0).unwrap();
//! let rows: Vec<usize> = (0..20).collect();
//! let before = Work::now();
//! fit(Method::Eg2, &frame, &rows, &prices, &mc, &FamilyParams::default(), 1);
//! let done = Work::now().since(before);
//! // The root's statistics at least: its 20 objects.
//! assert!(done.nodes >= 1 && done.objects >= 20, "{done:?}");
//! // It split the root (the classes part at 10 with a gain).
//! assert!(done.splits >= 1, "{done:?}");
//! # }
//! ```

use std::sync::atomic::{AtomicU64, Ordering};

static NODES: AtomicU64 = AtomicU64::new(0);
static OBJECTS: AtomicU64 = AtomicU64::new(0);
static SPLITS: AtomicU64 = AtomicU64::new(0);

/// The nodes whose split statistics were computed, the objects they held, and the nodes
/// split into children, counted from the start of the process (or between two readings,
/// with [`since`](Work::since)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Work {
    /// Nodes whose statistics were computed (not read back from a trie's memory).
    pub nodes: u64,
    /// The objects of those nodes, summed: each was read once per feature.
    pub objects: u64,
    /// Nodes split into children (a trie splits a node once per test, until it forgets
    /// the children).
    pub splits: u64,
}

impl Work {
    /// The counts so far.
    ///
    /// ```
    /// # #[cfg(feature = "work-counts")] {
    /// let (a, b) = (cslearn::testcost::Work::now(), cslearn::testcost::Work::now());
    /// assert!(b.nodes >= a.nodes);
    /// # }
    /// ```
    pub fn now() -> Work {
        Work {
            nodes: NODES.load(Ordering::Relaxed),
            objects: OBJECTS.load(Ordering::Relaxed),
            splits: SPLITS.load(Ordering::Relaxed),
        }
    }

    /// The work done between the reading `earlier` and this one.
    ///
    /// ```
    /// # #[cfg(feature = "work-counts")] {
    /// use cslearn::testcost::Work;
    /// let later = Work { nodes: 5, objects: 90, splits: 4 };
    /// let earlier = Work { nodes: 2, objects: 30, splits: 1 };
    /// assert_eq!(later.since(earlier), Work { nodes: 3, objects: 60, splits: 3 });
    /// # }
    /// ```
    pub fn since(self, earlier: Work) -> Work {
        Work {
            nodes: self.nodes.saturating_sub(earlier.nodes),
            objects: self.objects.saturating_sub(earlier.objects),
            splits: self.splits.saturating_sub(earlier.splits),
        }
    }
}

/// Counts a node of `objects` objects whose statistics were computed.
pub(super) fn scored(objects: usize) {
    NODES.fetch_add(1, Ordering::Relaxed);
    OBJECTS.fetch_add(objects as u64, Ordering::Relaxed);
}

/// Counts a node split into children.
pub(super) fn split() {
    SPLITS.fetch_add(1, Ordering::Relaxed);
}
