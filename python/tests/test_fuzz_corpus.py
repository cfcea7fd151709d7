"""The Python fuzz target's kept inputs, replayed (docs/testing.md#coverage-guided-fuzzing):
every file of fuzz/seeds/python, fuzz/corpus/python and fuzz/regressions/python goes
through the harness's own check, fuzz/python/fuzz_python.py's ``test_one_input``, on the
installed package (not instrumented). An input breaks a promise when the check raises: a
refusal that names no argument, a non-finite or mis-shaped output, a negative impulse,
energy created, an exception other than ValueError and TypeError.

The harness reads its bytes with atheris's FuzzedDataProvider, so atheris must be
installed: CI installs it and sets BILLIARD_CONTACT_REQUIRE_ATHERIS=1 (the test then fails
without it); elsewhere the test is skipped without atheris."""

from __future__ import annotations

import importlib.util
import os
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
HARNESS = REPO / "fuzz" / "python" / "fuzz_python.py"
FOLDERS = [REPO / "fuzz" / d / "python" for d in ("seeds", "corpus", "regressions")]


def _harness(tmp_path_factory):
    if os.environ.get("BILLIARD_CONTACT_REQUIRE_ATHERIS") != "1":
        pytest.importorskip("atheris")
    os.environ["FUZZ_PY_KNOWN"] = str(tmp_path_factory.mktemp("fuzz") / "known.txt")
    spec = importlib.util.spec_from_file_location("fuzz_python", HARNESS)
    module = importlib.util.module_from_spec(spec)
    sys.modules["fuzz_python"] = module
    spec.loader.exec_module(module)
    import billiard_contact

    module.bc = billiard_contact
    return module


@pytest.fixture(scope="module")
def harness(tmp_path_factory):
    return _harness(tmp_path_factory)


def inputs() -> list[Path]:
    return sorted(p for d in FOLDERS if d.is_dir() for p in d.iterdir() if p.is_file())


def test_there_are_inputs_of_every_kind():
    # Seeds and at least one regression (a cushion impact that stalled).
    assert any(p.parent.name == "python" and p.parent.parent.name == "seeds" for p in inputs())
    assert any(p.parent.parent.name == "regressions" for p in inputs())


def test_every_kept_input_keeps_the_promises(harness):
    broken = []
    for path in inputs():
        try:
            harness.test_one_input(path.read_bytes())
        except harness.Finding as e:
            broken.append(f"{path.relative_to(REPO)}: {str(e)[:300]}")
    assert not broken, "\n".join(broken)
