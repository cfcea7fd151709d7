"""Shared fixtures: the repository, its scenes, and the command-line program the Python
results are compared with (an independent path: its own argument handling, JSON printing,
CSV batch reading and writing, and the library's own lab frame)."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
# The two-ball, plane and cushion scenes: `run` and the command resolve them alike. Cluster
# scenes ([[balls]], docs/formats.md#cluster-scene) are run by the command only, not yet by
# bc.run.
SCENES = sorted(
    p
    for p in (REPO / "data" / "scenes").glob("*.toml")
    if "[[balls]]" not in p.read_text()
)


def _cli_path() -> Path:
    """BILLIARD_CONTACT_CLI, else the release binary of this repository (built with
    `cargo build --release` when missing)."""
    given = os.environ.get("BILLIARD_CONTACT_CLI")
    if given:
        return Path(given)
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    exe = target / "release" / "billiard-contact"
    if not exe.exists():
        subprocess.run(
            ["cargo", "build", "--release", "--bin", "billiard-contact"],
            cwd=REPO,
            check=True,
        )
    return exe


@pytest.fixture(scope="session")
def cli() -> Path:
    exe = _cli_path()
    assert exe.exists(), f"{exe}: the billiard-contact binary is missing"
    return exe


def run_cli(cli: Path, *args: str, check: bool = True) -> subprocess.CompletedProcess:
    return subprocess.run(
        [str(cli), *args], capture_output=True, text=True, check=check, cwd=REPO
    )


def cli_json(cli: Path, *args: str) -> dict:
    return json.loads(run_cli(cli, *args).stdout)


def cli_error(cli: Path, *args: str) -> str:
    """The command's one-line message for bad input (exit code 2), without `error: `."""
    p = run_cli(cli, *args, check=False)
    assert p.returncode == 2, (p.returncode, p.stderr)
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1, p.stderr
    assert lines[0].startswith("error: "), lines[0]
    return lines[0][len("error: ") :]


def pooltool_or_skip():
    """pooltool, required when BILLIARD_CONTACT_REQUIRE_POOLTOOL=1 (CI), else optional."""
    if os.environ.get("BILLIARD_CONTACT_REQUIRE_POOLTOOL") == "1":
        import pooltool

        return pooltool
    return pytest.importorskip("pooltool")


def required_or_skip(name: str):
    """An optional package (Dask for the parallel tests), required when
    BILLIARD_CONTACT_REQUIRE_POOLTOOL=1 (CI installs it with pooltool), else optional."""
    if os.environ.get("BILLIARD_CONTACT_REQUIRE_POOLTOOL") == "1":
        import importlib

        return importlib.import_module(name)
    return pytest.importorskip(name)
