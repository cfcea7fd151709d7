"""The package's surface: the documented example, stubs that match the extension,
docstrings with units."""

from __future__ import annotations

import ast
import importlib.resources
import inspect
from pathlib import Path

import numpy as np

import billiard_contact as bc
from conftest import REPO


def test_documented_example_runs():
    report = bc.run(str(REPO / "data/scenes/default.toml"), method="dop853", rtol=1e-10, samples=50)
    assert list(report["trace"]) == bc.TRACE_COLUMNS
    assert report["trace"]["t"][-1] == report["duration"]
    assert len(report["trace"]["t"]) >= 51
    text = (REPO / "data/scenes/default.toml").read_text()
    assert bc.run_toml(text, base_dir=".") == bc.run(str(REPO / "data/scenes/default.toml"))
    model = bc.BallBall(mass=0.170097, radius=0.028575, alpha=0.4, mu=0.06, restitution=1.0)
    sd = bc.BallBall(mass=0.170097, radius=0.028575, mu=bc.SpeedDependentFriction(a=9.951e-3, b=0.108, c=1.088))
    r = 0.028575
    pa, pb = np.array([0, 0, r]), np.array([2 * r * np.cos(0.5), 2 * r * np.sin(0.5), r])
    va, wa = np.array([1.0, 0, 0]), np.array([0, 1 / r, 0])
    for m in (model, sd):
        out = m.resolve_lab(pa, va, wa, pb, np.zeros(3), np.zeros(3), up=(0, 0, 1))
        # momentum is conserved (the balls are identical)
        np.testing.assert_allclose(out["va"] + out["vb"], va, atol=1e-15)
    assert repr(model).startswith("BallBall(mass=0.170097, radius=0.028575, alpha=0.4, mu=0.06")
    assert sd.mu.a == 9.951e-3 and sd.mu.evaluate == "along-contact"
    assert sd.mu.mu(0.0) == 9.951e-3 + 0.108


def stub_names(tree: ast.Module) -> set[str]:
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
    return names


def test_stubs_match_the_extension():
    stub = Path(bc._core.__file__).with_name("_core.pyi")
    assert stub.exists() and stub.with_name("py.typed").exists()
    tree = ast.parse(stub.read_text())
    # The TypedDicts are the stubs' own.
    results = {
        "LabResult", "PlaneResult", "CompliantPlaneResult", "CushionResult", "ClusterContact",
        "ClusterResult", "ClothContact", "ClothSpec",
    }
    declared = stub_names(tree) - results
    public = {n for n in dir(bc._core) if not n.startswith("_")} | {"__version__"}
    assert declared == public
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    for cls in ("BallBall", "SpeedDependentFriction", "BallPlane", "BallCushion", "Cluster"):
        members = {n.name for n in classes[cls].body if isinstance(n, ast.FunctionDef)} - {"__init__"}
        runtime = {n for n in dir(getattr(bc, cls)) if not n.startswith("_")}
        assert members == runtime, cls
    # the signatures the stubs give are the extension's
    assert list(inspect.signature(bc.BallBall.resolve_lab).parameters) == [
        "self", "pa", "va", "wa", "pb", "vb", "wb", "up", "method", "rtol", "time_transform"]
    assert list(inspect.signature(bc.run).parameters)[:4] == ["path", "method", "rtol", "samples"]


def test_help_tells_the_units():
    doc = bc.BallBall.__doc__
    for unit in ("(kg)", "(m)", "I = alpha m r^2", "ValueError"):
        assert unit in doc, unit
    doc = bc.BallBall.resolve_lab.__doc__
    for unit in ("(m)", "(m/s)", "(rad/s)", "N s", "degrees", "NaN"):
        assert unit in doc, unit
    assert "samples" in bc.run.__doc__ and "ValueError" in bc.run.__doc__
