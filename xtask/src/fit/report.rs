//! The search's report, from what it found: `report.md` (the chosen layout with its
//! scores on the three sets of seeds and its means against the target, the scores of the
//! random layouts, the local searches and the candidates) and the chosen map,
//! `fitted.toml`.

use std::fmt::Write as _;

use anyhow::Result;

use super::published::Target;
use super::{Cache, FitArgs, Found};
use crate::stats::Summary;

/// `report.md` and `fitted.toml` into `--out`, and the report on stdout.
pub(crate) fn write(args: &FitArgs, target: &Target, cache: &Cache, found: Found) -> Result<()> {
    let Found {
        search,
        select,
        report,
        random_scores,
        restarts,
        trail,
        candidates,
        best,
        select_score,
        elapsed,
    } = found;
    let report_score = cache.score(&best, &report, target);
    let mut s = String::new();
    let _ = writeln!(s, "# fit-map\n");
    let _ = writeln!(s, "Command: `cargo xtask fit-map {}`\n", command_line(args));
    let _ = writeln!(
        s,
        "Search seeds {:?}, selection seeds {:?}, report seeds {:?}; {} runs in the evaluations file; {elapsed:.0} s for this invocation (runs already in the file are not made again).\n",
        span(&search),
        span(&select),
        span(&report),
        cache.runs.len()
    );
    let _ = writeln!(s, "## Chosen layout\n\n```text\n{}\n```\n", best.text());
    let _ = writeln!(
        s,
        "| seeds | score |\n|---|---|\n| search ({} per strategy) | {} |\n| selection ({} per strategy) | {} |\n| report, unseen ({} per strategy) | {} |\n",
        search.len(),
        show(cache.score(&best, &search, target)),
        select.len(),
        show(Some(select_score)),
        report.len(),
        show(report_score)
    );
    if let Some(m) = cache.means(&best, &report) {
        let _ = writeln!(
            s,
            "Means on the report seeds against the target:\n\n| row | resetting | lazy | random | eager |\n|---|---|---|---|---|"
        );
        for ((row, ours), (_, theirs)) in m.iter().zip(target.0.iter()) {
            let cells: Vec<String> = (0..4)
                .map(|j| format!("{:.1} ({})", ours[j], theirs[j]))
                .collect();
            let _ = writeln!(s, "| {} | {} |", row.number(), cells.join(" | "));
        }
        s.push('\n');
    }
    let ok: Vec<f64> = random_scores.iter().flatten().copied().collect();
    let _ = writeln!(
        s,
        "## Random layouts\n\n{} uniformly random layouts, scored on the search seeds; {} had a run that did not converge within {} trials.\n",
        random_scores.len(),
        random_scores.len() - ok.len(),
        args.max_trials
    );
    if !ok.is_empty() {
        let q = quantiles(&ok);
        let _ = writeln!(
            s,
            "| {} |\n|{}\n| {} |\n",
            q.iter().map(|x| x.0).collect::<Vec<_>>().join(" | "),
            "---|".repeat(q.len()),
            q.iter()
                .map(|x| format!("{:.3}", x.1))
                .collect::<Vec<_>>()
                .join(" | ")
        );
        if let Some(m) = Summary::of(&ok) {
            let _ = writeln!(s, "Mean {:.3}, standard deviation {:.3}.\n", m.mean, m.sd);
        }
    }
    let _ = writeln!(
        s,
        "## Local search\n\nBest score on the search seeds per restart after each round:\n\n| round | {} |\n|---|{}",
        (1..=restarts)
            .map(|i| format!("restart {i}"))
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(restarts)
    );
    s.push_str(&trail);
    let _ = writeln!(
        s,
        "\n## Candidates\n\n| # | search score | selection score | layout |\n|---|---|---|---|"
    );
    for (i, (sc, l)) in candidates.iter().enumerate() {
        let _ = writeln!(
            s,
            "| {} | {sc:.3} | {} | `{}` |",
            i + 1,
            show(cache.score(l, &select, target)),
            l.key()
        );
    }
    let report_path = args.out.join("report.md");
    crate::files::write_atomic(&report_path, &s)?;
    let map_path = args.out.join("fitted.toml");
    let map = best.map("fitted")?;
    crate::files::write_atomic(&map_path, map.to_toml())?;
    crate::emit(&format!(
        "{s}\nWrote:\n  {}\n  {}\n  {}\n",
        report_path.display(),
        map_path.display(),
        args.out.join("evaluations.jsonl").display()
    ))?;
    Ok(())
}

fn show(x: Option<f64>) -> String {
    x.map_or("no score".into(), |x| format!("{x:.3}"))
}

/// The quantiles of some values: min, 10%, 25%, median, 75%, 90%, max (nearest rank).
fn quantiles(values: &[f64]) -> Vec<(&'static str, f64)> {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let at = |q: f64| v[((q * (v.len() - 1) as f64).round()) as usize];
    vec![
        ("min", at(0.0)),
        ("10%", at(0.1)),
        ("25%", at(0.25)),
        ("median", at(0.5)),
        ("75%", at(0.75)),
        ("90%", at(0.9)),
        ("max", at(1.0)),
    ]
}

fn span(seeds: &[u64]) -> std::ops::RangeInclusive<u64> {
    seeds[0]..=seeds[seeds.len() - 1]
}

/// The arguments as they would be typed (for the report).
fn command_line(a: &FitArgs) -> String {
    let mut s = format!(
        "--seed {} --width {} --height {} --obstacles {} --random {} --restarts {} --rounds {} --neighbours {} --candidates {} --search-seeds {} --select-seeds {} --report-seeds {} --max-trials {}",
        a.seed,
        a.width,
        a.height,
        a.obstacles,
        a.random,
        a.restarts,
        a.rounds,
        a.neighbours,
        a.candidates,
        a.search_seeds,
        a.select_seeds,
        a.report_seeds,
        a.max_trials
    );
    if let Some(t) = &a.target {
        let _ = write!(s, " --target {}", t.display());
    }
    s
}
