//! The trees ACT and CVT grow on the test-cost benchmark's data sets, fingerprinted: a
//! speed-up of the lookahead must grow the same trees, to the bit. Shared by the pin test
//! (`tests/lookahead_pins.rs`) and the speed example (`examples/lookahead_speed.rs`).

use std::path::{Path, PathBuf};

use cslearn::testcost::{
    Catalogue, CostTree, FamilyParams, Frame, Loaded, Method, MisclassCosts, SelectionPrices,
    TestPrices, fit, folds, random_prices,
};

/// One pinned tree: a data set, a learner, its prices, the prices selection sees, mc.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    pub dataset: String,
    pub learner: Method,
    /// `random` (uniform in [1, 100], seed 1) or `turney`.
    pub prices: String,
    pub selection: SelectionPrices,
    pub mc: f64,
    /// At most this many training objects, evenly spaced over the training part (the
    /// files of some data sets are sorted by class), 0 for all of them.
    pub objects: usize,
}

impl Case {
    /// The case's line in the pin file, without its fingerprint.
    pub fn key(&self) -> String {
        format!(
            "{} {} {} {} {} {}",
            self.dataset,
            self.learner.name(),
            self.prices,
            self.selection.name(),
            self.mc,
            self.objects
        )
    }

    /// Parses [`Case::key`].
    pub fn parse(key: &str) -> Case {
        let f: Vec<&str> = key.split_whitespace().collect();
        assert_eq!(
            f.len(),
            6,
            "a pin line has six fields before its fingerprint: {key}"
        );
        Case {
            dataset: f[0].to_string(),
            learner: Method::parse(f[1]).unwrap(),
            prices: f[2].to_string(),
            selection: SelectionPrices::parse(f[3]).unwrap(),
            mc: f[4].parse().unwrap(),
            objects: f[5].parse().unwrap(),
        }
    }

    /// The tree this case grows.
    pub fn grow(&self, loaded: &Loaded) -> CostTree {
        self.grow_on(loaded, 1)
    }

    /// The tree this case grows, ACT valuing a node's candidates on `threads` threads
    /// (the same tree on any number).
    pub fn grow_on(&self, loaded: &Loaded, threads: usize) -> CostTree {
        let frame: &Frame = &loaded.frame;
        let prices: TestPrices = match self.prices.as_str() {
            "random" => random_prices(frame.feature_count(), 1.0, 100.0, 1),
            "turney" => loaded
                .turney
                .clone()
                .expect("the data set has Turney's prices"),
            other => panic!("unknown prices {other}"),
        };
        let mc = MisclassCosts::uniform(frame.class_count(), self.mc).unwrap();
        let test = &folds(frame, 10, 1)[0];
        let mut train: Vec<usize> = (0..frame.len())
            .filter(|r| test.binary_search(r).is_err())
            .collect();
        if self.objects > 0 && self.objects < train.len() {
            let n = train.len();
            train = (0..self.objects)
                .map(|i| train[i * n / self.objects])
                .collect();
        }
        let defaults = FamilyParams::default();
        let params = FamilyParams {
            selection_prices: self.selection,
            act: defaults.act.with_threads(threads),
            ..defaults
        };
        fit(self.learner, frame, &train, &prices, &mc, &params, 1).tree
    }
}

/// The benchmark's manifest.
pub fn catalogue() -> Catalogue {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
    Catalogue::read(&root.join("datasets.toml")).unwrap()
}

/// The pin file.
pub fn pin_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/pins/lookahead.txt")
}

/// The pinned cases and their fingerprints, in the file's order.
pub fn pins() -> Vec<(Case, String)> {
    let text = std::fs::read_to_string(pin_file()).unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let (key, print) = l.rsplit_once(' ').unwrap();
            (Case::parse(key), print.to_string())
        })
        .collect()
}

/// FNV-1a over the tree's JSON, with its length: two trees have the same fingerprint when
/// they are the same tree (splits, thresholds, shares, labels and weights, to the bit).
pub fn fingerprint(tree: &CostTree) -> String {
    let json = serde_json::to_string(tree).unwrap();
    let hash = json.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    format!("{hash:016x}:{}", json.len())
}

/// The cases `cargo test` grows: ACT on every data set of the benchmark
/// ([`Catalogue::benchmark`]: not the sets kept for budgets only) at mc 500 (prices after
/// the path, the library's default) and 1000 (listed prices, the benchmark's), ACT under
/// Turney's prices where the data set has them, and CVT on the data sets small enough for
/// an unoptimised build (krk's training part cut to 1,500 of its objects).
pub fn test_cases(catalogue: &Catalogue) -> Vec<Case> {
    let case = |dataset: &str, learner, prices: &str, selection, mc, objects| Case {
        dataset: dataset.to_string(),
        learner,
        prices: prices.to_string(),
        selection,
        mc,
        objects,
    };
    let mut cases = Vec::new();
    for source in catalogue.benchmark() {
        let name = source.name.as_str();
        let objects = if name == "krk" { 1500 } else { 0 };
        cases.push(case(
            name,
            Method::Act,
            "random",
            SelectionPrices::Path,
            500.0,
            objects,
        ));
        cases.push(case(
            name,
            Method::Act,
            "random",
            SelectionPrices::Listed,
            1000.0,
            objects,
        ));
        if source.costs.is_some() {
            cases.push(case(
                name,
                Method::Act,
                "turney",
                SelectionPrices::Listed,
                500.0,
                objects,
            ));
        }
        if !matches!(name, "krk" | "nursery" | "thyroid" | "pima") {
            cases.push(case(
                name,
                Method::Cvt,
                "random",
                SelectionPrices::Listed,
                500.0,
                0,
            ));
        }
    }
    cases
}

/// The cases the speed example also checks, too slow for an unoptimised build: ACT on all
/// of krk, CVT on the four largest data sets (krk cut to 1,500 objects).
pub fn release_cases() -> Vec<Case> {
    let mut cases: Vec<Case> = [500.0, 1000.0]
        .into_iter()
        .map(|mc| Case {
            dataset: "krk".into(),
            learner: Method::Act,
            prices: "random".into(),
            selection: SelectionPrices::Listed,
            mc,
            objects: 0,
        })
        .collect();
    for (name, objects) in [("krk", 1500), ("nursery", 0), ("thyroid", 0), ("pima", 0)] {
        cases.push(Case {
            dataset: name.into(),
            learner: Method::Cvt,
            prices: "random".into(),
            selection: SelectionPrices::Listed,
            mc: 500.0,
            objects,
        });
    }
    cases
}
