//! The CSV reader under hostile input: malformed text never panics, every refusal names
//! its file, and what is not a regular file is refused unread.

use cslearn::{Dataset, DatasetOptions, Error};
use proptest::prelude::*;

const COSTS: &str = "feature,cost\na,1\nb,2\n";

fn read(data: &str) -> Result<Dataset, Error> {
    Dataset::from_readers(
        data.as_bytes(),
        "d.csv",
        COSTS.as_bytes(),
        "c.csv",
        &DatasetOptions::new("t"),
    )
}

#[test]
fn an_unterminated_quote_is_named_with_its_line() {
    // Once reported as a field-count mismatch on the wrong line.
    let err = read("a,b,t\n1,2,x\n\"3,4,y\n5,6,z\n").unwrap_err();
    assert!(
        matches!(err, Error::UnterminatedQuote { line: 3, .. }),
        "{err:?}"
    );
    assert!(err.to_string().contains("d.csv: line 3"), "{err}");
    // Closed quotes, doubled quotes and quoted newlines are fine.
    let ok = read("a,b,t\n\"1\",\"2\"\"\",x\n\"3\n\",4,y\n").unwrap();
    assert_eq!(ok.len(), 2);
}

#[cfg(unix)]
#[test]
fn what_is_not_a_regular_file_is_refused_unread() {
    let costs = tempfile::NamedTempFile::new().unwrap();
    std::fs::write(costs.path(), COSTS).unwrap();
    let options = DatasetOptions::new("t");
    let err = Dataset::load("/dev/zero".as_ref(), costs.path(), &options).unwrap_err();
    assert!(matches!(err, Error::NotAFile { .. }), "{err:?}");
    let dir = tempfile::tempdir().unwrap();
    let err = Dataset::load(dir.path(), costs.path(), &options).unwrap_err();
    assert!(matches!(err, Error::NotAFile { .. }), "{err:?}");
}

#[test]
fn a_reader_that_never_ends_is_cut_at_the_limit() {
    let endless = std::io::repeat(b'1');
    let err = Dataset::from_readers(
        endless,
        "endless.csv",
        COSTS.as_bytes(),
        "c.csv",
        &DatasetOptions::new("t"),
    )
    .unwrap_err();
    assert!(matches!(err, Error::TooLarge { .. }), "{err:?}");
}

/// CSV-like text built from the characters that matter to a CSV reader.
fn csvish() -> impl Strategy<Value = String> {
    proptest::collection::vec(
        prop_oneof![
            Just(","),
            Just("\n"),
            Just("\r\n"),
            Just("\""),
            Just("?"),
            Just(" "),
            Just("a"),
            Just("b"),
            Just("t"),
            Just("1"),
            Just("-2.5"),
            Just("NaN"),
            Just("inf"),
            Just("x"),
            Just("\u{fffd}"),
        ],
        0..60,
    )
    .prop_map(|parts| parts.concat())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn malformed_data_never_panics(body in csvish()) {
        let text = format!("a,b,t\n{body}");
        if let Err(e) = read(&text) {
            prop_assert!(e.to_string().contains("d.csv"), "{e}");
        }
    }

    #[test]
    fn malformed_costs_never_panic(costs in csvish(), bytes in proptest::collection::vec(any::<u8>(), 0..64)) {
        let _ = Dataset::from_readers("a,b,t\n1,2,x\n".as_bytes(), "d.csv", costs.as_bytes(), "c.csv", &DatasetOptions::new("t"));
        let _ = Dataset::from_readers(bytes.as_slice(), "d.csv", COSTS.as_bytes(), "c.csv", &DatasetOptions::new("t"));
    }
}

#[test]
fn lines_are_counted_right_after_crlf_line_ends() {
    // The CSV reader's own count ran one behind after a CRLF header.
    for end in ["\n", "\r\n"] {
        let text = ["a,b,t", "1,2,x", "3,4,y", "5,6,"].join(end) + end;
        let err = read(&text).unwrap_err();
        assert!(
            matches!(err, Error::MissingTarget { line: 4, .. }),
            "{end:?}: {err:?}"
        );
        let ragged = ["a,b,t", "1,2,x", "3,4"].join(end) + end;
        let err = read(&ragged).unwrap_err();
        assert!(
            matches!(err, Error::RaggedRecord { line: 3, .. }),
            "{end:?}: {err:?}"
        );
    }
}

/// Two values that every learner must separate: a threshold always falls between them,
/// even where their midpoint overflows or rounds onto the larger.
#[test]
fn every_learner_separates_extreme_and_adjacent_values() {
    use cslearn::testcost::{Column, FamilyParams, Frame, Method, MisclassCosts, TestPrices, fit};
    let tiny = f64::from_bits(1);
    let pairs = [
        (1e308, 1.5e308),
        (-1.5e308, -1e308),
        (1.0 + f64::EPSILON, 1.0 + 2.0 * f64::EPSILON),
        (tiny, f64::from_bits(2)),
        (-f64::MAX, f64::MAX),
    ];
    for (low, high) in pairs {
        let values: Vec<f64> = (0..20).map(|i| if i < 10 { low } else { high }).collect();
        let classes: Vec<u32> = (0..20).map(|i| u32::from(i >= 10)).collect();
        let frame = Frame::new(
            vec!["x".into()],
            vec![Column::Numeric(values)],
            classes,
            vec!["a".into(), "b".into()],
        )
        .unwrap();
        let prices = TestPrices::flat(&[1.0]).unwrap();
        let mc = MisclassCosts::uniform(2, 100.0).unwrap();
        let rows: Vec<usize> = (0..20).collect();
        for method in Method::ALL {
            let fitted = fit(
                method,
                &frame,
                &rows,
                &prices,
                &mc,
                &FamilyParams::default(),
                1,
            );
            for r in 0..20 {
                let c = fitted.tree.classify(&frame, r, &prices).class;
                assert_eq!(
                    c,
                    frame.class(r),
                    "{} misclassifies {:e} of the pair ({low:e}, {high:e})",
                    method.name(),
                    if r < 10 { low } else { high }
                );
            }
        }
    }
}

/// A column name holding a terminal's escape sequence is refused, and the refusal does not
/// print it.
#[test]
fn a_column_name_with_a_control_character_is_refused_without_printing_it() {
    let err = read("a\u{1b}[2J,b,t\n1,2,x\n").unwrap_err();
    let text = err.to_string();
    assert!(matches!(err, Error::BadInput { .. }), "{err:?}");
    assert!(text.contains("d.csv") && text.contains("U+001B"), "{text}");
    assert!(!text.contains('\u{1b}'), "{text:?}");
    use cslearn::testcost::{Frame, FrameSpec};
    let err = Frame::from_cells(
        "t.csv",
        &["a\u{7}", "c"],
        &[["1", "x"]],
        &FrameSpec::new("c"),
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("t.csv") && err.contains("U+0007"), "{err}");
    assert!(!err.contains('\u{7}'), "{err:?}");
}

#[cfg(unix)]
#[test]
fn a_manifest_that_is_no_regular_file_is_refused_unread() {
    let err = cslearn::testcost::Catalogue::read("/dev/zero".as_ref()).unwrap_err();
    assert!(matches!(err, Error::NotAFile { .. }), "{err:?}");
}

/// Files trusted too far: a discount above its full price, and a cost matrix whose header
/// names a class twice (the missing class's column once read as zeros), are refused with
/// the file and line.
#[test]
fn a_dearer_discount_and_a_class_named_twice_are_refused_with_file_and_line() {
    use cslearn::testcost::{MisclassCosts, TestPrices};
    let dir = tempfile::tempdir().unwrap();
    let base = dir.path().join("p");
    std::fs::write(base.with_extension("expense"), "a: 10, 2\nb: 8, 9\n").unwrap();
    std::fs::write(base.with_extension("group"), "G.\na: G.\nb: G.\n").unwrap();
    let names = ["a", "b"].map(String::from).to_vec();
    let err = TestPrices::read_turney(&base, &names, &Default::default())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("p.expense: line 2")
            && err.contains("a discount price of 9 above its full price 8"),
        "{err}"
    );
    let mc = dir.path().join("mc.csv");
    std::fs::write(&mc, "actual,n,n\nn,0,1\np,5,0\n").unwrap();
    let classes = ["n", "p"].map(String::from).to_vec();
    let err = MisclassCosts::read_csv(&mc, &classes)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("mc.csv: line 1") && err.contains("class `n` names two columns"),
        "{err}"
    );
}

/// A manifest naming a data set with no file is refused by name (it once panicked).
#[test]
fn a_manifest_data_set_without_files_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let manifest = dir.path().join("datasets.toml");
    std::fs::write(
        &manifest,
        "[[dataset]]\nname = \"x\"\nfiles = []\ncolumns = [\"a\", \"t\"]\ntarget = \"t\"\nmissing = []\n",
    )
    .unwrap();
    let err = cslearn::testcost::Catalogue::read(&manifest)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("data set `x`") && err.contains("`files` is empty"),
        "{err}"
    );
}
