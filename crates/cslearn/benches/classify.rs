//! Classification per object with a library of a few hundred examples, and tree building.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use cslearn::{ClassId, DecisionTree, FeatureCosts, Library, TreeOptions, Value};
use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// Objects as dense rows with their classes.
type Objects = Vec<(Vec<Option<Value>>, ClassId)>;

/// `n` objects over 20 features of 4 values with prices from 1 to 50; the class depends on
/// four of the features, so a learner has something to find.
fn objects(n: usize, seed: u64) -> (FeatureCosts, Objects) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let costs: Vec<f64> = (0..20).map(|_| rng.random_range(1.0..50.0)).collect();
    let rows = (0..n)
        .map(|_| {
            let row: Vec<u32> = (0..20).map(|_| rng.random_range(0..4)).collect();
            let class = ClassId(u32::from(row[3] + row[7] > 3) + u32::from(row[11] == row[15]));
            (row.into_iter().map(|v| Some(Value(v))).collect(), class)
        })
        .collect();
    (FeatureCosts::from_f64(&costs).unwrap(), rows)
}

fn trained(n: usize) -> (cslearn::CsId3, Objects) {
    let (costs, rows) = objects(n, 1);
    let mut learner = cslearn::cs_id3(costs);
    learner.stream(rows.iter().map(|(r, c)| (&r[..], *c)));
    let (_, fresh) = objects(256, 2);
    (learner, fresh)
}

fn classify(c: &mut Criterion) {
    let (mut learner, fresh) = trained(300);
    let mut i = 0;
    c.bench_function("cs-id3 classify, library of 300", |b| {
        b.iter(|| {
            i = (i + 1) % fresh.len();
            black_box(learner.classify(&fresh[i].0[..]))
        })
    });
    let (costs, rows) = objects(300, 1);
    let mut learner = cslearn::cs_ibl(costs, 1);
    learner.stream(rows.iter().map(|(r, c)| (&r[..], *c)));
    c.bench_function("cs-ibl classify, library of 300", |b| {
        b.iter(|| {
            i = (i + 1) % fresh.len();
            black_box(learner.classify(&fresh[i].0[..]))
        })
    });
}

fn build(c: &mut Criterion) {
    let (learner, _) = trained(300);
    let library: Library = learner.library().clone();
    let costs = learner.costs().clone();
    c.bench_function("tree build, library of 300", |b| {
        b.iter(|| {
            black_box(DecisionTree::build(
                &library,
                &costs,
                TreeOptions::observations(),
            ))
        })
    });
}

criterion_group!(benches, classify, build);
criterion_main!(benches);
