//! A fit stops when asked: `fit_until` with a stop never requested learns `fit`'s tree,
//! to the bit, for every learner; a stop requested before or during a fit that would
//! run for hours (ACT sampling 1000 trees per branch on krk, ICET's largest search, CVT on
//! krk) ends it with `Error::Stopped`.

use std::path::Path;

use cslearn::testcost::{
    ActParams, Catalogue, FamilyParams, Frame, IcetParams, Method, MisclassCosts, Stop, TestPrices,
    fit, fit_until, random_prices,
};

fn load(name: &str) -> (Frame, TestPrices, MisclassCosts) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci");
    let catalogue = Catalogue::read(&root.join("datasets.toml")).unwrap();
    let frame = catalogue.load(name).unwrap().frame;
    let prices = random_prices(frame.feature_count(), 1.0, 100.0, 3);
    let mc = MisclassCosts::uniform(frame.class_count(), 500.0).unwrap();
    (frame, prices, mc)
}

/// Settings under which each learner would run for hours on krk: ACT samples 1000 trees
/// under every branch of every candidate, ICET searches 10,000 individuals for 10,000
/// generations, CVT grows its seven growers on ten folds.
fn for_hours() -> FamilyParams {
    let mut params = FamilyParams {
        act: ActParams::with_samples(ActParams::MAX_SAMPLES).unwrap(),
        icet: IcetParams {
            population: IcetParams::MAX_POPULATION,
            generations: IcetParams::MAX_GENERATIONS,
            ..IcetParams::default()
        },
        ..FamilyParams::default()
    };
    params.cvt.folds = 10;
    params
}

#[test]
fn a_stop_never_requested_learns_fits_tree_for_every_learner() {
    let (frame, prices, mc) = load("heart");
    let rows: Vec<usize> = (0..frame.len()).collect();
    let params = FamilyParams::default();
    let stop = Stop::default();
    for method in Method::ALL {
        let until = fit_until(method, &frame, &rows, &prices, &mc, &params, 5, &stop)
            .unwrap_or_else(|e| panic!("{}: {e}", method.name()));
        let plain = fit(method, &frame, &rows, &prices, &mc, &params, 5);
        assert_eq!(until, plain, "{}", method.name());
    }
}

#[test]
fn a_stop_requested_before_a_fit_of_hours_ends_it_at_once() {
    let (frame, prices, mc) = load("krk");
    let rows: Vec<usize> = (0..frame.len()).collect();
    let stop = Stop::default();
    stop.request();
    for method in Method::ALL {
        let stopped = fit_until(method, &frame, &rows, &prices, &mc, &for_hours(), 1, &stop);
        assert!(
            matches!(stopped, Err(cslearn::Error::Stopped)),
            "{}: {stopped:?}",
            method.name()
        );
    }
}

#[test]
fn a_stop_requested_from_another_thread_ends_a_fit_of_hours() {
    let (frame, prices, mc) = load("krk");
    let rows: Vec<usize> = (0..frame.len()).collect();
    for method in [Method::Act, Method::Icet, Method::Cvt] {
        let stop = Stop::default();
        let stopped = std::thread::scope(|scope| {
            let fit = scope
                .spawn(|| fit_until(method, &frame, &rows, &prices, &mc, &for_hours(), 1, &stop));
            stop.request();
            fit.join().unwrap()
        });
        assert!(
            matches!(stopped, Err(cslearn::Error::Stopped)),
            "{}: {stopped:?}",
            method.name()
        );
    }
}
