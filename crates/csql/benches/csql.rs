//! CS-QL speed: moves per second, whole runs, and CLASSIFY with and without its cache.
//!
//! `cargo bench -p csql`

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use csql::{Classify, RunSettings, Setup, StrategyKind};
use std::hint::black_box;

fn runs(c: &mut Criterion) {
    let mut group = c.benchmark_group("run_tan8x8");
    group.sample_size(20);
    for k in StrategyKind::ALL {
        let settings = RunSettings::tan1991("tan8x8", k, 1);
        let setup = Setup::new(&settings).unwrap();
        let moves = csql::run_on(&setup, &settings).unwrap().moves;
        // Elements are moves: criterion reports moves per second.
        group.throughput(Throughput::Elements(moves));
        group.bench_function(k.name(), |b| {
            b.iter(|| black_box(csql::run_on(&setup, &settings).unwrap()))
        });
    }
    group.finish();
}

fn classify(c: &mut Criterion) {
    let settings = RunSettings::tan1991("tan8x8", StrategyKind::Lazy, 1);
    let setup = Setup::new(&settings).unwrap();
    let (_, rep) = csql::run_with_representation(&setup, &settings).unwrap();
    let states = setup.world.states();
    let world = setup.sensed(&settings);
    let mut group = c.benchmark_group("classify_all_50_states");
    group.throughput(Throughput::Elements(states.len() as u64));
    for (name, cache) in [("cached", true), ("plain", false)] {
        let mut classify = Classify::with_representation(&world, rep.clone()).with_cache(cache);
        group.bench_function(name, |b| {
            b.iter(|| {
                for &s in &states {
                    black_box(classify.classify_state(&world, s));
                }
            })
        });
    }
    group.finish();
}

criterion_group!(benches, runs, classify);
criterion_main!(benches);
