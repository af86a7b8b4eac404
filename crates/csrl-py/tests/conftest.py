"""Shared fixtures: the `csrl` command-line program the Python results are compared with."""

import os
import pathlib
import shutil
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[3]


@pytest.fixture(scope="session")
def cli() -> str:
    """The `csrl` program: $CSRL_CLI, else the workspace's release build (built if absent)."""
    given = os.environ.get("CSRL_CLI")
    if given:
        return given
    path = REPO / "target" / "release" / "csrl"
    if not path.exists():
        cargo = shutil.which("cargo")
        assert cargo, "set CSRL_CLI or put cargo on PATH to build the csrl program"
        subprocess.run([cargo, "build", "--release", "-p", "csrl"], cwd=REPO, check=True)
    return str(path)


@pytest.fixture(scope="session")
def repo() -> pathlib.Path:
    return REPO
