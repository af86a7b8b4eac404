//! The one entry point, `csql::run_resolved`: it runs every learner in every kind of
//! world and gives what its forms give, and the forms refuse what they cannot run
//! rather than running another learner in its place.

use csql::{
    CostlySettings, KeepTrace, LearnerKind, Report, Resolved, RunSettings, Setup, StrategyKind,
};

/// Settings of a learner played on episodes, priced and short, on a grid map.
fn on_episodes(kind: LearnerKind) -> RunSettings {
    let mut s = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 2).with_learner(kind);
    s.costly = Some(CostlySettings::new(1.0));
    s.max_trials = csql::TrialCap::new(20).unwrap();
    s
}

#[test]
fn every_form_of_a_run_judged_by_trials_refuses_a_learner_played_on_episodes() {
    for kind in [LearnerKind::AmrlQ, LearnerKind::Belief] {
        let s = on_episodes(kind);
        let setup = Setup::new(&s).unwrap();
        let classify = csql::Classify::new(&setup.sensed(&s));
        let refusals = [
            csql::run(&s).map(|_| ()),
            csql::run_on(&setup, &s).map(|_| ()),
            csql::run_observed(&setup, &s, &mut KeepTrace).map(|_| ()),
            csql::run_with_representation(&setup, &s).map(|_| ()),
            csql::run_on_with(&setup, &s, classify).map(|_| ()),
        ];
        for (i, r) in refusals.into_iter().enumerate() {
            let err = r.expect_err("refused").to_string();
            assert!(
                err.contains(&format!("learner = {kind}")) && err.contains("judged by trials"),
                "form {i}, {kind}: {err}"
            );
        }
    }
}

#[test]
fn the_entry_point_gives_what_its_forms_give() {
    // A grid map: the same report as `run_on`.
    let s = RunSettings::tan1991("tan3x3", StrategyKind::Random, 3);
    let setup = Setup::new(&s).unwrap();
    let report = csql::run_resolved(&Resolved::new(&s).unwrap(), &s, &mut KeepTrace).unwrap();
    assert_eq!(report.trials(), Some(&csql::run_on(&setup, &s).unwrap()));
    assert_eq!(report.trials(), Some(&csql::run(&s).unwrap()));
    // Episodes: the same report as `costed_report_in`.
    let s = on_episodes(LearnerKind::AmrlQ);
    let resolved = Resolved::new(&s).unwrap();
    let report = csql::run_resolved(&resolved, &s, &mut KeepTrace).unwrap();
    let direct = csql::costed_report_in(&resolved, &s, &mut KeepTrace).unwrap();
    assert_eq!(report.episodes(), Some(&direct));
    // Written as the one report it holds.
    assert_eq!(
        serde_json::to_string(&report).unwrap(),
        serde_json::to_string(&direct).unwrap()
    );
}

#[test]
fn a_world_given_in_code_runs_as_the_same_world_named() {
    let s = RunSettings::tan1991("frozenlake4x4", StrategyKind::Eager, 4);
    let named = csql::run_resolved(&Resolved::new(&s).unwrap(), &s, &mut KeepTrace).unwrap();
    let lake = mdp::builtin_world("frozenlake4x4", &Default::default()).unwrap();
    let given = Resolved::given(lake, &s).unwrap();
    let report = csql::run_resolved(&given, &s, &mut KeepTrace).unwrap();
    assert!(matches!(report, Report::Trials(_)));
    assert_eq!(report, named);
    // The world carries its own dynamics: settings that would change them are refused.
    let mut slipping = s.clone();
    slipping.world.slip = Some(mdp::Slip::new(0.2).unwrap());
    let lake = mdp::builtin_world("frozenlake4x4", &Default::default()).unwrap();
    let err = Resolved::given(lake, &slipping).unwrap_err().to_string();
    assert!(
        err.contains("frozenlake4x4") && err.contains("[world] slip"),
        "{err}"
    );
}

#[test]
fn the_entry_point_checks_the_settings_it_is_given_against_the_world() {
    // Settings changed after the world was resolved are checked again, on a grid too.
    let s = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    let resolved = Resolved::new(&s).unwrap();
    let mut judged = s.clone();
    judged.judge.quality_patience = 3;
    let err = csql::run_resolved(&resolved, &judged, &mut KeepTrace)
        .unwrap_err()
        .to_string();
    assert!(err.contains("quality_patience"), "{err}");
}
