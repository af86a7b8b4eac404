//! The project's Python environment: a virtual environment under `target/py-venv` with
//! the pinned packages of `crates/csrl-py/requirements-test.txt`, made and kept up to date
//! for `cargo xtask test` (the Python package's tests) and `cargo xtask testcost` (CEGB's
//! worker).
//!
//! The environment is made once, with `$PYTHON` or `python3` (`python -m venv`, or
//! virtualenv where Python ships without its venv module). The pinned packages are
//! installed whenever the requirements file differs from the copy kept inside the
//! environment after the last install that succeeded (`csrl-requirements.txt`), so an
//! environment made before a pin changed is brought up to date, and one that has them
//! costs no call to pip.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{Context, Result, bail, ensure};

/// The pinned requirements, relative to the workspace root.
pub const REQUIREMENTS: &str = "crates/csrl-py/requirements-test.txt";

/// Run a command, echoing it to stderr; its failure is an error naming it.
pub fn run(cmd: &mut Command) -> Result<()> {
    let shown = format!("{cmd:?}");
    eprintln!("==> {shown}");
    let status = cmd
        .status()
        .with_context(|| format!("cannot start {shown}"))?;
    ensure!(status.success(), "{shown} failed ({status})");
    Ok(())
}

/// The workspace root (the parent of xtask's own folder).
pub fn root() -> Result<PathBuf> {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    manifest
        .parent()
        .map(Path::to_path_buf)
        .context("xtask's folder has no parent")
}

/// Cargo's target folder: `$CARGO_TARGET_DIR`, else `target/` under the root.
pub fn target(root: &Path) -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"))
}

/// A virtual environment that has the pinned packages.
pub struct Venv {
    /// Its folder.
    pub dir: PathBuf,
    /// Its interpreter.
    pub python: PathBuf,
    /// `PATH` with the environment's programs first.
    path: OsString,
}

impl Venv {
    /// A command for `program` as it would run with the environment activated: its
    /// programs (maturin, for pip's build) first on `PATH`, `VIRTUAL_ENV` set.
    pub fn command(&self, program: &Path) -> Command {
        let mut c = Command::new(program);
        c.env("PATH", &self.path).env("VIRTUAL_ENV", &self.dir);
        c
    }

    /// `python -m pip install --quiet ...` in the environment, run from `root`.
    pub fn pip(&self, root: &Path, args: &[&str]) -> Command {
        let mut c = self.command(&self.python);
        c.args([
            "-m",
            "pip",
            "install",
            "--quiet",
            "--disable-pip-version-check",
        ])
        .args(args)
        .current_dir(root);
        c
    }
}

/// The environment at `target/py-venv`, made if it is missing, with the pinned packages
/// installed if they changed since the last install (module documentation).
pub fn venv(root: &Path, target: &Path) -> Result<Venv> {
    let dir = target.join("py-venv");
    let python = dir.join("bin").join("python");
    if !python.exists() {
        let base = std::env::var_os("PYTHON").unwrap_or_else(|| "python3".into());
        // Some systems ship Python without its venv module (Debian's python3-venv):
        // virtualenv, installed for the user by pip, makes the same environment.
        let made = run(Command::new(&base)
            .args(["-m", "venv"])
            .arg(&dir)
            .current_dir(root));
        if made.is_err() {
            eprintln!("python -m venv failed; trying virtualenv");
            let _ = std::fs::remove_dir_all(&dir);
            run(Command::new(&base)
                .args(["-m", "pip", "install", "--quiet", "--user", "virtualenv"])
                .current_dir(root))
            .and_then(|()| {
                run(Command::new(&base)
                    .args(["-m", "virtualenv"])
                    .arg(&dir)
                    .current_dir(root))
            })
            .context(
                "cannot make the virtual environment (Python 3.10 or newer with venv or pip is needed)",
            )?;
        }
    }
    if !python.exists() {
        bail!(
            "the virtual environment at {} has no bin/python",
            dir.display()
        );
    }
    let mut paths = vec![dir.join("bin")];
    paths.extend(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    ));
    let path = std::env::join_paths(paths).context("a folder of PATH holds a ':'")?;
    let venv = Venv { dir, python, path };
    let wanted = std::fs::read_to_string(root.join(REQUIREMENTS))
        .with_context(|| format!("cannot read {REQUIREMENTS}"))?;
    let stamp = venv.dir.join("csrl-requirements.txt");
    if std::fs::read_to_string(&stamp).ok().as_deref() != Some(wanted.as_str()) {
        run(&mut venv.pip(root, &["-r", REQUIREMENTS]))?;
        std::fs::write(&stamp, &wanted)
            .with_context(|| format!("cannot write {}", stamp.display()))?;
    }
    Ok(venv)
}
