//! Why a run ended without learning, and what to try: a report's `not_learned`, which
//! `csrl run` prints and its JSON carries.
//!
//! A run has learned when the oracle judged it converged, or when its policy quality
//! reached 0.95 and stayed there (specification 6.3). One that did neither ended for one
//! of four reasons: it was stopped from outside, its representation passed `max_rows`,
//! or it reached its trial cap, with or without a cause the run can see: no utility ever
//! fell (so the detector never fired and nothing was sensed), a temperature far below
//! the world's rewards, U-Tree's root never split, or moves that are random. Each cause
//! comes with the settings that address it; a built-in world's own settings
//! ([`crate::WorldDefaults`]) come first where the run did not use them.

use mdp::{ActionId, World};
use serde::Serialize;

use crate::judging::trials::Judging;
use crate::settings::defaults::WorldDefaults;
use crate::settings::extensions::DetectorKind;
use crate::settings::learner::{LearnerSettings, StrategyKind, UTreeParams};
use crate::settings::values::RunSettings;

/// Why a run ended without learning (neither converged nor at policy quality 0.95 kept
/// to its end), and the settings to try, each as a settings file writes it
/// (`temperature = 8`, `[extensions] detector = "action"`), the likeliest first.
///
/// ```
/// use csql::{RunSettings, StrategyKind};
/// // Taxi at the paper's settings (rewards from -10 to 20): nothing is ever sensed.
/// let mut s = RunSettings::tan1991("taxi", StrategyKind::Lazy, 1);
/// s.max_trials = csql::TrialCap::new(50).unwrap();
/// let report = csql::run(&s).unwrap();
/// let not = report.not_learned.unwrap();
/// assert!(not.why.contains("No utility ever decreased"), "{}", not.why);
/// assert_eq!(not.to_try[0], "temperature = 8");
/// assert!(not.to_try.contains(&"[extensions] detector = \"action\"".to_string()));
/// // The same world from its defaults learns, and says nothing.
/// let s = csql::SettingsDraft { map: Some("cliffwalking".into()), ..Default::default() };
/// assert!(csql::run(&s.build().unwrap()).unwrap().not_learned.is_none());
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NotLearned {
    /// Why, in sentences.
    pub why: String,
    /// Settings to try (`try` in JSON), the likeliest first; the text of an entry that is
    /// no setting says what to do instead.
    #[serde(rename = "try")]
    pub to_try: Vec<String>,
}

/// How a run ended: what [`diagnose`] reads.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Ending {
    pub judging: Judging,
    pub converged: bool,
    /// The policy quality reached 0.95 and stayed there to the end.
    pub kept_quality: bool,
    /// The final policy quality.
    pub quality: f64,
    pub trials: u32,
    /// The representation passed `max_rows`.
    pub capped: bool,
    /// Stopped from outside (Ctrl-C, SIGTERM, an observer).
    pub stopped: bool,
    /// Decreases detected over the whole run.
    pub decreases: u64,
    /// Rows of the final representation.
    pub descriptions: usize,
}

/// The rewards of a world's reachable transitions: the lowest, the largest in size, and
/// whether every move has one outcome.
struct Rewards {
    largest: f64,
    deterministic: bool,
}

impl Rewards {
    fn of<W: World + ?Sized>(world: &W) -> Rewards {
        let mut out = Vec::new();
        let (mut largest, mut deterministic) = (0.0f64, true);
        for s in world.states() {
            for a in 0..world.num_actions() as u32 {
                world.outcomes(s, ActionId(a), &mut out);
                deterministic &= out.len() <= 1;
                for (_, step) in &out {
                    largest = largest.max(step.reward.abs());
                }
            }
        }
        Rewards {
            largest,
            deterministic,
        }
    }
}

/// Settings to try, one per key, the first given for a key kept.
#[derive(Default)]
struct Tries(Vec<(String, String)>);

impl Tries {
    fn add(&mut self, key: &str, line: String) {
        if !self.0.iter().any(|(k, _)| k == key) {
            self.0.push((key.to_string(), line));
        }
    }
}

/// The most trials the diagnosis suggests (the trial cap the built-in worlds ask for at
/// most): beyond it, a run of a slow learner takes minutes.
const MANY_TRIALS: u32 = 200_000;

/// Why the run did not learn, and what to try; `None` if it learned.
pub(crate) fn diagnose<W: World + ?Sized>(
    world: &W,
    settings: &RunSettings,
    end: &Ending,
) -> Option<NotLearned> {
    if end.converged || end.kept_quality {
        return None;
    }
    let goal = match end.judging {
        Judging::Oracle => "converged",
        Judging::Quality => "kept policy quality 0.95",
    };
    let mut why: Vec<String> = Vec::new();
    let mut tries = Tries::default();
    let cap = settings.max_trials.get();
    if end.stopped {
        why.push(format!(
            "It was stopped from outside (Ctrl-C, SIGTERM or its observer) after {} trials, before it {goal}.",
            end.trials
        ));
        tries.add(
            "stop",
            format!("let it run to its trial cap (max_trials = {cap})"),
        );
        return Some(finish(why, tries));
    }
    if end.capped {
        why.push(format!(
            "Its representation passed max_rows = {} rows at trial {}, before it {goal}.",
            settings.max_rows, end.trials
        ));
        if !settings.world.sensor_noise().is_zero() && settings.cs_ql().is_some() {
            why.push(
                "Under sensor noise CS-QL makes a new description for every misreading."
                    .to_string(),
            );
            tries.add("reads", "[extensions] reads = 3".to_string());
            tries.add("confirm_new", "[extensions] confirm_new = 3".to_string());
        }
        tries.add(
            "world",
            "a smaller world, or settings that keep fewer descriptions".to_string(),
        );
        return Some(finish(why, tries));
    }
    let rewards = Rewards::of(world);
    let defaults = WorldDefaults::of_source(&settings.map);
    let temperature = settings.temperature.get();
    let beta = settings.beta.get();
    // A built-in world's own settings first, where the run did not use them.
    if let Some(own) = defaults.world {
        let mut differ = Vec::new();
        if own.temperature.is_some() && temperature != defaults.temperature.get() {
            differ.push("temperature");
            tries.add(
                "temperature",
                format!("temperature = {}", defaults.temperature.get()),
            );
        }
        let detector = defaults.detector_for(beta, &settings.world);
        if let Some(q) = settings.cs_ql()
            && own.detector.is_some()
            && rewards.deterministic
            && q.extensions.detector != detector
        {
            differ.push("detector");
            tries.add(
                "detector",
                format!("[extensions] detector = \"{}\"", detector.name()),
            );
        }
        if own.max_trials.is_some() && cap < defaults.max_trials.get() {
            differ.push("max_trials");
            tries.add(
                "max_trials",
                format!("max_trials = {}", defaults.max_trials.get()),
            );
        }
        if !differ.is_empty() {
            why.push(format!(
                "The run did not use the world's own {} (`csrl world show {}` says why).",
                differ.join(", "),
                settings.map,
            ));
        }
    }
    why.insert(
        0,
        format!(
            "It reached its trial cap, max_trials = {cap}, at policy quality {:.3}, without having {goal}.",
            end.quality
        ),
    );
    let scaled = 0.4 * rewards.largest;
    let cold = rewards.largest > 1.0 && temperature < scaled / 2.0;
    let never_refined = settings.cs_ql().is_some() && end.decreases == 0 && end.descriptions <= 1;
    match &settings.learner {
        LearnerSettings::CsQl(q) if never_refined => {
            let floor = crate::agent::main_loop::value_floor(world, settings.gamma.get());
            let mut text = "No utility ever decreased, so the detector never fired and nothing was sensed: one description stands for every state.".to_string();
            let penalties = rewards.deterministic && floor < 0.0;
            if penalties && q.extensions.detector != DetectorKind::Action {
                text.push_str(&format!(
                    " Q starts at the floor of the returns ({floor:.4}, specification 1.11), so in a deterministic world a utility only rises; a penalty that one state of a description pays for an action lowers that action's Q while V, the maximum, stays."
                ));
                if beta == 1.0 {
                    tries.add("detector", "[extensions] detector = \"action\"".to_string());
                }
            } else if !rewards.deterministic && q.extensions.detector != DetectorKind::Statistical {
                tries.add(
                    "detector",
                    "[extensions] detector = \"statistical\"".to_string(),
                );
            }
            why.push(text);
        }
        LearnerSettings::UTree(p) if end.descriptions <= 1 => {
            why.push("U-Tree never split its root: no distinction passed its test.".to_string());
            let looser = UTreeParams {
                alpha: 0.2,
                min_group: 2,
                patience: 100_000,
                ..*p
            };
            if *p != looser {
                tries.add(
                    "u_tree",
                    "[u_tree] alpha = 0.2, min_group = 2, patience = 100000".to_string(),
                );
            }
        }
        _ => {}
    }
    if cold {
        why.push(format!(
            "The temperature, {temperature}, is small for rewards of up to {} in size: once an action has paid a penalty, Boltzmann selection all but never tries it again (0.4 times the largest reward, {scaled}, keeps exploring).",
            rewards.largest
        ));
        tries.add("temperature", format!("temperature = {scaled}"));
    }
    if !rewards.deterministic || !settings.world.sensor_noise().is_zero() {
        why.push(format!(
            "Moves or readings are random here (slip, slide or sensor noise): a single decrease may be noise{}.",
            if beta > 0.1 {
                format!(", and at beta {beta} each sample moves Q a long way")
            } else {
                String::new()
            }
        ));
        if beta > 0.1 {
            tries.add("beta", "beta = 0.02".to_string());
        }
        if let Some(q) = settings.cs_ql()
            && q.extensions.detector != DetectorKind::Statistical
        {
            tries.add(
                "detector",
                "[extensions] detector = \"statistical\"".to_string(),
            );
        }
    }
    if !never_refined && settings.cs_ql().map(|q| q.strategy) == Some(StrategyKind::Resetting) {
        why.push("The resetting strategy starts every Q again at each refinement and needs many more trials than the others.".to_string());
    }
    // More trials do not help a run that no penalty can refine at its temperature, and
    // past a cap of MANY_TRIALS they would take minutes.
    let stuck = never_refined && (cold || tries.0.iter().any(|(k, _)| k == "detector"));
    if !stuck && cap < MANY_TRIALS {
        tries.add(
            "max_trials",
            format!("max_trials = {}", (cap.saturating_mul(10)).min(MANY_TRIALS)),
        );
    }
    if tries.0.is_empty() {
        why.push("No setting known to the run is sure to help: the learner may not be able to represent what this world needs (docs/worlds.md has what was measured).".to_string());
    }
    Some(finish(why, tries))
}

fn finish(why: Vec<String>, tries: Tries) -> NotLearned {
    NotLearned {
        why: why.join(" "),
        to_try: tries.0.into_iter().map(|(_, line)| line).collect(),
    }
}
