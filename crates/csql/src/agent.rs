//! CS-QL's agent: the paper's main loop ([`main_loop`]), with the agent of a run made
//! from its settings and the value its Q starts at; the four strategies ([`strategy`])
//! and the detectors that tell when a description's utility fell ([`detector`]); and the
//! same loop driven one move at a time by a caller ([`stepper`]). Learning over trials
//! with the oracle watching is the measures' (`judging::trials`).
//!
//! What these modules may use: the layers below, the perceptions (`crate::perception`)
//! and the settings (`crate::settings`), with the errors and the observer; never the
//! learners beside CS-QL's or the measures. The loop itself knows only the `Perception`
//! trait, its detector and its strategy. `docs/architecture.md` states the layers and
//! lists each module's uses, and a test holds both to the code.

pub(crate) mod detector;
pub(crate) mod main_loop;
pub(crate) mod stepper;
pub(crate) mod strategy;
