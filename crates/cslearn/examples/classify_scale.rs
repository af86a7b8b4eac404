//! How the time per object of streaming a data set through a learner grows with the
//! number of objects: the indexed procedure against the plain one, on generated data.
//!
//! ```text
//! cargo run --release -p cslearn --example classify_scale -- [OPTIONS]
//!   --rows 1000,2000,5000,10000,20000,40000   data set sizes (objects)
//!   --learner cs-id3|id3|cs-ibl               the learner (default cs-id3)
//!   --reference N                             also run the plain procedure up to N rows
//!                                             (default 10000; 0 for never), check that
//!                                             it reports the same, and print the ratio
//!   --seed S                                  the generator's and the stream's seed (1)
//!   --repeat K                                run the indexed procedure K times per size
//!                                             and take the median time (default 5)
//!   --features F                              the number of features (default 30)
//!   --classes K                               the number of classes (default 2; more
//!                                             than 2 draws each label uniformly)
//!   --write DIR                               write each data set as DIR/rows-N.csv and
//!                                             the prices as DIR/costs.csv, for
//!                                             `csrl classify`, and exit
//! ```
//!
//! # The generated data
//!
//! 30 nominal features `f00`..`f29` of four values `a`..`d` each, drawn uniformly and
//! independently by a `Xoshiro256PlusPlus` generator seeded with the seed; the price of
//! feature j is 1 + j (so the cheap features come first). Two classes, `yes` when
//! `f02 + f05 + f09 >= 5` (values counted from 0), else `no`; then 5% of the labels are
//! flipped, so that the library keeps growing with contradictions as real data would. Rows of the same seed share their prefix: the 2,000-row set begins with the
//! 1,000-row set.
//!
//! With `--features F` below 10 the rule reads the first three features (or all of them,
//! when fewer), `yes` when their sum is at least 5. With `--classes K` above 2 each label is
//! drawn uniformly from `c0`..`c{K-1}` instead: no structure, and as many classes as the
//! rows allow (the case of a data set whose target is nearly an identifier).
//!
//! # What it prints
//!
//! Per size: the CPU seconds (median of `--repeat` runs) of streaming the data once (in the seeded random order of
//! `csrl classify --seed`), objects per second, microseconds per object, the process's
//! peak memory so far, and, with the reference, the plain procedure's seconds and the
//! ratio. Then the least-squares exponent b of time per object ~ rows^b over the sizes.
//! CPU time is the thread's own (`/proc/self/schedstat`), so other work on the machine
//! does not count; where that file is missing, wall time is used and the table says so.

use std::fmt::Write as _;
use std::time::Instant;

use cslearn::{Dataset, DatasetOptions, LearnerKind, Procedure, StreamReport};
use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// The data set of `rows` objects of `features` features and `classes` classes, and the
/// price list, as CSV text.
fn generate(rows: usize, features: usize, classes: usize, seed: u64) -> (String, String) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut data = String::new();
    let names: Vec<String> = (0..features).map(|j| format!("f{j:02}")).collect();
    writeln!(data, "{},class", names.join(",")).unwrap();
    let rule: Vec<usize> = if features >= 10 {
        vec![2, 5, 9]
    } else {
        (0..features.min(3)).collect()
    };
    for _ in 0..rows {
        let x: Vec<u32> = (0..features).map(|_| rng.random_range(0..4)).collect();
        let label = if classes > 2 {
            format!("c{}", rng.random_range(0..classes))
        } else {
            let mut yes = rule.iter().map(|&j| x[j]).sum::<u32>() >= 5;
            if rng.random_bool(0.05) {
                yes = !yes;
            }
            String::from(if yes { "yes" } else { "no" })
        };
        for &v in &x {
            data.push(char::from(b'a' + v as u8));
            data.push(',');
        }
        data.push_str(&label);
        data.push('\n');
    }
    let mut costs = String::from("feature,cost\n");
    for (j, name) in names.iter().enumerate() {
        writeln!(costs, "{name},{}", j + 1).unwrap();
    }
    (data, costs)
}

/// CPU seconds of this thread, or wall seconds since `start` where the kernel does not
/// tell; and which it was.
fn seconds(start: Instant) -> (f64, &'static str) {
    std::fs::read_to_string("/proc/self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or((start.elapsed().as_secs_f64(), "wall"), |ns| {
            (ns * 1e-9, "cpu")
        })
}

/// The peak resident memory of the process so far, in MiB.
fn peak_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn timed(
    data: &Dataset,
    kind: LearnerKind,
    seed: u64,
    procedure: Procedure,
) -> (StreamReport, f64, &'static str) {
    let clock = Instant::now();
    let (before, _) = seconds(clock);
    let report = cslearn::stream_dataset_with(data, kind, seed, procedure);
    let (after, how) = seconds(clock);
    (report, after - before, how)
}

/// The least-squares slope of ln y against ln x.
fn exponent(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = points.iter().map(|&(x, y)| (x.ln(), y.ln())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

struct Options {
    rows: Vec<usize>,
    kind: LearnerKind,
    name: String,
    reference: usize,
    seed: u64,
    repeat: usize,
    write: Option<std::path::PathBuf>,
    features: usize,
    classes: usize,
}

fn options() -> Result<Options, String> {
    let mut o = Options {
        rows: vec![1000, 2000, 5000, 10_000, 20_000, 40_000],
        kind: LearnerKind::CsId3,
        name: "cs-id3".into(),
        reference: 10_000,
        seed: 1,
        repeat: 5,
        write: None,
        features: 30,
        classes: 2,
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let mut value = || args.next().ok_or(format!("{flag} needs a value"));
        match flag.as_str() {
            "--rows" => {
                o.rows = value()?
                    .split(',')
                    .map(|r| r.parse().map_err(|e| format!("--rows {r}: {e}")))
                    .collect::<Result<_, _>>()?;
            }
            "--learner" => {
                o.name = value()?;
                o.kind = match o.name.as_str() {
                    "cs-id3" => LearnerKind::CsId3,
                    "id3" => LearnerKind::Id3,
                    "cs-ibl" => LearnerKind::CsIbl { tolerance: 1 },
                    other => return Err(format!("unknown learner {other}")),
                };
            }
            "--reference" => o.reference = value()?.parse().map_err(|e| format!("{e}"))?,
            "--seed" => o.seed = value()?.parse().map_err(|e| format!("{e}"))?,
            "--repeat" => o.repeat = value()?.parse().map_err(|e| format!("{e}"))?,
            "--features" => o.features = value()?.parse().map_err(|e| format!("{e}"))?,
            "--classes" => o.classes = value()?.parse().map_err(|e| format!("{e}"))?,
            "--write" => o.write = Some(value()?.into()),
            other => return Err(format!("unknown option {other}")),
        }
    }
    Ok(o)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let o = options()?;
    if let Some(dir) = &o.write {
        std::fs::create_dir_all(dir)?;
        for &rows in &o.rows {
            let (data, costs) = generate(rows, o.features, o.classes, o.seed);
            std::fs::write(dir.join(format!("rows-{rows}.csv")), data)?;
            std::fs::write(dir.join("costs.csv"), costs)?;
        }
        return Ok(());
    }
    println!(
        "{} on {} features, {} classes, seed {}; plain procedure up to {} rows",
        o.name, o.features, o.classes, o.seed, o.reference
    );
    println!(
        "| rows | seconds | objects/s | µs/object | peak MiB | plain seconds | plain / indexed | accuracy | cost/object |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut points = Vec::new();
    let mut plain_points = Vec::new();
    let mut clock_kind = "cpu";
    for &rows in &o.rows {
        let (data, costs) = generate(rows, o.features, o.classes, o.seed);
        let options = DatasetOptions::new("class");
        let data = Dataset::from_readers(
            data.as_bytes(),
            "generated.csv",
            costs.as_bytes(),
            "costs.csv",
            &options,
        )?;
        // The median of several runs: on a machine shared with other work even CPU time
        // varies from run to run (caches, a sibling hyperthread).
        let mut runs: Vec<(StreamReport, f64, &str)> = (0..o.repeat.max(1))
            .map(|_| timed(&data, o.kind, o.seed, Procedure::Indexed))
            .collect();
        runs.sort_by(|a, b| a.1.total_cmp(&b.1));
        let (report, secs, how) = runs[runs.len() / 2];
        clock_kind = how;
        let peak = peak_mib().map_or("n/a".into(), |m| format!("{m:.0}"));
        let (plain, ratio) = if rows <= o.reference {
            let (reference, plain, _) = timed(&data, o.kind, o.seed, Procedure::Plain);
            assert_eq!(reference, report, "the plain procedure reports differently");
            plain_points.push((rows as f64, plain / rows as f64));
            (format!("{plain:.3}"), format!("{:.1}x", plain / secs))
        } else {
            ("-".into(), "-".into())
        };
        points.push((rows as f64, secs / rows as f64));
        println!(
            "| {rows} | {secs:.3} | {:.0} | {:.1} | {peak} | {plain} | {ratio} | {:.3} | {:.2} |",
            rows as f64 / secs,
            secs / rows as f64 * 1e6,
            report.accuracy,
            report.mean_cost,
        );
    }
    println!(
        "(seconds: {clock_kind} time of the stream alone, data generation and loading excluded)"
    );
    if points.len() >= 2 {
        println!(
            "time per object ~ rows^{:.2} (indexed, over {} sizes)",
            exponent(&points),
            points.len()
        );
    }
    if plain_points.len() >= 2 {
        println!(
            "time per object ~ rows^{:.2} (plain, over {} sizes)",
            exponent(&plain_points),
            plain_points.len()
        );
    }
    Ok(())
}
