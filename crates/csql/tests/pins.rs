//! Determinism pinned: the full JSON of runs of every strategy on six maps on fixed
//! seeds, and the layouts of random maps, hashed. A dependency upgrade or a refactor that changes any
//! number of these (a move, a charge, a float's last digit) fails here loudly.
//!
//! When a change of results is intended, print the new hashes with
//! `cargo test -p csql --test pins -- --nocapture`, explain the change in the commit, and
//! update the table below.

use csql::{RunSettings, StrategyKind};

/// 64-bit FNV-1a: small, fixed, and independent of any dependency's version.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

fn run_hash(map: &str, strategy: StrategyKind, seed: u64) -> (u64, usize) {
    let report = csql::run(&RunSettings::tan1991(map, strategy, seed)).unwrap();
    // A converged run of the paper's world has found an optimal policy: exactly what its
    // final policy quality must say.
    if report.converged {
        assert!(
            (report.policy_quality - 1.0).abs() < 1e-9,
            "{map} {strategy:?} {seed}: {}",
            report.policy_quality
        );
    }
    let json = pinned_json(&report);
    (fnv1a(json.as_bytes()), json.len())
}

/// The report's JSON as it was pinned: everything but the measures added to every report
/// after the pins were taken (they measure the learned policy, they do not change it):
/// the final `policy_quality` (checked on its own where it is known), `judged_by`, and,
/// in a run the oracle judges, the `quality` block; in a run judged by the quality, that
/// block's cost per state kept its old name, `sensing_cost_per_state`. The judging keys,
/// echoed in the settings' table `[judge]` since they left `[extensions]`, are put back
/// at the end of `[extensions]`, where they were pinned (every pinned run that has them
/// has an extension too). CS-QL's `random_moves`, echoed since only with the random
/// strategy (the only one that reads it), is put back where it was pinned: at its
/// default, after `max_moves`.
fn pinned_json(report: &csql::RunReport) -> String {
    let json = serde_json::to_string(report).unwrap();
    let json = json.replacen("},\"judge\":{", ",", 1);
    let json = match report.settings.cs_ql() {
        Some(q) if q.strategy != StrategyKind::Random => {
            assert!(!json.contains("\"random_moves\""));
            json.replacen(",\"tolerance\":", ",\"random_moves\":20,\"tolerance\":", 1)
        }
        _ => json,
    };
    let json = cut(&json, ",\"policy_quality\":");
    let json = cut(&json, ",\"judged_by\":");
    match report.judged_by {
        csql::Judging::Oracle => cut(&json, ",\"quality\":"),
        csql::Judging::Quality => json.replacen(
            "\"learner_cost_per_state\":",
            "\"sensing_cost_per_state\":",
            1,
        ),
    }
}

/// `json` without the top-level field that starts with `key` (`,"name":`): a number, a
/// string or an object without strings that hold braces.
fn cut(json: &str, key: &str) -> String {
    let at = json
        .find(key)
        .unwrap_or_else(|| panic!("every report has {key}"));
    let value = &json[at + key.len()..];
    let len = if value.starts_with('{') {
        let mut depth = 0;
        value
            .char_indices()
            .find_map(|(i, c)| {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    _ => {}
                }
                (depth == 0).then_some(i + 1)
            })
            .expect("a closed object")
    } else {
        value.find([',', '}']).expect("more follows")
    };
    format!("{}{}", &json[..at], &json[at + key.len() + len..])
}

/// (map, strategy, seed, hash of the full JSON report, its length). The first four are
/// the hand-made maze, pinned when it was still called `tan8x8`: renamed, its runs kept
/// every byte but the name.
const RUNS: &[(&str, StrategyKind, u64, u64, usize)] = &[
    (
        "tan8x8-maze",
        StrategyKind::Resetting,
        1,
        0x92fc8eee6babcdbd,
        239650,
    ),
    (
        "tan8x8-maze",
        StrategyKind::Lazy,
        2,
        0x6180a858c647faba,
        51421,
    ),
    (
        "tan8x8-maze",
        StrategyKind::Random,
        3,
        0xe3e3e0bedcb21558,
        49101,
    ),
    (
        "tan8x8-maze",
        StrategyKind::Eager,
        4,
        0x6aa6d8d73deb513f,
        43969,
    ),
    (
        "random:10x10:0.2:5@0:0",
        StrategyKind::Lazy,
        6,
        0xf829ad79d1d401c9,
        94904,
    ),
    (
        "tan3x3",
        StrategyKind::Resetting,
        2,
        0x6ac7f6aca48fc017,
        11931,
    ),
    ("tan3x3", StrategyKind::Lazy, 2, 0x10503189ea928b2e, 6056),
    ("tan3x3", StrategyKind::Random, 2, 0x680413c26ab29b3e, 4489),
    ("tan3x3", StrategyKind::Eager, 2, 0xcc4a3d04a90e1dca, 5408),
    ("dyna9x6", StrategyKind::Lazy, 2, 0x666efa435a29ad3b, 50669),
    (
        "dyna9x6",
        StrategyKind::Random,
        2,
        0x5b80759e379fc1f0,
        37906,
    ),
    ("dyna9x6", StrategyKind::Eager, 2, 0x1f936be7eee1794c, 46169),
    (
        "corridors9x5",
        StrategyKind::Resetting,
        2,
        0x232fd63fc06d92fe,
        264877,
    ),
    (
        "corridors9x5",
        StrategyKind::Lazy,
        2,
        0xf4de2e7a21c879fb,
        63095,
    ),
    (
        "corridors9x5",
        StrategyKind::Random,
        2,
        0x326fcef0e298d7bf,
        45640,
    ),
    (
        "corridors9x5",
        StrategyKind::Eager,
        2,
        0x1b928a0ca05dcf7d,
        43447,
    ),
    (
        "random:10x10:0.2:3",
        StrategyKind::Resetting,
        2,
        0xefd7584287a1d7c0,
        424317,
    ),
    (
        "random:10x10:0.2:3",
        StrategyKind::Lazy,
        2,
        0xe5fb78cbd7804f3e,
        87780,
    ),
    (
        "random:10x10:0.2:3",
        StrategyKind::Random,
        2,
        0xbab714badefc8ba9,
        76215,
    ),
    (
        "random:10x10:0.2:3",
        StrategyKind::Eager,
        2,
        0xd87a5779793f072f,
        76649,
    ),
    (
        "random:12x12:0.2:5",
        StrategyKind::Resetting,
        2,
        0x196544bb063f2c34,
        908567,
    ),
    (
        "random:12x12:0.2:5",
        StrategyKind::Lazy,
        2,
        0x86459a7c7b48d315,
        154134,
    ),
    (
        "random:12x12:0.2:5",
        StrategyKind::Random,
        2,
        0x07e63f0caf28aba0,
        128130,
    ),
    (
        "random:12x12:0.2:5",
        StrategyKind::Eager,
        2,
        0xda3de94f4dd3547b,
        122720,
    ),
    (
        "random:16x16:0.2:1",
        StrategyKind::Lazy,
        1,
        0xd7c80b2505503602,
        302577,
    ),
    (
        "random:16x16:0.2:1",
        StrategyKind::Random,
        1,
        0x21d9e0f367ed11e9,
        284238,
    ),
];

#[test]
fn runs_are_pinned() {
    let mut wrong = Vec::new();
    for &(map, strategy, seed, hash, len) in RUNS {
        let got = run_hash(map, strategy, seed);
        println!(
            "    (\"{map}\", StrategyKind::{strategy:?}, {seed}, {:#018x}, {}),",
            got.0, got.1
        );
        if got != (hash, len) {
            wrong.push(format!("{map} {strategy:?} seed {seed}"));
        }
    }
    assert!(wrong.is_empty(), "results changed: {wrong:?}");
}

#[test]
fn the_pin_sees_a_one_setting_change() {
    // The companion that shows the pin can fail: another temperature, another report.
    // The report echoes its settings; hash it without the echo, so that a setting the
    // run ignored would leave the two hashes equal.
    let outcome = |settings: &RunSettings| {
        let mut v = serde_json::to_value(csql::run(settings).unwrap()).unwrap();
        assert!(v.as_object_mut().unwrap().remove("settings").is_some());
        serde_json::to_string(&v).unwrap()
    };
    let mut settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    let a = outcome(&settings);
    settings.temperature = qlearn::Temperature::new(0.3).unwrap();
    let b = outcome(&settings);
    assert_ne!(fnv1a(a.as_bytes()), fnv1a(b.as_bytes()));
}

#[test]
fn random_maps_are_pinned() {
    let pinned: [(&str, u64); 4] = [
        ("random:8x8:0.2:7", 0x656454d75d5b062f),
        ("random:16x16:0.2:1", 0xdfdff6a8a3d9afc9),
        ("random:32x24:0.35:42", 0xace29ce547160b07),
        ("random:5x3:0.9:0", 0x639c1a0f7ee2ff98),
    ];
    let mut wrong = Vec::new();
    for (spec, hash) in pinned {
        let map = mdp::resolve(spec).unwrap();
        let got = fnv1a(map.to_toml().as_bytes());
        println!("(\"{spec}\", {got:#018x}),");
        if got != hash {
            wrong.push(spec);
        }
    }
    assert!(wrong.is_empty(), "random maps changed: {wrong:?}");
}

/// Runs beyond the paper, pinned the same way: (map, strategy, seed, TOML settings, hash
/// of the full JSON report, its length); a file that chooses a baseline leaves the
/// strategy unused. Short runs (a trial cap) of every learner and
/// remedy, so that a refactor of the perceptions, the quality measure or the sensors
/// cannot change them unnoticed.
const BEYOND: &[(&str, StrategyKind, u64, &str, u64, usize)] = &[
    (
        "tan8x8",
        StrategyKind::Lazy,
        1,
        "",
        0x22124b650e4f1daa,
        49766,
    ),
    (
        "tan8x8",
        StrategyKind::Lazy,
        2,
        "beta = 0.2\nmax_trials = 300\n[world]\nslip = 0.1\n[extensions]\ndetector = \"statistical\"",
        0x5e6501b818842f56,
        64305,
    ),
    (
        "tan8x8",
        StrategyKind::Lazy,
        3,
        "beta = 0.2\nmax_trials = 200\n[world]\nsensor_noise = 0.05\n[extensions]\nmatching = \"nearest\"\nconfirm_new = 3\nreads = 5\n[judge]\nquality_every = 50",
        0x20ea7bbb365a3db9,
        61451,
    ),
    (
        "tan8x8",
        StrategyKind::Lazy,
        4,
        "max_trials = 200\n[world]\nsensing_radius = 1\n[extensions]\nmemory = 2\n[judge]\nquality_every = 50",
        0x53312e21d5cd158b,
        181084,
    ),
    (
        "tan8x8",
        StrategyKind::Lazy,
        5,
        // Judged by the policy quality until U-Tree was judged as CS-QL is, by the
        // oracle in a deterministic world; the old pin (0xd3f34186b35bca99, 61834) is
        // still what the run gives with `judge_by_quality = true` (less that setting's
        // echo), and this run is the first 178 trials of that one, where it converges.
        // Regenerated again when the baselines stopped echoing a strategy they never
        // use (0xdc4d907857ca4e76, 44827, with `"strategy":"resetting"` in the report
        // and the settings and `"random_moves":20`; nothing else changed).
        "learner = \"u-tree\"\nmax_trials = 300",
        0x92904ea775ca1070,
        44773,
    ),
    (
        "dyna9x6",
        StrategyKind::Eager,
        6,
        // Regenerated when the baselines stopped echoing a strategy (0xd353eba1db9ec5b0,
        // 68471 with it; nothing else changed).
        "learner = \"full-sensing\"\nmax_trials = 300\n[world]\nsensing_radius = 2",
        0xcfa385571e345016,
        68415,
    ),
];

#[test]
fn runs_beyond_the_paper_are_pinned() {
    let mut wrong = Vec::new();
    for &(map, strategy, seed, toml, hash, len) in BEYOND {
        let mut settings = RunSettings::tan1991(map, strategy, seed);
        settings.apply_toml(toml, "pin").unwrap();
        let report = csql::run(&settings).unwrap();
        assert_eq!(report.policy_quality, report.quality.policy_quality);
        let json = pinned_json(&report);
        let got = (fnv1a(json.as_bytes()), json.len());
        println!("    {map} {strategy:?} {seed}: {:#018x}, {}", got.0, got.1);
        if got != (hash, len) {
            wrong.push(format!("{map} {strategy:?} seed {seed} {toml:?}"));
        }
    }
    assert!(wrong.is_empty(), "results changed: {wrong:?}");
}
