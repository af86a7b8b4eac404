//! Grid dynamics, sensing, the oracle and random maps.

use mdp::{
    Action, Cell, FeatureSpace, GridWorld, Manhattan, Mdp, Offset, Oracle, Pos, RandomMap, StateId,
    builtin, builtin_names,
};
use proptest::prelude::*;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

#[test]
fn moves_follow_the_cartesian_convention_and_blocked_moves_stay() {
    let world = GridWorld::new(&mdp::Map::from_layout("t", "...\n.#.\n..G").unwrap());
    let s = world.state_at(Pos::new(0, 1)).unwrap();
    let to = |a: Action| world.pos(world.step(s, a.id()).next);
    assert_eq!(to(Action::Up), Pos::new(0, 1)); // boundary
    assert_eq!(to(Action::Down), Pos::new(0, 1)); // obstacle
    assert_eq!(to(Action::Left), Pos::new(0, 0));
    assert_eq!(to(Action::Right), Pos::new(0, 2));
    for a in Action::ALL {
        let step = world.step(s, a.id());
        assert_eq!(
            (step.reward, step.terminated, step.truncated),
            (0.0, false, false)
        );
    }
    let near = world.state_at(Pos::new(1, 2)).unwrap();
    let step = world.step(near, Action::Down.id());
    assert_eq!(
        (step.next, step.reward, step.terminated),
        (world.goal(), 1.0, true)
    );
}

#[test]
fn shifted_rewards_are_non_negative() {
    let map = builtin("tan3x3").unwrap();
    let opts = mdp::GridOptions {
        step_reward: -1.0,
        negative_rewards: mdp::NegativeRewards::Shift,
        ..Default::default()
    };
    let world = GridWorld::with_options(&map, opts).unwrap();
    let s = world.state_at(Pos::new(2, 0)).unwrap();
    assert_eq!(world.step(s, Action::Up.id()).reward, 0.0);
    let near = world.state_at(Pos::new(0, 1)).unwrap();
    assert_eq!(world.step(near, Action::Right.id()).reward, 2.0);
    let refused = mdp::GridOptions {
        negative_rewards: mdp::NegativeRewards::Refuse,
        ..opts
    };
    assert!(matches!(
        GridWorld::with_options(&map, refused),
        Err(mdp::MdpError::NegativeReward { .. })
    ));
}

#[test]
fn feature_order_is_cost_then_clockwise_from_up() {
    let space = FeatureSpace::new(&builtin("tan8x8").unwrap(), &Manhattan).unwrap();
    let offsets: Vec<(i32, i32)> = space
        .features()
        .take(12)
        .map(|f| {
            let o = space.offset(f);
            (o.dx, o.dy)
        })
        .collect();
    assert_eq!(
        offsets,
        [
            (0, 1),
            (1, 0),
            (0, -1),
            (-1, 0),
            (0, 2),
            (1, 1),
            (2, 0),
            (1, -1),
            (0, -2),
            (-1, -1),
            (-2, 0),
            (-1, 1)
        ]
    );
    for f in space.features() {
        assert_eq!(space.feature_of(space.offset(f)), Some(f));
        let o = space.offset(f);
        assert_eq!(space.cost(f), (o.dx.abs() + o.dy.abs()) as f64);
    }
}

#[test]
fn every_state_sees_99_cells_of_the_bordered_8x8_world() {
    let map = builtin("tan8x8").unwrap();
    let world = GridWorld::new(&map);
    let space = FeatureSpace::new(&map, &Manhattan).unwrap();
    assert_eq!(space.len(), 360);
    for s in world.states() {
        let p = world.pos(s);
        let inside = space
            .features()
            .filter(|&f| {
                let o = space.offset(f);
                let (r, c) = (p.row as i64 - o.dy as i64, p.col as i64 + o.dx as i64);
                (-1..=8).contains(&r) && (-1..=8).contains(&c)
            })
            .count();
        assert_eq!(inside, 99);
    }
}

#[test]
fn sensing_reads_the_map_and_obstacles_beyond() {
    let map = builtin("tan3x3").unwrap();
    let world = GridWorld::new(&map);
    let s = world.state_at(Pos::new(2, 0)).unwrap();
    assert_eq!(world.sense(s, Offset::new(2, 2)), Cell::Goal);
    assert_eq!(world.sense(s, Offset::new(-3, 0)), Cell::Obstacle);
    assert_eq!(world.sense(s, Offset::new(0, -1)), Cell::Obstacle);
    assert_eq!(world.sense(s, Offset::new(1, 1)), Cell::Empty);
}

#[test]
fn grid_oracle_agrees_with_value_iteration_on_every_builtin() {
    for name in builtin_names() {
        let world = GridWorld::new(&builtin(name).unwrap());
        let bfs = Oracle::for_grid(&world, 0.9).unwrap();
        let vi = Oracle::solve(&world, 0.9).unwrap();
        for s in world.states() {
            assert!((bfs.v_star(s) - vi.v_star(s)).abs() < 1e-9, "{name} {s}");
            assert_eq!(bfs.optimal_actions(s), vi.optimal_actions(s), "{name} {s}");
            assert!(!bfs.optimal_actions(s).is_empty());
        }
    }
}

#[test]
fn oracle_refuses_bad_discounts() {
    let world = GridWorld::new(&builtin("tan3x3").unwrap());
    for g in [1.0, -0.1, f64::NAN] {
        assert!(matches!(
            Oracle::for_grid(&world, g),
            Err(mdp::MdpError::InvalidDiscount { .. })
        ));
    }
}

#[test]
fn tan3x3_distances_match_the_picture() {
    let world = GridWorld::new(&builtin("tan3x3").unwrap());
    let oracle = Oracle::for_grid(&world, 0.9).unwrap();
    let d: Vec<Vec<u32>> = (0..3)
        .map(|r| {
            (0..3)
                .map(|c| {
                    oracle
                        .distance(world.state_at(Pos::new(r, c)).unwrap())
                        .unwrap()
                })
                .collect()
        })
        .collect();
    assert_eq!(d, [[2, 1, 0], [3, 2, 1], [4, 3, 2]]);
}

#[test]
fn random_maps_are_reproducible() {
    let p = RandomMap {
        width: 12,
        height: 7,
        obstacle_density: 0.35,
    };
    let a = p
        .generate("r", &mut Xoshiro256PlusPlus::seed_from_u64(3))
        .unwrap();
    let b = p
        .generate("r", &mut Xoshiro256PlusPlus::seed_from_u64(3))
        .unwrap();
    assert_eq!(a, b);
    let bad = RandomMap {
        obstacle_density: 1.0,
        ..p
    };
    assert!(
        bad.generate("r", &mut Xoshiro256PlusPlus::seed_from_u64(3))
            .is_err()
    );
}

#[test]
fn text_rendering_draws_the_boundary() {
    let text = mdp::render_text(&builtin("tan3x3").unwrap(), &mdp::Overlay::default());
    assert_eq!(text, "#####\n#..G#\n#...#\n#...#\n#####\n");
}

#[test]
fn svg_rendering_escapes_and_shows_overlays() {
    let map = builtin("tan3x3").unwrap();
    let mut o = mdp::Overlay {
        title: Some("a < b".into()),
        ..Default::default()
    };
    o.arrow(Pos::new(0, 0), Action::Right)
        .tooltip(Pos::new(0, 0), "x & y");
    let svg = mdp::render_svg(&map, &o);
    assert!(svg.contains("a &lt; b") && svg.contains("x &amp; y"));
    assert_eq!(svg.matches("<line").count(), 1);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_maps_are_always_valid(w in 1usize..14, h in 1usize..14, density in 0.0f64..0.95, seed: u64) {
        prop_assume!(w * h >= 2);
        let p = RandomMap { width: w, height: h, obstacle_density: density };
        let map = p.generate("r", &mut Xoshiro256PlusPlus::seed_from_u64(seed)).unwrap();
        // Valid maps survive a round trip through the file format, which re-validates them.
        let back = mdp::Map::from_toml_str(&map.to_toml(), "r").unwrap();
        prop_assert_eq!(&back, &map);
        let world = GridWorld::new(&map);
        let oracle = Oracle::for_grid(&world, 0.9).unwrap();
        for s in world.states() {
            prop_assert!(oracle.distance(s).is_some());
        }
    }

    #[test]
    fn grid_oracle_agrees_with_value_iteration_on_random_maps(seed: u64, gamma in 0.05f64..0.99) {
        let p = RandomMap { width: 6, height: 5, obstacle_density: 0.3 };
        let world = GridWorld::new(&p.generate("r", &mut Xoshiro256PlusPlus::seed_from_u64(seed)).unwrap());
        let bfs = Oracle::for_grid(&world, gamma).unwrap();
        let vi = Oracle::solve(&world, gamma).unwrap();
        for s in 0..world.num_states() as u32 {
            let s = StateId(s);
            prop_assert!((bfs.v_star(s) - vi.v_star(s)).abs() < 1e-9);
            if !world.is_terminal(s) {
                prop_assert_eq!(bfs.optimal_actions(s), vi.optimal_actions(s));
            }
        }
    }
}

proptest::proptest! {
    /// Following a deterministic policy's paths gives what sweeping its Bellman equation
    /// gives, bit for bit, on random maps and random policies (whose paths end within a
    /// few dozen moves or loop).
    #[test]
    fn following_a_policy_agrees_with_sweeping_it(
        size in 3usize..9,
        seed in 0u64..1000,
        actions in proptest::collection::vec(0u32..4, 81),
    ) {
        let map = mdp::resolve(&format!("random:{size}x{size}:0.2:{seed}")).unwrap();
        let world = mdp::GridWorld::new(&map);
        let n = mdp::StochasticMdp::num_states(&world);
        let policy: Vec<mdp::ActionId> = (0..n).map(|s| mdp::ActionId(actions[s % 81])).collect();
        let swept = mdp::evaluate_policy(&world, 0.9, &policy).unwrap();
        // On a grid map no move but the goal's earns a reward: every loop is worth 0,
        // and following always answers.
        let followed = mdp::follow_policy(&world, 0.9, &policy).unwrap();
        proptest::prop_assert_eq!(followed, Some(swept));
        // The optimal policy always reaches the goal: never a loop.
        let oracle = mdp::Oracle::for_grid(&world, 0.9).unwrap();
        let best: Vec<_> = (0..n as u32)
            .map(|s| oracle.optimal_actions(mdp::StateId(s)).first().copied().unwrap_or(mdp::ActionId(0)))
            .collect();
        let followed = mdp::follow_policy(&world, 0.9, &best).unwrap();
        proptest::prop_assert_eq!(followed, Some(mdp::evaluate_policy(&world, 0.9, &best).unwrap()));
    }
}

/// A loop that pays (Taxi's -1 a move, forever against a wall) is left to the sweep.
#[test]
fn following_leaves_a_paying_loop_to_the_sweep() {
    let taxi = mdp::builtin_world("taxi", &Default::default()).unwrap();
    let n = mdp::StochasticMdp::num_states(&taxi);
    let south = vec![mdp::ActionId(0); n];
    assert_eq!(mdp::follow_policy(&taxi, 0.9, &south).unwrap(), None);
    assert!(
        mdp::evaluate_policy(&taxi, 0.9, &south)
            .unwrap()
            .iter()
            .all(|v| *v <= 0.0)
    );
}
