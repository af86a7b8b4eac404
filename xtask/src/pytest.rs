//! `cargo xtask test`: every test of the repository, Rust and Python.
//!
//! 1. `cargo test --workspace`, then the examples of `cslearn`'s work counts, which only
//!    a build with its `work-counts` feature has;
//! 2. the project's virtual environment under `target/py-venv` (`crate::python`: made
//!    once, with `$PYTHON` or `python3`, and given the pinned packages of
//!    `crates/csrl-py/requirements-test.txt` whenever they change);
//! 3. the Python package built and installed into it by its documented command,
//!    `pip install ./crates/csrl-py` (without build isolation: maturin is already there);
//! 4. the type check of the package's public API and its stubs: mypy, configured in
//!    `crates/csrl-py/pyproject.toml`;
//! 5. the release build of the `csrl` program, which the Python tests compare with;
//! 6. pytest, warnings as errors, strict (`xfail_strict`, `--strict-markers`,
//!    `--strict-config`): `crates/csrl-py/tests` and the examples of the package's
//!    docstrings.

use std::process::Command;

use anyhow::Result;

use crate::python::{run, venv};

/// Arguments of `cargo xtask test`.
#[derive(clap::Args)]
pub struct TestArgs {
    /// Skip the Rust tests (run only the Python tests).
    #[arg(long)]
    python_only: bool,
    /// Arguments passed on to pytest (after `--`).
    #[arg(last = true)]
    pytest: Vec<String>,
}

/// Run every test.
pub fn test(args: &TestArgs) -> Result<()> {
    let root = crate::python::root()?;
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let target = crate::python::target(&root);
    if !args.python_only {
        run(Command::new(&cargo)
            .args(["test", "--workspace"])
            .current_dir(&root))?;
        run(Command::new(&cargo)
            .args([
                "test",
                "-p",
                "cslearn",
                "--features",
                "work-counts",
                "--doc",
                "testcost::work",
            ])
            .current_dir(&root))?;
    }

    let env = venv(&root, &target)?;
    let python = &env.python;
    let in_venv = |program: &std::path::Path| env.command(program);
    run(&mut env.pip(
        &root,
        &[
            "--no-build-isolation",
            "--force-reinstall",
            "--no-deps",
            "./crates/csrl-py",
        ],
    ))?;

    // The type check, its cache kept under the target folder.
    run(in_venv(python)
        .args(["-m", "mypy", "--cache-dir"])
        .arg(target.join("mypy-cache"))
        .current_dir(root.join("crates/csrl-py")))?;

    run(Command::new(&cargo)
        .args(["build", "--release", "-p", "csrl"])
        .current_dir(&root))?;
    let cli = target.join("release").join("csrl");

    run(in_venv(python)
        .args(["-m", "pytest", "-W", "error", "-q", "tests"])
        .args(&args.pytest)
        .env("CSRL_CLI", &cli)
        .current_dir(root.join("crates/csrl-py")))?;
    // The docstrings' examples, from the installed package (run from outside the
    // package's folder, so its pytest settings are given here: the same strictness).
    run(in_venv(python)
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
