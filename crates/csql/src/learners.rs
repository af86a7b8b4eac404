//! The learners beside CS-QL's own: the U-Tree-like baseline ([`utree`], a perception
//! the main loop drives), AMRL-Q ([`amrl`]) and sensing by belief ([`belief`]), which
//! play episodes of their own, and the costed episodes that any of them plays when a
//! run is scored by its costed return ([`costly`]).
//!
//! What these modules may use: the layers below (the agent, the perceptions, the
//! settings, with their own parameters in `settings::costed`, the errors and the
//! observer); never the measures, so no learner can ask the oracle.
//! `docs/architecture.md` states the layers and lists each module's uses, and a test
//! holds both to the code.

#[cfg_attr(
    not(test),
    expect(
        clippy::expect_used,
        reason = "constants: a learning rate of 1 is valid by its type's check; a world has an action"
    )
)]
pub(crate) mod amrl;
#[cfg_attr(
    not(test),
    expect(
        clippy::expect_used,
        reason = "internal invariants: a node is of the plan just built"
    )
)]
pub(crate) mod belief;
pub(crate) mod costly;
#[cfg_attr(
    not(test),
    expect(
        clippy::expect_used,
        reason = "internal invariant: a walk given a table always ends at a row"
    )
)]
pub(crate) mod utree;
