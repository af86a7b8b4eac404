//! What measures a run from outside the learner: learning over trials with the oracle
//! watching ([`trials`]), the oracle's verdicts ([`judge`]), the policy quality
//! ([`quality`]), navigation after learning ([`navigate`]), the audit of predictions
//! ([`audit`]), the report and its Table 1 ([`report`]), why a run did not learn
//! ([`diagnosis`]), the figures ([`figure`]) and the paper's reference points
//! ([`reference`](self::reference)).
//!
//! What these modules may use: every folder below (the learners, the agent, the
//! settings, the perceptions), measuring a perception through its read-only views
//! (`perception::view`); a learner never uses them, so no learner can ask the oracle.
//! `docs/architecture.md` states the layers and lists each module's uses, and a test
//! holds both to the code.

pub(crate) mod audit;
pub(crate) mod diagnosis;
pub(crate) mod figure;
#[cfg_attr(
    not(test),
    expect(
        clippy::expect_used,
        reason = "internal invariants: every state of a sufficient representation has a row"
    )
)]
pub(crate) mod judge;
pub(crate) mod navigate;
pub(crate) mod quality;
#[cfg_attr(
    not(test),
    expect(
        clippy::expect_used,
        reason = "grid worlds have four actions, which a table accepts"
    )
)]
pub(crate) mod reference;
#[cfg_attr(
    not(test),
    expect(
        clippy::expect_used,
        reason = "internal invariants: grid worlds have four actions, a converged run matches every state"
    )
)]
pub(crate) mod report;
pub(crate) mod trials;
