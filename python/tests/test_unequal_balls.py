"""Balls of different mass, size and inertia: BallBall(a=Ball(...), b=Ball(...)).

The expected outcomes come from a first-principles resolution written here with numpy
(contact-point velocities, impulses applied at the contact point, r x F torques; the slip's
response to a tangential impulse is measured by applying a unit impulse), not from the
library; the identical-ball form given ball by ball must equal the identical form to the
last bit; and the lab frame of the bindings must agree with the command line's scene.
"""

from __future__ import annotations

import numpy as np
import pytest

import billiard_contact as bc


def apply(state, n, e, p, j, balls):
    """The state after the normal impulse p (N s) along +n on B (-n on A) and the
    tangential impulse j (N s) along +e on B (-e on A), both at the contact point; A's
    centre is at -r_A n from it, B's at +r_B n. Arrays of rows (shape (N, 3) and (N,))."""
    (ma, ra, ala), (mb, rb, alb) = balls
    ia, ib = ala * ma * ra * ra, alb * mb * rb * rb
    va, wa, vb, wb = state
    f_b = p[:, None] * n + j[:, None] * e
    # r x F about each centre: the contact point is at +r_A n from A, -r_B n from B.
    return (
        va - f_b / ma,
        wa + np.cross(ra * n, -f_b) / ia,
        vb + f_b / mb,
        wb + np.cross(-rb * n, f_b) / ib,
    )


def slip(state, n, balls):
    """Velocity of A's contact point relative to B's, tangential part (m/s)."""
    (_, ra, _), (_, rb, _) = balls
    va, wa, vb, wb = state
    rel = (va + np.cross(wa, ra * n)) - (vb + np.cross(wb, -rb * n))
    return rel - np.sum(rel * n, axis=1)[:, None] * n


def first_principles(pa, state, pb, balls, mu, e):
    """The outgoing state of constant-mu Coulomb friction with the stick rule: P = (1 + e)
    m* v_n for approaching balls, the friction impulse J = min(mu P, J_stop) against the
    initial slip, J_stop the impulse that brings the slip to zero."""
    (ma, _, _), (mb, _, _) = balls
    d = pb - pa
    n = d / np.linalg.norm(d, axis=1)[:, None]
    va, _, vb, _ = state
    vn = np.sum((va - vb) * n, axis=1)
    reduced = ma * mb / (ma + mb)
    p = np.where(vn > 0, (1 + e) * reduced * vn, 0.0)
    s0 = slip(state, n, balls)
    speed = np.linalg.norm(s0, axis=1)
    e_dir = np.where(speed[:, None] > 0, s0 / np.where(speed > 0, speed, 1.0)[:, None], 0.0)
    # The slip's change per unit tangential impulse, measured: K = |d slip| for J = 1.
    unit = apply(state, n, e_dir, np.zeros_like(p), np.ones_like(p), balls)
    k = np.sum((s0 - slip(unit, n, balls)) * e_dir, axis=1)
    j_stop = np.where(speed > 0, speed / np.where(k > 0, k, 1.0), 0.0)
    j = np.minimum(mu * p, j_stop)
    return apply(state, n, e_dir, p, j, balls), p, j


def random_pair(rng):
    """Mass ratio in [0.5, 2], radius ratio in [0.8, 1.25], alpha in (0, 2/3]."""
    ma = rng.uniform(0.1, 0.3)
    ra = rng.uniform(0.02, 0.04)
    mb = ma * np.exp(rng.uniform(np.log(0.5), np.log(2.0)))
    rb = ra * np.exp(rng.uniform(np.log(0.8), np.log(1.25)))
    ala, alb = (2 / 3) * (1 - rng.uniform(0, 1, 2))
    return (ma, ra, ala), (mb, rb, alb)


def random_rows(rng, balls, n_rows):
    (_, ra, _), (_, rb, _) = balls
    n = rng.normal(size=(n_rows, 3))
    n /= np.linalg.norm(n, axis=1)[:, None]
    pa = rng.normal(size=(n_rows, 3))
    pb = pa + (ra + rb) * n
    va, vb = rng.normal(size=(2, n_rows, 3))
    wa = rng.normal(size=(n_rows, 3)) / ra
    wb = rng.normal(size=(n_rows, 3)) / rb
    # Every other row: A driven into B nearly along the line of centres, little spin (a
    # small slip, so that sliding stops during the contact).
    near = slice(0, n_rows, 2)
    va[near] = n[near] * rng.uniform(0.5, 2.0, size=(len(va[near]), 1)) + 0.05 * va[near]
    wa[near] *= 0.02
    wb[near] *= 0.02
    return pa, (va, wa, vb, wb), pb


def test_resolve_lab_equals_the_first_principles_resolution():
    rng = np.random.default_rng(20251122)
    worst = 0.0
    kinds = {"stops": 0, "slides": 0}
    for _ in range(40):
        balls = random_pair(rng)
        mu, e = rng.uniform(0.0, 0.5), rng.uniform(0.0, 1.0)
        (ma, ra, ala), (mb, rb, alb) = balls
        model = bc.BallBall(
            a=bc.Ball(ma, ra, ala), b=bc.Ball(mass=mb, radius=rb, alpha=alb), mu=mu, restitution=e
        )
        pa, state, pb = random_rows(rng, balls, 500)
        out = model.resolve_lab(pa, *state[:2], pb, *state[2:])
        want, p, j = first_principles(pa, state, pb, balls, mu, e)
        va, wa, vb, wb = state
        scale = np.max(
            np.abs(np.hstack([va, vb, ra * wa, rb * wb])), axis=1
        )[:, None]
        errors = [
            (out["va"] - want[0]) / scale,
            ra * (out["wa"] - want[1]) / scale,
            (out["vb"] - want[2]) / scale,
            rb * (out["wb"] - want[3]) / scale,
        ]
        worst = max(worst, max(np.max(np.abs(x)) for x in errors))
        reduced = ma * mb / (ma + mb)
        np.testing.assert_allclose(out["impulse"], p, rtol=1e-12, atol=1e-15 * reduced)
        # J against m* times the row's speed scale (J is 0 where the balls do not slide).
        dj = np.abs(out["tangential_impulse"] - j) / (reduced * scale[:, 0])
        assert np.max(dj) < 1e-12, np.max(dj)
        kinds["stops"] += int(np.sum(out["sticks"] & (j > 0)))
        kinds["slides"] += int(np.sum(~out["sticks"] & (j > 0)))
    print(f"largest scaled error against first principles: {worst:.3e}, rows {kinds}")
    assert worst < 1e-12, worst
    # Both kinds of row occurred: sliding that stops (J < mu P) and sliding throughout.
    assert kinds["stops"] > 1000 and kinds["slides"] > 1000, kinds


def test_momentum_is_conserved_with_each_balls_mass():
    rng = np.random.default_rng(7)
    balls = ((0.184, 0.030163, 0.4), (0.17, 0.028575, 0.35))
    model = bc.BallBall(a=bc.Ball(*balls[0]), b=bc.Ball(*balls[1]), mu=0.06, restitution=0.93)
    pa, state, pb = random_rows(rng, balls, 1000)
    out = model.resolve_lab(pa, *state[:2], pb, *state[2:])
    (ma, _, _), (mb, _, _) = balls
    before = ma * state[0] + mb * state[2]
    after = ma * out["va"] + mb * out["vb"]
    scale = ma * np.max(np.abs(np.hstack(state[::2])))
    assert np.max(np.abs(after - before)) < 1e-14 * scale


def test_identical_balls_given_ball_by_ball_are_the_identical_form_to_the_last_bit():
    rng = np.random.default_rng(3)
    m, r, alpha = 0.170097, 0.028575, 0.4
    pair = ((m, r, alpha), (m, r, alpha))
    pa, state, pb = random_rows(rng, pair, 300)
    for mu in (0.06, bc.SpeedDependentFriction(a=9.951e-3, b=0.108, c=1.088, evaluate="initial-slip")):
        one = bc.BallBall(mass=m, radius=r, alpha=alpha, mu=mu, restitution=0.9)
        two = bc.BallBall(a=bc.Ball(m, r, alpha), b=bc.Ball(m, r, alpha), mu=mu, restitution=0.9)
        for method in (None, "dop853"):
            x = one.resolve_lab(pa, *state[:2], pb, *state[2:], method=method)
            y = two.resolve_lab(pa, *state[:2], pb, *state[2:], method=method)
            for key in x:
                np.testing.assert_array_equal(x[key], y[key], err_msg=key)
    one = bc.BallBall(mass=m, radius=r, alpha=alpha, mu=0.06)
    two = bc.BallBall(a=bc.Ball(m, r, alpha), b=bc.Ball(m, r), mu=0.06)
    assert two.mass == m and two.a == two.b == bc.Ball(m, r, alpha)
    assert repr(two).startswith("BallBall(a=Ball(mass=0.170097, radius=0.028575, alpha=0.4), b=")
    assert repr(one).startswith("BallBall(mass=0.170097, radius=0.028575, alpha=0.4, mu=0.06")


def test_the_lab_frame_agrees_with_the_command_lines_scene():
    """The bindings' own lab frame (centre of mass weighted by the masses, contact at
    r_A + r_B) against the library's lab scene run through run_toml."""
    a, b = (0.184, 0.030163, 0.4), (0.17, 0.028575, 0.35)
    model = bc.BallBall(a=bc.Ball(*a), b=bc.Ball(*b), mu=0.06, restitution=0.95)
    assert model.mass is None and model.radius is None and model.alpha is None
    assert (model.a.mass, model.b.radius, model.b.alpha) == (0.184, 0.028575, 0.35)
    ra, rb = a[1], b[1]
    cut = 0.4
    h = 2 * np.sqrt(ra * rb)
    pa = np.array([0.0, 0.0, ra])
    pb = pa + np.array([h * np.sin(cut), h * np.cos(cut), rb - ra])
    va, wa = np.array([0.0, 1.2, 0.0]), np.array([-1.2 / ra, 0.0, 5.0])
    vb, wb = np.zeros(3), np.zeros(3)
    out = model.resolve_lab(pa, va, wa, pb, vb, wb)
    vec = lambda v: "[" + ", ".join(repr(float(x)) for x in v) + "]"  # noqa: E731
    text = f"""
[balls.a]
mass = {a[0]}
radius = {a[1]}
alpha = {a[2]}
[balls.b]
mass = {b[0]}
radius = {b[1]}
alpha = {b[2]}
[contact]
mu = 0.06
restitution = 0.95
[contact.profile]
shape = "half-sine"
duration = 2.5e-4
[incoming.lab.a]
position = {vec(pa)}
velocity = {vec(va)}
spin = {vec(wa)}
[incoming.lab.b]
position = {vec(pb)}
velocity = {vec(vb)}
spin = {vec(wb)}
"""
    report = bc.run_toml(text, method="closed-form")
    lab = report["lab_out"]
    for key, mine in (("a", ("va", "wa")), ("b", ("vb", "wb"))):
        np.testing.assert_allclose(out[mine[0]], lab[key]["velocity"], rtol=0, atol=1e-15)
        np.testing.assert_allclose(out[mine[1]], lab[key]["spin"], rtol=0, atol=1e-12)
    assert abs(float(out["impulse"]) - report["impulse"]) <= 1e-15 * report["impulse"]
    assert abs(float(out["throw_angle_deg"]) - report["throw_angle_deg"]) < 1e-12


def test_bad_pairs_name_the_keys():
    with pytest.raises(ValueError, match=r"^ball\.mass = -1: > 0 kg"):
        bc.Ball(-1.0, 0.03)
    with pytest.raises(ValueError, match=r"^ball\.alpha = 0\.9: in \(0, 2/3\]"):
        bc.Ball(0.17, 0.03, 0.9)
    ball = bc.Ball(0.17, 0.028575)
    with pytest.raises(ValueError, match=r"balls\.mass/radius/alpha .*\[balls\.a\] and \[balls\.b\]"):
        bc.BallBall(mass=0.17, a=ball, b=ball, mu=0.06)
    with pytest.raises(ValueError, match=r"^balls\.b = missing"):
        bc.BallBall(a=ball, mu=0.06)
    with pytest.raises(ValueError, match=r"^balls\.mass = missing"):
        bc.BallBall(radius=0.03, mu=0.06)
    model = bc.BallBall(a=bc.Ball(0.184, 0.030163), b=ball, mu=0.06)
    r = 0.030163 + 0.028575
    with pytest.raises(ValueError, match=r"\|pb - pa\| = r_A \+ r_B = 0\.058738 m"):
        model.resolve_lab([0, 0, 0], [1, 0, 0], [0, 0, 0], [1.01 * r, 0, 0], [0, 0, 0], [0, 0, 0])
    with pytest.raises(TypeError):
        bc.BallBall(a=(0.17, 0.03), b=ball, mu=0.06)
