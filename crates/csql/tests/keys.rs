//! The one table of the settings' keys (`csql::SETTING_KEYS`): every key of every table
//! enumerated against every learner, refused exactly where the learner does not read it;
//! the table held to the fields of the settings and to the specification's list (6.9).

use csql::{LearnerKind, RunSettings, SETTING_KEYS, SettingKey, SettingsDraft, StrategyKind};

/// Every learner, those of `csql::run` and those played on costed episodes.
const EVERY: [LearnerKind; 5] = [
    LearnerKind::CsQl,
    LearnerKind::UTree,
    LearnerKind::FullSensing,
    LearnerKind::AmrlQ,
    LearnerKind::Belief,
];

/// A valid value, other than the default, of every key but `learner`, as TOML: the key
/// alone, and the key with what it needs to mean something (`random_moves` the random
/// strategy, `[prediction]` a level of prediction, ...). Keys of a table come with their
/// table's header.
fn sample(k: &SettingKey) -> (String, String) {
    let alone = |line: &str| match k.table {
        None => line.to_string(),
        Some(table) => format!("[{table}]\n{line}"),
    };
    let (value, needs): (&str, &str) = match (k.table, k.name) {
        (None, "map") => ("\"tan3x3\"", ""),
        (None, "seed") => ("5", ""),
        (None, "max_moves") => ("50", ""),
        (None, "max_trials") => ("30", ""),
        (None, "episodes") => ("30", ""),
        (None, "beta") => ("0.5", ""),
        (None, "gamma") => ("0.8", ""),
        (None, "temperature") => ("0.3", ""),
        (None, "tolerance") => ("0.001", ""),
        (None, "decrease_threshold") => ("0.1", ""),
        (None, "max_rows") => ("500", ""),
        (None, "strategy") => ("\"lazy\"", ""),
        (None, "random_moves") => ("5", "strategy = \"random\"\n"),
        (None, "predict_sensing") => ("\"learned\"", ""),
        (Some("world"), "slip") => ("0.1", ""),
        (Some("world"), "sensing_radius") => ("2", ""),
        (Some("world"), "slide") => ("0.5", ""),
        (Some("world"), "sensing") => ("\"local\"", ""),
        (Some("world"), "factor_costs") => ("[1.0, 2.0]", ""),
        (Some("world"), "sensor_noise") => ("0.1", ""),
        (Some("judge"), "judge_by_quality") => ("true", ""),
        (Some("judge"), "quality_every") => ("5", ""),
        (Some("judge"), "quality_patience") => ("3", ""),
        (Some("costly"), "price") => ("0.5", ""),
        (Some("costly"), "rule") => ("\"after-outcome\"\nprice = 0.5", ""),
        (Some("extensions"), "detector") => ("\"statistical\"", ""),
        (Some("extensions"), "rate") => ("{ window = 8 }\ndetector = \"statistical\"", ""),
        (Some("extensions"), "matching") => ("\"nearest\"", ""),
        (Some("extensions"), "confirm_new") => ("2", ""),
        (Some("extensions"), "reads") => ("3", ""),
        (Some("extensions"), "memory") => ("2", ""),
        (Some("prediction"), "confirmations") => ("4", "predict_sensing = \"learned\"\n"),
        (Some("prediction"), "recheck") => ("0.1", "predict_sensing = \"learned\"\n"),
        (Some("prediction"), "max_skips") => ("8", "predict_sensing = \"learned\"\n"),
        (Some("prediction"), "verify") => ("0.1", "predict_sensing = \"learned\"\n"),
        (Some("prediction"), "navigation_trials") => ("5", "predict_sensing = \"learned\"\n"),
        (Some("prediction"), "memory_moves") => ("2", "predict_sensing = \"motion\"\n"),
        (Some("u_tree"), "fringe") => ("3", ""),
        (Some("u_tree"), "alpha") => ("0.05", ""),
        (Some("u_tree"), "window") => ("1000", ""),
        (Some("u_tree"), "test_every") => ("10", ""),
        (Some("u_tree"), "min_group") => ("4", ""),
        (Some("u_tree"), "patience") => ("50", ""),
        (Some("amrl_q"), "learning_rate") => ("0.2", ""),
        (Some("amrl_q"), "epsilon") => ("0.2", ""),
        (Some("amrl_q"), "discount") => ("0.9", ""),
        (Some("amrl_q"), "measure_bias") => ("0.2", ""),
        (Some("amrl_q"), "greedy_share") => ("0.2", ""),
        (Some("amrl_q"), "measuring") => ("\"always\"", ""),
        (Some("belief"), "max_uncertain") => ("5", ""),
        (Some("belief"), "trust") => ("3", ""),
        (Some("belief"), "prior") => ("2.0", ""),
        (Some("belief"), "optimism") => ("0.5", ""),
        (Some("belief"), "whole_state") => ("true", ""),
        (Some("belief"), "max_beliefs") => ("100", ""),
        (Some("belief"), "move_cost") => ("1e-5", ""),
        (Some("belief"), "blind_plans") => ("8", ""),
        (Some("belief"), "shared_moves") => ("48", ""),
        _ => panic!("no sample value for the key {}: add one", k.path()),
    };
    let line = alone(&format!("{} = {value}", k.name));
    (line.clone(), format!("{needs}{line}"))
}

/// The key at its default value, as TOML with its table's header, for the keys that have
/// one: a key given is given, whatever its value, and is refused where it is not read
/// just as at any other value.
fn at_default(k: &SettingKey) -> Option<String> {
    let value = match (k.table, k.name) {
        (Some("world"), "slip" | "slide" | "sensor_noise") => "0.0",
        _ => return None,
    };
    Some(format!("[{}]\n{} = {value}", k.table?, k.name))
}

/// `text` read, over the smallest settings of learner `kind` (`[costly] price` for the
/// learners on costed episodes, unless `text` has its own `[costly]`).
fn draft_for(kind: LearnerKind, text: &str) -> SettingsDraft {
    let given = SettingsDraft::from_toml(text, "f.toml")
        .unwrap_or_else(|e| panic!("{text:?} is not read: {e}"));
    let base = match kind {
        LearnerKind::AmrlQ | LearnerKind::Belief => "[costly]\nprice = 0.1",
        _ => "",
    };
    let mut draft = SettingsDraft::from_toml(base, "base").unwrap();
    draft.learner = Some(kind);
    draft.overlay(given);
    draft
}

/// Every key of every table, given to every learner, is refused exactly when the learner
/// does not read it, with a message that names the key and the learner; read, it is
/// taken.
#[test]
fn every_key_is_refused_exactly_where_its_learner_does_not_read_it() {
    let mut refused = 0;
    for k in SETTING_KEYS.iter().filter(|k| k.name != "learner") {
        let (alone, with_needs) = sample(k);
        let samples =
            std::iter::once((alone, with_needs)).chain(at_default(k).map(|d| (d.clone(), d)));
        for (alone, with_needs) in samples {
            for kind in EVERY {
                let learner = format!("learner = {kind}");
                if k.reads(kind) {
                    let draft = draft_for(kind, &with_needs);
                    if let Err(e) = draft.build() {
                        panic!(
                            "{} is read by {kind} but {with_needs:?} is refused: {e}",
                            k.path()
                        );
                    }
                } else {
                    let err = draft_for(kind, &alone)
                        .build()
                        .map(|_| ())
                        .expect_err(&format!("{alone:?} with {kind} must be refused"));
                    let err = err.to_string();
                    assert!(
                        err.contains(k.name) && err.contains(&learner),
                        "{alone:?} with {kind}: {err}",
                    );
                    if let Some(table) = k.table {
                        assert!(err.contains(&format!("[{table}]")), "{err}");
                    }
                    refused += 1;
                }
            }
        }
    }
    // Nine keys of Q-learning and judging, and sensor noise (at another value and at its
    // default), for each learner on costed episodes; CS-QL's keys for four learners;
    // U-Tree's, AMRL-Q's and belief's for four; the price for U-Tree; `max_trials` for
    // the two learners on episodes and `episodes` for the three judged over trials;
    // belief's `blind_plans` and `shared_moves` for four each.
    assert_eq!(refused, 2 * 11 + 4 * 15 + 3 * 4 * 6 + 4 + 2 + 2 + 3 + 4 + 4);
}

/// A table of a learner that is not the run's is refused even empty or at its defaults,
/// as is a key of the top level given at its default.
#[test]
fn another_learners_table_is_refused_even_at_its_defaults() {
    let defaults = [
        ("u_tree", "fringe = 4"),
        ("amrl_q", "epsilon = 0.1"),
        ("belief", "max_uncertain = 7"),
        ("extensions", "reads = 1"),
        ("prediction", "confirmations = 3"),
        ("judge", "judge_by_quality = false"),
    ];
    for (table, at_default) in defaults {
        for kind in EVERY {
            let reads = SETTING_KEYS
                .iter()
                .any(|k| k.table == Some(table) && k.reads(kind));
            for text in [format!("[{table}]"), format!("[{table}]\n{at_default}")] {
                let built = draft_for(kind, &text).build();
                if reads {
                    continue;
                }
                let err = built.map(|_| ()).expect_err(&text).to_string();
                assert!(
                    err.starts_with(&format!("[{table}] and learner = {kind}")),
                    "{text:?} with {kind}: {err}"
                );
            }
        }
    }
    // The paper's values, given where they mean nothing, are refused all the same.
    for (text, named) in [
        ("gamma = 0.9", "gamma = 0.9"),
        ("beta = 1.0", "beta = 1"),
        ("max_rows = 100000", "max_rows = 100000"),
    ] {
        let err = draft_for(LearnerKind::Belief, text).build().unwrap_err();
        assert!(
            err.to_string()
                .starts_with(&format!("{named} and learner = belief")),
            "{err}"
        );
    }
    let err = draft_for(LearnerKind::UTree, "predict_sensing = \"off\"")
        .build()
        .unwrap_err();
    assert!(
        err.to_string()
            .starts_with("predict_sensing = off and learner = u-tree"),
        "{err}"
    );
}

/// A key of `[world]` is given or not, whatever its value: at its default it is refused,
/// by name, wherever the world or the agent does not read it, as at any other value;
/// where it is read, it is taken, echoed, and changes nothing else.
#[test]
fn world_keys_at_their_defaults_are_refused_where_the_world_does_not_read_them() {
    let resolve = |text: &str| {
        let s = SettingsDraft::from_toml(text, "f.toml")
            .unwrap()
            .build()
            .unwrap_or_else(|e| panic!("{text:?}: {e}"));
        csql::Resolved::new(&s).map(|_| ())
    };
    for (text, named) in [
        // A grid map moves one cell at a time and senses around the robot.
        (
            "[world]\nslide = 0.0",
            ["the grid map tan8x8", "[world] slide = 0"],
        ),
        (
            "map = \"tan3x3\"\n[world]\nsensing = \"local\"",
            ["the grid map tan3x3", "[world] sensing = \"local\""],
        ),
        // Taxi is deterministic: it reads no slip or slide.
        ("map = \"taxi\"\n[world]\nslip = 0.0", ["taxi", "slip"]),
        ("map = \"taxi\"\n[world]\nslide = 0.0", ["taxi", "slide"]),
    ] {
        let err = resolve(text)
            .expect_err(&format!("{text:?} must be refused"))
            .to_string();
        for n in named {
            assert!(err.contains(n), "{text:?}: {err}");
        }
    }
    // Read, a key at its default is taken, runs as if absent, and is echoed.
    for text in [
        "[world]\nslip = 0.0\nsensor_noise = 0.0",
        "map = \"frozenlake4x4\"\n[world]\nslip = 0.0\nslide = 0.0\nsensing = \"local\"",
        "map = \"taxi\"\n[world]\nsensing = \"factors\"",
    ] {
        resolve(text).unwrap_or_else(|e| panic!("{text:?}: {e}"));
        let s = SettingsDraft::from_toml(text, "f")
            .unwrap()
            .build()
            .unwrap();
        let echo = toml::to_string(&s).unwrap();
        assert!(echo.contains("[world]"), "{echo}");
        assert_eq!(
            SettingsDraft::from_toml(&echo, "echo")
                .unwrap()
                .build()
                .unwrap(),
            s
        );
    }
    // A world built in code carries its own dynamics, features and prices.
    let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
    for key in ["slip = 0.0", "slide = 0.0", "sensing = \"local\""] {
        let s = SettingsDraft::from_toml(&format!("[world]\n{key}"), "f")
            .unwrap()
            .build()
            .unwrap();
        let err = csql::Resolved::given(lake.clone(), &s)
            .map(|_| ())
            .expect_err(key)
            .to_string();
        let name = key.split(' ').next().unwrap();
        assert!(
            err.contains("the world frozenlake4x4 given to the run")
                && err.contains(&format!("[world] {name}")),
            "{key}: {err}"
        );
    }
    // A step-driven agent senses the caller's world: every key of [world] is refused.
    for key in ["slip = 0.0", "sensor_noise = 0.0", "slide = 0.0"] {
        let text = format!("[world]\n{key}");
        let err = SettingsDraft::from_toml(&text, "f")
            .unwrap()
            .build_for_stepper()
            .map(|_| ())
            .expect_err(&text)
            .to_string();
        let name = key.split(' ').next().unwrap();
        assert!(
            err.starts_with(&format!("[world] {name} = 0 and a step-driven agent")),
            "{text:?}: {err}"
        );
    }
}

/// The names serde's message of an unknown key lists as expected.
fn expected_fields(text: &str) -> Vec<String> {
    let err = SettingsDraft::from_toml(text, "f.toml")
        .unwrap_err()
        .to_string();
    let list = err
        .split_once("expected one of ")
        .or_else(|| err.split_once("expected "))
        .unwrap_or_else(|| panic!("{text:?}: {err}"))
        .1;
    list.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// The table of keys holds every field of the settings and nothing else: the top level's
/// keys and tables, and each table's keys, are the ones the settings file is read with.
#[test]
fn the_table_of_keys_is_the_fields_of_the_settings() {
    let mut top: Vec<String> = SETTING_KEYS
        .iter()
        .filter(|k| k.table.is_none())
        .map(|k| k.name.to_string())
        .chain(csql::setting_tables().map(str::to_string))
        .collect();
    let mut read = expected_fields("no_such_key = 1");
    top.sort();
    read.sort();
    assert_eq!(top, read, "the top level");
    for table in csql::setting_tables() {
        let mut keys: Vec<String> = SETTING_KEYS
            .iter()
            .filter(|k| k.table == Some(table))
            .map(|k| k.name.to_string())
            .collect();
        let mut read = expected_fields(&format!("[{table}]\nno_such_key = 1"));
        keys.sort();
        read.sort();
        assert_eq!(keys, read, "[{table}]");
    }
    // Every table but [world] is read whole or not at all by each learner, so that a
    // table of another learner is refused given at all.
    for table in csql::setting_tables().filter(|t| *t != "world") {
        let mut readers = SETTING_KEYS
            .iter()
            .filter(|k| k.table == Some(table))
            .map(|k| k.read_by);
        let first = readers.next().unwrap();
        assert!(readers.all(|r| r == first), "[{table}]");
    }
}

/// The judging keys have their own table; an old file with them under `[extensions]` is
/// told where they went.
#[test]
fn the_judging_keys_moved_to_their_own_table() {
    for key in [
        "judge_by_quality = true",
        "quality_every = 5",
        "quality_patience = 3",
    ] {
        let err = SettingsDraft::from_toml(&format!("[extensions]\n{key}"), "old.toml")
            .unwrap_err()
            .to_string();
        assert!(err.contains("moved") && err.contains("[judge]"), "{err}");
        let s = SettingsDraft::from_toml(&format!("[judge]\n{key}"), "new.toml")
            .unwrap()
            .build()
            .unwrap();
        assert_ne!(s.judge, csql::JudgeSettings::default());
        // The report's JSON has them in [judge] too, and reads back.
        let text = toml::to_string(&s).unwrap();
        assert!(text.contains("[judge]"), "{text}");
        assert_eq!(
            SettingsDraft::from_toml(&text, "echo")
                .unwrap()
                .build()
                .unwrap(),
            s
        );
    }
}

/// Settings of every learner, written out (a report's `settings`) and read back, are the
/// same settings; a file that chooses another learner starts it from what it reads.
#[test]
fn settings_of_every_learner_round_trip_and_change_learner() {
    for kind in EVERY {
        let mut s = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 4).with_learner(kind);
        if kind != LearnerKind::UTree {
            s.costly = Some(csql::CostlySettings::new(0.25));
        }
        let draft = SettingsDraft::from(&s);
        assert_eq!(draft.build().unwrap(), s, "{kind}");
        let text = toml::to_string(&s).unwrap();
        let read = SettingsDraft::from_toml(&text, "echo")
            .unwrap()
            .build()
            .unwrap();
        assert_eq!(read, s, "{kind}: {text}");
        if kind.on_episodes() {
            assert!(!text.contains("gamma") && !text.contains("beta"), "{text}");
        }
    }
    // CS-QL with its own keys and Q-learning's, then AMRL-Q, then CS-QL again.
    let mut s = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 4);
    s.apply_toml(
        "beta = 0.5\n[judge]\nquality_every = 3\n[world]\nsensor_noise = 0.1",
        "a",
    )
    .unwrap();
    s.apply_toml("learner = \"amrl-q\"\n[costly]\nprice = 0.5", "b")
        .unwrap();
    assert_eq!(s.learner.kind(), LearnerKind::AmrlQ);
    assert!(s.world.sensor_noise.is_none() && s.judge == csql::JudgeSettings::default());
    s.apply_toml("learner = \"full-sensing\"\nbeta = 0.5", "c")
        .unwrap();
    assert_eq!(
        (s.learner.kind(), s.beta.get()),
        (LearnerKind::FullSensing, 0.5)
    );
    assert!(
        s.apply_toml("gamma = 0.5\nlearner = \"belief\"", "d")
            .is_err()
    );
    // The random strategy's random moves, echoed with it only, at the paper's value are
    // left when another strategy is chosen; given with another, they are refused.
    let mut s = RunSettings::tan1991("tan3x3", StrategyKind::Random, 4);
    assert!(toml::to_string(&s).unwrap().contains("random_moves = 20"));
    s.apply_toml("strategy = \"lazy\"", "e").unwrap();
    assert!(!toml::to_string(&s).unwrap().contains("random_moves"));
    let err = s
        .apply_toml("random_moves = 20", "f")
        .unwrap_err()
        .to_string();
    assert!(
        err.starts_with("random_moves = 20 and strategy = lazy"),
        "{err}"
    );
    let err = SettingsDraft::from_toml("[prediction]", "g")
        .unwrap()
        .build()
        .unwrap_err();
    assert!(
        err.to_string()
            .starts_with("[prediction] and predict_sensing = off"),
        "{err}"
    );
}

/// The specification's list of keys (6.9) is the table of keys: every key, with the
/// learners that read it, and none other.
#[test]
fn the_specification_lists_the_keys_as_the_table_has_them() {
    let spec = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/specification.md"
    ))
    .unwrap();
    let header = "| key | cs-ql | u-tree | full-sensing | amrl-q | belief |";
    let at = spec
        .find(header)
        .expect("the specification has the table of keys");
    let rows: Vec<&str> = spec[at..]
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .collect();
    let listed: Vec<(String, Vec<LearnerKind>)> = rows
        .iter()
        .map(|row| {
            let cells: Vec<&str> = row.trim_matches('|').split('|').map(str::trim).collect();
            assert_eq!(cells.len(), 6, "{row}");
            let key = cells[0].trim_matches('`').to_string();
            let readers = EVERY
                .iter()
                .zip(&cells[1..])
                .filter_map(|(kind, cell)| match *cell {
                    "yes" => Some(*kind),
                    "" | "-" => None,
                    other => panic!("{row}: {other:?} is neither yes nor -"),
                })
                .collect();
            (key, readers)
        })
        .collect();
    let table: Vec<(String, Vec<LearnerKind>)> = SETTING_KEYS
        .iter()
        .map(|k| {
            let key = match k.table {
                Some(t) => format!("[{t}] {}", k.name),
                None => k.name.to_string(),
            };
            (key, k.read_by.to_vec())
        })
        .collect();
    assert_eq!(listed, table);
}
