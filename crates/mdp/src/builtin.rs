//! The built-in maps, compiled into the crate.

use crate::map::Map;

/// The built-in maps, compiled into the crate: `(name, TOML text)`.
const BUILTINS: &[(&str, &str)] = &[
    ("tan3x3", include_str!("../maps/tan3x3.toml")),
    ("tan8x8", include_str!("../maps/tan8x8.toml")),
    ("tan8x8-maze", include_str!("../maps/tan8x8-maze.toml")),
    ("dyna9x6", include_str!("../maps/dyna9x6.toml")),
    ("open8x8", include_str!("../maps/open8x8.toml")),
    ("corridors9x5", include_str!("../maps/corridors9x5.toml")),
];

/// The names of the built-in maps, in a fixed order.
///
/// ```
/// assert!(mdp::builtin_names().contains(&"tan8x8"));
/// ```
pub fn builtin_names() -> Vec<&'static str> {
    BUILTINS.iter().map(|(n, _)| *n).collect()
}

/// A built-in map by name, or `None` if there is no such map.
///
/// ```
/// let map = mdp::builtin("tan8x8").unwrap();
/// assert_eq!((map.width(), map.height(), map.states().len()), (8, 8, 50));
/// assert!(mdp::builtin("nope").is_none());
/// ```
#[cfg_attr(
    not(test),
    expect(
        clippy::expect_used,
        reason = "the built-in maps are checked by a test; a broken one is a bug of the crate, not of input"
    )
)]
pub fn builtin(name: &str) -> Option<Map> {
    BUILTINS.iter().find(|(n, _)| *n == name).map(|(n, text)| {
        Map::from_toml_str(text, &format!("built-in map {n}")).expect("built-in maps are valid")
    })
}
