//! The settings: each learner takes only its own, how a run is judged is one choice, and
//! the flat form round-trips (specification 6.9).

use csql::{
    LearnerKind, LearnerSettings, RunSettings, SettingsDraft, StrategyKind, UTreeParams, run,
};

/// Why the settings file `text` is refused once built.
fn refusal(text: &str) -> String {
    SettingsDraft::from_toml(text, "f.toml")
        .unwrap()
        .build()
        .unwrap_err()
        .to_string()
}

/// Every key that belongs to CS-QL, given with each baseline, is refused with a message
/// that names the key and the learner; the same keys with CS-QL are accepted.
#[test]
fn each_learner_takes_only_its_own_keys() {
    let cs_ql_keys = [
        ("strategy = \"eager\"", "strategy = eager"),
        ("random_moves = 7", "random_moves = 7"),
        ("predict_sensing = \"learned\"", "predict_sensing = learned"),
        ("[prediction]\nmax_skips = 3", "[prediction]"),
        ("[extensions]\ndetector = \"statistical\"", "detector"),
        ("[extensions]\nmatching = \"nearest\"", "matching"),
        ("[extensions]\nconfirm_new = 3", "confirm_new"),
        ("[extensions]\nreads = 3", "reads"),
        ("[extensions]\nmemory = 1", "memory"),
    ];
    for baseline in ["u-tree", "full-sensing"] {
        for (key, named) in cs_ql_keys {
            let text = format!("learner = \"{baseline}\"\n{key}");
            let err = refusal(&text);
            assert!(
                err.contains(named) && err.contains(&format!("learner = {baseline}")),
                "{text:?}: {err}"
            );
        }
    }
    // The keys a learner does not own are refused with it; a U-Tree table with CS-QL and
    // with full sensing.
    for learner in ["cs-ql", "full-sensing"] {
        let text = format!("learner = \"{learner}\"\n[u_tree]\nfringe = 3");
        let err = refusal(&text);
        assert!(
            err.contains("[u_tree]") && err.contains(&format!("learner = {learner}")),
            "{err}"
        );
    }
    // The same keys, each with its learner, are fine (the ones that need a partner with it).
    for text in [
        "strategy = \"random\"\nrandom_moves = 7",
        "predict_sensing = \"learned\"\n[prediction]\nmax_skips = 3",
        "[extensions]\ndetector = \"statistical\"\nmatching = \"nearest\"\nconfirm_new = 3\nreads = 3",
        "map = \"tan8x8\"\n[world]\nsensing_radius = 1\n[extensions]\nmemory = 1",
        "learner = \"u-tree\"\n[u_tree]\nfringe = 3",
    ] {
        let built = SettingsDraft::from_toml(text, "f.toml").unwrap().build();
        assert!(built.is_ok(), "{text:?}: {built:?}");
    }
}

/// How a run is judged is the one setting `judge_by_quality`, with its schedule, for every
/// learner; it survives a change of learner.
#[test]
fn the_judging_is_every_learners() {
    for learner in LearnerKind::ALL {
        let text = format!(
            "learner = \"{learner}\"\n[judge]\njudge_by_quality = true\nquality_every = 5\nquality_patience = 3"
        );
        let s = SettingsDraft::from_toml(&text, "f")
            .unwrap()
            .build()
            .unwrap();
        assert_eq!(s.learner.kind(), learner);
        assert!(s.judge.judge_by_quality && s.judged_by_quality(true));
        assert_eq!((s.judge.quality_every, s.judge.quality_patience), (5, 3));
    }
    let mut s = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    s.apply_toml(
        "[extensions]\nreads = 3\n[judge]\njudge_by_quality = true",
        "f",
    )
    .unwrap();
    // Another learner starts from its defaults: CS-QL's reads are gone, the judging stays.
    s.apply_toml("learner = \"u-tree\"", "f").unwrap();
    assert_eq!(s.learner, LearnerSettings::UTree(UTreeParams::default()));
    assert!(s.judge.judge_by_quality);
}

/// Flags over a file: a strategy from one and a baseline from the other are refused,
/// whichever gave which.
#[test]
fn a_flag_and_a_file_are_checked_together() {
    let mut from_file = SettingsDraft::from_toml("strategy = \"lazy\"", "f.toml").unwrap();
    from_file.overlay(SettingsDraft {
        learner: Some(LearnerKind::FullSensing),
        ..SettingsDraft::default()
    });
    let err = from_file.build().unwrap_err().to_string();
    assert!(
        err.contains("strategy = lazy") && err.contains("learner = full-sensing"),
        "{err}"
    );
    let mut from_flag = SettingsDraft::from_toml("learner = \"u-tree\"", "f.toml").unwrap();
    from_flag.overlay(SettingsDraft {
        strategy: Some(StrategyKind::Eager),
        ..SettingsDraft::default()
    });
    assert!(from_flag.build().is_err());
    // Nothing given: the defaults of `csrl run`.
    let s = SettingsDraft::default().build().unwrap();
    assert_eq!(
        s,
        RunSettings::tan1991(csql::DEFAULT_MAP, StrategyKind::Resetting, 1)
    );
}

/// The flat form a report echoes reads back to the same settings, for every learner and
/// with settings beyond the paper.
#[test]
fn settings_round_trip_through_their_json() {
    let texts = [
        "",
        "strategy = \"random\"\nrandom_moves = 5\nbeta = 0.5",
        "predict_sensing = \"learned\"\n[prediction]\nrecheck = 0.1",
        "beta = 0.2\n[world]\nsensor_noise = 0.05\n[extensions]\nmatching = \"nearest\"\nreads = 3\n[judge]\nquality_every = 50",
        "learner = \"u-tree\"\nmax_rows = 500\n[u_tree]\nalpha = 0.05\n[judge]\njudge_by_quality = true",
        "learner = \"full-sensing\"\n[world]\nslip = 0.1",
    ];
    for text in texts {
        let mut s = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 3);
        s.apply_toml(text, "f").unwrap();
        let json = serde_json::to_string(&s).unwrap();
        let back: RunSettings = serde_json::from_str(&json).unwrap();
        assert_eq!(back, s, "{text:?}: {json}");
    }
}

/// A baseline's report has no strategy, in the report or its settings; CS-QL's has it.
#[test]
fn a_baseline_echoes_no_strategy() {
    let s = RunSettings::tan1991("tan3x3", StrategyKind::Eager, 1);
    let cs_ql = serde_json::to_value(run(&s).unwrap()).unwrap();
    assert_eq!(cs_ql["strategy"], "eager");
    assert_eq!(cs_ql["settings"]["strategy"], "eager");
    for kind in [LearnerKind::UTree, LearnerKind::FullSensing] {
        let r = run(&s.clone().with_learner(kind)).unwrap();
        assert_eq!(r.strategy, None);
        let v = serde_json::to_value(&r).unwrap();
        assert!(v.get("strategy").is_none(), "{kind}");
        let settings = v["settings"].as_object().unwrap();
        for key in ["strategy", "random_moves", "predict_sensing", "prediction"] {
            assert!(!settings.contains_key(key), "{kind}: {key}");
        }
        assert_eq!(v["settings"]["learner"], kind.name());
    }
}

/// The level of sensing less that weighs acting on the likely descriptions is spelled
/// `weighed`; its old spelling `belief`, the name of another learner, is refused with a
/// pointer, in a file as in a flag.
#[test]
fn the_old_spelling_of_the_weighed_level_points_to_the_new() {
    let err = SettingsDraft::from_toml("predict_sensing = \"belief\"", "f.toml")
        .unwrap_err()
        .to_string();
    assert!(err.contains("predict_sensing = \"weighed\""), "{err}");
    assert!(err.contains("learner = \"belief\""), "{err}");
    let flag = "belief"
        .parse::<csql::PredictSensing>()
        .unwrap_err()
        .to_string();
    assert!(flag.contains("predict_sensing = \"weighed\""), "{flag}");
    let d = SettingsDraft::from_toml("predict_sensing = \"weighed\"\n[costly]\nprice = 0.01", "f")
        .unwrap();
    assert_eq!(
        d.build().unwrap().predict_sensing(),
        csql::PredictSensing::Weighed
    );
}

/// Trials and episodes are two counts: `max_trials` with a learner played on episodes,
/// and `episodes` with one judged over trials, are refused, each with a pointer to the
/// other; a report's settings echo the count the learner read, and build again to it.
#[test]
fn trials_and_episodes_are_counted_apart() {
    let err = refusal("learner = \"amrl-q\"\nmax_trials = 50\n[costly]\nprice = 0.1");
    assert!(
        err.starts_with("max_trials = 50 and learner = amrl-q cannot be used together"),
        "{err}"
    );
    assert!(err.contains("write episodes"), "{err}");
    let err = refusal("episodes = 50");
    assert!(
        err.starts_with("episodes = 50 and learner = cs-ql cannot be used together"),
        "{err}"
    );
    assert!(err.contains("max_trials"), "{err}");
    let s = SettingsDraft::from_toml(
        "learner = \"belief\"\nepisodes = 40\n[costly]\nprice = 0.1",
        "f",
    )
    .unwrap()
    .build()
    .unwrap();
    assert_eq!(s.max_trials.get(), 40);
    let echo = SettingsDraft::from(&s);
    assert_eq!(
        (echo.episodes.map(|n| n.get()), echo.max_trials),
        (Some(40), None)
    );
    assert_eq!(echo.build().unwrap(), s);
    let cs_ql = SettingsDraft::from(&run_settings_with_trials(70));
    assert_eq!(
        (cs_ql.max_trials.map(|n| n.get()), cs_ql.episodes),
        (Some(70), None)
    );
}

fn run_settings_with_trials(n: u32) -> RunSettings {
    SettingsDraft::from_toml(&format!("max_trials = {n}"), "f")
        .unwrap()
        .build()
        .unwrap()
}
