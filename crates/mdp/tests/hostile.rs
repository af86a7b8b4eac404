//! Hostile input: map specs and map paths that once crashed, hung or ate memory.

use mdp::{MAX_GOAL_MOVES, MapError, Pos};

/// Open `fifo` for writing on a thread of its own and close it at once. A reader that
/// wrongly opened the FIFO (and would wait for a writer for ever) is let go with an empty
/// file, so the test fails on its message instead of hanging, without a clock; a reader
/// that refuses the FIFO unopened leaves the thread waiting, harmlessly, until the test
/// process ends.
#[cfg(unix)]
fn let_go(fifo: &std::path::Path) {
    let fifo = fifo.to_path_buf();
    std::thread::spawn(move || {
        let _ = std::fs::OpenOptions::new().write(true).open(&fifo);
    });
}

#[test]
fn a_long_chain_of_goal_moves_is_refused_not_a_stack_overflow() {
    // Once resolved by recursion: 200,000 levels overflowed the stack and aborted.
    let spec = format!("tan3x3{}", "@0:0".repeat(200_000));
    let err = mdp::resolve(&spec).unwrap_err();
    assert!(matches!(err, MapError::BadSpec { .. }), "{err:?}");
    assert!(err.to_string().contains("goal moves"), "{err}");
}

#[test]
fn goal_moves_chain_up_to_the_limit() {
    let spec = format!("tan3x3{}@2:0", "@1:1".repeat(MAX_GOAL_MOVES - 1));
    let map = mdp::resolve(&spec).unwrap();
    assert_eq!(map.goal(), Pos::new(2, 0));
    assert_eq!(map.name(), spec);
    // A chain names each step by the spec up to it, as the recursive reading did.
    let two = mdp::resolve("tan3x3@2:0@1:1").unwrap();
    assert_eq!(two.goal(), Pos::new(1, 1));
    assert!(two.description().unwrap().contains("tan3x3@2:0"), "{two:?}");
}

#[test]
fn random_maps_take_goal_moves_like_every_map() {
    let base = mdp::resolve("random:8x8:0.2:7").unwrap();
    let free = base.states()[0];
    let spec = format!("random:8x8:0.2:7@{}:{}", free.row, free.col);
    let moved = mdp::resolve(&spec).unwrap();
    assert_eq!(moved.goal(), free);
    assert_eq!(moved.name(), spec);
    let err = mdp::resolve("random:8x8:0.2:7@x:1").unwrap_err();
    assert!(err.to_string().contains("the row `x`"), "{err}");
}

#[test]
fn a_seed_beyond_u64_is_refused_clearly() {
    let err = mdp::resolve("random:8x8:0.2:18446744073709551616").unwrap_err();
    assert!(err.to_string().contains("2^64 - 1"), "{err}");
}

#[cfg(unix)]
#[test]
fn a_fifo_is_refused_without_blocking() {
    let dir = std::env::temp_dir().join(format!("mdp-fifo-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("map.toml");
    let _ = std::fs::remove_file(&fifo);
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("mkfifo is not available: skipped");
        return;
    }
    let_go(&fifo);
    let err = mdp::Map::load(&fifo).unwrap_err();
    assert!(matches!(err, MapError::NotAFile { .. }), "{err:?}");
    // Through a spec too.
    let spec = fifo.display().to_string();
    let_go(&fifo);
    let err = mdp::resolve(&spec).unwrap_err();
    assert!(err.to_string().contains("not a regular file"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[cfg(unix)]
#[test]
fn a_device_is_refused_unread() {
    // /dev/zero never ends and reports a size of 0: its metadata says nothing. (Read, it
    // would stop at the size limit with another error: no clock is needed.)
    let err = mdp::Map::load(std::path::Path::new("/dev/zero")).unwrap_err();
    assert!(matches!(err, MapError::NotAFile { .. }), "{err:?}");
}

mod generated {
    use proptest::prelude::*;

    /// Map files built from the pieces that matter to the TOML reader and the layout
    /// checker, so that most cases get past the TOML parser.
    fn mapish() -> impl Strategy<Value = String> {
        let layout = proptest::collection::vec(
            prop_oneof![
                Just("."),
                Just("#"),
                Just("G"),
                Just("\n"),
                Just(" "),
                Just("\r"),
                Just("x"),
                Just("'"),
                Just("\\"),
                Just("\u{e9}"),
            ],
            0..80,
        )
        .prop_map(|p| p.concat());
        let key = prop_oneof![
            Just("name = \"m\"\n"),
            Just("name = \"\"\n"),
            Just("description = \"d\"\n"),
            Just("colour = 1\n"),
            Just("name = 3\n"),
            Just(""),
        ];
        let quote = prop_oneof![Just("'''"), Just("\"\"\""), Just("'"), Just("\"")];
        (key, quote, layout).prop_map(|(k, q, l)| format!("{k}layout = {q}\n{l}{q}\n"))
    }

    /// Map specs from the pieces of the spec grammar.
    fn specish() -> impl Strategy<Value = String> {
        proptest::collection::vec(
            prop_oneof![
                Just("tan3x3"),
                Just("tan8x8"),
                Just("random:"),
                Just("8x8"),
                Just("0x0"),
                Just("300x2"),
                Just(":"),
                Just("0.2"),
                Just("-0.0"),
                Just("NaN"),
                Just("1e308"),
                Just("@"),
                Just("0"),
                Just("18446744073709551616"),
                Just("x"),
            ],
            0..12,
        )
        .prop_map(|p| p.concat())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn malformed_map_files_never_panic(text in mapish()) {
            if let Err(e) = mdp::Map::from_toml_str(&text, "gen.toml") {
                prop_assert!(e.to_string().contains("gen.toml"), "{e}");
            }
        }

        #[test]
        fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..200)) {
            let _ = mdp::Map::from_toml_bytes(&bytes, "bytes.toml");
        }

        #[test]
        fn malformed_specs_never_panic(spec in specish()) {
            let _ = mdp::resolve(&spec);
        }
    }
}
