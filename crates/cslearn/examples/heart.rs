//! Stream the Cleveland heart-disease records through CS-ID3, CS-IBL and cost-blind ID3
//! for several seeds and print mean cost per object and accuracy.
//!
//! `cargo run --release -p cslearn --example heart -- [SEEDS]` (default 10 seeds, 0..SEEDS).

use std::path::Path;

use cslearn::{Dataset, DatasetOptions, StreamReport};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

fn main() -> Result<(), cslearn::Error> {
    let seeds: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(10);
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/heart-disease");
    let options = DatasetOptions::new("num").positive_if(">0");
    let data = Dataset::load(&dir.join("cleveland.csv"), &dir.join("costs.csv"), &options)?;
    println!("learner  seed  errors  accuracy  mean cost");
    for name in [
        "cs-id3",
        "cs-id3/no-recheck",
        "cs-ibl",
        "id3",
        "id3/no-recheck",
    ] {
        let mut sum = (0.0, 0.0);
        for seed in 0..seeds {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
            let order = data.shuffled(&mut rng);
            let objects = order.iter().map(|&i| (data.object(i), data.labels()[i]));
            let costs = data.costs().clone();
            let report: StreamReport = match name {
                "cs-id3" => cslearn::cs_id3(costs).stream(objects),
                "cs-id3/no-recheck" => cslearn::cs_id3(costs).recheck(false).stream(objects),
                "cs-ibl" => cslearn::cs_ibl(costs, 1).stream(objects),
                "id3" => cslearn::id3(costs, rng).stream(objects),
                _ => cslearn::id3(costs, rng).recheck(false).stream(objects),
            };
            println!(
                "{name:18} {seed:5} {:7} {:9.3} {:10.2}",
                report.errors, report.accuracy, report.mean_cost
            );
            sum.0 += report.accuracy;
            sum.1 += report.mean_cost;
        }
        let n = seeds as f64;
        println!(
            "{name:18}  mean         {:9.3} {:10.2}",
            sum.0 / n,
            sum.1 / n
        );
    }
    Ok(())
}
