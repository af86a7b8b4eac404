//! Sensing by belief: it learns the deterministic lake and then senses almost nothing, its runs
//! are its seed's, its prices scale, and bad settings are refused.

use csql::{BeliefParams, CostlySummary, belief_planning};
use mdp::{SensingModel, SensingRule, WorldOptions, builtin_world};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

fn lake(name: &str, slide: f64, price: f64) -> mdp::FiniteWorld {
    builtin_world(
        name,
        &WorldOptions {
            slide: Some(slide),
            sensing: Some(SensingModel::Factors),
            factor_costs: Some(vec![price, price]),
            ..Default::default()
        },
    )
    .unwrap()
}

/// A run at the world's own prices.
fn run(
    w: &mdp::FiniteWorld,
    p: &BeliefParams,
    rule: SensingRule,
    episodes: u32,
    seed: u64,
) -> Vec<csql::Episode> {
    run_at(w, p, 1.0, rule, episodes, seed)
}

/// A run with the world's costs priced at `price` reward units each.
fn run_at(
    w: &mdp::FiniteWorld,
    p: &BeliefParams,
    price: f64,
    rule: SensingRule,
    episodes: u32,
    seed: u64,
) -> Vec<csql::Episode> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    belief_planning(w, p, price, rule, episodes, 100, &mut rng).unwrap()
}

#[test]
fn on_the_deterministic_lake_it_ends_at_the_goal_sensing_almost_nothing() {
    let w = lake("frozenlake4x4", 0.0, 0.025);
    for rule in [SensingRule::WithMove, SensingRule::AfterOutcome] {
        let episodes = run(&w, &BeliefParams::default(), rule, 300, 2);
        let last = &episodes[250..];
        // The goal every time, by the shortest path and unmeasured but for a rare try of
        // a pair still worth learning.
        assert!(last.iter().all(|e| e.reached_goal), "{rule:?}");
        let plain = last
            .iter()
            .filter(|e| e.measurements == 0 && e.steps == 6)
            .count();
        assert!(plain >= 45, "{rule:?}: {plain} of 50");
        let s = CostlySummary::of(&episodes);
        assert!(s.mean_all > 0.9, "{rule:?}: {s:?}");
    }
}

#[test]
fn on_the_semi_slippery_lake_it_measures_less_than_every_move() {
    let w = lake("frozenlake4x4", 0.5, 0.025);
    let episodes = run(&w, &BeliefParams::default(), SensingRule::WithMove, 600, 1);
    // Always measuring scores 0.7375 at best; once learned, it pays less than half of
    // what measuring both coordinates with every move would.
    let last = &episodes[540..];
    let s = CostlySummary::of(last);
    assert!(s.mean_all > 0.85, "{s:?}");
    let paid: f64 = last.iter().map(|e| e.sensing).sum();
    let every: f64 = last.iter().map(|e| 0.05 * f64::from(e.steps)).sum();
    assert!(paid < every / 2.0, "{paid} against {every}");
}

#[test]
fn a_run_is_its_seed_and_prices_scale() {
    let w = lake("frozenlake4x4", 0.5, 0.025);
    let p = BeliefParams::default();
    let a = run(&w, &p, SensingRule::WithMove, 60, 7);
    assert_eq!(a, run(&w, &p, SensingRule::WithMove, 60, 7));
    assert_ne!(a, run(&w, &p, SensingRule::WithMove, 60, 8));
    // Prices given as costs of 1 each, priced at 0.025 reward units: the same run.
    let unit = lake("frozenlake4x4", 0.5, 1.0);
    assert_eq!(a, run_at(&unit, &p, 0.025, SensingRule::WithMove, 60, 7));
}

#[test]
fn whole_state_measurements_cost_the_sum_of_the_prices() {
    let w = lake("frozenlake4x4", 0.5, 0.025);
    let p = BeliefParams {
        whole_state: true,
        ..Default::default()
    };
    for e in run(&w, &p, SensingRule::WithMove, 100, 3) {
        assert!(
            (e.sensing - 0.05 * f64::from(e.measurements)).abs() < 1e-9,
            "{e:?}"
        );
    }
}

#[test]
fn bad_settings_are_refused_naming_them() {
    let w = lake("frozenlake4x4", 0.0, 0.025);
    let cases = [
        (
            BeliefParams {
                trust: 0,
                ..Default::default()
            },
            "trust",
        ),
        (
            BeliefParams {
                prior: 0.0,
                ..Default::default()
            },
            "prior",
        ),
        (
            BeliefParams {
                prior: f64::NAN,
                ..Default::default()
            },
            "prior",
        ),
        (
            BeliefParams {
                optimism: f64::INFINITY,
                ..Default::default()
            },
            "optimism",
        ),
        (
            BeliefParams {
                max_beliefs: 0,
                ..Default::default()
            },
            "max_beliefs",
        ),
    ];
    for (p, name) in cases {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
        let err =
            belief_planning(&w, &p, 1.0, SensingRule::WithMove, 5, 100, &mut rng).unwrap_err();
        assert!(err.to_string().contains(name), "{err}");
    }
    let p = BeliefParams::default();
    for (price, max_moves, name) in [
        (1.0, 0, "max_moves"),
        (-1.0, 100, "price"),
        (f64::NAN, 100, "price"),
    ] {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
        let err = belief_planning(&w, &p, price, SensingRule::WithMove, 5, max_moves, &mut rng)
            .unwrap_err();
        assert!(err.to_string().contains(name), "{err}");
    }
}

/// The learner `belief` of a run's settings: `[belief]` read, what it leaves to the lake
/// filled with the lake's own, echoed and read back, its price `[costly] price`, played by `costed_report` exactly as `belief_planning`
/// plays it, and refused by `csql::run`.
#[test]
fn the_learner_belief_of_a_runs_settings() {
    let text = "map = \"frozenlake4x4\"\nlearner = \"belief\"\nepisodes = 60\nseed = 8\n\
                [belief]\ntrust = 2\nwhole_state = true\n[world]\nsensing = \"factors\"\n\
                [costly]\nprice = 0.025\nrule = \"after-outcome\"";
    let s = csql::SettingsDraft::from_toml(text, "f")
        .unwrap()
        .build()
        .unwrap();
    let csql::LearnerSettings::Belief(p) = s.learner else {
        panic!("{:?}", s.learner)
    };
    assert_eq!(
        p,
        BeliefParams {
            trust: 2,
            whole_state: true,
            // The lake's own, which [belief] does not give.
            shared_moves: Some(48),
            blind_plans: Some(64),
            ..BeliefParams::default()
        }
    );
    // Echoed and read back.
    let echo = toml::to_string(&s).unwrap();
    assert!(
        echo.contains("[belief]") && !echo.contains("price_scale"),
        "{echo}"
    );
    assert_eq!(toml::from_str::<csql::RunSettings>(&echo).unwrap(), s);
    // Played as belief_planning plays it.
    let world = lake("frozenlake4x4", 0.0, 1.0);
    let r = csql::costed_report(&world, "frozenlake4x4", &s, &mut csql::KeepTrace).unwrap();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(8);
    let episodes = belief_planning(
        &world,
        &p,
        0.025,
        SensingRule::AfterOutcome,
        60,
        100,
        &mut rng,
    )
    .unwrap();
    assert_eq!(r.costly, csql::CostedRun::of(s.costly.unwrap(), &episodes));
    assert_eq!(
        (r.learner, r.whole_state_price),
        (csql::LearnerKind::Belief, 0.05)
    );
    // Not a learner of csql::run.
    let err = csql::run(&s).unwrap_err().to_string();
    assert!(err.contains("learner = belief"), "{err}");
    // Without [costly], refused.
    let mut unpriced = s;
    unpriced.costly = None;
    let err = unpriced.validate().unwrap_err().to_string();
    assert!(
        err.contains("learner = belief") && err.contains("[costly] price"),
        "{err}"
    );
}

/// Says no the `at`-th time it is asked whether to go on.
struct SayNoAt {
    asked: u32,
    at: u32,
}

impl csql::Observer for SayNoAt {
    fn keep_trace(&self) -> bool {
        false
    }

    fn trial(&mut self, _: &csql::TracePoint) -> csql::Flow {
        csql::Flow::Continue
    }

    fn keep_going(&mut self) -> bool {
        self.asked += 1;
        self.asked < self.at
    }
}

/// The largest plan the settings allow, on the slippery lake, takes minutes to build: the
/// plan being built asks the observer too, so a no ends the run within the plan, before
/// its first episode, rather than after it (which would end with an episode played).
#[test]
fn a_plan_being_built_stops_when_the_observer_says_so() {
    let text = "map = \"frozenlake4x4\"\nlearner = \"belief\"\nepisodes = 20\n\
                [world]\nslip = 0.6666666666666666\nsensing = \"factors\"\n\
                [costly]\nprice = 0.025\n\
                [belief]\nmax_beliefs = 1000000\nmax_uncertain = 64";
    let s = csql::SettingsDraft::from_toml(text, "f")
        .unwrap()
        .build()
        .unwrap();
    let resolved = csql::Resolved::new(&s).unwrap();
    // Asked once before the first episode, then while the plan is built.
    let mut no = SayNoAt { asked: 0, at: 3 };
    let report = csql::run_resolved(&resolved, &s, &mut no).unwrap();
    let played = report.episodes().unwrap();
    assert_eq!(played.costly.summary.episodes, 0);
    assert_eq!(no.asked, 3);
}
