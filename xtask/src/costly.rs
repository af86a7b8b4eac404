//! `cargo xtask costly`: the active-measurement benchmark (specification 6.10 and 6.11).
//!
//! FrozenLake 4x4 (1000 episodes a run) and 8x8 (2000), each deterministic,
//! semi-slippery (`slide = 0.5`) and slippery (`slip = 2/3`), sensed by its row and
//! column, each coordinate priced 0.025 or 0.05 reward units; every learner under both
//! sensing rules, `--runs` seeded runs each (run i seeded S + i). Sharded and resumable
//! as `cargo xtask sweep` is. The report: `costly.csv` (the published rule: sensing
//! decided with the move), `costly_after_outcome.csv` (sensing after the outcome), both
//! with one row per world, dynamics, price and learner; `costly.md`; and one figure per
//! world of the costed return against episodes.
//!
//! This file holds the arguments, the table's definition, its jobs and their running
//! (each learner's play); `costly/report.rs` writes the tables and the figures.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Result, anyhow, bail};
use clap::Args;
use csql::{
    AmrlParams, CostlySettings, CostlySummary, Episode, LearnerKind, Measuring, PredictSensing,
    RunSettings, StrategyKind,
};
use mdp::{FiniteWorld, SensingModel, SensingRule, WorldOptions};
use qlearn::MoveCap;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::{Deserialize, Serialize};

use crate::shard::JobLine;

mod join;
mod optimum;
mod report;

/// Arguments of `cargo xtask costly`.
#[derive(Args, Clone, Debug)]
pub struct CostlyArgs {
    /// Runs per world, dynamics, price, rule and learner.
    #[arg(long, default_value_t = 5)]
    runs: u64,
    /// Base seed: run i uses seed S + i.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// This machine's shard, `K/N` (K from 1 to N).
    #[arg(long, default_value = "1/1")]
    shard: String,
    /// Worker threads (default: every core). Results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// Output folder (shared by all shards).
    #[arg(long, default_value = "results/costly")]
    out: PathBuf,
    /// Run nothing: write the report from the shards under `--out`.
    #[arg(long)]
    report: bool,
    /// Also write the tables and figures into `docs/` (`docs/costly_results.md`,
    /// `docs/figures/costly_*.svg`); only for the whole table.
    #[arg(long)]
    bless: bool,
    /// Worlds, comma-separated, as `costly.csv` spells them (default: all).
    #[arg(long, value_delimiter = ',')]
    worlds: Vec<String>,
    /// Dynamics, comma-separated, as `costly.csv` spells them (default: all).
    #[arg(long, value_delimiter = ',')]
    dynamics: Vec<String>,
    /// Learners, comma-separated, as `costly.csv` spells them (default: the table's; also
    /// `belief-blind`, sensing by belief with each pair apart and free to stop measuring,
    /// run only when named).
    #[arg(long, value_delimiter = ',')]
    learners: Vec<String>,
    /// Prices per coordinate, comma-separated, as `costly.csv` spells them (default: all).
    #[arg(long, value_delimiter = ',')]
    prices: Vec<String>,
    /// Sensing rules, comma-separated: `with-move` (`costly.csv`) and `after-outcome`
    /// (`costly_after_outcome.csv`) (default: both).
    #[arg(long, value_delimiter = ',')]
    rules: Vec<String>,
    /// Run no learner: bracket the optimum of every lake of the table with its model
    /// known (`mdp::optimum_bounds`, about a minute and a half) and write
    /// `docs/costly_optimum.csv`, the tables' last column.
    #[arg(long, conflicts_with_all = ["report", "bless", "with"])]
    optimum: bool,
    /// Results folders of other runs of part of the table (the same `--seed`), joined in
    /// order: a row this table has is replaced by longer runs of it (at least as many;
    /// the runs both hold must agree to the bit), a row it lacks (a learner run only when
    /// named) is added; each row says how many runs it averages. The committed table
    /// takes the slippery lakes' rows from 20 runs this way (`docs/costly.md`).
    #[arg(long, value_delimiter = ',')]
    with: Vec<PathBuf>,
}

/// The part of the table a flag keeps: the entries of `all` (spelled by `name`) that
/// `given` names, in the table's order; every entry when `given` is empty. An unknown
/// spelling or an entry named twice is refused, naming the flag and the valid spellings.
fn select<T: Copy>(
    flag: &str,
    given: &[String],
    all: &[T],
    name: impl Fn(T) -> String,
) -> Result<Vec<T>> {
    if given.is_empty() {
        return Ok(all.to_vec());
    }
    crate::files::distinct(flag, given)?;
    let names: Vec<String> = all.iter().map(|&t| name(t)).collect();
    if let Some(bad) = given.iter().find(|g| !names.contains(g)) {
        bail!(
            "{flag} names `{bad}`, which the table does not hold; valid: {}",
            names.join(", ")
        );
    }
    Ok(all
        .iter()
        .zip(&names)
        .filter(|(_, n)| given.contains(n))
        .map(|(&t, _)| t)
        .collect())
}

impl CostlyArgs {
    /// The part of the table the flags select.
    fn definition(&self) -> Result<Definition> {
        let worlds: Vec<usize> = (0..WORLDS.len()).collect();
        Ok(Definition {
            runs: self.runs,
            seed: self.seed,
            worlds: select("--worlds", &self.worlds, &worlds, |w| {
                WORLDS[w].0.to_string()
            })?,
            dynamics: select("--dynamics", &self.dynamics, &Dynamics::ALL, |d| {
                d.name().to_string()
            })?,
            prices: select("--prices", &self.prices, &PRICES, |p| p.to_string())?,
            rules: select("--rules", &self.rules, &RULES, |r| r.name().to_string())?,
            // The table's learners by default; the others only when named.
            learners: if self.learners.is_empty() {
                Learner::TABLE.to_vec()
            } else {
                select("--learners", &self.learners, &Learner::NAMED, |l| {
                    l.name().to_string()
                })?
            },
        })
    }
}

/// The lakes: name, episodes a run, moves an episode (Gymnasium's caps).
const WORLDS: [(&str, u32, u32); 2] = [("frozenlake4x4", 1000, 100), ("frozenlake8x8", 2000, 200)];

/// The price of each coordinate, in reward units (measuring the whole state costs twice).
const PRICES: [f64; 2] = [0.025, 0.05];

/// Episodes averaged into one point of a learning curve.
const BLOCK: usize = 25;

/// How the lake moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Dynamics {
    /// Every move as intended.
    Deterministic,
    /// One more cell with probability 1/2 (`slide = 0.5`).
    SemiSlippery,
    /// Gymnasium's slippery lake (`slip = 2/3`).
    Slippery,
}

impl Dynamics {
    const ALL: [Dynamics; 3] = [
        Dynamics::Deterministic,
        Dynamics::SemiSlippery,
        Dynamics::Slippery,
    ];

    fn name(self) -> &'static str {
        match self {
            Dynamics::Deterministic => "deterministic",
            Dynamics::SemiSlippery => "semi-slippery",
            Dynamics::Slippery => "slippery",
        }
    }

    fn options(self) -> WorldOptions {
        let (slip, slide) = match self {
            Dynamics::Deterministic => (None, None),
            Dynamics::SemiSlippery => (None, Some(0.5)),
            Dynamics::Slippery => (Some(2.0 / 3.0), None),
        };
        WorldOptions {
            slip,
            slide,
            sensing: Some(SensingModel::Factors),
            factor_costs: None,
        }
    }
}

/// The sensing rules, the published one first.
const RULES: [SensingRule; 2] = [SensingRule::WithMove, SensingRule::AfterOutcome];

/// A learner of the benchmark.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Learner {
    /// AMRL-Q with its published parameters (`csql::amrl_q`), exploring in every run
    /// and greedy in the last 10% of each run's episodes, as the method is described.
    AmrlQ,
    /// AMRL-Q as the published harness runs it: the first run as [`Learner::AmrlQ`],
    /// every later one greedy from its first episode (`greedy_share = 1`), since the
    /// harness reuses one agent object whose greedy switch stays on.
    AmrlQGreedyAfterFirst,
    /// The same Q-learning measuring the whole state at every step
    /// (`csql::Measuring::Always`).
    AlwaysMeasuring,
    /// CS-QL with the resetting strategy and the paper's settings otherwise
    /// (`csql::costed_episodes`).
    CsQl,
    /// Q-learning sensing every feature at every step, in CS-QL's main loop
    /// (`csql::costed_episodes` with `learner = "full-sensing"`).
    FullSensing,
    /// Sensing by belief as a run on the lake has it by default: a learned model (each
    /// move learned once for every cell), a plan over beliefs free to stop measuring, the
    /// row and the column measured apart (`csql::belief_planning` with the lake's
    /// `[belief]` settings, [`csql::WorldDefaults::belief_for`]).
    Belief,
    /// CS-QL as [`Learner::CsQl`], sensing by its belief over descriptions
    /// (`predict_sensing = "weighed"`, `[prediction]` at its defaults).
    CsQlWeighed,
    /// Sensing by belief as it was before the lakes asked for their own settings: each
    /// pair learned apart, the plan never free to stop measuring (`[belief]
    /// shared_moves = 0`, `blind_plans = 0`).
    BeliefApart,
    /// Sensing by belief as [`Learner::BeliefApart`], its plan free to stop measuring for
    /// the rest of an episode (`[belief] blind_plans` = [`BLIND_PLANS`]). Not in the
    /// committed table: run by naming it in `--learners`.
    BeliefBlind,
}

/// The open-loop plans a step of [`Learner::BeliefBlind`] (`[belief] blind_plans`).
const BLIND_PLANS: usize = 16;

impl Learner {
    /// Every learner `--learners` takes: the committed table's, in its order, then those
    /// run only when named.
    const NAMED: [Learner; 9] = [
        Learner::AmrlQ,
        Learner::AmrlQGreedyAfterFirst,
        Learner::AlwaysMeasuring,
        Learner::CsQl,
        Learner::FullSensing,
        Learner::Belief,
        Learner::CsQlWeighed,
        Learner::BeliefApart,
        Learner::BeliefBlind,
    ];

    /// The learners of the committed table (the default of `--learners`).
    const TABLE: &[Learner] = Learner::NAMED.as_slice().split_at(8).0;

    fn name(self) -> &'static str {
        match self {
            Learner::AmrlQ => "amrl-q",
            Learner::AmrlQGreedyAfterFirst => "amrl-q-greedy-after-first",
            Learner::AlwaysMeasuring => "always-measuring",
            Learner::CsQl => "cs-ql",
            Learner::FullSensing => "full-sensing",
            Learner::Belief => "belief",
            Learner::CsQlWeighed => "cs-ql-weighed",
            Learner::BeliefApart => "belief-apart",
            Learner::BeliefBlind => "belief-blind",
        }
    }

    /// One run of `play`'s episodes by this learner.
    fn play(self, play: &Play<'_>) -> Result<Vec<Episode>> {
        match self {
            Learner::AmrlQ => Ok(amrl(play, Measuring::Choose, AmrlParams::default())),
            Learner::AmrlQGreedyAfterFirst => {
                let mut params = AmrlParams::default();
                if play.run > 0 {
                    params.greedy_share = 1.0;
                }
                Ok(amrl(play, Measuring::Choose, params))
            }
            Learner::AlwaysMeasuring => Ok(amrl(play, Measuring::Always, AmrlParams::default())),
            Learner::CsQl => cs_ql(play, (LearnerKind::CsQl, PredictSensing::Off)),
            Learner::FullSensing => cs_ql(play, (LearnerKind::FullSensing, PredictSensing::Off)),
            Learner::CsQlWeighed => cs_ql(play, (LearnerKind::CsQl, PredictSensing::Weighed)),
            Learner::Belief | Learner::BeliefApart | Learner::BeliefBlind => {
                let apart = |blind_plans| csql::BeliefParams {
                    blind_plans: Some(blind_plans),
                    shared_moves: Some(0),
                    ..csql::BeliefParams::default()
                };
                let params = match self {
                    Learner::Belief => {
                        let sensed = csql::WorldExtras {
                            sensing: Some(SensingModel::Factors),
                            ..csql::WorldExtras::default()
                        };
                        csql::WorldDefaults::of(play.world).belief_for(
                            csql::BeliefParams::default(),
                            &sensed,
                            play.max_moves,
                        )
                    }
                    Learner::BeliefApart => apart(0),
                    _ => apart(BLIND_PLANS),
                };
                // Each coordinate costs 1: its price in reward units is the price.
                let mut rng = Xoshiro256PlusPlus::seed_from_u64(play.seed);
                Ok(csql::belief_planning(
                    play.lake,
                    &params,
                    play.price,
                    play.rule,
                    play.episodes,
                    play.max_moves,
                    &mut rng,
                )?)
            }
        }
    }
}

/// What one run plays, whatever the learner: `episodes` episodes of at most `max_moves`
/// moves on `lake` (the built-in world `world`), each coordinate at `price` reward units,
/// sensed under `rule`, seeded with `seed`; `run` is its number among the runs of its row
/// (from 0).
struct Play<'a> {
    run: u64,
    lake: &'a FiniteWorld,
    world: &'a str,
    price: f64,
    rule: SensingRule,
    episodes: u32,
    max_moves: u32,
    seed: u64,
}

/// AMRL-Q or the always-measuring learner with `params` otherwise, measuring the whole
/// state: every coordinate at once.
fn amrl(play: &Play<'_>, measuring: Measuring, params: AmrlParams) -> Vec<Episode> {
    let params = AmrlParams {
        measuring,
        ..params
    };
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(play.seed);
    csql::amrl_q(
        play.lake,
        &params,
        2.0 * play.price,
        play.rule,
        play.episodes,
        play.max_moves,
        &mut rng,
    )
}

/// CS-QL (the resetting strategy, at the given `predict_sensing` level) or full
/// sensing, with the paper's settings and the lake's move cap; each coordinate costs 1
/// and is priced `play.price` reward units.
fn cs_ql(play: &Play<'_>, (kind, level): (LearnerKind, PredictSensing)) -> Result<Vec<Episode>> {
    let mut settings = RunSettings::tan1991(play.world, StrategyKind::Resetting, play.seed);
    if kind != LearnerKind::CsQl {
        settings = settings.with_learner(kind);
    }
    if let Some(q) = settings.cs_ql_mut() {
        q.predict_sensing = level;
    }
    if level == PredictSensing::Weighed {
        // The weighed level weighs sensing at the price it is scored at.
        settings.costly = Some(CostlySettings {
            price: play.price,
            rule: play.rule,
        });
    }
    settings.max_moves = MoveCap::new(u64::from(play.max_moves))?;
    Ok(csql::costed_episodes(
        play.lake,
        &settings,
        play.rule,
        play.price,
        play.episodes,
    )?)
}

/// What the job list is: shards of one list agree on it. The part of the table it runs:
/// the worlds (indices into [`WORLDS`]), dynamics, prices, rules and learners, each in
/// the table's order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Definition {
    runs: u64,
    seed: u64,
    worlds: Vec<usize>,
    dynamics: Vec<Dynamics>,
    prices: Vec<f64>,
    rules: Vec<SensingRule>,
    learners: Vec<Learner>,
}

impl Definition {
    /// Whether it is the whole table.
    fn is_whole(&self) -> bool {
        self.worlds.len() == WORLDS.len()
            && self.dynamics.len() == Dynamics::ALL.len()
            && self.prices.len() == PRICES.len()
            && self.rules.len() == RULES.len()
            && self.learners == Learner::TABLE
    }
}

/// One finished run.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct JobResult {
    id: u64,
    world: String,
    dynamics: Dynamics,
    price: f64,
    rule: SensingRule,
    learner: Learner,
    seed: u64,
    summary: Summary,
    /// The mean costed return of each block of [`BLOCK`] episodes, in order.
    curve: Vec<f64>,
}

/// [`CostlySummary`] as a results line holds it.
#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
pub struct Summary {
    episodes: usize,
    mean_all: f64,
    mean_last10: f64,
    sensing_per_episode: f64,
    steps_per_episode: f64,
    success: f64,
}

impl Summary {
    /// Every figure's bits, to compare two runs exactly.
    fn to_bits(self) -> [u64; 6] {
        [
            self.episodes as u64,
            self.mean_all.to_bits(),
            self.mean_last10.to_bits(),
            self.sensing_per_episode.to_bits(),
            self.steps_per_episode.to_bits(),
            self.success.to_bits(),
        ]
    }
}

impl From<CostlySummary> for Summary {
    fn from(s: CostlySummary) -> Summary {
        Summary {
            episodes: s.episodes,
            mean_all: s.mean_all,
            mean_last10: s.mean_last10,
            sensing_per_episode: s.sensing_per_episode,
            steps_per_episode: s.steps_per_episode,
            success: s.success,
        }
    }
}

impl JobLine for JobResult {
    fn id(&self) -> u64 {
        self.id
    }
}

/// A job of the list: (world, dynamics, price, rule, learner, run), from its number.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Job {
    world: usize,
    dynamics: Dynamics,
    price: f64,
    rule: SensingRule,
    learner: Learner,
    run: u64,
}

/// The size of the job list.
fn total(def: &Definition) -> Result<u64> {
    let per_run = (def.worlds.len()
        * def.dynamics.len()
        * def.prices.len()
        * def.rules.len()
        * def.learners.len()) as u64;
    per_run
        .checked_mul(def.runs)
        .ok_or_else(|| anyhow!("--runs is more jobs than can be numbered"))
}

/// Job `id`, in the order world, dynamics, price, rule, learner, run.
fn job(def: &Definition, id: u64) -> Job {
    let run = id % def.runs;
    let mut rest = id / def.runs;
    let mut take = |n: usize| {
        let i = rest % n as u64;
        rest /= n as u64;
        i as usize
    };
    let learner = def.learners[take(def.learners.len())];
    let rule = def.rules[take(def.rules.len())];
    let price = def.prices[take(def.prices.len())];
    let dynamics = def.dynamics[take(def.dynamics.len())];
    let world = def.worlds[take(def.worlds.len())];
    Job {
        world,
        dynamics,
        price,
        rule,
        learner,
        run,
    }
}

/// One run of a job.
fn run_job(
    def: &Definition,
    lakes: &BTreeMap<(usize, Dynamics), FiniteWorld>,
    id: u64,
) -> Result<JobResult> {
    let j = job(def, id);
    let (world, episodes, max_moves) = WORLDS[j.world];
    let lake = &lakes[&(j.world, j.dynamics)];
    let seed = def.seed + j.run;
    let run = j.learner.play(&Play {
        run: j.run,
        lake,
        world,
        price: j.price,
        rule: j.rule,
        episodes,
        max_moves,
        seed,
    })?;
    Ok(JobResult {
        id,
        world: world.to_string(),
        dynamics: j.dynamics,
        price: j.price,
        rule: j.rule,
        learner: j.learner,
        seed,
        summary: CostlySummary::of(&run).into(),
        curve: run
            .chunks(BLOCK)
            .map(|b| b.iter().map(Episode::costed_return).sum::<f64>() / b.len() as f64)
            .collect(),
    })
}

/// `cargo xtask costly`.
pub fn costly(args: &CostlyArgs) -> Result<()> {
    if args.runs == 0 {
        bail!("costly needs --runs of at least 1");
    }
    if args.optimum {
        return optimum::write(Path::new(optimum::PATH));
    }
    crate::files::seeds(args.seed, args.runs)?;
    let def = args.definition()?;
    if args.bless && !def.is_whole() {
        bail!(
            "--bless writes the committed tables: run the whole table (no --worlds, --dynamics, --learners, --prices or --rules)"
        );
    }
    if !args.report {
        let mut lakes = BTreeMap::new();
        for &w in &def.worlds {
            for &d in &def.dynamics {
                lakes.insert((w, d), mdp::builtin_world(WORLDS[w].0, &d.options())?);
            }
        }
        crate::shard::run_shard(
            &args.out,
            &args.shard,
            def.clone(),
            total(&def)?,
            args.threads,
            |_| 1.0,
            |id| run_job(&def, &lakes, id),
        )?;
        if crate::shard::one_of_several(&args.shard, "costly")? {
            return Ok(());
        }
    }
    let by_id: BTreeMap<u64, JobResult> = crate::shard::collect_of(&args.out, &def)?;
    let mut results: Vec<JobResult> = by_id.into_values().collect();
    let mut joined = Vec::new();
    for dir in &args.with {
        let (other, by_id): (Definition, BTreeMap<u64, JobResult>) =
            crate::shard::collect(std::slice::from_ref(dir))?;
        results = join::join(&def, results, (&other, by_id.into_values().collect()), dir)?;
        joined.push(other.command());
    }
    report::write(&results, &joined, &args.out, "costly.md")?;
    if args.bless {
        report::write(&results, &joined, Path::new("docs"), "costly_results.md")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(runs: u64) -> CostlyArgs {
        CostlyArgs {
            runs,
            seed: 1,
            shard: "1/1".to_string(),
            threads: None,
            out: PathBuf::from("unused"),
            report: false,
            bless: false,
            optimum: false,
            with: vec![],
            worlds: vec![],
            dynamics: vec![],
            learners: vec![],
            prices: vec![],
            rules: vec![],
        }
    }

    fn def(runs: u64) -> Definition {
        args(runs).definition().unwrap()
    }

    fn names(list: &str) -> Vec<String> {
        list.split(',').map(str::to_string).collect()
    }

    #[test]
    fn the_flags_select_part_of_the_table() {
        let mut a = args(2);
        a.worlds = names("frozenlake8x8");
        a.dynamics = names("slippery,deterministic");
        a.learners = names("belief,amrl-q-greedy-after-first");
        a.prices = names("0.025");
        a.rules = names("with-move");
        let d = a.definition().unwrap();
        assert!(!d.is_whole() && def(2).is_whole());
        // A learner outside the table runs only when named.
        assert!(!def(2).learners.contains(&Learner::BeliefBlind));
        a.learners = names("belief-blind,belief");
        let blind = a.definition().unwrap();
        assert_eq!(blind.learners, [Learner::Belief, Learner::BeliefBlind]);
        assert!(!blind.is_whole());
        a.learners = names("belief,amrl-q-greedy-after-first");
        // In the table's order, whatever the order given.
        assert_eq!(d.worlds, [1]);
        assert_eq!(d.dynamics, [Dynamics::Deterministic, Dynamics::Slippery]);
        assert_eq!(
            d.learners,
            [Learner::AmrlQGreedyAfterFirst, Learner::Belief]
        );
        assert_eq!(
            (d.prices.clone(), d.rules.clone()),
            (vec![0.025], vec![SensingRule::WithMove])
        );
        let n = total(&d).unwrap();
        assert_eq!(n, 2 * 2 * 2);
        for id in 0..n {
            let j = job(&d, id);
            assert_eq!(
                (j.world, j.price, j.rule),
                (1, 0.025, SensingRule::WithMove)
            );
            assert!(d.dynamics.contains(&j.dynamics) && d.learners.contains(&j.learner));
        }
        // A job of the part is the same job of the whole table: same seed, same run.
        let whole = def(2);
        let j = job(&d, n - 1);
        let found = (0..total(&whole).unwrap())
            .map(|id| job(&whole, id))
            .find(|w| *w == j);
        assert_eq!(found, Some(j));
    }

    #[test]
    fn an_unknown_spelling_is_refused_with_the_valid_ones() {
        type Field = fn(&mut CostlyArgs) -> &mut Vec<String>;
        let cases: [(&str, Field, &str, &str); 5] = [
            (
                "--worlds",
                |a| &mut a.worlds,
                "frozenlake5x5",
                "frozenlake4x4, frozenlake8x8",
            ),
            (
                "--dynamics",
                |a| &mut a.dynamics,
                "semislippery",
                "deterministic, semi-slippery, slippery",
            ),
            (
                "--learners",
                |a| &mut a.learners,
                "amrlq",
                "amrl-q, amrl-q-greedy-after-first, always-measuring, cs-ql, full-sensing, belief, cs-ql-weighed, belief-apart, belief-blind",
            ),
            ("--prices", |a| &mut a.prices, "0.050", "0.025, 0.05"),
            (
                "--rules",
                |a| &mut a.rules,
                "after",
                "with-move, after-outcome",
            ),
        ];
        for (flag, field, bad, valid) in cases {
            let mut a = args(1);
            *field(&mut a) = vec![bad.to_string()];
            let e = a.definition().unwrap_err().to_string();
            assert!(e.contains(flag) && e.contains(&format!("`{bad}`")), "{e}");
            assert!(e.ends_with(&format!("valid: {valid}")), "{e}");
        }
        let mut a = args(1);
        a.prices = names("0.05,0.05");
        let e = a.definition().unwrap_err().to_string();
        assert!(e.contains("--prices names `0.05` twice"), "{e}");
    }

    #[test]
    fn the_published_protocol_is_greedy_after_the_first_run() {
        let lake = mdp::builtin_world("frozenlake4x4", &Dynamics::Deterministic.options()).unwrap();
        let play = |learner: Learner, run: u64| {
            let p = Play {
                run,
                lake: &lake,
                world: "frozenlake4x4",
                price: 0.025,
                rule: SensingRule::WithMove,
                episodes: 40,
                max_moves: 100,
                seed: 7,
            };
            CostlySummary::of(&learner.play(&p).unwrap())
        };
        // The first run explores as AMRL-Q does; a later one is greedy throughout, and so
        // differs from AMRL-Q's run of the same seed.
        assert_eq!(
            play(Learner::AmrlQGreedyAfterFirst, 0),
            play(Learner::AmrlQ, 0)
        );
        let greedy = play(Learner::AmrlQGreedyAfterFirst, 1);
        assert_ne!(greedy, play(Learner::AmrlQ, 1));
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        let params = AmrlParams {
            greedy_share: 1.0,
            ..AmrlParams::default()
        };
        let run = csql::amrl_q(
            &lake,
            &params,
            0.05,
            SensingRule::WithMove,
            40,
            100,
            &mut rng,
        );
        assert_eq!(greedy, CostlySummary::of(&run));
    }

    #[test]
    fn every_job_is_numbered_once() {
        let d = def(3);
        let n = total(&d).unwrap();
        assert_eq!(n, 2 * 3 * 2 * 2 * Learner::TABLE.len() as u64 * 3);
        let jobs: Vec<Job> = (0..n).map(|id| job(&d, id)).collect();
        for (i, a) in jobs.iter().enumerate() {
            assert!(jobs[i + 1..].iter().all(|b| b != a), "{a:?} twice");
        }
        // Runs are the innermost: a job's runs are neighbours.
        assert_eq!((jobs[0].run, jobs[1].run, jobs[2].run), (0, 1, 2));
        assert_eq!(jobs[0].world, 0);
        assert_eq!(jobs[(n - 1) as usize].world, 1);
    }

    #[test]
    fn a_run_is_its_seeds_alone() {
        let d = def(2);
        let mut lakes = BTreeMap::new();
        lakes.insert(
            (0, Dynamics::SemiSlippery),
            mdp::builtin_world("frozenlake4x4", &Dynamics::SemiSlippery.options()).unwrap(),
        );
        // Job 0 of the second rule, price and dynamics of the 4x4 lake.
        let id = (0..total(&d).unwrap())
            .find(|&id| {
                let j = job(&d, id);
                j.world == 0 && j.dynamics == Dynamics::SemiSlippery && j.run == 1
            })
            .unwrap();
        let a = serde_json::to_string(&run_job(&d, &lakes, id).unwrap()).unwrap();
        let b = serde_json::to_string(&run_job(&d, &lakes, id).unwrap()).unwrap();
        assert_eq!(a, b);
        let r = run_job(&d, &lakes, id).unwrap();
        assert_eq!((r.seed, r.curve.len()), (2, 1000 / BLOCK));
    }
}
