//! Map parsing and validation: every bad-map case has its own clear message with a position.

use mdp::{MapError, Position, builtin, builtin_names};

fn parse(text: &str) -> Result<mdp::Map, MapError> {
    mdp::Map::from_toml_str(text, "test.toml")
}

fn file(layout: &str) -> String {
    format!("name = \"t\"\nlayout = '''\n{layout}'''\n")
}

fn at(line: usize, column: usize) -> Position {
    Position { line, column }
}

#[test]
fn a_good_file_parses_with_its_fields() {
    let map =
        parse("name = \"t\"\ndescription = \"d\"\nlayout = '''\n  ..G\n  .#.\n'''\n").unwrap();
    assert_eq!(map.name(), "t");
    assert_eq!(map.description(), Some("d"));
    assert_eq!(
        (
            map.width(),
            map.height(),
            map.states().len(),
            map.obstacles()
        ),
        (3, 2, 4, 1)
    );
}

#[test]
fn ragged_row_names_line_and_column() {
    let err = parse(&file("..G\n..\n")).unwrap_err();
    assert!(
        matches!(err, MapError::RaggedRow { at: p, row: 1, expected: 3, found: 2, .. } if p == at(4, 3)),
        "{err:?}"
    );
    assert!(
        err.to_string().contains("test.toml at line 4, column 3"),
        "{err}"
    );
}

#[test]
fn unknown_character_names_line_and_column() {
    let err = parse(&file("..G\n.x.\n")).unwrap_err();
    assert!(
        matches!(err, MapError::UnknownChar { at: p, found: 'x', .. } if p == at(4, 2)),
        "{err:?}"
    );
    assert!(err.to_string().contains("'x'"), "{err}");
}

#[test]
fn no_goal_is_refused() {
    let err = parse(&file("...\n")).unwrap_err();
    assert!(matches!(err, MapError::NoGoal { .. }), "{err:?}");
    assert!(err.to_string().contains("no goal"), "{err}");
}

#[test]
fn second_goal_names_both_positions() {
    let err = parse(&file("G..\n..G\n")).unwrap_err();
    assert!(
        matches!(err, MapError::SecondGoal { at: p, first: f, .. } if p == at(4, 3) && f == at(3, 1)),
        "{err:?}"
    );
}

#[test]
fn unreachable_cell_is_named() {
    let err = parse(&file(".#G\n##.\n")).unwrap_err();
    assert!(
        matches!(err, MapError::Unreachable { at: p, cell, .. } if p == at(3, 1) && cell == mdp::Pos::new(0, 0)),
        "{err:?}"
    );
}

#[test]
fn empty_layout_is_refused() {
    let err = parse(&file("\n   \n")).unwrap_err();
    assert!(matches!(err, MapError::EmptyLayout { .. }), "{err:?}");
}

#[test]
fn goal_only_is_refused() {
    let err = parse(&file("G\n")).unwrap_err();
    assert!(matches!(err, MapError::NoStates { .. }), "{err:?}");
}

#[test]
fn unknown_key_is_refused_by_name() {
    let err = parse("name = \"t\"\nsize = 3\nlayout = 'G.'\n").unwrap_err();
    assert!(
        matches!(err, MapError::Toml { at: Some(p), .. } if p.line == 2),
        "{err:?}"
    );
    assert!(err.to_string().contains("size"), "{err}");
}

#[test]
fn missing_layout_is_refused_by_name() {
    let err = parse("name = \"t\"\n").unwrap_err();
    assert!(err.to_string().contains("layout"), "{err}");
}

#[test]
fn malformed_toml_has_a_position() {
    let err = parse("name = \"t\nlayout = 'G.'\n").unwrap_err();
    assert!(matches!(err, MapError::Toml { at: Some(_), .. }), "{err:?}");
}

#[test]
fn blank_name_is_refused() {
    let err = parse("name = \"  \"\nlayout = 'G.'\n").unwrap_err();
    assert!(matches!(err, MapError::EmptyName { .. }), "{err:?}");
}

#[test]
fn not_utf8_is_refused_with_position() {
    let err = mdp::Map::from_toml_bytes(b"name = \"t\"\n\xff", "bin.toml").unwrap_err();
    assert!(
        matches!(err, MapError::NotUtf8 { at: p, .. } if p == at(2, 1)),
        "{err:?}"
    );
}

#[test]
fn too_large_layout_is_refused_before_building() {
    let row = ".".repeat(mdp::MAX_SIDE + 1);
    let err = parse(&file(&format!("G{row}\n"))).unwrap_err();
    assert!(
        matches!(err, MapError::TooLarge { max, .. } if max == mdp::MAX_SIDE),
        "{err:?}"
    );
    let tall = "G\n".to_string() + &".\n".repeat(mdp::MAX_SIDE);
    assert!(matches!(
        parse(&file(&tall)),
        Err(MapError::TooLarge { .. })
    ));
}

#[test]
fn too_large_file_is_refused_unread() {
    let bytes = vec![b' '; mdp::MAX_FILE_BYTES as usize + 1];
    let err = mdp::Map::from_toml_bytes(&bytes, "big.toml").unwrap_err();
    assert!(matches!(err, MapError::FileTooLarge { .. }), "{err:?}");
}

#[test]
fn escaped_layouts_report_layout_positions() {
    let err = parse("name = \"t\"\nlayout = \"..G\\n.?.\"\n").unwrap_err();
    assert!(
        matches!(err, MapError::UnknownChar { at: p, .. } if p == at(2, 2)),
        "{err:?}"
    );
}

#[test]
fn load_names_the_file() {
    let dir = std::env::temp_dir().join(format!("mdp-maps-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("ragged.toml");
    std::fs::write(&path, file("..G\n.\n")).unwrap();
    let err = mdp::Map::load(&path).unwrap_err();
    assert!(err.to_string().contains("ragged.toml"), "{err}");
    let err = mdp::Map::load(&dir).unwrap_err();
    assert!(matches!(err, MapError::NotAFile { .. }), "{err:?}");
    let err = mdp::resolve("surely/not/here.toml").unwrap_err();
    assert!(matches!(err, MapError::UnknownMap { .. }), "{err:?}");
}

#[test]
fn builtins_are_valid_and_as_specified() {
    for name in builtin_names() {
        let map = builtin(name).unwrap();
        assert_eq!(map.name(), name);
        let back = mdp::Map::from_toml_str(&map.to_toml(), "round trip").unwrap();
        assert_eq!(back, map);
    }
    let tan8 = builtin("tan8x8").unwrap();
    assert_eq!(
        (
            tan8.width(),
            tan8.height(),
            tan8.obstacles(),
            tan8.states().len()
        ),
        (8, 8, 13, 50)
    );
    let tan3 = builtin("tan3x3").unwrap();
    assert_eq!((tan3.obstacles(), tan3.states().len()), (0, 8));
}

mod never_panics {
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        #[test]
        fn on_arbitrary_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..200)) {
            let _ = mdp::Map::from_toml_bytes(&bytes, "fuzz");
        }

        #[test]
        fn on_arbitrary_layouts(layout in "[.#G\n x]{0,60}") {
            let text = format!("name = \"f\"\nlayout = '''\n{layout}'''\n");
            if let Ok(map) = mdp::Map::from_toml_str(&text, "fuzz") {
                prop_assert_eq!(map.cells().filter(|(_, c)| *c == mdp::Cell::Goal).count(), 1);
                prop_assert!(!map.states().is_empty());
            }
        }
    }
}

#[test]
fn map_specs_resolve_and_bad_ones_say_why() {
    let moved = mdp::resolve("tan3x3@2:0").unwrap();
    assert_eq!(
        (moved.goal(), moved.states().len(), moved.name()),
        (mdp::Pos::new(2, 0), 8, "tan3x3@2:0")
    );
    let r = mdp::resolve("random:9x4:0.3:11").unwrap();
    assert_eq!(r, mdp::resolve("random:9x4:0.3:11").unwrap());
    assert_ne!(r, mdp::resolve("random:9x4:0.3:12").unwrap());
    for (spec, says) in [
        ("tan8x8-maze@0:5", "not a free cell"),
        ("tan8x8@9:0", "not a free cell"),
        ("tan8x8@1", "ROW:COL"),
        ("tan8x8@a:1", "row"),
        ("random:7x5:0.2", "random:WxH"),
        ("random:75:0.2:1", "WxH"),
        ("random:7x5:1.5:1", "obstacle_density"),
        ("random:0x5:0.2:1", "width"),
        ("nowhere@1:1", "nowhere"),
    ] {
        let err = mdp::resolve(spec).unwrap_err();
        assert!(err.to_string().contains(says), "{spec}: {err}");
    }
}
