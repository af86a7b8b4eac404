//! The learners beside CS-QL's own: the U-Tree-like baseline ([`utree`], a perception
//! the main loop drives), AMRL-Q ([`amrl`]) and sensing by belief ([`belief`]), which
//! play episodes of their own, and the costed episodes that any of them plays when a
//! run is scored by its costed return ([`costly`]).
//!
//! What these modules may use: AMRL-Q and sensing by belief stand on their own (the
//! errors and the observer only), so the settings can name their parameters; U-Tree
//! uses the perceptions; the costed episodes use the agent, the perceptions, the
//! settings and the policy quality. The layer table in `docs/architecture.md` lists each
//! module's uses, and a test holds it to the code.

#[cfg_attr(
    not(test),
    expect(
        clippy::expect_used,
        reason = "constants: the published parameters and a learning rate of 1 are valid by their types' checks (the defaults' doc test builds them); a world has an action"
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
