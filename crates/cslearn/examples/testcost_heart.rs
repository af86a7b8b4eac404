//! The test-cost family on the Cleveland heart-disease data with Turney's prices and
//! group discounts: one run of 10-fold cross-validation, misclassification cost 500.
//!
//! `cargo run --release -p cslearn --example testcost_heart [-- MC]`

use std::path::Path;
use std::time::Instant;

use cslearn::testcost::{
    FamilyParams, Frame, FrameSpec, Method, MisclassCosts, TestPrices, fit, folds, standard_cost,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mc_value: f64 = std::env::args().nth(1).map_or(Ok(500.0), |a| a.parse())?;
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/uci/heart-disease");
    let columns: Vec<String> = [
        "age", "sex", "cp", "trestbps", "chol", "fbs", "restecg", "thalach", "exang", "oldpeak",
        "slope", "ca", "thal", "num",
    ]
    .map(String::from)
    .to_vec();
    let spec =
        FrameSpec::new("num").nominal(["sex", "cp", "fbs", "restecg", "exang", "slope", "thal"]);
    let frame = Frame::read_delimited(&root.join("processed.cleveland.data"), &columns, "", &spec)?;
    // Two classes: no disease (0) against any (1 to 4).
    let map: Vec<u32> = frame
        .class_names()
        .iter()
        .map(|n| u32::from(n != "0" && n != "0.0"))
        .collect();
    let frame = frame.with_classes(&map, vec!["healthy".into(), "sick".into()])?;
    let prices = TestPrices::read_turney(
        &root.join("costs/heart-disease"),
        frame.names(),
        &Default::default(),
    )?;
    let mc = MisclassCosts::uniform(2, mc_value)?;
    let standard = standard_cost(&frame, &prices, &mc);
    println!(
        "heart: {} objects, all tests {:.2}, standard cost {:.2}",
        frame.len(),
        prices.total(),
        standard
    );
    println!("learner        total  tests  errors  nodes  ms/tree  % standard");
    let params = FamilyParams::default();
    for method in Method::ALL {
        let (mut total, mut tests, mut errors, mut nodes, mut trees) =
            (0.0, 0.0, 0usize, 0usize, 0usize);
        let start = Instant::now();
        for (f, test) in folds(&frame, 10, 1).iter().enumerate() {
            let train: Vec<usize> = (0..frame.len())
                .filter(|r| test.binary_search(r).is_err())
                .collect();
            let fitted = fit(method, &frame, &train, &prices, &mc, &params, f as u64);
            nodes += fitted.tree.len();
            trees += 1;
            for &r in test {
                let c = fitted.tree.classify(&frame, r, &prices);
                let wrong = c.class != frame.class(r);
                errors += usize::from(wrong);
                tests += c.test_cost;
                total += c.test_cost + mc.cost(c.class as usize, frame.class(r) as usize);
            }
        }
        let ms = start.elapsed().as_secs_f64() * 1e3 / trees as f64;
        let n = frame.len() as f64;
        println!(
            "{:<13} {:6.1} {:6.1} {:7.3} {:6.1} {:8.3} {:10.1}",
            method.name(),
            total / n,
            tests / n,
            errors as f64 / n,
            nodes as f64 / trees as f64,
            ms,
            100.0 * total / n / standard
        );
    }
    Ok(())
}
