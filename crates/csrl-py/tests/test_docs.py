"""The examples of docs/python.md print what the page says they print."""

import pathlib
import re
import subprocess
import sys

import pytest

DOCS = pathlib.Path(__file__).resolve().parents[3] / "docs" / "python.md"


def printed(example: str) -> str:
    """The text block that follows the line naming `example` as what prints."""
    text = DOCS.read_text(encoding="utf-8")
    m = re.search(
        r"prints \(`python crates/csrl-py/examples/" + re.escape(example) + r"`[^\n]*\n(?:[^\n]*\n)*?\n```text\n(.*?)```",
        text,
        re.S,
    )
    assert m, f"docs/python.md shows no output of {example}"
    return m.group(1)


@pytest.mark.parametrize(
    "example", ["taxi.py", "heart_pipeline.py", "heart_testcost.py", "sensing_tabular.py", "frozenlake_agent.py"]
)
def test_example_prints_what_the_docs_show(repo, example):
    out = subprocess.run(
        [sys.executable, str(repo / "crates" / "csrl-py" / "examples" / example)],
        capture_output=True, text=True, cwd=repo, timeout=600,
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout == printed(example)
