//! Cost-sensitive learning: classify objects while paying as little as possible for the
//! measurements, and learn from each object as it comes.
//!
//! # Quick start
//!
//! Add to `Cargo.toml` (the `rand` and `rand_xoshiro` versions are the ones this
//! workspace's examples and tests use; `rand` is needed for the cost-blind ID3 baseline's
//! seeded generator):
//!
//! ```toml
//! [dependencies]
//! cslearn = "0.1.0"
//! rand = { version = "0.10.0", default-features = false, features = ["std"] }
//! rand_xoshiro = "0.8.0"
//! ```
//!
//! Then learn from objects one at a time, paying for each measurement:
//!
//! ```
//! use cslearn::{ClassId, FeatureCosts, Value};
//! // Two features: a cheap one (price 1) and an expensive one (price 10).
//! let mut learner = cslearn::cs_id3_indexed(FeatureCosts::from_f64(&[1.0, 10.0]).unwrap());
//! let objects = [
//!     ([Some(Value(0)), Some(Value(7))], ClassId(0)),
//!     ([Some(Value(1)), Some(Value(7))], ClassId(1)),
//! ];
//! for _ in 0..3 {
//!     for (object, class) in &objects {
//!         learner.learn(&object[..], *class);
//!     }
//! }
//! let answer = learner.classify(&[Some(Value(1)), Some(Value(7))][..]);
//! assert_eq!(answer.class, Some(ClassId(1)));
//! assert_eq!(answer.cost.get(), 1.0); // only the cheap feature was needed
//! ```
//!
//! This crate implements the cost-sensitive learning framework of Tan (AAAI-91, section
//! "Cost-Sensitive Learning", Figure 2) and its instantiations CS-ID3 and CS-IBL. It
//! stands alone: a user with a table of objects and a price for each measurement can
//! learn and classify with it. It knows nothing of MDPs, Q-values or grids (the `csql`
//! crate builds its state classification from these parts).
//!
//! # The cycle
//!
//! For each new object, labelled only by its class, a [`Learner`]:
//!
//! 1. repeatedly **attends** to the stored examples that agree with what has been measured,
//!    **selects** a cost-effective feature from them and **measures** it through a
//!    [`Sensor`] (the [`Ledger`] records the value and charges its [`Cost`]), until a class
//!    can be **predicted**;
//! 2. compares the prediction with the true class;
//! 3. on an error, **discriminates**: measures more features until the examples that misled
//!    it no longer agree with the object;
//! 4. **updates** the library with the new example: every value measured, and the class.
//!
//! # The five functions, and who implements them
//!
//! | Figure 2 function | trait | CS-ID3 ([`cs_id3`]) | CS-IBL ([`cs_ibl`]) | ID3 baseline ([`id3`]) | CS-QL's CLASSIFY (csql) |
//! |---|---|---|---|---|---|
//! | example attending | [`Attend`] | [`ObservationAttending`] | [`RankedAttending`] | [`ObservationAttending`] | [`RuleAttending`] |
//! | feature selection | [`Select`] | [`InfoCost`], [`MissingRule::OwnBranch`] | [`InfoCost`], [`MissingRule::OwnBranch`] | [`InfoCost::cost_blind`] | [`InfoCost::select_from`], [`MissingRule::C45`] |
//! | class prediction | [`Predict`] | [`Unanimous`] | [`Nearest`] | [`Unanimous`] | its own |
//! | example discrimination | [`Discriminate`] | [`CheapestFirst`] | [`CheapestFirst`] | [`RandomOrder`] | none needed |
//! | library updating | [`Update`] | [`AppendAll`] | [`AppendAll`] | [`AppendAll`] | its own |
//!
//! [`DecisionTree`] builds a cost-sensitive decision tree from a library by greedy I^2/C,
//! for observations or for rules ([`TreeOptions`]), with its expected classification cost
//! and a Graphviz DOT picture. [`Dataset`] reads a CSV table of objects and a CSV table of
//! costs.
//!
//! # Example
//!
//! ```
//! use cslearn::{ClassId, DecisionTree, FeatureCosts, TreeOptions, Value};
//!
//! // Two features: a cheap one that decides the class and an expensive one that does not.
//! let costs = FeatureCosts::from_f64(&[1.0, 100.0]).unwrap();
//! let objects = [
//!     ([Some(Value(0)), Some(Value(0))], ClassId(0)),
//!     ([Some(Value(1)), Some(Value(0))], ClassId(1)),
//!     ([Some(Value(0)), Some(Value(1))], ClassId(0)),
//!     ([Some(Value(1)), Some(Value(1))], ClassId(1)),
//! ];
//! let mut learner = cslearn::cs_id3(costs.clone());
//! let first = learner.stream(objects.iter().map(|(row, class)| (&row[..], *class)));
//! let second = learner.stream(objects.iter().map(|(row, class)| (&row[..], *class)));
//! assert_eq!(second.errors, 0);
//! assert!(second.mean_cost <= 1.0 && first.full_cost == 101.0);
//!
//! // A tree over what was learned measures only the cheap feature.
//! let tree = DecisionTree::build(learner.library(), &costs, TreeOptions::observations());
//! let result = tree.classify(&objects[3].0[..]);
//! assert_eq!((result.class, result.cost.get()), (Some(ClassId(1)), 1.0));
//! ```
//!
//! # On real data: the Cleveland heart-disease records
//!
//! The workspace ships the 304 Cleveland records of the UCI heart-disease data with
//! Turney's (1995) test costs (`data/heart-disease/`, with its attribution). Streaming them
//! once in a seeded random order, each object predicted with charged measurements and then
//! learned with its true class (`num` 0 against greater than 0), gives, over seeds 1 to 10:
//!
//! | learner | accuracy, mean (min-max) | measuring cost per object, mean (min-max) |
//! |---|---|---|
//! | CS-ID3 | 0.653 (0.618-0.684) | 5.0 (4.2-6.4) |
//! | CS-ID3 without the recheck | 0.656 (0.615-0.688) | 4.7 (4.1-6.2) |
//! | CS-IBL, tolerance 1 | 0.649 (0.622-0.688) | 48.0 (41.8-51.2) |
//! | ID3, cost-blind | 0.643 (0.602-0.688) | 148.8 (87.2-188.4) |
//! | measuring everything | | 600.57 |
//!
//! CS-ID3 pays about a thirtieth of what cost-blind ID3 pays, at the same accuracy, and
//! both far less than measuring every test. CS-IBL pays for its tolerance of a wrong value:
//! an instance must be told apart from its rivals by two features instead of one. The
//! table comes from `cargo run --release -p cslearn --example heart -- 10`; one row of it
//! for one seed from
//! `csrl classify --data data/heart-disease/cleveland.csv --costs data/heart-disease/costs.csv
//! --target num --positive-if '>0' --learner cs-id3 --seed 1` (add `--json` for a JSON
//! object).
//!
//! # At scale: the indexed learners
//!
//! [`cs_id3_indexed`] and [`id3_indexed`] ([`IndexedLearner`]) are CS-ID3 and ID3 over a
//! lazily built tree of per-node class counts ([`SplitCounts`] while a node has few classes;
//! past that, hash maps with exact running sums of the score's terms, which bound
//! [`InfoCost::select_from_counts`]'s scores, falling back on it where the bounds do not
//! decide): the same features measured in the same order, the same
//! predictions, charges and library as [`cs_id3`] and [`id3`], bit for bit
//! (`tests/indexed.rs`), in time per object that barely grows with the library.
//! [`stream_dataset`], and so `csrl classify`, uses them. On generated data of 30 features
//! (the generator is documented in `examples/classify_scale.rs`), CPU seconds of the
//! stream, in one process, on a shared 2-core machine:
//!
//! | rows | indexed CS-ID3 | µs per object | plain CS-ID3 | plain / indexed |
//! |---:|---:|---:|---:|---:|
//! | 1,000 | 0.008 | 7.9 | 0.181 | 23x |
//! | 10,000 | 0.103 | 10.3 | 25.5 | 246x |
//! | 40,000 | 0.661 | 16.5 | | |
//!
//! Time per object grows as rows^0.23 over 1k..40k rows (the plain procedure: rows^1.14),
//! from `cargo run --release -p cslearn --example classify_scale`. As a whole process,
//! `csrl classify --learner cs-id3` on the 10,000-row file takes 0.20 CPU seconds against
//! 24.4 before (121x). CS-IBL has no index: its attending ranks every instance of the
//! library, so it stays linear in the library per object. `docs/cslearn-speed.md` has the
//! full tables and commands.
//!
//! # Design choices
//!
//! * **Sparse examples, no closed world.** An [`Example`] is a sorted list of (feature,
//!   value) pairs and a class; [`FeatureId`], [`Value`] and [`ClassId`] are plain numbers, so
//!   new ones can appear at any time ([`Learner::add_feature`] prices a new feature).
//! * **Observations versus rules.** A feature an example lacks was never measured; a
//!   feature a csql description lacks means "any value". Attending is a trait precisely so
//!   the two can differ ([`Semantics`]).
//! * **One selection criterion, two missing-value rules.** [`InfoCost`] scores I^2/C, with
//!   examples lacking the feature as a branch of their own (CS-ID3) or, as in C4.5, the
//!   gain computed on the examples having it and scaled by their share (csql). Ties go to
//!   the lower cost, then the lower id, so with no information anywhere the cheapest
//!   candidate is measured.
//! * **Discrimination reuses attending.** "Until the new example is told apart from the
//!   conflicting examples" means "until the learner's own attending function drops them",
//!   so CS-IBL's tolerance carries over to discrimination unchanged.
//! * **A recheck after learning.** After updating the library, the learner classifies the
//!   object again, replaying the values it already paid for, and discriminates further if
//!   the object is still not recognised ([`Learner::recheck`]). Greedy selection can
//!   otherwise, rarely, prefer a feature the new example lacks once that example is in the
//!   library; with the recheck, an object just learned is recognised when it comes again
//!   (on noiseless, non-contradictory data). It costs 0.3 per object on the heart data.
//! * **No allocation per measurement.** The learner, the attention and the selector keep
//!   their buffers between objects.
//!   `cargo bench -p cslearn` measures classifying one object against a library of 300
//!   examples over 20 features (about 45 µs for CS-ID3, 150 µs for CS-IBL on a 2-core
//!   machine) and building a tree from that library (about 190 µs).
//! * **Reproducible.** Ties are broken by documented rules, never by hash order; the only
//!   randomness (ID3's discrimination order) comes from a generator the caller seeds.
//!
//! # Where this differs from the paper
//!
//! * The paper gives CS-ID3's rules in prose. The working rules here (the project's
//!   specification, `docs/specification.md` §2, which the "§" references in this crate
//!   cite) fix what it leaves open: which examples attend (those having the measured
//!   value), what to predict when none or mixed remain, and which examples count as
//!   conflicting (the attended ones of another class at the moment of prediction).
//! * CS-IBL follows the description of Tan and Schlimmer (1990) in outline only: instances
//!   are ranked by mismatches on the measured features, a feature lacking counting as a
//!   mismatch; the attended instances are those within a tolerance of wrong values; the
//!   prediction is made once they agree. With tolerance t, an object with at most t wrong
//!   values is still classified by its own stored instance.
//! * Numeric columns are binned at quartiles before learning ([`Binning`]); the paper's
//!   domains were nominal.
//! * The recheck after learning (above) is not in the paper.
//! * The ID3 baseline takes every cost as equal in selection and discriminates in a random
//!   order: with equal costs and ties by column order, the heart data's column order
//!   (nearly its cost order) would smuggle cost information in.

#![deny(missing_docs)]
#![cfg_attr(not(test), warn(clippy::unwrap_used, clippy::expect_used))]

mod attend;
mod counts;
mod dataset;
mod discriminate;
mod error;
mod example;
mod indexed;
mod learner;
mod model;
mod predict;
mod select;
mod sensing;
mod stream;
pub mod testcost;
mod tree;
mod types;
mod update;

pub use attend::{
    Attend, Attention, ObservationAttending, RankedAttending, RuleAttending, Semantics,
};
pub use dataset::{Binning, Dataset, DatasetOptions, MAX_CELLS, MAX_FILE_BYTES, MAX_TOTAL_COST};
pub use discriminate::{CheapestFirst, Discriminate, RandomOrder};
pub use error::Error;
pub use example::{Example, Library};
pub use indexed::{IndexedCsId3, IndexedId3, IndexedLearner, cs_id3_indexed, id3_indexed};
pub use learner::{
    Classified, CsIbl, CsId3, Id3, Learner, Outcome, StreamReport, cs_ibl, cs_id3, id3,
};
pub use model::{MODEL_FORMAT, MODEL_VERSION, Model, Prediction};
pub use predict::{Decision, Nearest, Predict, Unanimous, Votes};
pub use select::{BestScore, InfoCost, MissingRule, Select, SplitCounts};
pub use sensing::{Ledger, Probe, Sensor};
pub use stream::{
    LearnerKind, Procedure, stream_dataset, stream_dataset_keeping, stream_dataset_with,
    stream_dataset_with_progress,
};
pub use tree::{Branch, DecisionTree, Labels, Node, NodeId, PlainLabels, TreeOptions};
pub use types::{ClassId, Cost, CostBlind, Costs, FeatureCosts, FeatureId, Value};
pub use update::{AppendAll, AppendErrors, Update};
