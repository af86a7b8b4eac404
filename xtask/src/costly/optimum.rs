//! The optimum of each lake of the table with its model known (`mdp::optimum_bounds`):
//! `cargo xtask costly --optimum` brackets it for every world, dynamics, price and rule
//! and writes `docs/costly_optimum.csv`, which the report reads for its last column.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use mdp::{BoundOptions, SensingMenu, SensingRule, WorldOptions};

use super::{Dynamics, PRICES, RULES, WORLDS};

/// Where the bounds are kept.
pub(crate) const PATH: &str = "docs/costly_optimum.csv";

/// The search stops when the bounds are this close.
const GAP: f64 = 1e-3;

/// The most trials of the search on a lake of `states` cells: enough to close the 4x4
/// lakes to [`GAP`]; on the 8x8 slippery lake the bracket stays open (its bounds are
/// then the search's after that many trials, as `docs/costly.md` reads them).
fn max_trials(states: usize) -> usize {
    if states <= 16 { 20_000 } else { 300 }
}

/// The bounds of one lake of the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Bounds {
    pub lower: f64,
    pub upper: f64,
    /// Whether they met within the gap (else the trials ran out).
    pub converged: bool,
}

impl Bounds {
    /// As the table shows them: one figure where they meet to four places.
    pub(crate) fn text(&self) -> String {
        let (lower, upper) = (format!("{:.4}", self.lower), format!("{:.4}", self.upper));
        let open = if self.converged { "" } else { " (open)" };
        if lower == upper {
            format!("{lower}{open}")
        } else {
            format!("{lower} to {upper}{open}")
        }
    }
}

/// A lake of the table: world, dynamics, price per coordinate and rule, as the CSV
/// spells them.
pub(crate) type Key = (String, String, String, String);

pub(crate) fn key(world: &str, dynamics: Dynamics, price: f64, rule: SensingRule) -> Key {
    (
        world.to_string(),
        dynamics.name().to_string(),
        price.to_string(),
        rule.name().to_string(),
    )
}

/// Brackets the optimum of every lake of the table (the row and the column measured
/// apart, as the learners may; an episode as long as the benchmark's), printing each
/// with its time, and writes them to `path`.
pub(crate) fn write(path: &Path) -> Result<()> {
    let mut csv = String::from("world,dynamics,price,rule,lower,upper,converged,trials\n");
    for &(world, _, moves) in &WORLDS {
        for dynamics in Dynamics::ALL {
            for price in PRICES {
                for rule in RULES {
                    let started = Instant::now();
                    let b = bounds_of(world, moves, dynamics, price, rule)?;
                    let (w, d, p, r) = key(world, dynamics, price, rule);
                    println!(
                        "{w} {d} {p} {r}: {:.4} to {:.4}, {} trials, {:.1} s",
                        b.lower,
                        b.upper,
                        b.trials,
                        started.elapsed().as_secs_f64()
                    );
                    let _ = writeln!(
                        csv,
                        "{w},{d},{p},{r},{},{},{},{}",
                        b.lower, b.upper, b.converged, b.trials
                    );
                }
            }
        }
    }
    crate::files::write_atomic(path, csv)
}

/// The search's bounds of one lake of the table: `world` of `moves` moves an episode, its
/// row and column measured apart at `price` each.
fn bounds_of(
    world: &str,
    moves: u32,
    dynamics: Dynamics,
    price: f64,
    rule: SensingRule,
) -> Result<mdp::OptimumBounds> {
    let lake = mdp::builtin_world(
        world,
        &WorldOptions {
            factor_costs: Some(vec![price, price]),
            ..dynamics.options()
        },
    )?;
    let options = BoundOptions {
        horizon: moves,
        gap: GAP,
        max_trials: max_trials(mdp::World::states(&lake).len()),
        ..BoundOptions::default()
    };
    mdp::optimum_bounds(&lake, SensingMenu::Features, rule, &options)
        .with_context(|| format!("the optimum of {world}, {}", dynamics.name()))
}

/// The bounds kept at `path`; none when there is no such file.
pub(crate) fn read(path: &Path) -> Result<BTreeMap<Key, Bounds>> {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(BTreeMap::new()),
        Err(e) => return Err(e).with_context(|| format!("reading {}", path.display())),
    };
    let mut bounds = BTreeMap::new();
    for (i, line) in text.lines().enumerate().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        let bad = || format!("{} line {}: `{line}`", path.display(), i + 1);
        let [w, d, p, r, lower, upper, converged, _trials] = cells[..] else {
            bail!("{}: 8 cells expected", bad());
        };
        let number = |s: &str| s.parse::<f64>().with_context(bad);
        bounds.insert(
            (w.to_string(), d.to_string(), p.to_string(), r.to_string()),
            Bounds {
                lower: number(lower)?,
                upper: number(upper)?,
                converged: converged.parse::<bool>().with_context(bad)?,
            },
        );
    }
    Ok(bounds)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed bounds hold the lakes' known optima (the deterministic lakes' 1.0,
    /// under both rules and prices) and bracket what no policy passes on every lake; a
    /// line of the wrong shape is refused by its number.
    #[test]
    fn the_committed_bounds_hold_the_known_optima() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let bounds = read(&root.join(PATH)).unwrap();
        assert_eq!(bounds.len(), 2 * 3 * 2 * 2, "every lake of the table");
        for (k, b) in &bounds {
            assert!(b.lower <= b.upper + 1e-9, "{k:?}: {b:?}");
            if k.1 == "deterministic" {
                assert!((b.lower - 1.0).abs() < 1e-9 && b.converged, "{k:?}: {b:?}");
                assert_eq!(b.text(), "1.0000");
            }
        }
        let slippery = &bounds[&key(
            "frozenlake4x4",
            Dynamics::Slippery,
            0.025,
            SensingRule::WithMove,
        )];
        assert!(slippery.converged && slippery.upper - slippery.lower <= GAP + 1e-12);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bad.csv");
        std::fs::write(&path, "header\nfrozenlake4x4,slippery,0.025\n").unwrap();
        let err = format!("{:#}", read(&path).unwrap_err());
        assert!(err.contains("line 2"), "{err}");
        assert!(read(&dir.path().join("none.csv")).unwrap().is_empty());
    }

    /// One lake's bounds computed again are the committed ones, to the bit.
    #[test]
    fn a_lakes_bounds_computed_again_are_the_committed_ones() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let committed = read(&root.join(PATH)).unwrap();
        let (dynamics, price, rule) = (Dynamics::SemiSlippery, 0.05, SensingRule::AfterOutcome);
        let b = bounds_of("frozenlake4x4", WORLDS[0].2, dynamics, price, rule).unwrap();
        let kept = committed[&key("frozenlake4x4", dynamics, price, rule)];
        assert_eq!(
            (b.lower, b.upper, b.converged),
            (kept.lower, kept.upper, kept.converged)
        );
    }
}
