//! Reading CSV tables: the shipped heart-disease data, binning, targets, and every error.

use std::path::PathBuf;

use cslearn::{Binning, ClassId, Dataset, DatasetOptions, Error, FeatureId, Value};

fn heart_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/heart-disease")
}

fn read(data: &str, costs: &str, options: &DatasetOptions) -> Result<Dataset, Error> {
    Dataset::from_readers(data.as_bytes(), "d.csv", costs.as_bytes(), "c.csv", options)
}

fn err(data: &str, costs: &str, options: &DatasetOptions) -> Error {
    read(data, costs, options).unwrap_err()
}

#[test]
fn the_heart_data_loads_as_its_readme_says() {
    let dir = heart_dir();
    let options = DatasetOptions::new("num").positive_if(">0");
    let ds = Dataset::load(&dir.join("cleveland.csv"), &dir.join("costs.csv"), &options).unwrap();
    assert_eq!(
        (ds.len(), ds.feature_count(), ds.class_count()),
        (304, 13, 2)
    );
    assert!((ds.costs().total().get() - 600.57).abs() < 1e-9);
    let numeric = ["age", "trestbps", "chol", "thalch", "oldpeak", "ca"];
    for f in 0..13 {
        let f = FeatureId(f);
        let name = ds.feature_name(f).unwrap();
        assert_eq!(
            ds.cut_points(f).is_some(),
            numeric.contains(&name),
            "{name}"
        );
    }
    // Quartiles of age put about a quarter of the records in each bin.
    let age = ds.feature_id("age").unwrap();
    let mut counts = [0; 4];
    for i in 0..ds.len() {
        counts[ds.object(i)[age.index()].unwrap().0 as usize] += 1;
    }
    assert!(counts.iter().all(|&n| (60..=95).contains(&n)), "{counts:?}");
    // Missing cells stay missing (ca and thal have a few).
    let missing = (0..ds.len())
        .filter(|&i| ds.object(i).contains(&None))
        .count();
    assert!((1..=10).contains(&missing), "{missing}");
    let sick = ds.labels().iter().filter(|&&c| c == ClassId(1)).count();
    assert!((130..=150).contains(&sick), "{sick}");
}

#[test]
fn numeric_columns_are_cut_at_quartiles_and_ties_fall_low() {
    let data = "x,t\n1,a\n2,a\n3,a\n4,a\n5,a\n,a\n";
    let costs = "feature,cost\nx,1\n";
    let ds = read(data, costs, &DatasetOptions::new("t")).unwrap();
    assert_eq!(ds.cut_points(FeatureId(0)), Some(&[2.0, 3.0, 4.0][..]));
    let values: Vec<Option<Value>> = (0..6).map(|i| ds.object(i)[0]).collect();
    let v = |n| Some(Value(n));
    assert_eq!(values, vec![v(0), v(0), v(1), v(2), v(3), None]);
    assert_eq!(ds.value_name(FeatureId(0), Value(1)), Some("(2, 3]"));
    assert_eq!(ds.value_name(FeatureId(0), Value(3)), Some("> 4"));
    // Nominal binning keeps every number as a category.
    let ds = read(
        data,
        costs,
        &DatasetOptions::new("t").binning(Binning::Nominal),
    )
    .unwrap();
    assert_eq!(ds.cut_points(FeatureId(0)), None);
    assert_eq!(ds.value_name(FeatureId(0), Value(4)), Some("5"));
}

#[test]
fn positive_if_expressions_split_the_target() {
    let data = "x,t\n1,0\n1,1\n1,2\n1,?\n";
    let costs = "feature,cost\nx,1\n";
    let classes = |expr: &str| {
        let data = data.replace("1,?\n", "");
        read(&data, costs, &DatasetOptions::new("t").positive_if(expr))
            .unwrap()
            .labels()
            .iter()
            .map(|c| c.0)
            .collect::<Vec<_>>()
    };
    assert_eq!(classes(">0"), vec![0, 1, 1]);
    assert_eq!(classes(">=2"), vec![0, 0, 1]);
    assert_eq!(classes("<1"), vec![1, 0, 0]);
    assert_eq!(classes("<=1"), vec![1, 1, 0]);
    assert_eq!(classes("==1"), vec![0, 1, 0]);
    assert_eq!(classes("!=0"), vec![0, 1, 1]);
    assert_eq!(classes("2"), vec![0, 0, 1]);
    let text = "x,t\n1,sick\n1,well\n";
    let ds = read(text, costs, &DatasetOptions::new("t").positive_if("sick")).unwrap();
    assert_eq!(ds.labels(), &[ClassId(1), ClassId(0)]);
    assert_eq!(ds.class_name(ClassId(0)), Some("not t ==sick"));
    // Without an expression, one class per target value, in numeric order.
    let ds = read("x,t\n1,10\n1,9\n1,10\n", costs, &DatasetOptions::new("t")).unwrap();
    assert_eq!(ds.labels(), &[ClassId(1), ClassId(0), ClassId(1)]);
    // A missing target is an error, with its line.
    let e = err(data, costs, &DatasetOptions::new("t"));
    assert!(matches!(e, Error::MissingTarget { line: 5, .. }), "{e}");
}

#[test]
fn bad_expressions_are_refused() {
    let (data, costs) = ("x,t\n1,0\n", "feature,cost\nx,1\n");
    for (expr, reason) in [
        ("", "empty"),
        (">", "nothing to compare"),
        ("<= five", "needs a number"),
    ] {
        let e = err(data, costs, &DatasetOptions::new("t").positive_if(expr));
        assert!(matches!(e, Error::BadExpression { .. }), "{e}");
        assert!(e.to_string().contains(reason), "{e}");
    }
}

#[test]
fn broken_data_files_name_file_and_line() {
    let costs = "feature,cost\na,1\nb,1\n";
    let options = DatasetOptions::new("t");
    let e = err("a,b,t\n1,2,3\n1,2\n", costs, &options);
    assert_eq!(
        e.to_string(),
        "d.csv: line 3: 2 fields, but the header has 3"
    );
    let e = Dataset::from_readers(
        &b"a,b,t\n1,\xff,3\n"[..],
        "d.csv",
        costs.as_bytes(),
        "c.csv",
        &options,
    )
    .unwrap_err();
    assert!(matches!(e, Error::NotUtf8 { line: 2, .. }), "{e}");
    assert!(matches!(err("", costs, &options), Error::EmptyFile { .. }));
    assert!(matches!(
        err("a,b,t\n", costs, &options),
        Error::NoRecords { .. }
    ));
    assert!(matches!(
        err("t\n1\n", costs, &options),
        Error::NoFeatures { .. }
    ));
    let e = err("a,a,t\n1,2,3\n", costs, &options);
    assert!(
        matches!(e, Error::DuplicateColumn { ref column, .. } if column == "a"),
        "{e}"
    );
    let e = err("a,b,c\n1,2,3\n", costs, &options);
    assert_eq!(
        e.to_string(),
        "d.csv: no target column `t` (columns: a, b, c)"
    );
}

#[test]
fn broken_costs_files_name_file_line_and_feature() {
    let data = "a,b,t\n1,2,3\n";
    let options = DatasetOptions::new("t");
    let e = err(data, "feature,cost\na,1\n", &options);
    assert_eq!(e.to_string(), "c.csv: no cost for column `b`");
    let e = err(data, "feature,cost\na,1\nb,-0.5\n", &options);
    assert_eq!(
        e.to_string(),
        "c.csv: line 3: the cost of `b` is `-0.5`, but costs must be finite, non-negative numbers"
    );
    for bad in ["NaN", "inf", "cheap", ""] {
        let e = err(data, &format!("feature,cost\na,1\nb,{bad}\n"), &options);
        assert!(matches!(e, Error::BadCost { line: 3, .. }), "{bad}: {e}");
    }
    let e = err(data, "feature,cost\na,1\nb,1\nz,1\n", &options);
    assert!(
        matches!(e, Error::UnknownCostFeature { line: 4, .. }),
        "{e}"
    );
    let e = err(data, "feature,cost\na,1\na,2\nb,1\n", &options);
    assert!(matches!(e, Error::DuplicateCost { line: 3, .. }), "{e}");
    let e = err(data, "name,price\na,1\nb,1\n", &options);
    assert!(matches!(e, Error::CostsHeader { .. }), "{e}");
    // A price for the target is ignored: it is never measured.
    let ds = read(data, "feature,cost\na,1\nb,2\nt,100\n", &options).unwrap();
    assert_eq!(ds.costs().total().get(), 3.0);
}

#[test]
fn a_positive_if_rule_that_matches_no_value_is_refused_with_the_values_present() {
    let costs = "feature,cost\na,1\n";
    let e = err(
        "a,t\n1,Male\n2,Female\n",
        costs,
        &DatasetOptions::new("t").positive_if("male"),
    );
    assert!(
        matches!(e, Error::PositiveIfMatchesNothing { count: 2, .. }),
        "{e:?}"
    );
    assert_eq!(
        e.to_string(),
        "d.csv: the positive-if expression `==male` matches no value of column `t` (values present: Female, Male; 2 values)"
    );
    let many: String = (0..40).fold("a,t\n".to_string(), |s, i| format!("{s}{i},{i}\n"));
    let e = err(&many, costs, &DatasetOptions::new("t").positive_if(">100"));
    assert_eq!(
        e.to_string(),
        "d.csv: the positive-if expression `>100` matches no value of column `t` (values present: 0, 1, 2, 3, 4, ...; 40 values)"
    );
    // A rule that holds for every object is allowed (all positive is a real answer).
    let ds = read(
        "a,t\n1,3\n2,4\n",
        costs,
        &DatasetOptions::new("t").positive_if(">0"),
    )
    .unwrap();
    assert_eq!(ds.labels(), &[ClassId(1), ClassId(1)]);
}

#[test]
fn prices_whose_totals_cannot_be_represented_are_refused() {
    let data = "a,b,t\n1,x,0\n2,y,1\n";
    let e = err(
        data,
        "feature,cost\na,1e308\nb,1e308\n",
        &DatasetOptions::new("t"),
    );
    assert!(
        matches!(e, Error::CostsTooLarge { objects: 2, .. }),
        "{e:?}"
    );
    assert!(
        e.to_string()
            .starts_with("c.csv: the prices sum to inf per object"),
        "{e}"
    );
    // Finite per object, not over the objects.
    let e = err(
        data,
        "feature,cost\na,1e300\nb,1e300\n",
        &DatasetOptions::new("t"),
    );
    assert!(matches!(e, Error::CostsTooLarge { .. }), "{e:?}");
    let max = cslearn::MAX_TOTAL_COST;
    let ok = format!("feature,cost\na,{}\nb,{}\n", max / 4.0, max / 4.0);
    let ds = read(data, &ok, &DatasetOptions::new("t")).unwrap();
    assert!(ds.costs().total().get().is_finite());
}

#[test]
fn a_wide_table_reads_and_its_errors_are_found_at_the_far_end() {
    // 100,000 columns and one row: read through an index of the header and of the costs
    // (see `examples/wide_csv.rs` for the time against 20,000 columns).
    let n = 100_000;
    let names: Vec<String> = (0..n).map(|j| format!("c{j}")).collect();
    let data = format!("{},t\n{}x\n", names.join(","), "1,".repeat(n));
    let costs: String = names
        .iter()
        .fold("feature,cost\n".to_string(), |s, c| s + c + ",1\n");
    let ds = read(&data, &costs, &DatasetOptions::new("t")).unwrap();
    assert_eq!(ds.feature_count(), n);
    assert_eq!(ds.feature_id("c99999"), Some(FeatureId(99_999)));
    let dup = data
        .replacen(",t\n", ",c0,t\n", 1)
        .replacen("x\n", "1,x\n", 1);
    let e = err(&dup, &costs, &DatasetOptions::new("t"));
    assert!(
        matches!(&e, Error::DuplicateColumn { column, .. } if column == "c0"),
        "{e:?}"
    );
    let e = err(
        &data,
        &format!("{costs}nope,1\n"),
        &DatasetOptions::new("t"),
    );
    assert!(
        matches!(&e, Error::UnknownCostFeature { line, .. } if *line == n as u64 + 2),
        "{e:?}"
    );
}
