//! How the main loop decides that a description is inconsistent: a value the loop asks
//! after every update of V.
//!
//! | detector | decides "inconsistent" when | where |
//! |---|---|---|
//! | [`AnyDrop`] | V fell by more than the decrease threshold (the paper's rule, Theorem 2) | deterministic worlds |
//! | [`RateTest`] | V fell noticeably in too many of the description's last updates | slippery or noisy worlds |
//! | [`ActionDrop`] | V fell, or Q of the action taken fell after that action had been tried in the description before | deterministic worlds with penalties, beta 1 |
//!
//! # Why Q of an action may speak for the description
//!
//! From the floor of the returns ([`crate::value_floor`]), in a deterministic world whose
//! descriptions are homomorphic and with beta 1, the target of `Q(x, a)` is `r + gamma
//! V(y)` with the same `r` and the same next description `y` every time, and `V(y)` never
//! falls (Theorem 1): so once `(x, a)` has been tried, its Q never falls either, and a fall
//! proves that `x`'s states disagree on `a`. V alone can miss this: where one state of a
//! description pays a penalty for an action that others do not (the cliff, an illegal
//! pick-up), that action's Q falls while V, the maximum, stays, and Boltzmann selection
//! then stops trying the action in every state of the description.
//!
//! In a deterministic world any decrease of V proves an inconsistent description
//! (Theorem 2). In a slippery world, with beta below 1, the V of a description that is one
//! true state still falls whenever a slip gives a worse sample than the current estimate,
//! so the paper's rule refines without end. [`RateTest`] asks instead whether V falls more
//! often than one state of a slippery world would make it fall.
//!
//! # The rate test
//!
//! For each description it keeps the last `window` updates and whether each lowered V by
//! more than `relative_drop` times its value before. The null hypothesis is "this
//! description is one state": then each update is a fall with some small probability
//! `q0` (about the chance that a slip leads somewhere worse, at most the slip probability),
//! and the count of falls in the window is Binomial(`window`, `q0`). The description is
//! called inconsistent when the window is full and more than `rate * window` of its
//! updates were falls; the window is then emptied, and emptied when the description is
//! refined or the table reset. With the defaults (window 20, rate 0.2, so 5 falls or more;
//! relative drop 0.5%), the chance of a false alarm per full window is
//! P(Bin(20, q0) >= 5): 0.003 at q0 = 0.05, 0.043 at q0 = 0.1, 0.17 at q0 = 0.15; the
//! chance of missing an aliased description whose targets fall with q1 is
//! P(Bin(20, q1) <= 4): 0.24 at q1 = 0.3, 0.05 at q1 = 0.4, 0.006 at q1 = 0.5. The
//! relative drop keeps the small falls of a converging estimate (beta moves V a fraction
//! of the way to each target) from counting.

use qlearn::{RowId, VChange};

use crate::settings::extensions::{DetectorKind, RateParams};

/// What the main loop asks after every update of a description's V.
///
/// ```
/// use csql::{AnyDrop, Detector};
/// use qlearn::{RowId, VChange};
/// let mut d = AnyDrop;
/// assert!(d.inconsistent(RowId(0), VChange { before: 1.0, after: 0.5 }, true));
/// ```
pub trait Detector {
    /// An update changed V of `row`; `dropped` says whether it fell by more than the
    /// decrease threshold. Is the description inconsistent?
    fn inconsistent(&mut self, row: RowId, change: VChange, dropped: bool) -> bool;
    /// Called before [`Detector::inconsistent`] for the same update: Q of `action` in
    /// `row` was updated, and `fell` says whether it fell by more than the decrease
    /// threshold. By default nothing is kept.
    fn action_updated(&mut self, row: RowId, action: mdp::ActionId, fell: bool) {
        let _ = (row, action, fell);
    }
    /// The description of `row` was refined: what was seen no longer describes it.
    fn refined(&mut self, row: RowId);
    /// Every Q and V was reset.
    fn reset(&mut self);
}

/// The paper's rule: any decrease beyond the threshold is inconsistency.
///
/// ```
/// use csql::{AnyDrop, Detector};
/// use qlearn::{RowId, VChange};
/// assert!(!AnyDrop.inconsistent(RowId(3), VChange { before: 1.0, after: 0.9 }, false));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AnyDrop;

impl Detector for AnyDrop {
    fn inconsistent(&mut self, _row: RowId, _change: VChange, dropped: bool) -> bool {
        dropped
    }
    fn refined(&mut self, _row: RowId) {}
    fn reset(&mut self) {}
}

/// The statistical detector: a description is inconsistent when V fell noticeably in
/// more than `rate` of its last `window` updates.
///
/// ```
/// use csql::{Detector, RateParams, RateTest};
/// use qlearn::{RowId, VChange};
/// let mut d = RateTest::new(RateParams { window: 4, rate: 0.5, relative_drop: 0.01 });
/// let fall = VChange { before: 1.0, after: 0.9 };
/// let rise = VChange { before: 0.9, after: 1.0 };
/// assert!(!d.inconsistent(RowId(0), fall, true)); // the window is not full yet
/// assert!(!d.inconsistent(RowId(0), rise, false));
/// assert!(!d.inconsistent(RowId(0), fall, true));
/// assert!(d.inconsistent(RowId(0), fall, true)); // 3 falls in 4 > 0.5
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct RateTest {
    params: RateParams,
    /// Per row: the last updates as bits (1 = a fall), newest lowest, and how many.
    seen: Vec<(u64, u32)>,
}

impl RateTest {
    /// A rate test with its parameters (a window of at most 64 updates is kept).
    ///
    /// ```
    /// let t = csql::RateTest::new(csql::RateParams::default());
    /// ```
    pub fn new(params: RateParams) -> RateTest {
        RateTest {
            params: RateParams {
                window: params.window.clamp(1, 64),
                ..params
            },
            seen: Vec::new(),
        }
    }
}

impl Detector for RateTest {
    fn inconsistent(&mut self, row: RowId, change: VChange, _dropped: bool) -> bool {
        let i = row.0 as usize;
        if self.seen.len() <= i {
            self.seen.resize(i + 1, (0, 0));
        }
        let w = self.params.window;
        let mask = if w == 64 { u64::MAX } else { (1u64 << w) - 1 };
        let fall = change.after < change.before * (1.0 - self.params.relative_drop);
        let (bits, n) = &mut self.seen[i];
        *bits = ((*bits << 1) | u64::from(fall)) & mask;
        *n = (*n + 1).min(w);
        let hit = *n == w && f64::from(bits.count_ones()) > self.params.rate * f64::from(w);
        if hit {
            self.seen[i] = (0, 0);
        }
        hit
    }
    fn refined(&mut self, row: RowId) {
        if let Some(x) = self.seen.get_mut(row.0 as usize) {
            *x = (0, 0);
        }
    }
    fn reset(&mut self) {
        self.seen.clear();
    }
}

/// Any fall of V, or a fall of Q for an action the description had tried before (see the
/// module docs; the setting `detector = "action"`, beta 1 only).
///
/// ```
/// use csql::{ActionDrop, Detector};
/// use qlearn::{RowId, VChange};
/// let mut d = ActionDrop::default();
/// let same = VChange { before: -10.0, after: -10.0 };
/// // The first try of an action may fall below the floor: no evidence.
/// d.action_updated(RowId(0), mdp::ActionId(1), true);
/// assert!(!d.inconsistent(RowId(0), same, false));
/// // A second fall of the same action in the same description is.
/// d.action_updated(RowId(0), mdp::ActionId(1), true);
/// assert!(d.inconsistent(RowId(0), same, false));
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ActionDrop {
    /// For each row, the actions tried since the last reset (bit `a`; actions past 63
    /// share bit 63, which only makes the detector slower to speak).
    tried: Vec<u64>,
    /// Whether the update being judged lowered the Q of an action tried before.
    fell: bool,
}

impl Detector for ActionDrop {
    fn action_updated(&mut self, row: RowId, action: mdp::ActionId, fell: bool) {
        let i = row.0 as usize;
        if self.tried.len() <= i {
            self.tried.resize(i + 1, 0);
        }
        let bit = 1u64 << action.0.min(63);
        let before = self.tried[i] & bit != 0;
        self.tried[i] |= bit;
        self.fell = before && fell;
    }
    fn inconsistent(&mut self, _row: RowId, _change: VChange, dropped: bool) -> bool {
        std::mem::take(&mut self.fell) || dropped
    }
    fn refined(&mut self, _row: RowId) {}
    fn reset(&mut self) {
        self.tried.clear();
    }
}

/// The detector of a run, chosen by a setting.
///
/// ```
/// use csql::{Detector, DetectorKind, RateParams, RunDetector};
/// let mut d = RunDetector::new(DetectorKind::Decrease, RateParams::default());
/// assert!(d.inconsistent(qlearn::RowId(0), qlearn::VChange { before: 1.0, after: 0.0 }, true));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum RunDetector {
    /// The paper's rule.
    Decrease(AnyDrop),
    /// The rate test.
    Statistical(RateTest),
    /// Falls of V or of a tried action's Q.
    Action(ActionDrop),
}

impl RunDetector {
    /// The detector of a kind.
    ///
    /// ```
    /// let d = csql::RunDetector::new(csql::DetectorKind::Statistical, csql::RateParams::default());
    /// assert!(matches!(d, csql::RunDetector::Statistical(_)));
    /// ```
    pub fn new(kind: DetectorKind, params: RateParams) -> RunDetector {
        match kind {
            DetectorKind::Decrease => RunDetector::Decrease(AnyDrop),
            DetectorKind::Statistical => RunDetector::Statistical(RateTest::new(params)),
            DetectorKind::Action => RunDetector::Action(ActionDrop::default()),
        }
    }
}

impl Default for RunDetector {
    fn default() -> RunDetector {
        RunDetector::Decrease(AnyDrop)
    }
}

impl Detector for RunDetector {
    fn inconsistent(&mut self, row: RowId, change: VChange, dropped: bool) -> bool {
        match self {
            RunDetector::Decrease(d) => d.inconsistent(row, change, dropped),
            RunDetector::Statistical(d) => d.inconsistent(row, change, dropped),
            RunDetector::Action(d) => d.inconsistent(row, change, dropped),
        }
    }
    fn refined(&mut self, row: RowId) {
        match self {
            RunDetector::Decrease(d) => d.refined(row),
            RunDetector::Statistical(d) => d.refined(row),
            RunDetector::Action(d) => d.refined(row),
        }
    }
    fn action_updated(&mut self, row: RowId, action: mdp::ActionId, fell: bool) {
        if let RunDetector::Action(d) = self {
            d.action_updated(row, action, fell);
        }
    }
    fn reset(&mut self) {
        match self {
            RunDetector::Decrease(d) => d.reset(),
            RunDetector::Statistical(d) => d.reset(),
            RunDetector::Action(d) => d.reset(),
        }
    }
}
