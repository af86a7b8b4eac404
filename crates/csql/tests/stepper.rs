//! A `Stepper` driven by a world, drawing the world's starts and outcomes from the
//! stepper's generator, learns exactly what `csql::run` learns for the same settings:
//! the same trials, moves, costs, descriptions and values, bit for bit.

use csql::{Moment, RefineFrom, RunReport, RunSettings, Stepper, StrategyKind};
use mdp::{Reading, Sensors, StochasticMdp, World};

/// Drive `stepper` in `world` for `trials` trials as `csql::run` does: draw the start,
/// act, sample the outcome from the same generator, cut the trial at the move cap.
fn drive<W: World + ?Sized>(world: &W, stepper: &mut Stepper, trials: u32, max_moves: u32) {
    for _ in 0..trials {
        let mut x = world.sample_start(stepper.rng());
        for moves in 1..=max_moves {
            let a = stepper.act(&mut |_: Moment, f| world.read(x, f)).unwrap();
            let step = world.sample(x, a, stepper.rng());
            let left = x;
            stepper
                .update(
                    step.reward,
                    step.terminated,
                    moves == max_moves,
                    &mut |at: Moment, f| match at {
                        Moment::Now => world.read(step.next, f),
                        Moment::Left => world.read(left, f),
                    },
                )
                .unwrap();
            if step.terminated {
                break;
            }
            x = step.next;
        }
    }
}

/// The stepper's learning against the run's report.
fn assert_same<W: World + ?Sized>(world: &W, stepper: &Stepper, report: &RunReport) {
    let what = format!("{} {:?} seed {}", report.map, report.strategy, report.seed);
    assert_eq!(stepper.trials(), report.trials, "{what}");
    assert_eq!(stepper.moves(), report.moves, "{what}");
    assert_eq!(
        stepper.cost().to_bits(),
        report.total_cost.to_bits(),
        "{what}"
    );
    let last = stepper.last_trial().unwrap();
    let point = report.trace.last().unwrap();
    assert_eq!(
        (last.trial, last.moves, last.decreases, last.refinements),
        (point.trial, point.moves, point.decreases, point.refinements),
        "{what}"
    );
    let mine = stepper.descriptions();
    assert_eq!(mine.len(), report.descriptions.len(), "{what}");
    for (d, theirs) in mine.iter().zip(&report.descriptions) {
        // Grids report a feature by its offset, other worlds by its name.
        let grid = world.grid().is_some();
        let mut named: Vec<(Option<String>, String, u64)> = d
            .iter()
            .map(|&(f, v)| {
                let f = mdp::Feature(f);
                let name = (!grid).then(|| world.feature_name(f));
                (
                    name,
                    world.reading_name(f, Reading(v)),
                    world.price(f).to_bits(),
                )
            })
            .collect();
        named.sort();
        let mut reported: Vec<(Option<String>, String, u64)> = theirs
            .features
            .iter()
            .map(|f| (f.feature.clone(), f.value.clone(), f.cost.to_bits()))
            .collect();
        reported.sort();
        assert_eq!(named, reported, "{what}: description {}", theirs.label);
    }
    for s in &report.states {
        if let (Some(d), Some(v)) = (s.description, s.value) {
            let mine = stepper.table().v(qlearn::RowId(d));
            assert_eq!(mine.to_bits(), v.to_bits(), "{what}: V of {:?}", s.label);
        }
    }
}

fn stepper_for<W: World + ?Sized>(world: &W, settings: &RunSettings) -> Stepper {
    let prices: Vec<f64> = (0..world.num_features() as u32)
        .map(|f| world.price(mdp::Feature(f)))
        .collect();
    let readings: Vec<u32> = (0..world.num_features() as u32)
        .map(|f| world.readings(mdp::Feature(f)))
        .collect();
    Stepper::new(&prices, &readings, world.num_actions(), settings)
        .unwrap()
        .starting_at(csql::value_floor(world, settings.gamma.get()))
        .unwrap()
}

#[test]
fn a_grid_map_learns_as_run_does() {
    for (map, strategy, seed) in [
        ("tan8x8", StrategyKind::Lazy, 1),
        ("tan8x8", StrategyKind::Resetting, 2),
        ("tan8x8", StrategyKind::Random, 3),
        ("tan8x8", StrategyKind::Eager, 4),
        ("tan3x3", StrategyKind::Random, 5),
    ] {
        let settings = RunSettings::tan1991(map, strategy, seed);
        let setup = csql::Setup::new(&settings).unwrap();
        let (report, rep) = csql::run_with_representation(&setup, &settings).unwrap();
        let world = setup.sensed(&settings);
        let mut stepper = stepper_for(&world, &settings);
        drive(
            &world,
            &mut stepper,
            report.trials,
            settings.max_moves.get(),
        );
        assert_same(&world, &stepper, &report);
        assert_eq!(stepper.representation().len(), rep.len());
        for ((_, a), (_, b)) in stepper.representation().iter().zip(rep.iter()) {
            assert!(a.features().eq(b.features()), "{map} {strategy} {seed}");
        }
    }
}

#[test]
fn a_finite_world_learns_as_run_does() {
    for (name, strategy, seed) in [
        ("frozenlake4x4", StrategyKind::Lazy, 1),
        ("frozenlake4x4", StrategyKind::Random, 5),
        ("frozenlake8x8", StrategyKind::Eager, 2),
        ("cliffwalking", StrategyKind::Resetting, 3),
    ] {
        let mut settings = RunSettings::tan1991(name, strategy, seed);
        settings.max_trials = csql::TrialCap::new(300).unwrap();
        let report = csql::run(&settings).unwrap();
        let world = mdp::builtin_world(name, &Default::default()).unwrap();
        let mut stepper = stepper_for(&world, &settings);
        drive(
            &world,
            &mut stepper,
            report.trials,
            settings.max_moves.get(),
        );
        assert_same(&world, &stepper, &report);
    }
}

#[test]
fn slippery_moves_drawn_from_the_same_generator_learn_as_run_does() {
    let mut settings = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 3);
    settings.world.slip = Some(mdp::Slip::new(0.1).unwrap());
    let setup = csql::Setup::new(&settings).unwrap();
    let report = csql::run_on(&setup, &settings).unwrap();
    let world = setup.sensed(&settings);
    // The stepper refuses [world] settings: it is given the world's features alone.
    let mut plain = settings.clone();
    plain.world = Default::default();
    let mut stepper = stepper_for(&world, &plain);
    drive(
        &world,
        &mut stepper,
        report.trials,
        settings.max_moves.get(),
    );
    assert_same(&world, &stepper, &report);
}

#[test]
fn refining_from_the_next_state_sensed_learns_too() {
    let settings = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 1);
    let setup = csql::Setup::new(&settings).unwrap();
    let world = setup.sensed(&settings);
    let mut stepper = stepper_for(&world, &settings).refining_from(RefineFrom::NextSensed);
    // This sensor cannot read the state left.
    for _ in 0..400 {
        let mut x = world.sample_start(stepper.rng());
        for moves in 1..=100 {
            let a = stepper.act(&mut |_: Moment, f| world.read(x, f)).unwrap();
            let step = world.sample(x, a, stepper.rng());
            let mut now_only = |at: Moment, f| {
                assert_eq!(at, Moment::Now);
                world.read(step.next, f)
            };
            stepper
                .update(step.reward, step.terminated, moves == 100, &mut now_only)
                .unwrap();
            if step.terminated {
                break;
            }
            x = step.next;
        }
    }
    assert!(stepper.descriptions().len() > 10);
    // The last trials reach the goal.
    assert!(stepper.last_trial().unwrap().reached_goal);
}

#[test]
fn bad_readings_and_calls_out_of_order_are_errors() {
    let settings = RunSettings::tan1991("any", StrategyKind::Eager, 1);
    let mut stepper = Stepper::new(&[1.0, 1.0], &[2, 2], 2, &settings).unwrap();
    let mut ok = |_: Moment, _| Reading(1);
    assert!(matches!(
        stepper.update(0.0, false, false, &mut ok),
        Err(csql::StepError::OutOfOrder { .. })
    ));
    stepper.act(&mut ok).unwrap();
    assert!(stepper.act(&mut ok).is_err());
    assert!(matches!(
        stepper.update(f64::NAN, false, false, &mut ok),
        Err(csql::StepError::Reward(_))
    ));
    // Learn until CLASSIFY measures something, with a sensor that reads out of range.
    let mut bad = |_: Moment, _| Reading(7);
    let mut failed = None;
    for _ in 0..200 {
        if let Err(e) = stepper.update(-1.0, false, false, &mut bad) {
            failed = Some(e);
            break;
        }
        if let Err(e) = stepper.act(&mut bad) {
            failed = Some(e);
            break;
        }
    }
    let e = failed.expect("a decrease refines, then a measurement reads 7");
    assert!(e.to_string().contains("reads 0 to 1"), "{e}");
    assert!(matches!(
        stepper.act(&mut ok),
        Err(csql::StepError::Stopped(_))
    ));
}

/// Sizes are checked before anything is built: more actions or features than a world
/// may have are refused, and a feature of 2^32 - 1 readings costs only what is sensed
/// (CLASSIFY runs without its cache, whose records would be 2^32 words each).
#[test]
fn sizes_are_checked_and_a_huge_range_of_readings_costs_what_is_sensed() {
    let settings = RunSettings::tan1991("any", StrategyKind::Eager, 1);
    let e = Stepper::new(&[1.0], &[2], 1_000_000_000, &settings).unwrap_err();
    assert!(e.to_string().contains("1000000000 actions"), "{e}");
    assert!(e.to_string().contains("at most 64 actions"), "{e}");
    let many = vec![1.0; 4097];
    let e = Stepper::new(&many, &vec![2; 4097], 2, &settings).unwrap_err();
    assert!(e.to_string().contains("4097 features"), "{e}");
    let mut stepper = Stepper::new(&[1.0, 2.0], &[u32::MAX, u32::MAX], 2, &settings).unwrap();
    // A corridor 0 -> 1 -> 2 (the goal), cells read as large numbers.
    let read = |cell: u32| move |_: Moment, f: mdp::Feature| Reading(4_000_000_000 - cell - f.0);
    for _ in 0..40 {
        let mut cell = 0u32;
        for moves in 1..=50 {
            let a = stepper.act(&mut read(cell)).unwrap();
            let next = if a.0 == 1 {
                cell + 1
            } else {
                cell.saturating_sub(1)
            };
            let goal = next == 2;
            stepper
                .update(
                    f64::from(u8::from(goal)),
                    goal,
                    moves == 50,
                    &mut |at: Moment, f| match at {
                        Moment::Now => read(next)(at, f),
                        Moment::Left => read(cell)(at, f),
                    },
                )
                .unwrap();
            if goal {
                break;
            }
            cell = next;
        }
    }
    assert_eq!(stepper.trials(), 40);
}

#[test]
fn rewards_and_prices_whose_sums_could_overflow_are_refused() {
    let settings = RunSettings::tan1991("any", StrategyKind::Eager, 1);
    for price in [1e308, 1.5e200, f64::MAX] {
        let Err(err) = Stepper::new(&[1.0, price], &[2, 2], 2, &settings) else {
            panic!("a price of {price:e} was accepted");
        };
        let err = err.to_string();
        assert!(err.contains("mdp::MAX_PRICE"), "{err}");
    }
    assert!(Stepper::new(&[1.0, mdp::MAX_PRICE], &[2, 2], 2, &settings).is_ok());
    let mut stepper = Stepper::new(&[1.0, 1.0], &[2, 2], 2, &settings).unwrap();
    let mut read = |_: Moment, _| Reading(1);
    stepper.act(&mut read).unwrap();
    for reward in [1e308, -1e308, 1.5e200] {
        let err = stepper.update(reward, false, false, &mut read).unwrap_err();
        assert!(matches!(err, csql::StepError::Reward(_)), "{err}");
        assert!(err.to_string().contains("mdp::MAX_REWARD"), "{err}");
    }
    // The largest reward, learned from again and again, leaves every value finite.
    stepper
        .update(mdp::MAX_REWARD, false, false, &mut read)
        .unwrap();
    for _ in 0..1000 {
        stepper.act(&mut read).unwrap();
        stepper
            .update(mdp::MAX_REWARD, false, false, &mut read)
            .unwrap();
    }
    let t = stepper.table();
    assert!(
        t.q_values()
            .iter()
            .chain(t.v_values())
            .all(|v| v.is_finite())
    );
}
