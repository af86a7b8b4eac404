//! `cargo xtask reproduce`: the paper's Table 1 and Figures 4b and 5, beside ours.
//!
//! Seeds: run `i` (from 0) of every strategy uses seed `S + i`, so the strategies are
//! compared on the same seeds and the full-sensing reference uses them too. The results
//! are collected in job order, so they do not depend on the number of threads.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use csql::{Reference, RunReport, RunSettings, Setup, StateTree, StrategyKind, Table1Row};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use crate::figures;
use crate::files::pool;
pub use crate::results::ReproduceArgs;
use crate::results::Results;
use crate::stats::{Summary, rows, summary};

/// The committed copy of the default table.
const COMMITTED: &str = "docs/table1.md";

/// The committed copies of figures, refreshed by `--bless`.
const BLESSED_FIGURES: [&str; 7] = [
    "learning_curves.svg",
    "policy_tan8x8_lazy.svg",
    "descriptions_tan8x8_lazy.svg",
    "descriptions_tan8x8_lazy.md",
    "tree_tan8x8_resetting.svg",
    "tree_tan8x8_resetting.dot",
    "figure5_tan3x3.svg",
];

#[derive(Clone, Copy, Debug)]
enum Job {
    Csql { strategy: StrategyKind, run: u64 },
    FullSensing { run: u64 },
}

enum Outcome {
    Csql {
        report: Box<RunReport>,
        fixed: Reference,
    },
    FullSensing(Reference),
}

fn progress(len: u64, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(len);
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} runs ({elapsed})")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    bar
}

/// Run every job of a reproduction.
pub fn compute(args: &ReproduceArgs) -> Result<Results> {
    crate::files::seeds(args.seed, args.runs)?;
    if args.strategies.is_empty() {
        bail!("--strategies must name at least one strategy");
    }
    crate::files::distinct("--strategies", &args.strategies)?;
    let base = RunSettings::tan1991(&args.map, StrategyKind::Resetting, args.seed);
    let setup = Setup::new(&base)?;
    let mut jobs = Vec::new();
    for &strategy in &args.strategies {
        jobs.extend((0..args.runs).map(|run| Job::Csql { strategy, run }));
    }
    jobs.extend((0..args.runs).map(|run| Job::FullSensing { run }));
    let bar = progress(jobs.len() as u64, &format!("CS-QL on {}", setup.map.name()));
    let outcomes: Vec<Outcome> = pool(args.threads)?.install(|| {
        jobs.par_iter()
            .map(|&job| -> Result<Outcome> {
                let out = match job {
                    Job::Csql { strategy, run } => {
                        let mut settings = base.clone();
                        settings.learner = csql::LearnerSettings::cs_ql(strategy);
                        settings.seed = args.seed + run;
                        let (report, rep) = csql::run_with_representation(&setup, &settings)?;
                        let fixed = csql::fixed_representation_reference(&setup, &settings, rep);
                        Outcome::Csql {
                            report: Box::new(report),
                            fixed,
                        }
                    }
                    Job::FullSensing { run } => {
                        let mut settings = base.clone();
                        settings.seed = args.seed + run;
                        Outcome::FullSensing(csql::full_sensing_reference(&setup, &settings))
                    }
                };
                bar.inc(1);
                Ok(out)
            })
            .collect::<Result<Vec<_>>>()
    })?;
    bar.finish_and_clear();
    let mut runs: Vec<(StrategyKind, Vec<RunReport>, Vec<Reference>)> = args
        .strategies
        .iter()
        .map(|&k| (k, Vec::new(), Vec::new()))
        .collect();
    let mut full = Vec::new();
    for (job, outcome) in jobs.iter().zip(outcomes) {
        match (job, outcome) {
            (Job::Csql { strategy, .. }, Outcome::Csql { report, fixed }) => {
                let slot = runs
                    .iter_mut()
                    .find(|r| r.0 == *strategy)
                    .expect("asked for");
                slot.1.push(*report);
                slot.2.push(fixed);
            }
            (Job::FullSensing { .. }, Outcome::FullSensing(r)) => full.push(r),
            _ => unreachable!("outcomes follow their jobs"),
        }
    }
    Ok(Results {
        args: args.clone(),
        setup,
        runs,
        full,
    })
}

impl Results {
    fn strategy(&self, k: StrategyKind) -> Option<&(StrategyKind, Vec<RunReport>, Vec<Reference>)> {
        self.runs.iter().find(|r| r.0 == k)
    }

    fn mean(&self, k: StrategyKind, row: Table1Row) -> Option<f64> {
        self.strategy(k)
            .and_then(|r| summary(&r.1, row))
            .map(|s| s.mean)
    }

    /// `table1.csv`: one line per (row, strategy).
    pub fn csv(&self) -> String {
        let mut s = String::from("row,strategy,paper,n,mean,sd,min,max\n");
        for (name, _, row) in rows() {
            for (k, runs, _) in &self.runs {
                let paper = row
                    .paper(*k)
                    .filter(|_| self.args.on_papers_map())
                    .map_or(String::new(), |p| p.to_string());
                let cell = |x: f64| format!("{x:.6}");
                match summary(runs, row) {
                    Some(m) => {
                        let _ = writeln!(
                            s,
                            "\"{name}\",{k},\"{paper}\",{},{},{},{},{}",
                            m.n,
                            cell(m.mean),
                            cell(m.sd),
                            cell(m.min),
                            cell(m.max)
                        );
                    }
                    None => {
                        let _ = writeln!(s, "\"{name}\",{k},\"{paper}\",0,,,,");
                    }
                }
            }
        }
        s
    }

    /// `table1.md`: the table beside the paper's, the references and the reading.
    pub fn markdown(&self) -> String {
        let a = &self.args;
        let mut s = String::new();
        if a.on_papers_map() {
            let _ = writeln!(s, "# Table 1: the paper's figures and ours\n");
        } else {
            let _ = writeln!(s, "# Table 1 on `{}`\n", a.map);
        }
        let _ = writeln!(
            s,
            "Map `{}` ({} states), {} runs per strategy with seeds {}..={}, the paper's parameters \
             (beta 1, gamma 0.9, T 0.4, 100 moves per trial, 20 random moves). Ours: mean ± \
             standard deviation [min–max] over the runs that reached the figure. Made by \
             `cargo xtask reproduce{}`.\n",
            self.setup.map.name(),
            self.setup.map.states().len(),
            a.runs,
            a.seed,
            a.seed + a.runs - 1,
            if a.is_default() {
                String::new()
            } else {
                format!(
                    " --map {} --runs {} --seed {} --strategies {}",
                    a.map,
                    a.runs,
                    a.seed,
                    a.strategies
                        .iter()
                        .map(|k| k.name())
                        .collect::<Vec<_>>()
                        .join(",")
                )
            }
        );
        let converged: Vec<String> = self
            .runs
            .iter()
            .map(|(k, runs, _)| {
                format!(
                    "{k} {}/{}",
                    runs.iter().filter(|r| r.converged).count(),
                    runs.len()
                )
            })
            .collect();
        let _ = writeln!(
            s,
            "Runs converged to an optimal policy: {}.\n",
            converged.join(", ")
        );
        if let Some(fit) = self.fit_score() {
            let _ = writeln!(
                s,
                "Fit to the paper's Table 1 (the specification's section 6.1: root mean square of ln(ours / paper's) over rows 1 to 4, 6 and 7 of the four strategies): {fit:.3} on these seeds.\n"
            );
        }
        let _ = write!(s, "| row |");
        for (k, _, _) in &self.runs {
            let _ = write!(s, " {k} |");
        }
        let _ = write!(s, "\n|---|");
        for _ in &self.runs {
            let _ = write!(s, "---|");
        }
        s.push('\n');
        for (name, decimals, row) in rows() {
            if a.on_papers_map() && row.paper(StrategyKind::Resetting).is_some() {
                let _ = write!(s, "| {name}, paper |");
                for (k, _, _) in &self.runs {
                    let p = row.paper(*k).map_or(String::new(), |p| p.to_string());
                    let _ = write!(s, " {p} |");
                }
                s.push('\n');
            }
            let _ = write!(s, "| {name}, ours |");
            for (_, runs, _) in &self.runs {
                let cell =
                    summary(runs, row).map_or("not reached".to_string(), |m| m.show(decimals));
                let _ = write!(s, " {cell} |");
            }
            s.push('\n');
        }
        self.references(&mut s);
        self.reading(&mut s);
        s
    }

    fn references(&self, s: &mut String) {
        let _ = writeln!(s, "\n## Reference points\n");
        let full = |f: fn(&Reference) -> f64| {
            Summary::of(
                &self
                    .full
                    .iter()
                    .filter(|r| r.converged)
                    .map(f)
                    .collect::<Vec<_>>(),
            )
        };
        let one_per_state = self.runs.iter().all(|(_, runs, _)| {
            runs.iter()
                .all(|r| r.table1.descriptions == Some(self.setup.map.states().len()))
        });
        if one_per_state {
            let _ = writeln!(
                s,
                "With one description per state, Q-learning on a final representation follows the same trajectories as the plain learner on the same seeds, so their trials agree; only what a classification costs differs.\n"
            );
        }
        let _ = writeln!(
            s,
            "| learner | runs converged | trials to convergence | sensing cost to convergence |"
        );
        let _ = writeln!(s, "|---|---|---|---|");
        let n_full = self.full.iter().filter(|r| r.converged).count();
        let _ = writeln!(
            s,
            "| plain Q-learning, every state identified, sensing the whole bordered world at every classification ({} per classification on average) | {}/{} | {} | {} |",
            self.full
                .first()
                .and_then(|r| r.cost_per_classification)
                .map_or("?".to_string(), |c| format!("{c:.1}")),
            n_full,
            self.full.len(),
            full(|r| f64::from(r.trials)).map_or("not reached".into(), |m| m.show(1)),
            full(|r| r.cost).map_or("not reached".into(), |m| m.show(0)),
        );
        for (k, _, fixed) in &self.runs {
            let conv: Vec<&Reference> = fixed.iter().filter(|r| r.converged).collect();
            let _ = writeln!(
                s,
                "| Q-learning from zero on the final representation of the {k} runs, classifying with CLASSIFY | {}/{} | {} | {} |",
                conv.len(),
                fixed.len(),
                Summary::of(&conv.iter().map(|r| f64::from(r.trials)).collect::<Vec<_>>())
                    .map_or("not reached".into(), |m| m.show(1)),
                Summary::of(&conv.iter().map(|r| r.cost).collect::<Vec<_>>())
                    .map_or("not reached".into(), |m| m.show(0)),
            );
        }
        let cheapest = csql::cheapest_interior_cost(&self.setup.world, &self.setup.space);
        let _ = writeln!(
            s,
            "\nSensing every interior cell once from the cheapest state costs {cheapest:.0}{}.",
            self.paper("at least 256 on its 8 by 8 map")
        );
    }

    /// The fit score (`docs/specification.md`, section 6.1) of the means, on the paper's map with all four strategies.
    fn fit_score(&self) -> Option<f64> {
        if !self.args.on_papers_map() {
            return None;
        }
        let means = crate::fit::Fitted::try_from_fn(|row| {
            let mut means = [0.0; 4];
            for (j, k) in StrategyKind::ALL.iter().enumerate() {
                means[j] = self.mean(*k, row)?;
            }
            Some(means)
        })?;
        Some(crate::fit::score(
            &means,
            &crate::fit::published::Target::paper(),
        ))
    }

    /// ` (the paper: TEXT)` on the paper's map; nothing elsewhere, where the paper's
    /// figures belong to another world.
    fn paper(&self, text: &str) -> String {
        if self.args.on_papers_map() {
            format!(" (the paper: {text})")
        } else {
            String::new()
        }
    }

    /// `; the paper: TEXT` on the paper's map, for inside parentheses; nothing elsewhere.
    fn paper_in(&self, text: &str) -> String {
        if self.args.on_papers_map() {
            format!("; the paper: {text}")
        } else {
            String::new()
        }
    }

    fn reading(&self, s: &mut String) {
        use StrategyKind::{Eager, Lazy, Random, Resetting};
        let _ = writeln!(s, "\n## Reading\n");
        if !self.args.on_papers_map() {
            let _ = writeln!(
                s,
                "This is not the paper's map, so the paper's numbers are not shown. The claims about order (which strategies converge, which cost less, which give the most compact or the largest descriptions, whether classifying is cheaper than sensing everything) can be checked on any map; the paper's own figures (its ratios, shares, break-even and trial counts) belong to its map and are not compared here.\n"
            );
        }
        let have = |k| self.strategy(k).is_some();
        let all = |k: StrategyKind| {
            self.strategy(k)
                .is_some_and(|r| r.1.iter().all(|x| x.converged))
        };
        let verdict = |ok: bool| if ok { "holds" } else { "does not hold" };
        // Claim: all four find the optimal policy.
        let every = self.runs.iter().all(|r| all(r.0));
        let _ = writeln!(
            s,
            "* Every strategy finds the optimal policy in every run: {}.",
            verdict(every)
        );
        if have(Resetting) && have(Lazy) && have(Random) {
            let (r, l, x) = (
                self.mean(Resetting, Table1Row::CostToConverge),
                self.mean(Lazy, Table1Row::CostToConverge),
                self.mean(Random, Table1Row::CostToConverge),
            );
            if let (Some(r), Some(l), Some(x)) = (r, l, x) {
                let _ = writeln!(
                    s,
                    "* Lazy and random cost far less than resetting before convergence: {} (resetting {r:.0}, {:.1} times lazy's {l:.0} and {:.1} times random's {x:.0}{}).",
                    verdict(r > 2.0 * l && r > 2.0 * x),
                    r / l,
                    r / x,
                    self.paper_in("7.2 and 8.3 times")
                );
            }
        }
        let features: Vec<(StrategyKind, f64)> = self
            .runs
            .iter()
            .filter_map(|(k, _, _)| self.mean(*k, Table1Row::MeanFeatures).map(|m| (*k, m)))
            .collect();
        let list = features
            .iter()
            .map(|(k, m)| format!("{k} {m:.2}"))
            .collect::<Vec<_>>()
            .join(", ");
        if features.len() > 1 {
            let min = features
                .iter()
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .expect("some");
            let max = features
                .iter()
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .expect("some");
            if have(Resetting) {
                let _ = writeln!(
                    s,
                    "* Resetting yields the most compact descriptions: {} (mean features per description: {list}{}).",
                    verdict(min.0 == Resetting),
                    self.paper_in("6.4, 6.9, 7.5, 10.2")
                );
            }
            if have(Eager) {
                let _ = writeln!(
                    s,
                    "* Eager yields the largest descriptions: {}.",
                    verdict(max.0 == Eager)
                );
            }
        }
        self.row7(s);
        if have(Eager) {
            for k in [Lazy, Random] {
                if let (Some(kc), Some(ec), Some(kt), Some(et), Some(kd), Some(ed)) = (
                    self.mean(k, Table1Row::CostToConverge),
                    self.mean(Eager, Table1Row::CostToConverge),
                    self.mean(k, Table1Row::TreeCostPerState),
                    self.mean(Eager, Table1Row::TreeCostPerState),
                    self.mean(k, Table1Row::DescriptionCostPerState),
                    self.mean(Eager, Table1Row::DescriptionCostPerState),
                ) {
                    let _ = writeln!(
                        s,
                        "* {k} is more efficient than eager both before convergence and per state after it (the paper's reason not to recommend eager): {} (cost to convergence {kc:.0} against {ec:.0}; tree cost per state {kt:.2} against {et:.2}; description cost per state {kd:.2} against {ed:.2}).",
                        verdict(kc < ec && kt < et && kd < ed)
                    );
                }
            }
        }
        let shares: Vec<String> = self
            .runs
            .iter()
            .filter_map(|(k, _, _)| {
                Some(format!(
                    "{k} {:.0}%",
                    100.0 * self.mean(*k, Table1Row::CostToSufficient)?
                        / self.mean(*k, Table1Row::CostToConverge)?
                ))
            })
            .collect();
        let _ = writeln!(
            s,
            "* Share of the sensing cost to convergence spent learning the representation: {}{}.",
            shares.join(", "),
            self.paper("92%, 89%, 62%, 31%, so 30% to 90%")
        );
        let cheapest = csql::cheapest_interior_cost(&self.setup.world, &self.setup.space);
        let worst8 = self
            .runs
            .iter()
            .filter_map(|(k, _, _)| {
                Some(
                    self.mean(*k, Table1Row::TreeCostPerState)?
                        .max(self.mean(*k, Table1Row::DescriptionCostPerState)?),
                )
            })
            .fold(0.0, f64::max);
        let _ = writeln!(
            s,
            "* Classifying a state after learning is far cheaper than sensing the whole grid once: {} (at most {worst8:.2} per state against {cheapest:.0}).",
            verdict(worst8 < cheapest)
        );
        // The break-even remark.
        if have(Resetting) {
            for k in [Lazy, Random] {
                let (Some(rc), Some(kc)) = (
                    self.mean(Resetting, Table1Row::CostToConverge),
                    self.mean(k, Table1Row::CostToConverge),
                ) else {
                    continue;
                };
                let extra = rc - kc;
                let mut parts = Vec::new();
                for (row, what) in [
                    (Table1Row::TreeCostPerState, "decision tree"),
                    (Table1Row::DescriptionCostPerState, "description features"),
                ] {
                    let (Some(rs), Some(ks)) = (self.mean(Resetting, row), self.mean(k, row))
                    else {
                        continue;
                    };
                    let saving = ks - rs;
                    parts.push(if saving > 0.0 {
                        format!(
                            "by the {what} cost, resetting saves {saving:.2} per state and pays off after {:.0} states",
                            extra / saving
                        )
                    } else {
                        format!("by the {what} cost, resetting saves nothing per state ({rs:.2} against {ks:.2}) and never pays off")
                    });
                }
                let _ = writeln!(
                    s,
                    "* Break-even against {k}{}: resetting spends {extra:.0} more before convergence; {}.",
                    self.paper("about 220,000 future states"),
                    parts.join("; ")
                );
            }
            if let (Some(r2), Some(r4), Some(r1), Some(r3)) = (
                self.mean(Resetting, Table1Row::TrialsToSufficient),
                self.mean(Resetting, Table1Row::Trials),
                self.mean(Resetting, Table1Row::CostToSufficient),
                self.mean(Resetting, Table1Row::CostToConverge),
            ) {
                let fixed = self.strategy(Resetting).map(|r| &r.2).expect("have");
                let ft = Summary::of(
                    &fixed
                        .iter()
                        .map(|r| f64::from(r.trials))
                        .collect::<Vec<_>>(),
                );
                let fc = Summary::of(&fixed.iter().map(|r| r.cost).collect::<Vec<_>>());
                let extra: Vec<String> = [Lazy, Random]
                    .into_iter()
                    .filter_map(|k| {
                        Some(format!(
                            "{k} {:.0}",
                            self.mean(k, Table1Row::Trials)?
                                - self.mean(k, Table1Row::TrialsToSufficient)?
                        ))
                    })
                    .collect();
                let _ = writeln!(
                    s,
                    "* After its representation is sufficient, resetting needs {:.0} more trials and {:.0} more sensing to converge{}; Q-learning started from zero on its final representation needs {} trials and {} sensing. The heuristic strategies need {} more trials after theirs{}.",
                    r4 - r2,
                    r3 - r1,
                    self.paper("76 and 38545"),
                    ft.map_or("?".into(), |m| format!("{:.0}", m.mean)),
                    fc.map_or("?".into(), |m| format!("{:.0}", m.mean)),
                    extra.join(" and "),
                    self.paper("13 and 29")
                );
            }
        }
        if self.args.on_papers_map() {
            let _ = writeln!(
                s,
                "\n`tan8x8` is a reconstruction: the paper's Figure 4a is not in its text. Its layout was chosen by `cargo xtask fit-map` as the one whose Table 1 is closest to the paper's (rows 1 to 4, 6 and 7; see the README), so agreement in rows 1 to 4, 6 and 7 is partly by construction; rows 5 and 8, the reference points and the claims above were not fitted. A layout consistent with the paper's numbers is not the paper's layout."
            );
        }
    }

    /// Row 7, explained where it differs from the paper by more than a fifth.
    fn row7(&self, s: &mut String) {
        let mut parts = Vec::new();
        for (k, runs, _) in &self.runs {
            let Some(ours) = self.mean(*k, Table1Row::MaxFeatures) else {
                continue;
            };
            let paper = Table1Row::MaxFeatures.paper(*k).map(|p| p.value());
            let differs = paper.is_some_and(|p| (ours / p).ln().abs() > 0.2);
            if self.args.on_papers_map() && !differs {
                continue;
            }
            // The largest description of the first run: how far its costliest feature lies.
            let Some(big) = runs[0].descriptions.iter().max_by_key(|d| d.features.len()) else {
                continue;
            };
            let far = big.features.iter().map(|f| f.cost).fold(0.0, f64::max);
            let cheaper = big.features.iter().filter(|f| f.cost < far).count();
            parts.push(format!(
                "{k} {ours:.1}{} (seed {}: its largest description has {} features, {cheaper} of them cheaper than its costliest at distance {far:.0})",
                if self.args.on_papers_map() {
                    format!(" against {}", paper.map_or("?".into(), |p| p.to_string()))
                } else {
                    String::new()
                },
                runs[0].seed,
                big.features.len(),
            ));
        }
        if parts.is_empty() {
            if self.args.on_papers_map() {
                let _ = writeln!(
                    s,
                    "* Row 7 (max features in a description) is within a fifth of the paper's for every strategy."
                );
            }
            return;
        }
        let _ = writeln!(
            s,
            "* Row 7 (max features in a description){}: {}. Row 7 is the largest description of a run, one extreme per run. A description grows by the next cheapest feature it lacks, so one whose states first differ at distance d carries most features cheaper than d (4 at distance 1, 12 up to distance 2, 24 up to distance 3): the row is set by the one pair of states that looks alike furthest out, which the layout decides.",
            if self.args.on_papers_map() {
                ", where it differs from the paper's by more than a fifth"
            } else {
                ""
            },
            parts.join("; ")
        );
    }
}

/// The figures of a reproduction.
fn write_figures(res: &Results, out: &Path) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    // The map's name comes from input: made safe before it becomes part of a file name.
    let name = crate::files::safe_name(res.setup.map.name());
    let curves: Vec<figures::Curve> = res
        .runs
        .iter()
        .map(|(k, runs, _)| figures::Curve::of(k.to_string(), runs))
        .collect();
    let path = out.join("learning_curves.svg");
    figures::learning_curves(
        &path,
        &format!(
            "CS-QL on {name}: cumulative sensing cost over {} runs per strategy",
            res.args.runs
        ),
        &curves,
    )?;
    written.push(path);
    // Figure 4b: policy and descriptions of the first run of each strategy.
    for (k, runs, _) in &res.runs {
        let path = out.join(format!("policy_{name}_{k}.svg"));
        crate::files::write_atomic(&path, csql::policy_svg(&res.setup, &runs[0]))?;
        written.push(path);
        let path = out.join(format!("descriptions_{name}_{k}.svg"));
        crate::files::write_atomic(&path, csql::descriptions_svg(&runs[0]))?;
        written.push(path);
        let path = out.join(format!("descriptions_{name}_{k}.md"));
        crate::files::write_atomic(&path, csql::descriptions_table(&runs[0]))?;
        written.push(path);
    }
    // Figure 5d: the tree over the final descriptions of the first run of the first strategy.
    let (k, runs, _) = &res.runs[0];
    let settings = runs[0].settings.clone();
    let (_, rep) = csql::run_with_representation(&res.setup, &settings)?;
    let tree = StateTree::build(&rep, res.setup.space.costs());
    let path = out.join(format!("tree_{name}_{k}.svg"));
    crate::files::write_atomic(
        &path,
        figures::tree_svg(
            tree.tree(),
            &res.setup.space,
            &format!(
                "Decision tree over the {} descriptions ({k}, seed {})",
                rep.len(),
                settings.seed
            ),
        ),
    )?;
    written.push(path);
    let path = out.join(format!("tree_{name}_{k}.dot"));
    crate::files::write_atomic(&path, tree.to_dot(&res.setup.sensed(&settings)))?;
    written.push(path);
    // Figure 5 for tan3x3: descriptions with policy, and tree; only beside the paper's
    // map (the default) or when tan3x3 is the map asked for, never beside another map.
    let tan3x3 = mdp::resolve("tan3x3")?;
    if !(res.args.on_papers_map() || res.setup.map.layout() == tan3x3.layout()) {
        return Ok(written);
    }
    let mut small = RunSettings::tan1991("tan3x3", res.runs[0].0, res.args.seed);
    small.max_trials = settings.max_trials;
    let setup3 = Setup::new(&small)?;
    let (report3, rep3) = csql::run_with_representation(&setup3, &small)?;
    let tree3 = StateTree::build(&rep3, setup3.space.costs());
    let figure5 = figures::side_by_side(
        &format!(
            "Figure 5 on tan3x3: {} descriptions for {} states (the paper: 7)",
            rep3.len(),
            setup3.map.states().len()
        ),
        &[
            csql::policy_svg(&setup3, &report3),
            figures::tree_svg(tree3.tree(), &setup3.space, "decision tree"),
        ],
    );
    let path = out.join("figure5_tan3x3.svg");
    crate::files::write_atomic(&path, figure5)?;
    written.push(path);
    let path = out.join("tree_tan3x3.dot");
    crate::files::write_atomic(&path, tree3.to_dot(&setup3.sensed(&small)))?;
    written.push(path);
    Ok(written)
}

/// `cargo xtask reproduce`.
pub fn run(args: &ReproduceArgs) -> Result<()> {
    if args.check {
        let check = ReproduceArgs {
            runs: 5,
            seed: 1,
            map: "tan8x8".into(),
            strategies: StrategyKind::ALL.to_vec(),
            ..args.clone()
        };
        let fresh = compute(&check)?.markdown();
        let committed = std::fs::read_to_string(COMMITTED).with_context(|| {
            format!("cannot read {COMMITTED}; run `cargo xtask reproduce --bless` to write it")
        })?;
        if fresh == committed {
            crate::emit(&format!("{COMMITTED} is what the code produces today\n"))?;
            return Ok(());
        }
        for (i, (a, b)) in committed.lines().zip(fresh.lines()).enumerate() {
            if a != b {
                crate::note(&format!(
                    "{COMMITTED}:{}: differs\n  committed: {a}\n  now:       {b}",
                    i + 1
                ));
            }
        }
        if committed.lines().count() != fresh.lines().count() {
            crate::note(&format!(
                "{COMMITTED}: {} lines committed, {} produced now",
                committed.lines().count(),
                fresh.lines().count()
            ));
        }
        bail!("{COMMITTED} is out of date: run `cargo xtask reproduce --bless` and commit it");
    }
    if args.bless && !args.is_default() {
        bail!(
            "--bless refreshes the committed default table: it takes the default --map, --runs, --seed and --strategies"
        );
    }
    let res = compute(args)?;
    crate::files::create_dir(&args.out)?;
    let _lock = crate::files::OutLock::acquire(&args.out)?;
    let md = res.markdown();
    let write = |name: &str, text: &str| -> Result<PathBuf> {
        let path = args.out.join(name);
        crate::files::write_atomic(&path, text)
            .with_context(|| format!("cannot write {}", path.display()))?;
        Ok(path)
    };
    let mut written = vec![write("table1.md", &md)?, write("table1.csv", &res.csv())?];
    let mut jsonl = String::new();
    for (_, runs, _) in &res.runs {
        for r in runs {
            jsonl.push_str(&serde_json::to_string(r)?);
            jsonl.push('\n');
        }
    }
    written.push(write("runs.jsonl", &jsonl)?);
    written.extend(write_figures(&res, &args.out)?);
    written.extend(crate::sense::write(&res, &args.out, args.bless)?);
    if args.bless {
        // The committed copies that the README shows and `--check` compares with.
        crate::files::write_atomic(Path::new(COMMITTED), &md)?;
        written.push(PathBuf::from(COMMITTED));
        crate::files::create_dir(Path::new("docs/figures"))?;
        for name in BLESSED_FIGURES {
            let to = Path::new("docs/figures").join(name);
            let from = args.out.join(name);
            let bytes =
                std::fs::read(&from).with_context(|| format!("cannot read {}", from.display()))?;
            crate::files::write_atomic(&to, bytes)?;
            written.push(to);
        }
    }
    let mut text = format!("{md}\nWrote:\n");
    for p in written {
        let _ = writeln!(text, "  {}", p.display());
    }
    crate::emit(&text)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(threads: usize) -> ReproduceArgs {
        ReproduceArgs {
            runs: 2,
            seed: 3,
            map: "tan3x3".into(),
            strategies: vec![StrategyKind::Resetting, StrategyKind::Random],
            threads: Some(threads),
            out: PathBuf::from("unused"),
            check: false,
            bless: false,
        }
    }

    #[test]
    fn results_do_not_depend_on_the_thread_count() {
        let one = compute(&args(1)).unwrap();
        let two = compute(&args(2)).unwrap();
        assert_eq!(one.csv(), two.csv());
        assert_eq!(one.markdown(), two.markdown());
        // The table holds what the runs measured, seeds 3 and 4, in order.
        let seeds: Vec<u64> = one.runs[0].1.iter().map(|r| r.seed).collect();
        assert_eq!(seeds, [3, 4]);
        assert!(one.markdown().contains("resetting 2/2, random 2/2"));
        assert_eq!(one.csv().lines().count(), 1 + 9 * 2);
    }

    #[test]
    fn every_figure_renders_and_is_of_a_sane_size() {
        let a = ReproduceArgs {
            runs: 1,
            seed: 1,
            map: crate::results::PAPERS_MAP.into(),
            strategies: vec![StrategyKind::Resetting, StrategyKind::Lazy],
            threads: Some(2),
            out: PathBuf::from("unused"),
            check: false,
            bless: false,
        };
        let res = compute(&a).unwrap();
        let dir = std::env::temp_dir().join(format!("csrl-figures-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let written = write_figures(&res, &dir).unwrap();
        let svgs: Vec<&PathBuf> = written
            .iter()
            .filter(|p| p.extension().is_some_and(|e| e == "svg"))
            .collect();
        // Curves, a policy and descriptions per strategy, the tree, Figure 5.
        assert_eq!(svgs.len(), 1 + 2 * 2 + 1 + 1, "{written:?}");
        for p in svgs {
            let text = std::fs::read_to_string(p).unwrap();
            let (w, h) = crate::render::check(&text, &p.display().to_string()).unwrap();
            assert!(w >= 200.0 && h >= 150.0, "{}: {w} by {h}", p.display());
            let png = crate::render::png(&text, 0.25, "figure").unwrap();
            assert!(png.starts_with(b"\x89PNG"));
        }
        // The DOT and the description table sit beside the pictures.
        assert!(
            written
                .iter()
                .any(|p| p.extension().is_some_and(|e| e == "dot"))
        );
        assert!(
            written
                .iter()
                .any(|p| p.extension().is_some_and(|e| e == "md"))
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn the_figure_check_refuses_bad_documents() {
        assert!(crate::render::check("<svg", "cut").is_err());
        let huge = r#"<svg xmlns="http://www.w3.org/2000/svg" width="4252" height="600"></svg>"#;
        let e = crate::render::check(huge, "huge").unwrap_err();
        assert!(e.to_string().contains("4252 by 600"), "{e}");
        let fine = r#"<svg xmlns="http://www.w3.org/2000/svg" width="400" height="300"><text x="10" y="20">ok</text></svg>"#;
        assert_eq!(crate::render::check(fine, "fine").unwrap(), (400.0, 300.0));
    }

    #[test]
    fn bless_needs_the_default_arguments_and_the_paper_is_shown_only_on_its_map() {
        let mut a = args(1);
        a.bless = true;
        let e = run(&a).unwrap_err();
        assert!(e.to_string().contains("--bless"), "{e}");
        // tan3x3 is not the paper's map: no paper row, no paper figures in the reading.
        let md = compute(&args(1)).unwrap().markdown();
        assert!(!md.contains(", paper |"));
        assert!(!md.contains("(the paper:"));
        assert!(md.contains("not the paper's map"));
    }

    #[test]
    fn bad_arguments_are_refused() {
        let mut a = args(1);
        a.runs = 0;
        assert!(compute(&a).is_err());
        let mut a = args(1);
        a.map = "no-such-map".into();
        assert!(compute(&a).is_err());
        // Once a panic: a strategy named twice.
        let mut a = args(1);
        a.strategies = vec![StrategyKind::Lazy, StrategyKind::Lazy];
        let err = compute(&a).err().unwrap().to_string();
        assert!(err.contains("twice"), "{err}");
        // Once wrapped around silently: seeds beyond the integer limit.
        let mut a = args(1);
        (a.seed, a.runs) = (u64::MAX, 2);
        let err = compute(&a).err().unwrap().to_string();
        assert!(err.contains("--seed"), "{err}");
        let mut a = args(1);
        a.threads = Some(1_000_000);
        assert!(compute(&a).is_err());
    }

    #[test]
    fn a_map_name_with_path_separators_stays_inside_out() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("evil.toml");
        std::fs::write(&file, "name = \"../../escaped\"\nlayout = '''\n..G\n'''\n").unwrap();
        let mut a = args(1);
        a.map = file.display().to_string();
        a.runs = 1;
        a.strategies = vec![StrategyKind::Eager];
        let res = compute(&a).unwrap();
        let out = dir.path().join("out").join("deeper");
        std::fs::create_dir_all(&out).unwrap();
        let written = write_figures(&res, &out).unwrap();
        for p in &written {
            assert!(
                p.starts_with(&out) && p.parent() == Some(out.as_path()),
                "{}",
                p.display()
            );
        }
        assert!(!dir.path().join("escaped_eager.svg").exists());
    }

    #[test]
    fn figure_5_of_tan3x3_is_written_only_for_the_default_map_or_tan3x3() {
        // Once: `--map my.toml` also wrote figure5_tan3x3.svg and tree_tan3x3.dot.
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("my.toml");
        std::fs::write(&file, "name = \"mine\"\nlayout = '''\n...\n..G\n'''\n").unwrap();
        let names = |map: &str| -> Vec<String> {
            let mut a = args(1);
            (a.map, a.runs, a.strategies) = (map.to_string(), 1, vec![StrategyKind::Lazy]);
            let out = dir.path().join(crate::files::safe_name(map));
            std::fs::create_dir_all(&out).unwrap();
            let written = write_figures(&compute(&a).unwrap(), &out).unwrap();
            written
                .iter()
                .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
                .collect()
        };
        let mine = names(&file.display().to_string());
        assert!(!mine.iter().any(|n| n.contains("tan3x3")), "{mine:?}");
        assert!(mine.contains(&"tree_mine_lazy.dot".to_string()), "{mine:?}");
        let small = names("tan3x3");
        assert!(
            small.contains(&"figure5_tan3x3.svg".to_string()),
            "{small:?}"
        );
        assert!(small.contains(&"tree_tan3x3.dot".to_string()), "{small:?}");
    }
}
