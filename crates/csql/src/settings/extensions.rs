//! Settings beyond the paper, in two small groups that are off by default: the world's
//! departures from the paper's assumptions ([`WorldExtras`], for every learner) and
//! CS-QL's remedies ([`Extensions`], part of [`crate::CsQlSettings`]). At their defaults
//! neither is written into a run's JSON, so every default run is byte-identical to the
//! paper's procedure. The detector a run uses is one of CS-QL's remedies: its kind and
//! the rate test's parameters ([`DetectorKind`], [`RateParams`]) are settings here, the
//! detectors themselves the agent's; CLASSIFY is set from the remedies here too
//! (`Classify::with_extensions`).

use mdp::{SensorNoise, Slip};
use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::perception::classify::{Classify, Matching};

/// How the world departs from the paper's assumptions (specification §6): slippery moves, noisy
/// sensors, a sensing range; what a built-in world senses and its prices. All absent by
/// default. A key is given or not, whatever its value: given where the learner or the
/// world does not read it (`sensor_noise` with a learner on costed episodes, `slide` on a
/// grid map, `slip` on Taxi or on a world that carries its own dynamics, ...), it is
/// refused, at its default value as at any other.
///
/// ```
/// let mut s = csql::RunSettings::tan1991("tan8x8", csql::StrategyKind::Lazy, 1);
/// s.apply_toml("[world]\nslip = 0.1\nsensing_radius = 2", "x.toml").unwrap();
/// assert_eq!(s.world.slip(), mdp::Slip::new(0.1).unwrap());
/// assert!(!s.world.is_default());
/// // Given at 0, slip is given (and echoed), and moves as if it were absent.
/// s.apply_toml("[world]\nslip = 0.0", "x.toml").unwrap();
/// assert!(s.world.slip.is_some() && s.world.slip().is_zero() && !s.world.departs_from_the_paper());
/// ```
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WorldExtras {
    /// The probability that a move slips to a perpendicular direction (half each); 0
    /// when absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slip: Option<Slip>,
    /// The probability that a measurement reads one of the other conditions; 0 when
    /// absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sensor_noise: Option<SensorNoise>,
    /// The most a sensable feature may cost (with the paper's costs, the Manhattan
    /// distance; 1 means only the four neighbours). Unbounded when absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sensing_radius: Option<u32>,
    /// The probability that a move carries on one more cell in the same direction,
    /// unless the first cell ends the trial (built-in worlds beyond grid maps only:
    /// FrozenLake's "semi-slippery" lake has 0.5); 0 when absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slide: Option<Slip>,
    /// What the agent senses in a built-in world: `local` (the cells around it) or
    /// `factors` (the world's own state variables); the world's default when absent.
    /// Grid maps sense locally only, and refuse it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sensing: Option<mdp::SensingModel>,
    /// The price of each factor, in the world's factor order (`sensing = "factors"`
    /// only; 1 each when absent).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub factor_costs: Option<Vec<f64>>,
}

impl WorldExtras {
    /// Whether every setting of the world is at its default.
    ///
    /// ```
    /// assert!(csql::WorldExtras::default().is_default());
    /// ```
    pub fn is_default(&self) -> bool {
        *self == WorldExtras::default()
    }

    /// The probability that a move slips: `slip`, 0 where it is not given.
    ///
    /// ```
    /// assert!(csql::WorldExtras::default().slip().is_zero());
    /// ```
    pub fn slip(&self) -> Slip {
        self.slip.unwrap_or_default()
    }

    /// The probability that a move slides one more cell: `slide`, 0 where it is not
    /// given.
    ///
    /// ```
    /// assert!(csql::WorldExtras::default().slide().is_zero());
    /// ```
    pub fn slide(&self) -> Slip {
        self.slide.unwrap_or_default()
    }

    /// The probability that a measurement reads wrong: `sensor_noise`, 0 where it is not
    /// given.
    ///
    /// ```
    /// assert!(csql::WorldExtras::default().sensor_noise().is_zero());
    /// ```
    pub fn sensor_noise(&self) -> SensorNoise {
        self.sensor_noise.unwrap_or_default()
    }

    /// Whether the world departs from the paper's assumptions (slip, slide, noise, a
    /// sensing range), so that runs are judged by the policy quality. The choice of
    /// sensing model and of prices does not.
    ///
    /// ```
    /// let mut w = csql::WorldExtras::default();
    /// w.sensing = Some(mdp::SensingModel::Factors);
    /// assert!(!w.departs_from_the_paper());
    /// w.slide = Some(mdp::Slip::new(0.0).unwrap());
    /// assert!(!w.departs_from_the_paper());
    /// w.slide = Some(mdp::Slip::new(0.5).unwrap());
    /// assert!(w.departs_from_the_paper());
    /// ```
    pub fn departs_from_the_paper(&self) -> bool {
        !(self.slip().is_zero()
            && self.slide().is_zero()
            && self.sensor_noise().is_zero()
            && self.sensing_radius.is_none())
    }

    /// The options of a built-in world that these settings give (each given or not, as
    /// here).
    ///
    /// ```
    /// let mut w = csql::WorldExtras::default();
    /// assert_eq!(w.world_options().slip, None);
    /// w.slip = Some(mdp::Slip::new(0.2).unwrap());
    /// assert_eq!(w.world_options().slip, Some(0.2));
    /// ```
    pub fn world_options(&self) -> mdp::WorldOptions {
        mdp::WorldOptions {
            slip: self.slip.map(Slip::get),
            slide: self.slide.map(Slip::get),
            sensing: self.sensing,
            factor_costs: self.factor_costs.clone(),
        }
    }
}

/// CS-QL's remedies beyond the paper (specification §6), the keys of the TOML table
/// `[extensions]` (CS-QL only). All off by default.
///
/// ```
/// let mut s = csql::RunSettings::tan1991("tan8x8", csql::StrategyKind::Lazy, 1);
/// s.apply_toml("[extensions]\ndetector = \"statistical\"\nmatching = \"nearest\"", "x.toml").unwrap();
/// assert_eq!(s.cs_ql().unwrap().extensions.detector, csql::DetectorKind::Statistical);
/// assert!(s.apply_toml("[extensions]\nreads = 0", "x.toml").is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extensions {
    /// How an inconsistent description is recognised.
    pub detector: DetectorKind,
    /// The statistical detector's parameters.
    pub rate: RateParams,
    /// How CLASSIFY matches descriptions.
    pub matching: Matching,
    /// Sightings of an unmatched measurement before it becomes a new description (1: at
    /// once, the paper's CLASSIFY; see [`crate::Classify::with_confirmation`]). 1 to 16.
    pub confirm_new: u32,
    /// Reads of each measured feature, the majority taken, each charged (1: the paper's
    /// single read; see [`crate::Classify::with_reads`]). 1 to 9.
    pub reads: u32,
    /// Steps of history a description may use once its sensable features are exhausted
    /// (0: none, the paper's CLASSIFY; see [`crate::Remembering`]). At most 8.
    pub memory: u32,
}

impl Default for Extensions {
    fn default() -> Extensions {
        Extensions {
            detector: DetectorKind::Decrease,
            rate: RateParams::default(),
            matching: Matching::Exact,
            confirm_new: 1,
            reads: 1,
            memory: 0,
        }
    }
}

impl Extensions {
    /// Whether every extension is off.
    ///
    /// ```
    /// assert!(csql::Extensions::default().is_default());
    /// ```
    pub fn is_default(&self) -> bool {
        *self == Extensions::default()
    }

    pub(crate) fn validate(&self) -> Result<(), Error> {
        let bad = |name: &'static str, value: String, expected: &'static str| {
            Err(Error::InvalidSetting {
                value: format!("{name} = {value}"),
                expected,
            })
        };
        if !(1..=16).contains(&self.confirm_new) {
            return bad(
                "extensions.confirm_new",
                self.confirm_new.to_string(),
                "1 to 16",
            );
        }
        if !(1..=9).contains(&self.reads) {
            return bad("extensions.reads", self.reads.to_string(), "1 to 9");
        }
        if self.memory > 8 {
            return bad("extensions.memory", self.memory.to_string(), "0 to 8");
        }
        if !(1..=64).contains(&self.rate.window) {
            return bad(
                "extensions.rate.window",
                self.rate.window.to_string(),
                "1 to 64",
            );
        }
        if !(0.0..1.0).contains(&self.rate.rate) {
            return bad(
                "extensions.rate.rate",
                self.rate.rate.to_string(),
                "a number in [0, 1)",
            );
        }
        if !(0.0..1.0).contains(&self.rate.relative_drop) {
            return bad(
                "extensions.rate.relative_drop",
                self.rate.relative_drop.to_string(),
                "a number in [0, 1)",
            );
        }
        Ok(())
    }
}

/// Which detector a run uses (a setting; `"decrease"` is the paper's rule).
///
/// ```
/// let d: csql::DetectorKind = serde_json::from_str("\"statistical\"").unwrap();
/// assert_eq!(d, csql::DetectorKind::Statistical);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DetectorKind {
    /// [`crate::AnyDrop`].
    #[default]
    Decrease,
    /// [`crate::RateTest`].
    Statistical,
    /// [`crate::ActionDrop`].
    Action,
}

impl DetectorKind {
    /// The setting's value: `decrease`, `statistical` or `action`.
    ///
    /// ```
    /// assert_eq!(csql::DetectorKind::Statistical.name(), "statistical");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            DetectorKind::Decrease => "decrease",
            DetectorKind::Statistical => "statistical",
            DetectorKind::Action => "action",
        }
    }
}

/// The parameters of the [`crate::RateTest`] (`agent/detector.rs` gives its error rates).
///
/// ```
/// let p = csql::RateParams::default();
/// assert_eq!((p.window, p.rate, p.relative_drop), (20, 0.2, 0.005));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RateParams {
    /// Updates per description in the window.
    pub window: u32,
    /// Inconsistent when more than this share of the window were falls.
    pub rate: f64,
    /// A fall is a drop of V by more than this share of its value before.
    pub relative_drop: f64,
}

impl Default for RateParams {
    fn default() -> RateParams {
        RateParams {
            window: 20,
            rate: 0.2,
            relative_drop: 0.005,
        }
    }
}

impl Classify {
    /// CLASSIFY as CS-QL's extensions of a run set it: their matching, confirmation and
    /// repeated reads.
    pub(crate) fn with_extensions(self, e: &Extensions) -> Classify {
        self.with_matching(e.matching)
            .with_confirmation(e.confirm_new)
            .with_reads(e.reads)
    }
}
