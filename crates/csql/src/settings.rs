//! A run's settings: the validated values ([`values`]: `RunSettings`), the learner and
//! its own settings ([`learner`]), the settings beyond the paper ([`extensions`]), the
//! settings file's form and its one conversion ([`draft`]), the defaults a world asks
//! for ([`defaults`]), what the settings name ([`resolve`]) and a grid map prepared for
//! a run ([`setup`]).
//!
//! What these modules may use: the parameter types of the parts they configure (the
//! strategies and detectors, AMRL-Q's and sensing by belief's parameters, the levels of
//! sensing less), and, to resolve a world, the policy quality's value floor and the rows
//! of full sensing; never the main loop or the reports. The layer table in
//! `docs/architecture.md` lists each module's uses, and a test holds it to the code.

pub(crate) mod defaults;
pub(crate) mod draft;
pub(crate) mod extensions;
pub(crate) mod learner;
pub(crate) mod resolve;
pub(crate) mod setup;
pub(crate) mod values;
