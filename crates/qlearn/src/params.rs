//! Validated learning parameters and the paper's preset.
//!
//! Each parameter is a newtype that can only hold a valid value: constructors and
//! deserialisation go through the same check and return [`Error`] on a bad value, so a
//! settings file with `temperature = 0` is refused when it is read, not when the first
//! division by zero happens.

use std::fmt;
use std::num::NonZeroU32;

use serde::{Deserialize, Serialize};

use crate::error::Error;

/// The learning rate beta of equation 2, in `(0, 1]`.
///
/// ```
/// use qlearn::LearningRate;
/// assert_eq!(LearningRate::new(0.5).unwrap().get(), 0.5);
/// assert!(LearningRate::new(0.0).is_err());
/// assert!(LearningRate::new(1.5).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd, Serialize, Deserialize)]
#[serde(try_from = "f64", into = "f64")]
pub struct LearningRate(f64);

impl LearningRate {
    /// A learning rate, if `beta` is in `(0, 1]` (NaN is refused).
    ///
    /// ```
    /// assert!(qlearn::LearningRate::new(1.0).is_ok());
    /// assert!(qlearn::LearningRate::new(f64::NAN).is_err());
    /// ```
    pub fn new(beta: f64) -> Result<LearningRate, Error> {
        if beta > 0.0 && beta <= 1.0 {
            Ok(LearningRate(beta))
        } else {
            Err(Error::LearningRate { value: beta })
        }
    }

    /// The value.
    ///
    /// ```
    /// assert_eq!(qlearn::LearningRate::new(0.25).unwrap().get(), 0.25);
    /// ```
    #[inline]
    pub fn get(self) -> f64 {
        self.0
    }
}

/// The discount gamma of equation 2, in `[0, 1)`.
///
/// ```
/// use qlearn::Discount;
/// assert_eq!(Discount::new(0.9).unwrap().get(), 0.9);
/// assert!(Discount::new(1.0).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd, Serialize, Deserialize)]
#[serde(try_from = "f64", into = "f64")]
pub struct Discount(f64);

impl Discount {
    /// A discount, if `gamma` is in `[0, 1)` (NaN is refused).
    ///
    /// ```
    /// assert!(qlearn::Discount::new(0.0).is_ok());
    /// assert!(qlearn::Discount::new(-0.1).is_err());
    /// ```
    pub fn new(gamma: f64) -> Result<Discount, Error> {
        if (0.0..1.0).contains(&gamma) {
            Ok(Discount(gamma))
        } else {
            Err(Error::Discount { value: gamma })
        }
    }

    /// The value.
    ///
    /// ```
    /// assert_eq!(qlearn::Discount::new(0.5).unwrap().get(), 0.5);
    /// ```
    #[inline]
    pub fn get(self) -> f64 {
        self.0
    }
}

/// The Boltzmann temperature T of Figure 1, finite and greater than 0.
///
/// Any positive value is accepted, however small: selection subtracts the row maximum
/// before exponentiating, so `1e-6` is numerically safe and simply makes the choice
/// (almost) greedy.
///
/// ```
/// use qlearn::Temperature;
/// assert_eq!(Temperature::new(0.4).unwrap().get(), 0.4);
/// assert!(Temperature::new(0.0).is_err());
/// assert!(Temperature::new(f64::INFINITY).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd, Serialize, Deserialize)]
#[serde(try_from = "f64", into = "f64")]
pub struct Temperature(f64);

impl Temperature {
    /// A temperature, if `t` is finite and greater than 0.
    ///
    /// ```
    /// assert!(qlearn::Temperature::new(1e-6).is_ok());
    /// assert!(qlearn::Temperature::new(-1.0).is_err());
    /// ```
    pub fn new(t: f64) -> Result<Temperature, Error> {
        if t > 0.0 && t.is_finite() {
            Ok(Temperature(t))
        } else {
            Err(Error::Temperature { value: t })
        }
    }

    /// The value.
    ///
    /// ```
    /// assert_eq!(qlearn::Temperature::new(2.0).unwrap().get(), 2.0);
    /// ```
    #[inline]
    pub fn get(self) -> f64 {
        self.0
    }
}

/// The exploration rate epsilon of epsilon-greedy selection, in `[0, 1]`.
///
/// ```
/// use qlearn::Epsilon;
/// assert_eq!(Epsilon::new(0.1).unwrap().get(), 0.1);
/// assert!(Epsilon::new(1.1).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd, Serialize, Deserialize)]
#[serde(try_from = "f64", into = "f64")]
pub struct Epsilon(f64);

impl Epsilon {
    /// An exploration rate, if `epsilon` is in `[0, 1]` (NaN is refused).
    ///
    /// ```
    /// assert!(qlearn::Epsilon::new(0.0).is_ok());
    /// assert!(qlearn::Epsilon::new(f64::NAN).is_err());
    /// ```
    pub fn new(epsilon: f64) -> Result<Epsilon, Error> {
        if (0.0..=1.0).contains(&epsilon) {
            Ok(Epsilon(epsilon))
        } else {
            Err(Error::Epsilon { value: epsilon })
        }
    }

    /// The value.
    ///
    /// ```
    /// assert_eq!(qlearn::Epsilon::new(0.2).unwrap().get(), 0.2);
    /// ```
    #[inline]
    pub fn get(self) -> f64 {
        self.0
    }
}

/// The most moves a trial may take before it is cut off (truncated), at least 1.
///
/// ```
/// use qlearn::MoveCap;
/// assert_eq!(MoveCap::new(100).unwrap().get(), 100);
/// assert!(MoveCap::new(0).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(try_from = "u64", into = "u64")]
pub struct MoveCap(NonZeroU32);

impl MoveCap {
    /// A move cap, if `moves` is in `1..=u32::MAX`.
    ///
    /// ```
    /// assert!(qlearn::MoveCap::new(u64::from(u32::MAX) + 1).is_err());
    /// ```
    pub fn new(moves: u64) -> Result<MoveCap, Error> {
        u32::try_from(moves)
            .ok()
            .and_then(NonZeroU32::new)
            .map(MoveCap)
            .ok_or(Error::MoveCap { value: moves })
    }

    /// The value.
    ///
    /// ```
    /// assert_eq!(qlearn::MoveCap::new(7).unwrap().get(), 7);
    /// ```
    #[inline]
    pub fn get(self) -> u32 {
        self.0.get()
    }
}

macro_rules! float_conversions {
    ($($ty:ident),*) => {$(
        impl TryFrom<f64> for $ty {
            type Error = Error;
            fn try_from(value: f64) -> Result<$ty, Error> {
                $ty::new(value)
            }
        }
        impl From<$ty> for f64 {
            fn from(value: $ty) -> f64 {
                value.0
            }
        }
        impl fmt::Display for $ty {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                fmt::Display::fmt(&self.0, f)
            }
        }
    )*};
}
float_conversions!(LearningRate, Discount, Temperature, Epsilon);

impl TryFrom<u64> for MoveCap {
    type Error = Error;
    fn try_from(value: u64) -> Result<MoveCap, Error> {
        MoveCap::new(value)
    }
}

impl From<MoveCap> for u64 {
    fn from(value: MoveCap) -> u64 {
        u64::from(value.get())
    }
}

impl fmt::Display for MoveCap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.0, f)
    }
}

/// The settings of plain Q-learning with Boltzmann selection in trials.
///
/// There is deliberately no `Default`: the paper's values are the named preset
/// [`Params::tan1991`], and any other choice is spelled out. Read from a file, unknown
/// keys and invalid values are refused.
///
/// ```
/// use qlearn::Params;
/// let p: Params = toml::from_str(
///     "learning_rate = 1.0\ndiscount = 0.9\ntemperature = 0.4\nmax_moves = 100",
/// ).unwrap();
/// assert_eq!(p, Params::tan1991());
/// assert!(toml::from_str::<Params>(
///     "learning_rate = 1.0\ndiscount = 0.9\ntemperature = 0.0\nmax_moves = 100",
/// ).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Params {
    /// Beta: how far one update moves `Q(x, a)` towards its target.
    #[serde(alias = "beta")]
    pub learning_rate: LearningRate,
    /// Gamma: the weight of the next state's utility in the target.
    #[serde(alias = "gamma")]
    pub discount: Discount,
    /// T: the randomness of Boltzmann selection.
    pub temperature: Temperature,
    /// The most moves in one trial; a trial cut off here bootstraps its last update.
    pub max_moves: MoveCap,
}

impl Params {
    /// The paper's settings (section "Experiments in a Navigation Domain"): beta 1,
    /// gamma 0.9, T 0.4, at most 100 moves per trial.
    ///
    /// ```
    /// let p = qlearn::Params::tan1991();
    /// assert_eq!(
    ///     (p.learning_rate.get(), p.discount.get(), p.temperature.get(), p.max_moves.get()),
    ///     (1.0, 0.9, 0.4, 100),
    /// );
    /// ```
    pub fn tan1991() -> Params {
        Params {
            learning_rate: LearningRate(1.0),
            discount: Discount(0.9),
            temperature: Temperature(0.4),
            max_moves: MoveCap(NonZeroU32::MIN.saturating_add(99)),
        }
    }
}
