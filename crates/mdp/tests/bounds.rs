//! Rewards and prices whose sums over a run could overflow are refused when a world is
//! read: every number a run prints from a valid world is finite.

/// A world of two states: `a` loops on itself with `reward`, `b` leads to the goal; one
/// feature at `price`.
fn world(reward: f64, price: f64) -> String {
    format!(
        r#"{{"format": "csrl-world", "version": 1, "name": "loop",
  "states": ["a", "b", "g"], "actions": ["stay", "go"], "start": [[1.0, 0]], "terminal": [2],
  "transitions": [
    [0, 0, [[1.0, 0, {reward:e}, false]]], [0, 1, [[1.0, 1, 0.0, false]]],
    [1, 0, [[1.0, 1, 0.0, false]]], [1, 1, [[1.0, 2, 1.0, true]]]],
  "features": [{{"name": "where", "price": {price:e}, "readings": ["a", "b", "g"]}}],
  "readings": [[0], [1], [2]]}}"#
    )
}

#[test]
fn a_reward_too_large_to_sum_is_refused_naming_the_bound() {
    for reward in [1e308, -1e308, 1.5e200, f64::MAX] {
        let err = mdp::FiniteWorld::from_json(&world(reward, 1.0))
            .unwrap_err()
            .to_string();
        assert!(err.contains("state 0, action 0"), "{err}");
        assert!(err.contains("mdp::MAX_REWARD"), "{err}");
    }
}

#[test]
fn a_price_too_large_to_sum_is_refused_naming_the_bound() {
    for price in [1e308, 1.5e200, f64::MAX] {
        let err = mdp::FiniteWorld::from_json(&world(0.0, price))
            .unwrap_err()
            .to_string();
        assert!(err.contains("`where`"), "{err}");
        assert!(err.contains("mdp::MAX_PRICE"), "{err}");
    }
}

#[test]
fn rewards_and_prices_at_the_bound_give_finite_values() {
    let w = mdp::FiniteWorld::from_json(&world(-mdp::MAX_REWARD, mdp::MAX_PRICE)).unwrap();
    let w2 = mdp::FiniteWorld::from_json(&world(mdp::MAX_REWARD, 0.0)).unwrap();
    for world in [&w, &w2] {
        for gamma in [0.9, 0.99] {
            let oracle = mdp::Oracle::solve_stochastic(world, gamma).unwrap();
            for s in 0..3 {
                let v = oracle.v_star(mdp::StateId(s));
                assert!(v.is_finite(), "{v}");
            }
        }
    }
}

#[test]
fn factor_costs_too_large_to_sum_are_refused() {
    let options = mdp::WorldOptions {
        sensing: Some(mdp::SensingModel::Factors),
        factor_costs: Some(vec![1.0, 1e308]),
        ..Default::default()
    };
    let err = mdp::builtin_world("frozenlake4x4", &options)
        .unwrap_err()
        .to_string();
    assert!(err.contains("factor_costs"), "{err}");
    assert!(err.contains("cost 1 is 1e308"), "{err}");
    assert!(err.contains("mdp::MAX_PRICE"), "{err}");
    let options = mdp::WorldOptions {
        factor_costs: Some(vec![1.0, mdp::MAX_PRICE]),
        ..options
    };
    assert!(mdp::builtin_world("frozenlake4x4", &options).is_ok());
}

#[test]
fn a_cost_model_too_large_to_sum_is_refused() {
    struct Huge;
    impl mdp::CostModel for Huge {
        fn cost(&self, _: mdp::Offset) -> f64 {
            1e300
        }
    }
    let map = mdp::builtin("tan3x3").unwrap();
    let err = mdp::FeatureSpace::new(&map, &Huge).unwrap_err().to_string();
    assert!(err.contains("mdp::MAX_PRICE"), "{err}");
}
