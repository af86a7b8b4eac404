//! Pinned runs: the full JSON report of a few runs on maps other than `tan8x8`, for every
//! strategy, hashed. A refactor or a speed-up of CS-QL must leave every one of these
//! bytes as it is; a change that has to change results is a setting, off by default.
//!
//! When a deliberate change of results is made, print the new hashes with
//! `CSQL_PRINT_PINS=1 cargo test -p csql --test pinned -- --nocapture` and say why in the
//! commit.

use csql::{RunSettings, StrategyKind};

/// FNV-1a, 64 bits: a stable hash that no dependency upgrade can change.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

fn pin(map: &str, strategy: StrategyKind, seed: u64) -> (u64, usize) {
    let report = csql::run(&RunSettings::tan1991(map, strategy, seed)).unwrap();
    assert!(report.converged, "{map} {strategy} {seed} did not converge");
    let json = serde_json::to_string(&report).unwrap();
    (fnv1a(json.as_bytes()), json.len())
}

/// (map, strategy, seed, hash of the JSON, its length).
const PINS: &[(&str, StrategyKind, u64, u64, usize)] = &[
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
fn pinned_runs_are_unchanged() {
    let print = std::env::var_os("CSQL_PRINT_PINS").is_some();
    let mut changed = Vec::new();
    for &(map, strategy, seed, hash, len) in PINS {
        let got = pin(map, strategy, seed);
        if print {
            println!(
                "    (\"{map}\", StrategyKind::{strategy:?}, {seed}, {:#018x}, {}),",
                got.0, got.1
            );
        }
        if got != (hash, len) {
            changed.push(format!("{map} {strategy} seed {seed}: {got:x?}"));
        }
    }
    assert!(changed.is_empty(), "runs changed:\n{}", changed.join("\n"));
}

#[test]
fn the_pin_sees_a_one_setting_change() {
    // The companion that shows the pin can fail: another temperature, another report.
    let mut settings = RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1);
    let a = serde_json::to_string(&csql::run(&settings).unwrap()).unwrap();
    settings.temperature = qlearn::Temperature::new(0.3).unwrap();
    let b = serde_json::to_string(&csql::run(&settings).unwrap()).unwrap();
    assert_ne!(fnv1a(a.as_bytes()), fnv1a(b.as_bytes()));
}
