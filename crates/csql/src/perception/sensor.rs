//! What a learner's sensors do to the world's exact reading.
//!
//! The world's truth is exact ([`mdp::Sensors::read`]); errors and repeated reads belong
//! to the sensor. A [`SensorModel`] is exact (the truth, nothing drawn) or noisy (each read
//! misread with the probability of an [`mdp::SensorNoise`], its errors drawn from the
//! sensor's own generator), and reads each measured feature [`SensorModel::reads`] times, every
//! read charged. A perception holds one and reads through it ([`crate::Classify`],
//! [`crate::UTree`]); the free noisy views that evaluate a policy make one over the
//! evaluation's generator (`SensorModel<&mut R>`), so they never draw from the learner's.
//!
//! Not to be confused with [`cslearn::Sensor`], cslearn's measuring of one object.

use std::num::NonZeroU32;

use mdp::{Feature, Reading, SensorNoise, Sensors, StateId};
use rand::Rng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// A learner's sensors: how a measured feature's value comes out of the world's exact
/// reading, and how many reads each measurement is charged for. `G` is the generator
/// the errors are drawn from: the sensor's own, or a borrowed one (`&mut R`).
///
/// ```
/// use csql::SensorModel;
/// use mdp::{Feature, SensorNoise, Sensors};
/// use rand::SeedableRng;
/// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
/// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
/// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
/// let s = world.states()[0];
/// let truth = sensed.read(s, Feature(0));
/// // Exact sensors read the truth, however many times.
/// let mut exact: SensorModel = SensorModel::exact().with_reads(3);
/// assert_eq!((exact.read(&sensed, s, Feature(0)), exact.reads()), (truth, 3));
/// // Sensors that always misread never read the truth.
/// let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// let mut wrong = SensorModel::noisy(SensorNoise::new(1.0).unwrap(), rng);
/// assert_ne!(wrong.read(&sensed, s, Feature(0)), truth);
/// ```
#[derive(Clone, Debug)]
pub enum SensorModel<G = Xoshiro256PlusPlus> {
    /// The world's reading as it is; nothing is drawn, however many reads.
    Exact {
        /// Reads of each measured feature, each charged.
        reads: NonZeroU32,
    },
    /// Each read wrong with the probability of `noise`, the value read most often kept
    /// ([`SensorNoise::majority_reading`], with its draws from `rng`).
    Noisy {
        /// The probability that one read is wrong.
        noise: SensorNoise,
        /// Reads of each measured feature, each charged.
        reads: NonZeroU32,
        /// The generator the errors are drawn from.
        rng: G,
    },
}

impl<G> Default for SensorModel<G> {
    fn default() -> SensorModel<G> {
        SensorModel::exact()
    }
}

impl<G> SensorModel<G> {
    /// Exact sensors reading once: the paper's.
    ///
    /// ```
    /// assert_eq!(csql::SensorModel::<rand_xoshiro::Xoshiro256PlusPlus>::exact().reads(), 1);
    /// ```
    pub fn exact() -> SensorModel<G> {
        SensorModel::Exact {
            reads: NonZeroU32::MIN,
        }
    }

    /// Sensors that misread with probability `noise` (a wrong reading is charged like a
    /// right one), their errors drawn from `rng`, reading once. Noise 0 is exact (and
    /// `rng` is never drawn from, so it is not kept).
    ///
    /// ```
    /// use rand::SeedableRng;
    /// let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
    /// assert!(csql::SensorModel::noisy(mdp::SensorNoise::default(), rng).is_exact());
    /// ```
    pub fn noisy(noise: SensorNoise, rng: G) -> SensorModel<G> {
        if noise.is_zero() {
            return SensorModel::exact();
        }
        SensorModel::Noisy {
            noise,
            reads: NonZeroU32::MIN,
            rng,
        }
    }

    /// The same sensors reading each measured feature `reads` times (at least once) and
    /// keeping the value read most often; every read is charged.
    ///
    /// ```
    /// let s: csql::SensorModel = csql::SensorModel::exact().with_reads(0);
    /// assert_eq!(s.reads(), 1);
    /// ```
    pub fn with_reads(mut self, reads: u32) -> SensorModel<G> {
        let reads = NonZeroU32::new(reads).unwrap_or(NonZeroU32::MIN);
        match &mut self {
            SensorModel::Exact { reads: r } | SensorModel::Noisy { reads: r, .. } => *r = reads,
        }
        self
    }

    /// Reads of each measured feature: what a measurement is charged, in multiples of
    /// the feature's price.
    ///
    /// ```
    /// let s: csql::SensorModel = csql::SensorModel::exact().with_reads(5);
    /// assert_eq!(s.reads(), 5);
    /// ```
    pub fn reads(&self) -> u32 {
        match self {
            SensorModel::Exact { reads } | SensorModel::Noisy { reads, .. } => reads.get(),
        }
    }

    /// Whether the sensors read the truth (and never draw).
    ///
    /// ```
    /// assert!(csql::SensorModel::<rand_xoshiro::Xoshiro256PlusPlus>::exact().is_exact());
    /// ```
    pub fn is_exact(&self) -> bool {
        matches!(self, SensorModel::Exact { .. })
    }
}

impl<G: Rng> SensorModel<G> {
    /// What the sensors report for feature `f` of state `s`: the world's reading for
    /// exact sensors (nothing drawn), else the majority of [`SensorModel::reads`] noisy reads
    /// with the draws of [`SensorNoise::majority_reading`] (one read is
    /// [`SensorNoise::corrupt_reading`]).
    ///
    /// ```
    /// use mdp::{Feature, SensorNoise, Sensors};
    /// use rand::SeedableRng;
    /// let world = mdp::GridWorld::new(&mdp::builtin("tan3x3").unwrap());
    /// let space = mdp::FeatureSpace::new(world.map(), &mdp::Manhattan).unwrap();
    /// let sensed = mdp::SensedGrid::new(&world, &space, mdp::Slip::default());
    /// let s = world.states()[0];
    /// let noise = SensorNoise::new(0.3).unwrap();
    /// let mut a = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(4);
    /// let mut b = a.clone();
    /// // A sensor over a borrowed generator draws what the noise itself draws.
    /// let mut sensor = csql::SensorModel::noisy(noise, &mut a).with_reads(3);
    /// let read = sensor.read(&sensed, s, Feature(2));
    /// let truth = sensed.read(s, Feature(2));
    /// assert_eq!(read, noise.majority_reading(truth, sensed.readings(Feature(2)), 3, &mut b));
    /// ```
    #[inline]
    pub fn read<W: Sensors + ?Sized>(&mut self, world: &W, s: StateId, f: Feature) -> Reading {
        match self {
            SensorModel::Exact { .. } => world.read(s, f),
            SensorModel::Noisy { noise, reads, rng } => {
                noise.majority_reading(world.read(s, f), world.readings(f), reads.get(), rng)
            }
        }
    }
}
