//! Determinism pinned: the full JSON of one run per strategy on fixed seeds, and the
//! layouts of random maps, hashed. A dependency upgrade or a refactor that changes any
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
    let json = serde_json::to_string(&report).unwrap();
    (fnv1a(json.as_bytes()), json.len())
}

#[test]
fn one_run_per_strategy_is_pinned() {
    let pinned: [(&str, StrategyKind, u64, u64, usize); 5] = [
        (
            "tan8x8",
            StrategyKind::Resetting,
            1,
            0xad5275db2b14b213,
            239640,
        ),
        ("tan8x8", StrategyKind::Lazy, 2, 0x2e2cafa2f99b40ce, 51411),
        ("tan8x8", StrategyKind::Random, 3, 0xb23c87dc51d0e1fc, 49091),
        ("tan8x8", StrategyKind::Eager, 4, 0x5837a390410bc555, 43959),
        (
            "random:10x10:0.2:5@0:0",
            StrategyKind::Lazy,
            6,
            0xf829ad79d1d401c9,
            94904,
        ),
    ];
    let mut wrong = Vec::new();
    for (map, strategy, seed, hash, len) in pinned {
        let got = run_hash(map, strategy, seed);
        println!(
            "(\"{map}\", StrategyKind::{strategy:?}, {seed}, {:#018x}, {}),",
            got.0, got.1
        );
        if got != (hash, len) {
            wrong.push(format!("{map} {strategy:?} seed {seed}"));
        }
    }
    assert!(wrong.is_empty(), "results changed: {wrong:?}");
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
