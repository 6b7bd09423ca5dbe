"""Shared fixtures: the repository's case files and the `tribo` command's own outputs, which
the Python package must reproduce digit for digit."""

import json
import os
import pathlib
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
CASES = ROOT / "cases" / "ssnp154"


def tribo_bin():
    """The `tribo` command: $TRIBO_BIN, else the release build of this checkout."""
    path = os.environ.get("TRIBO_BIN") or str(ROOT / "target" / "release" / "tribo")
    if not os.path.isfile(path):
        pytest.fail(f"the tribo command is needed at {path} (cargo build --release, or set TRIBO_BIN)")
    return path


@pytest.fixture(scope="session")
def cli_a(tmp_path_factory):
    """`tribo run a.toml` of SSNP154 A: (case path, results.json, output folder)."""
    d = tmp_path_factory.mktemp("cli_a")
    case = d / "a.toml"
    shutil.copy(CASES / "a.toml", case)
    subprocess.run([tribo_bin(), "run", str(case), "-o", str(d / "out")], check=True,
                   capture_output=True)
    results = json.loads((d / "out" / "results.json").read_text())
    return case, results, d / "out"
