//! Beyond the paper: everything off gives the paper's runs; each extension changes a run
//! only when it is on.

use csql::{DetectorKind, Matching, RunSettings, StrategyKind};

fn json(s: &RunSettings) -> String {
    serde_json::to_string(&csql::run(s).unwrap()).unwrap()
}

#[test]
fn extensions_at_their_defaults_change_nothing() {
    let plain = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 3);
    let mut explicit = plain.clone();
    explicit
        .apply_toml(
            "[world]\nslip = 0.0\nsensor_noise = 0.0\n[extensions]\ndetector = \"decrease\"\nmatching = \"exact\"",
            "t",
        )
        .unwrap();
    assert_eq!(json(&plain), json(&explicit));
    assert!(!json(&plain).contains("quality"));
    assert!(!json(&plain).contains("slip"));
}

#[test]
fn each_extension_changes_the_run_only_when_on() {
    let base = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 2);
    let reference = json(&base);
    let tweaks = [
        "max_trials = 100\n[extensions]\nquality_every = 50\n[world]\nslip = 0.1",
        "max_trials = 100\n[extensions]\nquality_every = 50\n[world]\nsensor_noise = 0.05",
        "max_trials = 100\n[extensions]\nquality_every = 50\n[world]\nsensing_radius = 1",
        "max_trials = 100\n[extensions]\nquality_every = 50\ndetector = \"statistical\"",
        "max_trials = 100\n[world]\nsensor_noise = 0.05\n[extensions]\nquality_every = 50\nmatching = \"nearest\"",
    ];
    for t in tweaks {
        let mut s = base.clone();
        s.apply_toml(t, "t").unwrap();
        let out = json(&s);
        assert_ne!(out, reference, "{t}");
        assert!(out.contains("policy_quality"), "{t}");
    }
}

#[test]
fn runs_beyond_the_paper_are_pure_functions_of_their_settings() {
    let mut s = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 5);
    s.apply_toml(
        "max_trials = 60\n[world]\nslip = 0.1\nsensor_noise = 0.05\n[extensions]\nquality_every = 30\ndetector = \"statistical\"\nmatching = \"nearest\"",
        "t",
    )
    .unwrap();
    assert_eq!(json(&s), json(&s));
    let q = csql::run(&s).unwrap().quality.unwrap();
    assert_eq!(q.method, csql::QualityMethod::MonteCarlo);
    assert!(q.standard_error < 0.005 || q.standard_error.is_finite());
}

#[test]
fn slip_with_the_statistical_detector_reaches_quality() {
    let mut s = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 1);
    s.apply_toml(
        "beta = 0.2\nmax_trials = 2000\n[world]\nslip = 0.1\n[extensions]\ndetector = \"statistical\"",
        "t",
    )
    .unwrap();
    assert_eq!(s.extensions.detector, DetectorKind::Statistical);
    let r = csql::run(&s).unwrap();
    let q = r.quality.unwrap();
    assert!(q.trials_to_quality.is_some(), "{q:?}");
    assert!(q.policy_quality >= 0.95);
    // The run ended by the rule of the specification's section 6, well before its cap.
    assert!(r.trials < 2000);
}

#[test]
fn nearest_matching_makes_fewer_descriptions_under_noise() {
    let mut exact = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 4);
    exact
        .apply_toml(
            "max_trials = 150\n[world]\nsensor_noise = 0.05\n[extensions]\nquality_every = 150",
            "t",
        )
        .unwrap();
    let mut near = exact.clone();
    near.extensions.matching = Matching::Nearest;
    let a = csql::run(&exact).unwrap().quality.unwrap();
    let b = csql::run(&near).unwrap().quality.unwrap();
    assert!(
        b.descriptions < a.descriptions,
        "{} vs {}",
        b.descriptions,
        a.descriptions
    );
}

#[test]
fn bad_settings_say_what_and_where() {
    let mut s = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    let e = s
        .apply_toml("[world]\nslip = 2.0", "mine.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("mine.toml") && e.contains("slip"), "{e}");
    let e = s
        .apply_toml("[world]\nsensing_radius = 0", "mine.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("sensing_radius"), "{e}");
    assert!(
        s.apply_toml("[extensions]\ndetectr = \"statistical\"", "m")
            .is_err()
    );
}
