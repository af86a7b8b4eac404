//! CS-QL's agent: the paper's main loop ([`main_loop`]), the four strategies
//! ([`strategy`]) and the detectors that tell when a description's utility fell
//! ([`detector`]), learning over trials with the oracle watching ([`trials`]), and the
//! same loop driven one move at a time by a caller ([`stepper`]).
//!
//! What these modules may use: the perceptions (`crate::perception`), the settings and
//! the measures that judge a run (`judging::judge`, `judging::quality`); the loop itself
//! knows only the `Perception` trait, its detector and its strategy. The layer table in
//! `docs/architecture.md` lists each module's uses, and a test holds it to the code.

pub(crate) mod detector;
pub(crate) mod main_loop;
pub(crate) mod stepper;
pub(crate) mod strategy;
pub(crate) mod trials;
