"""BallPlane(tangential="mindlin"): Hertz's normal force and Mindlin's tangential spring
(docs/tangential.md), against values derived here from outside the library.

Hertz (a sphere of mass m, radius r, Young's modulus E and Poisson's ratio nu on a plane
of E_p, nu_p; rigid: 1/E_p = 0): F = k delta^(3/2), k = (4/3) E* sqrt(r),
1/E* = (1 - nu^2)/E + (1 - nu_p^2)/E_p; at approach speed v_n the largest compression is
delta_max = (5 m v_n^2 / (4 k))^(2/5) and the contact lasts
t_c = 2 (delta_max / v_n) int_0^1 dx / sqrt(1 - x^(5/2)), the integral (2/5) B(2/5, 1/2).
Elastic: v_n' = -v_n. Gross sliding (Maw, Barber and Fawcett 1976: the slip never stops
when its incidence is large): the tangential impulse is mu P with P = 2 m v_n, opposite to
the slip, as in the rigid model. At moderate incidence the contact point's tangential
velocity reverses (Maw et al.'s negative rebound), which the rigid stick rule cannot give.
"""

from __future__ import annotations

import copy
import math
import pickle

import numpy as np
import pytest

import billiard_contact as bc

# Chung and Ooi's aluminium oxide sphere (R = 2.5 mm, 4000 kg/m^3, E = 380 GPa, nu = 0.23).
R = 0.0025
M = 4000 * 4 / 3 * math.pi * R**3
E, NU = 3.8e11, 0.23
MU = 0.092


def model(**kw):
    return bc.BallPlane(mass=M, radius=R, mu=kw.pop("mu", MU), tangential="mindlin",
                        youngs_modulus=E, poisson_ratio=NU, **kw)


def at(deg, speed=3.9):
    """Velocity at incidence `deg` from the normal (0, 1, 0), towards the plane."""
    a = math.radians(deg)
    return speed * np.array([math.sin(a), -math.cos(a), 0.0])


def test_frictionless_impact_is_hertz():
    for plane, e_star_inv in [
        ({}, (1 - NU**2) / E),
        (dict(plane_youngs_modulus=2.1e11, plane_poisson_ratio=0.3),
         (1 - NU**2) / E + (1 - 0.3**2) / 2.1e11),
    ]:
        v = at(30)
        out = model(mu=0.0, **plane).resolve(v, [0.0, 0.0, 0.0], [0.0, 1.0, 0.0])
        np.testing.assert_allclose(out["v"], [v[0], -v[1], 0.0], atol=1e-7 * 3.9)
        np.testing.assert_allclose(out["w"], 0.0, atol=1e-12)
        vn = -v[1]
        assert out["impulse"] == pytest.approx(2 * M * vn, rel=1e-7)
        k = 4 / 3 * math.sqrt(R) / e_star_inv
        delta_max = (5 * M * vn**2 / (4 * k)) ** 0.4
        integral = 0.4 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)
        assert out["contact_time"] == pytest.approx(2 * integral * delta_max / vn, rel=1e-6)


def test_gross_sliding_is_the_rigid_answer():
    # At 80 degrees the slip cannot stop: the Coulomb impulse mu P against it throughout.
    v = at(80)
    out = model().resolve(v, [0.0, 0.0, 0.0], [0.0, 1.0, 0.0])
    p = 2 * M * -v[1]
    assert out["tangential_impulse"] == pytest.approx(MU * p, rel=1e-6)
    assert out["v"][0] == pytest.approx(v[0] - MU * p / M, rel=1e-6)
    # Friction -x at the contact point (0, -R, 0): torque (0, -R, 0) x (-J, 0, 0) = -R J z.
    assert out["w"][2] == pytest.approx(-R * MU * p / (0.4 * M * R**2), rel=1e-6)
    rigid = bc.BallPlane(mass=M, radius=R, mu=MU).resolve(v, [0.0, 0.0, 0.0], [0.0, 1.0, 0.0])
    np.testing.assert_allclose(out["v"], rigid["v"], atol=1e-6 * 3.9)


def test_the_contact_point_rebounds_backwards_at_moderate_incidence():
    # Maw et al.'s normalised incidence Psi_1 = chi tan(incidence), chi = 2 (1 - nu) /
    # (mu (2 - nu)) on a rigid plane: at Psi_1 = 3 their theory gives a negative rebound
    # (the contact point's tangential velocity reversed); the rigid rule gives 0 (it sticks).
    chi = 2 * (1 - NU) / (MU * (2 - NU))
    deg = math.degrees(math.atan(3 / chi))
    out = model().resolve(at(deg), [0.0, 0.0, 0.0], [0.0, 1.0, 0.0])
    assert out["rebound_angle"] < -0.01
    rigid = bc.BallPlane(mass=M, radius=R, mu=MU).resolve(at(deg), [0, 0, 0], [0, 1, 0])
    assert rigid["sticks"]


def test_rows_match_single_impacts_and_a_receding_ball_passes():
    v = np.array([at(d) for d in (10, 40, 70)] + [-at(20)])
    w = np.array([[0.0, 0.0, 300.0]] * 4)
    out = model().resolve(v, w, [0.0, 1.0, 0.0])
    for i in range(3):
        one = model().resolve(v[i], w[i], [0.0, 1.0, 0.0])
        np.testing.assert_array_equal(out["v"][i], one["v"])
        assert out["impulse"][i] == one["impulse"]
    np.testing.assert_array_equal(out["v"][3], v[3])
    assert out["impulse"][3] == 0.0


def test_pickles_and_the_rigid_default_is_unchanged():
    m = model(plane_youngs_modulus=2.1e11, plane_poisson_ratio=0.3)
    for other in [pickle.loads(pickle.dumps(m)), copy.deepcopy(m)]:
        assert other == m and repr(other) == repr(m) and other.tangential == "mindlin"
    rigid = bc.BallPlane(mass=M, radius=R, mu=MU)
    explicit = bc.BallPlane(mass=M, radius=R, mu=MU, tangential="rigid")
    assert rigid == explicit and rigid.tangential == "rigid" and rigid != model()
    v, w = at(30), [1.0, 2.0, 3.0]
    assert rigid.resolve(v, w, [0, 1, 0])["v"].tobytes() == explicit.resolve(v, w, [0, 1, 0])["v"].tobytes()


@pytest.mark.parametrize(
    "kw, words",
    [
        (dict(tangential="elastic"), ["tangential", "mindlin"]),
        (dict(tangential="mindlin"), ["youngs_modulus, poisson_ratio", "not given"]),
        (dict(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU, restitution=0.9),
         ["restitution = 0.9", "damping law"]),
        (dict(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU, restitution=0.9,
              damping="hunt-crossley"), ["coefficient, at_speed"]),
        (dict(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU, coefficient=0.1),
         ["damping", "elastic Hertz takes neither"]),
        (dict(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU, damping="viscous",
              coefficient=0.1), ["damping", "hunt-crossley"]),
        (dict(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU,
              damping="hunt-crossley", coefficient=-0.1), ["coefficient = -0.1"]),
        (dict(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU, restitution=1.5,
              damping="hunt-crossley", at_speed=3.9), ["restitution = 1.5"]),
        (dict(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU,
              damping="hunt-crossley", at_speed=0.0), ["at_speed = 0", "> 0"]),
        (dict(damping="hunt-crossley", coefficient=0.1), ["tangential", "rigid"]),
        (dict(youngs_modulus=E, poisson_ratio=NU), ["tangential", "rigid"]),
        (dict(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU,
              plane_youngs_modulus=2e11), ["plane_youngs_modulus, plane_poisson_ratio"]),
        (dict(tangential="mindlin", youngs_modulus=-1.0, poisson_ratio=NU),
         ["youngs_modulus = -1"]),
        (dict(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU,
              plane_youngs_modulus=2e11, plane_poisson_ratio=0.6), ["plane_poisson_ratio = 0.6"]),
    ],
)
def test_bad_keywords_are_refused_naming_them(kw, words):
    with pytest.raises(ValueError) as e:
        bc.BallPlane(mass=M, radius=R, mu=MU, **kw)
    for word in words:
        assert word in str(e.value), (word, str(e.value))


def test_a_ball_without_inertia_is_refused_naming_alpha():
    # The compliant contact's bound (docs/tangential.md): alpha >= 1e-4, as at a cushion; the
    # sticking spring turns the spin 1/alpha times faster than the velocity.
    with pytest.raises(ValueError) as e:
        model(alpha=1e-5).resolve(at(30), [0, 0, 0], [0, 1, 0])
    msg = str(e.value)
    assert "alpha = " in msg and "1e-4" in msg and "balls." not in msg, msg
    assert model(alpha=1e-4).resolve(at(30), [0, 0, 0], [0, 1, 0])["v"][1] > 0


def test_a_method_is_refused_with_mindlin():
    with pytest.raises(ValueError, match="method"):
        model().resolve(at(30), [0, 0, 0], [0, 1, 0], method="dop853")


def test_chung_ooi_test_3_restitution_through_python():
    # Chung and Ooi's Test 3 (data/chung_ooi/README.md): aluminium oxide at 3.9 m/s on a rigid
    # plane; the damping calibrated to e at that speed gives -v_n'/v_n = e, the benchmark's
    # expected value, for both laws.
    for damping in ["hunt-crossley", "kuwabara-kono"]:
        for e in [0.2, 0.6, 0.9]:
            m = bc.BallPlane(mass=M, radius=R, mu=0.0, restitution=e, tangential="mindlin",
                             youngs_modulus=E, poisson_ratio=NU, damping=damping, at_speed=3.9)
            out = m.resolve([0.0, -3.9, 0.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0])
            assert out["v"][1] / 3.9 == pytest.approx(e, abs=1e-7)
            assert pickle.loads(pickle.dumps(m)) == m
            assert f'damping="{damping}"' in repr(m)


def test_a_damped_oblique_impact_loses_energy_and_keeps_coulomb():
    m = bc.BallPlane(mass=M, radius=R, mu=MU, restitution=0.7, tangential="mindlin",
                     youngs_modulus=E, poisson_ratio=NU, damping="hunt-crossley", at_speed=3.9)
    v = np.array([at(d) for d in (5, 20, 45, 80)])
    out = m.resolve(v, np.zeros((4, 3)), [0.0, 1.0, 0.0])
    k0 = 0.5 * M * np.sum(v**2, axis=1)
    k1 = 0.5 * M * np.sum(out["v"] ** 2, axis=1) + 0.2 * M * R**2 * np.sum(out["w"] ** 2, axis=1)
    assert np.all(k1 < k0)
    assert np.all(out["tangential_impulse"] <= MU * out["impulse"] * (1 + 1e-9))
    # On a plane friction does not act back on the normal motion: the normal rebound is that
    # of a head-on impact at the same normal speed, which with Hunt-Crossley damping (e a
    # function of beta v_n alone) rises as v_n falls from the calibration's 3.9 m/s.
    head_on = m.resolve(v * [0.0, 1.0, 0.0], np.zeros((4, 3)), [0.0, 1.0, 0.0])
    np.testing.assert_allclose(out["v"][:, 1], head_on["v"][:, 1], rtol=1e-7)
    e = out["v"][:, 1] / -v[:, 1]
    assert np.all(np.diff(e) > 0) and e[0] > 0.7
