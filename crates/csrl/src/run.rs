//! `csrl run`: one CS-QL run.

use std::io::Write;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::Result;
use clap::Args;
use csql::{Flow, Observer, RunReport, RunSettings, SettingsDraft, StrategyKind, TracePoint};

use crate::{Status, shown, shown_lines};

/// Arguments of `csrl run`.
#[derive(Args)]
pub struct RunArgs {
    /// A map: a built-in name, a map file, `random:WxH:DENSITY:SEED`, or `MAP@ROW:COL`
    /// for MAP with its goal moved (default: the config's map, else tan8x8).
    #[arg(long, conflicts_with = "world")]
    map: Option<String>,
    /// The world: a built-in world (`csrl world list`), a world file (`.json`) or any
    /// map `--map` takes.
    #[arg(long)]
    world: Option<String>,
    /// resetting, lazy, random or eager (default: the config's, else resetting).
    #[arg(long)]
    strategy: Option<StrategyKind>,
    /// The seed of the run (default: the config's, else 1).
    #[arg(long)]
    seed: Option<u64>,
    /// A TOML file of settings that override the paper's; flags given here override the
    /// file (`--help` lists the keys, and the learners that read each).
    #[arg(long, long_help = config_help())]
    config: Option<PathBuf>,
    /// off, learned, motion or weighed: predict the next description instead of sensing
    /// it (default: the config's `predict_sensing`, else off; the `[prediction]` table of
    /// the config tunes it). weighed weighs acting on the likely descriptions against sensing at
    /// `--price` and needs it.
    #[arg(long)]
    predict_sensing: Option<csql::PredictSensing>,
    /// cs-ql (the default), u-tree, full-sensing, amrl-q or belief: the learner (default:
    /// the config's `learner`, else cs-ql). The first three are judged the same way: by
    /// the oracle's convergence in a deterministic world in the paper's setting, else by
    /// the policy quality; every report also gives the cost and trials until quality
    /// 0.95. amrl-q (AMRL-Q, its published parameters by default, tuned by the config's
    /// `[amrl_q]`) and belief (sensing by belief: a learned model and a plan over
    /// beliefs, tuned by the config's `[belief]`) play exactly `--episodes` episodes and
    /// need `--price`; their report is the costed return of every episode and their
    /// summary.
    #[arg(long)]
    learner: Option<csql::LearnerKind>,
    /// Price sensing in reward units: a feature of cost c costs c times PRICE (the
    /// config's `[costly] price`). The report then also scores every trial by its costed
    /// return (reward less the prices of what was sensed) and sums them up (cs-ql,
    /// full-sensing, amrl-q, belief).
    #[arg(long, value_name = "PRICE")]
    price: Option<f64>,
    /// with-move (the published rule: sensing decided with the move, paid even when the
    /// move ends the episode) or after-outcome: when priced sensing is charged (the
    /// config's `[costly] rule`, else with-move).
    #[arg(long, value_parser = parse_rule)]
    sensing_rule: Option<mdp::SensingRule>,
    /// Stop an unconverged run after this many trials (cs-ql, u-tree, full-sensing;
    /// default: the config's, else 20000, or a built-in world's own: `csrl world show
    /// NAME`).
    #[arg(long)]
    max_trials: Option<csql::TrialCap>,
    /// The number of episodes amrl-q and belief play (the config's `episodes`, else
    /// 20000).
    #[arg(long)]
    episodes: Option<csql::TrialCap>,
    /// Exit with code 3 if the run does not converge, or, for a run judged by the policy
    /// quality, if the quality did not reach 0.95 and stay there (by default a run that
    /// reaches its trial cap is a result like any other and exits 0).
    #[arg(long)]
    require_convergence: bool,
    /// Keep the per-trial learning curve and print it as the JSON's `trace` (one point
    /// per trial, so memory grows with the run; without this flag `trace` is empty).
    #[arg(long)]
    trace: bool,
    /// Print one JSON object instead of tables.
    #[arg(long)]
    json: bool,
    /// Also draw the map with the learned policy and descriptions to this SVG file.
    #[arg(long)]
    svg: Option<PathBuf>,
}

impl RunArgs {
    fn settings(&self) -> Result<RunSettings> {
        // The file's settings, then the flags over them, checked together once all are
        // in (a `--learner u-tree` gives a file's `[u_tree]` its meaning).
        let mut draft = match &self.config {
            Some(path) => SettingsDraft::from_file(path)?,
            None => SettingsDraft::default(),
        };
        draft.overlay(SettingsDraft {
            map: self.map.as_ref().or(self.world.as_ref()).map(Into::into),
            strategy: self.strategy,
            seed: self.seed,
            max_trials: self.max_trials,
            episodes: self.episodes,
            predict_sensing: self.predict_sensing,
            learner: self.learner,
            ..SettingsDraft::default()
        });
        if self.price.is_some() || self.sensing_rule.is_some() {
            let table = draft.costly.get_or_insert_default();
            table.price = self.price.or(table.price);
            table.rule = self.sensing_rule.or(table.rule);
        }
        Ok(draft.build()?)
    }
}

/// The long help of `--config`: the keys of a settings file, from the one table of them
/// ([`csql::SETTING_KEYS`]).
fn config_help() -> String {
    format!(
        "A TOML file of settings that override the paper's; flags given here override the file. \
         A key the learner does not read is refused (with its learners in parentheses where \
         not every learner reads it), and so is a table of another learner:\n{}",
        csql::settings_keys_help()
    )
}

/// `--sensing-rule`.
fn parse_rule(s: &str) -> Result<mdp::SensingRule, String> {
    [mdp::SensingRule::WithMove, mdp::SensingRule::AfterOutcome]
        .into_iter()
        .find(|r| r.name() == s)
        .ok_or_else(|| format!("{s:?}: expected with-move or after-outcome"))
}

/// Shows progress on a terminal (nothing otherwise), keeps the trace only when asked,
/// and stops the run when Ctrl-C was pressed (or SIGTERM received), in learning or in
/// the navigation after it.
struct Watch {
    bar: indicatif::ProgressBar,
    keep_trace: bool,
    stop: Arc<AtomicBool>,
    stopped: bool,
    /// Whether the ready line is still to be written ([`READY_VARIABLE`] set, and not
    /// written yet).
    ready: bool,
    /// Write it at the first question to stop, not after the first trial: a learner
    /// played on episodes is asked before every episode and calls no trial.
    ready_at_first_check: bool,
}

/// The environment variable that asks `csrl run` for its ready line: set (to anything),
/// the program writes [`READY_LINE`] to stderr once the run is under way with its stop
/// handler installed (after the first trial of learning; before the first episode of a
/// learner played on episodes), so that a script or a test can send Ctrl-C or SIGTERM
/// knowing it will be honoured, without waiting a fixed time.
pub(crate) const READY_VARIABLE: &str = "CSRL_READY_LINE";

/// The ready line (see [`READY_VARIABLE`]).
pub(crate) const READY_LINE: &str = "csrl: under way (Ctrl-C or SIGTERM stops with the report)";

impl Watch {
    fn new(bar: indicatif::ProgressBar, keep_trace: bool, ready_at_first_check: bool) -> Watch {
        Watch {
            bar,
            keep_trace,
            stop: ctrl_c_flag(),
            stopped: false,
            ready: std::env::var_os(READY_VARIABLE).is_some(),
            ready_at_first_check,
        }
    }

    fn announce(&mut self) {
        if self.ready {
            self.ready = false;
            crate::note(format_args!("{READY_LINE}"));
        }
    }
}

impl Observer for Watch {
    fn keep_trace(&self) -> bool {
        self.keep_trace
    }

    fn trial(&mut self, point: &TracePoint) -> Flow {
        self.announce();
        self.bar.set_position(u64::from(point.trial));
        if point.trial.is_multiple_of(16) {
            self.bar.set_message(format!(
                "{} descriptions, sensing cost {:.0}",
                point.descriptions, point.cumulative_cost
            ));
        }
        if self.keep_going() {
            Flow::Continue
        } else {
            Flow::Stop
        }
    }

    fn keep_going(&mut self) -> bool {
        if self.ready_at_first_check {
            self.announce();
        }
        if self.stop.load(Ordering::Relaxed) {
            self.stopped = true;
        }
        !self.stopped
    }
}

/// A flag that Ctrl-C (SIGINT) and SIGTERM set (the `ctrlc` crate's `termination`
/// feature), so that both stop the run with its report. If a handler cannot be installed
/// (one already is, in tests for instance), the signals keep their default effect.
fn ctrl_c_flag() -> Arc<AtomicBool> {
    let flag = Arc::new(AtomicBool::new(false));
    let set = Arc::clone(&flag);
    let _ = ctrlc::set_handler(move || set.store(true, Ordering::Relaxed));
    flag
}

fn progress_bar(len: u32) -> indicatif::ProgressBar {
    // Drawn on standard error only when it is a terminal; hidden otherwise.
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(u64::from(len)),
        indicatif::ProgressDrawTarget::stderr(),
    );
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "trial {pos}/{len} {wide_bar} {elapsed_precise} {msg} (Ctrl-C stops with a summary)",
    ) {
        bar.set_style(style);
    }
    bar
}

/// Run `csrl run`.
pub fn run(args: &RunArgs, out: &mut dyn Write) -> Result<()> {
    let settings = args.settings()?;
    let resolved = csql::Resolved::new(&settings)?;
    let on_episodes = settings.learner.kind().on_episodes();
    if on_episodes {
        for (given, flag) in [
            (args.svg.is_some(), "--svg"),
            (args.require_convergence, "--require-convergence"),
            (args.trace, "--trace"),
        ] {
            if given {
                return Err(csql::Error::Conflict {
                    first: flag.to_string(),
                    second: format!("learner = {}", settings.learner.kind()),
                    why: "the learner plays a fixed number of episodes, scored by the costed return: no policy to draw, nothing to converge, its every episode already in the report",
                }
                .into());
            }
        }
    } else if args.svg.is_some() && !matches!(resolved, csql::Resolved::Grid(_)) {
        return Err(csql::Error::GridOnly {
            what: "--svg (the policy drawn on a grid map)",
        }
        .into());
    }
    let mut watch = if on_episodes {
        Watch::new(indicatif::ProgressBar::hidden(), false, true)
    } else {
        Watch::new(progress_bar(settings.max_trials.get()), args.trace, false)
    };
    let report = csql::run_resolved(&resolved, &settings, &mut watch)?;
    watch.bar.finish_and_clear();
    // The JSON is the one report the run made, whichever its kind.
    let json = |out: &mut dyn Write| -> Result<()> {
        Ok(writeln!(out, "{}", serde_json::to_string(&report)?)?)
    };
    match &report {
        csql::Report::Episodes(report) => {
            if args.json {
                json(out)?;
            } else {
                print_episodes(report, out)?;
            }
            if watch.stopped {
                return Err(Status::interrupted(report.costly.summary.episodes as u64).into());
            }
            Ok(())
        }
        csql::Report::Trials(report) => {
            let map = match &resolved {
                csql::Resolved::Grid(setup) => Some(setup),
                csql::Resolved::Finite { .. } => None,
            };
            if let (Some(path), Some(setup)) = (&args.svg, map) {
                crate::write_file(path, csql::policy_svg(setup, report))?;
                crate::note(format_args!(
                    "wrote the policy picture to {}",
                    path.display()
                ));
                // The picture's legend points to "the table beside this figure".
                let table = path.with_extension("md");
                crate::write_file(&table, csql::descriptions_table(report))?;
                crate::note(format_args!(
                    "wrote the descriptions table beside it to {}",
                    table.display()
                ));
            }
            if args.json {
                json(out)?;
            } else {
                print_report(report, out)?;
                writeln!(out)?;
                print_policy(report, map.map(|s| &s.map), out)?;
                writeln!(out)?;
                write!(out, "{}", shown_lines(&csql::descriptions_table(report)))?;
            }
            if watch.stopped {
                return Err(Status::interrupted(u64::from(report.trials)).into());
            }
            // Beyond the paper, "converged" is the policy quality reached and kept
            // (specification §6.3).
            let settled = match report.judged_by {
                csql::Judging::Quality => report.quality.trials_to_quality.is_some(),
                csql::Judging::Oracle => report.converged,
            };
            if args.require_convergence && !settled {
                return Err(Status::not_converged(report.trials).into());
            }
            Ok(())
        }
    }
}

/// The report of AMRL-Q or sensing by belief: what was played, and the costed return.
fn print_episodes(report: &csql::CostedReport, out: &mut dyn Write) -> std::io::Result<()> {
    let (map, seed, n) = (
        shown(&report.map),
        report.seed,
        report.costly.summary.episodes,
    );
    match &report.settings.learner {
        csql::LearnerSettings::Belief(p) => writeln!(
            out,
            "Sensing by belief on {map}, seed {seed}: {n} episodes, each feature measured at its cost times {} reward units (the whole state at {}{})",
            report.costly.price,
            report.whole_state_price,
            if p.whole_state {
                ", measured whole"
            } else {
                ""
            }
        )?,
        _ => writeln!(
            out,
            "AMRL-Q on {map}, seed {seed}: {n} episodes, the whole state measured at {} reward units",
            report.whole_state_price
        )?,
    }
    print_costly(&report.costly, out)
}

/// The costed return's summary, in two lines.
fn print_costly(c: &csql::CostedRun, out: &mut dyn Write) -> std::io::Result<()> {
    let s = &c.summary;
    writeln!(
        out,
        "Costed return (sensing at {} reward units per unit of cost, {}): {:.3} a trial over all {} trials, {:.3} over the last 10%",
        c.price,
        c.rule.name(),
        s.mean_all,
        s.episodes,
        s.mean_last10
    )?;
    writeln!(
        out,
        "Per trial: {:.2} sensing acts, {:.2} moves; {:.1}% reached the goal",
        s.sensing_per_episode,
        s.steps_per_episode,
        100.0 * s.success
    )
}

/// The learned policy: on a grid map, the greedy action of each state's description as an
/// arrow on the map; in any other world, a table of state -> greedy action and
/// description.
fn print_policy(r: &RunReport, map: Option<&mdp::Map>, out: &mut dyn Write) -> std::io::Result<()> {
    if let Some(map) = map {
        let mut overlay = mdp::Overlay::default();
        for st in &r.states {
            let action = st
                .greedy_action
                .as_deref()
                .and_then(|name| mdp::Action::ALL.into_iter().find(|a| a.name() == name));
            if let (Some(row), Some(col), Some(action)) = (st.row, st.col, action) {
                overlay.arrow(mdp::Pos::new(row, col), action);
            }
        }
        writeln!(
            out,
            "Learned policy (the greedy action of each state's description):"
        )?;
        return write!(out, "{}", mdp::render_text(map, &overlay));
    }
    writeln!(out, "Learned policy:")?;
    writeln!(out)?;
    writeln!(out, "| state | greedy action | description |")?;
    writeln!(out, "|---|---|---|")?;
    for st in &r.states {
        writeln!(
            out,
            "| {} | {} | {} |",
            shown(st.label.as_deref().unwrap_or("?")),
            shown(st.greedy_action.as_deref().unwrap_or("none")),
            st.description
                .map_or("none".to_string(), |d| format!("d{d}"))
        )?;
    }
    Ok(())
}

fn print_report(r: &RunReport, out: &mut dyn Write) -> std::io::Result<()> {
    let map = shown(&r.map);
    let who = match &r.settings.learner {
        csql::LearnerSettings::CsQl(q) => {
            format!("CS-QL on {map} with the {} strategy", q.strategy)
        }
        csql::LearnerSettings::UTree(_) => format!("U-Tree on {map}"),
        csql::LearnerSettings::FullSensing => format!("Full sensing on {map}"),
        csql::LearnerSettings::AmrlQ(_) => format!("AMRL-Q on {map}"),
        csql::LearnerSettings::Belief(_) => format!("Sensing by belief on {map}"),
    };
    // The same three lines for every learner, so that runs compare line by line.
    let verdict = match r.judged_by {
        csql::Judging::Oracle if r.converged => "converged (the oracle's verdict)",
        csql::Judging::Oracle => "did NOT converge (the oracle's verdict)",
        csql::Judging::Quality => "judged by the policy quality",
    };
    writeln!(
        out,
        "{who}, seed {}: {verdict} after {} trials ({} moves, sensing cost {:.0})",
        r.seed, r.trials, r.moves, r.total_cost
    )?;
    let q = &r.quality;
    let held = match (q.trials_to_quality, q.cost_to_quality) {
        (Some(t), Some(c)) => {
            format!("at least 0.95 from trial {t} on (sensing cost {c:.0} by then)")
        }
        _ => "did NOT stay at 0.95".to_string(),
    };
    writeln!(
        out,
        "Policy quality {:.3} ({}), {held}",
        q.policy_quality,
        q.method.name()
    )?;
    writeln!(
        out,
        "After learning: {} descriptions, {:.2} features each; the learner's own classification costs {:.2} per state",
        q.descriptions, q.mean_features, q.learner_cost_per_state
    )?;
    if let Some(why) = &r.stopped {
        writeln!(out, "Stopped early: {why}")?;
    }
    if let Some(not) = &r.not_learned {
        writeln!(out, "Not learned: {}", shown(&not.why))?;
        if !not.to_try.is_empty() {
            writeln!(
                out,
                "Try (in a --config file): {}",
                shown(&not.to_try.join("; "))
            )?;
        }
    }
    if let Some(c) = &r.costly {
        print_costly(c, out)?;
    }
    if let Some(why) = &r.costly_missing {
        writeln!(out, "Costed returns missing: {why}")?;
    }
    if let Some(p) = &r.prediction {
        let narrowed = if p.narrowed > 0 {
            format!(", {} told apart among the likely descriptions", p.narrowed)
        } else {
            String::new()
        };
        writeln!(
            out,
            "Sensing less ({}): {} classifications skipped{narrowed}, {} re-checked ({} found wrong); the oracle counts {} wrong, at most {} of one transition in a row",
            r.settings.predict_sensing(),
            p.skipped,
            p.rechecks,
            p.caught,
            p.wrong,
            p.longest_wrong_run
        )?;
    }
    writeln!(out)?;
    write!(out, "{}", r.table1)?;
    if let (Some(cost), Some(success)) = (r.navigation_cost_per_move, r.navigation_success) {
        writeln!(
            out,
            "Navigation after learning ({}): sensing cost {cost:.2} per move, {:.1}% of trials by an optimal path",
            r.settings.predict_sensing(),
            100.0 * success
        )?;
    }
    Ok(())
}
