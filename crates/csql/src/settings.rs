//! A run's settings: the validated values ([`values`]: `RunSettings`), the learner and
//! its own settings ([`learner`], with the strategy's kind), the settings beyond the
//! paper ([`extensions`], with the detector's kind), the parameters of the learners on
//! costed episodes ([`costed`]), the settings file's form and its one conversion
//! ([`draft`]), the defaults a world asks for ([`defaults`]), what the settings name and
//! whether a world is deterministic ([`resolve`]) and a grid map prepared for a run
//! ([`setup`]).
//!
//! What these modules may use: the errors, and the perceptions whose options they name
//! (CLASSIFY's matching, the levels of sensing less, the size of full sensing's rows);
//! every parameter type the settings name that is not a perception's lives here, so they
//! never use the agent, the learners or the measures. `docs/architecture.md` states the
//! layers and lists each module's uses, and a test holds both to the code.

#[cfg_attr(
    not(test),
    expect(
        clippy::expect_used,
        reason = "constants: the published parameters are valid by their types' checks (the defaults' doc test builds them)"
    )
)]
pub(crate) mod costed;
pub(crate) mod defaults;
pub(crate) mod draft;
pub(crate) mod extensions;
pub(crate) mod learner;
pub(crate) mod resolve;
pub(crate) mod setup;
pub(crate) mod values;
