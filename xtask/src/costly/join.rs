//! `--with`: other runs of part of the table join it. A folder of `cargo xtask costly
//! --runs N ...` (the same base seed) gives the rows of its cells: where the table has a
//! row, longer runs of it (at least as many; the runs both hold must agree to the bit, so
//! that a folder made by other code or settings is refused rather than mixed in); where
//! it has none (a learner run only when named), a row added. Each row says how many runs
//! it averages.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Result, bail};

use super::{Definition, Dynamics, JobResult, Learner, PRICES, RULES, WORLDS};

/// A row of the table: world, dynamics, price, rule and learner, as the CSV spells them.
type Cell = (String, Dynamics, String, String, Learner);

fn cell(r: &JobResult) -> Cell {
    (
        r.world.clone(),
        r.dynamics,
        r.price.to_string(),
        r.rule.name().to_string(),
        r.learner,
    )
}

/// The table's results with those of `other` (read from `dir`) in place of its own in
/// every cell `other` covers, or added where it has none. Refused, naming the reason:
/// another base seed, a world, dynamics, price or rule outside the table, fewer runs of a
/// cell than the table's, or a shared run that differs.
pub(crate) fn join(
    table: &Definition,
    results: Vec<JobResult>,
    (other, other_results): (&Definition, Vec<JobResult>),
    dir: &Path,
) -> Result<Vec<JobResult>> {
    let d = dir.display();
    if other.seed != table.seed {
        bail!(
            "--with {d}: its runs start at seed {}, this table's at {}: give it the same --seed",
            other.seed,
            table.seed
        );
    }
    let outside =
        |what: &str| anyhow::anyhow!("--with {d}: it holds {what}, which this table does not");
    if let Some(w) = other.worlds.iter().find(|w| !table.worlds.contains(w)) {
        return Err(outside(WORLDS[*w].0));
    }
    if let Some(x) = other.dynamics.iter().find(|x| !table.dynamics.contains(x)) {
        return Err(outside(x.name()));
    }
    if let Some(p) = other.prices.iter().find(|p| !table.prices.contains(p)) {
        return Err(outside(&format!("price {p}")));
    }
    if let Some(r) = other.rules.iter().find(|r| !table.rules.contains(r)) {
        return Err(outside(r.name()));
    }
    let mut runs: BTreeMap<Cell, u64> = BTreeMap::new();
    for r in &results {
        *runs.entry(cell(r)).or_insert(0) += 1;
    }
    let mine: BTreeMap<(Cell, u64), &JobResult> =
        results.iter().map(|r| ((cell(r), r.seed), r)).collect();
    for r in &other_results {
        let key = cell(r);
        let (world, dynamics, price, rule, learner) = &key;
        let name = format!(
            "{world}, {}, price {price}, {rule}, {}",
            dynamics.name(),
            learner.name()
        );
        if let Some(&n) = runs.get(&key)
            && other.runs < n
        {
            bail!(
                "--with {d}: its {} runs of ({name}) do not extend this table's {n}: give it at \
                 least --runs {n}",
                other.runs
            );
        }
        if let Some(m) = mine.get(&(key.clone(), r.seed)) {
            let same = m.summary.to_bits() == r.summary.to_bits()
                && (m.curve.iter().map(|x| x.to_bits())).eq(r.curve.iter().map(|x| x.to_bits()));
            if !same {
                bail!(
                    "--with {d}: its run of seed {} ({name}) differs from this table's: the two \
                     were made by other code or settings",
                    r.seed
                );
            }
        }
    }
    let covered: std::collections::BTreeSet<Cell> = other_results.iter().map(cell).collect();
    let mut joined: Vec<JobResult> = results
        .into_iter()
        .filter(|r| !covered.contains(&cell(r)))
        .collect();
    joined.extend(other_results);
    Ok(joined)
}

impl Definition {
    /// The command that runs this job list (`cargo xtask costly` and the flags that differ
    /// from the whole table's defaults).
    pub(crate) fn command(&self) -> String {
        let mut line = format!("cargo xtask costly --runs {}", self.runs);
        if self.seed != 1 {
            let _ = write!(line, " --seed {}", self.seed);
        }
        let mut flag = |name: &str, given: Vec<String>, all: usize| {
            if given.len() < all {
                let _ = write!(line, " --{name} {}", given.join(","));
            }
        };
        flag(
            "worlds",
            self.worlds
                .iter()
                .map(|&w| WORLDS[w].0.to_string())
                .collect(),
            WORLDS.len(),
        );
        flag(
            "dynamics",
            self.dynamics.iter().map(|d| d.name().to_string()).collect(),
            Dynamics::ALL.len(),
        );
        flag(
            "prices",
            self.prices.iter().map(f64::to_string).collect(),
            PRICES.len(),
        );
        flag(
            "rules",
            self.rules.iter().map(|r| r.name().to_string()).collect(),
            RULES.len(),
        );
        if self.learners != Learner::TABLE {
            let names: Vec<String> = self.learners.iter().map(|l| l.name().to_string()).collect();
            let _ = write!(line, " --learners {}", names.join(","));
        }
        line
    }
}

#[cfg(test)]
mod tests {
    use super::super::Summary;
    use super::*;
    use mdp::SensingRule;

    /// The whole table's definition at `runs` runs, or the slippery lakes' part of it.
    fn def(runs: u64, slippery_only: bool) -> Definition {
        Definition {
            runs,
            seed: 1,
            worlds: vec![0, 1],
            dynamics: if slippery_only {
                vec![Dynamics::Slippery]
            } else {
                Dynamics::ALL.to_vec()
            },
            prices: PRICES.to_vec(),
            rules: RULES.to_vec(),
            learners: Learner::TABLE.to_vec(),
        }
    }

    /// A run of `learner` on the 4x4 lake of `dynamics` whose figures are `value`.
    fn run(dynamics: Dynamics, learner: Learner, seed: u64, value: f64) -> JobResult {
        JobResult {
            id: seed,
            world: "frozenlake4x4".into(),
            dynamics,
            price: 0.025,
            rule: SensingRule::WithMove,
            learner,
            seed,
            summary: Summary {
                episodes: 1000,
                mean_all: value,
                mean_last10: value,
                sensing_per_episode: 1.0,
                steps_per_episode: 6.0,
                success: 0.5,
            },
            curve: vec![value; 40],
        }
    }

    /// Five runs of belief on the deterministic and the slippery lake, figures 0.1 s.
    fn table() -> Vec<JobResult> {
        let mut out = Vec::new();
        for d in [Dynamics::Deterministic, Dynamics::Slippery] {
            for seed in 1..=5 {
                out.push(run(d, Learner::Belief, seed, 0.1 * seed as f64));
            }
        }
        out
    }

    fn longer(runs: u64) -> Vec<JobResult> {
        (1..=runs)
            .map(|seed| run(Dynamics::Slippery, Learner::Belief, seed, 0.1 * seed as f64))
            .collect()
    }

    #[test]
    fn longer_runs_replace_the_rows_they_cover_and_no_other() {
        let joined = join(
            &def(5, false),
            table(),
            (&def(20, true), longer(20)),
            Path::new("more"),
        )
        .unwrap();
        let seeds = |d: Dynamics| -> Vec<u64> {
            joined
                .iter()
                .filter(|r| r.dynamics == d)
                .map(|r| r.seed)
                .collect()
        };
        assert_eq!(seeds(Dynamics::Slippery), (1..=20).collect::<Vec<_>>());
        assert_eq!(seeds(Dynamics::Deterministic), (1..=5).collect::<Vec<_>>());
    }

    #[test]
    fn a_shared_run_that_differs_is_refused_by_seed_and_cell() {
        let mut other = longer(20);
        other[3].summary.success = 0.6;
        let e = join(
            &def(5, false),
            table(),
            (&def(20, true), other),
            Path::new("more"),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("--with more: its run of seed 4 (frozenlake4x4, slippery, price 0.025, with-move, belief) differs"), "{e}");
        // A difference in the curve alone is one too.
        let mut other = longer(20);
        other[0].curve[39] += 1e-12;
        assert!(
            join(
                &def(5, false),
                table(),
                (&def(20, true), other),
                Path::new("m")
            )
            .is_err()
        );
    }

    #[test]
    fn fewer_runs_another_seed_or_another_part_is_refused() {
        let e = join(
            &def(5, false),
            table(),
            (&def(3, true), longer(3)),
            Path::new("m"),
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("its 3 runs of (frozenlake4x4, slippery, price 0.025, with-move, belief) do not extend this table's 5"),
            "{e}"
        );
        let mut seeded = def(20, true);
        seeded.seed = 2;
        assert!(
            join(
                &def(5, false),
                table(),
                (&seeded, longer(20)),
                Path::new("m")
            )
            .is_err()
        );
        let mut narrow = def(5, false);
        narrow.dynamics = vec![Dynamics::Deterministic];
        let e = join(
            &narrow,
            table(),
            (&def(20, true), longer(20)),
            Path::new("m"),
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("it holds slippery, which this table does not"),
            "{e}"
        );
    }

    #[test]
    fn a_learner_the_table_lacks_is_added_with_its_own_runs() {
        let mut blind = def(3, true);
        blind.learners = vec![Learner::BeliefBlind];
        let added: Vec<JobResult> = (1..=3)
            .map(|seed| run(Dynamics::Slippery, Learner::BeliefBlind, seed, 0.05))
            .collect();
        let joined = join(&def(5, false), table(), (&blind, added), Path::new("m")).unwrap();
        let count = |l: Learner| joined.iter().filter(|r| r.learner == l).count();
        assert_eq!(
            (count(Learner::Belief), count(Learner::BeliefBlind)),
            (10, 3)
        );
        // Then longer runs of the added rows replace them.
        let mut longer_blind = def(20, true);
        longer_blind.learners = vec![Learner::BeliefBlind];
        let more: Vec<JobResult> = (1..=20)
            .map(|seed| run(Dynamics::Slippery, Learner::BeliefBlind, seed, 0.05))
            .collect();
        let joined = join(
            &def(5, false),
            joined,
            (&longer_blind, more),
            Path::new("m"),
        )
        .unwrap();
        assert_eq!(
            joined
                .iter()
                .filter(|r| r.learner == Learner::BeliefBlind)
                .count(),
            20
        );
    }

    #[test]
    fn the_command_names_the_flags_of_a_part() {
        assert_eq!(def(5, false).command(), "cargo xtask costly --runs 5");
        assert_eq!(
            def(20, true).command(),
            "cargo xtask costly --runs 20 --dynamics slippery"
        );
        let mut d = def(3, true);
        d.seed = 9;
        d.worlds = vec![1];
        d.prices = vec![0.05];
        d.rules = vec![SensingRule::AfterOutcome];
        d.learners = vec![Learner::Belief, Learner::BeliefBlind];
        assert_eq!(
            d.command(),
            "cargo xtask costly --runs 3 --seed 9 --worlds frozenlake8x8 --dynamics slippery \
             --prices 0.05 --rules after-outcome --learners belief,belief-blind"
        );
    }
}
