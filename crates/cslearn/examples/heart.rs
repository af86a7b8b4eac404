//! Stream the Cleveland heart-disease records (target `num > 0`) through CS-ID3, CS-IBL
//! and cost-blind ID3 for several seeds, and print accuracy and cost per object.
//!
//! `cargo run --release -p cslearn --example heart -- [SEEDS]` uses seeds `1..=SEEDS`
//! (default 10), the seeds `csrl classify --seed N` takes.

use std::path::Path;

use cslearn::{Dataset, DatasetOptions, LearnerKind, StreamReport};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// CS-ID3 without the recheck after learning, streamed exactly as `stream_dataset` does.
fn cs_id3_without_recheck(data: &Dataset, seed: u64) -> StreamReport {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let order = data.shuffled(&mut rng);
    cslearn::cs_id3(data.costs().clone())
        .recheck(false)
        .stream(order.iter().map(|&i| (data.object(i), data.labels()[i])))
}

fn main() -> Result<(), cslearn::Error> {
    let seeds: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(10);
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/heart-disease");
    let options = DatasetOptions::new("num").positive_if(">0");
    let data = Dataset::load(&dir.join("cleveland.csv"), &dir.join("costs.csv"), &options)?;
    println!("| learner | accuracy (min-max) | mean cost per object (min-max) |");
    println!("|---|---|---|");
    let learners: [(&str, Option<LearnerKind>); 4] = [
        ("CS-ID3", Some(LearnerKind::CsId3)),
        ("CS-ID3, no recheck", None),
        (
            "CS-IBL, tolerance 1",
            Some(LearnerKind::CsIbl { tolerance: 1 }),
        ),
        ("ID3 (cost-blind)", Some(LearnerKind::Id3)),
    ];
    for (name, kind) in learners {
        let reports: Vec<StreamReport> = (1..=seeds)
            .map(|seed| match kind {
                Some(kind) => cslearn::stream_dataset(&data, kind, seed),
                None => cs_id3_without_recheck(&data, seed),
            })
            .collect();
        let stats = |f: fn(&StreamReport) -> f64| {
            let xs: Vec<f64> = reports.iter().map(f).collect();
            let mean = xs.iter().sum::<f64>() / xs.len() as f64;
            let min = xs.iter().copied().fold(f64::INFINITY, f64::min);
            let max = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (mean, min, max)
        };
        let (acc, acc_lo, acc_hi) = stats(|r| r.accuracy);
        let (cost, cost_lo, cost_hi) = stats(|r| r.mean_cost);
        println!(
            "| {name} | {acc:.3} ({acc_lo:.3}-{acc_hi:.3}) | {cost:.1} ({cost_lo:.1}-{cost_hi:.1}) |"
        );
    }
    println!(
        "| measuring everything | | {:.2} |",
        data.costs().total().get()
    );
    Ok(())
}
