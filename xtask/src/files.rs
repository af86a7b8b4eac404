//! Safe output: files written whole or not at all, one writer per output folder, and
//! names from input made safe before they become parts of paths.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

/// Write `bytes` to `path` through a temporary file in the same folder and a rename, so
/// that a kill mid-write leaves the old file or the new one, never a truncated one.
pub fn write_atomic(path: &Path, bytes: impl AsRef<[u8]>) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut tmp = tempfile::NamedTempFile::new_in(dir)
        .with_context(|| format!("cannot create a temporary file in {}", dir.display()))?;
    tmp.write_all(bytes.as_ref())
        .and_then(|()| tmp.as_file().sync_all())
        .with_context(|| format!("cannot write {}", tmp.path().display()))?;
    tmp.persist(path)
        .with_context(|| format!("cannot move the new {} into place", path.display()))?;
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
pub struct OutLock {
    path: PathBuf,
}

impl OutLock {
    /// Lock `dir` (which must exist) or say who holds it.
    pub fn acquire(dir: &Path) -> Result<OutLock> {
        let path = dir.join(".lock");
        for _ in 0..2 {
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&path)
            {
                Ok(mut f) => {
                    let _ = writeln!(f, "{}", std::process::id());
                    return Ok(OutLock { path });
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    let holder = std::fs::read_to_string(&path).unwrap_or_default();
                    let pid = holder.trim();
                    if pid_is_gone(pid) {
                        crate::note(&format!(
                            "{}: taking over a lock left by process {pid}, which no longer runs",
                            path.display()
                        ));
                        let _ = std::fs::remove_file(&path);
                        continue;
                    }
                    bail!(
                        "{} is in use by another writer (process {pid}, lock file {}); wait for it, \
                         use another output folder, or delete the lock file if no such process runs",
                        dir.display(),
                        path.display()
                    );
                }
                Err(e) => {
                    return Err(e).with_context(|| format!("cannot create {}", path.display()));
                }
            }
        }
        bail!("{}: cannot take the lock", path.display())
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
