//! Run settings under hostile input: malformed TOML never panics, and what is not a
//! regular file is refused unread.

use csql::{RunSettings, StrategyKind};
use proptest::prelude::*;

fn settings() -> RunSettings {
    RunSettings::tan1991("tan3x3", StrategyKind::Lazy, 1)
}

#[cfg(unix)]
#[test]
fn a_device_is_refused_unread() {
    // /dev/zero reports a size of 0 and never ends.
    let err = settings()
        .apply_file(std::path::Path::new("/dev/zero"))
        .unwrap_err();
    assert!(err.to_string().contains("not a regular file"), "{err}");
}

fn settingsish() -> impl Strategy<Value = String> {
    let key = prop_oneof![
        Just("beta"),
        Just("gamma"),
        Just("temperature"),
        Just("max_moves"),
        Just("random_moves"),
        Just("tolerance"),
        Just("decrease_threshold"),
        Just("max_trials"),
        Just("seed"),
        Just("map"),
        Just("strategy"),
        Just("colour"),
    ];
    let value = prop_oneof![
        Just("0"),
        Just("1"),
        Just("-1"),
        Just("0.5"),
        Just("1e400"),
        Just("nan"),
        Just("inf"),
        Just("18446744073709551616"),
        Just("\"lazy\""),
        Just("\"tan3x3@0:0\""),
        Just("\"random:0x0:2:1\""),
        Just("[1]"),
        Just("'"),
    ];
    proptest::collection::vec((key, value), 0..6).prop_map(|kv| {
        kv.iter()
            .map(|(k, v)| format!("{k} = {v}\n"))
            .collect::<String>()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn malformed_settings_never_panic(text in settingsish()) {
        let mut s = settings();
        if s.apply_toml(&text, "gen.toml").is_ok() {
            // Whatever was accepted holds valid values (the types guarantee it), and
            // loading its map never panics either.
            prop_assert!(s.tolerance.get() >= 0.0 && s.max_trials.get() >= 1);
            let _ = csql::Setup::new(&s);
        }
    }
}
