//! `csrl world list|show|export|check`: worlds beyond grid maps, and every map as a world.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Result;
use clap::Subcommand;
use mdp::{ActionId, Feature, FiniteWorld, Oracle, Sensors, StateId, StochasticMdp, World};
use serde::Serialize;

use crate::shown;

/// The discount `show` and `check` value worlds with (the paper's).
const GAMMA: f64 = 0.9;

#[derive(Subcommand)]
pub enum WorldCommand {
    /// The built-in worlds beyond grid maps (every map of `csrl maps` is a world too).
    List {
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// A world's states, actions, features and prices, and its optimal value.
    Show {
        /// A built-in world, a world file (`.json`), or any map `--map` takes.
        world: String,
        /// Settings whose `[world]` table sets slip, slide, sensing and factor costs.
        #[arg(long)]
        config: Option<PathBuf>,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Write a world as a world file (JSON, format `csrl-world` version 1).
    Export {
        /// A built-in world, a world file, or any map `--map` takes.
        world: String,
        /// Settings whose `[world]` table sets slip, slide, sensing and factor costs.
        #[arg(long)]
        config: Option<PathBuf>,
        /// Where to write it (default: standard output).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Validate a world; with `--paper-assumptions`, also refuse a world where two
    /// states that need different actions or have different values read the same on
    /// every feature (no description could tell them apart).
    Check {
        /// A built-in world, a world file, or any map `--map` takes.
        world: String,
        /// Settings whose `[world]` table sets slip, slide, sensing and factor costs.
        #[arg(long)]
        config: Option<PathBuf>,
        /// Refuse states no feature set tells apart from a non-equivalent state.
        #[arg(long)]
        paper_assumptions: bool,
    },
}

/// The world a name, a file or a map spec names, with the `[world]` settings of
/// `config`, as a [`FiniteWorld`] (maps are exported with their local sensing).
pub(crate) fn resolve(name: &str, config: Option<&PathBuf>) -> Result<FiniteWorld> {
    Ok(resolve_with(name, config)?.0)
}

/// [`resolve`], with the `[world]` settings it was resolved with.
fn resolve_with(name: &str, config: Option<&PathBuf>) -> Result<(FiniteWorld, csql::WorldExtras)> {
    let mut settings = csql::RunSettings::tan1991(name, csql::StrategyKind::Lazy, 1);
    if let Some(path) = config {
        settings.apply_file(path)?;
        settings.map = name.into();
    }
    let world = match csql::Resolved::new(&settings)? {
        csql::Resolved::Grid(setup) => FiniteWorld::from_grid(&setup.sensed(&settings)),
        csql::Resolved::Finite { world, .. } => world,
    };
    Ok((world, settings.world))
}

pub fn run(cmd: &WorldCommand, out: &mut dyn Write) -> Result<()> {
    match cmd {
        WorldCommand::List { json } => list(*json, out),
        WorldCommand::Show {
            world,
            config,
            json,
        } => {
            let (w, extras) = resolve_with(world, config.as_ref())?;
            let summary = Summary::new(&w, RunDefaults::of(world, &extras))?;
            if *json {
                writeln!(out, "{}", serde_json::to_string_pretty(&summary)?)?;
            } else {
                summary.print(out)?;
            }
            Ok(())
        }
        WorldCommand::Export {
            world,
            config,
            out: path,
        } => {
            let w = resolve(world, config.as_ref())?;
            let text = w.to_json();
            match path {
                Some(path) => {
                    crate::write_file(path, &text)?;
                    crate::note(format_args!(
                        "wrote {} to {}",
                        shown(w.name()),
                        path.display()
                    ));
                }
                None => write!(out, "{text}")?,
            }
            Ok(())
        }
        WorldCommand::Check {
            world,
            config,
            paper_assumptions,
        } => {
            let w = resolve(world, config.as_ref())?;
            if *paper_assumptions {
                let aliased = w.aliased(GAMMA)?;
                if let Some(&(a, b)) = aliased.pairs.first() {
                    anyhow::bail!(
                        "{world}: {} pairs of states read the same on every feature but are not equivalent (gamma {GAMMA}); the first is {} and {}: no description can tell them apart, which the paper assumes it can",
                        aliased.count,
                        shown(&w.state_label(a)),
                        shown(&w.state_label(b))
                    );
                }
            }
            writeln!(
                out,
                "{world}: valid world `{}`, {} states ({} a trial may visit), {} actions, {} features{}",
                shown(w.name()),
                w.num_states(),
                w.states().len(),
                w.num_actions(),
                w.num_features(),
                if *paper_assumptions {
                    "; every pair of states that reads the same is equivalent"
                } else {
                    ""
                }
            )?;
            Ok(())
        }
    }
}

fn list(json: bool, out: &mut dyn Write) -> Result<()> {
    let mut rows = Vec::new();
    for &name in mdp::builtin_world_names() {
        let w = mdp::builtin_world(name, &mdp::WorldOptions::default())?;
        rows.push(Summary::new(
            &w,
            RunDefaults::of(name, &csql::WorldExtras::default()),
        )?);
    }
    if json {
        writeln!(out, "{}", serde_json::to_string_pretty(&rows)?)?;
        return Ok(());
    }
    for r in &rows {
        writeln!(
            out,
            "{:<14} {:>4} states {:>2} actions {:>3} features  rewards {} to {}  (runs at temperature {}, detector {}, max_trials {})",
            r.name,
            r.visited_states,
            r.actions.len(),
            r.features.len(),
            r.min_reward,
            r.max_reward,
            r.run_defaults.temperature,
            r.run_defaults.detector,
            r.run_defaults.max_trials
        )?;
    }
    writeln!(
        out,
        "\nEvery grid map (`csrl maps`) is a world too; `[world] sensing = \"factors\"` and `slip`/`slide` change a built-in world (`csrl world show NAME --config FILE`). A run takes the temperature, detector and trial cap above where its settings give none (`csrl world show NAME` says why)."
    )?;
    Ok(())
}

/// What `show` prints.
#[derive(Serialize)]
struct Summary {
    name: String,
    states: usize,
    visited_states: usize,
    terminal_states: usize,
    start_states: usize,
    actions: Vec<String>,
    deterministic: bool,
    min_reward: f64,
    max_reward: f64,
    features: Vec<FeatureSummary>,
    /// The optimal value of the start distribution at the paper's discount.
    start_value: f64,
    /// What a run in the world defaults to where its settings do not say.
    run_defaults: RunDefaults,
}

/// What a run of a learner judged over trials defaults to in a world
/// ([`csql::WorldDefaults`]): the paper's values, or a built-in world's own.
#[derive(Serialize)]
struct RunDefaults {
    temperature: f64,
    /// CS-QL's `[extensions] detector` (with beta 1; the paper's with another beta).
    detector: &'static str,
    max_trials: u32,
    /// Sensing by belief's `[belief] shared_moves` and `blind_plans` where the world, as
    /// sensed with these `[world]` settings, asks for them (absent otherwise: each pair
    /// learned apart, no open-loop plans).
    #[serde(skip_serializing_if = "Option::is_none")]
    belief_shared_moves: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    belief_blind_plans: Option<usize>,
    /// `world` (the built-in world's own) or `paper`.
    from: &'static str,
    /// Why the world asks for them (absent for the paper's).
    #[serde(skip_serializing_if = "Option::is_none")]
    why: Option<&'static str>,
}

impl RunDefaults {
    /// The defaults of the world `name` names, with the `[world]` settings `extras`.
    fn of(name: &str, extras: &csql::WorldExtras) -> RunDefaults {
        let d = csql::WorldDefaults::of(name);
        let own = d.world.filter(|w| !w.is_paper());
        // Any move cap the open-loop plans hold (a run's larger cap turns them off).
        let belief = d.belief_for(csql::BeliefParams::default(), extras, 1);
        RunDefaults {
            belief_shared_moves: belief.shared_moves,
            belief_blind_plans: belief.blind_plans,
            temperature: d.temperature.get(),
            detector: d.detector_for(1.0, extras).name(),
            max_trials: d.max_trials.get(),
            from: if own.is_some() { "world" } else { "paper" },
            why: own.map(|w| w.why),
        }
    }
}

#[derive(Serialize)]
struct FeatureSummary {
    name: String,
    price: f64,
    readings: u32,
}

impl Summary {
    fn new(w: &FiniteWorld, run_defaults: RunDefaults) -> Result<Summary> {
        let oracle = Oracle::solve_stochastic(w, GAMMA)?;
        let mut out = Vec::new();
        let (mut lo, mut hi, mut deterministic) = (f64::INFINITY, f64::NEG_INFINITY, true);
        for s in w.states() {
            for a in (0..w.num_actions() as u32).map(ActionId) {
                w.outcomes(s, a, &mut out);
                deterministic &= out.len() == 1;
                for (_, step) in &out {
                    lo = lo.min(step.reward);
                    hi = hi.max(step.reward);
                }
            }
        }
        let start = w.start_distribution();
        Ok(Summary {
            name: w.name().to_string(),
            states: w.num_states(),
            visited_states: w.states().len(),
            terminal_states: (0..w.num_states() as u32)
                .filter(|&s| w.is_terminal(StateId(s)))
                .count(),
            start_states: start.len(),
            actions: (0..w.num_actions() as u32)
                .map(|a| w.action_name(ActionId(a)))
                .collect(),
            deterministic,
            min_reward: if lo.is_finite() { lo } else { 0.0 },
            max_reward: if hi.is_finite() { hi } else { 0.0 },
            features: (0..w.num_features() as u32)
                .map(Feature)
                .map(|f| FeatureSummary {
                    name: w.feature_name(f),
                    price: w.price(f),
                    readings: w.readings(f),
                })
                .collect(),
            start_value: start.iter().map(|&(p, s)| p * oracle.v_star(s)).sum(),
            run_defaults,
        })
    }

    fn print(&self, out: &mut dyn Write) -> Result<()> {
        writeln!(out, "{}", shown(&self.name))?;
        writeln!(
            out,
            "states      {} ({} a trial may visit, {} terminal, {} where trials start)",
            self.states, self.visited_states, self.terminal_states, self.start_states
        )?;
        let actions: Vec<_> = self.actions.iter().map(|a| shown(a)).collect();
        writeln!(out, "actions     {}", actions.join(", "))?;
        writeln!(
            out,
            "dynamics    {}",
            if self.deterministic {
                "deterministic"
            } else {
                "stochastic"
            }
        )?;
        writeln!(
            out,
            "rewards     {} to {}",
            self.min_reward, self.max_reward
        )?;
        writeln!(
            out,
            "value       {:.4} from the start (optimal, gamma {GAMMA})",
            self.start_value
        )?;
        let total: f64 = self.features.iter().map(|f| f.price).sum();
        writeln!(
            out,
            "features    {} (sensing all of them costs {total})",
            self.features.len()
        )?;
        const SHOWN: usize = 12;
        for f in self.features.iter().take(SHOWN) {
            writeln!(
                out,
                "  {:<12} price {:<6} {} readings",
                shown(&f.name),
                f.price,
                f.readings
            )?;
        }
        if self.features.len() > SHOWN {
            writeln!(
                out,
                "  ... and {} more (--json lists them all)",
                self.features.len() - SHOWN
            )?;
        }
        let d = &self.run_defaults;
        writeln!(
            out,
            "defaults    temperature = {}, [extensions] detector = \"{}\", max_trials = {} ({}; \
             a setting given in a file, by a flag or from Python wins)",
            d.temperature,
            d.detector,
            d.max_trials,
            match d.from {
                "world" => "the world's own defaults",
                _ => "the paper's defaults",
            }
        )?;
        if let (Some(shared), Some(blind)) = (d.belief_shared_moves, d.belief_blind_plans) {
            writeln!(
                out,
                "            sensing by belief: [belief] shared_moves = {shared}, blind_plans = {blind}"
            )?;
        }
        if let Some(why) = d.why {
            writeln!(out, "            because {why}")?;
        }
        Ok(())
    }
}
