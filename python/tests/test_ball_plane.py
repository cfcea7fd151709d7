"""BallPlane: a ball against a plane, against expected values derived here from the ball's
own equations (docs/plane.md), independently of the library's closed form.

The ball (mass m, radius r, I = alpha m r^2) meets a plane of unit normal n (out of the
plane, towards the ball) with velocity v and spin w. The normal impulse is
P = (1 + e) m |v.n| for an approaching ball; the contact point slips with
u = v_t - r (w x n); friction gives J = min(mu P, m |u| / (1 + 1/alpha)) against u, so

    v' = v + (P n - J u/|u|) / m,      w' = w + (r J / I) (n x u/|u|).
"""

from __future__ import annotations

import copy
import math
import pickle

import numpy as np
import pytest

import billiard_contact as bc

M, R = 0.170097, 0.028575


def unit(x):
    x = np.asarray(x, dtype=float)
    return x / np.linalg.norm(x, axis=-1, keepdims=True)


def random_rotation(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    if np.linalg.det(q) < 0:  # a proper rotation: the spin, a pseudovector, rotates too
        q[:, 0] *= -1
    return q


def tangent_basis(n):
    """Two unit vectors t, s with (t, s, n) right-handed."""
    a = np.eye(3)[np.argmin(np.abs(n))]
    t = unit(a - n * a.dot(n))
    return t, np.cross(n, t)


def test_frictionless_is_newtons_rule():
    """mu = 0: v_n' = -e v_n, the tangential velocity and the spin unchanged."""
    rng = np.random.default_rng(1)
    e = 0.8
    plane = bc.BallPlane(mass=M, radius=R, mu=0.0, restitution=e)
    n = unit(rng.normal(size=(200, 3)))
    v = rng.normal(size=(200, 3))
    v -= n * (np.abs((v * n).sum(1)) + 0.1)[:, None]  # approaching: v.n < 0
    w = rng.normal(size=(200, 3)) * 40
    out = plane.resolve(v, w, n)
    vn = (v * n).sum(1)
    np.testing.assert_allclose((out["v"] * n).sum(1), -e * vn, rtol=1e-13, atol=1e-15)
    t_in = v - n * vn[:, None]
    t_out = out["v"] - n * (out["v"] * n).sum(1)[:, None]
    np.testing.assert_allclose(t_out, t_in, atol=1e-14)
    assert np.array_equal(out["w"], w)
    assert np.all(out["tangential_impulse"] == 0)
    np.testing.assert_allclose(out["impulse"], (1 + e) * M * -vn, rtol=1e-14)
    assert np.all(np.isnan(out["stick_impulse"]))


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
@pytest.mark.parametrize("angle_deg", [5.0, 20.0, 40.0])
def test_solid_ball_below_the_gross_sliding_limit_keeps_five_sevenths(e, angle_deg):
    """No spin, tan(incidence) < (1 + 1/alpha) mu (1 + e) = 3.5 mu (1 + e): the slip stops
    after J = m |v_t| / (1 + 1/alpha) = (2/7) m |v_t|, so the centre keeps 5/7 of its
    tangential velocity, v_n' = -e v_n, and the ball leaves rolling with
    w' = (r J / I) n x t = (5/7) |v_t| / r about n x t."""
    mu = 0.3
    a = math.radians(angle_deg)
    assert math.tan(a) < 3.5 * mu * (1 + e)
    plane = bc.BallPlane(mass=M, radius=R, mu=mu, restitution=e)
    speed = 2.0
    v = speed * np.array([math.sin(a), 0.0, -math.cos(a)])
    out = plane.resolve(v, np.zeros(3), [0, 0, 1])
    vt = speed * math.sin(a)
    np.testing.assert_allclose(out["v"], [5 / 7 * vt, 0, e * speed * math.cos(a)], rtol=1e-14, atol=1e-15)
    # n x t = z x x = y
    np.testing.assert_allclose(out["w"], [0, 5 / 7 * vt / R, 0], rtol=1e-14, atol=1e-12)
    assert out["sticks"] and type(out["sticks"]) is np.bool_
    np.testing.assert_allclose(out["tangential_impulse"], 2 / 7 * M * vt, rtol=1e-14)
    # p_stick = m |u| / ((1 + 1/alpha) mu)
    np.testing.assert_allclose(out["stick_impulse"], M * vt / (3.5 * mu), rtol=1e-14)
    # rolling: the contact point's slip v_t' - r (w' x n) vanishes
    slip = out["v"] - np.array([0, 0, out["v"][2]]) - R * np.cross(out["w"], [0, 0, 1])
    assert np.linalg.norm(slip) < 1e-14


@pytest.mark.parametrize("e", [0.0, 0.7, 1.0])
@pytest.mark.parametrize("alpha", [0.4, 2 / 3, 0.25])
def test_gross_sliding_keeps_one_minus_mu_one_plus_e_over_tan(e, alpha):
    """Above tan(incidence) > (1 + 1/alpha) mu (1 + e) the ball slides throughout: J = mu P
    = mu (1 + e) m |v_n|, so the tangential velocity of the centre keeps
    1 - mu (1 + e) / tan(incidence) of itself, and the spin gains r J / I about n x t."""
    mu = 0.1
    threshold = (1 + 1 / alpha) * mu * (1 + e)
    tan_a = 1.5 * threshold + 0.05
    a = math.atan(tan_a)
    plane = bc.BallPlane(mass=M, radius=R, alpha=alpha, mu=mu, restitution=e)
    speed = 3.0
    v = speed * np.array([math.sin(a), 0.0, -math.cos(a)])
    out = plane.resolve(v, np.zeros(3), [0, 0, 1])
    keep = 1 - mu * (1 + e) / tan_a
    np.testing.assert_allclose(out["v"][0], keep * v[0], rtol=1e-13)
    np.testing.assert_allclose(out["v"][2], -e * v[2], rtol=1e-13, atol=1e-15)
    assert not out["sticks"]
    j = mu * (1 + e) * M * speed * math.cos(a)
    np.testing.assert_allclose(out["tangential_impulse"], j, rtol=1e-13)
    np.testing.assert_allclose(out["w"], [0, R * j / (alpha * M * R * R), 0], rtol=1e-13, atol=1e-12)


@pytest.mark.parametrize(
    "v",
    [[0.5, 0.2, 0.3], [1.0, -2.0, 0.0]],  # leaving (v.n > 0), grazing (v.n = 0)
)
def test_a_ball_not_approaching_passes_unchanged(v):
    """The library gives a ball with v.n >= 0 no impulse (as two balls that do not
    approach): it passes unchanged, impulse 0, sticks False, no stick impulse."""
    plane = bc.BallPlane(mass=M, radius=R, mu=0.2, restitution=0.9)
    w = np.array([10.0, -20.0, 5.0])
    for method in (None, "closed-form", "rk4"):
        out = plane.resolve(v, w, [0, 0, 1], method=method)
        assert np.array_equal(out["v"], v) and np.array_equal(out["w"], w), method
        assert out["impulse"] == 0 and out["tangential_impulse"] == 0 and not out["sticks"]
        assert np.isnan(out["stick_impulse"])


def random_impacts(rng, n):
    normal = unit(rng.normal(size=(n, 3)))
    v = rng.normal(size=(n, 3)) * 2
    v -= normal * (np.abs((v * normal).sum(1)) + 0.05)[:, None]
    w = rng.normal(size=(n, 3)) * 60
    return v, w, normal


def expected(m, r, alpha, mu, e, v, w, n):
    """The closed form of the module docstring, written out row by row in numpy."""
    vn = (v * n).sum(1)
    p = np.where(vn < 0, (1 + e) * m * -vn, 0.0)
    u = v - n * vn[:, None] - r * np.cross(w, n)
    s = np.linalg.norm(u, axis=1)
    j = np.minimum(mu * p, m * s / (1 + 1 / alpha))
    d = u / np.where(s > 0, s, 1)[:, None]
    return (v + (p[:, None] * n - j[:, None] * d) / m,
            w + (r * j / (alpha * m * r * r))[:, None] * np.cross(n, d), p, j)


def test_random_impacts_against_the_formulas():
    rng = np.random.default_rng(5)
    v, w, n = random_impacts(rng, 500)
    plane = bc.BallPlane(mass=0.21, radius=0.0305, alpha=0.38, mu=0.25, restitution=0.6)
    out = plane.resolve(v, w, n)
    ev, ew, ep, ej = expected(0.21, 0.0305, 0.38, 0.25, 0.6, v, w, n)
    np.testing.assert_allclose(out["v"], ev, atol=1e-12)
    np.testing.assert_allclose(out["w"], ew, atol=1e-9)
    np.testing.assert_allclose(out["impulse"], ep, rtol=1e-13)
    np.testing.assert_allclose(out["tangential_impulse"], ej, rtol=1e-12, atol=1e-16)
    assert out["sticks"].any() and not out["sticks"].all()


def test_any_normal_orientation_rotates_the_answer():
    """A case rotated by R gives the rotated answer (v, w: R v, R w), and a normal of any
    length the unit normal's answer."""
    rng = np.random.default_rng(9)
    plane = bc.BallPlane(mass=M, radius=R, mu=0.2, restitution=0.9)
    v, w, n = random_impacts(rng, 50)
    base = plane.resolve(v, w, n)
    for _ in range(5):
        q = random_rotation(rng)
        rot = plane.resolve(v @ q.T, w @ q.T, n @ q.T)
        np.testing.assert_allclose(rot["v"], base["v"] @ q.T, atol=1e-12)
        np.testing.assert_allclose(rot["w"], base["w"] @ q.T, atol=1e-9)
        np.testing.assert_allclose(rot["impulse"], base["impulse"], rtol=1e-12)
        np.testing.assert_allclose(rot["tangential_impulse"], base["tangential_impulse"], rtol=1e-11)
        assert np.array_equal(rot["sticks"], base["sticks"])
    scaled = plane.resolve(v, w, n * 7.5)
    np.testing.assert_allclose(scaled["v"], base["v"], atol=1e-13)
    # a wall (normal along -y) and the floor (+z): the same impact, turned
    t, s = tangent_basis(np.array([0.0, -1.0, 0.0]))
    floor = plane.resolve([0.4, 0.1, -1.0], [3.0, -2.0, 7.0], [0, 0, 1])
    frame = np.column_stack([t, s, [0.0, -1.0, 0.0]])  # floor axes (x, y, z) -> (t, s, n)
    wall = plane.resolve(frame @ [0.4, 0.1, -1.0], frame @ [3.0, -2.0, 7.0], [0, -1, 0])
    np.testing.assert_allclose(wall["v"], frame @ floor["v"], atol=1e-14)
    np.testing.assert_allclose(wall["w"], frame @ floor["w"], atol=1e-12)


def test_rows_equal_single_calls_and_the_methods_agree():
    rng = np.random.default_rng(3)
    v, w, n = random_impacts(rng, 40)
    plane = bc.BallPlane(mass=M, radius=R, mu=0.15, restitution=0.75)
    out = plane.resolve(v, w, n[0])  # one normal for every row
    for i in (0, 7, 39):
        one = plane.resolve(v[i], w[i], n[0])
        for k in one:
            assert np.array_equal(out[k][i], one[k], equal_nan=k == "stick_impulse"), k
        assert one["v"].shape == (3,) and np.ndim(one["impulse"]) == 0
    for method in ("closed-form", "dop853", "rk4"):
        other = plane.resolve(v, w, n[0], method=method)
        np.testing.assert_allclose(other["v"], out["v"], atol=1e-9, err_msg=method)
        np.testing.assert_allclose(other["w"], out["w"], atol=1e-9 / R, err_msg=method)
        np.testing.assert_allclose(other["impulse"], out["impulse"], rtol=1e-12)
        np.testing.assert_allclose(other["tangential_impulse"], out["tangential_impulse"], rtol=1e-8, atol=1e-12)
        assert np.array_equal(other["sticks"], out["sticks"]), method


def test_many_rows_in_parallel_equal_the_serial_rows():
    rng = np.random.default_rng(11)
    v, w, n = random_impacts(rng, 5000)
    plane = bc.BallPlane(mass=M, radius=R, mu=0.2, restitution=0.9)
    out = plane.resolve(v, w, n)
    parts = [plane.resolve(v[a:a + 1000], w[a:a + 1000], n[a:a + 1000]) for a in range(0, 5000, 1000)]
    for k in out:
        assert np.array_equal(out[k], np.concatenate([p[k] for p in parts]), equal_nan=True), k
    # any memory order: Fortran-ordered and strided views give the same numbers
    vf = np.asfortranarray(v)
    wide = np.zeros((5000, 6))
    wide[:, ::2] = w
    again = plane.resolve(vf, wide[:, ::2], n)
    assert np.array_equal(again["v"], out["v"]) and np.array_equal(again["w"], out["w"])


@pytest.mark.parametrize(
    "kwargs,message",
    [
        (dict(mass=-1.0), r"^mass = -1: > 0 kg"),
        (dict(radius=0.0), r"^radius = 0: > 0 m"),
        (dict(alpha=0.7), r"^alpha = 0.7: in \(0, 2/3\]"),
        (dict(mu=-0.1), r"^mu = -0.1: mu >= 0"),
        (dict(mu=math.nan), r"^mu = NaN"),
        (dict(restitution=1.5), r"^restitution = 1.5: in \[0, 1\]"),
    ],
)
def test_bad_keywords_name_the_argument_and_the_range(kwargs, message):
    params = dict(mass=M, radius=R, mu=0.2, restitution=0.9)
    params.update(kwargs)
    with pytest.raises(ValueError, match=message) as e:
        bc.BallPlane(**params)
    assert "\n" not in str(e.value)


def test_bad_arrays():
    plane = bc.BallPlane(mass=M, radius=R, mu=0.2)
    v = np.tile([0.3, 0.0, -1.0], (6, 1))
    with pytest.raises(TypeError, match="^w has dtype complex128"):
        plane.resolve(v, np.zeros(3, dtype=complex), [0, 0, 1])
    with pytest.raises(ValueError, match=r"^normal has shape \(2,\): expected \(3,\) or \(N, 3\)"):
        plane.resolve(v, np.zeros(3), [0, 1])
    with pytest.raises(ValueError, match="^w has 5 rows but v has 6"):
        plane.resolve(v, np.zeros((5, 3)), [0, 0, 1])
    bad = v.copy()
    bad[4, 1] = math.nan
    with pytest.raises(ValueError, match=r"^row 4: v\[1\] = NaN: a finite number$"):
        plane.resolve(bad, np.zeros(3), [0, 0, 1])
    normals = np.tile([0.0, 0.0, 1.0], (6, 1))
    normals[2] = 0
    with pytest.raises(ValueError, match=r"^row 2: normal = \[0, 0, 0\]: a non-zero, finite direction"):
        plane.resolve(v, np.zeros(3), normals)
    with pytest.raises(ValueError, match=r"^normal = \[0, 0, 0\]"):
        plane.resolve(v[0], np.zeros(3), [0, 0, 0])
    # an impact whose result overflows: named output and row, in the serial and the
    # parallel paths
    huge = np.tile([0.0, 0.0, -1.0], (3000, 1))
    huge[2500] = [0.0, 0.0, -1.5e308]
    for rows in (huge[2000:], huge):
        # P / m overflows to inf: v[0] = 0 + 0 inf is NaN, the first output named
        with pytest.raises(ValueError, match=r"^row \d+: v\[0\] = NaN: the result is not finite") as e:
            plane.resolve(rows, np.zeros(3), [0, 0, 1])
        assert f"row {2500 - (3000 - len(rows))}:" in str(e.value)
    with pytest.raises(ValueError, match=r"^v\[0\] = NaN: the result is not finite"):
        plane.resolve(huge[2500], np.zeros(3), [0, 0, 1])
    # By a method, through the library's plane collision: a velocity whose length
    # overflows (1.8e308, -1.5e308) is refused naming v (found by the Python fuzz target,
    # which saw the library's own name for the equivalent pair's state).
    for method in ("rk4", "dop853"):
        with pytest.raises(ValueError, match=r"^v = \[.*\]: finite numbers with a finite length"):
            plane.resolve([1.79769313e308, -5.74, -1.54390116e308], np.zeros(3), [1, 1, 1], method=method)
        with pytest.raises(ValueError, match=r"^w = \[.*\]: finite numbers with a finite length"):
            plane.resolve([-0.3, 0, -1], [1.79769313e308, -5.74, -1.54390116e308], [0, 0, 1], method=method)


COPIES = [
    lambda x: pickle.loads(pickle.dumps(x)),
    lambda x: pickle.loads(pickle.dumps(x, protocol=2)),
    copy.copy,
    copy.deepcopy,
]


@pytest.mark.parametrize("copier", COPIES)
def test_pickle_and_copies_round_trip_bit_identical(copier):
    plane = bc.BallPlane(mass=0.1633, radius=0.0291, alpha=0.39, mu=0.17, restitution=0.83)
    again = copier(plane)
    assert type(again) is bc.BallPlane and again == plane and repr(again) == repr(plane)
    assert repr(plane) == "BallPlane(mass=0.1633, radius=0.0291, alpha=0.39, mu=0.17, restitution=0.83)"
    v, w, n = random_impacts(np.random.default_rng(2), 100)
    a, b = plane.resolve(v, w, n), again.resolve(v, w, n)
    for k in a:
        assert np.array_equal(a[k], b[k], equal_nan=True), k
    assert (again.mass, again.radius, again.alpha, again.mu, again.restitution) == (
        0.1633, 0.0291, 0.39, 0.17, 0.83)
