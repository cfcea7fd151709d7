"""BallCushion: a ball on the cloth against a cushion (Mathavan, Jackson and Parkin 2010),
in the cushion's frame (x along it, y towards it, z up), against expected values derived
here.

The cushion touches the ball at height h above the cloth, at angle theta above the centre:
sin theta = (h - r) / r. Its normal force acts on the ball along -(0, cos theta, sin theta)
(back from the cushion and down); the cloth's acts along +z under the ball.
"""

from __future__ import annotations

import copy
import math
import pickle

import numpy as np
import pytest

import billiard_contact as bc

M, R, H = 0.170097, 0.028575, 0.64 * 2 * 0.028575


def kinetic(v, w, alpha=0.4):
    v, w = np.asarray(v), np.asarray(w)
    return 0.5 * M * (v * v).sum(-1) + 0.5 * alpha * M * R * R * (w * w).sum(-1)


@pytest.mark.parametrize("rule", ["stronge", "newton"])
@pytest.mark.parametrize("e", [0.0, 0.6, 1.0])
def test_frictionless_cushion_and_cloth(rule, e):
    """mu_cushion = mu_table = 0: the forces are normal. The cushion's pushes along
    -(0, cos theta, sin theta); the cloth takes the vertical part, so v_z stays 0 and only
    v_y changes, by -cos theta dP_I / m: the normal velocity at the cushion, v_y cos theta,
    goes from v_n to -e v_n under either rule (the works of compression and restitution are
    m v_y^2 / 2 and e^2 that), so v_y' = -e v_y, P_I = (1 + e) m v_y / cos theta, the cloth's
    impulse P_I sin theta; the spin is unchanged (normal forces through the centre)."""
    cushion = bc.BallCushion(mass=M, radius=R, height=H, mu_cushion=0.0, mu_table=0.0,
                             restitution=e, rule=rule)
    rng = np.random.default_rng(4)
    v = np.column_stack([rng.uniform(-2, 2, 50), rng.uniform(0.1, 3, 50), np.zeros(50)])
    w = rng.normal(size=(50, 3)) * 60
    out = cushion.resolve(v, w)
    np.testing.assert_allclose(out["v"][:, 0], v[:, 0], rtol=1e-12, atol=1e-12)
    # The end of compression (and of restitution) is an event located to about 1e-12 of
    # the impulse, so v_y' holds to that fraction of v_y (at e = 0: |v_y'| <= 1e-12 v_y).
    np.testing.assert_allclose(out["v"][:, 1] / v[:, 1], -e, rtol=1e-9, atol=2e-12)
    np.testing.assert_allclose(out["v"][:, 2], 0, atol=1e-12)
    np.testing.assert_allclose(out["w"], w, rtol=1e-12, atol=1e-9)
    s = (H - R) / R
    c = math.sqrt(1 - s * s)
    np.testing.assert_allclose(out["impulse"], (1 + e) * M * v[:, 1] / c, rtol=1e-9)
    np.testing.assert_allclose(out["impulse_compression"], M * v[:, 1] / c, rtol=1e-9)
    np.testing.assert_allclose(out["impulse_table"], out["impulse"] * s, rtol=1e-9)
    np.testing.assert_allclose(out["work_compression"], 0.5 * M * v[:, 1] ** 2, rtol=1e-9)
    np.testing.assert_allclose(out["work_restitution"], e * e * 0.5 * M * v[:, 1] ** 2, rtol=1e-9,
                               atol=1e-15)
    assert not out["lifts_off"].any() and out["events"] == [[]] * 50


@pytest.mark.parametrize("rule", ["stronge", "newton"])
def test_a_cushion_at_the_equator_without_cloth_friction_is_a_plane(rule):
    """h -> r (theta -> 0) and mu_table = 0: the cushion's contact is at the ball's equator
    and its normal horizontal, -y; without spin about x the slip there is horizontal, so the
    cushion's friction is too and the cloth carries nothing: the impact is that of a ball
    on the plane of normal (0, -1, 0) with the cushion's friction, whose restitution rules
    agree."""
    h = R * (1 + 1e-9)
    mu, e = 0.2, 0.8
    cushion = bc.BallCushion(mass=M, radius=R, height=h, mu_cushion=mu, mu_table=0.0,
                             restitution=e, rule=rule)
    plane = bc.BallPlane(mass=M, radius=R, mu=mu, restitution=e)
    rng = np.random.default_rng(8)
    n = 40
    v = np.column_stack([rng.uniform(-3, 3, n), rng.uniform(0.2, 3, n), np.zeros(n)])
    w = np.column_stack([np.zeros(n), rng.normal(size=n) * 50, rng.normal(size=n) * 80])
    got = cushion.resolve(v, w)
    want = plane.resolve(v, w, [0.0, -1.0, 0.0])
    scale = np.linalg.norm(v, axis=1, keepdims=True) + R * np.linalg.norm(w, axis=1, keepdims=True)
    assert np.all(np.abs(got["v"] - want["v"]) <= 1e-7 * scale)
    assert np.all(R * np.abs(got["w"] - want["w"]) <= 1e-7 * scale)
    np.testing.assert_allclose(got["impulse"], want["impulse"], rtol=1e-7)
    assert np.all(np.abs(got["impulse_table"]) <= 1e-7 * M * scale[:, 0])
    assert np.all(np.abs(got["v"][:, 2]) <= 1e-7 * scale[:, 0])
    # sticking at the cushion where the plane's slip stops
    assert [any(ev[1] == "sticks" for ev in evs) for evs in got["events"]] == list(want["sticks"])


def test_energy_and_the_outputs():
    cushion = bc.BallCushion(mass=M, radius=R, height=H, mu_cushion=0.2, mu_table=0.2,
                             restitution=0.85)
    v = np.array([[0.7, 2.0, 0.0], [1.5, 0.4, 0.0], [-0.3, 1.0, 0.0]])
    w = np.array([[-10.0, 30.0, 5.0], [0.0, 0.0, -60.0], [-35.0, -10.0, 0.0]])
    out = cushion.resolve(v, w)
    lost = kinetic(v, w) - kinetic(out["v"], out["w"])
    np.testing.assert_allclose(out["energy_lost"], lost, rtol=1e-8)
    assert (out["energy_lost"] > 0).all()
    # Stronge's rule: the work of restitution is e^2 that of compression
    np.testing.assert_allclose(out["work_restitution"], 0.85 ** 2 * out["work_compression"], rtol=1e-8)
    assert (out["v"][:, 1] < 0).all()  # it leaves the cushion
    assert out["v"].shape == (3, 3) and out["lifts_off"].dtype == bool and len(out["events"]) == 3
    for events in out["events"]:
        for contact, change, p in events:
            assert contact in ("cushion", "table")
            assert change in ("sticks", "reverses", "restarts", "lifts-off", "touches-down")
            assert 0 <= p <= out["impulse"].max()
    one = cushion.resolve(v[0], w[0])
    assert one["v"].shape == (3,) and np.ndim(one["impulse"]) == 0
    for k in ("v", "w", "impulse", "impulse_table", "energy_lost", "lifts_off"):
        assert np.array_equal(one[k], out[k][0]), k
    assert one["events"] == out["events"][0]
    # the methods agree
    for method, rtol in (("dop853", 1e-12), ("rk4", None)):
        other = cushion.resolve(v, w, method=method, rtol=rtol, steps=20000 if rtol is None else None)
        np.testing.assert_allclose(other["v"], out["v"], atol=1e-6)


@pytest.mark.parametrize("method,rtol", [("dopri5", 1e-10), ("dopri5", 1e-8), ("dop853", 1e-8),
                                         ("dop853", 1e-4), ("dopri5", 1e-4)])
def test_every_tolerance_resolves_a_sticking_impact(method, rtol):
    """An impact whose cushion contact sticks and slides again near the end of compression:
    the adaptive methods stalled on it at some tolerances (more than 100,000 steps) before
    the kernel's fix; every tolerance resolves it now, to its accuracy."""
    cushion = bc.BallCushion(mass=M, radius=R, height=H, mu_cushion=0.2, mu_table=0.2,
                             restitution=0.85)
    v, w = [-0.3, 1.0, 0.0], [-35.0, -10.0, 0.0]
    ref = cushion.resolve(v, w, rtol=1e-12)
    out = cushion.resolve(v, w, method=method, rtol=rtol)
    np.testing.assert_allclose(out["v"], ref["v"], atol=max(1e-6, 100 * rtol))


def test_rows_in_parallel_equal_single_calls():
    cushion = bc.BallCushion(mass=M, radius=R, height=H, mu_cushion=0.2, mu_table=0.2,
                             restitution=0.85)
    rng = np.random.default_rng(12)
    n = 200
    speed, a = rng.uniform(0.5, 2.5, n), np.radians(rng.uniform(10, 80, n))
    v = np.column_stack([speed * np.cos(a), speed * np.sin(a), np.zeros(n)])
    w = np.column_stack([-v[:, 1], v[:, 0], np.zeros(n)]) / R  # rolling
    out = cushion.resolve(v, w)
    for i in (0, 77, 199):
        one = cushion.resolve(v[i], w[i])
        assert np.array_equal(one["v"], out["v"][i]) and np.array_equal(one["w"], out["w"][i])


@pytest.mark.parametrize(
    "kwargs,message",
    [
        (dict(mass=-1.0), r"^mass = -1: > 0 kg"),
        (dict(alpha=0.0), r"^alpha = 0: in \(0, 2/3\]"),
        (dict(height=0.02), r"^height = 0.02: in \(radius, 2 radius\)"),
        (dict(height=0.06), r"^height = 0.06: in \(radius, 2 radius\)"),
        (dict(height=-1.0), r"^height = -1: > 0 m"),
        (dict(mu_cushion=-0.1), r"^mu_cushion = -0.1: in \[0, "),
        (dict(mu_table=math.inf), r"^mu_table = inf"),
        (dict(restitution=1.1), r"^restitution = 1.1: in \[0, 1\]"),
        (dict(rule="poisson"), r'^rule = "poisson": "stronge" .* or "newton"'),
    ],
)
def test_bad_keywords_name_the_argument(kwargs, message):
    params = dict(mass=M, radius=R, height=H, mu_cushion=0.2, mu_table=0.2, restitution=0.85)
    params.update(kwargs)
    with pytest.raises(ValueError, match=message) as e:
        bc.BallCushion(**params)
    assert "\n" not in str(e.value)


def test_bad_states_name_the_row_and_the_argument():
    cushion = bc.BallCushion(mass=M, radius=R, height=H, mu_cushion=0.2, mu_table=0.2,
                             restitution=0.85)
    v = np.tile([0.5, 1.0, 0.0], (5, 1))
    v[3, 1] = -0.2
    with pytest.raises(ValueError, match=r"^row 3: v = \[0.5, -0.2, 0\]: v_y > 0"):
        cushion.resolve(v, np.zeros(3))
    v[3] = [0.5, 1.0, 0.1]
    with pytest.raises(ValueError, match=r"^row 3: v = .*: v_z = 0"):
        cushion.resolve(v, np.zeros(3))
    v[3] = [0.5, 1.0, 0.0]
    w = np.zeros((5, 3))
    w[1, 2] = math.nan
    with pytest.raises(ValueError, match=r"^row 1: w = \[0, 0, NaN\]: finite numbers"):
        cushion.resolve(v, w)
    with pytest.raises(ValueError, match=r"^method = \"closed-form\": \"dop853\", \"dopri5\" or \"rk4\""):
        cushion.resolve(v, np.zeros(3), method="closed-form")
    with pytest.raises(TypeError, match="^v has dtype complex128"):
        cushion.resolve(v.astype(complex), np.zeros(3))
    with pytest.raises(TypeError, match=r"^height: expected a real number \(float or int\), got str"):
        bc.BallCushion(mass=M, radius=R, height="4 cm", mu_cushion=0.2, mu_table=0.2, restitution=0.85)


@pytest.mark.parametrize("copier", [lambda x: pickle.loads(pickle.dumps(x)), copy.copy, copy.deepcopy])
def test_pickle_and_copies_round_trip_bit_identical(copier):
    cushion = bc.BallCushion(mass=0.16, radius=0.0286, alpha=0.39, height=0.037, mu_cushion=0.17,
                             mu_table=0.21, restitution=0.8, rule="newton")
    again = copier(cushion)
    assert type(again) is bc.BallCushion and again == cushion and repr(again) == repr(cushion)
    assert repr(cushion) == ('BallCushion(mass=0.16, radius=0.0286, alpha=0.39, height=0.037, '
                             'mu_cushion=0.17, mu_table=0.21, restitution=0.8, rule="newton")')
    v, w = np.array([[0.4, 1.3, 0.0], [1.0, 0.5, 0.0]]), np.array([[5.0, -20.0, 30.0], [0, 0, 0]])
    a, b = cushion.resolve(v, w), again.resolve(v, w)
    for k in a:
        assert np.array_equal(a[k], b[k]) if k != "events" else a[k] == b[k], k
