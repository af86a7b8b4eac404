//! The learners of the test-cost family, by name, and ICET's genetic search.

use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

use super::act::{Act, ActParams};
use super::budget::Budget;
use super::criterion::Criterion;
use super::cvt::{CvtChoice, CvtParams, CvtTries, cvt_tree_in};
use super::data::Frame;
use super::evaluate::shuffle;
use super::prices::{MisclassCosts, TestPrices};
use super::splits::Splits;
use super::stop::Stop;
use super::tree::{CostTree, GrowParams, Pruning, SelectionPrices};
use super::voi::{VoiParams, voi_tree_in, voi_trie};
use crate::Error;

/// A learner of the family.
///
/// ```
/// use cslearn::testcost::Method;
/// assert_eq!(Method::parse("eg2").unwrap(), Method::Eg2);
/// assert_eq!(Method::CsId3Batch.name(), "cs-id3-batch");
/// assert!(Method::parse("c5").unwrap_err().to_string().contains("c45"));
/// ```
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub enum Method {
    /// ID3: information gain, no pruning.
    Id3,
    /// C4.5: gain ratio, numeric thresholds, pessimistic pruning.
    C45,
    /// IDX: gain / price, pruned as C4.5.
    Idx,
    /// CS-ID3 as a batch tree: gain^2 / price, pruned as C4.5.
    CsId3Batch,
    /// EG2: (2^gain - 1) / (price + 1)^w, pruned as C4.5.
    Eg2,
    /// DTMC: the largest reduction of expected total cost; stops when none reduces it.
    Dtmc,
    /// ICET: EG2 with prices, w and pruning confidence found by a genetic search.
    Icet,
    /// ACT: each split chosen by the cost of stochastic EG2 trees sampled under it.
    Act,
    /// CVT, the cost-validated tree: the grower and the point where growth stops chosen
    /// by cross-validated total cost.
    Cvt,
    /// VOI, the value-of-information tree: each test bought where, looking
    /// [`VoiParams::lookahead`] tests ahead under smoothed class estimates, it lowers the
    /// expected total cost.
    Voi,
}

impl Method {
    /// Every learner, in the order of the benchmark's tables.
    pub const ALL: [Method; 10] = [
        Method::C45,
        Method::Id3,
        Method::Idx,
        Method::CsId3Batch,
        Method::Eg2,
        Method::Dtmc,
        Method::Icet,
        Method::Act,
        Method::Cvt,
        Method::Voi,
    ];

    /// The learner's name, as `csrl classify --learner` and `cargo xtask testcost` spell it.
    ///
    /// ```
    /// assert_eq!(cslearn::testcost::Method::C45.name(), "c45");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Method::Id3 => "id3-batch",
            Method::C45 => "c45",
            Method::Idx => "idx",
            Method::CsId3Batch => "cs-id3-batch",
            Method::Eg2 => "eg2",
            Method::Dtmc => "dtmc",
            Method::Icet => "icet",
            Method::Act => "act",
            Method::Cvt => "cvt",
            Method::Voi => "voi",
        }
    }

    /// The learner called `name`.
    ///
    /// ```
    /// assert_eq!(cslearn::testcost::Method::parse("icet").unwrap(), cslearn::testcost::Method::Icet);
    /// ```
    pub fn parse(name: &str) -> Result<Method, Error> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == name)
            .ok_or_else(|| Error::Invalid {
                what: format!("learner `{name}`"),
                reason: format!(
                    "not a learner of the family (learners: {})",
                    Method::ALL.map(Method::name).join(", ")
                ),
            })
    }

    /// Whether the tree's shape depends on the misclassification costs (DTMC, ICET, ACT,
    /// CVT);
    /// the others grow the same tree whatever they are and only label it by them.
    ///
    /// ```
    /// assert!(cslearn::testcost::Method::Dtmc.depends_on_mc());
    /// assert!(!cslearn::testcost::Method::Eg2.depends_on_mc());
    /// ```
    pub fn depends_on_mc(self) -> bool {
        matches!(
            self,
            Method::Dtmc | Method::Icet | Method::Act | Method::Cvt | Method::Voi
        )
    }

    /// How the learner grows its tree (ICET: the start of its search; ACT: the EG2 it
    /// samples with, and its pruning; CVT: the first of its growers, unpruned).
    ///
    /// ```
    /// use cslearn::testcost::{FamilyParams, Method};
    /// assert_eq!(Method::Idx.grow_params(&FamilyParams::default()).confidence, Some(0.25));
    /// ```
    pub fn grow_params(self, params: &FamilyParams) -> GrowParams {
        let pruned = |c| GrowParams::new(c).pruned(params.confidence);
        let grow = match self {
            Method::Id3 => GrowParams::new(Criterion::Id3),
            Method::C45 => pruned(Criterion::C45),
            Method::Idx => pruned(Criterion::Idx),
            Method::CsId3Batch => pruned(Criterion::CsId3),
            Method::Eg2 | Method::Icet => pruned(Criterion::Eg2 { w: params.eg2_w }),
            Method::Dtmc | Method::Voi => GrowParams::new(Criterion::Dtmc),
            Method::Act => GrowParams::new(Criterion::Eg2 { w: params.eg2_w })
                .pruned(params.act.confidence)
                .pruning_by(Pruning::Costs),
            Method::Cvt => GrowParams::new(Criterion::Eg2 { w: 0.0 }),
        };
        let grow = grow.selecting_at(params.selection_prices);
        if self.grows_within_budget() {
            grow.within(params.budget)
        } else {
            grow
        }
    }

    /// Whether [`fit`] grows the learner's tree within [`FamilyParams::budget`] (the
    /// greedy learners: ID3, C4.5, IDX, CS-ID3, EG2, DTMC), rather than leaving the budget
    /// to classification ([`CostTree::classify_within`]): ICET chooses its tests at
    /// biased prices, ACT's lookahead and CVT's growers choose theirs through their own
    /// searches, and their trees are cut only where an object runs out of budget.
    ///
    /// ```
    /// use cslearn::testcost::{Budget, FamilyParams, Method};
    /// let params = FamilyParams { budget: Budget::new(None, Some(2)).unwrap(), ..FamilyParams::default() };
    /// assert_eq!(Method::Eg2.grow_params(&params).budget, params.budget);
    /// assert!(!Method::Act.grows_within_budget());
    /// ```
    pub fn grows_within_budget(self) -> bool {
        !matches!(self, Method::Icet | Method::Act | Method::Cvt)
    }
}

/// The family's settings.
///
/// ```
/// let p = cslearn::testcost::FamilyParams::default();
/// assert_eq!((p.confidence, p.eg2_w, p.icet.population, p.icet.generations), (0.25, 1.0, 50, 20));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FamilyParams {
    /// C4.5's pruning confidence, for every pruned learner but ICET (which searches it).
    pub confidence: f64,
    /// EG2's weight of the price.
    pub eg2_w: f64,
    /// ICET's search.
    pub icet: IcetParams,
    /// ACT's sampling.
    #[serde(default)]
    pub act: ActParams,
    /// CVT's cross-validation.
    #[serde(default)]
    pub cvt: CvtParams,
    /// VOI's lookahead and smoothing.
    #[serde(default, skip_serializing_if = "VoiParams::is_default")]
    pub voi: VoiParams,
    /// The price every learner's selection function sees for a test: after the node's
    /// path (the default) or as listed.
    #[serde(default)]
    pub selection_prices: SelectionPrices,
    /// The most one object may spend on tests. The greedy learners grow within it
    /// ([`Method::grows_within_budget`]); every learner's tree is held to it when it
    /// classifies through [`CostTree::classify_within`]. Unlimited by default, which
    /// learns the same trees as before budgets existed.
    #[serde(default, skip_serializing_if = "Budget::is_unlimited")]
    pub budget: Budget,
    /// The most features ACT's sampled lookahead (ACT with samples, and CVT's lookahead
    /// grower) may be run on ([`FamilyParams::check`]):
    /// [`DEFAULT_MAX_LOOKAHEAD_FEATURES`](FamilyParams::DEFAULT_MAX_LOOKAHEAD_FEATURES)
    /// unless raised.
    #[serde(
        default = "default_max_lookahead_features",
        skip_serializing_if = "is_default_max_lookahead_features"
    )]
    pub max_lookahead_features: usize,
}

fn default_max_lookahead_features() -> usize {
    FamilyParams::DEFAULT_MAX_LOOKAHEAD_FEATURES
}

fn is_default_max_lookahead_features(features: &usize) -> bool {
    *features == FamilyParams::DEFAULT_MAX_LOOKAHEAD_FEATURES
}

impl Default for FamilyParams {
    fn default() -> FamilyParams {
        FamilyParams {
            confidence: 0.25,
            eg2_w: 1.0,
            icet: IcetParams::default(),
            act: ActParams::default(),
            cvt: CvtParams::default(),
            voi: VoiParams::default(),
            selection_prices: SelectionPrices::Path,
            budget: Budget::UNLIMITED,
            max_lookahead_features: FamilyParams::DEFAULT_MAX_LOOKAHEAD_FEATURES,
        }
    }
}

impl FamilyParams {
    /// The most class weights a fit may hold ([`check`](FamilyParams::check)): 2^27, a
    /// GiB of them.
    pub const MAX_CLASS_WEIGHTS: usize = 1 << 27;

    /// The most features ACT's sampled lookahead is run on unless
    /// [`max_lookahead_features`](FamilyParams::max_lookahead_features) says otherwise. At
    /// every node the lookahead grows trees under each branch of every candidate test, and
    /// each of their nodes scores every test, so its time grows with the square of the
    /// features: on 50 objects one ACT fit took 1.2 s on 200 features, 6.7 s on 500 and
    /// about 36 s on 1000, CVT about four times as long; on 10,000 it would take hours.
    pub const DEFAULT_MAX_LOOKAHEAD_FEATURES: usize = 1000;

    /// Whether `method` can learn with these settings from `objects` training objects of
    /// `frame`, checked before anything is allocated: CVT's folds at most the objects (a
    /// fold holds at least one), ICET's search within [`IcetParams::MAX_POPULATION`] and
    /// [`IcetParams::MAX_GENERATIONS`] and on at least 2 objects, ACT's samples within
    /// [`ActParams::MAX_SAMPLES`]; a learner's settings are checked only when it reads
    /// them. The front ends call it with the smallest training part's size.
    ///
    /// Whatever the learner, the weights a fit may hold are bounded: every node of a tree
    /// and every cell of a split trie keeps one weight per class, a tree may grow about a
    /// node per training object (one per object of its own class, where the classes are
    /// as many as the objects), and a fit holds a trie and a tree (ICET and ACT a third:
    /// the search's trie, the lookahead's cells), CVT ten on each of its folds and on all
    /// the objects. Classes times objects times those copies must be at most
    /// [`MAX_CLASS_WEIGHTS`](FamilyParams::MAX_CLASS_WEIGHTS): a target with as many
    /// classes as objects (a numeric column named as the class) is refused here, not
    /// after gigabytes. ACT with samples and CVT (its lookahead grower) are refused on
    /// more features than [`max_lookahead_features`](FamilyParams::max_lookahead_features).
    ///
    /// ```
    /// use cslearn::testcost::{Column, CvtParams, FamilyParams, Frame, Method};
    /// let frame = |classes: u32| Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0; 20_000])],
    ///     (0..20_000).map(|i| i % classes).collect(), (0..classes).map(|c| c.to_string()).collect()).unwrap();
    /// let p = FamilyParams { cvt: CvtParams::with_folds(10).unwrap(), ..FamilyParams::default() };
    /// let two = frame(2);
    /// assert!(p.check(Method::Cvt, &two, 10).is_ok());
    /// let e = p.check(Method::Cvt, &two, 9).unwrap_err().to_string();
    /// assert!(e.contains("10 folds") && e.contains("9 training objects"), "{e}");
    /// assert!(p.check(Method::Eg2, &two, 9).is_ok());
    /// // 10,000 classes of two objects each: too many weights for any learner.
    /// let e = p.check(Method::Eg2, &frame(10_000), 18_000).unwrap_err().to_string();
    /// assert!(e.contains("10000 classes over 18000 training objects"), "{e}");
    /// // 1001 features: the lookahead would take too long, unless the limit is raised.
    /// let wide = Frame::new((0..1001).map(|j| format!("x{j}")).collect(),
    ///     (0..1001).map(|_| Column::Numeric(vec![0.0; 6])).collect(), vec![0, 1, 0, 1, 0, 1],
    ///     vec!["a".into(), "b".into()]).unwrap();
    /// let e = FamilyParams::default().check(Method::Cvt, &wide, 6).unwrap_err().to_string();
    /// assert!(e.contains("1001 features for CVT's lookahead grower") && e.contains("at most 1000"), "{e}");
    /// let raised = FamilyParams { max_lookahead_features: 1001, ..FamilyParams::default() };
    /// assert!(raised.check(Method::Cvt, &wide, 6).is_ok());
    /// ```
    pub fn check(&self, method: Method, frame: &Frame, objects: usize) -> Result<(), Error> {
        let invalid = |what: String, reason: String| Err(Error::Invalid { what, reason });
        let cvt = self.cvt.folds;
        if method == Method::Cvt && (cvt < 2 || cvt > objects) {
            return invalid(
                format!("{cvt} folds for CVT"),
                format!(
                    "between 2 and the {objects} training objects (each fold holds at least one)"
                ),
            );
        }
        if method == Method::Voi {
            self.voi.check()?;
        }
        let features = frame.feature_count();
        let lookahead = match method {
            Method::Act if self.act.samples > 0 => Some("ACT's lookahead"),
            Method::Cvt if self.cvt.samples > 0 => Some("CVT's lookahead grower"),
            Method::Voi if self.voi.lookahead_for(features) > 1 => Some("VOI's lookahead"),
            _ => None,
        };
        if let Some(lookahead) = lookahead
            && features > self.max_lookahead_features
        {
            return invalid(
                format!("{features} features for {lookahead}"),
                format!(
                    "at most {} (the lookahead grows trees under every candidate test, each of \
                     whose nodes scores every test: its time grows with the square of the \
                     features)",
                    self.max_lookahead_features
                ),
            );
        }
        let classes = frame.class_count();
        let copies = match method {
            Method::Cvt => 10 * (cvt + 1),
            Method::Icet | Method::Act => 3,
            _ => 2,
        };
        let weights = classes.saturating_mul(objects).saturating_mul(copies);
        if weights > FamilyParams::MAX_CLASS_WEIGHTS {
            return invalid(
                format!("{classes} classes over {objects} training objects"),
                format!(
                    "every node of a tree keeps a weight per class, and {} may hold {copies} \
                     nodes or trie cells per training object: {weights} weights, more than the \
                     {} a fit may hold (a numeric column named as the class? merge its values \
                     into fewer classes)",
                    method.name(),
                    FamilyParams::MAX_CLASS_WEIGHTS
                ),
            );
        }
        let icet = &self.icet;
        if method == Method::Icet {
            if icet.population < 2 || icet.population > IcetParams::MAX_POPULATION {
                return invalid(
                    format!("an ICET population of {}", icet.population),
                    format!("between 2 and {}", IcetParams::MAX_POPULATION),
                );
            }
            if icet.generations < 1 || icet.generations > IcetParams::MAX_GENERATIONS {
                return invalid(
                    format!("{} ICET generations", icet.generations),
                    format!("between 1 and {}", IcetParams::MAX_GENERATIONS),
                );
            }
            if icet.search_objects < 2 {
                return invalid(
                    format!("an ICET search on {} objects", icet.search_objects),
                    "at least 2 (one per half)".into(),
                );
            }
        }
        if method == Method::Act && self.act.samples > ActParams::MAX_SAMPLES {
            return invalid(
                format!("{} ACT samples", self.act.samples),
                format!("at most {}", ActParams::MAX_SAMPLES),
            );
        }
        if method == Method::Cvt {
            self.cvt.with_samples(self.cvt.samples)?;
        }
        Ok(())
    }
}

/// ICET's genetic search (Turney 1995): each individual is one price bias per test, EG2's
/// `w` and the pruning confidence; its fitness is the mean total cost (real prices plus
/// misclassification) on one half of the training objects of the EG2 tree it grows on
/// the other half. Turney's population (50) and number of generations (20: 1000 trees).
///
/// ```
/// let p = cslearn::testcost::IcetParams::default();
/// assert_eq!(p.population * p.generations, 1000);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct IcetParams {
    /// Individuals per generation.
    pub population: usize,
    /// Generations (the first one included).
    pub generations: usize,
    /// The chance that two parents are crossed (Turney's GENESIS setting, 0.6).
    pub crossover: f64,
    /// The chance that one gene of a child is drawn anew.
    pub mutation: f64,
    /// The most training objects the search uses (half to grow, half to score), drawn
    /// stratified; the final tree grows on all of them. 400 by default, which leaves
    /// Turney's smaller data sets whole and keeps the search's cost bounded on large ones.
    pub search_objects: usize,
    /// How its trees are pruned: by errors, as C4.5 and Turney's ICET (the default), or
    /// by total cost at the real prices ([`Pruning::Costs`]), which lets the search cut a
    /// test that does not pay for itself.
    #[serde(default)]
    pub pruning: Pruning,
}

impl IcetParams {
    /// The largest population [`FamilyParams::check`] accepts (200 times Turney's).
    pub const MAX_POPULATION: usize = 10_000;
    /// The most generations [`FamilyParams::check`] accepts (500 times Turney's).
    pub const MAX_GENERATIONS: usize = 10_000;
}

impl Default for IcetParams {
    fn default() -> IcetParams {
        IcetParams {
            population: 50,
            generations: 20,
            crossover: 0.6,
            mutation: 0.05,
            search_objects: 400,
            pruning: Pruning::Errors,
        }
    }
}

/// The best individual ICET found.
///
/// ```
/// let g = cslearn::testcost::IcetGenome { prices: vec![1.0], w: 1.0, confidence: 0.25, fitness: 3.0 };
/// assert_eq!(g.prices.len(), 1);
/// ```
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct IcetGenome {
    /// The biased price of each test EG2 selects with.
    pub prices: Vec<f64>,
    /// EG2's `w`.
    pub w: f64,
    /// The pruning confidence.
    pub confidence: f64,
    /// Its mean total cost on the held-out half.
    pub fitness: f64,
}

/// A learned tree, and for ICET the individual it was grown from, for CVT its choice.
#[derive(Clone, Debug, PartialEq)]
pub struct Fitted {
    /// The tree.
    pub tree: CostTree,
    /// ICET's best individual (`None` for the other learners).
    pub genome: Option<IcetGenome>,
    /// CVT's grower and stopping point (`None` for the other learners).
    pub cvt: Option<CvtChoice>,
}

/// Learns a tree with `method` on the objects `rows` of `frame`. `seed` matters only to
/// ICET (its halves and its search), ACT (its samples) and CVT (its folds).
///
/// ```
/// use cslearn::testcost::{fit, Column, FamilyParams, Frame, Method, MisclassCosts, TestPrices};
/// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric((0..20).map(f64::from).collect())],
///     (0..20).map(|i| u32::from(i >= 10)).collect(), vec!["a".into(), "b".into()]).unwrap();
/// let prices = TestPrices::flat(&[5.0]).unwrap();
/// let mc = MisclassCosts::uniform(2, 100.0).unwrap();
/// let rows: Vec<usize> = (0..20).collect();
/// for method in Method::ALL {
///     let fitted = fit(method, &frame, &rows, &prices, &mc, &FamilyParams::default(), 1);
///     assert_eq!(fitted.tree.classify(&frame, 15, &prices).class, 1, "{}", method.name());
/// }
/// ```
pub fn fit(
    method: Method,
    frame: &Frame,
    rows: &[usize],
    prices: &TestPrices,
    mc: &MisclassCosts,
    params: &FamilyParams,
    seed: u64,
) -> Fitted {
    fit_watching(
        method,
        frame,
        rows,
        prices,
        mc,
        params,
        seed,
        &Stop::default(),
    )
}

/// [`fit`], unless `stop` is requested before it ends: then it ends at once (every trie it
/// grows through offers no more tests, ICET's search takes no more individuals) with
/// [`Error::Stopped`], and what it grew is dropped. A stop never requested gives
/// [`fit`]'s tree, to the bit.
///
/// # Errors
/// [`Error::Stopped`] when `stop` was requested.
///
/// ```
/// use cslearn::testcost::{fit, fit_until, Column, FamilyParams, Frame, Method, MisclassCosts, Stop, TestPrices};
/// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric((0..20).map(f64::from).collect())],
///     (0..20).map(|i| u32::from(i >= 10)).collect(), vec!["a".into(), "b".into()]).unwrap();
/// let (prices, mc) = (TestPrices::flat(&[5.0]).unwrap(), MisclassCosts::uniform(2, 100.0).unwrap());
/// let rows: Vec<usize> = (0..20).collect();
/// let params = FamilyParams::default();
/// let stop = Stop::default();
/// let fitted = fit_until(Method::Act, &frame, &rows, &prices, &mc, &params, 1, &stop).unwrap();
/// assert_eq!(fitted, fit(Method::Act, &frame, &rows, &prices, &mc, &params, 1));
/// stop.request();
/// let stopped = fit_until(Method::Act, &frame, &rows, &prices, &mc, &params, 1, &stop);
/// assert!(matches!(stopped, Err(cslearn::Error::Stopped)));
/// ```
#[expect(clippy::too_many_arguments, reason = "fit's arguments and the stop")]
pub fn fit_until(
    method: Method,
    frame: &Frame,
    rows: &[usize],
    prices: &TestPrices,
    mc: &MisclassCosts,
    params: &FamilyParams,
    seed: u64,
    stop: &Stop,
) -> Result<Fitted, Error> {
    let fitted = fit_watching(method, frame, rows, prices, mc, params, seed, stop);
    if stop.is_requested() {
        return Err(Error::Stopped);
    }
    Ok(fitted)
}

/// [`fit`] through split tries that watch `stop`.
#[expect(clippy::too_many_arguments, reason = "fit's arguments and the stop")]
fn fit_watching(
    method: Method,
    frame: &Frame,
    rows: &[usize],
    prices: &TestPrices,
    mc: &MisclassCosts,
    params: &FamilyParams,
    seed: u64,
    stop: &Stop,
) -> Fitted {
    if matches!(method, Method::Act | Method::Cvt) {
        // Their tree at one cost is fit_each's, through tries of its own.
        let mut one = fit_each_watching(
            method,
            frame,
            rows,
            prices,
            std::slice::from_ref(mc),
            params,
            seed,
            stop,
        );
        return one.remove(0);
    }
    if method == Method::Voi {
        let grow = method.grow_params(params);
        let mut splits = voi_trie(frame, rows, mc, &grow);
        splits.watch(stop);
        return Fitted {
            tree: voi_tree_in(&mut splits, prices, mc, &params.voi, &grow),
            genome: None,
            cvt: None,
        };
    }
    if method == Method::Icet {
        let genome = icet_search(frame, rows, prices, mc, params, seed, stop);
        let biased = prices
            .repriced(&genome.prices)
            .unwrap_or_else(|_| prices.clone());
        let grow = GrowParams::new(Criterion::Eg2 { w: genome.w })
            .pruned(genome.confidence)
            .selecting_at(params.selection_prices);
        let grow = grow.pruning_by(params.icet.pruning);
        return Fitted {
            tree: icet_tree(frame, rows, &biased, prices, mc, &grow, stop),
            genome: Some(genome),
            cvt: None,
        };
    }
    Fitted {
        tree: grow_watching(frame, rows, prices, mc, &method.grow_params(params), stop),
        genome: None,
        cvt: None,
    }
}

/// [`CostTree::grow`] through a split trie that watches `stop`.
fn grow_watching(
    frame: &Frame,
    rows: &[usize],
    prices: &TestPrices,
    mc: &MisclassCosts,
    params: &GrowParams,
    stop: &Stop,
) -> CostTree {
    let ones = vec![1.0; rows.len()];
    let mut splits = Splits::new(frame, rows, &ones, mc, params.criterion, params.min_objects);
    splits.watch(stop);
    CostTree::grow_in(&mut splits, prices, mc, params)
}

/// The tree `method` learns on the objects `rows` of `frame` at each misclassification
/// cost of `mcs`, in order: each one the tree [`fit`] learns at that cost with the same
/// seed, to the bit, for less time. A learner whose tree does not depend on the costs
/// ([`Method::depends_on_mc`]) grows it once and labels it at each; ACT and CVT grow
/// through split tries kept from one cost to the next, so that the statistics of a set
/// of objects (which do not depend on the costs, DTMC's aside) are computed once for
/// all of them; DTMC and ICET fit at each cost alone.
///
/// ```
/// use cslearn::testcost::{fit, fit_each, Column, FamilyParams, Frame, Method, MisclassCosts, TestPrices};
/// let x: Vec<f64> = (0..60).map(|i| f64::from((i * 7) % 60)).collect();
/// let y: Vec<f64> = (0..60).map(|i| f64::from((i * 11) % 60)).collect();
/// let classes: Vec<u32> = (0..60).map(|i| u32::from(x[i] + y[i] > 50.0)).collect();
/// let frame = Frame::new(vec!["x".into(), "y".into()], vec![Column::Numeric(x), Column::Numeric(y)],
///     classes, vec!["a".into(), "b".into()]).unwrap();
/// let prices = TestPrices::flat(&[4.0, 9.0]).unwrap();
/// let mcs: Vec<MisclassCosts> = [20.0, 100.0, 500.0]
///     .map(|m| MisclassCosts::uniform(2, m).unwrap()).to_vec();
/// let rows: Vec<usize> = (0..60).collect();
/// let params = FamilyParams::default();
/// let each = fit_each(Method::Act, &frame, &rows, &prices, &mcs, &params, 3);
/// for (fitted, mc) in each.iter().zip(&mcs) {
///     assert_eq!(fitted, &fit(Method::Act, &frame, &rows, &prices, mc, &params, 3));
/// }
/// ```
pub fn fit_each(
    method: Method,
    frame: &Frame,
    rows: &[usize],
    prices: &TestPrices,
    mcs: &[MisclassCosts],
    params: &FamilyParams,
    seed: u64,
) -> Vec<Fitted> {
    fit_each_watching(
        method,
        frame,
        rows,
        prices,
        mcs,
        params,
        seed,
        &Stop::default(),
    )
}

/// [`fit_each`] through split tries that watch `stop`.
#[expect(
    clippy::too_many_arguments,
    reason = "fit_each's arguments and the stop"
)]
fn fit_each_watching(
    method: Method,
    frame: &Frame,
    rows: &[usize],
    prices: &TestPrices,
    mcs: &[MisclassCosts],
    params: &FamilyParams,
    seed: u64,
    stop: &Stop,
) -> Vec<Fitted> {
    let Some(first) = mcs.first() else {
        return Vec::new();
    };
    match method {
        Method::Act => {
            let act = |mc| Act {
                prices,
                mc,
                params: &params.act,
                w: params.eg2_w,
                selection: params.selection_prices,
                seed,
            };
            let mut splits = act(first).trie(frame, rows);
            splits.watch(stop);
            mcs.iter()
                .map(|mc| Fitted {
                    tree: act(mc).tree_in(&mut splits),
                    genome: None,
                    cvt: None,
                })
                .collect()
        }
        Method::Cvt => {
            let mut tries = CvtTries::default();
            mcs.iter()
                .map(|mc| {
                    let (tree, choice) = cvt_tree_in(
                        frame,
                        rows,
                        prices,
                        mc,
                        &params.cvt,
                        params.selection_prices,
                        seed,
                        &mut tries,
                        stop,
                    );
                    Fitted {
                        tree,
                        genome: None,
                        cvt: Some(choice),
                    }
                })
                .collect()
        }
        _ if method.depends_on_mc() => mcs
            .iter()
            .map(|mc| fit_watching(method, frame, rows, prices, mc, params, seed, stop))
            .collect(),
        _ => {
            let fitted = fit_watching(method, frame, rows, prices, first, params, seed, stop);
            mcs.iter()
                .map(|mc| {
                    let mut each = fitted.clone();
                    each.tree.relabel(mc);
                    each
                })
                .collect()
        }
    }
}

/// ICET's tree: grown by `grow` at the `biased` prices; pruned by errors, or by total
/// cost at the `real` prices (tests are chosen at the biased prices and must pay for
/// themselves at the real ones), as its search's fitness prunes it; grown through a split
/// trie that watches `stop`.
fn icet_tree(
    frame: &Frame,
    rows: &[usize],
    biased: &TestPrices,
    real: &TestPrices,
    mc: &MisclassCosts,
    grow: &GrowParams,
    stop: &Stop,
) -> CostTree {
    match (grow.pruning, grow.confidence) {
        (Pruning::Costs, Some(confidence)) => {
            let unpruned = GrowParams {
                confidence: None,
                ..*grow
            };
            let mut tree = grow_watching(frame, rows, biased, mc, &unpruned, stop);
            tree.prune_by_cost(confidence, real);
            tree
        }
        _ => grow_watching(frame, rows, biased, mc, grow, stop),
    }
}

/// The mean total cost (tests at `prices` plus misclassification at `mc`) of `tree` on
/// the objects `rows`.
///
/// ```
/// use cslearn::testcost::{mean_total_cost, Column, CostTree, Criterion, Frame, GrowParams, MisclassCosts, TestPrices};
/// let frame = Frame::new(vec!["x".into()], vec![Column::Numeric(vec![0.0, 1.0])],
///     vec![0, 1], vec!["a".into(), "b".into()]).unwrap();
/// let (prices, mc) = (TestPrices::flat(&[3.0]).unwrap(), MisclassCosts::uniform(2, 50.0).unwrap());
/// let stump = CostTree::grow(&frame, &[0], &prices, &mc, &GrowParams::new(Criterion::Id3));
/// assert_eq!(mean_total_cost(&stump, &frame, &[0, 1], &prices, &mc), 25.0);
/// ```
pub fn mean_total_cost(
    tree: &CostTree,
    frame: &Frame,
    rows: &[usize],
    prices: &TestPrices,
    mc: &MisclassCosts,
) -> f64 {
    if rows.is_empty() {
        return 0.0;
    }
    let total: f64 = rows
        .iter()
        .map(|&r| {
            let c = tree.classify(frame, r, prices);
            c.test_cost + mc.cost(c.class as usize, frame.class(r) as usize)
        })
        .sum();
    total / rows.len() as f64
}

/// The genes of one individual: a log2 factor per test, then `w`, then the confidence.
type Genes = Vec<f64>;

/// How far a price bias may move a price: (price + 1) * 2^u - 1 with u in [-SPAN, SPAN].
const SPAN: f64 = 6.0;

fn decode(genes: &Genes, prices: &TestPrices) -> (Vec<f64>, f64, f64) {
    let n = prices.len();
    let biased = (0..n)
        .map(|i| ((prices.test(i).full + 1.0) * genes[i].exp2() - 1.0).max(0.0))
        .collect();
    (biased, genes[n], genes[n + 1])
}

fn random_genes<R: rand::Rng>(n: usize, rng: &mut R) -> Genes {
    let mut genes: Genes = (0..n).map(|_| rng.random_range(-SPAN..=SPAN)).collect();
    genes.push(rng.random_range(0.0..=1.0));
    genes.push(rng.random_range(0.01..=0.99));
    genes
}

/// ICET's genetic search, its trees grown through a split trie that watches `stop`; it
/// takes no more individuals once `stop` is requested.
fn icet_search(
    frame: &Frame,
    rows: &[usize],
    prices: &TestPrices,
    mc: &MisclassCosts,
    params: &FamilyParams,
    seed: u64,
    stop: &Stop,
) -> IcetGenome {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let n = prices.len();
    // Two halves, stratified by class: grow on one, score on the other.
    let mut by_class: Vec<Vec<usize>> = vec![Vec::new(); frame.class_count()];
    for &r in rows {
        by_class[frame.class(r) as usize].push(r);
    }
    // Each class shuffled, then all interleaved in proportion (the object at position i
    // of a class of n comes at (i + 0.5) / n), so any prefix is stratified too.
    let mut dealt: Vec<(f64, usize)> = Vec::with_capacity(rows.len());
    for class_rows in &mut by_class {
        shuffle(class_rows, &mut rng);
        let n = class_rows.len() as f64;
        for (i, &r) in class_rows.iter().enumerate() {
            dealt.push(((i as f64 + 0.5) / n, r));
        }
    }
    dealt.sort_by(|a, b| a.0.total_cmp(&b.0));
    dealt.truncate(params.icet.search_objects.max(2));
    let (mut grow_half, mut score_half) = (Vec::new(), Vec::new());
    for (i, &(_, r)) in dealt.iter().enumerate() {
        if i % 2 == 0 {
            grow_half.push(r);
        } else {
            score_half.push(r);
        }
    }
    if score_half.is_empty() {
        score_half.clone_from(&grow_half);
    }
    // Every tree of the search grows on the same half: they share one split trie.
    let min_objects = GrowParams::new(Criterion::Eg2 { w: 1.0 }).min_objects;
    let ones = vec![1.0; grow_half.len()];
    let mut splits = Splits::new(
        frame,
        &grow_half,
        &ones,
        mc,
        Criterion::Eg2 { w: 1.0 },
        min_objects,
    );
    splits.hold_out(&score_half);
    splits.watch(stop);
    let mut fitness = |genes: &Genes| -> f64 {
        let (biased, w, confidence) = decode(genes, prices);
        let biased = prices.repriced(&biased).unwrap_or_else(|_| prices.clone());
        let grow = GrowParams::new(Criterion::Eg2 { w })
            .pruned(confidence)
            .selecting_at(params.selection_prices)
            .pruning_by(params.icet.pruning);
        CostTree::held_out_cost(&mut splits, &biased, prices, mc, &grow)
    };

    let icet = params.icet;
    let size = icet.population.max(2);
    // The first individual is plain EG2 with C4.5's confidence: the search starts from it.
    let mut start: Genes = vec![0.0; n];
    start.push(params.eg2_w);
    start.push(params.confidence);
    let mut population: Vec<(Genes, f64)> = Vec::with_capacity(size);
    population.push((start.clone(), fitness(&start)));
    while population.len() < size && !stop.is_requested() {
        let genes = random_genes(n, &mut rng);
        let f = fitness(&genes);
        population.push((genes, f));
    }
    for _ in 1..icet.generations.max(1) {
        if stop.is_requested() {
            break;
        }
        let best = population
            .iter()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .cloned()
            .unwrap_or_else(|| (start.clone(), f64::INFINITY));
        let mut next = vec![best];
        while next.len() < size && !stop.is_requested() {
            let pick = |rng: &mut Xoshiro256PlusPlus| {
                let a = &population[rng.random_range(0..population.len())];
                let b = &population[rng.random_range(0..population.len())];
                if a.1 <= b.1 { a.0.clone() } else { b.0.clone() }
            };
            let mut child = pick(&mut rng);
            if rng.random_bool(icet.crossover.clamp(0.0, 1.0)) {
                let other = pick(&mut rng);
                for (g, o) in child.iter_mut().zip(other) {
                    if rng.random_bool(0.5) {
                        *g = o;
                    }
                }
            }
            let fresh = random_genes(n, &mut rng);
            for (g, f) in child.iter_mut().zip(fresh) {
                if rng.random_bool(icet.mutation.clamp(0.0, 1.0)) {
                    *g = f;
                }
            }
            let f = fitness(&child);
            next.push((child, f));
        }
        population = next;
    }
    let (genes, fitness) = population
        .into_iter()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((start, f64::INFINITY));
    let (biased, w, confidence) = decode(&genes, prices);
    IcetGenome {
        prices: biased,
        w,
        confidence,
        fitness,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testcost::Catalogue;

    /// ICET's fitness, computed from the weights sent down the split trie, is the mean
    /// total cost of classifying the held-out objects one by one, on data without
    /// missing values, for any prices, `w` and confidence.
    #[test]
    fn held_out_cost_equals_classifying_one_by_one() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
        let catalogue = Catalogue::read(&root.join("datasets.toml")).unwrap();
        for name in ["bupa", "tae", "monks2"] {
            let frame = catalogue.load(name).unwrap().frame;
            let prices = crate::testcost::random_prices(frame.feature_count(), 1.0, 100.0, 5);
            let mc = MisclassCosts::uniform(frame.class_count(), 500.0).unwrap();
            let grow: Vec<usize> = (0..frame.len()).step_by(2).collect();
            let score: Vec<usize> = (1..frame.len()).step_by(2).collect();
            let ones = vec![1.0; grow.len()];
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(9);
            let mut splits = Splits::new(&frame, &grow, &ones, &mc, Criterion::Eg2 { w: 1.0 }, 2.0);
            splits.hold_out(&score);
            for i in 0..40 {
                let genes = random_genes(prices.len(), &mut rng);
                let (biased, w, confidence) = decode(&genes, &prices);
                let biased = prices.repriced(&biased).unwrap();
                // Every way of pricing a selection and of pruning, in turn.
                let params = GrowParams::new(Criterion::Eg2 { w })
                    .pruned(confidence)
                    .selecting_at(SelectionPrices::ALL[i % 2])
                    .pruning_by(Pruning::ALL[(i / 2) % 2]);
                let walked = CostTree::held_out_cost(&mut splits, &biased, &prices, &mc, &params);
                let tree = icet_tree(
                    &frame,
                    &grow,
                    &biased,
                    &prices,
                    &mc,
                    &params,
                    &Stop::default(),
                );
                let direct = mean_total_cost(&tree, &frame, &score, &prices, &mc);
                assert!(
                    (walked - direct).abs() < 1e-9 * direct.max(1.0),
                    "{name}: walked {walked}, classified {direct} ({params:?})"
                );
            }
        }
    }
}
