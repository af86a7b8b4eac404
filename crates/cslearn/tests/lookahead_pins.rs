//! ACT's and CVT's trees pinned on the data sets of the test-cost benchmark: a speed-up
//! of the lookahead (or of the split trie the greedy learners share) must grow the same
//! trees, to the bit. `tests/pins/lookahead.txt` holds each case's fingerprint, taken
//! before the lookahead was made fast; the cases too slow for an unoptimised build are
//! checked by `cargo run --release -p cslearn --example lookahead_speed -- --check`.
//!
//! ACT's cases are grown on one thread and on two (a node's candidates valued at the same
//! time): the same trees.
//!
//! When a change of trees is intended, explain it in the commit and write the new
//! fingerprints with `CSLEARN_PINS_WRITE=1 cargo test --release -p cslearn --test
//! lookahead_pins`.

mod support;

use cslearn::testcost::Method;
use support::lookahead::{Case, catalogue, fingerprint, pin_file, pins, release_cases, test_cases};

#[test]
fn act_and_cvt_grow_the_pinned_trees() {
    let catalogue = catalogue();
    let cases = test_cases(&catalogue);
    if std::env::var_os("CSLEARN_PINS_WRITE").is_some() {
        let mut text = String::from(
            "# dataset learner prices selection mc objects fingerprint (tests/lookahead_pins.rs)\n",
        );
        for case in cases.iter().chain(&release_cases()) {
            let loaded = catalogue.load(&case.dataset).unwrap();
            let tree = case.grow(&loaded);
            text.push_str(&format!("{} {}\n", case.key(), fingerprint(&tree)));
        }
        std::fs::write(pin_file(), text).unwrap();
    }
    let pinned = pins();
    let listed: Vec<Case> = pinned.iter().map(|(c, _)| c.clone()).collect();
    let expected: Vec<Case> = cases.iter().cloned().chain(release_cases()).collect();
    assert_eq!(
        listed, expected,
        "the pin file lists other cases than the test's"
    );
    let mut failed = Vec::new();
    for (case, print) in pinned.iter().filter(|(c, _)| cases.contains(c)) {
        let loaded = catalogue.load(&case.dataset).unwrap();
        let tree = case.grow(&loaded);
        let got = fingerprint(&tree);
        if &got != print {
            failed.push(format!("{}: pinned {print}, grown {got}", case.key()));
        }
        // ACT valuing each node's candidates on two threads grows the same tree.
        if case.learner == Method::Act {
            let got = fingerprint(&case.grow_on(&loaded, 2));
            if &got != print {
                failed.push(format!(
                    "{} on two threads: pinned {print}, grown {got}",
                    case.key()
                ));
            }
        }
    }
    assert!(failed.is_empty(), "trees changed:\n{}", failed.join("\n"));
}
