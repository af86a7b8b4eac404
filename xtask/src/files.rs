//! Safe output: files written whole or not at all, one writer per output folder, and
//! names from input made safe before they become parts of paths.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

/// An output that cannot be written: a file, a folder or a lock (exit code 4, as in
/// `csrl`). The operating system's error is its source.
#[derive(Debug)]
pub struct CannotWrite {
    path: PathBuf,
    source: std::io::Error,
}

impl std::fmt::Display for CannotWrite {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "cannot write {}", self.path.display())
    }
}

impl std::error::Error for CannotWrite {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.source)
    }
}

/// A [`CannotWrite`] for `path`, as an error.
pub fn cannot_write(path: &Path, source: std::io::Error) -> anyhow::Error {
    anyhow::Error::new(CannotWrite {
        path: path.to_path_buf(),
        source,
    })
}

/// Create the folder `dir` and its parents; a failure is a [`CannotWrite`].
pub fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| cannot_write(dir, e))
}

/// Open `path` for appending, created if missing; a failure is a [`CannotWrite`].
pub fn open_append(path: &Path) -> Result<std::fs::File> {
    std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)
        .map_err(|e| cannot_write(path, e))
}

/// Read `path`, which must be a regular file (`what`, for the message) of at most `max`
/// bytes, as UTF-8 text.
pub fn read_text(path: &Path, max: u64, what: &str) -> Result<String> {
    let bytes = read_bytes(path, max, what)?;
    String::from_utf8(bytes).with_context(|| format!("{}: not UTF-8 text", path.display()))
}

/// Read `path`, which must be a regular file (`what`, for the message) of at most `max`
/// bytes: a FIFO, a device or a folder is refused unread, so nothing blocks or reads
/// without end.
pub fn read_bytes(path: &Path, max: u64, what: &str) -> Result<Vec<u8>> {
    use std::io::Read;
    let meta =
        std::fs::metadata(path).with_context(|| format!("cannot read {}", path.display()))?;
    anyhow::ensure!(
        meta.is_file(),
        "{}: not a regular file ({what} is needed)",
        path.display()
    );
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|file| file.take(max + 1).read_to_end(&mut bytes))
        .with_context(|| format!("cannot read {}", path.display()))?;
    anyhow::ensure!(
        bytes.len() as u64 <= max,
        "{}: longer than the {max} bytes {what} may have here",
        path.display()
    );
    Ok(bytes)
}

/// Write `bytes` to `path` through a temporary file in the same folder and a rename, so
/// that a kill mid-write leaves the old file or the new one, never a truncated one. A
/// failure is a [`CannotWrite`] naming `path`.
pub fn write_atomic(path: &Path, bytes: impl AsRef<[u8]>) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut tmp = tempfile::NamedTempFile::new_in(dir).map_err(|e| cannot_write(path, e))?;
    tmp.write_all(bytes.as_ref())
        .and_then(|()| tmp.as_file().sync_all())
        .map_err(|e| cannot_write(path, e))?;
    tmp.persist(path).map_err(|e| cannot_write(path, e.error))?;
    Ok(())
}

/// A name from input (a map's name, a strategy) made safe as one file-name component:
/// letters, digits, `-`, `_` and inner `.` are kept, anything else (path separators, `..`,
/// control characters) becomes `_`.
pub fn safe_name(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.starts_with('.') || s.is_empty() {
        s.insert(0, '_');
    }
    s.truncate(100);
    s
}

/// The lock of an output folder: at most one writer at a time. The lock file holds the
/// writer's process id; a lock left by a process that no longer runs (after `kill -9`)
/// is taken over with a note. Dropping the value removes the file.
///
/// Taking over is atomic, with exactly one winner however many writers start together:
/// a stale lock is removed only by the holder of `.lock.takeover` (created exclusively),
/// which reads the lock again under it; the lock itself is only ever created
/// exclusively. A writer that finds a takeover under way is refused as a busy folder.
pub struct OutLock {
    path: PathBuf,
}

/// The guard of a takeover (`.lock.takeover`), removed when dropped.
struct Takeover {
    path: PathBuf,
}

impl Drop for Takeover {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Create `path` if it does not exist, holding this process's id; `Ok(false)` if it exists.
fn create_exclusive(path: &Path) -> Result<bool> {
    match std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(path)
    {
        Ok(mut f) => {
            writeln!(f, "{}", std::process::id())
                .and_then(|()| f.sync_all())
                .map_err(|e| cannot_write(path, e))?;
            Ok(true)
        }
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(false),
        Err(e) => Err(cannot_write(path, e)),
    }
}

/// The process id a lock file names (empty while its writer is still writing it).
fn holder(path: &Path) -> String {
    std::fs::read_to_string(path)
        .unwrap_or_default()
        .trim()
        .to_string()
}

impl OutLock {
    /// Lock `dir` (which must exist) or say who holds it.
    pub fn acquire(dir: &Path) -> Result<OutLock> {
        let path = dir.join(".lock");
        let busy = |pid: &str| {
            anyhow::anyhow!(
                "{} is in use by another writer (process {pid}, lock file {}); wait for it, \
                 use another output folder, or delete the lock file if no such process runs",
                dir.display(),
                path.display()
            )
        };
        if create_exclusive(&path)? {
            return Ok(OutLock { path });
        }
        let pid = holder(&path);
        if !pid_is_gone(&pid) {
            return Err(busy(&pid));
        }
        // A stale lock: only the one writer holding the takeover guard may remove it.
        let guard_path = dir.join(".lock.takeover");
        if !create_exclusive(&guard_path)? {
            let other = holder(&guard_path);
            bail!(
                "{} is being taken over by another writer (process {other}, {}); wait for \
                 it, or delete that file if no such process runs",
                dir.display(),
                guard_path.display()
            );
        }
        let _guard = Takeover { path: guard_path };
        // Read again under the guard: another writer may have taken over meanwhile. No
        // one else removes a stale lock, so the one read here is still there.
        let now = holder(&path);
        if now == pid {
            crate::note(&format!(
                "{}: taking over a lock left by process {pid}, which no longer runs",
                path.display()
            ));
            match std::fs::remove_file(&path) {
                Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                    return Err(e)
                        .with_context(|| format!("cannot remove the stale {}", path.display()));
                }
                _ => {}
            }
        } else if path.exists() {
            return Err(busy(&now));
        }
        if create_exclusive(&path)? {
            Ok(OutLock { path })
        } else {
            Err(busy(&holder(&path)))
        }
    }
}

/// Whether no process `pid` runs (only decided where `/proc` exists; elsewhere a lock is
/// never taken over).
fn pid_is_gone(pid: &str) -> bool {
    let Ok(n) = pid.parse::<u32>() else {
        return false;
    };
    Path::new("/proc/self").exists() && !Path::new("/proc").join(n.to_string()).exists()
}

impl Drop for OutLock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Refuse a list argument that names an entry twice.
pub fn distinct<T: PartialEq + std::fmt::Display>(flag: &str, items: &[T]) -> Result<()> {
    for (i, a) in items.iter().enumerate() {
        if items[..i].contains(a) {
            bail!("{flag} names `{a}` twice; name each entry once");
        }
    }
    Ok(())
}

/// Refuse `--maps` that name one world twice, however it is written (`tan3x3` and
/// `tan3x3@0:2`, `random:+8x+8:0.2:1` and `random:8x8:0.2:1`): maps are compared by their
/// cells and goal, not by their text. `names[i]` is how `maps[i]` was given.
pub fn distinct_maps(names: &[String], maps: &[mdp::Map]) -> Result<()> {
    // The layout holds every cell, the goal among them, row by row.
    let mut seen: std::collections::BTreeMap<String, usize> = std::collections::BTreeMap::new();
    for (i, map) in maps.iter().enumerate() {
        if let Some(&j) = seen.get(&map.layout()) {
            let (a, b) = (
                names.get(j).map_or("?", String::as_str),
                names.get(i).map_or("?", String::as_str),
            );
            bail!("--maps names one world twice: `{a}` and `{b}` are the same map; name each once");
        }
        seen.insert(map.layout(), i);
    }
    Ok(())
}

/// Check that seeds `seed`, `seed + 1`, ..., `seed + runs - 1` all exist.
pub fn seeds(seed: u64, runs: u64) -> Result<()> {
    if runs == 0 {
        bail!("--runs must be at least 1");
    }
    if seed.checked_add(runs - 1).is_none() {
        bail!(
            "--seed {seed} with --runs {runs} needs seeds beyond {}; use a smaller --seed",
            u64::MAX
        );
    }
    Ok(())
}

/// The most worker threads `--threads` may ask for.
pub const MAX_THREADS: usize = 256;

/// Check `--threads` (none or 0: every core).
pub fn threads(threads: Option<usize>) -> Result<usize> {
    match threads {
        Some(n) if n > MAX_THREADS => {
            bail!("--threads {n}: at most {MAX_THREADS} (0 or none: every core)")
        }
        other => Ok(other.unwrap_or(0)),
    }
}

/// Build a thread pool of the asked size (0 or none: every core).
pub fn pool(threads: Option<usize>) -> Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(self::threads(threads)?)
        .build()
        .context("cannot start worker threads")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_never_leave_their_folder() {
        for (name, safe) in [
            ("tan8x8", "tan8x8"),
            ("../../etc/x", "_.._.._etc_x"),
            ("/abs", "_abs"),
            ("..", "_.."),
            ("", "_"),
            ("a b\\c", "a_b_c"),
            ("random:8x8:0.2:7@1:2", "random_8x8_0.2_7_1_2"),
        ] {
            assert_eq!(safe_name(name), safe, "{name}");
            assert!(!safe_name(name).contains('/'));
        }
    }

    #[test]
    fn lists_seeds_and_threads_are_checked() {
        assert!(distinct("--strategies", &["lazy", "lazy"]).is_err());
        assert!(distinct("--strategies", &["lazy", "eager"]).is_ok());
        assert!(seeds(u64::MAX, 2).is_err());
        assert!(seeds(u64::MAX, 1).is_ok());
        assert!(seeds(1, 0).is_err());
        assert!(threads(Some(100_000)).is_err());
        assert_eq!(threads(None).unwrap(), 0);
    }

    #[test]
    fn maps_are_compared_as_worlds_not_as_text() {
        let check = |list: &[&str]| {
            let names: Vec<String> = list.iter().map(|s| s.to_string()).collect();
            let maps: Vec<mdp::Map> = list.iter().map(|m| mdp::resolve(m).unwrap()).collect();
            distinct_maps(&names, &maps).map_err(|e| e.to_string())
        };
        let err = check(&["tan3x3", "tan3x3@0:2"]).unwrap_err();
        assert!(
            err.contains("`tan3x3` and `tan3x3@0:2` are the same map"),
            "{err}"
        );
        let err = check(&["tan8x8", "random:+8x+8:0.2:1", "random:8x8:0.2:1"]).unwrap_err();
        assert!(
            err.contains("`random:+8x+8:0.2:1` and `random:8x8:0.2:1`"),
            "{err}"
        );
        assert!(check(&["tan3x3", "tan8x8", "random:8x8:0.2:1", "random:8x8:0.2:2"]).is_ok());
    }

    #[test]
    fn a_stale_lock_is_taken_over_by_exactly_one_of_many_writers() {
        // Once: two writers both removed the stale lock and both created their own, and
        // both ran every job. Here 16 threads race for the same stale lock, 40 times.
        if !Path::new("/proc/self").exists() {
            return;
        }
        for round in 0..40 {
            let dir = tempfile::tempdir().unwrap();
            std::fs::write(dir.path().join(".lock"), "4294967295\n").unwrap();
            let threads = 16;
            let barrier = std::sync::Barrier::new(threads);
            let winners = std::sync::atomic::AtomicUsize::new(0);
            std::thread::scope(|s| {
                for _ in 0..threads {
                    s.spawn(|| {
                        barrier.wait();
                        let lock = OutLock::acquire(dir.path());
                        if lock.is_ok() {
                            winners.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                        }
                        // Every writer holds what it got until all have tried.
                        barrier.wait();
                        drop(lock);
                    });
                }
            });
            assert_eq!(
                winners.load(std::sync::atomic::Ordering::SeqCst),
                1,
                "round {round}"
            );
            // The guard is gone and the lock with its winner: the folder is free again.
            let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
            assert!(left.is_empty(), "round {round}: {left:?}");
        }
    }

    #[test]
    fn one_writer_per_folder_and_atomic_writes() {
        let dir = tempfile::tempdir().unwrap();
        let lock = OutLock::acquire(dir.path()).unwrap();
        let err = OutLock::acquire(dir.path()).err().unwrap().to_string();
        assert!(err.contains("in use by another writer"), "{err}");
        drop(lock);
        let again = OutLock::acquire(dir.path()).unwrap();
        drop(again);
        // A lock whose process is gone is taken over.
        std::fs::write(dir.path().join(".lock"), "4294967295\n").unwrap();
        if Path::new("/proc/self").exists() {
            assert!(OutLock::acquire(dir.path()).is_ok());
        }
        let path = dir.path().join("table.md");
        write_atomic(&path, "one").unwrap();
        write_atomic(&path, "two").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "two");
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(left.len(), 1, "no temporary file is left behind");
    }
}
