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

use mdp::{SensingRule, StateId, World};
use qlearn::QTable;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use crate::amrl::Episode;
use crate::classify::Classify;
use crate::error::Error;
use crate::learner::Learner;
use crate::main_loop::Agent;
use crate::perception::{FullView, Perception};
use crate::predict::level::PredictSensing;
use crate::settings::RunSettings;
use crate::strategy::{Never, Strategy};

/// What a perception would read classifying a state, learning nothing: the charge of a
/// move that ends an episode under [`SensingRule::WithMove`].
trait WouldRead: Perception {
    fn would_read<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> f64;
}

impl WouldRead for Classify {
    fn would_read<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> f64 {
        self.lookup_cost(world, s)
    }
}

impl WouldRead for FullView {
    fn would_read<W: World + ?Sized>(&mut self, world: &W, s: StateId) -> f64 {
        FullView::cost_of(world, s)
    }
}

/// Play the learner of `settings` (CS-QL without prediction or memory, or full sensing)
/// for exactly `episodes` episodes of at most `settings.max_moves` moves in `world`, and
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
    crate::resolve::check_with_world(
        settings,
        crate::quality::is_deterministic(world),
        world.grid().is_some(),
    )?;
    crate::resolve::check_size(settings, world)?;
    let refuse = |what: String, why: &'static str| Error::Conflict {
        first: "costed episodes".to_string(),
        second: what,
        why,
    };
    // Q and V start at the floor of the world's returns, as in `csql::run`.
    let floor = crate::quality::value_floor(world, settings.gamma.get());
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
        Learner::FullSensing => Ok(play.run(FullView::new(world), Never, table)),
        Learner::CsQl(q) => {
            if q.predict_sensing != PredictSensing::Off || q.extensions.memory > 0 {
                return Err(refuse(
                    "predict_sensing or memory".to_string(),
                    "they are scored for CS-QL classifying every state it reaches",
                ));
            }
            // CLASSIFY as `csql::run` builds it: the sensors' own generator, the run's
            // 2^128 draws ahead (drawn from only under sensor noise).
            let mut sensor_rng = Xoshiro256PlusPlus::seed_from_u64(settings.seed);
            sensor_rng.jump();
            let classify = Classify::new(world)
                .with_noise(settings.world.sensor_noise, sensor_rng)
                .with_extensions(&settings.extensions());
            Ok(play.run(classify, q.strategy.build(q.random_moves), table))
        }
        other => Err(refuse(
            format!("learner = {}", other.kind()),
            "they are scored for cs-ql, full-sensing and amrl-q",
        )),
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
            crate::learn::agent_of(perception, strategy, table, self.settings);
        // The run's generator, drawn from as `csql::run` draws: a start, then the trial.
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(self.settings.seed);
        let mut out = Vec::with_capacity(self.episodes as usize);
        for trial in 1..=self.episodes {
            let start = world.sample_start(&mut rng);
            let mut t = agent.begin_trial(world, start, trial);
            let mut e = Episode {
                reward: 0.0,
                sensing: 0.0,
                measurements: u32::from(t.rec.cost > 0.0),
                steps: 0,
                reached_goal: false,
            };
            let mut cost = t.rec.cost;
            while !t.over {
                let m = agent.choose(&mut t, &mut rng);
                let mut step = world.sample(t.state, m.action, &mut rng);
                step.truncated |= t.rec.moves + 1 >= agent.params.max_moves;
                let before = t.rec.cost;
                agent.observe(&mut t, world, m, step, &mut rng);
                let mut paid = t.rec.cost - before;
                if step.terminated {
                    e.reached_goal = step.reward > 0.0;
                    if self.rule == SensingRule::WithMove {
                        paid += agent.perception.would_read(world, step.next);
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
    use crate::strategy::StrategyKind;
    use crate::{LearnerKind, RunSettings};

    fn lake(name: &str, slide: f64) -> mdp::FiniteWorld {
        let options = mdp::WorldOptions {
            slide,
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
