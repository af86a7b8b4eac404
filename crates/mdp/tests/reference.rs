//! The reference points of costly sensing, checked against brute force on tiny worlds
//! and against the figures of the FrozenLake benchmark.

use mdp::{
    FiniteWorld, OutcomeSpec, ReferenceError, ReferenceOptions, SensingMenu, SensingModel,
    SensingRule, WorldOptions, WorldSpec, always_measuring, best_sensing, builtin_world, open_loop,
    reference_points,
};
use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

const EPS: f64 = 1e-9;

/// States that read alike on a probe set, with their probabilities.
type Group = (Vec<u32>, Vec<(usize, f64)>);

/// A tiny random world: `live` non-terminal states (0 starts), a goal (reward 1) and a
/// hole after them, `na` actions each with up to three outcomes (a small step reward on
/// some), and two binary features: bit 0 and bit 1 of the state id, priced `prices`.
fn tiny(seed: u64, live: u32, na: u32, prices: [f64; 2]) -> FiniteWorld {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let n = live + 2;
    let (goal, hole) = (live, live + 1);
    let mut transitions = Vec::new();
    for s in 0..live {
        for a in 0..na {
            let k = rng.random_range(1..=3u32);
            let mut weights: Vec<f64> = (0..k).map(|_| rng.random_range(1..=4u32) as f64).collect();
            let total: f64 = weights.iter().sum();
            for w in &mut weights {
                *w /= total;
            }
            let outs: Vec<OutcomeSpec> = weights
                .iter()
                .map(|&p| {
                    let next = rng.random_range(0..n);
                    let reward = if next == goal {
                        1.0
                    } else if rng.random_bool(0.2) {
                        -0.1
                    } else {
                        0.0
                    };
                    (p, next, reward, next == goal || next == hole)
                })
                .collect();
            transitions.push((s, a, outs));
        }
    }
    let spec = WorldSpec {
        format: "csrl-world".into(),
        version: 1,
        name: format!("tiny{seed}"),
        states: mdp::StatesSpec::Count(n as u64),
        actions: (0..na).map(|a| format!("a{a}")).collect(),
        start: vec![(1.0, 0)],
        terminal: vec![goal, hole],
        transitions,
        features: vec![
            mdp::FeatureSpec {
                name: "bit0".into(),
                price: prices[0],
                readings: vec![],
            },
            mdp::FeatureSpec {
                name: "bit1".into(),
                price: prices[1],
                readings: vec![],
            },
        ],
        readings: (0..n).map(|s| vec![s & 1, (s >> 1) & 1]).collect(),
    };
    FiniteWorld::new(spec).unwrap()
}

/// The model as plain tables: per (s, a) the outcomes `(p, next, reward, terminal)`.
struct Plain {
    na: usize,
    outs: Vec<Vec<(f64, usize, f64, bool)>>,
    read: Vec<[u32; 2]>,
    prices: [f64; 2],
}

fn plain(w: &FiniteWorld) -> Plain {
    use mdp::{ActionId, Feature, Sensors, StateId, StochasticMdp};
    let n = w.num_states();
    let na = w.num_actions();
    let mut outs = Vec::new();
    let mut o = Vec::new();
    for s in 0..n {
        for a in 0..na {
            w.outcomes(StateId(s as u32), ActionId(a as u32), &mut o);
            outs.push(
                o.iter()
                    .map(|(p, st)| (*p, st.next.index(), st.reward, st.terminated))
                    .collect(),
            );
        }
    }
    let read = (0..n)
        .map(|s| [0, 1].map(|f| w.read(StateId(s as u32), Feature(f)).0))
        .collect();
    let prices = [0, 1].map(|f| w.price(Feature(f)));
    Plain {
        na,
        outs,
        read,
        prices,
    }
}

/// Every plan of `h` actions, its expected return simulated forward.
fn brute_open_loop(p: &Plain, h: u32) -> f64 {
    let plans = (p.na as u64).pow(h);
    let mut best = f64::NEG_INFINITY;
    for code in 0..plans {
        let mut c = code;
        let mut dist: Vec<(usize, f64)> = vec![(0, 1.0)];
        let mut ret = 0.0;
        for _ in 0..h {
            let a = (c % p.na as u64) as usize;
            c /= p.na as u64;
            let mut next = Vec::new();
            for &(s, q) in &dist {
                for &(pr, t, r, term) in &p.outs[s * p.na + a] {
                    ret += q * pr * r;
                    if !term {
                        next.push((t, q * pr));
                    }
                }
            }
            dist = next;
        }
        best = best.max(ret);
    }
    best
}

/// Every Markov policy (a move for every step and state), measuring the whole state at
/// `c` after every move; evaluated exactly.
fn brute_always(p: &Plain, live: usize, h: u32, c: f64, rule: SensingRule) -> f64 {
    let choices = (p.na as u64).pow(live as u32 * h);
    let mut best = f64::NEG_INFINITY;
    for code in 0..choices {
        let action = |step: u32, s: usize| -> usize {
            let digit = step as u64 * live as u64 + s as u64;
            ((code / (p.na as u64).pow(digit as u32)) % p.na as u64) as usize
        };
        let mut dist: Vec<(usize, f64)> = vec![(0, 1.0)];
        let mut ret = 0.0;
        for step in 0..h {
            let mut next = Vec::new();
            for &(s, q) in &dist {
                if rule == SensingRule::WithMove {
                    ret -= q * c;
                }
                for &(pr, t, r, term) in &p.outs[s * p.na + action(step, s)] {
                    ret += q * pr * r;
                    if !term {
                        if rule == SensingRule::AfterOutcome && step + 1 < h {
                            ret -= q * pr * c;
                        }
                        next.push((t, q * pr));
                    }
                }
            }
            dist = next;
        }
        best = best.max(ret);
    }
    best
}

/// What a probe set reads on a state: the state itself for the whole state.
fn reads(p: &Plain, whole: bool, set: u32, s: usize) -> Vec<u32> {
    if whole {
        if set == 0 { vec![] } else { vec![s as u32] }
    } else {
        (0..2)
            .filter(|f| set >> f & 1 == 1)
            .map(|f| p.read[s][f as usize])
            .collect()
    }
}

/// What the brute force searches: the menu, the rule, the bound on uncertain steps and
/// whether the state is told for free past it (the relaxation of `sensing_ceiling`).
#[derive(Clone, Copy)]
struct Setup {
    whole: bool,
    rule: SensingRule,
    k: u32,
    reveal: bool,
}

/// Every sensing rule and menu of `w` (the whole state, or its features apart), each with
/// the brute force's setup for it: free to stay uncertain as long as it likes, nothing
/// told for free.
fn rules_and_menus(w: &FiniteWorld) -> Vec<(SensingRule, bool, SensingMenu, Setup)> {
    let mut all = Vec::new();
    for rule in [SensingRule::WithMove, SensingRule::AfterOutcome] {
        for whole in [true, false] {
            let menu = if whole {
                SensingMenu::whole(w)
            } else {
                SensingMenu::Features
            };
            let free = Setup {
                whole,
                rule,
                k: u32::MAX - 1,
                reveal: false,
            };
            all.push((rule, whole, menu, free));
        }
    }
    all
}

fn certain(d: &[(usize, f64)]) -> bool {
    let mut s: Vec<usize> = d.iter().filter(|x| x.1 > 0.0).map(|x| x.0).collect();
    s.sort();
    s.dedup();
    s.len() <= 1
}

/// The relaxation: the state of an uncertain `info` told, free.
fn told(p: &Plain, u: Setup, info: &[(usize, f64)], h: u32) -> f64 {
    info.iter()
        .map(|&(s, q)| brute_best(p, u, &[(s, q)], h, 0))
        .sum()
}

/// Group states by what a probe set reads.
fn groups(p: &Plain, whole: bool, set: u32, info: &[(usize, f64)]) -> Vec<Group> {
    let mut groups: Vec<Group> = Vec::new();
    for &(t, q) in info {
        let r = reads(p, whole, set, t);
        match groups.iter_mut().find(|g| g.0 == r) {
            Some(g) => g.1.push((t, q)),
            None => groups.push((r, vec![(t, q)])),
        }
    }
    groups
}

/// The optimum over every policy, by recursion over every history of what the agent
/// saw: `info` is the unnormalised distribution of the state given that history (no
/// beliefs are merged and nothing is rounded); `uncertain` counts the steps in a row
/// that left the agent uncertain, at most `u.k`.
fn brute_best(p: &Plain, u: Setup, info: &[(usize, f64)], h: u32, uncertain: u32) -> f64 {
    if h == 0 || info.is_empty() {
        return 0.0;
    }
    let price = |set: u32| -> f64 {
        if u.whole {
            if set == 0 {
                0.0
            } else {
                p.prices[0] + p.prices[1]
            }
        } else {
            (0..2)
                .filter(|f| set >> f & 1 == 1)
                .map(|f| p.prices[f as usize])
                .sum()
        }
    };
    let sets: Vec<u32> = if u.whole {
        vec![0, 1]
    } else {
        vec![0, 1, 2, 3]
    };
    let mut best = f64::NEG_INFINITY;
    for a in 0..p.na {
        let mut gain = 0.0;
        let mut next: Vec<(usize, f64)> = Vec::new();
        for &(s, q) in info {
            for &(pr, t, r, term) in &p.outs[s * p.na + a] {
                gain += q * pr * r;
                if !term {
                    next.push((t, q * pr));
                }
            }
        }
        let mass: f64 = info.iter().map(|x| x.1).sum();
        match u.rule {
            SensingRule::WithMove => {
                for &set in &sets {
                    let mut v = gain - mass * price(set);
                    let mut ok = true;
                    for (_, g) in &groups(p, u.whole, set, &next) {
                        let c = certain(g);
                        if !c && uncertain >= u.k {
                            if u.reveal {
                                v += told(p, u, g, h - 1);
                                continue;
                            }
                            ok = false;
                            break;
                        }
                        v += brute_best(p, u, g, h - 1, if c { 0 } else { uncertain + 1 });
                    }
                    if ok {
                        best = best.max(v);
                    }
                }
            }
            SensingRule::AfterOutcome => {
                let v = gain + brute_sense(p, u, &next, h - 1, uncertain + 1, 0);
                best = best.max(v);
            }
        }
    }
    best
}

/// After a move (the other rule): stop, or measure one more probe not yet measured.
fn brute_sense(
    p: &Plain,
    u: Setup,
    info: &[(usize, f64)],
    h: u32,
    uncertain: u32,
    done: u32,
) -> f64 {
    if h == 0 || info.is_empty() {
        return 0.0;
    }
    let c = certain(info);
    let mut best = f64::NEG_INFINITY;
    if c || uncertain <= u.k {
        best = brute_best(p, u, info, h, if c { 0 } else { uncertain });
    } else if u.reveal {
        best = told(p, u, info, h);
    }
    let mass: f64 = info.iter().map(|x| x.1).sum();
    let probes: Vec<u32> = if u.whole { vec![1] } else { vec![1, 2] };
    for probe in probes {
        if done & probe != 0 {
            continue;
        }
        let price = if u.whole {
            p.prices[0] + p.prices[1]
        } else {
            p.prices[(probe - 1) as usize]
        };
        let mut v = -mass * price;
        for (_, g) in &groups(p, u.whole, probe, info) {
            v += brute_sense(p, u, g, h, uncertain, done | probe);
        }
        best = best.max(v);
    }
    best
}

fn options(h: u32, k: Option<u32>) -> ReferenceOptions {
    ReferenceOptions {
        horizon: h,
        max_uncertain: k,
        ..ReferenceOptions::default()
    }
}

#[test]
fn open_loop_is_the_best_of_every_plan() {
    for seed in 0..12 {
        let w = tiny(seed, 4, 2 + (seed % 2) as u32, [0.05, 0.1]);
        let p = plain(&w);
        for h in 1..=5 {
            let got = open_loop(&w, &options(h, None)).unwrap();
            assert!(got.exact);
            let want = brute_open_loop(&p, h);
            assert!(
                (got.value - want).abs() < EPS,
                "seed {seed} h {h}: {} vs {want}",
                got.value
            );
        }
    }
}

#[test]
fn always_measuring_is_the_best_of_every_policy_that_measures_every_move() {
    for seed in 0..8 {
        let w = tiny(seed, 3, 2, [0.05, 0.1]);
        let p = plain(&w);
        for h in 1..=4 {
            for rule in [SensingRule::WithMove, SensingRule::AfterOutcome] {
                for menu in [SensingMenu::Features, SensingMenu::Whole { price: 0.07 }] {
                    let c = menu.whole_price(&w);
                    let got = always_measuring(&w, menu, rule, &options(h, None)).unwrap();
                    let want = brute_always(&p, 3, h, c, rule);
                    assert!(
                        (got - want).abs() < EPS,
                        "seed {seed} h {h} {rule:?}: {got} vs {want}"
                    );
                }
            }
        }
    }
}

#[test]
fn best_sensing_is_the_best_of_every_policy() {
    for seed in 0..10 {
        let w = tiny(seed, 4, 2, [0.03, 0.08]);
        let p = plain(&w);
        for h in 1..=4 {
            for k in [Some(0), Some(1), Some(2), None] {
                for (rule, whole, menu, free) in rules_and_menus(&w) {
                    let got = best_sensing(&w, menu, rule, &options(h, k)).unwrap().value;
                    let u = Setup {
                        k: k.unwrap_or(free.k),
                        ..free
                    };
                    let want = brute_best(&p, u, &[(0, 1.0)], h, 0);
                    assert!(
                        (got - want).abs() < EPS,
                        "seed {seed} h {h} k {k:?} {rule:?} whole {whole}: {got} vs {want}"
                    );
                }
            }
        }
    }
}

#[test]
fn the_reference_points_are_ordered() {
    // Measuring optionally is at least as good as always measuring and as the open loop
    // (with no bound on uncertain steps), and sensing after the outcome at least as good
    // as with the move.
    for seed in 0..10 {
        let w = tiny(seed, 4, 3, [0.02, 0.04]);
        for h in [3, 6] {
            let o = options(h, None);
            for menu in [SensingMenu::whole(&w), SensingMenu::Features] {
                let with = reference_points(&w, menu, SensingRule::WithMove, &o).unwrap();
                let after = reference_points(&w, menu, SensingRule::AfterOutcome, &o).unwrap();
                for r in [&with, &after] {
                    assert!(r.best_sensing.value >= r.always_measuring - EPS);
                    assert!(r.best_sensing.value >= r.open_loop.value - EPS);
                }
                assert!(after.best_sensing.value >= with.best_sensing.value - EPS);
                assert!(after.always_measuring >= with.always_measuring - EPS);
            }
        }
    }
}

fn lake(name: &str, slip: f64, slide: f64, price: f64) -> FiniteWorld {
    builtin_world(
        name,
        &WorldOptions {
            slip: Some(slip),
            slide: Some(slide),
            sensing: Some(SensingModel::Factors),
            factor_costs: Some(vec![price, price]),
        },
    )
    .unwrap()
}

#[test]
fn the_benchmark_figures_come_out() {
    let semi = lake("frozenlake4x4", 0.0, 0.5, 0.025);
    let o = options(100, Some(2));
    let whole = SensingMenu::whole(&semi);
    assert_eq!(whole, SensingMenu::Whole { price: 0.05 });
    // 4x4 semi-slippery: always measuring 0.7375; optional whole-state measuring 0.90;
    // row and column priced apart 0.95.
    let a = always_measuring(&semi, whole, SensingRule::WithMove, &o).unwrap();
    assert!((a - 0.7375).abs() < EPS, "{a}");
    let b = best_sensing(&semi, whole, SensingRule::WithMove, &o)
        .unwrap()
        .value;
    assert!((b - 0.90).abs() < EPS, "{b}");
    let c = best_sensing(&semi, SensingMenu::Features, SensingRule::WithMove, &o)
        .unwrap()
        .value;
    assert!((c - 0.95).abs() < EPS, "{c}");
    // A larger bound finds nothing better.
    let o3 = options(100, Some(3));
    let b3 = best_sensing(&semi, whole, SensingRule::WithMove, &o3)
        .unwrap()
        .value;
    assert!((b3 - 0.90).abs() < EPS, "{b3}");
    // 4x4 deterministic: the optimum is 1.0, open loop or not.
    let det = lake("frozenlake4x4", 0.0, 0.0, 0.025);
    let r = reference_points(&det, SensingMenu::whole(&det), SensingRule::WithMove, &o).unwrap();
    assert!(r.open_loop.exact && (r.open_loop.value - 1.0).abs() < EPS);
    assert!((r.best_sensing.value - 1.0).abs() < EPS);
    // 8x8 semi-slippery: an open-loop plan reaches the goal with probability 1.
    let semi8 = lake("frozenlake8x8", 0.0, 0.5, 0.025);
    let ol = open_loop(
        &semi8,
        &ReferenceOptions {
            max_plans: 100,
            ..options(200, None)
        },
    )
    .unwrap();
    assert!(ol.exact && (ol.value - 1.0).abs() < EPS, "{ol:?}");
}

#[test]
fn bad_settings_and_caps_are_refused_clearly() {
    let semi = lake("frozenlake4x4", 0.0, 0.5, 0.025);
    let err = best_sensing(
        &semi,
        SensingMenu::Whole { price: f64::NAN },
        SensingRule::WithMove,
        &options(10, Some(1)),
    )
    .unwrap_err();
    assert!(err.to_string().contains("price"), "{err}");
    let err = best_sensing(
        &semi,
        SensingMenu::Whole { price: -1.0 },
        SensingRule::WithMove,
        &options(10, Some(1)),
    )
    .unwrap_err();
    assert!(err.to_string().contains("-1"), "{err}");
    let capped = ReferenceOptions {
        max_beliefs: 5,
        ..options(10, Some(3))
    };
    let err = best_sensing(
        &semi,
        SensingMenu::Features,
        SensingRule::AfterOutcome,
        &capped,
    )
    .unwrap_err();
    assert!(
        matches!(err, ReferenceError::TooManyBeliefs { cap: 5, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("more than 5 beliefs"), "{err}");
    let err = always_measuring(
        &semi,
        SensingMenu::Features,
        SensingRule::WithMove,
        &options(0, None),
    )
    .unwrap_err();
    assert!(err.to_string().contains("horizon"), "{err}");
    let err = open_loop(
        &semi,
        &ReferenceOptions {
            max_plans: 0,
            ..options(5, None)
        },
    )
    .unwrap_err();
    assert!(err.to_string().contains("max_plans"), "{err}");
    // A capped open loop is a lower bound, and says so.
    let slippery = lake("frozenlake4x4", 2.0 / 3.0, 0.0, 0.025);
    let capped = open_loop(
        &slippery,
        &ReferenceOptions {
            max_plans: 4,
            ..options(30, None)
        },
    )
    .unwrap();
    let full = open_loop(&slippery, &options(6, None)).unwrap();
    assert!(!capped.exact && full.exact);
}

#[test]
fn aliased_features_with_a_bound_are_infeasible_not_a_panic() {
    // Two states that read alike: no measurement tells them apart.
    let text = r#"{"format": "csrl-world", "version": 1, "name": "twins",
      "states": 4, "actions": ["go"], "start": [[1.0, 0]], "terminal": [3],
      "transitions": [[0, 0, [[0.5, 1, 0.0, false], [0.5, 2, 0.0, false]]],
                      [1, 0, [[1.0, 3, 1.0, true]]], [2, 0, [[1.0, 3, 1.0, true]]]],
      "features": [{"name": "f", "price": 0.1}], "readings": [[0], [1], [1], [0]]}"#;
    let w = FiniteWorld::from_json(text).unwrap();
    let err = best_sensing(
        &w,
        SensingMenu::Features,
        SensingRule::WithMove,
        &options(3, Some(0)),
    )
    .unwrap_err();
    assert!(matches!(err, ReferenceError::Infeasible { k: 0 }), "{err}");
    // The whole state tells them apart; without a bound the twins need no telling.
    let ok = best_sensing(
        &w,
        SensingMenu::Whole { price: 0.1 },
        SensingRule::WithMove,
        &options(3, Some(0)),
    )
    .unwrap();
    assert!((ok.value - 0.9).abs() < EPS);
    let free = best_sensing(
        &w,
        SensingMenu::Features,
        SensingRule::AfterOutcome,
        &options(3, Some(1)),
    )
    .unwrap();
    assert!((free.value - 1.0).abs() < EPS);
}

/// The ceiling is the optimum of the relaxation (the state told for free past `k`
/// uncertain steps), and so above the optimum of every policy.
#[test]
fn the_sensing_ceiling_is_the_relaxation_and_bounds_every_policy() {
    for seed in 0..10 {
        let w = tiny(seed, 4, 2, [0.03, 0.08]);
        let p = plain(&w);
        for h in 1..=4 {
            for (rule, _, menu, free) in rules_and_menus(&w) {
                let all = brute_best(&p, free, &[(0, 1.0)], h, 0);
                for k in [0, 1, 2] {
                    let up = mdp::sensing_ceiling(&w, menu, rule, &options(h, Some(k)))
                        .unwrap()
                        .value;
                    let relaxed = brute_best(
                        &p,
                        Setup {
                            k,
                            reveal: true,
                            ..free
                        },
                        &[(0, 1.0)],
                        h,
                        0,
                    );
                    assert!(
                        (up - relaxed).abs() < EPS,
                        "seed {seed} h {h} k {k}: {up} vs {relaxed}"
                    );
                    let low = best_sensing(&w, menu, rule, &options(h, Some(k)))
                        .unwrap()
                        .value;
                    assert!(
                        up >= all - EPS && low <= all + EPS,
                        "seed {seed} h {h} k {k}: {low} {all} {up}"
                    );
                }
            }
        }
    }
}

#[test]
fn many_features_are_refused_with_the_move_and_taken_one_at_a_time_after() {
    // Taxi with local sensing is refused, so take the 8x8 lake sensed locally: hundreds
    // of features.
    let w = builtin_world(
        "frozenlake8x8",
        &WorldOptions {
            slide: Some(0.5),
            ..Default::default()
        },
    )
    .unwrap();
    let o = options(30, Some(1));
    let err = best_sensing(&w, SensingMenu::Features, SensingRule::WithMove, &o).unwrap_err();
    assert!(err.to_string().contains("features"), "{err}");
    let after = best_sensing(&w, SensingMenu::Features, SensingRule::AfterOutcome, &o).unwrap();
    assert!(after.value.is_finite());
}

/// What the reference policies measure in an episode: on lakes where every policy of
/// theirs reaches the goal, the value is 1 less the price of each probe times the probes
/// counted; where moves slip, the count is what the value loses per unit of price.
#[test]
fn the_reference_points_count_what_they_measure() {
    let o = options(100, Some(2));
    // Deterministic: six moves, measured by the always-measuring policy (five after the
    // outcome, the last one ending the episode); the best policy measures nothing.
    let det = lake("frozenlake4x4", 0.0, 0.0, 0.025);
    for (menu, per) in [
        (SensingMenu::whole(&det), 1.0),
        (SensingMenu::Features, 2.0),
    ] {
        for (rule, moves) in [
            (SensingRule::WithMove, 6.0),
            (SensingRule::AfterOutcome, 5.0),
        ] {
            let r = reference_points(&det, menu, rule, &o).unwrap();
            assert_eq!(r.always_measuring_sensing, per * moves, "{menu:?} {rule:?}");
            assert_eq!(r.best_sensing.sensing, 0.0, "{menu:?} {rule:?}");
        }
    }
    // Semi-slippery: every policy here reaches the goal, so value = 1 - price x probes.
    let semi = lake("frozenlake4x4", 0.0, 0.5, 0.025);
    for (menu, price) in [
        (SensingMenu::whole(&semi), 0.05),
        (SensingMenu::Features, 0.025),
    ] {
        for rule in [SensingRule::WithMove, SensingRule::AfterOutcome] {
            let r = reference_points(&semi, menu, rule, &o).unwrap();
            let always = (1.0 - r.always_measuring) / price;
            assert!((r.always_measuring_sensing - always).abs() < 1e-6, "{r:?}");
            let best = (1.0 - r.best_sensing.value) / price;
            assert!((r.best_sensing.sensing - best).abs() < 1e-6, "{r:?}");
            assert!(r.best_sensing.sensing > 0.0, "{r:?}");
        }
    }
    // 4x4 semi-slippery, row and column apart: 0.95, two coordinates an episode.
    let apart = best_sensing(&semi, SensingMenu::Features, SensingRule::WithMove, &o).unwrap();
    assert!((apart.sensing - 2.0).abs() < 1e-6, "{apart:?}");
    // Slippery: a policy reaches the goal only sometimes; its count is the slope of its
    // value in the price (the same policy at a price a little higher).
    let slope = |w: &FiniteWorld, v: &FiniteWorld, menu, rule| {
        let a = best_sensing(w, menu, rule, &o).unwrap();
        let b = best_sensing(v, menu, rule, &o).unwrap();
        (a.sensing, (a.value - b.value) / 1e-6)
    };
    let slip = lake("frozenlake4x4", 2.0 / 3.0, 0.0, 0.025);
    let dearer = lake("frozenlake4x4", 2.0 / 3.0, 0.0, 0.025 + 1e-6);
    for rule in [SensingRule::WithMove, SensingRule::AfterOutcome] {
        let (counted, lost) = slope(&slip, &dearer, SensingMenu::Features, rule);
        assert!(
            counted > 0.0 && (counted - lost).abs() < 1e-3,
            "{rule:?}: {counted} {lost}"
        );
    }
}

fn bound_options(h: u32, gap: f64) -> mdp::BoundOptions {
    mdp::BoundOptions {
        horizon: h,
        gap,
        ..mdp::BoundOptions::default()
    }
}

#[test]
fn the_optimum_bounds_bracket_the_best_of_every_policy() {
    // On tiny worlds the optimum of every policy is known by brute force over every
    // history; the bounds must hold it and meet within the gap. Five live states leave
    // two of them reading alike on both features.
    let gap = 1e-6;
    for seed in 0..10 {
        let live = if seed % 3 == 2 { 5 } else { 4 };
        let w = tiny(seed, live, 2, [0.03, 0.08]);
        let p = plain(&w);
        for h in 1..=4 {
            for (rule, whole, menu, every) in rules_and_menus(&w) {
                let optimum = brute_best(&p, every, &[(0, 1.0)], h, 0);
                let b = mdp::optimum_bounds(&w, menu, rule, &bound_options(h, gap)).unwrap();
                let why = format!("seed {seed} h {h} {rule:?} whole {whole}: {b:?} vs {optimum}");
                assert!(b.converged && b.upper - b.lower <= gap + EPS, "{why}");
                assert!(
                    b.lower <= optimum + EPS && b.upper >= optimum - EPS,
                    "{why}"
                );
                let always = always_measuring(&w, menu, rule, &options(h, None)).unwrap();
                let aliased = live == 5 && !whole;
                assert!(aliased || b.lower >= always - EPS, "{why}: always {always}");
            }
        }
    }
}

#[test]
fn the_optimum_bounds_hold_what_the_reference_points_prove() {
    // Where the best policy within K meets its ceiling the optimum is known; elsewhere the
    // bounds must lie on the right side of each reference point.
    let gap = 1e-4;
    for (slide, price) in [(0.0, 0.025), (0.0, 0.05), (0.5, 0.025)] {
        let w = lake("frozenlake4x4", 0.0, slide, price);
        for menu in [SensingMenu::whole(&w), SensingMenu::Features] {
            for rule in [SensingRule::WithMove, SensingRule::AfterOutcome] {
                let h = 12;
                let o = options(h, Some(2));
                let best = best_sensing(&w, menu, rule, &o).unwrap().value;
                let ceiling = mdp::sensing_ceiling(&w, menu, rule, &o).unwrap().value;
                let free = mdp::free_sensing(&w, &o).unwrap();
                let b = mdp::optimum_bounds(&w, menu, rule, &bound_options(h, gap)).unwrap();
                let why = format!("slide {slide} price {price} {menu:?} {rule:?}: {b:?}");
                assert!(b.converged && b.lower <= b.upper, "{why}");
                assert!(b.upper >= best - EPS && b.lower <= free + EPS, "{why}");
                assert!(b.lower >= best - gap, "{why}: best within 2 {best}");
                if (ceiling - best).abs() < EPS {
                    assert!(b.lower <= best + EPS && b.upper >= best - EPS, "{why}");
                }
            }
        }
    }
}

#[test]
fn on_the_slippery_lake_the_lower_bound_is_not_below_the_search_within_k() {
    let gap = 1e-3;
    let w = lake("frozenlake4x4", 2.0 / 3.0, 0.0, 0.025);
    let h = 10;
    for menu in [SensingMenu::whole(&w), SensingMenu::Features] {
        for rule in [SensingRule::WithMove, SensingRule::AfterOutcome] {
            let b = mdp::optimum_bounds(&w, menu, rule, &bound_options(h, gap)).unwrap();
            let why = format!("{menu:?} {rule:?}: {b:?}");
            assert!(b.converged && b.lower <= b.upper, "{why}");
            for k in [1, 2] {
                let best = best_sensing(&w, menu, rule, &options(h, Some(k)))
                    .unwrap()
                    .value;
                assert!(b.lower >= best - gap, "{why}: K {k} {best}");
                assert!(b.upper >= best - EPS, "{why}: K {k} {best}");
            }
            let ceiling = mdp::sensing_ceiling(&w, menu, rule, &options(h, Some(2))).unwrap();
            assert!(b.lower <= ceiling.value + EPS, "{why}: {ceiling:?}");
            let again = mdp::optimum_bounds(&w, menu, rule, &bound_options(h, gap)).unwrap();
            assert_eq!(again, b, "the search is deterministic");
        }
    }
}

#[test]
fn the_optimum_bounds_refuse_bad_settings_and_stop_at_their_budget() {
    let w = lake("frozenlake4x4", 2.0 / 3.0, 0.0, 0.025);
    let menu = SensingMenu::whole(&w);
    let rule = SensingRule::WithMove;
    let o = bound_options(20, 1e-3);
    for (bad, what) in [
        (mdp::BoundOptions { horizon: 0, ..o }, "horizon"),
        (mdp::BoundOptions { gap: -1.0, ..o }, "gap"),
        (mdp::BoundOptions { gap: f64::NAN, ..o }, "gap"),
        (
            mdp::BoundOptions {
                gap: f64::INFINITY,
                ..o
            },
            "gap",
        ),
        (
            mdp::BoundOptions {
                max_entries: 10,
                ..o
            },
            "max_entries",
        ),
    ] {
        let err = mdp::optimum_bounds(&w, menu, rule, &bad).unwrap_err();
        assert!(
            matches!(err, ReferenceError::BadSetting { .. }) && err.to_string().contains(what),
            "{err}"
        );
    }
    let price = SensingMenu::Whole { price: -1.0 };
    assert!(mdp::optimum_bounds(&w, price, rule, &o).is_err());
    let huge = mdp::BoundOptions {
        horizon: u32::MAX,
        ..o
    };
    assert!(mdp::optimum_bounds(&w, menu, rule, &huge).is_err());
    // No trial: the bounds the search starts from, a policy's value below, free sensing
    // (or lower) above.
    let none = mdp::BoundOptions { max_trials: 0, ..o };
    let b = mdp::optimum_bounds(&w, menu, rule, &none).unwrap();
    let free = mdp::free_sensing(&w, &options(20, None)).unwrap();
    assert!(!b.converged && b.trials == 0 && b.lower <= b.upper && b.upper <= free + EPS);
    let always = always_measuring(&w, menu, rule, &options(20, None)).unwrap();
    assert!(b.lower >= always - EPS, "{b:?} {always}");
}
