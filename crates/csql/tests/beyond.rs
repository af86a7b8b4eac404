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
    // The same run; the echo of the settings says what was given (a key of [world] is
    // given or not, whatever its value).
    assert_eq!(outcome(&plain), outcome(&explicit));
    assert!(json(&plain).contains("\"judged_by\":\"oracle\""));
    assert!(!json(&plain).contains("slip"));
    assert!(json(&explicit).contains("\"world\":{\"slip\":0.0,\"sensor_noise\":0.0}"));
}

/// The report without its echo of the settings: what the run did, and nothing it was told.
/// A setting that the run ignored leaves this unchanged.
fn outcome(s: &RunSettings) -> serde_json::Value {
    let mut v = serde_json::to_value(csql::run(s).unwrap()).unwrap();
    let echo = v.as_object_mut().unwrap().remove("settings");
    assert!(echo.is_some(), "the report has no `settings` to leave out");
    v
}

#[test]
fn each_extension_changes_the_run_only_when_on() {
    let base = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 2);
    // (the extension on, the same settings with it at its default); both judged alike,
    // so that only the extension itself can tell the two runs apart.
    let common = "max_trials = 100\n[judge]\njudge_by_quality = true\nquality_every = 50";
    let noisy = "max_trials = 100\n[world]\nsensor_noise = 0.05\n[judge]\nquality_every = 50";
    let near = "max_trials = 100\n[world]\nsensing_radius = 1\n[judge]\nquality_every = 50";
    let tweaks = [
        (
            "max_trials = 100\n[world]\nslip = 0.1\n[judge]\njudge_by_quality = true\nquality_every = 50".to_string(),
            common.to_string(),
        ),
        (noisy.to_string(), common.to_string()),
        (near.to_string(), common.to_string()),
        (
            format!("{common}\n[extensions]\ndetector = \"statistical\""),
            common.to_string(),
        ),
        (
            format!("{noisy}\n[extensions]\nmatching = \"nearest\""),
            noisy.to_string(),
        ),
        (format!("{noisy}\n[extensions]\nconfirm_new = 3"), noisy.to_string()),
        (format!("{common}\n[extensions]\nreads = 3"), common.to_string()),
        (format!("{near}\n[extensions]\nmemory = 2"), near.to_string()),
        (
            "max_trials = 100\n[judge]\njudge_by_quality = true".to_string(),
            "max_trials = 100".to_string(),
        ),
        (
            format!("learner = \"u-tree\"\n{common}"),
            common.to_string(),
        ),
        (
            format!("learner = \"full-sensing\"\n{common}"),
            common.to_string(),
        ),
    ];
    for (on, off) in &tweaks {
        let mut with = base.clone();
        with.apply_toml(on, "on").unwrap();
        let mut without = base.clone();
        without.apply_toml(off, "off").unwrap();
        assert_ne!(with, without, "{on}");
        let out = outcome(&with);
        assert_ne!(
            out,
            outcome(&without),
            "{on} changed nothing but the settings"
        );
        assert!(out.to_string().contains("policy_quality"), "{on}");
    }
}

#[test]
fn runs_beyond_the_paper_are_pure_functions_of_their_settings() {
    let mut s = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 5);
    s.apply_toml(
        "max_trials = 60\n[world]\nslip = 0.1\nsensor_noise = 0.05\n[extensions]\ndetector = \"statistical\"\nmatching = \"nearest\"\n[judge]\nquality_every = 30",
        "t",
    )
    .unwrap();
    assert_eq!(json(&s), json(&s));
    let q = csql::run(&s).unwrap().quality;
    // Under noise a memoryless policy is evaluated exactly from its sampled action
    // probabilities.
    assert_eq!(q.method, csql::QualityMethod::SampledPolicy);
    assert!(q.standard_error.is_finite() && q.standard_error < 0.05);
}

#[test]
fn slip_with_the_statistical_detector_reaches_quality() {
    let mut s = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 1);
    s.apply_toml(
        "beta = 0.2\nmax_trials = 2000\n[world]\nslip = 0.1\n[extensions]\ndetector = \"statistical\"",
        "t",
    )
    .unwrap();
    assert_eq!(s.extensions().detector, DetectorKind::Statistical);
    let r = csql::run(&s).unwrap();
    let q = r.quality;
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
            "max_trials = 150\n[world]\nsensor_noise = 0.05\n[judge]\nquality_every = 150",
            "t",
        )
        .unwrap();
    let mut near = exact.clone();
    near.cs_ql_mut().unwrap().extensions.matching = Matching::Nearest;
    let a = csql::run(&exact).unwrap().quality;
    let b = csql::run(&near).unwrap().quality;
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

#[test]
fn new_settings_at_their_defaults_change_nothing() {
    let plain = RunSettings::tan1991("tan3x3", StrategyKind::Eager, 2);
    let mut explicit = plain.clone();
    explicit
        .apply_toml(
            "learner = \"cs-ql\"\n[extensions]\nconfirm_new = 1\nreads = 1\nmemory = 0\n[judge]\njudge_by_quality = false",
            "t",
        )
        .unwrap();
    assert_eq!(json(&plain), json(&explicit));
    let out = json(&plain);
    for name in [
        "learner",
        "confirm_new",
        "reads",
        "memory",
        "judge_by_quality",
        "u_tree",
    ] {
        assert!(!out.contains(&format!("\"{name}\"")), "{name}");
    }
}

#[test]
fn reading_three_times_without_noise_learns_the_same_at_three_times_the_cost() {
    // Without noise every read agrees: the run is the same, each charge tripled.
    let mut once = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 6);
    once.judge.judge_by_quality = true;
    let mut thrice = once.clone();
    thrice.cs_ql_mut().unwrap().extensions.reads = 3;
    let (a, b) = (csql::run(&once).unwrap(), csql::run(&thrice).unwrap());
    assert_eq!(a.trials, b.trials);
    assert_eq!(a.descriptions, b.descriptions);
    assert_eq!(b.total_cost, 3.0 * a.total_cost);
    let (qa, qb) = (a.quality, b.quality);
    assert_eq!(qb.learner_cost_per_state, 3.0 * qa.learner_cost_per_state);
    assert_eq!(
        qb.cost_to_quality.unwrap(),
        3.0 * qa.cost_to_quality.unwrap()
    );
}

#[test]
fn confirming_new_descriptions_keeps_misreadings_out() {
    let mut plain = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 4);
    plain
        .apply_toml(
            "beta = 0.2\nmax_trials = 300\n[world]\nsensor_noise = 0.05\n[extensions]\nmatching = \"nearest\"\n[judge]\nquality_every = 300",
            "t",
        )
        .unwrap();
    let mut confirmed = plain.clone();
    confirmed.cs_ql_mut().unwrap().extensions.confirm_new = 3;
    let a = csql::run(&plain).unwrap().quality;
    let b = csql::run(&confirmed).unwrap().quality;
    assert!(
        2 * b.descriptions < a.descriptions,
        "{} vs {}",
        b.descriptions,
        a.descriptions
    );
}

#[test]
fn memory_tells_apart_what_a_radius_of_one_cannot() {
    let mut plain = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 1);
    plain
        .apply_toml(
            "max_trials = 300\n[world]\nsensing_radius = 1\n[judge]\nquality_every = 300",
            "t",
        )
        .unwrap();
    let mut remembering = plain.clone();
    remembering.cs_ql_mut().unwrap().extensions.memory = 1;
    let a = csql::run(&plain).unwrap().quality;
    let b = csql::run(&remembering).unwrap().quality;
    // Four neighbours give at most 3^4 views; a step of history gives more rows, and a
    // better policy.
    assert!(a.descriptions <= 81);
    assert!(b.descriptions > a.descriptions);
    assert!(
        b.policy_quality > a.policy_quality,
        "{} vs {}",
        b.policy_quality,
        a.policy_quality
    );
    // Remembering is free: every description still has at most the four features.
    assert!(b.mean_features <= 4.0);
}

#[test]
fn the_baselines_learn_the_paper_world() {
    for learner in [csql::LearnerKind::UTree, csql::LearnerKind::FullSensing] {
        let mut s = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 2);
        s = s.with_learner(learner);
        s.max_trials = csql::TrialCap::new(2000).unwrap();
        let r = csql::run(&s).unwrap();
        // Judged as CS-QL is: by the oracle, which ends the run at convergence.
        assert_eq!(r.judged_by, csql::Judging::Oracle);
        assert!(
            r.converged,
            "{learner}: not converged in {} trials",
            r.trials
        );
        assert_eq!(r.table1.trials_to_converge, Some(r.trials));
        let q = r.quality;
        assert_eq!(q.policy_quality, 1.0, "{learner}: {q:?}");
        assert!(
            q.trials_to_quality.is_some_and(|t| t <= r.trials),
            "{learner}"
        );
        if learner == csql::LearnerKind::FullSensing {
            // One row per state, charged the whole view.
            assert_eq!(q.descriptions, 50);
            let setup = csql::Setup::new(&s).unwrap();
            let whole: f64 = setup
                .world
                .states()
                .iter()
                .map(|&x| csql::whole_world_cost(&setup.world, &setup.space, x))
                .sum::<f64>()
                / 50.0;
            assert_eq!(q.learner_cost_per_state, whole);
        }
    }
}

#[test]
fn cs_ql_extensions_are_refused_with_another_learner() {
    let mut s = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    let e = s
        .apply_toml("learner = \"u-tree\"\n[extensions]\nreads = 3", "mine.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("u-tree"), "{e}");
    let e = s
        .apply_toml(
            "learner = \"full-sensing\"\npredict_sensing = \"learned\"",
            "mine.toml",
        )
        .unwrap_err()
        .to_string();
    assert!(e.contains("predict_sensing"), "{e}");
    assert!(s.apply_toml("[u_tree]\nalpha = 1.5", "m").is_err());
    assert!(s.apply_toml("[extensions]\nreads = 0", "m").is_err());
}

/// A setting that would do nothing, or that would change how a run is judged without
/// saying so, is refused with a message that names it (and the setting it conflicts with).
#[test]
fn settings_that_mean_nothing_are_refused() {
    let cases = [
        ("[extensions]\nrate = { window = 10 }", "rate"),
        ("[judge]\nquality_patience = 3", "quality_patience"),
        // The quality is measured in every run, on this schedule.
        ("[judge]\nquality_every = 11", ""),
        ("[extensions]\nmemory = 2", "memory"),
        ("[u_tree]\nfringe = 3", "u_tree"),
        ("[prediction]\nmax_skips = 3", "prediction"),
        ("learner = \"u-tree\"\nstrategy = \"eager\"", "strategy"),
        ("world = [0.3, 0.1]", "must be a table"),
        ("slip = 0.1", "[world]"),
        ("[world]\nbeta = 0.2", "top level"),
        ("[world]\nreads = 3", "[extensions]"),
        (
            "predict_sensing = \"motion\"\n[world]\nslip = 0.1",
            "motion",
        ),
        ("[extensions]\ndetector = \"action\"\n", ""),
        (
            "beta = 0.5\n[extensions]\ndetector = \"action\"",
            "beta = 1",
        ),
    ];
    for (toml, fragment) in cases {
        let mut s = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
        let outcome = s
            .apply_toml(toml, "x.toml")
            .and_then(|()| csql::run(&s).map(|_| ()));
        if fragment.is_empty() {
            assert!(outcome.is_ok(), "{toml:?}: {outcome:?}");
            continue;
        }
        let err = outcome.expect_err(toml).to_string();
        assert!(err.contains(fragment), "{toml:?}: {err}");
        // Said once: no part of the message repeats itself.
        let first = err.lines().next().unwrap_or("");
        assert_eq!(err.matches(first).count(), 1, "{err}");
    }
    // quality_every alone no longer turns a converging run into one judged by quality.
    let plain = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    assert!(!plain.beyond_paper());
}

/// A run whose descriptions keep multiplying (plain CS-QL under sensor noise) stays
/// bounded: it ends at the trial where its representation passes `max_rows`, and says so.
#[test]
fn a_run_ends_when_its_descriptions_pass_the_cap() {
    let mut s = RunSettings::tan1991("tan8x8", StrategyKind::Eager, 1);
    s.apply_toml(
        "max_rows = 300\nmax_trials = 5000\n[world]\nsensor_noise = 0.05",
        "cap.toml",
    )
    .unwrap();
    let r = csql::run(&s).unwrap();
    let why = r.stopped.as_deref().expect("the cap ended the run");
    assert!(why.contains("max_rows = 300"), "{why}");
    assert!(r.trials < 5000, "{}", r.trials);
    let rows = r.trace.last().map(|t| t.descriptions).unwrap();
    assert!((301..400).contains(&rows), "{rows}");
    // Without noise nothing multiplies: the paper's run never meets the cap.
    let plain = csql::run(&RunSettings::tan1991("tan8x8", StrategyKind::Eager, 1)).unwrap();
    assert!(plain.stopped.is_none() && plain.converged);
    let mut zero = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    assert!(zero.apply_toml("max_rows = 0", "zero.toml").is_err());
}

/// Every learner is judged the same way and reported on the same measures: the oracle's
/// convergence in a deterministic world (which ends the run), and the policy quality with
/// the trials and cost until it reached 0.95 and stayed there, so that runs of different
/// learners compare line by line. Asking for the quality instead judges all of them by it.
#[test]
fn every_learner_is_judged_alike() {
    for (world, toml) in [
        ("tan3x3", ""),
        ("frozenlake4x4", "[world]\nsensing = \"local\""),
        ("frozenlake4x4", "[world]\nsensing = \"factors\""),
    ] {
        for learner in csql::LearnerKind::ALL {
            let mut s = RunSettings::tan1991(world, StrategyKind::Lazy, 4);
            s.apply_toml(toml, "t").unwrap();
            if learner != csql::LearnerKind::CsQl {
                s = s.with_learner(learner);
            }
            let r = csql::run(&s).unwrap();
            let what = format!("{learner} on {world} {toml:?}");
            assert_eq!(r.judged_by, csql::Judging::Oracle, "{what}");
            assert!(r.converged, "{what}");
            // Converged by the oracle: the policy is optimal, exactly.
            assert_eq!(r.policy_quality, 1.0, "{what}");
            let (t, c) = (r.quality.trials_to_quality, r.quality.cost_to_quality);
            assert!(t.is_some_and(|t| t <= r.trials), "{what}: {t:?}");
            assert!(c.is_some_and(|c| c <= r.total_cost), "{what}: {c:?}");
            assert!(r.quality.evaluations >= 1, "{what}");
            // The same settings judged by the quality: no oracle's verdict, a run that
            // ends once the quality has held.
            s.judge.judge_by_quality = true;
            let q = csql::run(&s).unwrap();
            assert_eq!(q.judged_by, csql::Judging::Quality, "{what}");
            assert!(
                !q.converged && q.table1.trials_to_converge.is_none(),
                "{what}"
            );
            assert!(q.quality.trials_to_quality.is_some(), "{what}");
        }
    }
}
