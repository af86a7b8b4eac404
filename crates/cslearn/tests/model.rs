//! Models saved and read back, and new rows classified by them: the same classes and
//! charges as the learner that learned the library, columns matched by name, and every
//! malformed model or table refused with where the fault is.

use std::path::PathBuf;

use cslearn::{Dataset, DatasetOptions, Error, FeatureId, LearnerKind, Model};

fn heart(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/heart-disease")
        .join(name)
}

fn heart_data() -> Dataset {
    Dataset::load(
        &heart("cleveland.csv"),
        &heart("costs.csv"),
        &DatasetOptions::new("num").positive_if(">0"),
    )
    .unwrap()
}

const KINDS: [LearnerKind; 3] = [
    LearnerKind::CsId3,
    LearnerKind::CsIbl { tolerance: 1 },
    LearnerKind::Id3,
];

/// The classes and charges of `library`'s learner on every object of `data`, classified
/// without learning by the plain procedure.
fn reference(
    data: &Dataset,
    kind: LearnerKind,
    library: &cslearn::Library,
) -> Vec<(Option<cslearn::ClassId>, f64)> {
    use rand::SeedableRng;
    let costs = data.costs().clone();
    let rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(99);
    let objects = (0..data.len()).map(|i| data.object(i));
    macro_rules! with {
        ($learner:expr) => {{
            let mut learner = $learner;
            *learner.library_mut() = library.clone();
            objects
                .map(|o| learner.classify(o))
                .map(|c| (c.class, c.cost.get()))
                .collect()
        }};
    }
    match kind {
        LearnerKind::CsId3 => with!(cslearn::cs_id3(costs)),
        LearnerKind::CsIbl { tolerance } => with!(cslearn::cs_ibl(costs, tolerance)),
        LearnerKind::Id3 => with!(cslearn::id3(costs, rng)),
    }
}

#[test]
fn a_saved_model_classifies_as_the_learner_did() {
    let data = heart_data();
    let text = std::fs::read_to_string(heart("cleveland.csv")).unwrap();
    for kind in KINDS {
        let (_, library) = cslearn::stream_dataset_keeping(&data, kind, 3, &mut |_, _| {});
        let model = Model::new(&data, kind, library.clone());
        let read = Model::from_json(model.to_json().as_bytes(), "m.json").unwrap();
        assert_eq!(read, model, "{kind:?}");
        assert_eq!(read.learner(), kind);
        let rows = read
            .predict(text.as_bytes(), "new.csv", &mut |_, _| {})
            .unwrap();
        let want = reference(&data, kind, &library);
        assert_eq!(rows.len(), want.len());
        for (i, (row, (class, cost))) in rows.iter().zip(&want).enumerate() {
            assert_eq!(
                (row.class, row.cost.get()),
                (*class, *cost),
                "{kind:?}, row {i}"
            );
            // CRLF line ends: the first record is line 2.
            assert_eq!(row.line, i as u64 + 2);
        }
        assert!(
            rows.iter()
                .any(|r| r.cost.get() > 0.0 && !r.measured.is_empty())
        );
    }
}

#[test]
fn columns_are_matched_by_name() {
    let data = heart_data();
    let (_, library) =
        cslearn::stream_dataset_keeping(&data, LearnerKind::CsId3, 1, &mut |_, _| {});
    let model = Model::new(&data, LearnerKind::CsId3, library);
    let text = std::fs::read_to_string(heart("cleveland.csv")).unwrap();
    // The columns reversed, the target dropped and an unknown one added.
    let reversed: String = text
        .lines()
        .map(|l| {
            let mut cells: Vec<&str> = l.trim_end().split(',').collect();
            cells.pop();
            cells.reverse();
            cells.push("extra");
            cells.join(",") + "\n"
        })
        .collect();
    let a = model
        .predict(text.as_bytes(), "a.csv", &mut |_, _| {})
        .unwrap();
    let b = model
        .predict(reversed.as_bytes(), "b.csv", &mut |_, _| {})
        .unwrap();
    let strip = |rows: Vec<cslearn::Prediction>| {
        rows.into_iter()
            .map(|r| (r.class, r.cost, r.measured))
            .collect::<Vec<_>>()
    };
    assert_eq!(strip(a), strip(b));
}

fn small() -> Model {
    let ds = Dataset::from_readers(
        "x,c,t\n1,red,n\n2,blue,n\n3,red,y\n4,blue,y\n".as_bytes(),
        "d.csv",
        "feature,cost\nx,1\nc,2\n".as_bytes(),
        "c.csv",
        &DatasetOptions::new("t"),
    )
    .unwrap();
    let (_, library) = cslearn::stream_dataset_keeping(&ds, LearnerKind::CsId3, 1, &mut |_, _| {});
    Model::new(&ds, LearnerKind::CsId3, library)
}

#[test]
fn malformed_models_are_refused_saying_where() {
    let good: serde_json::Value = serde_json::from_str(&small().to_json()).unwrap();
    type Change = Box<dyn Fn(&mut serde_json::Value)>;
    let cases: Vec<(&str, Change, &str)> = vec![
        (
            "format",
            Box::new(|v| v["format"] = "zip".into()),
            "not a csrl-classifier model file (its format is `zip`)",
        ),
        (
            "no format",
            Box::new(|v| {
                v.as_object_mut().unwrap().remove("format");
            }),
            "key `format`: missing",
        ),
        (
            "version",
            Box::new(|v| v["version"] = 2.into()),
            "key `version`: version 2 is not supported",
        ),
        (
            "version text",
            Box::new(|v| v["version"] = "1".into()),
            "key `version`: missing or not a whole number",
        ),
        (
            "learner",
            Box::new(|v| v["learner"] = "knn".into()),
            "unknown variant `knn`",
        ),
        (
            "unknown key",
            Box::new(|v| v["colour"] = 1.into()),
            "unknown field `colour`",
        ),
        (
            "tolerance",
            Box::new(|v| v["tolerance"] = 1.into()),
            "key `tolerance`: only a cs-ibl model has one",
        ),
        (
            "ibl tolerance",
            Box::new(|v| v["learner"] = "cs-ibl".into()),
            "key `tolerance`: a cs-ibl model needs one",
        ),
        (
            "no classes",
            Box::new(|v| v["classes"] = serde_json::json!([])),
            "key `classes`: no classes",
        ),
        (
            "twice class",
            Box::new(|v| v["classes"] = serde_json::json!(["n", "n"])),
            "class 1: `n` appears twice",
        ),
        (
            "no features",
            Box::new(|v| v["features"] = serde_json::json!([])),
            "key `features`: no features",
        ),
        (
            "cost",
            Box::new(|v| v["features"][0]["cost"] = (-1).into()),
            "invalid cost -1",
        ),
        (
            "cuts",
            Box::new(|v| v["features"][0]["cuts"] = serde_json::json!([2.0, 1.0])),
            "feature 0 (`x`): cut points not ascending at cut 1",
        ),
        (
            "both",
            Box::new(|v| v["features"][0]["values"] = serde_json::json!(["a"])),
            "feature 0 (`x`): needs exactly one of `cuts` and `values`",
        ),
        (
            "twice name",
            Box::new(|v| v["features"][1]["name"] = "x".into()),
            "feature 1 (`x`): the name appears twice",
        ),
        (
            "target",
            Box::new(|v| v["features"][1]["name"] = "t".into()),
            "feature 1 (`t`): the target column cannot be a feature",
        ),
        (
            "value twice",
            Box::new(|v| v["features"][1]["values"] = serde_json::json!(["red", "red"])),
            "feature 1 (`c`): value `red` appears twice",
        ),
        (
            "class range",
            Box::new(|v| v["library"][0]["class"] = 7.into()),
            "library example 0: class 7 does not exist (the model has 2)",
        ),
        (
            "feature range",
            Box::new(|v| v["library"][0]["values"] = serde_json::json!([[5, 0]])),
            "library example 0: feature 5 does not exist (the model has 2)",
        ),
        (
            "value range",
            Box::new(|v| v["library"][0]["values"] = serde_json::json!([[1, 9]])),
            "library example 0: value 9 of feature 1 (`c`) does not exist (it has 2)",
        ),
        (
            "order",
            Box::new(|v| v["library"][0]["values"] = serde_json::json!([[1, 0], [0, 0]])),
            "library example 0: features not in ascending order",
        ),
        (
            "negative",
            Box::new(|v| v["library"][0]["class"] = (-1).into()),
            "invalid value: integer `-1`",
        ),
    ];
    for (name, change, want) in cases {
        let mut v = good.clone();
        change(&mut v);
        let err = Model::from_json(v.to_string().as_bytes(), "m.json").unwrap_err();
        let text = err.to_string();
        assert!(
            text.starts_with("m.json: ") && text.contains(want),
            "{name}: {text}"
        );
    }
    for (bytes, want) in [
        (
            &b""[..],
            "m.json: line 1, column 0: not valid JSON (EOF while parsing a value)",
        ),
        (b"[1]", "m.json: the top level: not a JSON object"),
        (
            b"{\"format\": \"csrl-classifier\",\n\"version\": 1,\n}",
            "m.json: line 3, column 1: not valid JSON (trailing comma)",
        ),
        (
            b"\xff\xfe",
            "m.json: line 1, column 1: not valid JSON (expected value)",
        ),
    ] {
        let err = Model::from_json(bytes, "m.json").unwrap_err();
        assert_eq!(err.to_string(), want);
    }
}

#[test]
fn tables_to_classify_are_checked_cell_by_cell() {
    let model = small();
    let predict = |text: &str| model.predict(text.as_bytes(), "new.csv", &mut |_, _| {});
    let err = predict("c\nred\n").unwrap_err();
    assert_eq!(
        err.to_string(),
        "new.csv: no column `x`, which the model reads (columns: c)"
    );
    let err = predict("x,c\n1,red\nten,red\n").unwrap_err();
    assert!(matches!(err, Error::NotANumber { line: 3, .. }), "{err:?}");
    assert!(err.to_string().contains("`ten` in column `x`"), "{err}");
    let err = predict("x,c,x\n1,red,2\n").unwrap_err();
    assert!(matches!(err, Error::DuplicateColumn { .. }), "{err:?}");
    assert!(matches!(
        predict("x,c\n").unwrap_err(),
        Error::NoRecords { .. }
    ));
    // A colour never seen and missing cells are values all the same: no error.
    let rows = predict("c,x\ngreen,9\n?,\n,1\n").unwrap();
    assert_eq!(rows.len(), 3);
    assert_eq!(rows[2].measured.first(), Some(&FeatureId(0)));
}

#[test]
fn a_model_whose_totals_cannot_be_represented_or_that_knows_nothing_is_refused() {
    let mut v: serde_json::Value = serde_json::from_str(&small().to_json()).unwrap();
    v["features"][0]["cost"] = 1e308.into();
    v["features"][1]["cost"] = 1e308.into();
    let model = Model::from_json(v.to_string().as_bytes(), "m.json").unwrap();
    let err = model
        .predict("x,c\n1,red\n2,blue\n".as_bytes(), "new.csv", &mut |_, _| {})
        .unwrap_err();
    assert!(matches!(err, Error::CostsTooLarge { .. }), "{err:?}");
    v["features"][0]["cost"] = 1.into();
    v["features"][1]["cost"] = 1.into();
    v["library"] = serde_json::json!([]);
    let err = Model::from_json(v.to_string().as_bytes(), "m.json").unwrap_err();
    assert_eq!(
        err.to_string(),
        "m.json: key `library`: no examples: the model could not classify"
    );
}

/// A nominal test must keep one child per value of its feature: a tree read from outside
/// whose test kept one child of three is refused.
#[test]
fn a_nominal_test_keeps_one_child_per_value() {
    use cslearn::testcost::{
        Column, CostTree, Criterion, FeatureShape, Frame, GrowParams, MisclassCosts, TestPrices,
    };
    let frame = Frame::new(
        vec!["colour".into()],
        vec![Column::Nominal {
            values: vec!["red".into(), "blue".into(), "green".into()],
            codes: (0..30).map(|i| i % 3).collect(),
        }],
        (0..30).map(|i| u32::from(i % 3 == 0)).collect(),
        vec!["no".into(), "yes".into()],
    )
    .unwrap();
    let rows: Vec<usize> = (0..30).collect();
    let tree = CostTree::grow(
        &frame,
        &rows,
        &TestPrices::flat(&[1.0]).unwrap(),
        &MisclassCosts::uniform(2, 100.0).unwrap(),
        &GrowParams::new(Criterion::Id3),
    );
    let three = [FeatureShape {
        name: "colour",
        values: Some(3),
    }];
    assert_eq!(tree.check(&three, 2), Ok(()));
    let fault = tree
        .check(
            &[FeatureShape {
                name: "colour",
                values: Some(1),
            }],
            2,
        )
        .unwrap_err();
    assert!(
        fault
            .reason
            .contains("3 children for the 1 values of nominal feature `colour`"),
        "{fault}"
    );
}
