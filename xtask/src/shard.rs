//! Sharded, resumable job lists, shared by `cargo xtask sweep` and `cargo xtask
//! robustness`.
//!
//! A job list is built in a fixed order and numbered from 0; shard `K/N` runs the jobs
//! whose number is `K - 1` modulo `N`. Each shard writes `shard-K-of-N/manifest.json`
//! (through a temporary file and a rename) and appends one line per finished job to
//! `shard-K-of-N/results.jsonl`, flushed at once: a shard that is killed and started
//! again skips the jobs it already has. A line that is not a result (a last line cut
//! short by a kill, or a corrupt line) is moved to `results.corrupt.jsonl` beside it,
//! never deleted, and its job runs again; so is a result whose job is not in the shard's
//! job list, or a second result for a job. The lines kept are kept byte for byte.
//!
//! A shard's jobs are computed from their numbers (`K - 1`, `K - 1 + N`, ...), never by
//! listing the whole job list: a shard costs memory in proportion to its own jobs.
//!
//! The worker threads take the jobs one at a time from one queue, heaviest first by the
//! caller's estimate of each job's work (longest processing time first), so that the run
//! does not end with one thread on a long tail while the others idle. A job's result
//! depends on its number only, never on the order it ran in or the thread that ran it.

use std::collections::BTreeMap;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use anyhow::{Context, Result, bail};
use indicatif::ProgressBar;
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

/// The job numbers of shard `k` of `n` (1 <= k <= n) among `total` jobs, in order:
/// `k - 1`, `k - 1 + n`, ..., computed one by one.
pub fn shard_jobs(k: u64, n: u64, total: u64) -> impl Iterator<Item = u64> {
    // A step past `usize::MAX` leaves the first job only, as a step of `n` would.
    let step = usize::try_from(n).unwrap_or(usize::MAX);
    (k.saturating_sub(1)..total).step_by(step)
}

/// The most jobs one shard may run (its job numbers are kept in memory and in its
/// manifest).
pub const MAX_SHARD_JOBS: u64 = 10_000_000;

/// Whether job `id` is in shard `k` of `n` among `total` jobs.
pub fn in_shard(id: u64, k: u64, n: u64, total: u64) -> bool {
    id < total && n > 0 && id % n == k.wrapping_sub(1)
}

/// The number of jobs of shard `k` of `n` among `total` jobs.
pub fn shard_len(k: u64, n: u64, total: u64) -> u64 {
    match total.checked_sub(k) {
        Some(rest) if k >= 1 && n > 0 => rest / n + 1,
        _ => 0,
    }
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

/// One result line as read: where it is, its text byte for byte, and the result.
pub struct Kept<T> {
    /// The 1-based line number.
    pub line: usize,
    /// The line as read, with its newline: written back unchanged.
    pub text: String,
    pub result: T,
}

/// A line set aside: where it was, its text, and why.
#[derive(Debug, PartialEq)]
pub struct SetAside {
    /// The 1-based line number.
    pub line: usize,
    /// The line as read.
    pub text: String,
    /// Why it is not kept, said after the place (`not a result line`, ...).
    pub why: String,
    /// Whether its job (one of the shard's) must run again.
    pub runs_again: bool,
}

/// A shard's results file as read: the good results, and the lines that are not results.
pub struct ReadResults<T> {
    pub results: Vec<Kept<T>>,
    /// Every line that is not a result: a last line cut short by a kill (no newline), or
    /// a corrupt line anywhere; after [`ReadResults::set_apart_foreign`], also results of
    /// jobs not in the shard and second results of a job.
    pub bad: Vec<SetAside>,
}

impl<T: JobLine> ReadResults<T> {
    /// Move to [`bad`](ReadResults::bad) every result whose job is not `belongs` (a
    /// foreign job id) and every second result of a job; the first stays.
    pub fn set_apart_foreign(&mut self, belongs: impl Fn(u64) -> bool) {
        let mut first: BTreeMap<u64, usize> = BTreeMap::new();
        let mut kept = Vec::with_capacity(self.results.len());
        for r in std::mem::take(&mut self.results) {
            let id = r.result.id();
            let why = if !belongs(id) {
                Some(format!("job {id} is not in this shard's job list"))
            } else if let Some(line) = first.get(&id) {
                Some(format!(
                    "job {id} again (its first result is on line {line})"
                ))
            } else {
                first.insert(id, r.line);
                None
            };
            match why {
                Some(why) => self.bad.push(SetAside {
                    line: r.line,
                    text: r.text,
                    why,
                    runs_again: false,
                }),
                None => kept.push(r),
            }
        }
        self.results = kept;
        self.bad.sort_by_key(|b| b.line);
    }
}

/// The most bytes a shard's results file may have (1 GiB: millions of job lines).
const MAX_RESULTS_BYTES: u64 = 1 << 30;

/// The most bytes a shard's manifest may have (its job list: 64 MiB).
const MAX_MANIFEST_BYTES: u64 = 64 << 20;

/// Read a shard's results, line by line; nothing is changed on disk.
pub fn read_results<T: DeserializeOwned>(path: &Path) -> Result<ReadResults<T>> {
    let mut out = ReadResults {
        results: Vec::new(),
        bad: Vec::new(),
    };
    match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(out),
        _ => {}
    }
    let bytes = crate::files::read_bytes(path, MAX_RESULTS_BYTES, "a results file")?;
    let text = String::from_utf8_lossy(&bytes).into_owned();
    for (i, line) in text.split_inclusive('\n').enumerate() {
        let complete = line.ends_with('\n');
        let parsed = complete
            .then(|| serde_json::from_str::<T>(line).ok())
            .flatten();
        match parsed {
            Some(result) => out.results.push(Kept {
                line: i + 1,
                text: line.to_string(),
                result,
            }),
            None => out.bad.push(SetAside {
                line: i + 1,
                text: line.to_string(),
                why: if complete {
                    "not a result line".to_string()
                } else {
                    "not a result line (cut short)".to_string()
                },
                runs_again: true,
            }),
        }
    }
    Ok(out)
}

/// Before a shard resumes: move every line of its results file that is not a result
/// into `results.corrupt.jsonl` beside it (appended, never deleted), say so, and rewrite
/// the results file with the good lines only, byte for byte as they were. Their jobs
/// then run again.
pub fn set_aside_bad_lines<T>(path: &Path, read: &ReadResults<T>) -> Result<()> {
    if read.bad.is_empty() {
        return Ok(());
    }
    let aside = path.with_file_name("results.corrupt.jsonl");
    let mut kept = crate::files::open_append(&aside)?;
    for bad in &read.bad {
        crate::note(&format!(
            "{}:{}: {}; set aside in {}{}",
            path.display(),
            bad.line,
            bad.why,
            aside.display(),
            if bad.runs_again {
                " and its job will run again"
            } else {
                ""
            }
        ));
        kept.write_all(bad.text.as_bytes())?;
        if !bad.text.ends_with('\n') {
            kept.write_all(b"\n")?;
        }
    }
    kept.sync_all()?;
    let mut good = String::new();
    for r in &read.results {
        good.push_str(&r.text);
    }
    crate::files::write_atomic(path, good)
}

/// Run shard `K/N` of a job list of `total` jobs under `out`: check (or write) its
/// manifest, set bad lines aside, and run every job it does not have yet with `run`,
/// in parallel on `threads` threads, appending each result as it ends.
pub fn run_shard<D, T, W, F>(
    out: &Path,
    shard: &str,
    definition: D,
    total: u64,
    threads: Option<usize>,
    weight: W,
    run: F,
) -> Result<()>
where
    D: Serialize + DeserializeOwned + PartialEq,
    T: JobLine,
    W: Fn(u64) -> f64,
    F: Fn(u64) -> Result<T> + Sync,
{
    let (k, n) = parse_shard(shard)?;
    let count = shard_len(k, n, total);
    if count > MAX_SHARD_JOBS {
        bail!(
            "shard {k}/{n} would run {count} of {total} jobs; a shard runs at most \
             {MAX_SHARD_JOBS}: cut the job list into more shards (--shard K/N)"
        );
    }
    let mine: Vec<u64> = shard_jobs(k, n, total).collect();
    let dir = out.join(format!("shard-{k}-of-{n}"));
    crate::files::create_dir(&dir)?;
    let _lock = crate::files::OutLock::acquire(&dir)?;
    let manifest = Manifest {
        sweep: definition,
        shard: k,
        shards: n,
        total_jobs: total,
        job_ids: mine.clone(),
    };
    let manifest_path = dir.join("manifest.json");
    if manifest_path.exists() {
        let text =
            crate::files::read_text(&manifest_path, MAX_MANIFEST_BYTES, "a shard's manifest")?;
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
    let mut read = read_results::<T>(&results_path)?;
    read.set_apart_foreign(|id| in_shard(id, k, n, total));
    set_aside_bad_lines(&results_path, &read)?;
    let done: std::collections::BTreeSet<u64> =
        read.results.iter().map(|r| r.result.id()).collect();
    let todo: Vec<u64> = mine.into_iter().filter(|id| !done.contains(id)).collect();
    crate::note(&format!(
        "shard {k}/{n}: {} jobs of {total}, {} already done, {} to run",
        todo.len() + done.len(),
        done.len(),
        todo.len()
    ));
    let file = crate::files::open_append(&results_path)?;
    let file = Mutex::new(file);
    let bar = ProgressBar::new(todo.len() as u64);
    let queue = heaviest_first(todo, weight);
    let write = |id: u64| -> Result<()> {
        let result = run(id)?;
        let line = serde_json::to_string(&result)? + "\n";
        let mut f = file
            .lock()
            .map_err(|_| anyhow::anyhow!("a writer of {} failed", results_path.display()))?;
        f.write_all(line.as_bytes())?;
        f.flush()?;
        bar.inc(1);
        Ok(())
    };
    run_queue(&queue, threads, write)?;
    bar.finish_and_clear();
    crate::note(&format!(
        "shard {k}/{n} complete: {}",
        results_path.display()
    ));
    Ok(())
}

/// The jobs in the order they are handed out: by decreasing weight, ties (and weights
/// that are not numbers) in the order given.
fn heaviest_first(mut jobs: Vec<u64>, weight: impl Fn(u64) -> f64) -> Vec<u64> {
    let key = |id: u64| {
        let w = weight(id);
        if w.is_nan() { f64::NEG_INFINITY } else { w }
    };
    jobs.sort_by(|a, b| key(*b).total_cmp(&key(*a)));
    jobs
}

/// Run every job of `queue` on `threads` worker threads, each taking the next job from
/// the front of the queue when it is free. The first error stops the handing out of jobs
/// and is returned once the running jobs end.
fn run_queue(
    queue: &[u64],
    threads: Option<usize>,
    run: impl Fn(u64) -> Result<()> + Sync,
) -> Result<()> {
    let next = AtomicUsize::new(0);
    let failed: Mutex<Option<anyhow::Error>> = Mutex::new(None);
    let stop = AtomicBool::new(false);
    crate::files::pool(threads)?.broadcast(|_| {
        while !stop.load(Ordering::Relaxed) {
            let Some(&id) = queue.get(next.fetch_add(1, Ordering::Relaxed)) else {
                break;
            };
            if let Err(e) = run(id) {
                stop.store(true, Ordering::Relaxed);
                if let Ok(mut first) = failed.lock() {
                    first.get_or_insert(e);
                }
            }
        }
    });
    match failed.into_inner() {
        Ok(None) => Ok(()),
        Ok(Some(e)) => Err(e),
        Err(_) => bail!("a worker thread failed"),
    }
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

/// Whether `shard` is one of several: then the results are reported once every shard is
/// done (this says how, for `cargo xtask {command}`), not by this run.
pub fn one_of_several(shard: &str, command: &str) -> Result<bool> {
    let several = parse_shard(shard)?.1 > 1;
    if several {
        crate::note(&format!(
            "run `cargo xtask {command} --report` with the same arguments once every shard is done"
        ));
    }
    Ok(several)
}

/// The results by job number of the job list `def` in `out` ([`collect`]), refused if
/// `out` holds another job list.
pub fn collect_of<D, T>(out: &Path, def: &D) -> Result<BTreeMap<u64, T>>
where
    D: DeserializeOwned + PartialEq + Clone + std::fmt::Debug,
    T: JobLine,
{
    let (found, by_id): (D, BTreeMap<u64, T>) = collect(&[out.to_path_buf()])?;
    if found != *def {
        bail!(
            "{} holds another job list ({found:?}); give its arguments, or another --out",
            out.display()
        );
    }
    Ok(by_id)
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
    // Where each job's result was read: the results file's index in `dirs` and the line.
    let mut places: BTreeMap<u64, (usize, usize)> = BTreeMap::new();
    for (d, dir) in dirs.iter().enumerate() {
        let path = dir.join("manifest.json");
        let text = crate::files::read_text(&path, MAX_MANIFEST_BYTES, "a shard's manifest")?;
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
        if let Some(SetAside { line, .. }) = read.bad.iter().find(|b| b.text.ends_with('\n')) {
            bail!(
                "{}:{line}: not a result line; nothing was merged. Run this shard again: \
                 it sets such lines aside in results.corrupt.jsonl and runs their jobs again",
                path.display()
            );
        }
        for r in read.results {
            let id = r.result.id();
            if !in_shard(id, m.shard, m.shards, m.total_jobs) {
                bail!(
                    "{}:{}: job {id} does not belong to this shard",
                    path.display(),
                    r.line
                );
            }
            if let Some(&(first_dir, first_line)) = places.get(&id) {
                bail!(
                    "job {id} appears twice: {}:{first_line} and {}:{}; nothing was merged",
                    dirs[first_dir].join("results.jsonl").display(),
                    path.display(),
                    r.line
                );
            }
            places.insert(id, (d, r.line));
            by_id.insert(id, r.result);
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

    /// A shard of definition `def` run on one thread, every job of equal weight.
    fn one_thread<T: JobLine>(
        out: &Path,
        shard: &str,
        def: &str,
        total: u64,
        job: impl Fn(u64) -> Result<T> + Sync,
    ) -> Result<()> {
        run_shard(out, shard, def.to_string(), total, Some(1), |_| 1.0, job)
    }

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

    #[cfg(unix)]
    #[test]
    fn a_results_file_or_manifest_that_is_no_regular_file_is_refused_unread() {
        // A FIFO would block the read for ever, /dev/zero would fill the memory.
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("results.jsonl");
        let made = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(made.success());
        for path in [fifo.as_path(), Path::new("/dev/zero")] {
            let err = read_results::<Line>(path).err().unwrap();
            assert!(format!("{err:#}").contains("not a regular file"), "{err:#}");
        }
        // A missing file is no results yet.
        let none = read_results::<Line>(&dir.path().join("none.jsonl")).unwrap();
        assert!(none.results.is_empty() && none.bad.is_empty());
        // A shard folder whose manifest is a FIFO.
        let shard = dir.path().join("shard-1-of-1");
        std::fs::create_dir(&shard).unwrap();
        let made = std::process::Command::new("mkfifo")
            .arg(shard.join("manifest.json"))
            .status()
            .unwrap();
        assert!(made.success());
        let err = collect::<String, Line>(&[shard]).err().unwrap();
        assert!(format!("{err:#}").contains("no shard"), "{err:#}");
    }

    #[test]
    fn jobs_are_handed_out_heaviest_first_ties_in_job_order() {
        let weights = [1.0, 5.0, f64::NAN, 5.0, 2.0];
        let order = heaviest_first((0..5).collect(), |id| weights[id as usize]);
        assert_eq!(order, vec![1, 3, 4, 0, 2]);
    }

    #[test]
    fn the_queue_runs_every_job_once_on_every_thread_count() {
        for threads in [1, 2, 3] {
            let seen = Mutex::new(Vec::new());
            let queue: Vec<u64> = (0..50).rev().collect();
            run_queue(&queue, Some(threads), |id| {
                seen.lock().unwrap().push(id);
                Ok(())
            })
            .unwrap();
            let mut seen = seen.into_inner().unwrap();
            seen.sort_unstable();
            assert_eq!(seen, (0..50).collect::<Vec<_>>(), "{threads} threads");
        }
    }

    #[test]
    fn the_first_failure_stops_the_queue_and_is_returned() {
        let ran = AtomicUsize::new(0);
        let queue: Vec<u64> = (0..100).collect();
        let err = run_queue(&queue, Some(1), |id| {
            ran.fetch_add(1, Ordering::Relaxed);
            if id == 3 {
                bail!("job {id} failed")
            } else {
                Ok(())
            }
        })
        .unwrap_err();
        assert_eq!(err.to_string(), "job 3 failed");
        assert_eq!(
            ran.load(Ordering::Relaxed),
            4,
            "no job is handed out after a failure"
        );
    }

    #[test]
    fn shards_parse_and_cover_the_jobs_once() {
        assert_eq!(parse_shard("2/8").unwrap(), (2, 8));
        for bad in ["0/3", "4/3", "x/3", "3", "1/0"] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
        for total in [0, 1, 2, 9, 10, 11] {
            for n in 1..=12 {
                let mut seen = vec![0; total as usize];
                for k in 1..=n {
                    let jobs: Vec<u64> = shard_jobs(k, n, total).collect();
                    let listed: Vec<u64> = (0..total).filter(|id| id % n == k - 1).collect();
                    assert_eq!(jobs, listed, "{k}/{n} of {total}");
                    assert_eq!(shard_len(k, n, total), jobs.len() as u64);
                    for &id in &jobs {
                        assert!(in_shard(id, k, n, total));
                        seen[id as usize] += 1;
                    }
                }
                assert!(seen.iter().all(|&c| c == 1));
            }
        }
        // A shard of a huge list is found without listing it.
        let last: Vec<u64> = shard_jobs(u64::MAX, u64::MAX, u64::MAX).collect();
        assert_eq!(last, [u64::MAX - 1]);
        assert_eq!(shard_len(u64::MAX, u64::MAX, u64::MAX), 1);
        assert_eq!(shard_len(1, 100_000_000, 100_000_000), 1);
        assert_eq!(shard_len(3, 4, 2), 0);
        assert!(!in_shard(5, 1, 1, 5));
    }

    #[test]
    fn a_resume_keeps_the_kept_lines_byte_for_byte() {
        // Once: the kept lines went through a float parse and back, and 0.30000000000000004
        // written by another serialiser (or 1e-7 as 1E-7, or 2.50) changed its digits.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("results.jsonl");
        let kept = "{\"id\":0,\"value\":0.1000000000000000055511151231257827}\n\
                    {\"id\": 1, \"value\": 1E-7}\n\
                    {\"value\":2.50,\"id\":2}\n";
        std::fs::write(&path, format!("{kept}{{\"id\":3,\"va")).unwrap();
        let read = read_results::<Line>(&path).unwrap();
        assert_eq!((read.results.len(), read.bad.len()), (3, 1));
        set_aside_bad_lines(&path, &read).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), kept);
    }

    #[test]
    fn a_foreign_or_repeated_job_is_set_aside_on_resume() {
        let dir = tempfile::tempdir().unwrap();
        let runs = std::sync::atomic::AtomicU64::new(0);
        let job = |id: u64| {
            runs.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            Ok(Line {
                id,
                value: id as f64,
            })
        };
        // Shard 1/2 of 4 jobs holds jobs 0 and 2. Its file also has job 1 (shard 2's), job
        // 7 (of no shard) and job 0 twice.
        let shard = dir.path().join("shard-1-of-2");
        std::fs::create_dir_all(&shard).unwrap();
        let results = shard.join("results.jsonl");
        let text = format!(
            "{}\n{}\n{}\n{}\n",
            result(0),
            result(1),
            result(7),
            result(0)
        );
        std::fs::write(&results, &text).unwrap();
        one_thread(dir.path(), "1/2", "def", 4, job).unwrap();
        // Only job 2 ran: job 0 was done; 1, 7 and the repeat of 0 are set aside.
        assert_eq!(runs.load(std::sync::atomic::Ordering::Relaxed), 1);
        let kept = std::fs::read_to_string(&results).unwrap();
        let ids: Vec<u64> = kept
            .lines()
            .map(|l| serde_json::from_str::<Line>(l).unwrap().id)
            .collect();
        assert_eq!(ids, [0, 2]);
        let aside = std::fs::read_to_string(shard.join("results.corrupt.jsonl")).unwrap();
        assert_eq!(
            aside,
            format!("{}\n{}\n{}\n", result(1), result(7), result(0))
        );
    }

    #[test]
    fn a_job_merged_twice_is_named_with_both_places() {
        let dir = tempfile::tempdir().unwrap();
        let job = |id: u64| {
            Ok(Line {
                id,
                value: id as f64,
            })
        };
        one_thread(dir.path(), "1/2", "def", 4, job).unwrap();
        one_thread(dir.path(), "2/2", "def", 4, job).unwrap();
        assert_eq!(
            collect::<String, Line>(&[dir.path().to_path_buf()])
                .unwrap()
                .1
                .len(),
            4
        );
        // Job 2 (shard 1's) written into shard 2's file as well, as after a lost lock race
        // between two folders merged together: both places are named.
        let second = dir.path().join("shard-2-of-2/results.jsonl");
        let mut text = std::fs::read_to_string(&second).unwrap();
        text.push_str(&format!("{}\n", result(1)));
        std::fs::write(&second, text).unwrap();
        let err = collect::<String, Line>(&[dir.path().to_path_buf()])
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains("job 1 appears twice"), "{err}");
        assert!(err.contains("shard-2-of-2/results.jsonl:1 and"), "{err}");
        assert!(err.contains("shard-2-of-2/results.jsonl:3"), "{err}");
        // A foreign job in a shard's file is named with its place.
        let first = dir.path().join("shard-1-of-2/results.jsonl");
        let mut text = std::fs::read_to_string(&first).unwrap();
        text.push_str(&format!("{}\n", result(3)));
        std::fs::write(&first, text).unwrap();
        let err = collect::<String, Line>(&[dir.path().to_path_buf()])
            .err()
            .unwrap()
            .to_string();
        assert!(
            err.contains("shard-1-of-2/results.jsonl:3: job 3 does not belong"),
            "{err}"
        );
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
        let ids: Vec<u64> = read.results.iter().map(|r| r.result.id).collect();
        assert_eq!(ids, [0, 1, 2]);
        let bad: Vec<(usize, &str)> = read.bad.iter().map(|b| (b.line, b.text.as_str())).collect();
        assert_eq!(bad, [(2, "{not json\n")]);
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
        one_thread(dir.path(), "1/1", "def", 3, job).unwrap();
        one_thread(dir.path(), "1/1", "def", 3, job).unwrap();
        assert_eq!(runs.load(std::sync::atomic::Ordering::Relaxed), 3);
        // Another definition in the same folder is refused.
        assert!(one_thread(dir.path(), "1/1", "other", 3, job).is_err());
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
