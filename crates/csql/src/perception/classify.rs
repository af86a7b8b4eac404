//! CLASSIFY (the paper's Figure 3), made from cslearn's parts, with a cache that never
//! changes what is charged.
//!
//! # The procedure (`docs/specification.md`, section 4.2)
//!
//! 1. The candidates are all descriptions; the new description is empty.
//! 2. If one candidate remains and every feature it has is measured, return it. If none
//!    remains, add the new description (the features measured in this call) and return it.
//! 3. Otherwise select a feature by I^2/C over the candidates ([`cslearn::InfoCost`] with
//!    the C4.5 missing-value rule: the gain of a feature is computed on the candidates that
//!    have it and scaled by their share; with every gain zero the cheapest candidate
//!    feature wins; ties go by the feature order), measure it on the state (charged),
//!    record it in the new description, drop the candidates that require another value
//!    ([`cslearn::RuleAttending`]: a description that lacks the feature stays), go to 2.
//!
//! # The cache
//!
//! Which feature step 3 picks depends only on the representation and on the values
//! measured so far in the call, so the whole procedure is a decision tree over the
//! current representation. [`Classify`] grows that tree lazily (a node is computed the
//! first time a classification reaches it) and keeps it across changes of the
//! representation: each node holds its candidates and the value counts its choice is
//! computed from, a new or refined description updates only the nodes where it is a
//! candidate, and a node's choice is recomputed from its counts when it is next reached
//! (the subtree below survives when the choice stays the same). A cached classification
//! measures exactly the features, in the same order, that the plain procedure measures:
//! the cache saves computation, never sensing. `tests/classify.rs` checks this feature
//! for feature against [`Classify::classify_plain`].
//!
//! # The free view
//!
//! [`Classify::lookup`] tells which description a state belongs to, without charging and
//! without creating anything: the oracle's view, used to judge the representation at the
//! end of a trial (it walks the same tree, reading the state for free).

mod cache;

use cslearn::{Attend, Attention, Cost, FeatureId, InfoCost, MissingRule, RuleAttending};
use mdp::{Feature, Reading, SensorNoise, Sensors, StateId};
use qlearn::{QTable, RowId};
use rand::Rng;
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::{Deserialize, Serialize};

use self::cache::{Cache, Step};
use crate::perception::representation::{DescriptionId, Representation, feature_id, value_of};
use crate::perception::rows::Perception;
use crate::perception::sensor::SensorModel;
use crate::perception::tree::StateTree;
use crate::perception::view::{Describes, Sees};

/// How a description is matched to a state.
///
/// ```
/// let m: csql::Matching = serde_json::from_str("\"nearest\"").unwrap();
/// assert_eq!(m, csql::Matching::Nearest);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Matching {
    /// CLASSIFY as the paper defines it: every feature of a description must match.
    #[default]
    Exact,
    /// When no description matches, take the one that differs from the state on exactly
    /// one feature (see [`crate::Classify::with_matching`]) instead of creating one.
    Nearest,
}

/// The result of one classification.
///
/// ```
/// use mdp::{FeatureSpace, GridWorld, Manhattan};
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
/// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
/// let out = csql::Classify::new(&sensed).classify_state(&sensed, world.states()[0]);
/// assert!(out.created && out.measured.is_empty());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Classification {
    /// The description returned.
    pub description: DescriptionId,
    /// Whether it was created by this call.
    pub created: bool,
    /// The features measured, in order, with the values read.
    pub measured: Vec<(Feature, Reading)>,
    /// Their summed cost.
    pub cost: f64,
}

/// The most readings a feature may have for CLASSIFY to use its cache: the cache keeps, at
/// every node, a child per reading and a count per reading of every feature, so its size
/// follows the largest reading of any feature. In a world with more (a feature reading
/// large numbers), CLASSIFY runs the plain procedure, whose memory follows what is
/// sensed; it measures the same features and finds the same descriptions, only slower.
///
/// ```
/// assert_eq!(csql::CACHE_MAX_READINGS, 64);
/// ```
pub const CACHE_MAX_READINGS: u32 = 64;

/// The CLASSIFY perception of CS-QL: the representation, the selection part and the
/// cache.
///
/// ```
/// use csql::Classify;
/// use mdp::{FeatureSpace, GridWorld, Manhattan};
/// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
/// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
/// let mut c = Classify::new(&sensed);
/// // The first call on an empty representation creates the empty description, for free.
/// let first = c.classify_state(&sensed, world.states()[0]);
/// assert!(first.created && first.cost == 0.0);
/// // It matches every state.
/// let again = c.classify_state(&sensed, world.states()[5]);
/// assert_eq!((again.description, again.created), (first.description, false));
/// ```
#[derive(Clone, Debug)]
pub struct Classify {
    prices: Vec<f64>,
    costs: Vec<Cost>,
    rep: Representation,
    select: InfoCost,
    attention: Attention,
    measured: Vec<(Feature, Reading)>,
    /// What the free view reads (never charged, never part of a classification).
    probe: Vec<(Feature, Reading)>,
    cache: Cache,
    use_cache: bool,
    /// Whether the world's features have few enough readings for the cache
    /// ([`CACHE_MAX_READINGS`]); if not, the plain procedure runs whatever
    /// [`Classify::with_cache`] asks.
    cache_fits: bool,
    /// What the learner's sensors make of the world's readings, and how many reads each
    /// measurement is charged for.
    sensor: SensorModel,
    matching: Matching,
    /// Sightings of a measurement before it makes a new description (1: at once, the
    /// paper's CLASSIFY), and the unmatched measurements seen so far.
    confirm: u32,
    sightings: std::collections::BTreeMap<Vec<(Feature, Reading)>, u32>,
}

impl Classify {
    /// CLASSIFY over an empty representation, with the cache on.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// assert!(csql::Classify::new(&sensed).representation().is_empty());
    /// ```
    pub fn new<W: Sensors + ?Sized>(world: &W) -> Classify {
        Classify::with_representation(world, Representation::default())
    }

    /// CLASSIFY over a given representation (for learning on a fixed one).
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut rep = csql::Representation::default();
    /// rep.push(&[]);
    /// assert_eq!(csql::Classify::with_representation(&sensed, rep).representation().len(), 1);
    /// ```
    pub fn with_representation<W: Sensors + ?Sized>(world: &W, rep: Representation) -> Classify {
        let features = (0..world.num_features() as u32).map(Feature);
        let prices: Vec<f64> = features.clone().map(|f| world.price(f)).collect();
        let costs = prices
            .iter()
            .map(|&c| Cost::new(c).expect("worlds hold valid prices"))
            .collect();
        let most = features.map(|f| world.readings(f)).max().unwrap_or(1);
        let cache_fits = most <= CACHE_MAX_READINGS;
        Classify {
            cache: Cache::new(if cache_fits { most } else { 1 }),
            prices,
            costs,
            rep,
            select: InfoCost::new(MissingRule::C45),
            attention: Attention::new(),
            measured: Vec::new(),
            probe: Vec::new(),
            use_cache: cache_fits,
            cache_fits,
            sensor: SensorModel::exact(),
            matching: Matching::Exact,
            confirm: 1,
            sightings: std::collections::BTreeMap::new(),
        }
    }

    /// Sensors that misread with probability `noise` (a wrong reading is charged like a
    /// right one), their errors drawn from `rng`. The free view ([`Classify::lookup`])
    /// stays exact: it is the oracle's.
    ///
    /// ```
    /// use mdp::{FeatureSpace, GridWorld, Manhattan, SensorNoise};
    /// use rand::SeedableRng;
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
    /// let mut c = csql::Classify::new(&sensed).with_noise(SensorNoise::new(1.0).unwrap(), rng);
    /// let s = world.states()[0];
    /// let d = c.classify_state(&sensed, s).description;
    /// c.add_feature(&sensed, d, s);
    /// // Every reading is wrong, so the state does not match its own description.
    /// assert_eq!(c.lookup(&sensed, s), None);
    /// ```
    pub fn with_noise(self, noise: SensorNoise, rng: Xoshiro256PlusPlus) -> Classify {
        let reads = self.sensor.reads();
        self.with_sensor(SensorModel::noisy(noise, rng).with_reads(reads))
    }

    /// Read every measurement through `sensor` (exact by default): what
    /// [`Classify::with_noise`] and [`Classify::with_reads`] set.
    ///
    /// ```
    /// use rand::SeedableRng;
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
    /// let sensor = csql::SensorModel::noisy(mdp::SensorNoise::new(0.1).unwrap(), rng).with_reads(3);
    /// let c = csql::Classify::new(&sensed).with_sensor(sensor);
    /// assert_eq!(c.sensor().reads(), 3);
    /// ```
    pub fn with_sensor(mut self, sensor: SensorModel) -> Classify {
        self.sensor = sensor;
        self
    }

    /// The learner's sensors.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// assert!(csql::Classify::new(&sensed).sensor().is_exact());
    /// ```
    pub fn sensor(&self) -> &SensorModel {
        &self.sensor
    }

    /// How descriptions are matched. With [`Matching::Nearest`], when no description
    /// matches a state, CLASSIFY takes, before creating one, the first description (in
    /// id order) of at least three features that differs from the state on exactly one
    /// of them, measuring (and charging) the features it lacks to find out: the
    /// nearest-neighbour match of CS-IBL (the paper's suggestion for bounded noise) with
    /// a distance of one, so that one misread value does not make a new description.
    ///
    /// ```
    /// use mdp::{Cell, Feature, FeatureSpace, GridWorld, Manhattan, Pos, Reading, Sensors};
    /// let world = GridWorld::new(&mdp::builtin("tan8x8").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let s = world.state_at(Pos::new(7, 0)).unwrap();
    /// let mut rep = csql::Representation::default();
    /// let truth: Vec<_> = (0..4).map(|f| (Feature(f), sensed.read(s, Feature(f)))).collect();
    /// let mut wrong = truth.clone();
    /// let [empty, wall] = [Cell::Empty, Cell::Obstacle].map(Reading::from);
    /// wrong[3].1 = if wrong[3].1 == empty { wall } else { empty };
    /// rep.push(&wrong);
    /// let mut exact = csql::Classify::with_representation(&sensed, rep.clone());
    /// assert!(exact.classify_state(&sensed, s).created);
    /// let mut near = csql::Classify::with_representation(&sensed, rep).with_matching(csql::Matching::Nearest);
    /// assert!(!near.classify_state(&sensed, s).created);
    /// ```
    pub fn with_matching(mut self, matching: Matching) -> Classify {
        self.matching = matching;
        self
    }

    /// Create a description only for a measurement that matched nothing `sightings` times
    /// (the same features with the same values); until then the state is given the
    /// closest description (see [`Classify::closest`]). 1, the default, creates at once,
    /// as the paper's CLASSIFY does. A misread measurement seldom repeats, while a state
    /// that no description covers yields the same measurement at every visit: under
    /// sensor noise this keeps misreadings from becoming descriptions (the run setting
    /// `extensions.confirm_new`). With no description yet, the first one is made at once.
    ///
    /// ```
    /// use mdp::{Cell, Feature, FeatureSpace, GridWorld, Manhattan, Reading};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut rep = csql::Representation::default();
    /// rep.push(&[(Feature(0), Reading::from(Cell::Obstacle))]); // a wall above
    /// let mut c = csql::Classify::with_representation(&sensed, rep).with_confirmation(2);
    /// let below = world.state_at(mdp::Pos::new(1, 0)).unwrap();
    /// // The first sighting of "no wall above" takes the closest description...
    /// assert!(!c.classify_state(&sensed, below).created);
    /// // ...the second makes one.
    /// assert!(c.classify_state(&sensed, below).created);
    /// ```
    pub fn with_confirmation(mut self, sightings: u32) -> Classify {
        self.confirm = sightings.max(1);
        self
    }

    /// Read every measured feature `reads` times and take the value read most often
    /// ([`mdp::SensorNoise::majority`]); each read is charged, so every cost of a
    /// classification is multiplied by `reads`. 1, the default, is the paper's sensing
    /// (the run setting `extensions.reads`).
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut c = csql::Classify::new(&sensed).with_reads(3);
    /// let s = world.states()[0];
    /// let d = c.classify_state(&sensed, s).description;
    /// assert_eq!(c.add_feature(&sensed, d, s), Some(3.0)); // a feature of cost 1, read three times
    /// ```
    pub fn with_reads(mut self, reads: u32) -> Classify {
        self.sensor = self.sensor.with_reads(reads);
        self
    }

    /// The description that agrees best with a measurement: the most features with the
    /// measured value less those with another value (features not measured count for
    /// neither); ties go to the lowest id. `None` with no description.
    ///
    /// ```
    /// use mdp::{Cell, Feature, FeatureSpace, Manhattan, Reading};
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut rep = csql::Representation::default();
    /// rep.push(&[(Feature(0), Reading::from(Cell::Obstacle)), (Feature(1), Reading::from(Cell::Empty))]);
    /// rep.push(&[(Feature(0), Reading::from(Cell::Empty)), (Feature(1), Reading::from(Cell::Empty))]);
    /// let c = csql::Classify::with_representation(&sensed, rep);
    /// let seen = [(Feature(0), Reading::from(Cell::Empty)), (Feature(1), Reading::from(Cell::Obstacle))];
    /// assert_eq!(c.closest(&seen), Some(csql::DescriptionId(1)));
    /// ```
    pub fn closest(&self, measured: &[(Feature, Reading)]) -> Option<DescriptionId> {
        let score = |d: crate::Description<'_>| -> i64 {
            d.features()
                .map(|(f, v)| match measured.iter().find(|(m, _)| *m == f) {
                    Some(&(_, x)) if x == v => 1,
                    Some(_) => -1,
                    None => 0,
                })
                .sum()
        };
        let mut best: Option<(i64, DescriptionId)> = None;
        for (id, d) in self.rep.iter() {
            let sc = score(d);
            if best.is_none_or(|(b, _)| sc > b) {
                best = Some((sc, id));
            }
        }
        best.map(|(_, id)| id)
    }

    /// Nearest matching (see [`Classify::with_matching`]): after the walk found no
    /// description, the first one at distance one from the state, if any.
    fn nearest<W: Sensors + ?Sized>(&mut self, world: &W, s: StateId) -> Option<DescriptionId> {
        let ids: Vec<DescriptionId> = self
            .rep
            .iter()
            .filter(|(_, d)| d.len() >= 3 && self.mismatches(*d) == 1)
            .map(|(id, _)| id)
            .collect();
        for id in ids {
            let missing: Vec<Feature> = self
                .rep
                .get(id)
                .features()
                .map(|(f, _)| f)
                .filter(|f| !self.measured.iter().any(|(m, _)| m == f))
                .collect();
            for f in missing {
                let v = self.sensor.read(world, s, f);
                self.measured.push((f, v));
                if self.mismatches(self.rep.get(id)) > 1 {
                    break;
                }
            }
            if self.mismatches(self.rep.get(id)) == 1 {
                return Some(id);
            }
        }
        None
    }

    /// How many of a description's features were measured in this call with another
    /// value.
    fn mismatches(&self, d: crate::Description<'_>) -> usize {
        d.features()
            .filter(|&(f, v)| self.measured.iter().any(|&(m, x)| m == f && x != v))
            .count()
    }

    /// Turn the cache off (every call runs the plain procedure) or on. It stays off for a
    /// world with a feature of more than [`CACHE_MAX_READINGS`] readings. Either way
    /// CLASSIFY measures the same features and finds the same descriptions.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let c = csql::Classify::new(&sensed).with_cache(false);
    /// ```
    pub fn with_cache(mut self, on: bool) -> Classify {
        self.use_cache = on && self.cache_fits;
        self
    }

    /// The representation.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// assert_eq!(csql::Classify::new(&sensed).representation().len(), 0);
    /// ```
    pub fn representation(&self) -> &Representation {
        &self.rep
    }

    /// Give up the representation.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// assert!(csql::Classify::new(&sensed).into_representation().is_empty());
    /// ```
    pub fn into_representation(self) -> Representation {
        self.rep
    }

    /// The feature space.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// assert_eq!(csql::Classify::new(&sensed).prices().len(), 80);
    /// ```
    pub fn prices(&self) -> &[f64] {
        &self.prices
    }

    /// Classify a state, creating a description if none matches; every measurement is
    /// charged. Uses the cache unless it is off.
    ///
    /// ```
    /// use mdp::{FeatureSpace, GridWorld, Manhattan};
    /// let world = GridWorld::new(&mdp::builtin("tan8x8").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut c = csql::Classify::new(&sensed);
    /// let s = world.states()[0];
    /// assert_eq!(c.classify_state(&sensed, s).description.0, 0);
    /// ```
    pub fn classify_state<W: Sensors + ?Sized>(&mut self, world: &W, s: StateId) -> Classification {
        let (d, created) = self.classify_quietly(world, s);
        self.report(d, created)
    }

    /// Classify without building a [`Classification`]: the hot path of the main loop, which
    /// allocates nothing once the cache is warm. The measured features stay in
    /// `self.measured`.
    pub(crate) fn classify_quietly<W: Sensors + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
    ) -> (DescriptionId, bool) {
        let found = if self.use_cache {
            self.walk_cached(world, s)
        } else {
            self.walk_plain(world, s)
        };
        let found = match found {
            None if self.matching == Matching::Nearest => self.nearest(world, s),
            found => found,
        };
        self.settle(found)
    }

    /// The plain procedure of Figure 3, step by step, with no cache: the reference the
    /// cached path is tested against.
    ///
    /// ```
    /// use mdp::{Cell, Feature, FeatureSpace, GridWorld, Manhattan, Pos, Reading};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut rep = csql::Representation::default();
    /// rep.push(&[(Feature(0), Reading::from(Cell::Obstacle))]); // a wall above
    /// let mut c = csql::Classify::with_representation(&sensed, rep);
    /// let below = world.state_at(Pos::new(1, 0)).unwrap();
    /// let out = c.classify_plain(&sensed, below);
    /// // It measures "up", finds no wall, and creates a description for it.
    /// assert_eq!(out.measured, vec![(Feature(0), Reading::from(Cell::Empty))]);
    /// assert!(out.created && out.cost == 1.0);
    /// ```
    pub fn classify_plain<W: Sensors + ?Sized>(&mut self, world: &W, s: StateId) -> Classification {
        let found = self.walk_plain(world, s);
        let (d, created) = self.settle(found);
        self.report(d, created)
    }

    /// Run the plain procedure until it finds a description (`Some`) or decides to create
    /// one (`None`).
    fn walk_plain<W: Sensors + ?Sized>(&mut self, world: &W, s: StateId) -> Option<DescriptionId> {
        self.measured.clear();
        RuleAttending.start(self.rep.library(), &mut self.attention);
        loop {
            match self.decide() {
                Step::Found(d) => return Some(d),
                Step::Create => return None,
                Step::Measure(f) => self.measure_and_attend(world, s, f),
            }
        }
    }

    /// Measure feature `f` on state `s` (charged) and drop the candidates it rules out.
    fn measure_and_attend<W: Sensors + ?Sized>(&mut self, world: &W, s: StateId, f: Feature) {
        let v = self.sensor.read(world, s, f);
        self.measured.push((f, v));
        RuleAttending.attend(
            self.rep.library(),
            feature_id(f),
            Some(value_of(v)),
            &mut self.attention,
        );
    }

    /// Whether state `s` matches description `d`, measuring (charged, in
    /// [`Classify::last_measured`]) its features in order until one differs.
    ///
    /// ```
    /// use mdp::{Cell, Feature, FeatureSpace, GridWorld, Manhattan, Pos, Reading};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut rep = csql::Representation::default();
    /// let wall = rep.push(&[(Feature(0), Reading::from(Cell::Obstacle))]);
    /// let mut c = csql::Classify::with_representation(&sensed, rep);
    /// let below = world.state_at(Pos::new(1, 0)).unwrap();
    /// assert!(!c.matches(&sensed, below, wall));
    /// assert_eq!(c.last_measured().len(), 1);
    /// ```
    pub fn matches<W: Sensors + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        d: DescriptionId,
    ) -> bool {
        self.measured.clear();
        let wanted: Vec<(Feature, Reading)> = self.rep.get(d).features().collect();
        for (f, want) in wanted {
            let v = self.sensor.read(world, s, f);
            self.measured.push((f, v));
            if v != want {
                return false;
            }
        }
        true
    }

    /// Which of `candidates` state `s` matches, measuring (charged, in
    /// [`Classify::last_measured`]) only what tells them apart, by the same I^2/C rule as
    /// CLASSIFY restricted to them; `None` if `s` matches none of them. The one candidate
    /// left is returned without measuring the rest of its features: this trusts that `s`
    /// matches one of them (navigation on the reduced map, see [`crate::Predicting`]).
    ///
    /// ```
    /// use mdp::{Cell, Feature, FeatureSpace, GridWorld, Manhattan, Pos, Reading};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut rep = csql::Representation::default();
    /// let wall = rep.push(&[(Feature(0), Reading::from(Cell::Obstacle)), (Feature(1), Reading::from(Cell::Empty))]);
    /// let open = rep.push(&[(Feature(0), Reading::from(Cell::Empty)), (Feature(1), Reading::from(Cell::Empty))]);
    /// let mut c = csql::Classify::with_representation(&sensed, rep);
    /// let below = world.state_at(Pos::new(1, 0)).unwrap();
    /// // One feature ("up") tells the two apart.
    /// assert_eq!(c.classify_among(&sensed, below, &[wall, open]), Some(open));
    /// assert_eq!(c.last_measured(), [(Feature(0), Reading::from(Cell::Empty))]);
    /// ```
    pub fn classify_among<W: Sensors + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        candidates: &[DescriptionId],
    ) -> Option<DescriptionId> {
        self.measured.clear();
        RuleAttending.start(self.rep.library(), &mut self.attention);
        self.attention
            .retain(|i| candidates.iter().any(|d| d.0 as usize == i));
        loop {
            let step = match *self.attention.attended() {
                [] => return None,
                [only] => return Some(DescriptionId(only as u32)),
                _ => self.select_next(),
            };
            match step {
                Step::Found(d) => return Some(d),
                Step::Create => return None,
                Step::Measure(f) => self.measure_and_attend(world, s, f),
            }
        }
    }

    /// Step 2's ending: the description found, or a new one made of the features
    /// measured (library updating); whether it was created.
    fn settle(&mut self, found: Option<DescriptionId>) -> (DescriptionId, bool) {
        match found {
            Some(d) => (d, false),
            None if self.confirm > 1 && !self.rep.is_empty() => {
                let seen = self.sightings.entry(self.measured.clone()).or_insert(0);
                *seen += 1;
                if *seen < self.confirm {
                    let d = self
                        .closest(&self.measured)
                        .expect("there is a description");
                    return (d, false);
                }
                self.sightings.remove(&self.measured);
                let d = self.rep.push(&self.measured);
                self.cache.on_push(self.rep.library(), d);
                (d, true)
            }
            None => {
                let d = self.rep.push(&self.measured);
                self.cache.on_push(self.rep.library(), d);
                (d, true)
            }
        }
    }

    /// The features measured by the last classification, in order, with their values.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut c = csql::Classify::new(&sensed);
    /// c.classify_state(&sensed, world.states()[0]);
    /// assert!(c.last_measured().is_empty()); // the first description is the empty one
    /// ```
    pub fn last_measured(&self) -> &[(Feature, Reading)] {
        &self.measured
    }

    /// The summed cost of [`Classify::last_measured`]: what the last classification
    /// charged.
    ///
    /// ```
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut c = csql::Classify::new(&sensed);
    /// let out = c.classify_state(&sensed, world.states()[0]);
    /// assert_eq!(c.last_cost(), out.cost);
    /// ```
    pub fn last_cost(&self) -> f64 {
        charge(&self.prices, &self.measured, &self.sensor)
    }

    /// Step 2 and 3 for the current attended candidates and measured features.
    fn decide(&mut self) -> Step {
        match *self.attention.attended() {
            [] => Step::Create,
            [only] => {
                let d = &self.rep.library().examples()[only];
                let all_measured = d
                    .pairs()
                    .iter()
                    .all(|&(f, _)| self.measured.iter().any(|&(m, _)| feature_id(m) == f));
                if all_measured {
                    Step::Found(DescriptionId(only as u32))
                } else {
                    self.select_next()
                }
            }
            _ => self.select_next(),
        }
    }

    fn select_next(&mut self) -> Step {
        let library = self.rep.library();
        let measured = &self.measured;
        let pick = self.select.select_from(
            self.attention
                .attended()
                .iter()
                .map(|&i| &library.examples()[i]),
            |f: FeatureId| measured.iter().any(|&(m, _)| feature_id(m) == f),
            &self.costs[..],
        );
        match pick {
            Some(f) => Step::Measure(Feature(f.0)),
            // Candidates that are all fully measured and matched would all match the
            // state; descriptions are pairwise disjoint, so at most one can remain.
            None => Step::Found(DescriptionId(self.attention.attended()[0] as u32)),
        }
    }

    fn report(&self, d: DescriptionId, created: bool) -> Classification {
        Classification {
            description: d,
            created,
            cost: self.last_cost(),
            measured: self.measured.clone(),
        }
    }

    /// The cached path: walk the decision tree of the procedure, growing it where no
    /// classification has been before.
    fn walk_cached<W: Sensors + ?Sized>(&mut self, world: &W, s: StateId) -> Option<DescriptionId> {
        let tree = (&mut self.cache, &self.rep, &self.costs[..]);
        walk(tree, &mut self.measured, world, s, &mut self.sensor)
    }

    /// The description state `s` belongs to, found without charging and without adding a
    /// description (`None` if CLASSIFY would create one): the oracle's view. The answer
    /// is what [`Classify::classify_state`] would return if the state matches a
    /// description.
    ///
    /// ```
    /// use mdp::{FeatureSpace, GridWorld, Manhattan};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut c = csql::Classify::new(&sensed);
    /// let s = world.states()[0];
    /// assert_eq!(c.lookup(&sensed, s), None); // nothing yet, and nothing is created
    /// let d = c.classify_state(&sensed, s).description;
    /// assert_eq!(c.lookup(&sensed, s), Some(d));
    /// assert_eq!(c.representation().len(), 1);
    /// ```
    pub fn lookup<W: Sensors + ?Sized>(&mut self, world: &W, s: StateId) -> Option<DescriptionId> {
        if self.use_cache {
            self.walk_free(world, s)
        } else {
            self.rep.matching(world, s)
        }
    }

    /// The description state `s` belongs to as the agent's noisy sensors see it, without
    /// charging and without adding a description (`None` if CLASSIFY would create one);
    /// errors are drawn from `rng`, not from the learner's sensors. Used to evaluate the
    /// learned policy under sensor noise.
    ///
    /// ```
    /// use mdp::{FeatureSpace, GridWorld, Manhattan, SensorNoise};
    /// use rand::SeedableRng;
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut c = csql::Classify::new(&sensed);
    /// let s = world.states()[0];
    /// let d = c.classify_state(&sensed, s).description;
    /// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(2);
    /// assert_eq!(c.lookup_noisy(&sensed, s, SensorNoise::new(0.5).unwrap(), &mut rng), Some(d));
    /// ```
    pub fn lookup_noisy<W: Sensors + ?Sized, R: rand::Rng + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        noise: SensorNoise,
        rng: &mut R,
    ) -> Option<DescriptionId> {
        // The learner's number of reads, with the evaluation's noise and generator.
        let mut sensor = SensorModel::noisy(noise, rng).with_reads(self.sensor.reads());
        let found = if self.use_cache {
            let tree = (&mut self.cache, &self.rep, &self.costs[..]);
            walk(tree, &mut self.probe, world, s, &mut sensor)
        } else {
            self.probe_plain(world, s, &mut sensor)
        };
        if found.is_some() {
            return found;
        }
        if self.matching == Matching::Exact {
            // A measurement seen for the first time takes the closest description when
            // new ones need confirming.
            return if self.confirm > 1 {
                self.closest(&self.probe)
            } else {
                None
            };
        }
        // Nearest matching, read for free.
        let measured = &self.probe;
        let near = self.rep.iter().find_map(|(id, d)| {
            if d.len() < 3 {
                return None;
            }
            let wrong = d
                .features()
                .filter(|&(f, v)| {
                    let x = measured
                        .iter()
                        .find(|(m, _)| *m == f)
                        .map_or_else(|| sensor.read(world, s, f), |p| p.1);
                    x != v
                })
                .count();
            (wrong == 1).then_some(id)
        });
        near.or_else(|| {
            (self.confirm > 1)
                .then(|| self.closest(&self.probe))
                .flatten()
        })
    }

    /// What classifying state `s` would charge now with exact sensors (the features the
    /// procedure measures on its way), without charging or creating anything.
    ///
    /// ```
    /// use mdp::{FeatureSpace, GridWorld, Manhattan};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut c = csql::Classify::new(&sensed);
    /// let s = world.states()[0];
    /// let d = c.classify_state(&sensed, s).description;
    /// c.add_feature(&sensed, d, s);
    /// assert_eq!(c.lookup_cost(&sensed, s), 1.0);
    /// ```
    pub fn lookup_cost<W: Sensors + ?Sized>(&mut self, world: &W, s: StateId) -> f64 {
        self.walk_free(world, s);
        charge(&self.prices, &self.probe, &self.sensor)
    }

    /// The cached walk for `s` read exactly and for free into `probe`: the oracle's view.
    fn walk_free<W: Sensors + ?Sized>(&mut self, world: &W, s: StateId) -> Option<DescriptionId> {
        if !self.use_cache {
            return self.probe_plain(world, s, &mut SensorModel::<Exact>::exact());
        }
        let tree = (&mut self.cache, &self.rep, &self.costs[..]);
        walk(
            tree,
            &mut self.probe,
            world,
            s,
            &mut SensorModel::<Exact>::exact(),
        )
    }

    /// The plain procedure for `s` read through `sensor` into `probe`, without charging
    /// and without adding a description: what the cached walk of the free views finds,
    /// when the cache is off.
    fn probe_plain<W: Sensors + ?Sized, G: Rng>(
        &mut self,
        world: &W,
        s: StateId,
        sensor: &mut SensorModel<G>,
    ) -> Option<DescriptionId> {
        // The procedure reads what it measured from `measured`: the probe takes its place
        // for the walk, and the classification's measurements are kept aside.
        std::mem::swap(&mut self.measured, &mut self.probe);
        self.measured.clear();
        RuleAttending.start(self.rep.library(), &mut self.attention);
        let found = loop {
            match self.decide() {
                Step::Found(d) => break Some(d),
                Step::Create => break None,
                Step::Measure(f) => {
                    let v = sensor.read(world, s, f);
                    self.measured.push((f, v));
                    RuleAttending.attend(
                        self.rep.library(),
                        feature_id(f),
                        Some(value_of(v)),
                        &mut self.attention,
                    );
                }
            }
        };
        std::mem::swap(&mut self.measured, &mut self.probe);
        found
    }

    /// Add the next cheapest feature a description lacks, valued at state `s`; returns the
    /// feature's cost, or `None` if the description already has every feature.
    ///
    /// ```
    /// use mdp::{FeatureSpace, GridWorld, Manhattan};
    /// let world = GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = FeatureSpace::new(world.map(), &Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let mut c = csql::Classify::new(&sensed);
    /// let s = world.states()[0];
    /// let d = c.classify_state(&sensed, s).description;
    /// assert_eq!(c.add_feature(&sensed, d, s), Some(1.0));
    /// assert_eq!(c.representation().get(d).len(), 1);
    /// ```
    pub fn add_feature<W: Sensors + ?Sized>(
        &mut self,
        world: &W,
        d: DescriptionId,
        s: StateId,
    ) -> Option<f64> {
        let f = self.rep.get(d).next_missing(self.prices.len())?;
        let v = self.sensor.read(world, s, f);
        self.rep.refine(d, f, v);
        self.cache.on_refine(self.rep.library(), d, f, v);
        Some(self.prices[f.index()] * f64::from(self.sensor.reads()))
    }
}

/// The generator type of a sensor that is exact by construction (it is never drawn
/// from).
type Exact = Xoshiro256PlusPlus;

/// Walk CLASSIFY's cached tree for state `s`, reading through `sensor`, the features read
/// in `out`. Exact sensors hand the walk the world's own reading, so the hot path pays
/// nothing per read for them.
fn walk<W: Sensors + ?Sized, G: Rng>(
    (cache, rep, costs): (&mut Cache, &Representation, &[Cost]),
    out: &mut Vec<(Feature, Reading)>,
    world: &W,
    s: StateId,
    sensor: &mut SensorModel<G>,
) -> Option<DescriptionId> {
    match sensor {
        SensorModel::Exact { .. } => cache.walk(rep.library(), costs, out, |f| world.read(s, f)),
        noisy => cache.walk(rep.library(), costs, out, |f| noisy.read(world, s, f)),
    }
}

/// What measuring `measured` through `sensor` charges: each feature's price, once per
/// read.
fn charge<G>(prices: &[f64], measured: &[(Feature, Reading)], sensor: &SensorModel<G>) -> f64 {
    let once: f64 = measured.iter().map(|&(f, _)| prices[f.index()]).sum();
    once * f64::from(sensor.reads())
}

impl Perception for Classify {
    fn classify<W: Sensors + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        table: &mut QTable,
    ) -> (RowId, f64) {
        let (d, created) = self.classify_quietly(world, s);
        if created {
            let row = table.add_row();
            debug_assert_eq!(row, d.row());
        }
        (d.row(), self.last_cost())
    }

    fn refine<W: Sensors + ?Sized>(&mut self, world: &W, row: RowId, s: StateId) -> Option<f64> {
        self.add_feature(world, DescriptionId(row.0), s)
    }

    fn rows(&self) -> usize {
        self.rep.len()
    }

    fn lookup<W: Sensors + ?Sized>(&mut self, world: &W, s: StateId) -> Option<RowId> {
        Classify::lookup(self, world, s).map(DescriptionId::row)
    }
}

impl Sees for Classify {
    fn sees<W: mdp::World + ?Sized, R: rand::Rng + ?Sized>(
        &mut self,
        world: &W,
        s: StateId,
        noise: SensorNoise,
        rng: &mut R,
    ) -> Option<RowId> {
        self.lookup_noisy(world, s, noise, rng).map(|d| d.row())
    }
}

impl Describes for Classify {
    fn described(&self) -> Vec<(qlearn::RowId, Vec<(mdp::Feature, Reading)>)> {
        self.representation()
            .iter()
            .map(|(id, d)| (id.row(), d.features().collect()))
            .collect()
    }
    fn cost_after_learning<W: mdp::World + ?Sized>(&mut self, world: &W, s: mdp::StateId) -> f64 {
        self.lookup_cost(world, s)
    }
    fn table1_costs<W: mdp::World + ?Sized>(&mut self, world: &W) -> (f64, f64) {
        let states = world.states();
        let rep = self.representation();
        let tree = StateTree::build(rep, self.prices());
        let costs: Vec<f64> = states.iter().map(|&s| tree.classify(world, s).1).collect();
        let tree_cost = costs.iter().sum::<f64>() / states.len() as f64;
        let labels: Vec<Option<DescriptionId>> =
            states.iter().map(|&s| self.lookup(world, s)).collect();
        let rep = self.representation();
        let plain: f64 = labels
            .iter()
            .flatten()
            .map(|&l| rep.get(l).cost(world))
            .sum();
        (tree_cost, plain / states.len() as f64)
    }
}
