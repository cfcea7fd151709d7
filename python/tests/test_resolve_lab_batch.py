"""`BallBall.resolve_lab` against the command's lab-frame batch (`billiard-contact batch`):
the command reads the states from CSV, puts them through the library's own lab frame and
writes CSV; resolve_lab reads numpy arrays and has its own change of frame."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

import billiard_contact as bc
from conftest import run_cli

M, R = 0.170097, 0.028575

SCENE = """\
name = "batch parameters"
[balls]
mass = {m!r}
radius = {r!r}
alpha = {alpha!r}
[contact]
mu = {mu}
restitution = {e!r}
[contact.profile]
shape = "half-sine"
duration = 2.5e-4
[incoming.cm]
u = [1.0, 0.0, 0.0]
"""


def random_states(n: int, seed: int, vertical: bool = True):
    """Touching balls with random lines of centres (mostly horizontal, some steep), speeds,
    spins and `up` directions; a tenth of the pairs separate."""
    rng = np.random.default_rng(seed)
    phi = rng.uniform(-np.pi, np.pi, n)
    lift = rng.uniform(-0.4, 0.4, n) if vertical else np.zeros(n)
    lift[: n // 20] = rng.uniform(-1.5, 1.5, n // 20)  # steep lines of centres
    d = np.stack([np.cos(phi) * np.cos(lift), np.sin(phi) * np.cos(lift), np.sin(lift)], 1)
    pa = rng.uniform(-1, 1, (n, 3))
    pb = pa + 2 * R * d
    scale = 10 ** rng.uniform(-2, 1, (n, 1))
    va = rng.normal(size=(n, 3)) * scale
    vb = rng.normal(size=(n, 3)) * scale * 0.3
    if not vertical:
        va[:, 2] = 0
        vb[:, 2] = 0
    # Most pairs approach: A's velocity along the line of centres exceeds B's.
    approach = np.einsum("ij,ij->i", va - vb, d)
    flip = (approach < 0) & (rng.uniform(size=n) < 0.9)
    va[flip] -= 2 * approach[flip, None] * d[flip]
    wa = rng.normal(size=(n, 3)) * scale / R
    wb = rng.normal(size=(n, 3)) * scale / R * 0.3
    wa[: n // 50] = 0  # no spin: stun shots
    up = np.tile([0.0, 0.0, 1.0], (n, 1))
    k = n // 10
    up[:k] = rng.normal(size=(k, 3))  # any direction, any length
    return pa, va, wa, pb, vb, wb, up


def batch_via_cli(cli, tmp_path, states, scene_text, method=None, mu=None, options=()):
    """The command's lab-frame batch on the same states; the output rows as dicts."""
    pa, va, wa, pb, vb, wb, up = states
    n = len(pa)
    scene = tmp_path / "scene.toml"
    scene.write_text(scene_text)
    inp = tmp_path / "in.csv"
    out = tmp_path / "out.csv"
    cols = []
    for prefix, arr in [("a_p", pa), ("a_v", va), ("a_w", wa), ("b_p", pb), ("b_v", vb), ("b_w", wb), ("up_", up)]:
        cols += [(prefix + ax, arr[:, k]) for k, ax in enumerate("xyz")]
    if mu is not None:
        cols.append(("mu", mu))
    with open(inp, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow([c for c, _ in cols])
        for i in range(n):
            w.writerow([repr(float(v[i])) for _, v in cols])
    args = ["batch", str(inp), "--out", str(out), "--scene", str(scene)]
    if method:
        args += ["--method", method]
    run_cli(cli, *args, *options)
    with open(out, newline="") as f:
        return list(csv.DictReader(f))


def number(cell: str) -> float:
    return math.nan if cell == "" else float(cell)


def compare(got, rows, states, m=M, r=R, tol=1e-12):
    """Every output within tol of the command's, scaled as the library's checks are:
    speeds by the row's reference speed v_ref (the largest of the balls' speeds and r times
    their spins), spins by v_ref / r, impulses by m v_ref; the throw angle in radians."""
    pa, va, wa, pb, vb, wb, up = states
    n = len(rows)
    assert len(got["impulse"]) == n
    v_ref = np.max(
        np.stack(
            [np.linalg.norm(va, axis=1), np.linalg.norm(vb, axis=1),
             r * np.linalg.norm(wa, axis=1), r * np.linalg.norm(wb, axis=1)], 1
        ),
        axis=1,
    )
    worst = 0.0
    for i, row in enumerate(rows):
        assert int(row["line"]) == i + 2
        ref = {
            "va": [number(row[c]) for c in ("a_vx", "a_vy", "a_vz")],
            "wa": [number(row[c]) for c in ("a_wx", "a_wy", "a_wz")],
            "vb": [number(row[c]) for c in ("b_vx", "b_vy", "b_vz")],
            "wb": [number(row[c]) for c in ("b_wx", "b_wy", "b_wz")],
        }
        s = v_ref[i]
        for key, scale in (("va", s), ("vb", s), ("wa", s / r), ("wb", s / r)):
            err = np.max(np.abs(got[key][i] - ref[key])) / scale
            worst = max(worst, err)
            assert err <= tol, (i, key, got[key][i], ref[key])
        for key in ("impulse", "tangential_impulse"):
            err = abs(got[key][i] - number(row[key])) / (m * s)
            worst = max(worst, err)
            assert err <= tol, (i, key)
        assert bool(got["sticks"][i]) == (row["sticks"] == "true"), i
        throw = number(row["throw_angle_deg"])
        if math.isnan(throw):
            assert math.isnan(got["throw_angle_deg"][i]), i
        else:
            assert abs(math.radians(got["throw_angle_deg"][i] - throw)) <= tol, i
    return worst


def test_10000_lab_states_agree_with_cli_batch(cli, tmp_path):
    states = random_states(10_000, seed=1)
    model = bc.BallBall(mass=M, radius=R, alpha=0.4, mu=0.06, restitution=1.0)
    got = model.resolve_lab(*states[:6], up=states[6])
    rows = batch_via_cli(cli, tmp_path, states, SCENE.format(m=M, r=R, alpha=0.4, mu=0.06, e=1.0))
    compare(got, rows, states)
    # The states cover what they should: sticking, sliding throughout, separating pairs.
    sticks = got["sticks"].sum()
    collided = (got["impulse"] > 0).sum()
    assert 200 < sticks < collided < 10_000
    assert (got["impulse"] == 0).sum() >= 300  # separating pairs


def test_speed_dependent_friction_and_restitution_agree_with_cli_batch(cli, tmp_path):
    states = random_states(2_000, seed=2)
    mu = bc.SpeedDependentFriction(a=9.951e-3, b=0.108, c=1.088)
    model = bc.BallBall(mass=0.16, radius=0.0305, alpha=0.35, mu=mu, restitution=0.93)
    # the states were drawn for radius R: scale the geometry to this radius
    s = 0.0305 / R
    states = (states[0], states[1], states[2] / s, states[0] + (states[3] - states[0]) * s,
              states[4], states[5] / s, states[6])
    got = model.resolve_lab(*states[:6], up=states[6])
    text = SCENE.format(
        m=0.16, r=0.0305, alpha=0.35, e=0.93,
        mu='{ model = "speed-dependent", a = 9.951e-3, b = 0.108, c = 1.088 }',
    )
    rows = batch_via_cli(cli, tmp_path, states, text)
    compare(got, rows, states, m=0.16, r=0.0305)


def test_mu_frozen_at_initial_slip_agrees_with_cli_per_row_mu(cli, tmp_path):
    """evaluate="initial": the command with a per-row constant mu = a + b exp(-c S(0)),
    S(0) computed here from the lab state (the tangential relative velocity of the contact
    points)."""
    a, b, c = 9.951e-3, 0.108, 1.088
    states = random_states(2_000, seed=3)
    pa, va, wa, pb, vb, wb, up = states
    n = (pb - pa) / np.linalg.norm(pb - pa, axis=1)[:, None]
    rel = (va + R * np.cross(wa, n)) - (vb + R * np.cross(wb, -n))
    tangential = rel - np.einsum("ij,ij->i", rel, n)[:, None] * n
    s0 = np.linalg.norm(tangential, axis=1)
    mu_rows = a + b * np.exp(-c * s0)
    model = bc.BallBall(
        mass=M, radius=R, mu=bc.SpeedDependentFriction(a, b, c, evaluate="initial")
    )
    got = model.resolve_lab(*states[:6], up=up)
    rows = batch_via_cli(
        cli, tmp_path, states, SCENE.format(m=M, r=R, alpha=0.4, mu=0.06, e=1.0), mu=mu_rows
    )
    # mu enters linearly; S(0) here and in the library differ by round-off only
    compare(got, rows, states, tol=1e-12)


def test_evaluate_aliases_are_the_library_names():
    """The first release's names "contact" and "initial-slip" are the library's
    "along-contact" and "initial": the same friction, the same numbers; the model reports the
    library's name. The two conventions differ (mu falls along the contact in one)."""
    states = random_states(500, seed=6)
    out = {}
    for name in ("along-contact", "contact", "initial", "initial-slip"):
        f = bc.SpeedDependentFriction(9.951e-3, 0.108, 1.088, evaluate=name)
        assert f.evaluate == {"contact": "along-contact", "initial-slip": "initial"}.get(name, name)
        out[name] = bc.BallBall(mass=M, radius=R, mu=f).resolve_lab(*states[:6], up=states[6])
    for alias, name in (("contact", "along-contact"), ("initial-slip", "initial")):
        for k in out[name]:
            np.testing.assert_array_equal(out[alias][k], out[name][k])
    assert not np.allclose(out["initial"]["tangential_impulse"], out["along-contact"]["tangential_impulse"])
    assert bc.SpeedDependentFriction(0.01, 0.1, 1.0).evaluate == "along-contact"


@pytest.mark.parametrize("transform", [False, True])
def test_time_transform_agrees_with_cli_batch(cli, tmp_path, transform):
    """A hertz pulse with dop853, integrated in the smoothed time variable or not, as the
    command's --time-transform."""
    states = random_states(200, seed=7)
    model = bc.BallBall(mass=M, radius=R, mu=0.06, profile="hertz")
    got = model.resolve_lab(*states[:6], up=states[6], method="dop853", time_transform=transform)
    text = SCENE.format(m=M, r=R, alpha=0.4, mu=0.06, e=1.0).replace('"half-sine"', '"hertz"')
    rows = batch_via_cli(
        cli, tmp_path, states, text, method="dop853",
        options=("--time-transform", "true" if transform else "false"),
    )
    # Within 1e-12: the other setting differs by the integration error (rtol 1e-10).
    compare(got, rows, states)


@pytest.mark.parametrize("method", ["dop853", "rk4"])
def test_time_stepping_methods_agree_with_cli_batch(cli, tmp_path, method):
    states = random_states(300, seed=4)
    model = bc.BallBall(mass=M, radius=R, mu=0.06)
    got = model.resolve_lab(*states[:6], up=states[6], method=method)
    rows = batch_via_cli(
        cli, tmp_path, states, SCENE.format(m=M, r=R, alpha=0.4, mu=0.06, e=1.0), method=method
    )
    compare(got, rows, states)


def test_memory_orders_and_broadcasting_give_the_same_numbers():
    states = random_states(500, seed=5)
    model = bc.BallBall(mass=M, radius=R, mu=0.06)
    ref = model.resolve_lab(*states[:6], up=states[6])
    fortran = [np.asfortranarray(x) for x in states]
    got = model.resolve_lab(*fortran[:6], up=fortran[6])
    # every other row of arrays twice as long, and transposed views
    strided = []
    for x in states:
        big = np.zeros((2 * len(x), 3))
        big[::2] = x
        strided.append(big[::2])
    got2 = model.resolve_lab(*strided[:6], up=strided[6])
    transposed = [np.ascontiguousarray(x.T).T for x in states]
    got3 = model.resolve_lab(*transposed[:6], up=transposed[6])
    for other in (got, got2, got3):
        for key in ref:
            np.testing.assert_array_equal(other[key], ref[key])
    # one row at a time, as (3,) arrays, lists, and broadcast against (N, 3)
    for i in (0, 17, 499):
        one = model.resolve_lab(*(x[i] for x in states[:6]), up=states[6][i])
        lists = model.resolve_lab(*(x[i].tolist() for x in states[:6]), up=tuple(states[6][i]))
        for key in ref:
            assert np.shape(one[key]) == np.shape(ref[key][i])
            np.testing.assert_array_equal(one[key], ref[key][i])
            np.testing.assert_array_equal(lists[key], ref[key][i])
    pb_rows = states[3][:3]
    b_at_rest = model.resolve_lab(
        states[0][:3], states[1][:3], states[2][:3], pb_rows, np.zeros(3), np.zeros(3),
        up=states[6][:3],
    )
    stacked = model.resolve_lab(
        states[0][:3], states[1][:3], states[2][:3], pb_rows, np.zeros((3, 3)), np.zeros((3, 3)),
        up=states[6][:3],
    )
    for key in ref:
        np.testing.assert_array_equal(b_at_rest[key], stacked[key])


def test_output_shapes_and_types():
    model = bc.BallBall(mass=M, radius=R, mu=0.06)
    one = model.resolve_lab([0, 0, R], [1, 0, 0], [0, 0, 0], [2 * R, 0, R], [0, 0, 0], [0, 0, 0])
    assert set(one) == {"va", "wa", "vb", "wb", "impulse", "tangential_impulse", "sticks", "throw_angle_deg"}
    for key in ("va", "wa", "vb", "wb"):
        assert isinstance(one[key], np.ndarray) and one[key].shape == (3,)
    for key in ("impulse", "tangential_impulse", "throw_angle_deg"):
        assert np.shape(one[key]) == () and np.asarray(one[key]).dtype == np.float64
    assert np.shape(one["sticks"]) == () and np.asarray(one["sticks"]).dtype == np.bool_
    # head-on, elastic: A stops, B leaves with A's velocity; no throw
    np.testing.assert_allclose(one["va"], [0, 0, 0], atol=1e-15)
    np.testing.assert_allclose(one["vb"], [1, 0, 0], atol=1e-15)
    assert one["impulse"] == pytest.approx(M * 1.0, rel=1e-15)
    assert one["throw_angle_deg"] == 0.0
    n = 4
    many = model.resolve_lab(
        np.tile([0, 0, R], (n, 1)), np.tile([1.0, 0, 0], (n, 1)), np.zeros((n, 3)),
        np.tile([2 * R, 0, R], (n, 1)), np.zeros((n, 3)), np.zeros((n, 3)),
    )
    for key in ("va", "wa", "vb", "wb"):
        assert many[key].shape == (n, 3) and many[key].flags.c_contiguous
    for key in ("impulse", "tangential_impulse", "sticks", "throw_angle_deg"):
        assert many[key].shape == (n,)
    assert many["sticks"].dtype == np.bool_
    empty = model.resolve_lab(*(np.zeros((0, 3)),) * 6)
    assert empty["va"].shape == (0, 3) and empty["impulse"].shape == (0,)


def test_one_collision_at_a_time_gives_the_rows_of_the_arrays():
    """Single (3,) calls take their own path (no shared buffer, numpy scalars made from the
    stack): every output equals the row of the (N, 3) call, which the CLI's batch checks
    above hold to first principles. Random states with spin, sticking and non-sticking."""
    model = bc.BallBall(mass=M, radius=R, mu=0.2, restitution=0.9)
    states = random_states(300, seed=7)
    pa, va, wa, pb, vb, wb, up = states
    rows = model.resolve_lab(pa, va, wa, pb, vb, wb, up=up)
    assert 0 < rows["sticks"].sum() < 300
    for i in range(300):
        one = model.resolve_lab(pa[i], va[i], wa[i], pb[i], vb[i], wb[i], up=up[i])
        for key in ("va", "wa", "vb", "wb"):
            assert isinstance(one[key], np.ndarray) and one[key].shape == (3,)
            assert one[key].flags.c_contiguous and one[key].flags.writeable
            np.testing.assert_array_equal(one[key], rows[key][i])
        for key in ("impulse", "tangential_impulse", "throw_angle_deg"):
            assert type(one[key]) is np.float64
            np.testing.assert_array_equal(one[key], rows[key][i])
        assert type(one["sticks"]) is np.bool_ and one["sticks"] == rows["sticks"][i]
    # outputs are fresh objects: writing one result leaves the next call's alone
    first = model.resolve_lab(pa[0], va[0], wa[0], pb[0], vb[0], wb[0], up=up[0])
    first["va"][:] = 0.0
    again = model.resolve_lab(pa[0], va[0], wa[0], pb[0], vb[0], wb[0], up=up[0])
    np.testing.assert_array_equal(again["va"], rows["va"][0])
    # a bad single row: the field, no row number
    with pytest.raises(ValueError, match=r"^pb = .*the balls must touch") as e:
        model.resolve_lab(pa[0], va[0], wa[0], pb[0] + 1e-3, vb[0], wb[0], up=up[0])
    assert "row" not in str(e.value)
