//! Streaming a data set through a learner in a seeded random order.

use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use crate::dataset::Dataset;
use crate::example::Library;
use crate::indexed::{cs_id3_indexed, id3_indexed};
use crate::learner::{StreamReport, cs_ibl, cs_id3, id3};

/// Which learner to stream a data set through.
///
/// ```
/// assert_ne!(cslearn::LearnerKind::CsId3, cslearn::LearnerKind::Id3);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LearnerKind {
    /// CS-ID3 ([`cs_id3`]).
    CsId3,
    /// CS-IBL tolerating up to `tolerance` wrong values per object ([`cs_ibl`]).
    CsIbl {
        /// The most mismatches an attended instance may have.
        tolerance: u32,
    },
    /// Cost-blind ID3 ([`id3`]).
    Id3,
}

/// How a learner finds its way through the library: both give the same results, bit for
/// bit; they differ only in time.
///
/// ```
/// assert_ne!(cslearn::Procedure::Indexed, cslearn::Procedure::Plain);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Procedure {
    /// CS-ID3 and ID3 over an index of the library ([`cs_id3_indexed`], [`id3_indexed`]);
    /// CS-IBL, which has no index, as in `Plain`.
    Indexed,
    /// The five functions as written ([`cs_id3`], [`cs_ibl`], [`id3`]): every object
    /// attends and counts the whole library afresh. The reference the indexed learners
    /// are tested and measured against.
    Plain,
}

/// Stream every object of `dataset` once through a fresh learner of `kind`, in a random
/// order drawn from `seed`: each object is predicted with charged measurements, then
/// learned with its true class.
///
/// The order is a shuffle by a `Xoshiro256PlusPlus` generator seeded with `seed`; ID3 then
/// draws its discrimination orders from the same generator. The report is therefore the
/// same for the same data, learner and seed, on every machine. CS-ID3 and ID3 run over an
/// index of the library ([`Procedure::Indexed`]); [`stream_dataset_with`] can run the plain
/// procedure instead, with the same result.
///
/// ```
/// use cslearn::{Dataset, DatasetOptions, LearnerKind};
/// let data = "a,b,t\n0,0,n\n0,1,n\n1,0,y\n1,1,y\n0,0,n\n1,1,y\n";
/// let costs = "feature,cost\na,1\nb,5\n";
/// let ds = Dataset::from_readers(data.as_bytes(), "d.csv", costs.as_bytes(), "c.csv", &DatasetOptions::new("t")).unwrap();
/// let report = cslearn::stream_dataset(&ds, LearnerKind::CsId3, 7);
/// assert_eq!(report.objects, 6);
/// assert_eq!(report.full_cost, 6.0);
/// assert_eq!(report, cslearn::stream_dataset(&ds, LearnerKind::CsId3, 7));
/// ```
pub fn stream_dataset(dataset: &Dataset, kind: LearnerKind, seed: u64) -> StreamReport {
    stream_dataset_with(dataset, kind, seed, Procedure::Indexed)
}

/// [`stream_dataset`] by the given procedure.
///
/// ```
/// use cslearn::{Dataset, DatasetOptions, LearnerKind, Procedure};
/// let data = "a,b,t\n0,0,n\n0,1,n\n1,0,y\n1,1,y\n0,0,n\n1,1,y\n";
/// let costs = "feature,cost\na,1\nb,5\n";
/// let ds = Dataset::from_readers(data.as_bytes(), "d.csv", costs.as_bytes(), "c.csv", &DatasetOptions::new("t")).unwrap();
/// for kind in [LearnerKind::CsId3, LearnerKind::Id3] {
///     let plain = cslearn::stream_dataset_with(&ds, kind, 3, Procedure::Plain);
///     assert_eq!(plain, cslearn::stream_dataset_with(&ds, kind, 3, Procedure::Indexed));
/// }
/// ```
pub fn stream_dataset_with(
    dataset: &Dataset,
    kind: LearnerKind,
    seed: u64,
    procedure: Procedure,
) -> StreamReport {
    stream(dataset, kind, seed, procedure, &mut |_, _| {}).0
}

/// [`stream_dataset`], calling `progress(done, total)` as each object is taken up, so a
/// long stream can show a sign of life. The report is exactly [`stream_dataset`]'s.
///
/// ```
/// use cslearn::{Dataset, DatasetOptions, LearnerKind};
/// let data = "a,t\n0,n\n1,y\n0,n\n";
/// let ds = Dataset::from_readers(data.as_bytes(), "d.csv", "feature,cost\na,1\n".as_bytes(), "c.csv", &DatasetOptions::new("t")).unwrap();
/// let mut seen = Vec::new();
/// let report = cslearn::stream_dataset_with_progress(&ds, LearnerKind::CsId3, 1, &mut |done, total| seen.push((done, total)));
/// assert_eq!(seen, [(0, 3), (1, 3), (2, 3)]);
/// assert_eq!(report, cslearn::stream_dataset(&ds, LearnerKind::CsId3, 1));
/// ```
pub fn stream_dataset_with_progress(
    dataset: &Dataset,
    kind: LearnerKind,
    seed: u64,
    progress: &mut dyn FnMut(usize, usize),
) -> StreamReport {
    stream(dataset, kind, seed, Procedure::Indexed, progress).0
}

/// [`stream_dataset_with_progress`], also giving the library the learner ended with (what
/// a [`Model`](crate::Model) keeps).
///
/// ```
/// use cslearn::{Dataset, DatasetOptions, LearnerKind};
/// let data = "a,t\n0,n\n1,y\n0,n\n";
/// let ds = Dataset::from_readers(data.as_bytes(), "d.csv", "feature,cost\na,1\n".as_bytes(), "c.csv", &DatasetOptions::new("t")).unwrap();
/// let (report, library) = cslearn::stream_dataset_keeping(&ds, LearnerKind::CsId3, 1, &mut |_, _| {});
/// assert_eq!(report, cslearn::stream_dataset(&ds, LearnerKind::CsId3, 1));
/// assert_eq!(library.len(), 3);
/// ```
pub fn stream_dataset_keeping(
    dataset: &Dataset,
    kind: LearnerKind,
    seed: u64,
    progress: &mut dyn FnMut(usize, usize),
) -> (StreamReport, Library) {
    stream(dataset, kind, seed, Procedure::Indexed, progress)
}

fn stream(
    dataset: &Dataset,
    kind: LearnerKind,
    seed: u64,
    procedure: Procedure,
    progress: &mut dyn FnMut(usize, usize),
) -> (StreamReport, Library) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let order = dataset.shuffled(&mut rng);
    let total = order.len();
    let objects = order.iter().enumerate().map(|(done, &i)| {
        progress(done, total);
        (dataset.object(i), dataset.labels()[i])
    });
    let costs = dataset.costs().clone();
    // The library is taken out of the learner, not copied: it can be most of the memory.
    macro_rules! indexed {
        ($learner:expr) => {{
            let mut learner = $learner;
            let report = learner.stream(objects);
            (report, learner.into_library())
        }};
    }
    macro_rules! plain {
        ($learner:expr) => {{
            let mut learner = $learner;
            let report = learner.stream(objects);
            (report, std::mem::take(learner.library_mut()))
        }};
    }
    match (kind, procedure) {
        (LearnerKind::CsId3, Procedure::Indexed) => indexed!(cs_id3_indexed(costs)),
        (LearnerKind::CsId3, Procedure::Plain) => plain!(cs_id3(costs)),
        (LearnerKind::CsIbl { tolerance }, _) => plain!(cs_ibl(costs, tolerance)),
        (LearnerKind::Id3, Procedure::Indexed) => indexed!(id3_indexed(costs, rng)),
        (LearnerKind::Id3, Procedure::Plain) => plain!(id3(costs, rng)),
    }
}
