//! The goals of the beyond-the-paper settings on one map and ten seeds: for each named
//! configuration, how many seeds reached policy quality 0.95, and the means of the
//! features per description, the descriptions, the sensing cost until the quality was
//! reached and the final quality.
//!
//! `cargo run --release -p csql --example beyond -- tan8x8 1 10`

use csql::{RunSettings, StrategyKind};

fn main() -> Result<(), csql::Error> {
    let args: Vec<String> = std::env::args().collect();
    let map = args.get(1).map_or("tan8x8", String::as_str);
    let first: u64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(1);
    let seeds: u64 = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(10);
    let only = args.get(4).cloned();
    let configs: [(&str, &str); 8] = [
        ("deterministic beta 1", ""),
        ("deterministic beta 0.2", "beta = 0.2"),
        (
            "slip 0.1 beta 0.2 decrease",
            "beta = 0.2\nmax_trials = 3000\n[world]\nslip = 0.1",
        ),
        (
            "slip 0.1 beta 0.2 statistical",
            "beta = 0.2\nmax_trials = 3000\n[world]\nslip = 0.1\n[extensions]\ndetector = \"statistical\"",
        ),
        (
            "noise 0.05 exact",
            "max_trials = 3000\n[world]\nsensor_noise = 0.05",
        ),
        (
            "noise 0.05 nearest",
            "max_trials = 3000\n[world]\nsensor_noise = 0.05\n[extensions]\nmatching = \"nearest\"",
        ),
        ("radius 1", "max_trials = 3000\n[world]\nsensing_radius = 1"),
        ("radius 2", "max_trials = 3000\n[world]\nsensing_radius = 2"),
    ];
    println!(
        "| configuration | reached 0.95 | features/description | descriptions | cost to quality (or converge) | trials | final quality |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (name, toml) in configs {
        if only.as_deref().is_some_and(|o| !name.contains(o)) {
            continue;
        }
        let (mut reached, mut feats, mut descs, mut cost, mut trials, mut quality) =
            (0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for seed in first..first + seeds {
            let mut s = RunSettings::tan1991(map, StrategyKind::Lazy, seed);
            s.apply_toml(toml, name)?;
            let r = csql::run(&s)?;
            let (ok, c, t, q, f, d) = match &r.quality {
                Some(q) => (
                    q.trials_to_quality.is_some(),
                    q.cost_to_quality.unwrap_or(r.total_cost),
                    q.trials_to_quality.unwrap_or(r.trials),
                    q.policy_quality,
                    q.mean_features,
                    q.descriptions as f64,
                ),
                None => (
                    r.converged,
                    r.table1.cost_to_converge.unwrap_or(r.total_cost),
                    r.table1.trials_to_converge.unwrap_or(r.trials),
                    1.0,
                    r.table1.mean_features.unwrap_or(f64::NAN),
                    r.table1.descriptions.map_or(f64::NAN, |d| d as f64),
                ),
            };
            reached += u32::from(ok);
            feats += f;
            descs += d;
            cost += c;
            trials += f64::from(t);
            quality += q;
        }
        let n = seeds as f64;
        println!(
            "| {name} | {reached}/{seeds} | {:.2} | {:.1} | {:.0} | {:.0} | {:.3} |",
            feats / n,
            descs / n,
            cost / n,
            trials / n,
            quality / n
        );
    }
    Ok(())
}
