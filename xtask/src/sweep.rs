//! `cargo xtask sweep` and `cargo xtask merge`: a grid of maps and strategies, cut into
//! shards that can run on different machines, and the merge of their outputs.
//!
//! The job list is built in a fixed order (map, then strategy, then run) and numbered
//! from 0; shard `K/N` runs the jobs whose number is `K - 1` modulo `N`. Run `i` uses seed
//! `S + i`. Each shard writes `shard-K-of-N/manifest.json` (through a temporary file and a
//! rename) and appends one line per finished job to `shard-K-of-N/results.jsonl`, flushed
//! at once: a shard that is killed and started again skips the jobs it already has.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use anyhow::{Context, Result, bail};
use clap::Args;
use csql::{RunSettings, Setup, StrategyKind, Table1};
use indicatif::ProgressBar;
use mdp::Map;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::stats::Summary;

/// Arguments of `cargo xtask sweep`.
#[derive(Args, Clone, Debug)]
pub struct SweepArgs {
    /// Maps, comma-separated: built-in names, map files, `random:WxH:DENSITY:SEED`, or
    /// `MAP@ROW:COL` for a map with its goal moved to (ROW, COL).
    #[arg(long, value_delimiter = ',', required = true)]
    maps: Vec<String>,
    /// Strategies, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "resetting,lazy,random,eager"
    )]
    strategies: Vec<StrategyKind>,
    /// Runs per map and strategy.
    #[arg(long, default_value_t = 5)]
    runs: u64,
    /// Base seed: run i uses seed S + i.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Trial cap of each run.
    #[arg(long, default_value_t = 20_000)]
    max_trials: u32,
    /// This machine's shard, `K/N` (K from 1 to N).
    #[arg(long, default_value = "1/1")]
    shard: String,
    /// Worker threads (default: every core).
    #[arg(long)]
    threads: Option<usize>,
    /// Output folder (shared by all shards).
    #[arg(long)]
    out: PathBuf,
}

/// Arguments of `cargo xtask merge`.
#[derive(Args, Clone, Debug)]
pub struct MergeArgs {
    /// Folders holding shard outputs (`shard-K-of-N` folders, or folders of them).
    #[arg(required = true)]
    dirs: Vec<PathBuf>,
    /// Where to write `sweep.md` and `sweep.csv`.
    #[arg(long, default_value = "results/sweep")]
    out: PathBuf,
}

/// What a sweep is: shards of the same sweep must agree on it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct Definition {
    maps: Vec<String>,
    strategies: Vec<StrategyKind>,
    runs: u64,
    seed: u64,
    max_trials: u32,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct Manifest {
    sweep: Definition,
    shard: u64,
    shards: u64,
    total_jobs: u64,
    job_ids: Vec<u64>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
struct JobResult {
    id: u64,
    map: String,
    strategy: StrategyKind,
    seed: u64,
    states: usize,
    converged: bool,
    trials: u32,
    table1: Table1Row,
}

/// The Table 1 measures, in a form that reads back from JSON.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
struct Table1Row {
    cost_to_sufficient: Option<f64>,
    trials_to_sufficient: Option<u32>,
    cost_to_converge: Option<f64>,
    trials_to_converge: Option<u32>,
    descriptions: Option<usize>,
    mean_features: Option<f64>,
    max_features: Option<usize>,
    tree_cost_per_state: Option<f64>,
    description_cost_per_state: Option<f64>,
}

impl From<&Table1> for Table1Row {
    fn from(t: &Table1) -> Self {
        Table1Row {
            cost_to_sufficient: t.cost_to_sufficient,
            trials_to_sufficient: t.trials_to_sufficient,
            cost_to_converge: t.cost_to_converge,
            trials_to_converge: t.trials_to_converge,
            descriptions: t.descriptions,
            mean_features: t.mean_features,
            max_features: t.max_features,
            tree_cost_per_state: t.tree_cost_per_state,
            description_cost_per_state: t.description_cost_per_state,
        }
    }
}

/// Parse `K/N`.
fn parse_shard(s: &str) -> Result<(u64, u64)> {
    let (k, n) = s
        .split_once('/')
        .with_context(|| format!("--shard `{s}`: expected K/N, for example 2/8"))?;
    let k: u64 = k
        .trim()
        .parse()
        .with_context(|| format!("--shard `{s}`: K is not a number"))?;
    let n: u64 = n
        .trim()
        .parse()
        .with_context(|| format!("--shard `{s}`: N is not a number"))?;
    if n == 0 || k == 0 || k > n {
        bail!("--shard `{s}`: need 1 <= K <= N");
    }
    Ok((k, n))
}

/// A shard's results file as read: the good results, and the lines that are not results.
struct ReadResults {
    results: Vec<JobResult>,
    /// `(line number, text)` of every line that is not a result: a last line cut short by
    /// a kill (no newline), or a corrupt line anywhere.
    bad: Vec<(usize, String)>,
}

/// Read a shard's results, line by line; nothing is changed on disk.
fn read_results(path: &Path) -> Result<ReadResults> {
    let text = match std::fs::read(path) {
        Ok(t) => String::from_utf8_lossy(&t).into_owned(),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Ok(ReadResults {
                results: Vec::new(),
                bad: Vec::new(),
            });
        }
        Err(e) => return Err(e).with_context(|| format!("cannot read {}", path.display())),
    };
    let mut out = ReadResults {
        results: Vec::new(),
        bad: Vec::new(),
    };
    for (i, line) in text.split_inclusive('\n').enumerate() {
        let parsed = line
            .ends_with('\n')
            .then(|| serde_json::from_str::<JobResult>(line).ok())
            .flatten();
        match parsed {
            Some(r) => out.results.push(r),
            None => out.bad.push((i + 1, line.to_string())),
        }
    }
    Ok(out)
}

/// Before a shard resumes: move every line of its results file that is not a result
/// into `results.corrupt.jsonl` beside it (appended, never deleted), say so, and rewrite
/// the results file with the good lines only. Their jobs then run again.
fn set_aside_bad_lines(path: &Path, read: &ReadResults) -> Result<()> {
    if read.bad.is_empty() {
        return Ok(());
    }
    let aside = path.with_file_name("results.corrupt.jsonl");
    let mut kept = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&aside)
        .with_context(|| format!("cannot open {}", aside.display()))?;
    for (line, text) in &read.bad {
        crate::note(&format!(
            "{}:{line}: not a result line{}; set aside in {} and its job will run again",
            path.display(),
            if text.ends_with('\n') {
                ""
            } else {
                " (cut short)"
            },
            aside.display()
        ));
        kept.write_all(text.as_bytes())?;
        if !text.ends_with('\n') {
            kept.write_all(b"\n")?;
        }
    }
    kept.sync_all()?;
    let mut good = String::new();
    for r in &read.results {
        good.push_str(&serde_json::to_string(r)?);
        good.push('\n');
    }
    crate::files::write_atomic(path, good)
}

/// `cargo xtask sweep`.
pub fn sweep(args: &SweepArgs) -> Result<()> {
    let (k, n) = parse_shard(&args.shard)?;
    if args.runs == 0 || args.strategies.is_empty() {
        bail!("a sweep needs --runs >= 1 and at least one strategy");
    }
    crate::files::seeds(args.seed, args.runs)?;
    crate::files::distinct("--maps", &args.maps)?;
    crate::files::distinct("--strategies", &args.strategies)?;
    let maps: Vec<Map> = args
        .maps
        .iter()
        .map(|m| mdp::resolve(m))
        .collect::<Result<_, _>>()?;
    let definition = Definition {
        maps: args.maps.clone(),
        strategies: args.strategies.clone(),
        runs: args.runs,
        seed: args.seed,
        max_trials: args.max_trials,
    };
    let mut jobs = Vec::new();
    for (m, _) in maps.iter().enumerate() {
        for &strategy in &args.strategies {
            for run in 0..args.runs {
                jobs.push((m, strategy, run));
            }
        }
    }
    let total = jobs.len() as u64;
    let mine: Vec<u64> = (0..total).filter(|id| id % n == k - 1).collect();
    let dir = args.out.join(format!("shard-{k}-of-{n}"));
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let _lock = crate::files::OutLock::acquire(&dir)?;
    let manifest = Manifest {
        sweep: definition,
        shard: k,
        shards: n,
        total_jobs: total,
        job_ids: mine.clone(),
    };
    let manifest_path = dir.join("manifest.json");
    if let Ok(text) = std::fs::read_to_string(&manifest_path) {
        let old: Manifest = serde_json::from_str(&text)
            .with_context(|| format!("{} is not a sweep manifest", manifest_path.display()))?;
        if old != manifest {
            bail!(
                "{} holds a different sweep; use another --out or remove it",
                dir.display()
            );
        }
    } else {
        crate::files::write_atomic(&manifest_path, serde_json::to_string_pretty(&manifest)?)?;
    }
    let results_path = dir.join("results.jsonl");
    let read = read_results(&results_path)?;
    set_aside_bad_lines(&results_path, &read)?;
    let done: Vec<u64> = read.results.iter().map(|r| r.id).collect();
    let todo: Vec<u64> = mine.into_iter().filter(|id| !done.contains(id)).collect();
    crate::note(&format!(
        "shard {k}/{n}: {} jobs of {total}, {} already done, {} to run",
        todo.len() + done.len(),
        done.len(),
        todo.len()
    ));
    let setups: Vec<Setup> = maps
        .iter()
        .map(|m| {
            let s = RunSettings::tan1991(m.name(), StrategyKind::Resetting, 0);
            Setup::for_map(m.clone(), &s)
        })
        .collect::<Result<_, _>>()?;
    let file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&results_path)
        .with_context(|| format!("cannot open {}", results_path.display()))?;
    let file = Mutex::new(file);
    let bar = ProgressBar::new(todo.len() as u64);
    let cap = csql::TrialCap::new(args.max_trials)?;
    crate::reproduce::pool(args.threads)?.install(|| {
        todo.par_iter().try_for_each(|&id| -> Result<()> {
            let (m, strategy, run) = jobs[id as usize];
            let mut settings = RunSettings::tan1991(&args.maps[m], strategy, args.seed + run);
            settings.max_trials = cap;
            let report = csql::run_on(&setups[m], &settings);
            let result = JobResult {
                id,
                map: args.maps[m].clone(),
                strategy,
                seed: settings.seed,
                states: setups[m].map.states().len(),
                converged: report.converged,
                trials: report.trials,
                table1: Table1Row::from(&report.table1),
            };
            let line = serde_json::to_string(&result)? + "\n";
            let mut f = file
                .lock()
                .map_err(|_| anyhow::anyhow!("a writer of {} failed", results_path.display()))?;
            f.write_all(line.as_bytes())?;
            f.flush()?;
            bar.inc(1);
            Ok(())
        })
    })?;
    bar.finish_and_clear();
    crate::note(&format!(
        "shard {k}/{n} complete: {}",
        results_path.display()
    ));
    Ok(())
}

/// Every `shard-*` folder in or at the given paths.
fn shard_dirs(dirs: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for d in dirs {
        if d.join("manifest.json").is_file() {
            out.push(d.clone());
            continue;
        }
        let entries =
            std::fs::read_dir(d).with_context(|| format!("cannot read {}", d.display()))?;
        let mut found: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.join("manifest.json").is_file())
            .collect();
        if found.is_empty() {
            bail!("{} holds no sweep shard (no manifest.json)", d.display());
        }
        found.sort();
        out.extend(found);
    }
    Ok(out)
}

/// `cargo xtask merge`.
pub fn merge(args: &MergeArgs) -> Result<()> {
    let dirs = shard_dirs(&args.dirs)?;
    let mut definition: Option<(Definition, u64)> = None;
    let mut by_id: BTreeMap<u64, JobResult> = BTreeMap::new();
    for dir in &dirs {
        let path = dir.join("manifest.json");
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let m: Manifest = serde_json::from_str(&text)
            .with_context(|| format!("{} is not a sweep manifest", path.display()))?;
        match &definition {
            None => definition = Some((m.sweep.clone(), m.total_jobs)),
            Some((d, _)) if *d != m.sweep => bail!(
                "{} belongs to a different sweep than {}",
                dir.display(),
                dirs[0].display()
            ),
            Some(_) => {}
        }
        let path = dir.join("results.jsonl");
        let read = read_results(&path)?;
        // A corrupt line is never dropped silently: the merge stops and names it. A last
        // line cut short by a kill is a job that did not finish, reported as missing below.
        if let Some((line, _)) = read.bad.iter().find(|(_, t)| t.ends_with('\n')) {
            bail!(
                "{}:{line}: not a result line; nothing was merged. Run this shard's sweep again: \
                 it sets such lines aside in results.corrupt.jsonl and runs their jobs again",
                path.display()
            );
        }
        for r in read.results {
            if !m.job_ids.contains(&r.id) {
                bail!(
                    "{}: job {} does not belong to this shard",
                    dir.display(),
                    r.id
                );
            }
            if by_id.insert(r.id, r).is_some() {
                bail!("job appears twice (in {} and another shard)", dir.display());
            }
        }
    }
    let Some((definition, total)) = definition else {
        bail!("no sweep shard to merge");
    };
    let missing: Vec<u64> = (0..total).filter(|id| !by_id.contains_key(id)).collect();
    if !missing.is_empty() {
        let shown: Vec<String> = missing.iter().take(20).map(u64::to_string).collect();
        bail!(
            "{} of {total} jobs are missing (ids {}{}); run their shards (again) before merging",
            missing.len(),
            shown.join(", "),
            if missing.len() > 20 { ", ..." } else { "" }
        );
    }
    let mut md = String::from("# Sweep\n\n");
    let _ = writeln!(
        md,
        "{} runs per map and strategy, seeds {}..={}, trial cap {}. Mean ± sd [min–max] over converged runs.\n",
        definition.runs,
        definition.seed,
        definition.seed + definition.runs - 1,
        definition.max_trials
    );
    md.push_str("| map | states | strategy | converged | trials to convergence | cost to convergence | descriptions | mean features | max features | tree cost/state |\n|---|---|---|---|---|---|---|---|---|---|\n");
    let mut csv = String::from(
        "map,states,strategy,runs,converged,trials_mean,cost_mean,descriptions_mean,mean_features_mean,max_features_mean,tree_cost_mean\n",
    );
    for map in &definition.maps {
        for &k in &definition.strategies {
            let rs: Vec<&JobResult> = by_id
                .values()
                .filter(|r| &r.map == map && r.strategy == k)
                .collect();
            let conv: Vec<&JobResult> = rs.iter().copied().filter(|r| r.converged).collect();
            let col = |f: fn(&Table1Row) -> Option<f64>| {
                Summary::of(&conv.iter().filter_map(|r| f(&r.table1)).collect::<Vec<_>>())
            };
            let cols = [
                col(|t| t.trials_to_converge.map(f64::from)),
                col(|t| t.cost_to_converge),
                col(|t| t.descriptions.map(|x| x as f64)),
                col(|t| t.mean_features),
                col(|t| t.max_features.map(|x| x as f64)),
                col(|t| t.tree_cost_per_state),
            ];
            let decimals = [1, 0, 1, 2, 1, 2];
            let states = rs.first().map_or(0, |r| r.states);
            let _ = write!(
                md,
                "| {map} | {states} | {k} | {}/{} |",
                conv.len(),
                rs.len()
            );
            let _ = write!(csv, "\"{map}\",{states},{k},{},{}", rs.len(), conv.len());
            for (c, d) in cols.iter().zip(decimals) {
                let _ = write!(md, " {} |", c.map_or("—".to_string(), |s| s.show(d)));
                let _ = write!(
                    csv,
                    ",{}",
                    c.map_or(String::new(), |s| format!("{:.6}", s.mean))
                );
            }
            md.push('\n');
            csv.push('\n');
        }
    }
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let _lock = crate::files::OutLock::acquire(&args.out)?;
    crate::files::write_atomic(&args.out.join("sweep.md"), &md)?;
    crate::files::write_atomic(&args.out.join("sweep.csv"), &csv)?;
    crate::emit(&format!(
        "{md}\nMerged {} shards, {total} jobs: {}\n",
        dirs.len(),
        args.out.join("sweep.md").display()
    ))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_parse_and_cover_the_jobs_once() {
        assert_eq!(parse_shard("2/8").unwrap(), (2, 8));
        for bad in ["0/3", "4/3", "x/3", "3", "1/0"] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
        let n = 3;
        let mut seen = [0; 10];
        for k in 1..=n {
            for id in (0..10u64).filter(|id| id % n == k - 1) {
                seen[id as usize] += 1;
            }
        }
        assert!(seen.iter().all(|&c| c == 1));
    }

    fn result(id: u64) -> String {
        let r = JobResult {
            id,
            map: "m".into(),
            strategy: StrategyKind::Lazy,
            seed: 1,
            states: 3,
            converged: true,
            trials: 2,
            table1: Table1Row::default(),
        };
        serde_json::to_string(&r).unwrap()
    }

    #[test]
    fn a_cut_last_line_is_set_aside_not_lost() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("results.jsonl");
        let line = result(4);
        std::fs::write(&path, format!("{line}\n{}", &line[..10])).unwrap();
        let read = read_results(&path).unwrap();
        assert_eq!((read.results.len(), read.bad.len()), (1, 1));
        set_aside_bad_lines(&path, &read).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), format!("{line}\n"));
        let aside = std::fs::read_to_string(dir.path().join("results.corrupt.jsonl")).unwrap();
        assert_eq!(aside, format!("{}\n", &line[..10]));
    }

    #[test]
    fn a_corrupt_middle_line_keeps_every_later_result() {
        // Once: the file was cut at the corrupt line, deleting every later result.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("results.jsonl");
        let text = format!("{}\n{{not json\n{}\n{}\n", result(0), result(1), result(2));
        std::fs::write(&path, &text).unwrap();
        let read = read_results(&path).unwrap();
        let ids: Vec<u64> = read.results.iter().map(|r| r.id).collect();
        assert_eq!(ids, [0, 1, 2]);
        assert_eq!(read.bad, [(2, "{not json\n".to_string())]);
        // Reading changes nothing on disk.
        assert_eq!(std::fs::read_to_string(&path).unwrap(), text);
        set_aside_bad_lines(&path, &read).unwrap();
        let kept = std::fs::read_to_string(&path).unwrap();
        assert_eq!(kept.lines().count(), 3);
        let aside = std::fs::read_to_string(dir.path().join("results.corrupt.jsonl")).unwrap();
        assert_eq!(aside, "{not json\n");
    }

    #[test]
    fn merge_refuses_a_corrupt_line_and_names_it() {
        let dir = tempfile::tempdir().unwrap();
        let shard = dir.path().join("shard-1-of-1");
        std::fs::create_dir_all(&shard).unwrap();
        let manifest = Manifest {
            sweep: Definition {
                maps: vec!["m".into()],
                strategies: vec![StrategyKind::Lazy],
                runs: 2,
                seed: 1,
                max_trials: 10,
            },
            shard: 1,
            shards: 1,
            total_jobs: 2,
            job_ids: vec![0, 1],
        };
        std::fs::write(
            shard.join("manifest.json"),
            serde_json::to_string(&manifest).unwrap(),
        )
        .unwrap();
        let text = format!("{}\ngarbage\n{}\n", result(0), result(1));
        std::fs::write(shard.join("results.jsonl"), &text).unwrap();
        let args = MergeArgs {
            dirs: vec![dir.path().to_path_buf()],
            out: dir.path().join("merged"),
        };
        let err = merge(&args).err().unwrap().to_string();
        assert!(err.contains("results.jsonl:2"), "{err}");
        assert_eq!(
            std::fs::read_to_string(shard.join("results.jsonl")).unwrap(),
            text
        );
    }
}
