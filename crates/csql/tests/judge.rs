//! The incremental judge gives, at the end of every trial, exactly the verdict of the
//! from-scratch judgement of the whole mapping from states to rows.

use csql::{
    Agent, Classify, Judge, LoopParams, Perception, RunSettings, Setup, StrategyKind, Verdict,
};
use qlearn::QTable;
use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

fn check(map: &str, strategy: StrategyKind, seed: u64, seen: &mut [bool; 3]) {
    let settings = RunSettings::tan1991(map, strategy, seed);
    let setup = Setup::new(&settings).unwrap();
    let world = setup.sensed(&settings);
    let mut agent = Agent::new(
        Classify::new(&world),
        strategy.build(settings.cs_ql().unwrap().random_moves),
        QTable::new(4).unwrap(),
        LoopParams::from(&settings),
    );
    let mut judge = Judge::default();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let states = setup.world.states();
    for trial in 1..=3000 {
        let start = states[rng.random_range(0..states.len())];
        agent.run_trial(&world, start, trial, &mut rng);
        let fast = judge.judge(&world, &setup.oracle, &mut agent, settings.tolerance.get());
        let rows: Vec<_> = states
            .iter()
            .map(|&s| Perception::lookup(&mut agent.perception, &world, s))
            .collect();
        let slow = Verdict::judge(
            &world,
            &setup.oracle,
            &agent.table,
            &rows,
            settings.tolerance.get(),
        );
        assert_eq!(fast, slow, "{map} {strategy} seed {seed}, trial {trial}");
        seen[0] |= fast.unmatched > 0;
        seen[1] |= fast.sufficient && !fast.converged;
        seen[2] |= fast.converged;
        if fast.converged {
            break;
        }
    }
    assert!(seen[2], "{map} {strategy} seed {seed} did not converge");
}

#[test]
fn the_incremental_judge_agrees_with_the_whole_judgement_at_every_trial() {
    let mut seen = [false; 3];
    for strategy in StrategyKind::ALL {
        check("tan3x3", strategy, 1, &mut seen);
        check("dyna9x6", strategy, 2, &mut seen);
        check("random:8x8:0.2:4", strategy, 3, &mut seen);
    }
    // The runs went through every kind of verdict (states without a description,
    // sufficient but not converged, converged), so each was compared.
    assert_eq!(seen, [true, true, true]);
}
