//! Plans over beliefs: the plan's value at the start is the reference search's, its
//! choices can be followed step by step, a learned model's tables are checked, and a
//! pair that must be measured is taken from a known state only; an open-loop plan pays for
//! its moves.

use rand::SeedableRng;

use mdp::{
    ActionId, BeliefPlan, CostlyModel, Decision, ModelParts, PlanOptions, ReferenceOptions,
    SensingMenu, SensingModel, SensingRule, Sensors, StateId, StochasticMdp, WorldOptions,
    best_sensing, builtin_world,
};

fn lake(slide: f64) -> mdp::FiniteWorld {
    builtin_world(
        "frozenlake4x4",
        &WorldOptions {
            slide: Some(slide),
            sensing: Some(SensingModel::Factors),
            factor_costs: Some(vec![0.025, 0.025]),
            ..Default::default()
        },
    )
    .unwrap()
}

#[test]
fn the_plan_values_the_start_as_the_reference_search_does() {
    let w = lake(0.5);
    let m = CostlyModel::of(&w).unwrap();
    for menu in [SensingMenu::Features, SensingMenu::Whole { price: 0.05 }] {
        for rule in [SensingRule::WithMove, SensingRule::AfterOutcome] {
            for k in [0, 1, 3] {
                let search = ReferenceOptions {
                    max_uncertain: Some(k),
                    ..Default::default()
                };
                let best = best_sensing(&w, menu, rule, &search).unwrap();
                let o = PlanOptions {
                    menu,
                    rule,
                    search,
                    move_cost: 0.0,
                    tolerance: 0.0,
                    blind_plans: 0,
                };
                let plan = BeliefPlan::build(&m, &o, &[StateId(0)]).unwrap();
                let v = plan.value(plan.point(StateId(0)).unwrap());
                assert_eq!(v, best.value, "{menu:?} {rule:?} K = {k}");
                assert_eq!(plan.nodes(), best.beliefs, "{menu:?} {rule:?} K = {k}");
            }
        }
    }
}

/// Follow the plan in the true world from the start, exactly (every outcome weighted):
/// the expected costed return of following it (less its price per move) equals its
/// value. The price per move keeps the plan from wandering between equal choices.
#[test]
fn following_the_plan_step_by_step_earns_its_value() {
    let w = lake(0.5);
    let m = CostlyModel::of(&w).unwrap();
    let o = PlanOptions {
        search: ReferenceOptions {
            horizon: 30,
            max_uncertain: Some(3),
            ..Default::default()
        },
        move_cost: 1e-6,
        ..Default::default()
    };
    let plan = BeliefPlan::build(&m, &o, &[StateId(0)]).unwrap();
    let start = plan.point(StateId(0)).unwrap();
    // (probability, true state, node, moves left)
    let mut frontier = vec![(1.0, 0u32, start, 30u32)];
    let mut total = 0.0;
    let mut out = Vec::new();
    while let Some((p, s, node, left)) = frontier.pop() {
        if left == 0 {
            continue;
        }
        let (c, Decision::Move { action, measure }) = plan.decide(node).unwrap() else {
            panic!("with the move every choice is a move")
        };
        let price = 0.025 * f64::from(measure.count_ones()) + 1e-6;
        total -= p * price;
        w.outcomes(StateId(s), action, &mut out);
        for (q, step) in out.clone() {
            if q == 0.0 {
                continue;
            }
            total += p * q * step.reward;
            if step.terminated || w.is_terminal(step.next) {
                continue;
            }
            let t = step.next;
            let next = plan
                .follow(node, c, |f| w.read(t, f.unwrap()).0)
                .expect("the true model never contradicts its plan");
            assert!(plan.belief(next).iter().any(|&(x, _)| x == t));
            frontier.push((p * q, t.0, next, left - 1));
        }
    }
    assert!(
        (total - plan.value(start)).abs() < 1e-7,
        "{total} vs {}",
        plan.value(start)
    );
    assert!((plan.value(start) - 0.95).abs() < 1e-4); // the reference figure, less moves
}

fn one_state(must_measure: bool) -> ModelParts {
    // States 0 and 1 read alike on feature 0 and apart on feature 1; action 0 from
    // either goes to 0 or 1 with equal odds, action 1 ends the episode with reward 1.
    ModelParts {
        num_actions: 2,
        terminal: vec![false, false],
        reward: vec![0.0, 1.0, 0.0, 1.0],
        next: vec![
            vec![(0, 0.5), (1, 0.5)],
            vec![],
            vec![(0, 0.5), (1, 0.5)],
            vec![],
        ],
        must_measure: vec![false, must_measure, false, false],
        prices: vec![0.1, 0.2],
        readings: vec![0, 0, 0, 1],
        start: vec![(1.0, 0)],
    }
}

#[test]
fn a_pair_that_must_be_measured_is_taken_from_a_known_state_only() {
    let o = PlanOptions {
        search: ReferenceOptions {
            horizon: 3,
            ..Default::default()
        },
        ..Default::default()
    };
    // Free to act on the belief: stay (action 0), unmeasured, then end with reward 1.
    let free = BeliefPlan::build(
        &CostlyModel::from_parts(one_state(false)).unwrap(),
        &o,
        &[StateId(1)],
    )
    .unwrap();
    let at1 = free.point(StateId(1)).unwrap();
    assert_eq!(free.value(at1), 1.0);
    // Pair (0, 1) must be measured: from the belief {0, 1} action 1 is not allowed, so
    // the plan ends at once from 1 (action 1 there is free).
    let forced = BeliefPlan::build(
        &CostlyModel::from_parts(one_state(true)).unwrap(),
        &o,
        &[StateId(0), StateId(1)],
    )
    .unwrap();
    let at0 = forced.point(StateId(0)).unwrap();
    // From 0 known, action 1 is allowed, and every feature is paid with it.
    assert_eq!(
        forced.decide(at0).unwrap().1,
        Decision::Move {
            action: ActionId(1),
            measure: mdp::EVERY_PROBE
        }
    );
    assert!((forced.value(at0) - (1.0 - 0.3)).abs() < 1e-12);
}

#[test]
fn bad_tables_are_refused_with_where() {
    type Spoil = Box<dyn Fn(&mut ModelParts)>;
    let cases: Vec<(Spoil, &str)> = vec![
        (
            Box::new(|p| p.reward.pop().map(drop).unwrap_or(())),
            "reward has 3 entries",
        ),
        (Box::new(|p| p.next[0] = vec![(1, 0.5), (0, 0.5)]), "sorted"),
        (Box::new(|p| p.next[0] = vec![(0, 0.8), (1, 0.8)]), "sum to"),
        (Box::new(|p| p.next[0] = vec![(5, 1.0)]), "state 5"),
        (
            Box::new(|p| p.prices[1] = f64::NAN),
            "feature 1 has price NaN",
        ),
        (
            Box::new(|p| p.readings.pop().map(drop).unwrap_or(())),
            "readings has 3 entries",
        ),
        (Box::new(|p| p.start = vec![(1.0, 7)]), "start"),
        (
            Box::new(|p| p.reward[1] = f64::INFINITY),
            "state 0, action 1: reward inf",
        ),
    ];
    for (spoil, wanted) in cases {
        let mut p = one_state(false);
        spoil(&mut p);
        let err = CostlyModel::from_parts(p).unwrap_err().to_string();
        assert!(err.contains(wanted), "{err} lacks {wanted}");
    }
    let m = CostlyModel::from_parts(one_state(false)).unwrap();
    let err = BeliefPlan::build(&m, &PlanOptions::default(), &[StateId(9)])
        .err()
        .unwrap();
    assert!(err.to_string().contains("state 9"), "{err}");
    let o = PlanOptions {
        move_cost: -1.0,
        ..Default::default()
    };
    let err = BeliefPlan::build(&m, &o, &[StateId(0)]).err().unwrap();
    assert!(err.to_string().contains("move_cost"), "{err}");
}

/// A graph counted past its bound on bytes stops with an error that says so and what it
/// held; the same search under the bound builds the same plan as with the default bound,
/// and what the plan holds is counted at most at its bound.
#[test]
fn a_plan_past_its_bound_on_bytes_stops_with_what_it_held() {
    let w = lake(0.5);
    let m = CostlyModel::of(&w).unwrap();
    let search = ReferenceOptions {
        max_uncertain: Some(3),
        ..Default::default()
    };
    let o = PlanOptions {
        rule: SensingRule::AfterOutcome,
        search,
        ..Default::default()
    };
    let roots = [StateId(0)];
    let plan = BeliefPlan::build(&m, &o, &roots).unwrap();
    let size = plan.size();
    assert_eq!(size.beliefs, plan.nodes());
    assert!(size.bytes() <= mdp::DEFAULT_MAX_PLAN_BYTES);
    // Bounded just at what it is counted at, it is the same plan; a byte less, refused.
    let at = |max_bytes| PlanOptions {
        search: ReferenceOptions {
            max_bytes,
            ..search
        },
        ..o
    };
    let same = BeliefPlan::build(&m, &at(size.bytes()), &roots).unwrap();
    assert_eq!(same.size(), size);
    let start = plan.point(StateId(0)).unwrap();
    assert_eq!(same.value(start), plan.value(start));
    match BeliefPlan::build(&m, &at(size.bytes() - 1), &roots) {
        Err(e @ mdp::ReferenceError::TooLarge { .. }) => {
            let text = e.to_string();
            assert!(
                text.starts_with(&format!(
                    "the belief graph would pass {} bytes",
                    size.bytes() - 1
                )) && text.contains("with at most 3 uncertain steps in a row"),
                "{text}"
            );
        }
        other => panic!(
            "a byte under what the plan is counted at: {:?}",
            other.map(|p| p.size())
        ),
    }
    // The reference search is bounded alike.
    let tiny = ReferenceOptions {
        max_bytes: 1000,
        ..search
    };
    let err = best_sensing(&w, SensingMenu::Features, SensingRule::WithMove, &tiny).unwrap_err();
    assert!(matches!(err, mdp::ReferenceError::TooLarge { .. }), "{err}");
}

/// An open-loop plan pays the price per move as every other choice of the plan does: on
/// the deterministic lake, from the start, it walks the shortest way (six moves), where
/// without that price a plan that dawdles and reaches the goal only after the episode's
/// last move would tie with it.
#[test]
fn an_open_loop_plan_walks_the_shortest_way() {
    let lake = lake(0.0);
    let model = CostlyModel::of(&lake).unwrap();
    let opts = PlanOptions {
        blind_plans: 64,
        move_cost: 1e-6,
        ..PlanOptions::default()
    };
    let plan = BeliefPlan::build(&model, &opts, &[StateId(0)]).unwrap();
    let start = plan.point(StateId(0)).unwrap();
    let moves = plan.blind_moves(start).unwrap();
    let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
    let mut s = StateId(0);
    let mut reached = None;
    for (i, &a) in moves.iter().enumerate() {
        let step = lake.sample(s, a, &mut rng);
        if step.terminated || lake.is_terminal(step.next) {
            reached = Some((i + 1, step.reward));
            break;
        }
        s = step.next;
    }
    assert_eq!(reached, Some((6, 1.0)));
}
