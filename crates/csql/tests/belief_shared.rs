//! Sensing by belief with shared moves (`[belief] shared_moves`): what each action does
//! learned over every cell at once. On the slippery lake, where a pair apart needs many
//! measured tries to be known, the shared model learns the slip in a few dozen and the
//! learner stops measuring; a world whose states are not a grid of readings is refused.

use csql::{BeliefParams, CostlySummary, belief_planning};
use mdp::{FiniteWorld, SensingRule};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

const EPISODES: u32 = 400;

fn slippery_lake() -> FiniteWorld {
    mdp::builtin_world(
        "frozenlake4x4",
        &mdp::WorldOptions {
            slip: Some(2.0 / 3.0),
            sensing: Some(mdp::SensingModel::Factors),
            factor_costs: Some(vec![0.025, 0.025]),
            ..Default::default()
        },
    )
    .unwrap()
}

/// A run of `params` on `world` from `seed`: over every episode, and over the last tenth.
fn run(world: &FiniteWorld, params: &BeliefParams, seed: u64) -> (CostlySummary, CostlySummary) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let run = belief_planning(
        world,
        params,
        1.0,
        SensingRule::WithMove,
        EPISODES,
        100,
        &mut rng,
    )
    .unwrap();
    let last = CostlySummary::of(&run[run.len() - run.len() / 10..]);
    (CostlySummary::of(&run), last)
}

/// Over three seeds of 400 episodes the learner's costed return is above 0 (the pairs
/// learned apart, free to stop measuring as well, lose 0.04 an episode over 20 runs of
/// 1000, `docs/costly.md`), and its last tenth measures at most once in two episodes.
#[test]
fn shared_moves_learn_the_slip_and_stop_measuring() {
    let lake = slippery_lake();
    let shared = BeliefParams {
        shared_moves: Some(48),
        blind_plans: Some(16),
        ..BeliefParams::default()
    };
    let mut total = 0.0;
    for seed in 1..=3 {
        let (all, last) = run(&lake, &shared, seed);
        assert!(last.sensing_per_episode <= 0.5, "seed {seed}: {last:?}");
        total += all.mean_all;
    }
    assert!(total > 0.0, "{total}");
}

#[test]
fn a_world_whose_states_are_not_a_grid_is_refused_by_the_key() {
    // Three cells read (0, 0), (0, 1), (1, 0): the fourth combination is missing.
    let json = r#"{"format": "csrl-world", "version": 1, "name": "ell", "states": 3,
        "actions": ["stay"], "start": [[1.0, 0]], "terminal": [2],
        "transitions": [[0, 0, [[1.0, 1, 0, false]]], [1, 0, [[1.0, 2, 1, true]]]],
        "features": [{"name": "row", "price": 0.025}, {"name": "col", "price": 0.025}],
        "readings": [[0, 0], [0, 1], [1, 0]]}"#;
    let world = FiniteWorld::from_json(json).unwrap();
    let params = BeliefParams {
        shared_moves: Some(8),
        ..BeliefParams::default()
    };
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    let err = belief_planning(&world, &params, 1.0, SensingRule::WithMove, 5, 10, &mut rng)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("belief.shared_moves") && err.contains("not every combination"),
        "{err}"
    );
    // Each pair apart, the same world runs.
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    assert!(
        belief_planning(
            &world,
            &BeliefParams::default(),
            1.0,
            SensingRule::WithMove,
            5,
            10,
            &mut rng
        )
        .is_ok()
    );
}
