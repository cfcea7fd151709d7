"""Cluster: N balls resolved together, against values derived here independently of the
library: conservation laws, Hertz's contact of two spheres, the restitution the damping was
calibrated to, and a line of balls integrated by a fixed-step Runge-Kutta scheme in numpy
(docs/cluster.md has the equations).

Hertz (two spheres of mass m, radius r, Young's modulus E, Poisson's ratio nu): the force
is k delta^(3/2) with k = (4/3) E* sqrt(R*), 1/E* = 2 (1 - nu^2) / E, R* = r / 2; with
the reduced mass m* = m / 2 and approach speed v, the largest compression is
delta_max = (5 m* v^2 / (4 k))^(2/5) and the contact lasts
t_c = 2 (delta_max / v) int_0^1 dx / sqrt(1 - x^(5/2)) = 2.943 delta_max / v (the integral
is (2/5) B(2/5, 1/2) = 1.47164).
"""

from __future__ import annotations

import copy
import math
import pickle

import numpy as np
import pytest

import billiard_contact as bc

M, R, E, NU = 0.17, 0.028575, 5.4e9, 0.34
BALL = bc.Ball(mass=M, radius=R, alpha=0.4)


def hertz_k():
    e_star = E / (2.0 * (1.0 - NU**2))
    return 4.0 / 3.0 * e_star * math.sqrt(R / 2.0)


def line(n, v, gap=0.0):
    """n balls on the x axis touching (or `gap` apart), the first moving at v along +x."""
    p = np.array([[2.0 * R * i + gap * i, 0.0, 0.0] for i in range(n)])
    vel = np.zeros((n, 3))
    vel[0, 0] = v
    return p, vel, np.zeros((n, 3))


def elastic(**kw):
    return bc.Cluster(balls=[BALL] * kw.pop("n", 2), mu=kw.pop("mu", 0.0),
                      youngs_modulus=E, poisson_ratio=NU, **kw)


def test_two_balls_head_on_swap_velocities_and_last_hertz_time():
    v = 2.0
    out = elastic().resolve(*line(2, v), rtol=1e-10)
    # Equal masses, elastic: momentum and energy give the exchange of velocities.
    np.testing.assert_allclose(out["velocities"], [[0, 0, 0], [v, 0, 0]], atol=1e-8 * v)
    np.testing.assert_array_equal(out["spins"], np.zeros((2, 3)))
    (c,) = out["contacts"]
    assert c["pair"] == (0, 1)
    assert c["impulse"] == pytest.approx(M * v, rel=1e-8)
    np.testing.assert_allclose(c["normal"], [1, 0, 0], atol=1e-15)
    delta_max = (5 * (M / 2) * v**2 / (4 * hertz_k())) ** 0.4
    # int_0^1 dx / sqrt(1 - x^(5/2)) = (2/5) B(2/5, 1/2) (x = y^(2/5)), Euler's Beta.
    integral = 0.4 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)
    assert integral == pytest.approx(1.47164, rel=2e-5)
    assert c["duration"] == pytest.approx(2 * integral * delta_max / v, rel=1e-4)
    assert c["heat"] == pytest.approx(0.0, abs=1e-9 * M * v**2)
    assert c["stick_time"] is None


def test_calibrated_damping_gives_its_restitution_head_on_at_its_speed():
    v, e = 1.0, 0.9
    for damping in ["hunt-crossley", "kuwabara-kono"]:
        model = elastic(damping=damping, restitution=e, at_speed=v)
        out = model.resolve(*line(2, v), rtol=1e-10)
        # Momentum m v = m (va + vb), restitution vb - va = e v.
        np.testing.assert_allclose(out["velocities"][:, 0], [(1 - e) / 2 * v, (1 + e) / 2 * v],
                                   atol=1e-7)
        heat = 0.5 * M * v**2 - 0.5 * M * np.sum(out["velocities"] ** 2)
        assert out["contacts"][0]["heat"] == pytest.approx(heat, rel=1e-6)


def chain_rk4(n, v, k, m, steps_per_tc=20000):
    """The head-on line of n equal balls, integrated independently: compressions
    delta_i = x_i - x_{i+1} + 2r of neighbours, force k delta^(3/2) when positive, fixed-step
    classical RK4 until every contact has opened and no neighbours close."""
    delta_max = (5 * (m / 2) * v**2 / (4 * k)) ** 0.4
    h = 2.943 * delta_max / v / steps_per_tc
    x = np.zeros(n)  # displacements from touching
    u = np.zeros(n)
    u[0] = v

    def acc(x):
        d = np.maximum(x[:-1] - x[1:], 0.0)
        f = k * d**1.5
        a = np.zeros(n)
        a[:-1] -= f / m
        a[1:] += f / m
        return a

    for _ in range(200 * steps_per_tc):
        k1x, k1u = u, acc(x)
        k2x, k2u = u + h / 2 * k1u, acc(x + h / 2 * k1x)
        k3x, k3u = u + h / 2 * k2u, acc(x + h / 2 * k2x)
        k4x, k4u = u + h * k3u, acc(x + h * k3x)
        x = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
        u = u + h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u)
        if np.all(x[:-1] - x[1:] < 0) and np.all(u[:-1] <= u[1:]):
            return u
    raise AssertionError("the chain did not separate")


def test_newtons_cradle_of_three_matches_an_independent_rk4_chain():
    v = 1.0
    expected = chain_rk4(3, v, hertz_k(), M)
    # Not the ideal (0, 0, v): Hertz contacts leave the first balls a little motion.
    assert abs(expected[2] - v) > 1e-3
    out = elastic(n=3).resolve(*line(3, v), rtol=1e-10)
    np.testing.assert_allclose(out["velocities"][:, 0], expected, atol=1e-6 * v)
    assert len(out["contacts"]) >= 2


def diamond():
    """Four balls in a touching diamond struck by a fifth with spin and a cut."""
    s = 2 * R
    p = np.array([[0, 0, 0], [s * math.cos(math.pi / 6), s / 2, 0],
                  [s * math.cos(math.pi / 6), -s / 2, 0], [2 * s * math.cos(math.pi / 6), 0, 0],
                  [-s - 1e-3, 0.01, 0]])
    v = np.zeros((5, 3))
    v[4] = [3.0, -0.2, 0.0]
    w = np.zeros((5, 3))
    w[4] = [5.0, 60.0, -30.0]
    return p, v, w


def test_a_struck_diamond_conserves_momentum_and_its_contacts_account_for_every_change():
    model = bc.Cluster(balls=[BALL] * 5, mu=0.06, youngs_modulus=E, poisson_ratio=NU,
                       damping="hunt-crossley", restitution=0.93, at_speed=1.0)
    p, v, w = diamond()
    out = model.resolve(p, v, w)
    vo, wo = out["velocities"], out["spins"]
    scale = M * np.abs(v).sum()
    np.testing.assert_allclose(M * vo.sum(axis=0), M * v.sum(axis=0), atol=1e-12 * scale)
    # Newton's third law, contact by contact: ball j gets P n - J, ball i -(P n - J).
    dv = np.zeros_like(v)
    dw = np.zeros_like(w)
    for c in out["contacts"]:
        i, j = c["pair"]
        on_j = c["impulse"] * c["normal"] - c["friction_impulse"]
        dv[j] += on_j / M
        dv[i] -= on_j / M
        # Friction acts at the contact point, r along n from i, r against it from j.
        dw[i] += np.cross(R * c["normal"], c["friction_impulse"]) / (0.4 * M * R**2)
        dw[j] += np.cross(-R * c["normal"], -c["friction_impulse"]) / (0.4 * M * R**2)
        assert c["impulse"] > 0 and c["heat"] >= 0
        assert np.linalg.norm(c["friction_impulse"]) <= 0.06 * c["impulse"] * (1 + 1e-9)
    np.testing.assert_allclose(vo - v, dv, atol=1e-9 * np.abs(v).max())
    np.testing.assert_allclose(wo - w, dw, atol=1e-9 * np.abs(w).max())
    energy = lambda v, w: 0.5 * M * np.sum(v**2) + 0.5 * 0.4 * M * R**2 * np.sum(w**2)
    heat = sum(c["heat"] for c in out["contacts"])
    assert energy(v, w) - energy(vo, wo) == pytest.approx(heat, rel=1e-6)


def test_pickles_and_copies_to_an_equal_model_with_the_same_answers():
    model = bc.Cluster(balls=[BALL, bc.Ball(mass=0.16, radius=0.028)], mu=0.05,
                       youngs_modulus=E, poisson_ratio=NU, damping="kuwabara-kono",
                       restitution=0.9, at_speed=2.0, stick=False)
    p = np.array([[0.0, 0.0, 0.0], [R + 0.028, 0.0, 0.0]])
    v = np.array([[1.0, 0.1, 0.0], [0.0, 0.0, 0.0]])
    w = np.array([[0.0, 0.0, 20.0], [0.0, 0.0, 0.0]])
    for other in [pickle.loads(pickle.dumps(model)), copy.deepcopy(model)]:
        assert other == model and repr(other) == repr(model)
        np.testing.assert_array_equal(other.resolve(p, v, w)["velocities"],
                                      model.resolve(p, v, w)["velocities"])
    assert "stick=False" in repr(model)


@pytest.mark.parametrize(
    "kw, words",
    [
        (dict(balls=[BALL], mu=0.1, stiffness=1e9), ["balls = 1 balls", "2 to 22"]),
        (dict(balls=[BALL] * 23, mu=0.1, stiffness=1e9), ["balls = 23 balls"]),
        (dict(balls=[BALL] * 2, mu=-1, stiffness=1e9), ["mu = -1", "[0, 1e6]"]),
        (dict(balls=[BALL] * 2, mu=0.1), ["youngs_modulus", "or stiffness"]),
        (dict(balls=[BALL] * 2, mu=0.1, youngs_modulus=E), ["youngs_modulus", "poisson_ratio"]),
        (dict(balls=[BALL] * 2, mu=0.1, stiffness=1e9, youngs_modulus=E, poisson_ratio=NU),
         ["stiffness", "not both"]),
        (dict(balls=[BALL] * 2, mu=0.1, stiffness=1e9, damping="viscous"),
         ["damping", "hunt-crossley"]),
        (dict(balls=[BALL] * 2, mu=0.1, stiffness=1e9, damping="hunt-crossley"),
         ["damping", "restitution"]),
        (dict(balls=[BALL] * 2, mu=0.1, stiffness=1e9, restitution=0.9),
         ["restitution, at_speed", "together"]),
        (dict(balls=[BALL] * 2, mu=0.1, stiffness=-1.0), ["stiffness = -1"]),
        # The calibration is checked when the model is built, not at its first resolve.
        (dict(balls=[BALL] * 3, mu=0.1, youngs_modulus=E, poisson_ratio=NU, restitution=0.93,
              at_speed=1.0), ["restitution = 0.93", "hunt-crossley"]),
        (dict(balls=[BALL] * 2, mu=0.1, youngs_modulus=E, poisson_ratio=0.7),
         ["poisson_ratio = 0.7"]),
    ],
)
def test_bad_models_are_refused_naming_the_keyword(kw, words):
    with pytest.raises(ValueError) as e:
        bc.Cluster(**kw)
    msg = str(e.value)
    assert "\n" not in msg
    for word in words:
        assert word in msg


def test_bad_states_are_refused_naming_the_balls():
    model = elastic()
    p, v, w = line(2, 1.0)
    cases = [
        ((p * 0.5, v, w), ["balls[0], balls[1]", "overlap"]),
        ((p, -v, w), ["balls", "approaches"]),
        ((p, np.where(v > 0, np.nan, v), w), ["balls[0]", "NaN", "finite"]),
        ((p[:, :2], v, w), ["positions", "(N, 3)"]),
        ((p, v[:1], w), ["velocities", "1 rows", "(2)"]),
        ((p, v, w, -1.0), ["rtol = -1"]),
    ]
    for args, words in cases:
        with pytest.raises(ValueError) as e:
            model.resolve(*args)
        for word in words:
            assert word in str(e.value), (words, str(e.value))
    with pytest.raises(TypeError, match="balls: expected a list of Ball"):
        bc.Cluster(balls=[BALL, 1.0], mu=0.0, stiffness=1e9)
