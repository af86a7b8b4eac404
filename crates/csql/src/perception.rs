//! What a learner knows of a state: how states become rows of the Q table
//! ([`rows`]: the `Perception` trait, every state its own row, full sensing), the
//! paper's CLASSIFY over a representation of descriptions ([`classify`],
//! [`representation`]), the sensors it reads through ([`sensor`], [`grid`]), and the
//! perceptions that wrap CLASSIFY: memory ([`memory`]) and sensing less by prediction
//! ([`sense_less`]); the tree over the final descriptions ([`tree`]); the read-only views
//! that measuring takes ([`view`]); a perception built on another ([`wraps`]).
//!
//! What these modules may use: each other and the errors; this is the lowest folder.
//! Their options are plain values (CLASSIFY's `Matching`, the levels of sensing less in
//! `sense_less::level`) that the settings name; they never use the settings, the agent,
//! the learners or the measures. `docs/architecture.md` states the layers and lists each
//! module's uses, and a test holds both to the code.

#[cfg_attr(
    not(test),
    expect(
        clippy::expect_used,
        reason = "internal invariants: feature spaces hold valid costs; a node with counts has a candidate feature"
    )
)]
pub(crate) mod classify;
pub(crate) mod grid;
pub(crate) mod memory;
#[cfg_attr(
    not(test),
    expect(
        clippy::expect_used,
        reason = "internal invariants: descriptions hold cell codes and ids index the representation"
    )
)]
pub(crate) mod representation;
#[cfg_attr(
    not(test),
    expect(
        clippy::expect_used,
        reason = "internal invariant: every state but the goal has a view"
    )
)]
pub(crate) mod rows;
pub(crate) mod sense_less;
pub(crate) mod sensor;
pub(crate) mod tree;
pub(crate) mod view;
pub(crate) mod wraps;
