//! The goals of the beyond-the-paper settings on one map and ten seeds: for each named
//! configuration, how many seeds reached policy quality 0.95, and the means of the
//! features per description, the descriptions, the sensing cost until the quality was
//! reached and the final quality.
//!
//! `cargo run --release -p csql --example beyond -- tan8x8 1 10 [NAME-PART]`

use csql::{RunSettings, StrategyKind};

fn main() -> Result<(), csql::Error> {
    let args: Vec<String> = std::env::args().collect();
    let map = args.get(1).map_or("tan8x8", String::as_str);
    let first: u64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(1);
    let seeds: u64 = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(10);
    let only = args.get(4).cloned();
    let noise =
        "beta = 0.2\nmax_trials = 1500\n[world]\nsensor_noise = 0.05\n[judge]\nquality_every = 25";
    let radius = "max_trials = 1500\n[world]\nsensing_radius = 1\n[judge]\nquality_every = 25";
    let configs: Vec<(&str, String)> = vec![
        ("deterministic beta 1", String::new()),
        ("deterministic beta 0.2", "beta = 0.2".into()),
        (
            "slip 0.1 beta 0.2 decrease",
            "beta = 0.2\nmax_trials = 3000\n[world]\nslip = 0.1".into(),
        ),
        (
            "slip 0.1 beta 0.2 statistical",
            "beta = 0.2\nmax_trials = 3000\n[world]\nslip = 0.1\n[extensions]\ndetector = \"statistical\"".into(),
        ),
        ("noise 0.05 exact", noise.into()),
        ("noise 0.05 nearest", format!("{noise}\nmatching = \"nearest\"")),
        (
            "noise 0.05 nearest statistical confirm 3",
            format!("{noise}\nmatching = \"nearest\"\ndetector = \"statistical\"\nconfirm_new = 3"),
        ),
        (
            "noise 0.05 nearest statistical confirm 3 reads 5",
            format!("{noise}\nmatching = \"nearest\"\ndetector = \"statistical\"\nconfirm_new = 3\nreads = 5"),
        ),
        ("radius 2", "max_trials = 1500\n[world]\nsensing_radius = 2".into()),
        ("radius 1", radius.into()),
        ("radius 1 memory 1", format!("{radius}\nmemory = 1")),
        ("radius 1 memory 2", format!("{radius}\nmemory = 2")),
        ("radius 1 full sensing", format!("learner = \"full-sensing\"\n{radius}")),
        ("radius 1 u-tree", format!("learner = \"u-tree\"\n{radius}")),
    ];
    println!(
        "| configuration | reached 0.95 | features/description | descriptions | cost to quality (or converge) | trials | final quality |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (name, toml) in &configs {
        if only.as_deref().is_some_and(|o| !name.contains(o)) {
            continue;
        }
        let (mut reached, mut feats, mut descs, mut cost, mut trials, mut quality) =
            (0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for seed in first..first + seeds {
            let mut s = RunSettings::tan1991(map, StrategyKind::Lazy, seed);
            s.apply_toml(toml, name)?;
            let r = csql::run(&s)?;
            let q = &r.quality;
            let (ok, c, t, f, d) = match r.judged_by {
                csql::Judging::Quality => (
                    q.trials_to_quality.is_some(),
                    q.cost_to_quality.unwrap_or(r.total_cost),
                    q.trials_to_quality.unwrap_or(r.trials),
                    q.mean_features,
                    q.descriptions as f64,
                ),
                csql::Judging::Oracle => (
                    r.converged,
                    r.table1.cost_to_converge.unwrap_or(r.total_cost),
                    r.table1.trials_to_converge.unwrap_or(r.trials),
                    r.table1.mean_features.unwrap_or(f64::NAN),
                    r.table1.descriptions.map_or(f64::NAN, |d| d as f64),
                ),
            };
            let q = q.policy_quality;
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
