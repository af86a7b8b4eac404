//! Watching a run as it goes: one call per trial, with the power to stop it.
//!
//! A long run (a huge trial cap, a tiny temperature) needs a sign of life, a bound on its
//! memory and a clean way out. [`run_observed`](crate::run_observed) calls an
//! [`Observer`] at the end of every trial with that trial's [`TracePoint`]; the observer
//! can show progress, write the point somewhere, or answer [`Flow::Stop`] (on Ctrl-C, for
//! example), and it decides whether the report keeps the whole per-trial trace in memory.
//! Observing changes nothing the run computes: a run observed to its end reports exactly
//! what [`run_on`](crate::run_on) reports, except for the trace when it is not kept.

use serde::Serialize;

/// One line of the learning curve: the state of the run at the end of a trial.
///
/// ```
/// let r = csql::run(&csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Eager, 1)).unwrap();
/// let last = r.trace.last().unwrap();
/// assert!(last.converged && last.cumulative_cost == r.total_cost);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TracePoint {
    /// The trial, from 1.
    pub trial: u32,
    /// Moves in this trial.
    pub moves: u32,
    /// Sensing cost charged so far in the run.
    pub cumulative_cost: f64,
    /// Descriptions at the end of the trial.
    pub descriptions: usize,
    /// Decreases seen in this trial.
    pub decreases: u32,
    /// Features added in this trial.
    pub refinements: u32,
    /// The representation is sufficient.
    pub sufficient: bool,
    /// The run has converged.
    pub converged: bool,
}

/// What the run does after an observed trial.
///
/// ```
/// assert_ne!(csql::Flow::Continue, csql::Flow::Stop);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    /// Go on with the next trial (if the run has not converged or reached its cap).
    Continue,
    /// End the run now and report what it reached.
    Stop,
}

/// How many moves of one trial, of learning or of navigation after it, pass between two
/// questions to the observer ([`Observer::keep_going`]).
///
/// ```
/// assert_eq!(csql::STOP_CHECK_MOVES, 4096);
/// ```
pub const STOP_CHECK_MOVES: u32 = 4096;

/// Whether `observer`, asked `moves` moves into a trial (every [`STOP_CHECK_MOVES`]
/// moves, not at the start), says to stop.
pub(crate) fn told_to_stop(observer: &mut dyn Observer, moves: u32) -> bool {
    moves > 0 && moves.is_multiple_of(STOP_CHECK_MOVES) && !observer.keep_going()
}

/// Watches a run trial by trial.
///
/// ```
/// use csql::{Flow, Observer, RunSettings, Setup, StrategyKind, TracePoint};
/// /// Stops after three trials and keeps no trace.
/// struct Three(u32);
/// impl Observer for Three {
///     fn keep_trace(&self) -> bool { false }
///     fn trial(&mut self, _: &TracePoint) -> Flow {
///         self.0 += 1;
///         if self.0 == 3 { Flow::Stop } else { Flow::Continue }
///     }
/// }
/// let settings = RunSettings::tan1991("tan8x8", StrategyKind::Resetting, 1);
/// let setup = Setup::new(&settings).unwrap();
/// let report = csql::run_observed(&setup, &settings, &mut Three(0)).unwrap();
/// assert_eq!((report.trials, report.converged, report.trace.len()), (3, false, 0));
/// ```
pub trait Observer {
    /// Whether the report keeps one [`TracePoint`] per trial (memory grows with the
    /// run's length when it does). The default keeps it, as [`run_on`](crate::run_on) does.
    fn keep_trace(&self) -> bool {
        true
    }

    /// Called at the end of every trial, after the oracle's judgement.
    fn trial(&mut self, point: &TracePoint) -> Flow;

    /// Asked where a run would otherwise not hear from its observer for long: every
    /// [`STOP_CHECK_MOVES`] moves within a trial of learning; before every trial of
    /// navigation after learning ([`crate::navigate`]) and every [`STOP_CHECK_MOVES`]
    /// moves within one; before every episode of a learner on costed episodes
    /// ([`crate::costed_report`]). `false` ends the trial there, as the move cap would
    /// (a learning run then asks [`Observer::trial`] as after any trial), or ends the
    /// navigation or the episodes, so that a stop asked for (Ctrl-C, say) is not left
    /// waiting. The default always goes on.
    ///
    /// ```
    /// use csql::{Flow, Observer, TracePoint};
    /// struct Never;
    /// impl Observer for Never {
    ///     fn trial(&mut self, _: &TracePoint) -> Flow { Flow::Continue }
    ///     fn keep_going(&mut self) -> bool { false }
    /// }
    /// assert!(!Never.keep_going());
    /// assert!(csql::KeepTrace.keep_going());
    /// ```
    fn keep_going(&mut self) -> bool {
        true
    }
}

/// The observer of a plain run: keeps the trace and never stops it.
///
/// ```
/// use csql::{KeepTrace, RunSettings, Setup, StrategyKind};
/// let settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
/// let setup = Setup::new(&settings).unwrap();
/// assert_eq!(
///     csql::run_observed(&setup, &settings, &mut KeepTrace).unwrap(),
///     csql::run_on(&setup, &settings).unwrap()
/// );
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct KeepTrace;

impl Observer for KeepTrace {
    fn trial(&mut self, _: &TracePoint) -> Flow {
        Flow::Continue
    }
}
