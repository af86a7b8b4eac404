//! Sharded, resumable job lists, shared by `cargo xtask sweep` and `cargo xtask
//! robustness`.
//!
//! A job list is built in a fixed order and numbered from 0; shard `K/N` runs the jobs
//! whose number is `K - 1` modulo `N`. Each shard writes `shard-K-of-N/manifest.json`
//! (through a temporary file and a rename) and appends one line per finished job to
//! `shard-K-of-N/results.jsonl`, flushed at once: a shard that is killed and started
//! again skips the jobs it already has. A line that is not a result (a last line cut
//! short by a kill, or a corrupt line) is moved to `results.corrupt.jsonl` beside it,
//! never deleted, and its job runs again.

use std::collections::BTreeMap;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use anyhow::{Context, Result, bail};
use indicatif::ProgressBar;
use rayon::prelude::*;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

/// One result line: it knows its job's number.
pub trait JobLine: Serialize + DeserializeOwned + Send {
    /// The job's number.
    fn id(&self) -> u64;
}

/// Parse `K/N`.
pub fn parse_shard(s: &str) -> Result<(u64, u64)> {
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

/// What a shard is: shards of the same job list must agree on the definition.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Manifest<D> {
    pub sweep: D,
    pub shard: u64,
    pub shards: u64,
    pub total_jobs: u64,
    pub job_ids: Vec<u64>,
}

/// A shard's results file as read: the good results, and the lines that are not results.
pub struct ReadResults<T> {
    pub results: Vec<T>,
    /// `(line number, text)` of every line that is not a result: a last line cut short by
    /// a kill (no newline), or a corrupt line anywhere.
    pub bad: Vec<(usize, String)>,
}

/// Read a shard's results, line by line; nothing is changed on disk.
pub fn read_results<T: DeserializeOwned>(path: &Path) -> Result<ReadResults<T>> {
    let mut out = ReadResults {
        results: Vec::new(),
        bad: Vec::new(),
    };
    let text = match std::fs::read(path) {
        Ok(t) => String::from_utf8_lossy(&t).into_owned(),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(out),
        Err(e) => return Err(e).with_context(|| format!("cannot read {}", path.display())),
    };
    for (i, line) in text.split_inclusive('\n').enumerate() {
        let parsed = line
            .ends_with('\n')
            .then(|| serde_json::from_str::<T>(line).ok())
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
pub fn set_aside_bad_lines<T: Serialize>(path: &Path, read: &ReadResults<T>) -> Result<()> {
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

/// Run shard `K/N` of a job list of `total` jobs under `out`: check (or write) its
/// manifest, set bad lines aside, and run every job it does not have yet with `run`,
/// in parallel on `threads` threads, appending each result as it ends.
pub fn run_shard<D, T, F>(
    out: &Path,
    shard: &str,
    definition: D,
    total: u64,
    threads: Option<usize>,
    run: F,
) -> Result<()>
where
    D: Serialize + DeserializeOwned + PartialEq,
    T: JobLine,
    F: Fn(u64) -> Result<T> + Sync,
{
    let (k, n) = parse_shard(shard)?;
    let mine: Vec<u64> = (0..total).filter(|id| id % n == k - 1).collect();
    let dir = out.join(format!("shard-{k}-of-{n}"));
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
        let old: Manifest<D> = serde_json::from_str(&text).with_context(|| {
            format!(
                "{} is not a manifest of this job list",
                manifest_path.display()
            )
        })?;
        if old != manifest {
            bail!(
                "{} holds a different job list; use another --out or remove it",
                dir.display()
            );
        }
    } else {
        crate::files::write_atomic(&manifest_path, serde_json::to_string_pretty(&manifest)?)?;
    }
    let results_path = dir.join("results.jsonl");
    let read = read_results::<T>(&results_path)?;
    set_aside_bad_lines(&results_path, &read)?;
    let done: std::collections::BTreeSet<u64> = read.results.iter().map(JobLine::id).collect();
    let todo: Vec<u64> = mine.into_iter().filter(|id| !done.contains(id)).collect();
    crate::note(&format!(
        "shard {k}/{n}: {} jobs of {total}, {} already done, {} to run",
        todo.len() + done.len(),
        done.len(),
        todo.len()
    ));
    let file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&results_path)
        .with_context(|| format!("cannot open {}", results_path.display()))?;
    let file = Mutex::new(file);
    let bar = ProgressBar::new(todo.len() as u64);
    crate::reproduce::pool(threads)?.install(|| {
        todo.par_iter().try_for_each(|&id| -> Result<()> {
            let result = run(id)?;
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
pub fn shard_dirs(dirs: &[PathBuf]) -> Result<Vec<PathBuf>> {
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
            bail!("{} holds no shard (no manifest.json)", d.display());
        }
        found.sort();
        out.extend(found);
    }
    Ok(out)
}

/// Read every shard under `dirs` and check that they are one job list, complete and
/// without duplicates; returns its definition and the results by job number.
pub fn collect<D, T>(dirs: &[PathBuf]) -> Result<(D, BTreeMap<u64, T>)>
where
    D: DeserializeOwned + PartialEq + Clone,
    T: JobLine,
{
    let dirs = shard_dirs(dirs)?;
    let mut definition: Option<(D, u64)> = None;
    let mut by_id: BTreeMap<u64, T> = BTreeMap::new();
    for dir in &dirs {
        let path = dir.join("manifest.json");
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let m: Manifest<D> = serde_json::from_str(&text)
            .with_context(|| format!("{} is not a manifest of this job list", path.display()))?;
        match &definition {
            None => definition = Some((m.sweep.clone(), m.total_jobs)),
            Some((d, _)) if *d != m.sweep => bail!(
                "{} belongs to a different job list than {}",
                dir.display(),
                dirs[0].display()
            ),
            Some(_) => {}
        }
        let path = dir.join("results.jsonl");
        let read = read_results::<T>(&path)?;
        // A corrupt line is never dropped silently: the merge stops and names it. A last
        // line cut short by a kill is a job that did not finish, reported as missing below.
        if let Some((line, _)) = read.bad.iter().find(|(_, t)| t.ends_with('\n')) {
            bail!(
                "{}:{line}: not a result line; nothing was merged. Run this shard again: \
                 it sets such lines aside in results.corrupt.jsonl and runs their jobs again",
                path.display()
            );
        }
        for r in read.results {
            let id = r.id();
            if !m.job_ids.contains(&id) {
                bail!("{}: job {id} does not belong to this shard", dir.display());
            }
            if by_id.insert(id, r).is_some() {
                bail!("job appears twice (in {} and another shard)", dir.display());
            }
        }
    }
    let Some((definition, total)) = definition else {
        bail!("no shard to merge");
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
    Ok((definition, by_id))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Serialize, Deserialize)]
    struct Line {
        id: u64,
        value: f64,
    }

    impl JobLine for Line {
        fn id(&self) -> u64 {
            self.id
        }
    }

    fn result(id: u64) -> String {
        serde_json::to_string(&Line { id, value: 1.5 }).unwrap()
    }

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

    #[test]
    fn a_cut_last_line_is_set_aside_not_lost() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("results.jsonl");
        let line = result(4);
        std::fs::write(&path, format!("{line}\n{}", &line[..10])).unwrap();
        let read = read_results::<Line>(&path).unwrap();
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
        let read = read_results::<Line>(&path).unwrap();
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
    fn a_shard_resumes_and_the_merge_refuses_a_corrupt_line() {
        let dir = tempfile::tempdir().unwrap();
        let runs = std::sync::atomic::AtomicU64::new(0);
        let job = |id: u64| {
            runs.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            Ok(Line {
                id,
                value: id as f64,
            })
        };
        run_shard(dir.path(), "1/1", "def".to_string(), 3, Some(1), job).unwrap();
        run_shard(dir.path(), "1/1", "def".to_string(), 3, Some(1), job).unwrap();
        assert_eq!(runs.load(std::sync::atomic::Ordering::Relaxed), 3);
        // Another definition in the same folder is refused.
        assert!(run_shard(dir.path(), "1/1", "other".to_string(), 3, Some(1), job).is_err());
        let (def, by_id) = collect::<String, Line>(&[dir.path().to_path_buf()]).unwrap();
        assert_eq!((def.as_str(), by_id.len()), ("def", 3));
        let results = dir.path().join("shard-1-of-1/results.jsonl");
        let text = std::fs::read_to_string(&results).unwrap();
        std::fs::write(&results, format!("garbage\n{text}")).unwrap();
        let err = collect::<String, Line>(&[dir.path().to_path_buf()])
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains("results.jsonl:1"), "{err}");
    }
}
