//! A request to stop a fit before it ends, shared between the fit and whoever may ask.

use std::sync::atomic::{AtomicBool, Ordering};

/// A request to stop a fit ([`fit_until`](super::fit_until)): made by one thread (a
/// front end that saw Ctrl-C), read by the fit on its own threads.
///
/// Once it is requested, every split trie the fit grows through offers no more tests, so
/// every grower (ACT's lookahead and its samples, ICET's search, CVT's growers and folds)
/// ends at once with the nodes it has; ICET's search also checks it before each
/// individual. The fit then answers [`Error::Stopped`](crate::Error::Stopped) and drops
/// what it grew. A request never made changes nothing: the fit is [`fit`](super::fit)'s,
/// to the bit.
///
/// ```
/// use cslearn::testcost::Stop;
/// let stop = Stop::default();
/// assert!(!stop.is_requested());
/// stop.request();
/// assert!(stop.is_requested());
/// ```
#[derive(Debug, Default)]
pub struct Stop {
    requested: AtomicBool,
}

impl Stop {
    /// Ask the fit to stop (from any thread); it cannot be taken back.
    pub fn request(&self) {
        self.requested.store(true, Ordering::Relaxed);
    }

    /// Whether a stop was requested.
    pub fn is_requested(&self) -> bool {
        self.requested.load(Ordering::Relaxed)
    }
}
