//! The sensing model: features are the conditions of cells at offsets from the robot,
//! each priced by a pluggable cost model, in one fixed order.
//!
//! # The feature order
//!
//! "The next cheapest feature" needs a total order. Features are sorted by ascending
//! cost; features of equal cost are taken clockwise by angle, starting from straight up.
//! With the default [`Manhattan`] cost the first four features are therefore up, right,
//! down and left of the robot, then the eight cells at distance 2 starting with `(0, 2)`.
//! The order is exact (integer arithmetic, no floating-point angles), so runs are
//! reproducible on every machine.

use serde::{Deserialize, Serialize};

use crate::geometry::{Cell, Offset};
use crate::grid::GridWorld;
use crate::map::Map;
use crate::process::StateId;

/// The largest price a feature may have: a run's total sensing cost, every feature
/// charged at every one of at most 2^64 moves (each read as often as a sensor repeats
/// it), stays far below `f64::MAX`. Larger prices are refused rather than summed to
/// infinity.
///
/// ```
/// assert_eq!(mdp::MAX_PRICE, 1e200);
/// ```
pub const MAX_PRICE: f64 = 1e200;

/// What a feature reads in a state: a small integer whose meaning the world names
/// ([`Sensors::reading_name`](crate::Sensors::reading_name)). On grids it is a [`Cell::code`].
///
/// ```
/// let r = mdp::Reading::from(mdp::Cell::Goal);
/// assert_eq!(r.0, 2);
/// assert_eq!(mdp::Cell::try_from(r), Ok(mdp::Cell::Goal));
/// ```
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Default, Serialize, Deserialize,
)]
#[serde(transparent)]
pub struct Reading(pub u32);

impl From<Cell> for Reading {
    fn from(c: Cell) -> Reading {
        Reading(c.code())
    }
}

impl TryFrom<Reading> for Cell {
    type Error = Reading;
    /// The cell a grid reading stands for; the reading itself if it stands for none.
    fn try_from(r: Reading) -> Result<Cell, Reading> {
        Cell::from_code(r.0).ok_or(r)
    }
}

/// The price of sensing the cell at an offset. Implement it to change the cost model.
///
/// Costs must be finite and non-negative; [`FeatureSpace::new`] checks.
///
/// ```
/// use mdp::{CostModel, Offset};
/// /// Sensing costs grow with the square of the distance.
/// struct Squared;
/// impl CostModel for Squared {
///     fn cost(&self, o: Offset) -> f64 { (o.dx * o.dx + o.dy * o.dy) as f64 }
/// }
/// assert_eq!(Squared.cost(Offset::new(1, 2)), 5.0);
/// ```
pub trait CostModel {
    /// The cost of sensing the cell at `o`.
    fn cost(&self, o: Offset) -> f64;
}

/// The paper's cost model: `|dx| + |dy|`.
///
/// ```
/// use mdp::{CostModel, Manhattan, Offset};
/// assert_eq!(Manhattan.cost(Offset::new(-2, 3)), 5.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Manhattan;

impl CostModel for Manhattan {
    fn cost(&self, o: Offset) -> f64 {
        (o.dx.unsigned_abs() + o.dy.unsigned_abs()) as f64
    }
}

/// A feature: an index into a [`FeatureSpace`], which is sorted in the feature order, so
/// a smaller index never costs more.
///
/// ```
/// assert!(mdp::Feature(0) < mdp::Feature(1));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct Feature(pub u32);

impl Feature {
    /// The feature as an index.
    ///
    /// ```
    /// assert_eq!(mdp::Feature(4).index(), 4);
    /// ```
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A cost that is not a finite non-negative number.
///
/// ```
/// use mdp::{CostModel, FeatureSpace, Offset};
/// struct Bad;
/// impl CostModel for Bad { fn cost(&self, _: Offset) -> f64 { -1.0 } }
/// let err = FeatureSpace::new(&mdp::builtin("tan3x3").unwrap(), &Bad).unwrap_err();
/// assert!(err.to_string().contains("-1"));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "the cost model gives offset {offset} the cost {cost}; costs must be finite, >= 0 and at most 1e200 (mdp::MAX_PRICE)"
)]
pub struct BadCost {
    /// The offset.
    pub offset: Offset,
    /// Its cost.
    pub cost: f64,
}

/// Every feature of a map, in the fixed feature order, with its cost.
///
/// The universe holds every offset that can land in the bordered world from some state:
/// `|dx| <= W + 1`, `|dy| <= H + 1`, `(dx, dy) != (0, 0)`.
///
/// ```
/// use mdp::{FeatureSpace, Manhattan, Offset};
/// let space = FeatureSpace::new(&mdp::builtin("tan8x8").unwrap(), &Manhattan).unwrap();
/// assert_eq!(space.len(), 360);
/// let first: Vec<Offset> = (0..4).map(|i| space.offset(mdp::Feature(i))).collect();
/// assert_eq!(first, [Offset::new(0, 1), Offset::new(1, 0), Offset::new(0, -1), Offset::new(-1, 0)]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct FeatureSpace {
    offsets: Vec<Offset>,
    costs: Vec<f64>,
    half_w: i32,
    half_h: i32,
    index: Vec<u32>,
}

impl FeatureSpace {
    /// The feature universe of a map under a cost model.
    ///
    /// ```
    /// let s = mdp::FeatureSpace::new(&mdp::builtin("tan3x3").unwrap(), &mdp::Manhattan).unwrap();
    /// assert_eq!(s.len(), 9 * 9 - 1); // |dx|, |dy| <= 4, less (0, 0)
    /// ```
    pub fn new(map: &Map, model: &dyn CostModel) -> Result<FeatureSpace, BadCost> {
        let (hw, hh) = (map.width() as i32 + 1, map.height() as i32 + 1);
        let mut entries = Vec::with_capacity(((2 * hw + 1) * (2 * hh + 1)) as usize);
        for dy in -hh..=hh {
            for dx in -hw..=hw {
                if (dx, dy) == (0, 0) {
                    continue;
                }
                let o = Offset::new(dx, dy);
                let cost = model.cost(o);
                if !(cost.is_finite() && (0.0..=MAX_PRICE).contains(&cost)) {
                    return Err(BadCost { offset: o, cost });
                }
                entries.push((o, cost));
            }
        }
        entries.sort_by(|a, b| a.1.total_cmp(&b.1).then_with(|| a.0.clockwise_cmp(&b.0)));
        let width = (2 * hw + 1) as usize;
        let mut index = vec![u32::MAX; width * (2 * hh + 1) as usize];
        for (i, (o, _)) in entries.iter().enumerate() {
            index[(o.dy + hh) as usize * width + (o.dx + hw) as usize] = i as u32;
        }
        Ok(FeatureSpace {
            offsets: entries.iter().map(|e| e.0).collect(),
            costs: entries.iter().map(|e| e.1).collect(),
            half_w: hw,
            half_h: hh,
            index,
        })
    }

    /// The features whose cost is at most `max_cost` (a sensing range: with the
    /// [`Manhattan`] model, `within(1.0)` keeps only the four neighbours). The order and
    /// the costs of the kept features are unchanged; a cut feature has no index.
    ///
    /// ```
    /// use mdp::{FeatureSpace, Manhattan, Offset};
    /// let all = FeatureSpace::new(&mdp::builtin("tan8x8").unwrap(), &Manhattan).unwrap();
    /// let near = all.within(2.0);
    /// assert_eq!(near.len(), 12);
    /// assert_eq!(near.offset(mdp::Feature(5)), all.offset(mdp::Feature(5)));
    /// assert_eq!(near.feature_of(Offset::new(0, 3)), None);
    /// ```
    pub fn within(&self, max_cost: f64) -> FeatureSpace {
        let keep = self.costs.iter().take_while(|&&c| c <= max_cost).count();
        let mut index = self.index.clone();
        for i in &mut index {
            if *i as usize >= keep {
                *i = u32::MAX;
            }
        }
        FeatureSpace {
            offsets: self.offsets[..keep].to_vec(),
            costs: self.costs[..keep].to_vec(),
            half_w: self.half_w,
            half_h: self.half_h,
            index,
        }
    }

    /// The number of features.
    ///
    /// ```
    /// let s = mdp::FeatureSpace::new(&mdp::builtin("tan8x8").unwrap(), &mdp::Manhattan).unwrap();
    /// assert!(!s.is_empty());
    /// ```
    pub fn len(&self) -> usize {
        self.offsets.len()
    }

    /// Whether there are no features (never, for a valid map).
    ///
    /// ```
    /// let s = mdp::FeatureSpace::new(&mdp::builtin("tan3x3").unwrap(), &mdp::Manhattan).unwrap();
    /// assert!(!s.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.offsets.is_empty()
    }

    /// The offset a feature senses.
    ///
    /// ```
    /// let s = mdp::FeatureSpace::new(&mdp::builtin("tan3x3").unwrap(), &mdp::Manhattan).unwrap();
    /// assert_eq!(s.offset(mdp::Feature(4)), mdp::Offset::new(0, 2));
    /// ```
    #[inline]
    pub fn offset(&self, f: Feature) -> Offset {
        self.offsets[f.index()]
    }

    /// The cost of sensing a feature.
    ///
    /// ```
    /// let s = mdp::FeatureSpace::new(&mdp::builtin("tan3x3").unwrap(), &mdp::Manhattan).unwrap();
    /// assert_eq!(s.cost(mdp::Feature(0)), 1.0);
    /// ```
    #[inline]
    pub fn cost(&self, f: Feature) -> f64 {
        self.costs[f.index()]
    }

    /// Every cost, indexed by feature.
    ///
    /// ```
    /// let s = mdp::FeatureSpace::new(&mdp::builtin("tan3x3").unwrap(), &mdp::Manhattan).unwrap();
    /// assert!(s.costs().windows(2).all(|w| w[0] <= w[1]));
    /// ```
    pub fn costs(&self) -> &[f64] {
        &self.costs
    }

    /// The feature that senses an offset, if the offset is in the universe.
    ///
    /// ```
    /// use mdp::{Feature, Offset};
    /// let s = mdp::FeatureSpace::new(&mdp::builtin("tan3x3").unwrap(), &mdp::Manhattan).unwrap();
    /// assert_eq!(s.feature_of(Offset::new(-1, 0)), Some(Feature(3)));
    /// assert_eq!(s.feature_of(Offset::new(0, 0)), None);
    /// assert_eq!(s.feature_of(Offset::new(99, 0)), None);
    /// ```
    pub fn feature_of(&self, o: Offset) -> Option<Feature> {
        if o.dx.abs() > self.half_w || o.dy.abs() > self.half_h {
            return None;
        }
        let width = (2 * self.half_w + 1) as usize;
        let i = self.index[(o.dy + self.half_h) as usize * width + (o.dx + self.half_w) as usize];
        (i != u32::MAX).then_some(Feature(i))
    }

    /// Every feature in order.
    ///
    /// ```
    /// let s = mdp::FeatureSpace::new(&mdp::builtin("tan3x3").unwrap(), &mdp::Manhattan).unwrap();
    /// assert_eq!(s.features().count(), s.len());
    /// ```
    pub fn features(&self) -> impl Iterator<Item = Feature> + '_ {
        (0..self.offsets.len() as u32).map(Feature)
    }

    /// Measure one feature of one state of a world.
    ///
    /// ```
    /// use mdp::{Cell, Feature, FeatureSpace, GridWorld, Manhattan, Pos};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let s = world.state_at(Pos::new(0, 0)).unwrap();
    /// assert_eq!(space.measure(&world, s, Feature(0)), Cell::Obstacle); // up: the boundary
    /// ```
    #[inline]
    pub fn measure(&self, world: &GridWorld, s: StateId, f: Feature) -> Cell {
        world.sense(s, self.offsets[f.index()])
    }
}
