//! CS-QL: cost-sensitive Q-learning (Tan, AAAI-91, Figure 3).
//!
//! PLACEHOLDER
#![deny(missing_docs)]

mod check;
mod classify;
mod error;
mod figure;
mod learner;
mod reference;
mod representation;
mod run;
mod settings;
mod strategy;
mod tree;

pub use check::Verdict;
pub use classify::{Classification, Classify};
pub use error::Error;
pub use figure::policy_svg;
pub use learner::{Identified, LoopParams, Never, Perception, TrialRecord, run_trial};
pub use reference::{
    Reference, cheapest_interior_cost, fixed_representation_reference, full_sensing_reference,
    whole_world_cost,
};
pub use representation::{Description, DescriptionId, Representation};
pub use run::{
    DescriptionReport, FeatureReport, RunReport, Setup, StateReport, Table1, TracePoint, run,
    run_on, run_on_with, run_with_representation,
};
pub use settings::RunSettings;
pub use strategy::{
    Eager, Lazy, RandomMoves, Reaction, Resetting, Strategy, StrategyKind, UnknownStrategy,
};
pub use tree::{StateSensor, StateTree};
