//! VOI, the value-of-information tree: the cases worked by hand.

use cslearn::testcost::{
    Budget, Column, FamilyParams, Frame, Method, MisclassCosts, TestPrices, VoiLeaf, VoiParams, fit,
};

/// Two binary tests whose exclusive or is the class, and a third that tells nothing:
/// `copies` objects of each of the four combinations.
fn xor(copies: usize) -> Frame {
    let mut a = Vec::new();
    let mut b = Vec::new();
    let mut noise = Vec::new();
    let mut classes = Vec::new();
    for i in 0..4 * copies {
        let (x, y) = ((i % 4) / 2, i % 2);
        a.push(x as f64);
        b.push(y as f64);
        noise.push((i / 4 % 2) as f64);
        classes.push((x ^ y) as u32);
    }
    Frame::new(
        vec!["a".into(), "b".into(), "noise".into()],
        vec![
            Column::Numeric(a),
            Column::Numeric(b),
            Column::Numeric(noise),
        ],
        classes,
        vec!["even".into(), "odd".into()],
    )
    .unwrap()
}

fn voi(lookahead: usize, leaf: VoiLeaf) -> FamilyParams {
    FamilyParams {
        voi: VoiParams {
            lookahead: Some(lookahead),
            leaf,
        },
        ..FamilyParams::default()
    }
}

/// The exclusive-or data of `xor(10)`, every object to learn from, the prices of the two
/// tests (2 and 3) and the noise (1), and an error priced 100.
fn xor_problem() -> (Frame, Vec<usize>, TestPrices, MisclassCosts) {
    let frame = xor(10);
    let rows: Vec<usize> = (0..frame.len()).collect();
    let prices = TestPrices::flat(&[2.0, 3.0, 1.0]).unwrap();
    let mc = MisclassCosts::uniform(2, 100.0).unwrap();
    (frame, rows, prices, mc)
}

/// Neither test alone changes the odds (half the objects of each branch are odd), so
/// with one test of lookahead none pays for itself; two together tell every object, and
/// at a lookahead of two the pair is bought: 2 + 3 in tests against half of 100 in errors.
/// So with either leaf estimate.
#[test]
fn a_pair_that_pays_is_bought_where_neither_test_alone_pays() {
    let (frame, rows, prices, mc) = xor_problem();
    for leaf in [VoiParams::default().leaf, VoiLeaf::MEstimate { m: 2.0 }] {
        let at = |lookahead| voi(lookahead, leaf);
        let myopic = fit(Method::Voi, &frame, &rows, &prices, &mc, &at(1), 1);
        assert_eq!(
            myopic.tree.len(),
            1,
            "{leaf:?}: one test ahead, none pays alone"
        );
        let two = fit(Method::Voi, &frame, &rows, &prices, &mc, &at(2), 1);
        for &row in &rows {
            let c = two.tree.classify(&frame, row, &prices);
            assert_eq!(c.class, frame.classes()[row], "{leaf:?}: object {row}");
            assert_eq!(
                c.test_cost, 5.0,
                "{leaf:?}: object {row} buys both, no other"
            );
        }
        // The pair does not pay where an error costs less than the tests: 5 in tests
        // against 4 expected in errors (and each estimate adds a little to the errors).
        let cheap = MisclassCosts::uniform(2, 8.0).unwrap();
        let stop = fit(Method::Voi, &frame, &rows, &prices, &cheap, &at(2), 1);
        assert_eq!(stop.tree.len(), 1, "{leaf:?}");
    }
}

/// A budget of one test leaves nothing worth buying in the pair: the tree stays a leaf,
/// where without the budget it buys both.
#[test]
fn a_budget_too_small_for_the_pair_buys_nothing() {
    let (frame, rows, prices, mc) = xor_problem();
    let params = FamilyParams {
        budget: Budget::new(None, Some(1)).unwrap(),
        ..voi(2, VoiParams::default().leaf)
    };
    let fitted = fit(Method::Voi, &frame, &rows, &prices, &mc, &params, 1);
    assert_eq!(fitted.tree.len(), 1);
}

/// VOI draws nothing at random: any seed learns the same tree, to the bit.
#[test]
fn voi_learns_the_same_tree_from_any_seed() {
    let n = 120;
    let x: Vec<f64> = (0..n).map(|i| f64::from((i * 37) % 101)).collect();
    let y: Vec<f64> = (0..n).map(|i| f64::from((i * 53) % 97)).collect();
    let classes: Vec<u32> = (0..n as usize)
        .map(|i| u32::from(x[i] + 0.5 * y[i] > 70.0) + u32::from(y[i] > 80.0))
        .collect();
    let frame = Frame::new(
        vec!["x".into(), "y".into()],
        vec![Column::Numeric(x), Column::Numeric(y)],
        classes,
        vec!["a".into(), "b".into(), "c".into()],
    )
    .unwrap();
    let rows: Vec<usize> = (0..frame.len()).collect();
    let prices = TestPrices::flat(&[5.0, 9.0]).unwrap();
    let mc = MisclassCosts::uniform(3, 200.0).unwrap();
    let first = fit(
        Method::Voi,
        &frame,
        &rows,
        &prices,
        &mc,
        &voi(2, VoiParams::default().leaf),
        1,
    );
    assert!(first.tree.len() > 1, "the data is worth some tests");
    for seed in [2, 99, u64::MAX] {
        assert_eq!(
            fit(
                Method::Voi,
                &frame,
                &rows,
                &prices,
                &mc,
                &voi(2, VoiParams::default().leaf),
                seed
            ),
            first
        );
    }
}

/// The settings are checked where a fit is asked for.
#[test]
fn settings_out_of_range_are_refused_by_check() {
    let frame = xor(2);
    let with_leaf = |leaf| VoiParams {
        leaf,
        ..VoiParams::default()
    };
    for bad in [
        VoiParams {
            lookahead: Some(0),
            ..VoiParams::default()
        },
        VoiParams {
            lookahead: Some(4),
            ..VoiParams::default()
        },
        with_leaf(VoiLeaf::MEstimate { m: f64::NAN }),
        with_leaf(VoiLeaf::Pessimistic { confidence: 0.0 }),
    ] {
        let params = FamilyParams {
            voi: bad,
            ..FamilyParams::default()
        };
        let e = params
            .check(Method::Voi, &frame, 8)
            .unwrap_err()
            .to_string();
        assert!(e.contains("VOI"), "{e}");
        // Other learners do not read VOI's settings.
        assert!(params.check(Method::Eg2, &frame, 8).is_ok());
    }
}

/// VOI on the exclusive-or problem, two tests ahead, the counts as they are (an
/// m-estimate with m = 0).
fn counted_pair(
    frame: &Frame,
    rows: &[usize],
    prices: &TestPrices,
    mc: &MisclassCosts,
) -> cslearn::testcost::Fitted {
    let params = voi(2, VoiLeaf::MEstimate { m: 0.0 });
    fit(Method::Voi, frame, rows, prices, mc, &params, 1)
}

/// The explanation of an object's classification, worked by hand on the exclusive-or
/// pair with the counts as they are (an m-estimate with m = 0). At the root (20 objects
/// of each class) stopping costs 50 per object, half of them wrong at 100; test `a` at
/// 2 then `b` at 3 tell every object, so buying `a` costs 5 and saves 45 (`b` first costs
/// the same and comes later). Below `a`, stopping costs 50 again and `b` costs 3: it
/// saves 47. An object missing `b` buys it all the same and answers from both branches;
/// one held to 2 buys `a` and answers where `b` is asked for.
#[test]
fn an_explanation_gives_each_test_its_price_node_probabilities_and_expected_saving() {
    use cslearn::testcost::{CostTree, Criterion, GrowParams};
    let (frame, rows, prices, mc) = xor_problem();
    let fitted = counted_pair(&frame, &rows, &prices, &mc);
    let tree = &fitted.tree;
    let root = tree.node(0).value.unwrap();
    assert_eq!(
        (root.stop, root.test, root.gain()),
        (50.0, Some(5.0), Some(45.0))
    );
    let why = tree.explain(&frame, 3, &prices, &Budget::UNLIMITED);
    let bought: Vec<(usize, f64, Option<f64>)> = why
        .steps
        .iter()
        .map(|s| (s.feature, s.paid, s.expected_gain))
        .collect();
    assert_eq!(bought, [(0, 2.0, Some(45.0)), (1, 3.0, Some(47.0))]);
    assert_eq!(why.steps[0].node, Some(0));
    assert_eq!(why.steps[0].probabilities, Some(vec![0.5, 0.5]));
    assert_eq!(why.steps[1].probabilities, Some(vec![0.5, 0.5]));
    assert_eq!(why.classification, tree.classify(&frame, 3, &prices));
    let leaf = why.stopped_at.unwrap();
    assert!(tree.node(leaf).split.is_none());
    // Ten objects of class `even` at the leaf: (10 + 1) / (10 + 2).
    assert_eq!(
        why.classification.probabilities,
        vec![11.0 / 12.0, 1.0 / 12.0]
    );

    // Missing `b`: both tests bought at their nodes, the answer from both branches.
    let missing = Frame::new(
        vec!["a".into(), "b".into(), "noise".into()],
        vec![
            Column::Numeric(vec![1.0]),
            Column::Numeric(vec![f64::NAN]),
            Column::Numeric(vec![0.0]),
        ],
        vec![1],
        vec!["even".into(), "odd".into()],
    )
    .unwrap();
    let why = tree.explain(&missing, 0, &prices, &Budget::UNLIMITED);
    assert_eq!(why.stopped_at, None);
    assert_eq!(why.steps.len(), 2);
    assert!(why.steps.iter().all(|s| s.node.is_some()));
    assert_eq!(why.classification, tree.classify(&missing, 0, &prices));

    // Held to 2: `a` only, and the node that asks for `b` answers.
    let budget = Budget::new(Some(2.0), None).unwrap();
    let why = tree.explain(&frame, 3, &prices, &budget);
    assert_eq!(why.steps.len(), 1);
    let asked = why.stopped_at.unwrap();
    assert_eq!(
        tree.node(asked).split.as_ref().map(|s| s.feature()),
        Some(1)
    );
    assert_eq!(
        why.classification,
        tree.classify_within(&frame, 3, &prices, &budget)
    );

    // A learner that does not value its tests explains without expected savings.
    let a: Vec<f64> = (0..40).map(|i| f64::from(i % 2)).collect();
    let told = Frame::new(
        vec!["a".into()],
        vec![Column::Numeric(a.clone())],
        a.iter().map(|&x| x as u32).collect(),
        vec!["even".into(), "odd".into()],
    )
    .unwrap();
    let prices = TestPrices::flat(&[2.0]).unwrap();
    let id3 = CostTree::grow(&told, &rows, &prices, &mc, &GrowParams::new(Criterion::Id3));
    let why = id3.explain(&told, 3, &prices, &Budget::UNLIMITED);
    assert!(!why.steps.is_empty());
    assert!(why.steps.iter().all(|s| s.expected_gain.is_none()));
    let paid: f64 = why.steps.iter().map(|s| s.paid).sum();
    assert_eq!(paid, why.classification.test_cost);
}

/// VOI's node values travel in its model file, and a file with a value that is not a
/// cost is refused, naming the node.
#[test]
fn node_values_are_saved_with_the_tree_and_checked_when_read() {
    use cslearn::testcost::TreeModel;
    let (frame, rows, prices, mc) = xor_problem();
    let fitted = counted_pair(&frame, &rows, &prices, &mc);
    let model = TreeModel::new(Method::Voi, &frame, "class", None, &fitted, &prices);
    let text = model.to_json();
    assert!(
        text.contains(r#""value":{"stop":50.0,"test":5.0}"#),
        "{text}"
    );
    let again = TreeModel::from_json(text.as_bytes(), "m.json").unwrap();
    assert_eq!(again.tree().node(0).value, fitted.tree.node(0).value);
    let bad = text.replacen(r#""stop":50.0"#, r#""stop":-1.0"#, 1);
    let err = TreeModel::from_json(bad.as_bytes(), "m.json")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("tree node 0") && err.contains("`stop` or `test`"),
        "{err}"
    );
    // The other learners' files have no values.
    let eg2 = fit(
        Method::Eg2,
        &frame,
        &rows,
        &prices,
        &mc,
        &FamilyParams::default(),
        1,
    );
    let text = TreeModel::new(Method::Eg2, &frame, "class", None, &eg2, &prices).to_json();
    assert!(!text.contains("\"value\""), "{text}");
}
