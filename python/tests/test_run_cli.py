"""`run` and `run_toml` give the command's JSON, key for key and value for value."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

import billiard_contact as bc
from conftest import SCENES, cli_json, run_cli


def test_every_scene_is_found():
    assert len(SCENES) >= 11


@pytest.mark.parametrize("scene", SCENES, ids=[s.stem for s in SCENES])
def test_run_equals_cli_json(cli, scene):
    expected = cli_json(cli, "run", str(scene), "--json")
    got = bc.run(str(scene))
    assert list(got) == list(expected)  # the same keys in the same order
    assert got == expected


@pytest.mark.parametrize("scene", SCENES, ids=[s.stem for s in SCENES])
def test_run_toml_equals_run(cli, scene):
    text = scene.read_text()
    got = bc.run_toml(text, base_dir=str(scene.parent))
    assert got == cli_json(cli, "run", str(scene), "--json")


@pytest.mark.parametrize(
    "scene,options,args",
    [
        ("default.toml", dict(method="closed-form"), ["--method", "closed-form"]),
        ("default.toml", dict(method="rk4", steps=64), ["--method", "rk4", "--steps", "64"]),
        ("stun_cut_sticks.toml", dict(method="dopri5", rtol=1e-7), ["--method", "dopri5", "--rtol", "1e-7"]),
        ("draw_side_spin.toml", dict(rtol=1e-8, atol=1e-6), ["--rtol", "1e-8", "--atol", "1e-6"]),
        ("cut_speed_dependent.toml", dict(method="dop853", rtol=1e-12), ["--method", "dop853", "--rtol", "1e-12"]),
        ("hertz_material.toml", dict(method="dop853", time_transform=False), ["--method", "dop853", "--time-transform", "false"]),
        ("hertz_material.toml", dict(method="rk4", time_transform=True), ["--method", "rk4", "--time-transform", "true"]),
    ],
)
def test_solver_options_equal_cli_options(cli, scene, options, args):
    path = str(SCENES[0].parent / scene)
    got = bc.run(path, **options)
    expected = cli_json(cli, "run", path, "--json", *args)
    assert got == expected
    assert got["solver"]["method"] == options.get("method", got["solver"]["method"])


def test_time_transform_reaches_the_solver():
    """A hertz pulse integrated in the smoothed time variable and without it: different step
    sequences (the option is passed on), the same collision to the tolerance; None is the
    library's default (on), and run_toml takes the option too."""
    path = SCENES[0].parent / "hertz_material.toml"
    on = bc.run(str(path), method="dop853")
    off = bc.run(str(path), method="dop853", time_transform=False)
    assert bc.run(str(path), method="dop853", time_transform=True) == on
    assert off["solver"] != on["solver"]
    for k in ("impulse", "tangential_impulse", "s_out"):
        assert off[k] == pytest.approx(on[k], rel=1e-8, abs=1e-12), k
    text = path.read_text()
    assert bc.run_toml(text, base_dir=str(path.parent), method="dop853", time_transform=False) == off


def read_trace_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


@pytest.mark.parametrize(
    "scene,method,samples",
    [
        ("default.toml", "dop853", 50),
        ("stun_cut_sticks.toml", "rk4", 40),
        ("head_on_stun.toml", None, 10),  # S(0) = 0: theta is empty in the CSV, NaN here
        ("tabulated_pulse.toml", "closed-form", 25),
        ("separating.toml", None, 5),
    ],
)
def test_trace_equals_cli_trace_csv(cli, tmp_path, scene, method, samples):
    path = str(SCENES[0].parent / scene)
    trace_csv = tmp_path / "trace.csv"
    args = ["run", path, "--json", "--trace", str(trace_csv), "--samples", str(samples)]
    if method:
        args += ["--method", method]
    expected = cli_json(cli, *args)
    got = bc.run(path, method=method, samples=samples)
    trace = got.pop("trace")
    assert got == expected
    header, rows = read_trace_csv(trace_csv)
    names = [h.split(" (")[0] for h in header]
    assert list(trace) == names == list(bc.TRACE_COLUMNS)
    assert len(rows) >= samples + 1
    for k, name in enumerate(names):
        column = trace[name]
        assert isinstance(column, np.ndarray) and column.dtype == np.float64
        assert column.shape == (len(rows),)
        for i, row in enumerate(rows):
            cell = row[k]
            if cell == "":
                assert name == "theta" and math.isnan(column[i])
            else:
                assert column[i] == float(cell), (name, i)


def test_trace_true_gives_the_steps_trace(cli, tmp_path):
    path = str(SCENES[0].parent / "default.toml")
    trace_csv = tmp_path / "steps.csv"
    run_cli(cli, "run", path, "--json", "--trace", str(trace_csv))
    _, rows = read_trace_csv(trace_csv)
    trace = bc.run(path, trace=True)["trace"]
    assert len(trace["t"]) == len(rows)
    assert [float(r[0]) for r in rows] == list(trace["t"])


def test_readme_example_throw_angle():
    report = bc.run(str(SCENES[0].parent / "default.toml"))
    assert abs(report["throw_angle_deg"] - 1.718) < 5e-4


@pytest.mark.parametrize(
    "options,args",
    [
        (dict(method="rk4", steps=400), ["--method", "rk4", "--steps", "400"]),
        (dict(method="dopri5", rtol=1e-9), ["--method", "dopri5", "--rtol", "1e-9"]),
        (dict(rtol=1e-11, atol=1e-12), ["--rtol", "1e-11", "--atol", "1e-12"]),
    ],
)
def test_a_cushion_scene_with_options_equals_the_command(cli, options, args):
    scene = next(s for s in SCENES if s.stem == "cushion_stun_45")
    assert bc.run(str(scene), **options) == cli_json(cli, "run", str(scene), "--json", *args)


def test_a_cushion_scene_refuses_what_it_has_no_use_for():
    scene = str(next(s for s in SCENES if s.stem == "cushion_stun_45"))
    assert bc.run(scene)["target"] == "cushion"
    with pytest.raises(ValueError, match="^samples = 10: not for a cushion scene"):
        bc.run(scene, samples=10)
    with pytest.raises(ValueError, match="^trace = True: False for a cushion scene"):
        bc.run(scene, trace=True)
    with pytest.raises(ValueError, match="^steps = 50: only with the method rk4"):
        bc.run(scene, steps=50)
    with pytest.warns(UserWarning, match="time_transform= has no effect on a cushion impact"):
        bc.run(scene, time_transform=False)
    with pytest.warns(UserWarning, match="rtol= and atol= have no effect with rk4"):
        bc.run(scene, method="rk4", rtol=1e-6)
