//! The settings of sensing less: which knowledge lets the agent skip measurements
//! ([`PredictSensing`], the run setting `predict_sensing`) and the rates and rules of
//! `[prediction]` ([`PredictionParams`]). Depends only on the error type, so that the settings
//! can name them without knowing the perception that uses them.

use serde::{Deserialize, Serialize};

use crate::error::Error;

/// Which knowledge lets the agent skip measurements (the run setting `predict_sensing`).
///
/// ```
/// use csql::PredictSensing;
/// assert_eq!(PredictSensing::default(), PredictSensing::Off);
/// assert_eq!(PredictSensing::Motion.name(), "motion");
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase", try_from = "String")]
pub enum PredictSensing {
    /// Classify every next state (the paper's procedure; the default).
    #[default]
    Off,
    /// A learned model of (description, action) -> next description.
    Learned,
    /// The learned model, and features carried over by dead reckoning.
    Motion,
    /// The learned model with the frequencies of every next description: the agent
    /// skips a measurement when acting on its belief loses less than measuring costs at
    /// `[costly] price`, and otherwise measures only what tells the likely descriptions
    /// apart (see `docs/predict_sensing.md`). Spelled `belief` before; that spelling is
    /// refused with a pointer here, since `learner = "belief"` is another thing.
    Weighed,
}

impl PredictSensing {
    /// The four levels, in order.
    ///
    /// ```
    /// assert_eq!(csql::PredictSensing::ALL.len(), 4);
    /// ```
    pub const ALL: [PredictSensing; 4] = [
        PredictSensing::Off,
        PredictSensing::Learned,
        PredictSensing::Motion,
        PredictSensing::Weighed,
    ];

    /// The setting's value: `off`, `learned`, `motion` or `weighed`.
    ///
    /// ```
    /// assert_eq!(csql::PredictSensing::Learned.name(), "learned");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            PredictSensing::Off => "off",
            PredictSensing::Learned => "learned",
            PredictSensing::Motion => "motion",
            PredictSensing::Weighed => "weighed",
        }
    }

    /// Whether this is `off` (for serde's `skip_serializing_if`).
    ///
    /// ```
    /// assert!(csql::PredictSensing::Off.is_off());
    /// ```
    pub fn is_off(&self) -> bool {
        *self == PredictSensing::Off
    }
}

impl std::fmt::Display for PredictSensing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for PredictSensing {
    type Err = Error;
    fn from_str(s: &str) -> Result<PredictSensing, Error> {
        PredictSensing::ALL
            .into_iter()
            .find(|l| l.name() == s)
            .ok_or_else(|| Error::InvalidSetting {
                value: format!("predict_sensing = {s}"),
                expected: if s == "belief" {
                    "predict_sensing = \"weighed\", the new spelling of the level that weighs \
                     acting on the likely descriptions against measuring (learner = \"belief\" \
                     is the learner that plans over beliefs)"
                } else {
                    "one of off, learned, motion, weighed"
                },
            })
    }
}

/// A settings file's string, read as [`std::str::FromStr`] reads it, so that a file
/// and a flag are refused with the same words.
///
/// ```
/// let err = toml::from_str::<std::collections::BTreeMap<String, csql::PredictSensing>>(
///     "predict_sensing = \"belief\"",
/// )
/// .unwrap_err();
/// assert!(err.to_string().contains("predict_sensing = \"weighed\""), "{err}");
/// ```
impl TryFrom<String> for PredictSensing {
    type Error = Error;
    fn try_from(s: String) -> Result<PredictSensing, Error> {
        s.parse()
    }
}

/// The most evaluation trials of navigation from each state that a run may ask for
/// ([`PredictionParams::navigation_trials`]): navigation makes that many from every non-goal
/// state, each of up to `max_moves` moves.
///
/// ```
/// let p = csql::PredictionParams { navigation_trials: csql::MAX_NAVIGATION_TRIALS + 1, ..Default::default() };
/// assert!(p.validate().unwrap_err().to_string().contains("at most 10000"));
/// ```
pub const MAX_NAVIGATION_TRIALS: u32 = 10_000;

/// The confidence rule, the re-check rates and the evaluation of navigation (the TOML
/// table `[prediction]`; every key optional). Used only when `predict_sensing` is not
/// `off`.
///
/// ```
/// let p = csql::PredictionParams::default();
/// assert_eq!((p.confirmations, p.max_skips, p.navigation_trials, p.memory_moves), (3, 16, 10, 1));
/// assert_eq!((p.recheck, p.verify), (0.05, 0.05));
/// assert!(p.validate().is_ok());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PredictionParams {
    /// Equal measurements in a row, and none different, before a transition is trusted
    /// (default 3).
    pub confirmations: u32,
    /// Probability of re-checking a trusted transition while learning (default 0.05).
    pub recheck: f64,
    /// Most unmeasured uses of one transition in a row: the bound on how long a wrong
    /// prediction can go unmeasured (default 16).
    pub max_skips: u32,
    /// Probability of verifying a trusted transition while navigating (default 0.05).
    pub verify: f64,
    /// Evaluation trials of navigation from each non-goal free state (default 10, at most
    /// [`MAX_NAVIGATION_TRIALS`]).
    pub navigation_trials: u32,
    /// At the motion level, for how many moves a sensed cell is remembered (default 1:
    /// what was sensed at the previous state).
    pub memory_moves: u32,
}

impl Default for PredictionParams {
    fn default() -> PredictionParams {
        PredictionParams {
            confirmations: 3,
            recheck: 0.05,
            max_skips: 16,
            verify: 0.05,
            navigation_trials: 10,
            memory_moves: 1,
        }
    }
}

impl PredictionParams {
    /// Whether every value is the default (for serde's `skip_serializing_if`).
    ///
    /// ```
    /// assert!(csql::PredictionParams::default().is_default());
    /// ```
    pub fn is_default(&self) -> bool {
        *self == PredictionParams::default()
    }

    /// Check the ranges: probabilities in [0, 1], at least one confirmation, skip,
    /// evaluation trial and remembered move, and at most [`MAX_NAVIGATION_TRIALS`]
    /// evaluation trials.
    ///
    /// ```
    /// let p = csql::PredictionParams { recheck: 1.5, ..Default::default() };
    /// let err = p.validate().unwrap_err();
    /// assert!(matches!(err, csql::Error::InvalidSetting { .. }));
    /// assert!(err.to_string().contains("prediction.recheck"));
    /// ```
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |name: &'static str, value: String, expected: &'static str| {
            Err(Error::InvalidSetting {
                value: format!("{name} = {value}"),
                expected,
            })
        };
        for (name, p) in [
            ("prediction.recheck", self.recheck),
            ("prediction.verify", self.verify),
        ] {
            if !(0.0..=1.0).contains(&p) {
                return bad(name, p.to_string(), "a probability in [0, 1]");
            }
        }
        for (name, n) in [
            ("prediction.confirmations", self.confirmations),
            ("prediction.max_skips", self.max_skips),
            ("prediction.navigation_trials", self.navigation_trials),
            ("prediction.memory_moves", self.memory_moves),
        ] {
            if n == 0 {
                return bad(name, "0".to_string(), "at least 1");
            }
        }
        if self.navigation_trials > MAX_NAVIGATION_TRIALS {
            return bad(
                "prediction.navigation_trials",
                self.navigation_trials.to_string(),
                "at most 10000 evaluation trials from each state",
            );
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_are_checked() {
        for bad in [
            PredictionParams {
                verify: -0.1,
                ..Default::default()
            },
            PredictionParams {
                max_skips: 0,
                ..Default::default()
            },
            PredictionParams {
                confirmations: 0,
                ..Default::default()
            },
        ] {
            assert!(bad.validate().is_err());
        }
        assert_eq!(
            "motion".parse::<PredictSensing>().unwrap(),
            PredictSensing::Motion
        );
        assert!("on".parse::<PredictSensing>().is_err());
    }
}
