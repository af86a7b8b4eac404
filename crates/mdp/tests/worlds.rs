//! Finite worlds: the world file, the grid export and the built-in worlds beyond grids.

use mdp::{
    ActionId, Feature, FeatureSpace, FiniteWorld, GridWorld, Manhattan, Oracle, Reading,
    SensedGrid, SensingModel, Sensors, Slip, StateId, Step, StochasticMdp, World, WorldOptions,
    builtin, builtin_world, builtin_world_names,
};
use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

fn world(name: &str) -> FiniteWorld {
    builtin_world(name, &WorldOptions::default()).unwrap()
}

fn with(name: &str, options: WorldOptions) -> FiniteWorld {
    builtin_world(name, &options).unwrap()
}

fn outs(w: &FiniteWorld, s: u32, a: u32) -> Vec<(f64, u32, f64, bool)> {
    let mut out = Vec::new();
    w.outcomes(StateId(s), ActionId(a), &mut out);
    out.iter()
        .map(|(p, st)| (*p, st.next.0, st.reward, st.terminated))
        .collect()
}

fn close(a: &[(f64, u32, f64, bool)], b: &[(f64, u32, f64, bool)]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| (x.0 - y.0).abs() < 1e-12 && (x.1, x.2, x.3) == (y.1, y.2, y.3))
}

/// Every option combination the tests build.
fn every_world() -> Vec<FiniteWorld> {
    let mut all = Vec::new();
    for name in builtin_world_names() {
        all.push(world(name));
        if *name != "taxi" {
            for (slip, slide) in [(2.0 / 3.0, 0.0), (0.0, 0.3), (0.2, 0.5), (1.0, 1.0)] {
                all.push(with(
                    name,
                    WorldOptions {
                        slip: Some(slip),
                        slide: Some(slide),
                        ..Default::default()
                    },
                ));
            }
            all.push(with(
                name,
                WorldOptions {
                    sensing: Some(SensingModel::Factors),
                    factor_costs: Some(vec![2.0, 0.5]),
                    ..Default::default()
                },
            ));
        }
    }
    all
}

#[test]
fn every_probability_list_sums_to_one_and_terminated_matches() {
    let mut out = Vec::new();
    for w in every_world() {
        for s in 0..w.num_states() as u32 {
            for a in 0..w.num_actions() as u32 {
                w.outcomes(StateId(s), ActionId(a), &mut out);
                let total: f64 = out.iter().map(|o| o.0).sum();
                assert!((total - 1.0).abs() < 1e-12, "{} s{s} a{a}", w.name());
                for (p, st) in &out {
                    assert!((0.0..=1.0).contains(p));
                    assert_eq!(st.terminated, w.is_terminal(st.next));
                }
            }
        }
        let total: f64 = w.start_distribution().iter().map(|x| x.0).sum();
        assert!((total - 1.0).abs() < 1e-12);
        assert!(w.price(Feature(0)) >= 0.0);
        for f in 1..w.num_features() as u32 {
            assert!(w.price(Feature(f - 1)) <= w.price(Feature(f)));
        }
    }
}

#[test]
fn frozenlake_facts() {
    let w = world("frozenlake4x4");
    assert_eq!((w.num_states(), w.num_actions()), (16, 4));
    let names: Vec<String> = (0..4).map(|a| w.action_name(ActionId(a))).collect();
    assert_eq!(names, ["left", "down", "right", "up"]);
    let terminal: Vec<u32> = (0..16).filter(|&s| w.is_terminal(StateId(s))).collect();
    assert_eq!(terminal, [5, 7, 11, 12, 15]);
    assert_eq!(w.start_distribution(), vec![(1.0, StateId(0))]);
    assert_eq!(w.states().len(), 11);
    assert_eq!(w.state_label(StateId(14)), "(3,2)");
    assert_eq!(outs(&w, 14, 2), [(1.0, 15, 1.0, true)]);
    assert_eq!(outs(&w, 14, 0), [(1.0, 13, 0.0, false)]);
    assert_eq!(
        outs(&w, 0, 0),
        [(1.0, 0, 0.0, false)],
        "clamped at the edge"
    );
    assert_eq!(outs(&w, 0, 3), [(1.0, 0, 0.0, false)]);
    assert_eq!(
        outs(&w, 1, 1),
        [(1.0, 5, 0.0, true)],
        "a hole ends the trial"
    );
    let t = 1.0 / 3.0;
    let slippery = with(
        "frozenlake4x4",
        WorldOptions {
            slip: Some(2.0 / 3.0),
            ..Default::default()
        },
    );
    // Gymnasium's order: (a - 1) mod 4, a, (a + 1) mod 4.
    assert!(close(
        &outs(&slippery, 0, 1),
        &[(t, 0, 0.0, false), (t, 4, 0.0, false), (t, 1, 0.0, false)]
    ));
    assert!(close(
        &outs(&slippery, 14, 2),
        &[(t, 14, 0.0, false), (t, 15, 1.0, true), (t, 10, 0.0, false)]
    ));
    let sliding = with(
        "frozenlake4x4",
        WorldOptions {
            slide: Some(0.25),
            ..Default::default()
        },
    );
    assert_eq!(
        outs(&sliding, 0, 2),
        [(0.75, 1, 0.0, false), (0.25, 2, 0.0, false)]
    );
    assert_eq!(
        outs(&sliding, 4, 1),
        [(0.75, 8, 0.0, false), (0.25, 12, 0.0, true)]
    );
    assert_eq!(
        outs(&sliding, 1, 1),
        [(1.0, 5, 0.0, true)],
        "no slide off a hole"
    );
    assert_eq!(outs(&sliding, 14, 2), [(1.0, 15, 1.0, true)]);
    assert_eq!(
        outs(&sliding, 0, 0),
        [(0.75, 0, 0.0, false), (0.25, 0, 0.0, false)],
        "kept apart, not merged"
    );
    let both = with(
        "frozenlake4x4",
        WorldOptions {
            slip: Some(0.5),
            slide: Some(0.5),
            ..Default::default()
        },
    );
    assert_eq!(
        outs(&both, 0, 2),
        [
            (0.125, 4, 0.0, false),
            (0.125, 8, 0.0, false),
            (0.25, 1, 0.0, false),
            (0.25, 2, 0.0, false),
            (0.125, 0, 0.0, false),
            (0.125, 0, 0.0, false),
        ]
    );
    let big = world("frozenlake8x8");
    assert_eq!(big.num_states(), 64);
    let holes: Vec<u32> = (0..64)
        .filter(|&s| big.is_terminal(StateId(s)) && s != 63)
        .collect();
    assert_eq!(holes, [19, 29, 35, 41, 42, 46, 49, 52, 54, 59]);
    assert_eq!(outs(&big, 62, 2), [(1.0, 63, 1.0, true)]);
}

#[test]
fn local_sensing_matches_the_feature_space_of_a_map_of_that_size() {
    let lake = world("frozenlake4x4");
    let map = mdp::Map::from_layout("same-size", "....\n....\n....\n...G").unwrap();
    let space = FeatureSpace::new(&map, &Manhattan).unwrap();
    let grid = GridWorld::new(&map);
    let sensed = SensedGrid::new(&grid, &space, Slip::default());
    assert_eq!(lake.num_features(), space.len());
    for f in 0..space.len() as u32 {
        assert_eq!(
            lake.feature_name(Feature(f)),
            sensed.feature_name(Feature(f))
        );
        assert_eq!(lake.price(Feature(f)), sensed.price(Feature(f)));
    }
    let up = Feature(0);
    let right = Feature(1);
    assert_eq!(lake.feature_name(up), "(0,+1)");
    assert_eq!(lake.reading_name(up, lake.read(StateId(0), up)), "obstacle");
    assert_eq!(
        lake.reading_name(right, lake.read(StateId(4), right)),
        "hole"
    );
    assert_eq!(lake.read(StateId(14), right), Reading(2));
    assert_eq!(lake.reading_name(right, Reading(2)), "goal");
    assert_eq!(lake.read(StateId(0), right), Reading(0));
    let cliff = world("cliffwalking");
    assert_eq!(
        cliff.reading_name(right, cliff.read(StateId(36), right)),
        "cliff"
    );
    let down = Feature(2);
    assert_eq!(
        cliff.read(StateId(24), down),
        Reading(0),
        "the start reads empty"
    );
}

#[test]
fn factors_sensing_reads_the_factors() {
    let lake = with(
        "frozenlake4x4",
        WorldOptions {
            sensing: Some(SensingModel::Factors),
            factor_costs: Some(vec![3.0, 2.0]),
            ..Default::default()
        },
    );
    assert_eq!(lake.num_features(), 2);
    assert_eq!(lake.feature_name(Feature(0)), "col", "cheapest first");
    assert_eq!((lake.price(Feature(0)), lake.price(Feature(1))), (2.0, 3.0));
    assert_eq!(lake.read(StateId(6), Feature(0)), Reading(2));
    assert_eq!(lake.read(StateId(6), Feature(1)), Reading(1));
    assert_eq!(lake.reading_name(Feature(1), Reading(3)), "3");
    let taxi = world("taxi");
    let names: Vec<String> = (0..4).map(|f| taxi.feature_name(Feature(f))).collect();
    assert_eq!(names, ["row", "col", "passenger", "destination"]);
    // (2, 3, in the taxi, to Y)
    let s = StateId(((2 * 5 + 3) * 5 + 4) * 4 + 2);
    let read: Vec<u32> = (0..4).map(|f| taxi.read(s, Feature(f)).0).collect();
    assert_eq!(read, [2, 3, 4, 2]);
    assert_eq!(taxi.reading_name(Feature(2), Reading(4)), "taxi");
    assert_eq!(taxi.reading_name(Feature(3), Reading(2)), "Y");
    assert_eq!(taxi.state_label(s), "(2,3,taxi,Y)");
}

fn taxi_state(row: u32, col: u32, pass: u32, dest: u32) -> u32 {
    ((row * 5 + col) * 5 + pass) * 4 + dest
}

#[test]
fn taxi_facts() {
    let w = world("taxi");
    assert_eq!((w.num_states(), w.num_actions()), (500, 6));
    let starts = w.start_distribution();
    assert_eq!(starts.len(), 300);
    assert!(starts.iter().all(|&(p, _)| p == starts[0].0));
    assert_eq!((0..500).filter(|&s| w.is_terminal(StateId(s))).count(), 100);
    assert_eq!(w.states().len(), 400);
    let names: Vec<String> = (0..6).map(|a| w.action_name(ActionId(a))).collect();
    assert_eq!(
        names,
        ["south", "north", "east", "west", "pickup", "dropoff"]
    );
    let (east, west, south, north, pickup, dropoff) = (2, 3, 0, 1, 4, 5);
    // A wall blocks east from (0,1) and west from (0,2); (0,0) to (0,1) is open.
    let s = taxi_state(0, 1, 0, 1);
    assert_eq!(outs(&w, s, east), [(1.0, s, -1.0, false)]);
    assert_eq!(
        outs(&w, taxi_state(0, 2, 0, 1), west),
        [(1.0, taxi_state(0, 2, 0, 1), -1.0, false)]
    );
    assert_eq!(
        outs(&w, taxi_state(0, 0, 0, 1), east),
        [(1.0, taxi_state(0, 1, 0, 1), -1.0, false)]
    );
    assert_eq!(
        outs(&w, taxi_state(3, 1, 0, 1), west),
        [(1.0, taxi_state(3, 1, 0, 1), -1.0, false)],
        "the wall of row 3 between columns 0 and 1"
    );
    assert_eq!(
        outs(&w, taxi_state(4, 4, 0, 1), south),
        [(1.0, taxi_state(4, 4, 0, 1), -1.0, false)]
    );
    assert_eq!(
        outs(&w, taxi_state(1, 4, 0, 1), north),
        [(1.0, taxi_state(0, 4, 0, 1), -1.0, false)]
    );
    // Pickups.
    assert_eq!(
        outs(&w, taxi_state(0, 0, 0, 1), pickup),
        [(1.0, taxi_state(0, 0, 4, 1), -1.0, false)]
    );
    assert_eq!(
        outs(&w, taxi_state(0, 4, 0, 1), pickup),
        [(1.0, taxi_state(0, 4, 0, 1), -10.0, false)]
    );
    assert_eq!(
        outs(&w, taxi_state(0, 0, 4, 1), pickup),
        [(1.0, taxi_state(0, 0, 4, 1), -10.0, false)]
    );
    // Drop-offs.
    assert_eq!(
        outs(&w, taxi_state(0, 4, 4, 1), dropoff),
        [(1.0, taxi_state(0, 4, 1, 1), 20.0, true)]
    );
    assert_eq!(
        outs(&w, taxi_state(4, 0, 4, 1), dropoff),
        [(1.0, taxi_state(4, 0, 2, 1), -1.0, false)]
    );
    assert_eq!(
        outs(&w, taxi_state(2, 2, 4, 1), dropoff),
        [(1.0, taxi_state(2, 2, 4, 1), -10.0, false)]
    );
    assert_eq!(
        outs(&w, taxi_state(0, 0, 0, 1), dropoff),
        [(1.0, taxi_state(0, 0, 0, 1), -10.0, false)]
    );
}

#[test]
fn cliffwalking_facts() {
    let w = world("cliffwalking");
    assert_eq!((w.num_states(), w.num_actions()), (48, 4));
    let names: Vec<String> = (0..4).map(|a| w.action_name(ActionId(a))).collect();
    assert_eq!(names, ["up", "right", "down", "left"]);
    assert_eq!(w.start_distribution(), vec![(1.0, StateId(36))]);
    assert_eq!(
        outs(&w, 36, 1),
        [(1.0, 36, -100.0, false)],
        "into the cliff"
    );
    assert_eq!(outs(&w, 25, 2), [(1.0, 36, -100.0, false)]);
    assert_eq!(outs(&w, 36, 0), [(1.0, 24, -1.0, false)]);
    assert_eq!(outs(&w, 35, 2), [(1.0, 47, -1.0, true)]);
    assert_eq!(outs(&w, 36, 3), [(1.0, 36, -1.0, false)]);
    assert!(w.is_terminal(StateId(47)));
    assert!(!w.is_terminal(StateId(40)));
    let states = w.states();
    assert_eq!(states.len(), 37);
    assert!(states.iter().all(|s| !(37..=47).contains(&s.0)));
}

/// Follow the first optimal action of a deterministic world from `s`; the rewards.
fn greedy_run(w: &FiniteWorld, o: &Oracle, mut s: StateId) -> Vec<f64> {
    let mut rewards = Vec::new();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(0);
    for _ in 0..200 {
        let a = o.optimal_actions(s)[0];
        let step: Step = w.sample(s, a, &mut rng);
        rewards.push(step.reward);
        if step.terminated {
            return rewards;
        }
        s = step.next;
    }
    panic!("{}: no goal within 200 moves", w.name());
}

#[test]
fn the_oracle_solves_every_builtin_world() {
    let lake = world("frozenlake4x4");
    let o = Oracle::solve_stochastic(&lake, 0.9).unwrap();
    assert_eq!(greedy_run(&lake, &o, StateId(0)), [0., 0., 0., 0., 0., 1.]);
    let big = world("frozenlake8x8");
    let o = Oracle::solve_stochastic(&big, 0.9).unwrap();
    assert_eq!(greedy_run(&big, &o, StateId(0)).len(), 14);
    let cliff = world("cliffwalking");
    let o = Oracle::solve_stochastic(&cliff, 0.99).unwrap();
    assert_eq!(greedy_run(&cliff, &o, StateId(36)), vec![-1.0; 13]);
    let taxi = world("taxi");
    let o = Oracle::solve_stochastic(&taxi, 0.99).unwrap();
    for (_, s) in taxi.start_distribution() {
        let r = greedy_run(&taxi, &o, s);
        assert_eq!(r.last(), Some(&20.0));
        assert!(r[..r.len() - 1].iter().all(|&x| x == -1.0), "{r:?}");
    }
    let slippery = with(
        "frozenlake4x4",
        WorldOptions {
            slip: Some(2.0 / 3.0),
            ..Default::default()
        },
    );
    let o = Oracle::solve_stochastic(&slippery, 0.99).unwrap();
    // Gymnasium's slippery lake: the optimal start value with gamma 0.99 is about 0.542.
    assert!(
        (o.v_star(StateId(0)) - 0.542).abs() < 0.002,
        "{}",
        o.v_star(StateId(0))
    );
}

#[test]
fn sampling_draws_as_documented() {
    let lake = world("frozenlake4x4");
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(9);
    let mut twin = rng.clone();
    // One outcome: nothing drawn. One start state: one random_range(0..1).
    let _ = lake.sample(StateId(0), ActionId(2), &mut rng);
    assert_eq!(rng, twin);
    assert_eq!(lake.sample_start(&mut rng), StateId(0));
    let _ = twin.random_range(0..1usize);
    assert_eq!(rng, twin);
    // Several outcomes: one random::<f64>() and the cumulative rule.
    let slippery = with(
        "frozenlake4x4",
        WorldOptions {
            slip: Some(0.5),
            ..Default::default()
        },
    );
    for _ in 0..100 {
        let u = twin.random::<f64>();
        let got = slippery.sample(StateId(5 + 1), ActionId(2), &mut rng).next;
        // (a-1) = down: 10 below 0.25; right: 7 below 0.75; up: 2 otherwise.
        let want = if u < 0.25 {
            10
        } else if u < 0.75 {
            7
        } else {
            2
        };
        assert_eq!(got, StateId(want));
    }
    assert_eq!(rng, twin);
    // Unequal starts: one random::<f64>().
    let text = WORLD.replace("\"start\": [[1.0, 0]]", "\"start\": [[0.25, 0], [0.75, 1]]");
    let w = FiniteWorld::from_json(&text).unwrap();
    for _ in 0..50 {
        let u = twin.random::<f64>();
        assert_eq!(w.sample_start(&mut rng), StateId(u32::from(u >= 0.25)));
    }
}

#[test]
fn the_grid_export_draws_and_reads_as_the_grid() {
    for map in ["tan8x8", "tan3x3"] {
        let grid = GridWorld::new(&builtin(map).unwrap());
        let space = FeatureSpace::new(grid.map(), &Manhattan).unwrap();
        for slip in [0.0, 0.2] {
            let sensed = SensedGrid::new(&grid, &space, Slip::new(slip).unwrap());
            let w = FiniteWorld::from_grid(&sensed);
            assert_eq!(w.name(), map);
            assert_eq!(w.states(), sensed.states());
            assert_eq!(w.start_distribution(), sensed.start_distribution());
            assert_eq!(
                StochasticMdp::num_states(&w),
                StochasticMdp::num_states(&sensed)
            );
            let mut a = Xoshiro256PlusPlus::seed_from_u64(17);
            let mut b = a.clone();
            let mut actions = Xoshiro256PlusPlus::seed_from_u64(18);
            for _ in 0..50 {
                let mut s = w.sample_start(&mut a);
                assert_eq!(s, sensed.sample_start(&mut b));
                for _ in 0..40 {
                    let act = ActionId(actions.random_range(0..4u32));
                    let x = w.sample(s, act, &mut a);
                    assert_eq!(x, sensed.sample(s, act, &mut b));
                    if x.terminated {
                        break;
                    }
                    s = x.next;
                }
                assert_eq!(a, b);
            }
            let (mut x, mut y) = (Vec::new(), Vec::new());
            for s in 0..w.num_states() as u32 {
                assert_eq!(w.state_label(StateId(s)), sensed.state_label(StateId(s)));
                assert_eq!(w.is_terminal(StateId(s)), sensed.is_terminal(StateId(s)));
                for act in 0..4 {
                    w.outcomes(StateId(s), ActionId(act), &mut x);
                    sensed.outcomes(StateId(s), ActionId(act), &mut y);
                    let total = |o: &[(f64, Step)], n: StateId| {
                        o.iter().filter(|e| e.1.next == n).map(|e| e.0).sum::<f64>()
                    };
                    if !w.is_terminal(StateId(s)) {
                        for e in &y {
                            assert!((total(&x, e.1.next) - total(&y, e.1.next)).abs() < 1e-12);
                        }
                    }
                }
            }
            assert_eq!(w.num_features(), sensed.num_features());
            for f in 0..w.num_features() as u32 {
                let f = Feature(f);
                assert_eq!(w.price(f), sensed.price(f));
                assert_eq!(w.feature_name(f), sensed.feature_name(f));
                for s in 0..w.num_states() as u32 {
                    assert_eq!(w.read(StateId(s), f), sensed.read(StateId(s), f));
                }
                for v in 0..3 {
                    assert_eq!(
                        w.reading_name(f, Reading(v)),
                        sensed.reading_name(f, Reading(v))
                    );
                }
            }
            let back = FiniteWorld::from_json(&w.to_json()).unwrap();
            assert_eq!(back, w);
        }
    }
}

#[test]
fn json_round_trips_exactly() {
    let mut all = every_world();
    all.push(FiniteWorld::from_json(WORLD).unwrap());
    for w in all {
        let text = w.to_json();
        let back = FiniteWorld::from_json(&text).unwrap();
        assert_eq!(back, w, "{}", w.name());
        assert_eq!(back.to_json(), text);
        let spec: mdp::WorldSpec = serde_json::from_str(&text).unwrap();
        assert_eq!(spec, w.to_spec());
    }
}

/// A small valid world: features given out of price order.
const WORLD: &str = r#"{
  "format": "csrl-world",
  "version": 1,
  "name": "two-rooms",
  "states": 3,
  "actions": ["stay", "go"],
  "start": [[1.0, 0]],
  "terminal": [2],
  "transitions": [
    [0, 0, [[1.0, 0, 0.0, false]]],
    [0, 1, [[0.9, 1, 0.0, false], [0.1, 0, 0.0, false]]],
    [1, 0, [[1.0, 1, 0.0, false]]],
    [1, 1, [[1.0, 2, 1.0, true]]]
  ],
  "features": [
    {"name": "light", "price": 1.0, "readings": ["off", "on"]},
    {"name": "smell", "price": 0.5},
    {"name": "sound", "price": 1.0}
  ],
  "readings": [[0, 7, 1], [1, 7, 2], [1, 0, 3]]
}"#;

#[test]
fn a_world_file_is_read_with_features_cheapest_first() {
    let w = FiniteWorld::from_json(WORLD).unwrap();
    assert_eq!(w.name(), "two-rooms");
    let names: Vec<String> = (0..3).map(|f| w.feature_name(Feature(f))).collect();
    assert_eq!(names, ["smell", "light", "sound"]);
    assert_eq!(w.read(StateId(1), Feature(0)), Reading(7));
    assert_eq!(w.read(StateId(1), Feature(1)), Reading(1));
    assert_eq!(w.read(StateId(1), Feature(2)), Reading(2));
    assert_eq!(w.reading_name(Feature(1), Reading(1)), "on");
    assert_eq!(w.reading_name(Feature(0), Reading(7)), "7");
    assert_eq!(w.state_label(StateId(2)), "s2");
    assert_eq!(w.action_name(ActionId(1)), "go");
    assert_eq!(w.states(), [StateId(0), StateId(1)]);
    assert_eq!(outs(&w, 0, 1), [(0.9, 1, 0.0, false), (0.1, 0, 0.0, false)]);
    assert_eq!(outs(&w, 2, 0), [(1.0, 2, 0.0, true)], "terminal: stays");
    let text = w.to_json();
    assert!(text.find("\"smell\"").unwrap() < text.find("\"light\"").unwrap());
    let dir = std::env::temp_dir().join(format!("mdp-worlds-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("w.json");
    std::fs::write(&path, &text).unwrap();
    assert_eq!(FiniteWorld::read(&path).unwrap(), w);
    std::fs::write(&path, b"{\"format\": \xff}").unwrap();
    let err = FiniteWorld::read(&path).unwrap_err().to_string();
    assert!(err.contains("w.json") && err.contains("UTF-8"), "{err}");
    let big = vec![b' '; mdp::MAX_FILE_BYTES as usize + 1];
    std::fs::write(&path, big).unwrap();
    let err = FiniteWorld::read(&path).unwrap_err().to_string();
    assert!(err.contains("more than"), "{err}");
    let err = FiniteWorld::read(&dir).unwrap_err().to_string();
    assert!(err.contains("not a regular file"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn malformed_world_files_are_refused_clearly() {
    let cases: &[(&str, &str, &str)] = &[
        (
            "\"format\": \"csrl-world\"",
            "\"format\": \"gym\"",
            "\"gym\"",
        ),
        (
            "\"version\": 1",
            "\"version\": 2",
            "version 2 is not supported",
        ),
        (
            "\"name\"",
            "\"colour\": 1, \"name\"",
            "unknown field `colour`",
        ),
        (
            "[0.9, 1, 0.0, false]",
            "[0.5, 1, 0.0, false]",
            "(state 0, action 1): probabilities sum to 0.6",
        ),
        (
            "[0.9, 1, 0.0, false], [0.1",
            "[1.1, 1, 0.0, false], [-0.1",
            "outcome 0: probability 1.1",
        ),
        (
            "[1.0, 2, 1.0, true]",
            "[1.0, 3, 1.0, true]",
            "outcome 0: state 3 does not exist",
        ),
        (
            "[1.0, 2, 1.0, true]",
            "[1.0, 2, 1.0, false]",
            "`terminated` is false but state 2 is terminal",
        ),
        (
            "[1.0, 1, 0.0, false]]],\n    [1, 1",
            "[1.0, 2, 0.0, false]]],\n    [1, 1",
            "`transitions`[2] (state 1, action 0), outcome 0: `terminated` is false",
        ),
        (
            "    [1, 1, [[1.0, 2, 1.0, true]]]\n",
            "    [1, 1, [[1.0, 2, 1.0, true]]],\n    [0, 1, [[1.0, 0, 0.0, false]]]\n",
            "`transitions`[4] (state 0, action 1): given twice (first at `transitions`[1])",
        ),
        (
            ",\n    [1, 1, [[1.0, 2, 1.0, true]]]",
            "",
            "state 1, action 1: no transition given",
        ),
        (
            "[1, 0, [[1.0, 1, 0.0, false]]]",
            "[1, 0, []]",
            "(state 1, action 0): no outcomes",
        ),
        (
            "[1, 0, [[1.0, 1, 0.0, false]]]",
            "[1, 2, [[1.0, 1, 0.0, false]]]",
            "`transitions`[2]: action 2 does not exist",
        ),
        (
            "[1, 0, [[1.0, 1, 0.0, false]]]",
            "[2, 0, [[1.0, 2, 0.0, true]]]",
            "state 2 is terminal; a terminal state has no transitions",
        ),
        ("[1.0, 2, 1.0, true]", "[1.0, 2, 1e999, true]", "line 13"),
        (
            "\"price\": 0.5",
            "\"price\": -0.5",
            "`features`[1] `smell`: price -0.5",
        ),
        (
            "[1, 0, 3]]",
            "[1, 0]]",
            "`readings`[2]: 2 readings, but there are 3 features",
        ),
        (
            ", [1, 0, 3]]",
            "]",
            "`readings`: 2 rows, but there are 3 states",
        ),
        (
            "[[0, 7, 1]",
            "[[2, 7, 1]",
            "`readings`[0][0]: state 0 reads 2 on feature `light`, which names only 2 readings",
        ),
        (
            "[[1.0, 0]]",
            "[]",
            "`start`: the start distribution is empty",
        ),
        (
            "[[1.0, 0]]",
            "[[0.5, 0]]",
            "`start`: probabilities sum to 0.5",
        ),
        (
            "[[1.0, 0]]",
            "[[1.0, 2]]",
            "`start`[0]: state 2 is terminal",
        ),
        (
            "[[1.0, 0]]",
            "[[1.0, 9]]",
            "`start`[0]: state 9 does not exist",
        ),
        (
            "\"terminal\": [2]",
            "\"terminal\": [5]",
            "`terminal`[0]: state 5 does not exist",
        ),
        (
            "\"states\": 3",
            "\"states\": 70000",
            "states: 70000, more than the limit of 65536",
        ),
        (
            "\"states\": 3",
            "\"states\": \"three\"",
            "a number of states or a list of state labels",
        ),
        (
            "\"actions\": [\"stay\", \"go\"]",
            "\"actions\": []",
            "`actions`: a world needs at least one action",
        ),
        (
            "\"actions\": [\"stay\", \"go\"],",
            "",
            "missing field `actions`",
        ),
        ("\"version\": 1,", "", "`version`: missing"),
        (
            "{\n  \"format\"",
            "{\n  \"format\": 1, \"x\"",
            "`format` is 1",
        ),
        ("\n}", ",\n}", "line 21, column 1"),
    ];
    for (from, to, fragment) in cases {
        assert!(WORLD.contains(from), "case {from:?} does not apply");
        let text = WORLD.replacen(from, to, 1);
        let err = FiniteWorld::from_json(&text)
            .expect_err(&format!("{to:?} accepted"))
            .to_string();
        assert!(err.contains(fragment), "{to:?}: `{err}` lacks `{fragment}`");
    }
    let many_actions: Vec<String> = (0..65).map(|a| format!("\"a{a}\"")).collect();
    let text = WORLD.replace(
        "[\"stay\", \"go\"]",
        &format!("[{}]", many_actions.join(",")),
    );
    let err = FiniteWorld::from_json(&text).unwrap_err().to_string();
    assert!(
        err.contains("actions: 65, more than the limit of 64"),
        "{err}"
    );
    let mut spec: mdp::WorldSpec = serde_json::from_str(WORLD).unwrap();
    spec.states = mdp::StatesSpec::Count(65_536);
    spec.features = (0..4_096)
        .map(|i| mdp::FeatureSpec {
            name: format!("f{i}"),
            price: 1.0,
            readings: vec![],
        })
        .collect();
    let err = FiniteWorld::new(spec.clone()).unwrap_err().to_string();
    assert!(
        err.contains(
            "readings (states times features): 268435456, more than the limit of 16777216"
        ),
        "{err}"
    );
    spec.features.push(spec.features[0].clone());
    let err = FiniteWorld::new(spec).unwrap_err().to_string();
    assert!(
        err.contains("features: 4097, more than the limit of 4096"),
        "{err}"
    );
    let err = FiniteWorld::from_json("[1]").unwrap_err().to_string();
    assert!(err.contains("expected a csrl world file"), "{err}");
    // No prefix of a valid file panics, and each is refused.
    for end in 0..WORLD.len() {
        assert!(FiniteWorld::from_json(&WORLD[..end]).is_err());
    }
    let err = FiniteWorld::from_json("").unwrap_err().to_string();
    assert!(err.contains("line 1, column 0"), "{err}");
}

#[test]
fn readings_beyond_the_largest_and_names_given_twice_are_refused() {
    let refused = |from: &str, to: &str, fragment: &str| {
        assert!(WORLD.contains(from), "case {from:?} does not apply");
        let err = FiniteWorld::from_json(&WORLD.replacen(from, to, 1))
            .expect_err(&format!("{to:?} accepted"))
            .to_string();
        assert!(err.contains(fragment), "{to:?}: `{err}` lacks `{fragment}`");
    };
    // 4294967295 would make the feature's count of readings wrap to 0.
    refused(
        "[1, 0, 3]]",
        "[1, 0, 4294967295]]",
        "`readings`[2][2]: state 2 reads 4294967295 on feature `sound`, more than the \
         largest reading a feature may have (4294967294)",
    );
    let w =
        FiniteWorld::from_json(&WORLD.replacen("[1, 0, 3]]", "[1, 0, 4294967294]]", 1)).unwrap();
    assert_eq!(w.readings(Feature(2)), u32::MAX);
    assert_eq!(mdp::MAX_READING, u32::MAX - 1);
    refused(
        "\"states\": 3",
        "\"states\": [\"hall\", \"kitchen\", \"hall\"]",
        "`states`[2]: state label \"hall\" is also `states`[0]'s",
    );
    refused(
        "[\"stay\", \"go\"]",
        "[\"go\", \"go\"]",
        "`actions`[1]: action name \"go\" is also `actions`[0]'s",
    );
    refused(
        "\"name\": \"sound\"",
        "\"name\": \"light\"",
        "`features`[2]: feature name \"light\" is also `features`[0]'s",
    );
    refused(
        "[\"off\", \"on\"]",
        "[\"off\", \"off\"]",
        "`features`[0] `light` `readings`[1]: reading name \"off\" is also",
    );
    // Every built-in world and every built-in map's export has distinct names.
    for w in every_world() {
        assert_eq!(FiniteWorld::from_json(&w.to_json()).unwrap(), w);
    }
    for name in mdp::builtin_names() {
        let grid = mdp::GridWorld::new(&mdp::builtin(name).unwrap());
        let space = mdp::FeatureSpace::new(grid.map(), &mdp::Manhattan).unwrap();
        let sensed = mdp::SensedGrid::new(&grid, &space, mdp::Slip::default());
        let w = FiniteWorld::from_grid(&sensed);
        assert_eq!(FiniteWorld::from_json(&w.to_json()).unwrap(), w, "{name}");
    }
}

#[test]
fn builtin_options_are_checked() {
    let bad = |name: &str, o: WorldOptions, fragment: &str| {
        let err = builtin_world(name, &o).unwrap_err().to_string();
        assert!(err.contains(fragment), "{err}");
    };
    bad(
        "frozenlake4x4",
        WorldOptions {
            slip: Some(-0.1),
            ..Default::default()
        },
        "option `slip`: -0.1 is not a probability",
    );
    bad(
        "cliffwalking",
        WorldOptions {
            slide: Some(f64::NAN),
            ..Default::default()
        },
        "option `slide`: NaN",
    );
    bad(
        "taxi",
        WorldOptions {
            slip: Some(0.1),
            ..Default::default()
        },
        "Taxi-v3 is deterministic",
    );
    bad(
        "taxi",
        WorldOptions {
            sensing: Some(SensingModel::Local),
            ..Default::default()
        },
        "local sensing is refused for taxi",
    );
    bad(
        "taxi",
        WorldOptions {
            factor_costs: Some(vec![1.0, 2.0]),
            ..Default::default()
        },
        "2 costs given, but taxi has 4 factors",
    );
    bad(
        "frozenlake8x8",
        WorldOptions {
            sensing: Some(SensingModel::Factors),
            factor_costs: Some(vec![1.0, f64::INFINITY]),
            ..Default::default()
        },
        "cost 1 is inf",
    );
    bad(
        "frozenlake8x8",
        WorldOptions {
            factor_costs: Some(vec![1.0, 1.0]),
            ..Default::default()
        },
        "factors sensing only",
    );
    bad(
        "lake",
        WorldOptions::default(),
        "built-in worlds: frozenlake4x4",
    );
    let o: WorldOptions = serde_json::from_str(r#"{"slip": 0.1, "sensing": "factors"}"#).unwrap();
    assert_eq!(o.sensing, Some(SensingModel::Factors));
    assert!(serde_json::from_str::<WorldOptions>(r#"{"slipp": 0.1}"#).is_err());
}

#[test]
fn aliasing_is_found_where_features_cannot_tell_states_apart() {
    // States 0 and 1 read alike but 1 is one step nearer the exit.
    let text = WORLD.replace("[[0, 7, 1], [1, 7, 2]", "[[1, 7, 2], [1, 7, 2]");
    let w = FiniteWorld::from_json(&text).unwrap();
    let a = w.aliased(0.9).unwrap();
    assert_eq!(a.pairs, [(StateId(0), StateId(1))]);
    assert_eq!(a.count, 1);
    assert_eq!(
        FiniteWorld::from_json(WORLD)
            .unwrap()
            .aliased(0.9)
            .unwrap()
            .count,
        0
    );
    let lake = with(
        "frozenlake4x4",
        WorldOptions {
            sensing: Some(SensingModel::Factors),
            ..Default::default()
        },
    );
    assert_eq!(lake.aliased(0.9).unwrap().count, 0);
    assert!(lake.aliased(1.0).is_err());
    for name in builtin_world_names() {
        assert_eq!(
            world(name).aliased(0.9).unwrap(),
            mdp::Aliasing::default(),
            "{name}"
        );
    }
    // A lake sensed by the column alone aliases every row.
    let spec = {
        let mut s = lake.to_spec();
        s.features.truncate(1);
        for row in &mut s.readings {
            row.truncate(1);
        }
        s
    };
    let cols = FiniteWorld::new(spec).unwrap();
    assert!(cols.aliased(0.9).unwrap().count > 0);
}

/// The settings a built-in world asks of a run follow the rule its docs state: a
/// temperature of 0.4 times the largest reward in size where that is not 1 (the paper's
/// scale), and a detector only where the world penalises.
#[test]
fn every_builtin_world_states_its_settings_on_its_reward_scale() {
    for &name in builtin_world_names() {
        let w = world(name);
        let asked = mdp::builtin_world_settings(name).unwrap();
        let mut largest = 0.0f64;
        let mut penalty = false;
        let mut out = Vec::new();
        for s in w.states() {
            for a in 0..w.num_actions() as u32 {
                w.outcomes(s, ActionId(a), &mut out);
                for (_, step) in &out {
                    largest = largest.max(step.reward.abs());
                    penalty |= step.reward < 0.0;
                }
            }
        }
        let scaled = (largest != 1.0).then_some(0.4 * largest);
        assert_eq!(asked.temperature, scaled, "{name}");
        assert_eq!(asked.detector.is_some(), penalty, "{name}");
        assert!(!asked.why.is_empty(), "{name}");
    }
    assert!(mdp::builtin_world_settings("tan8x8").is_none());
}
