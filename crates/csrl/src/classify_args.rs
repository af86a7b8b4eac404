//! The flags of `csrl classify`, read by the incremental learners (`classify`) and by the
//! test-cost family (`testcost`), which `classify` hands the family's learners to.

use std::path::PathBuf;

use clap::{Args, ValueEnum};

/// The learners `csrl classify` can run: the incremental ones of the paper, and the
/// batch trees of the test-cost family (`cslearn::testcost`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum ClassifierKind {
    /// CS-ID3: I^2/C selection, cheapest-first discrimination.
    CsId3,
    /// CS-IBL: instances ranked by mismatches, tolerant of wrong values.
    CsIbl,
    /// Cost-blind ID3: every cost taken as equal, random discrimination order.
    Id3,
    /// Batch tree: ID3 (information gain, no pruning), cost-blind.
    #[value(name = "id3-batch")]
    Id3Batch,
    /// Batch tree: C4.5 (gain ratio, pessimistic pruning), cost-blind.
    #[value(name = "c45")]
    C45,
    /// Batch tree: IDX (gain / price), pruned as C4.5.
    #[value(name = "idx")]
    Idx,
    /// Batch tree: CS-ID3's gain^2 / price, pruned as C4.5.
    #[value(name = "cs-id3-batch")]
    CsId3Batch,
    /// Batch tree: EG2 ((2^gain - 1) / (price + 1)), pruned as C4.5.
    #[value(name = "eg2")]
    Eg2,
    /// Batch tree: DTMC (least expected total cost of tests and errors).
    #[value(name = "dtmc")]
    Dtmc,
    /// Batch tree: ICET (EG2 on prices found by a genetic search).
    #[value(name = "icet")]
    Icet,
    /// Batch tree: ACT (each split by the cost of stochastic EG2 trees sampled under it).
    #[value(name = "act")]
    Act,
    /// Batch tree: CVT (grower and stopping point chosen by cross-validated total cost).
    #[value(name = "cvt")]
    Cvt,
    /// Batch tree: VOI (each test bought where, looking two or three tests ahead under
    /// smoothed class estimates, it lowers the expected total cost).
    #[value(name = "voi")]
    Voi,
}

impl ClassifierKind {
    /// The learner of the test-cost family, for a batch tree.
    pub(crate) fn family(self) -> Option<cslearn::testcost::Method> {
        use cslearn::testcost::Method;
        match self {
            ClassifierKind::CsId3 | ClassifierKind::CsIbl | ClassifierKind::Id3 => None,
            ClassifierKind::Id3Batch => Some(Method::Id3),
            ClassifierKind::C45 => Some(Method::C45),
            ClassifierKind::Idx => Some(Method::Idx),
            ClassifierKind::CsId3Batch => Some(Method::CsId3Batch),
            ClassifierKind::Eg2 => Some(Method::Eg2),
            ClassifierKind::Dtmc => Some(Method::Dtmc),
            ClassifierKind::Icet => Some(Method::Icet),
            ClassifierKind::Act => Some(Method::Act),
            ClassifierKind::Cvt => Some(Method::Cvt),
            ClassifierKind::Voi => Some(Method::Voi),
        }
    }

    /// The name `--learner` takes.
    pub(crate) fn name(self) -> &'static str {
        match (self, self.family()) {
            (_, Some(method)) => method.name(),
            (ClassifierKind::CsId3, None) => "cs-id3",
            (ClassifierKind::CsIbl, None) => "cs-ibl",
            (_, None) => "id3",
        }
    }
}

/// Arguments of `csrl classify`.
#[derive(Args)]
#[command(
    after_help = "The incremental learners (cs-id3, cs-ibl, id3) stream the objects \
(prequential accuracy, and --holdout or --folds beside it). The batch trees of the test-cost \
family (id3-batch, c45, idx, cs-id3-batch, eg2, dtmc, icet, act, cvt) are grown on training parts and judged on \
the held-out objects by the total cost of their tests and errors (10-fold unless --holdout or \
--folds); they read numeric columns as numbers, --costs also in Turney's format \
(FILE.expense or FILE.cost) with --groups, and --mc, --mc-matrix and --cost-name. A flag \
that the chosen learner does not read is refused."
)]
pub struct ClassifyArgs {
    /// The data: a CSV file with a header, one object per row; empty cells and `?` are
    /// missing values.
    #[arg(long, value_name = "FILE.csv")]
    pub(crate) data: PathBuf,
    /// The price of each feature: a CSV file with the header `feature,cost`; for the
    /// family learners also Turney's format, a file ending in `.expense` (`name: full,
    /// discount`) or `.cost` (`name: price`).
    #[arg(long, value_name = "FILE.csv")]
    pub(crate) costs: PathBuf,
    /// The column holding the class.
    #[arg(long, value_name = "COLUMN")]
    pub(crate) target: String,
    /// Make two classes of the target: where EXPR holds and where not. EXPR is `>0`,
    /// `>=1`, `<2`, `<=2`, `==1`, `!=0` or a category name.
    #[arg(long, value_name = "EXPR", allow_hyphen_values = true)]
    pub(crate) positive_if: Option<String>,
    /// The learner.
    #[arg(long, value_enum, default_value_t = ClassifierKind::CsId3)]
    pub(crate) learner: ClassifierKind,
    /// The seed of the random order of the objects (and of ID3's discrimination orders;
    /// for the family, of the folds and of ICET's search).
    #[arg(long, default_value_t = 1)]
    pub(crate) seed: u64,
    /// CS-IBL only: the most wrong feature values tolerated per object (1 unless given).
    #[arg(long, value_name = "N")]
    pub(crate) tolerance: Option<u32>,
    /// Also evaluate on held-out data: this share of the objects (seeded) is the test
    /// part, the rest the training part (for the family, a share of each class).
    #[arg(long, value_name = "F", conflicts_with = "folds")]
    pub(crate) holdout: Option<f64>,
    /// Also evaluate by K-fold cross-validation (seeded folds; for the family,
    /// stratified by class, and 10 unless --holdout or --folds is given).
    #[arg(long, value_name = "K")]
    pub(crate) folds: Option<usize>,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub(crate) json: bool,
    /// CS-ID3 only: write the decision tree grown (I^2/C, observation semantics) from the
    /// library the prequential pass learned, as Graphviz DOT (`dot -Tsvg FILE.dot`).
    #[arg(long, value_name = "FILE.dot")]
    pub(crate) dot: Option<PathBuf>,
    /// Save what the prequential pass learned as a model file (versioned JSON, format
    /// `csrl-classifier`), for `csrl predict --model FILE`; for the family, the tree grown
    /// on every object (format `csrl-cost-tree`). It may not name an input file.
    #[arg(long, value_name = "MODEL.json")]
    pub(crate) save: Option<PathBuf>,
    /// Family only: Turney's groups of tests (a `.group` file: the group names on its
    /// first line, then `name: group.`); the first test of a group bought for an object
    /// is paid in full, the others at their discount. Needs --costs FILE.expense.
    #[arg(long, value_name = "FILE.group")]
    pub(crate) groups: Option<PathBuf>,
    /// Family only: what each wrong answer costs, the same for every pair of classes.
    /// Without --mc or --mc-matrix it is the price of every test together (discounts
    /// applied; 1 if that is 0), so that one error costs as much as measuring everything.
    #[arg(
        long,
        value_name = "N",
        conflicts_with = "mc_matrix",
        allow_negative_numbers = true
    )]
    pub(crate) mc: Option<f64>,
    /// Family only: a misclassification cost matrix, a CSV file with the header
    /// `actual,<class>,...` and one row `<class>,<costs>...` per class (the cost of each
    /// answer for an object of that class). Classes are named as the data names them
    /// (`no` and `yes` with --positive-if).
    #[arg(long, value_name = "FILE.csv")]
    pub(crate) mc_matrix: Option<PathBuf>,
    /// Family only: the price files call data column COLUMN by NAME (repeatable), as in
    /// `--cost-name thalch=thalach`.
    #[arg(long, value_name = "COLUMN=NAME")]
    pub(crate) cost_name: Vec<String>,
    /// Family only: the price the selection functions see for a test: `path` (after the
    /// node's path: a test done once is free further down; the default), `listed`
    /// (its listed price whatever the path, as the published implementations score
    /// tests) or `listed-once` (listed, but nothing for a test the path already did).
    /// An object pays after its path either way.
    #[arg(long, value_name = "path|listed|listed-once")]
    pub(crate) selection_prices: Option<String>,
    /// ICET only: how its trees are pruned: `errors` (C4.5's, Turney's; the default) or
    /// `costs` (a test must pay for itself at the real prices).
    #[arg(long, value_name = "errors|costs")]
    pub(crate) icet_pruning: Option<String>,
    /// ACT only: the trees sampled under each branch of each candidate test (its `r`;
    /// default 5). More samples, better estimates, more time.
    #[arg(long, value_name = "R")]
    pub(crate) act_samples: Option<usize>,
    /// CVT only: the folds of the cross-validation on the training objects that chooses
    /// its grower and where its tree stops (default 5; at least 2).
    #[arg(long, value_name = "K")]
    pub(crate) cvt_folds: Option<usize>,
    /// VOI only: how many tests ahead a test is valued, 1 to 3 (default: 3 on data of at
    /// most 21 features, 2 beyond): at 1 a test must pay for itself alone, at 2 a pair
    /// that pays together is bought.
    #[arg(long, value_name = "D")]
    pub(crate) voi_lookahead: Option<usize>,
    /// VOI only: what stopping at a node costs is estimated pessimistically, C4.5's
    /// upper limit of the error rate at this confidence (default 0.25).
    #[arg(long, value_name = "C")]
    pub(crate) voi_confidence: Option<f64>,
    /// VOI only: estimate what stopping costs by an m-estimate of the classes instead, the
    /// class shares weighing this many objects (0 takes the training counts as they are).
    #[arg(long, value_name = "M")]
    pub(crate) voi_m: Option<f64>,
    /// ACT only: the most threads one fit uses (default 1; 0 for every core): the
    /// candidate tests of a node are valued at the same time, and the tree and every
    /// output are the same on any number of threads.
    #[arg(long, value_name = "N")]
    pub(crate) act_threads: Option<usize>,
    /// CVT only: the most threads one fit uses (default 1; 0 for every core): its trees
    /// on all the objects and on each fold grow at the same time, each from its own seed,
    /// so the tree and every output are the same on any number of threads.
    #[arg(long, value_name = "N")]
    pub(crate) cvt_threads: Option<usize>,
    /// CVT only: the trees its lookahead grower samples under each branch (default 5,
    /// ACT's): fewer, a faster CVT (its time is mostly the lookahead's) and other trees; 0
    /// leaves the lookahead out, CVT choosing among its greedy growers only.
    #[arg(long, value_name = "R")]
    pub(crate) cvt_samples: Option<usize>,
    /// ACT and CVT only: the most features ACT's sampled lookahead (ACT, and CVT's
    /// lookahead grower) is run on (1000 by default): its time grows with the square of
    /// the features, and a wider table is refused unless this raises the limit.
    #[arg(long, value_name = "N")]
    pub(crate) max_lookahead_features: Option<usize>,
    /// Family only: the most one object may pay for its tests (after group discounts; a
    /// test done once is free further down). The greedy learners (id3-batch, c45, idx,
    /// cs-id3-batch, eg2, dtmc) grow within it; every learner's tree classifies within it,
    /// answering from the node whose test the object cannot afford.
    #[arg(long, value_name = "B", allow_negative_numbers = true)]
    pub(crate) max_test_cost: Option<f64>,
    /// Family only: the most distinct tests one object may buy, held as --max-test-cost
    /// is (the two together: whichever binds first).
    #[arg(long, value_name = "K")]
    pub(crate) max_tests: Option<usize>,
    /// Family only: the most distinct classes the target may have (1000 by default): a
    /// numeric column named as the target by mistake has as many classes as rows, and
    /// every node of a tree keeps a weight for each. Raised, a fit is still refused when
    /// its classes times its training objects would hold too many weights.
    #[arg(long, value_name = "N")]
    pub(crate) max_classes: Option<usize>,
}
