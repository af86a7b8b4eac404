//! The report of a reproduction, from its results: Table 1 beside the paper's with the
//! reference points and the reading (`table1.md`), its CSV, the runs (`runs.jsonl`) and
//! the figures.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use csql::{Reference, RunReport, RunSettings, Setup, StateTree, StrategyKind, Table1Row};

use super::{Results, published};
use crate::figures;
use crate::fit::published::Target;
use crate::stats::{Summary, rows, summary};

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
            self.paper(published::CHEAPEST_INTERIOR)
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
        Some(crate::fit::score(&means, &Target::paper()))
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
                    self.paper_in(published::RESETTING_OVER_LAZY_RANDOM)
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
                    self.paper_in(published::MEAN_FEATURES)
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
            self.paper(published::REPRESENTATION_SHARE)
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
                    self.paper(published::BREAK_EVEN),
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
                    self.paper(published::RESETTING_AFTER_SUFFICIENT),
                    ft.map_or("?".into(), |m| format!("{:.0}", m.mean)),
                    fc.map_or("?".into(), |m| format!("{:.0}", m.mean)),
                    extra.join(" and "),
                    self.paper(published::HEURISTICS_AFTER_SUFFICIENT)
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

/// `table1.md` (the table `md`), `table1.csv`, `runs.jsonl` and the figures into `out`:
/// the files written, in order.
pub(crate) fn write(res: &Results, md: &str, out: &Path) -> Result<Vec<PathBuf>> {
    let write = |name: &str, text: &str| -> Result<PathBuf> {
        let path = out.join(name);
        crate::files::write_atomic(&path, text)
            .with_context(|| format!("cannot write {}", path.display()))?;
        Ok(path)
    };
    let mut written = vec![write("table1.md", md)?, write("table1.csv", &res.csv())?];
    let mut jsonl = String::new();
    for (_, runs, _) in &res.runs {
        for r in runs {
            jsonl.push_str(&serde_json::to_string(r)?);
            jsonl.push('\n');
        }
    }
    written.push(write("runs.jsonl", &jsonl)?);
    written.extend(write_figures(res, out)?);
    Ok(written)
}

/// The figures of a reproduction.
pub(crate) fn write_figures(res: &Results, out: &Path) -> Result<Vec<PathBuf>> {
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
            "Figure 5 on tan3x3: {} descriptions for {} states (the paper: {})",
            rep3.len(),
            setup3.map.states().len(),
            published::FIGURE5_DESCRIPTIONS
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
