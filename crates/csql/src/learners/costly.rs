//! CS-QL and full sensing scored on costed episodes (specification 6.12): the learner of
//! a run's settings played for a fixed number of episodes, each scored as the
//! active-measurement benchmark scores AMRL-Q ([`crate::amrl_q`]).
//!
//! The learner is the main loop of [`crate::run`], driven episode by episode from the
//! run's generator exactly as `csql::run` drives it (the same starts, moves and
//! learning), but for a fixed number of episodes: nothing judges it and nothing stops
//! it early. Each episode's sensing is what the learner really read in it, each feature
//! at its price times `reward_per_cost`: CS-QL's CLASSIFY of the start state and of every
//! state a move reached (a goal or a hole is never classified), with a refinement's
//! feature read on the state left; full sensing's every feature at every state.
//!
//! The two sensing rules differ only at the move that ends an episode:
//!
//! * [`SensingRule::AfterOutcome`]: nothing is charged for the state a move that ends
//!   the episode reaches (the learner does not classify it);
//! * [`SensingRule::WithMove`]: sensing is chosen with the move, before its outcome, so
//!   the move that ends the episode is charged what the learner would have read
//!   classifying the state it reached, learning nothing from it: CS-QL's features along
//!   its descriptions until one matches or none can (as CLASSIFY would read them, without
//!   creating a description), full sensing's every feature.
//!
//! A move cut by the move cap is not an end of the episode for the learner: the state
//! reached is classified, and charged, under both rules (as AMRL-Q measures there too).
//! A sensing act (an [`Episode`]'s `measurements`) is a state classified with at least
//! one feature read.

use mdp::{ActionId, SensingRule, StateId, World};
use qlearn::{QTable, RowId};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use serde::Serialize;

use crate::agent::main_loop::Agent;
use crate::agent::strategy::{Never, Strategy};
use crate::error::Error;
use crate::learners::amrl::{CostlySummary, Episode};
use crate::observe::Observer;
use crate::perception::classify::Classify;
use crate::perception::rows::{FullView, Perception};
use crate::perception::sense_less::Predicting;
use crate::perception::sense_less::level::PredictSensing;
use crate::settings::learner::LearnerSettings;
use crate::settings::values::{CostlySettings, RunSettings};

/// What a perception would read classifying a state, learning nothing: the charge of a
/// move that ends an episode under [`SensingRule::WithMove`].
trait WouldRead: Perception {
    /// Action `a` was taken from row `from` and will end the episode: a perception that
    /// chooses what to sense with the move chooses it now, before the move is learned
    /// from.
    fn before_outcome(&mut self, from: RowId, a: ActionId, table: &QTable) {
        let _ = (from, a, table);
    }
    /// What it would read on `s`, reached by `a` from `from`.
    fn would_read<W: World + ?Sized>(
        &mut self,
        world: &W,
        from: RowId,
        a: ActionId,
        s: StateId,
        table: &QTable,
    ) -> f64;
}

impl WouldRead for Classify {
    fn would_read<W: World + ?Sized>(
        &mut self,
        world: &W,
        _: RowId,
        _: ActionId,
        s: StateId,
        _: &QTable,
    ) -> f64 {
        self.lookup_cost(world, s)
    }
}

impl WouldRead for FullView {
    fn would_read<W: World + ?Sized>(
        &mut self,
        world: &W,
        _: RowId,
        _: ActionId,
        s: StateId,
        _: &QTable,
    ) -> f64 {
        FullView::cost_of(world, s)
    }
}

impl WouldRead for Predicting {
    fn before_outcome(&mut self, from: RowId, a: ActionId, table: &QTable) {
        self.choose_with_move(from, a, table);
    }
    fn would_read<W: World + ?Sized>(
        &mut self,
        world: &W,
        from: RowId,
        a: ActionId,
        s: StateId,
        table: &QTable,
    ) -> f64 {
        self.would_read_by_belief(world, from, a, s, table)
    }
}

/// Play the learner of `settings` (CS-QL without prediction or memory, or full sensing)
/// for exactly `episodes` episodes (at most [`crate::MAX_EPISODES`]) of at most
/// `settings.max_moves` moves in `world`, and
/// score each: its undiscounted reward, and the prices of what it sensed (the world's
/// feature costs times `reward_per_cost`, reward units per unit of cost) under `rule`.
///
/// The episodes are those of `csql::run` with the same settings, trial for trial, for as
/// long as that run goes: under [`SensingRule::AfterOutcome`] their sensing is its
/// cost times `reward_per_cost`.
///
/// ```
/// use csql::{LearnerKind, RunSettings, StrategyKind};
/// use mdp::SensingRule;
/// let options = mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() };
/// let lake = mdp::builtin_world("frozenlake4x4", &options).unwrap();
/// let settings = RunSettings::tan1991("frozenlake4x4", StrategyKind::Resetting, 1);
/// let run = csql::costed_episodes(&lake, &settings, SensingRule::WithMove, 0.025, 200).unwrap();
/// assert_eq!(run.len(), 200); // never stopped early
/// let full = settings.clone().with_learner(LearnerKind::FullSensing);
/// let run = csql::costed_episodes(&lake, &full, SensingRule::AfterOutcome, 0.025, 200).unwrap();
/// // Full sensing reads the row and the column of every state it classifies.
/// assert!(run.iter().all(|e| (e.sensing - 0.05 * f64::from(e.measurements)).abs() < 1e-9));
/// assert!(csql::costed_episodes(&lake, &settings, SensingRule::WithMove, f64::NAN, 1).is_err());
/// assert!(csql::costed_episodes(&lake, &settings, SensingRule::WithMove, 0.025, u32::MAX).is_err());
/// ```
pub fn costed_episodes<W: World + ?Sized>(
    world: &W,
    settings: &RunSettings,
    rule: SensingRule,
    reward_per_cost: f64,
    episodes: u32,
) -> Result<Vec<Episode>, Error> {
    if !(reward_per_cost.is_finite() && reward_per_cost >= 0.0) {
        return Err(Error::InvalidSetting {
            value: format!("reward_per_cost = {reward_per_cost}"),
            expected: "a finite price of at least 0 reward units per unit of sensing cost",
        });
    }
    settings.validate()?;
    if episodes > crate::settings::costed::MAX_EPISODES {
        return Err(Error::InvalidSetting {
            value: format!("episodes = {episodes}"),
            expected: "at most 1000000 episodes (csql::MAX_EPISODES): every episode is returned",
        });
    }
    crate::settings::resolve::check_with_world(
        settings,
        crate::settings::resolve::is_deterministic(world),
        world.grid().is_some(),
    )?;
    crate::settings::resolve::check_size(settings, world)?;
    let refuse = |what: String, why: &'static str| Error::Conflict {
        first: "costed episodes".to_string(),
        second: what,
        why,
    };
    // Q and V start at the floor of the world's returns, as in `csql::run`.
    let floor = crate::agent::main_loop::value_floor(world, settings.gamma.get());
    let table = QTable::new(world.num_actions())
        .and_then(|t| t.starting_at(floor))
        .map_err(|_| Error::InvalidSetting {
            value: format!("{} actions, returns from {floor}", world.num_actions()),
            expected: "a world of at least one action and finite returns",
        })?;
    let play = Play {
        world,
        settings,
        rule,
        reward_per_cost,
        episodes,
    };
    match &settings.learner {
        LearnerSettings::FullSensing => Ok(play.run(FullView::new(world), Never, table)),
        LearnerSettings::CsQl(q) => {
            let belief = q.predict_sensing == PredictSensing::Weighed;
            if !(q.predict_sensing.is_off() || belief) || q.extensions.memory > 0 {
                return Err(refuse(
                    format!("predict_sensing = {} or memory", q.predict_sensing),
                    "they are scored for CS-QL classifying every state it reaches, or sensing by its belief (predict_sensing = belief)",
                ));
            }
            // CLASSIFY as `csql::run` builds it: the sensors' own generator, the run's
            // 2^128 draws ahead (drawn from only under sensor noise).
            let mut sensor_rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed);
            sensor_rng.jump();
            let classify = Classify::new(world)
                .with_noise(settings.world.sensor_noise(), sensor_rng)
                .with_extensions(&settings.extensions());
            let strategy = q.strategy.build(q.random_moves);
            if belief {
                if settings.costly.map(|c| c.price) != Some(reward_per_cost) {
                    return Err(refuse(
                        "predict_sensing = belief".to_string(),
                        "the weighed level weighs sensing at the price it is scored at: give [costly] price the value of reward_per_cost",
                    ));
                }
                let p = Predicting::weighed(
                    classify,
                    &q.prediction,
                    world.num_actions(),
                    reward_per_cost,
                );
                return Ok(play.run(p, strategy, table));
            }
            Ok(play.run(classify, strategy, table))
        }
        other => Err(refuse(
            format!("learner = {}", other.kind()),
            "they play cs-ql and full-sensing; amrl-q and belief play through csql::costed_report",
        )),
    }
}

/// A run's trials scored by their costed return: what a report carries when the settings
/// price sensing (`[costly]`).
///
/// ```
/// let e = |r: f64| csql::Episode { reward: r, sensing: 0.1, measurements: 2, steps: 3, reached_goal: r > 0.0 };
/// let c = csql::CostedRun::of(csql::CostlySettings::new(0.05), &[e(0.0), e(1.0)]);
/// assert_eq!(c.returns.len(), 2);
/// assert!((c.returns[1] - 0.9).abs() < 1e-12 && (c.summary.mean_all - 0.4).abs() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CostedRun {
    /// Reward units per unit of sensing cost.
    pub price: f64,
    /// When sensing was decided.
    pub rule: SensingRule,
    /// The costed return of every episode (trial), in order.
    pub returns: Vec<f64>,
    /// The episodes summed up.
    pub summary: CostlySummary,
}

impl CostedRun {
    /// The costed returns and summary of `episodes`, scored under `costly`.
    ///
    /// ```
    /// let c = csql::CostedRun::of(csql::CostlySettings::new(0.05), &[]);
    /// assert_eq!(c.summary.episodes, 0);
    /// ```
    pub fn of(costly: CostlySettings, episodes: &[Episode]) -> CostedRun {
        CostedRun {
            price: costly.price,
            rule: costly.rule,
            returns: episodes.iter().map(Episode::costed_return).collect(),
            summary: CostlySummary::of(episodes),
        }
    }
}

/// The costed run of `trials` trials of the learner of `settings` in `world`, when the
/// settings price sensing (`None` otherwise): what `csql::run` attaches to its report.
pub(crate) fn costed_run<W: World + ?Sized>(
    world: &W,
    settings: &RunSettings,
    trials: u32,
) -> Result<Option<CostedRun>, Error> {
    let Some(c) = settings.costly else {
        return Ok(None);
    };
    let episodes = costed_episodes(world, settings, c.rule, c.price, trials)?;
    Ok(Some(CostedRun::of(c, &episodes)))
}

/// What `csrl run` reports for a learner played on episodes of the costed return
/// (`--learner amrl-q` or `--learner belief`): `episodes` episodes, each scored by its
/// costed return.
///
/// ```
/// let mut s = csql::SettingsDraft::from_toml("learner = \"amrl-q\"\nepisodes = 20\n[costly]\nprice = 0.5", "f")
///     .unwrap()
///     .build()
///     .unwrap();
/// let lake = mdp::builtin_world("frozenlake4x4", &mdp::WorldOptions::default()).unwrap();
/// let r: csql::CostedReport = csql::costed_report(&lake, "frozenlake4x4", &s, &mut csql::KeepTrace).unwrap();
/// let json = serde_json::to_value(&r).unwrap();
/// assert_eq!(json["learner"], "amrl-q");
/// assert_eq!(json["settings"]["costly"]["rule"], "with-move");
/// // Not a learner of `csql::run`.
/// s.map = "frozenlake4x4".into();
/// assert!(csql::run(&s).unwrap_err().to_string().contains("learner = amrl-q"));
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CostedReport {
    /// The world's name.
    pub map: String,
    /// `amrl-q` or `belief`.
    pub learner: crate::LearnerKind,
    /// The seed of the run's generator.
    pub seed: u64,
    /// The price of measuring the whole state, in reward units: `[costly] price` times
    /// the sum of the world's feature costs (each feature alone costs its cost times
    /// `[costly] price`).
    pub whole_state_price: f64,
    /// Every episode's costed return, and their summary.
    pub costly: CostedRun,
    /// The settings.
    pub settings: RunSettings,
}

/// The learner of `settings` played on episodes of the costed return in `world` (named
/// `name`): `episodes` episodes of at most `max_moves` moves, under `[costly] rule`,
/// from one generator seeded with `seed`. `observer` is asked before every episode
/// whether to go on ([`Observer::keep_going`]; within an episode of `amrl-q` too, every
/// [`crate::STOP_CHECK_MOVES`] moves): a no ends the run there, and the report holds
/// the episodes played.
///
/// * `amrl-q`: exactly [`crate::amrl_q`] with the parameters of `[amrl_q]`, measuring
///   the whole state at `[costly] price` times the sum of the world's feature costs;
/// * `belief`: exactly [`crate::belief_planning`] with the parameters of `[belief]`, a
///   feature priced at its cost times `[costly] price`.
///
/// # Errors
/// Settings refused by [`RunSettings::validate`], a learner of [`crate::run`] or no
/// `[costly] price` ([`Error::Conflict`]), or a world sensing by belief cannot plan in
/// ([`Error::Plan`]).
///
/// ```
/// let mut s = csql::RunSettings::tan1991("frozenlake4x4", csql::StrategyKind::Lazy, 3)
///     .with_learner(csql::LearnerKind::AmrlQ);
/// s.costly = Some(csql::CostlySettings::new(0.025));
/// s.max_trials = csql::TrialCap::new(300).unwrap();
/// let options = mdp::WorldOptions { sensing: Some(mdp::SensingModel::Factors), ..Default::default() };
/// let lake = mdp::builtin_world("frozenlake4x4", &options).unwrap();
/// let r = csql::costed_report(&lake, "frozenlake4x4", &s, &mut csql::KeepTrace).unwrap();
/// assert_eq!((r.costly.returns.len(), r.whole_state_price), (300, 0.05));
/// // Sensing by belief, its features priced at [costly] price.
/// s.learner = csql::LearnerSettings::Belief(csql::BeliefParams::default());
/// let r = csql::costed_report(&lake, "frozenlake4x4", &s, &mut csql::KeepTrace).unwrap();
/// assert_eq!((r.learner, r.costly.summary.episodes), (csql::LearnerKind::Belief, 300));
/// ```
pub fn costed_report<W: World + ?Sized>(
    world: &W,
    name: &str,
    settings: &RunSettings,
    observer: &mut dyn Observer,
) -> Result<CostedReport, Error> {
    settings.validate()?;
    crate::settings::resolve::check_size(settings, world)?;
    let kind = settings.learner.kind();
    let refuse = || Error::Conflict {
        first: format!("learner = {kind}"),
        second: "a report on costed episodes".to_string(),
        why: "it needs learner = amrl-q or belief, and [costly] price",
    };
    let Some(costly) = settings.costly else {
        return Err(refuse());
    };
    let whole: f64 = (0..world.num_features() as u32)
        .map(|f| world.price(mdp::Feature(f)))
        .sum();
    let whole_state_price = costly.price * whole;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed);
    let play = crate::learners::amrl::Episodes {
        episodes: settings.max_trials.get(),
        max_moves: settings.max_moves.get(),
    };
    let played = match &settings.learner {
        LearnerSettings::AmrlQ(params) => crate::learners::amrl::amrl_q_observed(
            world,
            params,
            whole_state_price,
            costly.rule,
            play,
            &mut rng,
            observer,
        ),
        LearnerSettings::Belief(params) => crate::learners::belief::belief_planning_observed(
            world,
            params,
            costly.price,
            costly.rule,
            play,
            &mut rng,
            observer,
        )?,
        _ => return Err(refuse()),
    };
    Ok(CostedReport {
        map: name.to_string(),
        learner: kind,
        seed: settings.seed,
        whole_state_price,
        costly: CostedRun::of(costly, &played),
        settings: settings.clone(),
    })
}

/// [`costed_report`] in the world resolved from `settings` (a grid map sensed as the
/// settings say, or a world beyond grids): what `csrl run --learner amrl-q` and
/// `--learner belief` print.
///
/// ```
/// let s = csql::SettingsDraft::from_toml("map = \"frozenlake4x4\"\nlearner = \"belief\"\nepisodes = 30\n[world]\nsensing = \"factors\"\n[costly]\nprice = 0.025", "f")
///     .unwrap()
///     .build()
///     .unwrap();
/// let r = csql::costed_report_in(&csql::Resolved::new(&s).unwrap(), &s, &mut csql::KeepTrace).unwrap();
/// assert_eq!((r.map.as_str(), r.costly.returns.len()), ("frozenlake4x4", 30));
/// ```
pub fn costed_report_in(
    resolved: &crate::settings::resolve::Resolved,
    settings: &RunSettings,
    observer: &mut dyn Observer,
) -> Result<CostedReport, Error> {
    match resolved {
        crate::settings::resolve::Resolved::Grid(setup) => costed_report(
            &setup.sensed(settings),
            setup.map.name(),
            settings,
            observer,
        ),
        crate::settings::resolve::Resolved::Finite { world, .. } => {
            costed_report(world, world.name(), settings, observer)
        }
    }
}

/// One call of [`costed_episodes`], its arguments checked.
struct Play<'a, W: ?Sized> {
    world: &'a W,
    settings: &'a RunSettings,
    rule: SensingRule,
    reward_per_cost: f64,
    episodes: u32,
}

impl<W: World + ?Sized> Play<'_, W> {
    fn run<P: WouldRead, S: Strategy>(
        &self,
        perception: P,
        strategy: S,
        table: QTable,
    ) -> Vec<Episode> {
        let world = self.world;
        let mut agent: Agent<P, S> =
            crate::agent::main_loop::agent_of(perception, strategy, table, self.settings);
        // The run's generator, drawn from as `csql::run` draws: a start, then the trial.
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(self.settings.seed);
        let mut out = Vec::with_capacity(self.episodes as usize);
        for trial in 1..=self.episodes {
            let start = world.sample_start(&mut rng);
            let mut t = agent.begin_trial(world, start, trial);
            let mut e = Episode {
                measurements: u32::from(t.rec.cost > 0.0),
                ..Episode::default()
            };
            let mut cost = t.rec.cost;
            while !t.over {
                let m = agent.choose(&mut t, &mut rng);
                let mut step = world.sample(t.state, m.action, &mut rng);
                step.truncated |= t.rec.moves + 1 >= agent.params.max_moves;
                let (before, from) = (t.rec.cost, t.row);
                let with_move = step.terminated && self.rule == SensingRule::WithMove;
                if with_move {
                    agent
                        .perception
                        .before_outcome(from, m.action, &agent.table);
                }
                agent.observe(&mut t, world, m, step, &mut rng);
                let mut paid = t.rec.cost - before;
                if step.terminated {
                    e.reached_goal = step.reward > 0.0;
                    if with_move {
                        paid += agent.perception.would_read(
                            world,
                            from,
                            m.action,
                            step.next,
                            &agent.table,
                        );
                    }
                }
                e.measurements += u32::from(paid > 0.0);
                e.reward += step.reward;
                e.steps += 1;
                cost += paid;
            }
            // Nobody judges these episodes.
            agent.clear_journal();
            e.sensing = cost * self.reward_per_cost;
            out.push(e);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::learner::StrategyKind;
    use crate::{LearnerKind, RunSettings};

    fn lake(name: &str, slide: f64) -> mdp::FiniteWorld {
        let options = mdp::WorldOptions {
            slide: Some(slide),
            sensing: Some(mdp::SensingModel::Factors),
            ..Default::default()
        };
        mdp::builtin_world(name, &options).unwrap()
    }

    /// Under the second rule, the episodes are the run's trials: their sensing sums to
    /// the run's cost, and their moves to its moves.
    #[test]
    fn after_the_outcome_the_episodes_are_the_runs_trials() {
        for (learner, strategy) in [
            (LearnerKind::CsQl, StrategyKind::Resetting),
            (LearnerKind::CsQl, StrategyKind::Lazy),
            (LearnerKind::FullSensing, StrategyKind::Resetting),
        ] {
            let world = lake("frozenlake4x4", 0.5);
            let mut settings = RunSettings::tan1991("frozenlake4x4", strategy, 3);
            if learner != LearnerKind::CsQl {
                settings = settings.with_learner(learner);
            }
            let oracle = mdp::Oracle::solve_stochastic(&world, settings.gamma.get()).unwrap();
            let scene = crate::Scene::new(&world, &oracle, &oracle, "lake");
            let report = crate::run_in(&scene, &settings, &mut crate::KeepTrace).unwrap();
            let run = costed_episodes(
                &world,
                &settings,
                SensingRule::AfterOutcome,
                1.0,
                report.trials,
            )
            .unwrap();
            let sensing: f64 = run.iter().map(|e| e.sensing).sum();
            let moves: u64 = run.iter().map(|e| u64::from(e.steps)).sum();
            assert!(
                (sensing - report.total_cost).abs() < 1e-6,
                "{sensing} {report:?}"
            );
            assert_eq!(moves, report.moves, "{learner}");
        }
    }

    /// With the move, a move that ends an episode is charged; after the outcome it is
    /// not, and nothing else differs.
    #[test]
    fn with_the_move_the_last_move_is_charged() {
        let world = lake("frozenlake4x4", 0.0);
        let settings = RunSettings::tan1991("frozenlake4x4", StrategyKind::Resetting, 2);
        let with = costed_episodes(&world, &settings, SensingRule::WithMove, 0.025, 300).unwrap();
        let after =
            costed_episodes(&world, &settings, SensingRule::AfterOutcome, 0.025, 300).unwrap();
        for (w, a) in with.iter().zip(&after) {
            assert_eq!((w.reward, w.steps), (a.reward, a.steps));
            assert!(w.sensing >= a.sensing - 1e-12 && w.measurements >= a.measurements);
        }
        assert!(
            with.iter().map(|e| e.sensing).sum::<f64>()
                > after.iter().map(|e| e.sensing).sum::<f64>()
        );
        let full = settings.with_learner(LearnerKind::FullSensing);
        let with = costed_episodes(&world, &full, SensingRule::WithMove, 0.025, 50).unwrap();
        for e in &with {
            // Row and column after every move, the start's too, the last included.
            assert_eq!(e.measurements, e.steps + 1);
            assert!((e.sensing - 0.05 * f64::from(e.steps + 1)).abs() < 1e-9);
        }
    }

    #[test]
    fn other_learners_are_refused() {
        let world = lake("frozenlake4x4", 0.0);
        let settings = RunSettings::tan1991("frozenlake4x4", StrategyKind::Resetting, 2)
            .with_learner(LearnerKind::UTree);
        let err = costed_episodes(&world, &settings, SensingRule::WithMove, 0.025, 3)
            .unwrap_err()
            .to_string();
        assert!(err.contains("learner = u-tree"), "{err}");
    }
}
