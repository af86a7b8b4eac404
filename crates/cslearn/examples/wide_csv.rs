//! How the time to read a data set grows with its number of columns: one row, 20,000
//! columns against 100,000 (and any others asked for), with a price for each.
//!
//! ```text
//! cargo run --release -p cslearn --example wide_csv -- [COLUMNS...]
//! ```
//!
//! Reading is linear in the file: the header and the costs file are indexed once (a
//! `BTreeMap`, so a lookup is logarithmic), never searched per column. It prints the
//! seconds of each read (the median of three) and, for each size, the ratio of its time
//! to the first size's time beside the ratio of the sizes; a quadratic reader would show
//! the square of the size ratio (25 for 100k against 20k; it took 22 s against 0.5 s).

use std::fmt::Write as _;
use std::time::Instant;

use cslearn::{Dataset, DatasetOptions};

/// A one-row data set of `columns` feature columns and a target, and its price list.
fn generate(columns: usize) -> (String, String) {
    let mut header = String::new();
    let mut row = String::new();
    let mut costs = String::from("feature,cost\n");
    for j in 0..columns {
        write!(header, "c{j},").unwrap();
        write!(row, "{},", j % 7).unwrap();
        writeln!(costs, "c{j},{}", 1 + j % 10).unwrap();
    }
    (format!("{header}t\n{row}yes\n"), costs)
}

fn seconds(columns: usize) -> f64 {
    let (data, costs) = generate(columns);
    let mut times: Vec<f64> = (0..3)
        .map(|_| {
            let start = Instant::now();
            let ds = Dataset::from_readers(
                data.as_bytes(),
                "wide.csv",
                costs.as_bytes(),
                "costs.csv",
                &DatasetOptions::new("t"),
            )
            .expect("the generated data reads");
            assert_eq!(ds.feature_count(), columns);
            start.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[1]
}

fn main() {
    let mut sizes: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a number of columns"))
        .collect();
    if sizes.is_empty() {
        sizes = vec![20_000, 100_000];
    }
    let base = seconds(sizes[0]);
    println!(
        "{:>9}  {:>9}  {:>10}  {:>10}",
        "columns", "seconds", "time ratio", "size ratio"
    );
    for &n in &sizes {
        let t = if n == sizes[0] { base } else { seconds(n) };
        println!(
            "{n:>9}  {t:>9.4}  {:>10.2}  {:>10.2}",
            t / base,
            n as f64 / sizes[0] as f64
        );
    }
}
