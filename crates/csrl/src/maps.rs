//! `csrl maps`, `csrl map show` and `csrl map check`.

use std::io::Write;

use anyhow::Result;
use clap::Subcommand;
use mdp::{GridWorld, Map, Oracle, Pos};
use serde::Serialize;

/// The `map` subcommands.
#[derive(Subcommand)]
pub enum MapCommand {
    /// Print a map (a built-in name, a file path, `random:WxH:DENSITY:SEED` or
    /// `MAP@ROW:COL`) with its figures.
    Show {
        /// A built-in map name (see `csrl maps`), a path to a map file, or a spec.
        map: String,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Validate a map (a file, a built-in name or a spec, as for `show`): print a line on
    /// stdout and exit 0 if it is valid, otherwise print why on stderr and exit 1.
    Check {
        /// A map file, a built-in map name, or a spec.
        map: String,
    },
}

/// `csrl maps`.
pub fn list(json: bool, out: &mut dyn Write) -> Result<()> {
    let mut all = Vec::new();
    for name in mdp::builtin_names() {
        let map = mdp::resolve(name)?;
        if json {
            all.push(serde_json::json!({
                "name": name,
                "width": map.width(),
                "height": map.height(),
                "states": map.states().len(),
                "obstacles": map.obstacles(),
                "description": map.description(),
            }));
            continue;
        }
        let first = map
            .description()
            .and_then(|d| d.split(". ").next())
            .unwrap_or("")
            .trim_end_matches('.');
        writeln!(
            out,
            "{name:<14} {:>2}x{:<2} {:>3} states  {first}",
            map.width(),
            map.height(),
            map.states().len()
        )?;
    }
    if json {
        writeln!(out, "{}", serde_json::to_string_pretty(&all)?)?;
    }
    Ok(())
}

/// `csrl map ...`.
pub fn run(cmd: &MapCommand, out: &mut dyn Write) -> Result<()> {
    match cmd {
        MapCommand::Show { map, json } => {
            let map = mdp::resolve(map)?;
            if *json {
                writeln!(
                    out,
                    "{}",
                    serde_json::to_string_pretty(&MapJson::new(&map)?)?
                )?;
            } else {
                show(&map, out)?;
            }
            Ok(())
        }
        MapCommand::Check { map: spec } => {
            let map = mdp::resolve(spec)?;
            writeln!(
                out,
                "{spec}: valid map `{}`, {}x{}, {} states",
                map.name(),
                map.width(),
                map.height(),
                map.states().len()
            )?;
            Ok(())
        }
    }
}

fn show(map: &Map, out: &mut dyn Write) -> Result<()> {
    let world = GridWorld::new(map);
    let oracle = Oracle::for_grid(&world, 0.9)?;
    writeln!(out, "{}", map.name())?;
    if let Some(d) = map.description() {
        writeln!(out, "{d}")?;
    }
    writeln!(out)?;
    write!(out, "{}", mdp::render_text(map, &mdp::Overlay::default()))?;
    let distances: Vec<u32> = world
        .states()
        .iter()
        .filter_map(|&s| oracle.distance(s))
        .collect();
    let longest = distances.iter().max().copied().unwrap_or(0);
    let mean = distances.iter().sum::<u32>() as f64 / distances.len().max(1) as f64;
    writeln!(out)?;
    writeln!(out, "size        {} x {}", map.width(), map.height())?;
    writeln!(out, "obstacles   {}", map.obstacles())?;
    writeln!(
        out,
        "states      {} (free cells other than the goal)",
        map.states().len()
    )?;
    writeln!(
        out,
        "goal        row {}, col {}",
        map.goal().row,
        map.goal().col
    )?;
    writeln!(
        out,
        "distance    mean {mean:.2}, longest {longest} moves to the goal"
    )?;
    writeln!(out)?;
    writeln!(out, "Moves to the goal:")?;
    for r in 0..map.height() {
        let line: Vec<String> = (0..map.width())
            .map(|c| match world.state_at(Pos::new(r, c)) {
                Some(s) => oracle
                    .distance(s)
                    .map_or_else(|| "  ?".to_string(), |d| format!("{d:>3}")),
                None => "  #".to_string(),
            })
            .collect();
        writeln!(out, "{}", line.join(""))?;
    }
    Ok(())
}

#[derive(Serialize)]
struct RowCol {
    row: usize,
    col: usize,
}

#[derive(Serialize)]
struct CellJson {
    row: usize,
    col: usize,
    kind: &'static str,
    distance: Option<u32>,
}

#[derive(Serialize)]
struct MapJson {
    name: String,
    description: Option<String>,
    width: usize,
    height: usize,
    states: usize,
    obstacles: usize,
    goal: RowCol,
    layout: Vec<String>,
    cells: Vec<CellJson>,
}

impl MapJson {
    fn new(map: &Map) -> Result<MapJson> {
        let world = GridWorld::new(map);
        let oracle = Oracle::for_grid(&world, 0.9)?;
        Ok(MapJson {
            name: map.name().to_string(),
            description: map.description().map(str::to_string),
            width: map.width(),
            height: map.height(),
            states: map.states().len(),
            obstacles: map.obstacles(),
            goal: RowCol {
                row: map.goal().row,
                col: map.goal().col,
            },
            layout: map.layout().lines().map(str::to_string).collect(),
            cells: map
                .cells()
                .map(|(p, c)| CellJson {
                    row: p.row,
                    col: p.col,
                    kind: c.name(),
                    distance: world.state_at(p).and_then(|s| oracle.distance(s)),
                })
                .collect(),
        })
    }
}
