//! Map specs: one string that names a map, for command lines and configuration files.

use std::path::Path;

use crate::builtin::{builtin, builtin_names};
use crate::error::MapError;
use crate::geometry::Pos;
use crate::map::Map;
use crate::random::RandomMap;

/// A map from a spec:
///
/// | spec | map |
/// |---|---|
/// | `tan8x8` | a built-in map |
/// | `path/to/map.toml` | a map file |
/// | `random:WxH:DENSITY:SEED` | a [`RandomMap`] drawn with `Xoshiro256PlusPlus` seeded by SEED |
/// | `SPEC@ROW:COL` | the map of SPEC (any of the above) with its goal moved to (ROW, COL), which must be free |
///
/// A built-in name or an existing file wins over the other readings. Goal moves chain
/// (`tan3x3@2:0@1:1`), at most [`MAX_GOAL_MOVES`] of them. A random map's obstacle share
/// is the density before the free cells cut off from the goal are filled in, so the final
/// map can have more obstacles (`random:8x8:0.2:7` has 17, not 13): see
/// [`RandomMap::generate`].
///
/// ```
/// assert_eq!(mdp::resolve("tan3x3").unwrap().states().len(), 8);
/// assert_eq!(mdp::resolve("random:7x5:0.2:3@0:0").unwrap().goal(), mdp::Pos::new(0, 0));
/// assert_eq!(mdp::resolve("tan3x3@2:0").unwrap().goal(), mdp::Pos::new(2, 0));
/// let r = mdp::resolve("random:7x5:0.2:3").unwrap();
/// assert_eq!((r.width(), r.height()), (7, 5));
/// let err = mdp::resolve("no-such-map.toml").unwrap_err();
/// assert!(err.to_string().contains("no-such-map.toml"));
/// ```
pub fn resolve(spec: &str) -> Result<Map, MapError> {
    let bad = |reason: String| MapError::BadSpec {
        spec: spec.to_string(),
        reason,
    };
    // Peel `@ROW:COL` suffixes from the right, in a loop rather than by recursion, so that
    // a long chain is refused with a message instead of overflowing the stack.
    let mut base = spec;
    let mut moves: Vec<(usize, Pos)> = Vec::new();
    loop {
        let named = builtin_names().contains(&base) || Path::new(base).exists();
        let plain_random = base.starts_with(RANDOM_PREFIX) && !base.contains('@');
        if named || plain_random {
            break;
        }
        let Some((rest, goal)) = base.rsplit_once('@') else {
            break;
        };
        if moves.len() == MAX_GOAL_MOVES {
            return Err(bad(format!(
                "more than {MAX_GOAL_MOVES} goal moves (`@ROW:COL`) in one spec"
            )));
        }
        let (r, c) = goal
            .split_once(':')
            .ok_or_else(|| bad("expected SPEC@ROW:COL".to_string()))?;
        let to = Pos::new(
            r.parse()
                .map_err(|_| bad(format!("the row `{r}` is not a number")))?,
            c.parse()
                .map_err(|_| bad(format!("the column `{c}` is not a number")))?,
        );
        moves.push((base.len(), to));
        base = rest;
    }
    let mut map = resolve_base(base)?;
    // Innermost move first; each map is named by the spec up to its move.
    for &(end, to) in moves.iter().rev() {
        map = map.with_goal(to, &spec[..end])?;
    }
    Ok(map)
}

/// The most `@ROW:COL` goal moves one spec may chain (each one re-validates the map).
///
/// ```
/// let long = format!("tan3x3{}", "@0:0@0:1".repeat(mdp::MAX_GOAL_MOVES));
/// assert!(mdp::resolve(&long).unwrap_err().to_string().contains("goal moves"));
/// ```
pub const MAX_GOAL_MOVES: usize = 16;

const RANDOM_PREFIX: &str = "random:";

/// A spec without goal moves: a built-in name, a file or a random map.
fn resolve_base(spec: &str) -> Result<Map, MapError> {
    if let Some(map) = builtin(spec) {
        return Ok(map);
    }
    let path = Path::new(spec);
    if path.exists() {
        return Map::load(path);
    }
    let bad = |reason: &str| MapError::BadSpec {
        spec: spec.to_string(),
        reason: reason.to_string(),
    };
    if let Some(rest) = spec.strip_prefix(RANDOM_PREFIX) {
        let parts: Vec<&str> = rest.split(':').collect();
        let [size, density, seed] = parts[..] else {
            return Err(bad("expected random:WxH:DENSITY:SEED"));
        };
        let (w, h) = size
            .split_once('x')
            .ok_or_else(|| bad("the size is not WxH"))?;
        let params = RandomMap {
            width: w.parse().map_err(|_| bad("the width is not a number"))?,
            height: h.parse().map_err(|_| bad("the height is not a number"))?,
            obstacle_density: density
                .parse()
                .map_err(|_| bad("the density is not a number"))?,
        };
        let seed: u64 = seed
            .parse()
            .map_err(|_| bad("the seed is not a whole number from 0 to 2^64 - 1"))?;
        let mut rng = <rand_xoshiro::Xoshiro256PlusPlus as rand::SeedableRng>::seed_from_u64(seed);
        return params.generate(spec, &mut rng);
    }
    Err(MapError::UnknownMap {
        name: spec.to_string(),
        builtins: builtin_names().join(", "),
    })
}
