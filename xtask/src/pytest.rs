//! `cargo xtask test`: every test of the repository, Rust and Python.
//!
//! 1. `cargo test --workspace`;
//! 2. a virtual environment under `target/py-venv` (made once, with `$PYTHON` or
//!    `python3`), with what the Python tests need from
//!    `crates/csrl-py/requirements-test.txt`;
//! 3. the Python package built and installed into it by its documented command,
//!    `pip install ./crates/csrl-py` (without build isolation: maturin is already there);
//! 4. the type check of the package's public API and its stubs: mypy, configured in
//!    `crates/csrl-py/pyproject.toml`;
//! 5. the release build of the `csrl` program, which the Python tests compare with;
//! 6. pytest, warnings as errors, strict (`xfail_strict`, `--strict-markers`,
//!    `--strict-config`): `crates/csrl-py/tests` and the examples of the package's
//!    docstrings.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{Context, Result, bail, ensure};

/// Arguments of `cargo xtask test`.
#[derive(clap::Args)]
pub struct TestArgs {
    /// Skip `cargo test --workspace` (run only the Python tests).
    #[arg(long)]
    python_only: bool,
    /// Arguments passed on to pytest (after `--`).
    #[arg(last = true)]
    pytest: Vec<String>,
}

fn run(cmd: &mut Command) -> Result<()> {
    let shown = format!("{cmd:?}");
    eprintln!("==> {shown}");
    let status = cmd
        .status()
        .with_context(|| format!("cannot start {shown}"))?;
    ensure!(status.success(), "{shown} failed ({status})");
    Ok(())
}

/// The workspace root (the parent of xtask's own folder).
fn root() -> Result<PathBuf> {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    manifest
        .parent()
        .map(Path::to_path_buf)
        .context("xtask's folder has no parent")
}

/// Run every test.
pub fn test(args: &TestArgs) -> Result<()> {
    let root = root()?;
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"));
    if !args.python_only {
        run(Command::new(&cargo)
            .args(["test", "--workspace"])
            .current_dir(&root))?;
    }

    let venv = target.join("py-venv");
    let python = venv.join("bin").join("python");
    if !python.exists() {
        let base = std::env::var_os("PYTHON").unwrap_or_else(|| "python3".into());
        // Some systems ship Python without its venv module (Debian's python3-venv):
        // virtualenv, installed for the user by pip, makes the same environment.
        let made = run(Command::new(&base)
            .args(["-m", "venv"])
            .arg(&venv)
            .current_dir(&root));
        if made.is_err() {
            eprintln!("python -m venv failed; trying virtualenv");
            let _ = std::fs::remove_dir_all(&venv);
            run(Command::new(&base)
                .args(["-m", "pip", "install", "--quiet", "--user", "virtualenv"])
                .current_dir(&root))
            .and_then(|()| {
                run(Command::new(&base)
                    .args(["-m", "virtualenv"])
                    .arg(&venv)
                    .current_dir(&root))
            })
            .context(
                "cannot make the virtual environment (Python 3.10 or newer with venv or pip is needed)",
            )?;
        }
    }
    if !python.exists() {
        bail!(
            "the virtual environment at {} has no bin/python",
            venv.display()
        );
    }
    // The environment's programs (maturin, for pip's build) come first on PATH, as
    // activating the environment would put them.
    let bin = venv.join("bin");
    let mut paths = vec![bin.clone()];
    paths.extend(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    ));
    let path = std::env::join_paths(paths).context("a folder of PATH holds a ':'")?;
    let in_venv = |program: &Path| {
        let mut c = Command::new(program);
        c.env("PATH", &path).env("VIRTUAL_ENV", &venv);
        c
    };
    let pip = |extra: &[&str]| {
        let mut c = in_venv(&python);
        c.args([
            "-m",
            "pip",
            "install",
            "--quiet",
            "--disable-pip-version-check",
        ])
        .args(extra)
        .current_dir(&root);
        c
    };
    run(&mut pip(&["-r", "crates/csrl-py/requirements-test.txt"]))?;
    run(&mut pip(&[
        "--no-build-isolation",
        "--force-reinstall",
        "--no-deps",
        "./crates/csrl-py",
    ]))?;

    // The type check, its cache kept under the target folder.
    run(in_venv(&python)
        .args(["-m", "mypy", "--cache-dir"])
        .arg(target.join("mypy-cache"))
        .current_dir(root.join("crates/csrl-py")))?;

    run(Command::new(&cargo)
        .args(["build", "--release", "-p", "csrl"])
        .current_dir(&root))?;
    let cli = target.join("release").join("csrl");

    run(in_venv(&python)
        .args(["-m", "pytest", "-W", "error", "-q", "tests"])
        .args(&args.pytest)
        .env("CSRL_CLI", &cli)
        .current_dir(root.join("crates/csrl-py")))?;
    // The docstrings' examples, from the installed package (run from outside the
    // package's folder, so its pytest settings are given here: the same strictness).
    run(in_venv(&python)
        .args([
            "-m",
            "pytest",
            "-W",
            "error",
            "-q",
            "-o",
            "xfail_strict=true",
            "--strict-markers",
            "--strict-config",
            "--doctest-modules",
            "-p",
            "no:cacheprovider",
            "--pyargs",
            "csrl",
        ])
        .env("CSRL_CLI", &cli)
        .current_dir(&target))?;
    Ok(())
}
