//! Q-learning steps per second on the open 8 by 8 room: the crate's general API
//! against a minimal hand-written loop of the same task.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use mdp::{GridWorld, Pos};
use qlearn::{Params, QLearner, Start};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

mod support {
    pub mod reference;
}

/// Moves per measured iteration: long enough for values to settle, as they do in the
/// example's long runs.
const STEPS: u64 = 1_000_000;
const SEED: u64 = 1991;

fn throughput(c: &mut Criterion) {
    let world = GridWorld::new(&mdp::builtin("open8x8").unwrap());
    let start = world.state_at(Pos::new(0, 0)).unwrap();
    let mut group = c.benchmark_group("open8x8");
    group.throughput(Throughput::Elements(STEPS));
    group.sample_size(20);
    group.measurement_time(Duration::from_secs(12));
    group.bench_function("reference", |b| {
        b.iter(|| {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(SEED);
            black_box(support::reference::run(black_box(STEPS), &mut rng))
        })
    });
    group.bench_function("qlearn", |b| {
        b.iter(|| {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(SEED);
            let mut learner =
                QLearner::new(&world, Params::tan1991(), Start::Fixed(start)).unwrap();
            learner.run_steps(black_box(STEPS), &mut rng);
            black_box(learner.into_table())
        })
    });
    group.finish();
}

criterion_group!(benches, throughput);
criterion_main!(benches);
