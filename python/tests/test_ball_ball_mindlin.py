"""BallBall(tangential="mindlin"): two balls with Hertz's normal force and Mindlin's
tangential spring (docs/tangential.md#two-spheres), and the pooltool plug-in's
install(engine, tangential="mindlin", ...), against values derived here from outside the
library.

Hertz for two balls of one material (E, nu), masses m_a, m_b and radii r_a, r_b:
F = k delta^(3/2), k = (4/3) E* sqrt(R*), 1/E* = 2 (1 - nu^2)/E, 1/R* = 1/r_a + 1/r_b,
m* = m_a m_b / (m_a + m_b); at approach speed v_n the largest compression is
delta_max = (5 m* v_n^2 / (4 k))^(2/5) and the contact lasts
t_c = 2 (delta_max / v_n) int_0^1 dx / sqrt(1 - x^(5/2)), the integral (2/5) B(2/5, 1/2).
Elastic and frictionless, head on: the normal impulse P = 2 m* v_n, so equal balls exchange
their velocities and unequal ones leave with v_a' = (m_a - m_b) v / (m_a + m_b),
v_b' = 2 m_a v / (m_a + m_b). Gross sliding (the slip never stops: at a cut angle theta,
equal solid balls without spin slide throughout when tan theta > 7 mu, the slip's change
mu P (1/m*) (1 + 1/alpha) = 7 mu v cos theta being less than the slip v sin theta): the
tangential impulse is mu P, opposite to the slip of A's contact point over B's, as in the
rigid model (Peskin 2020, eqs 24-35 while sliding).

Damped (docs/contact-law.md): calibrated to a restitution e at an approach speed v, a
frictionless head-on pair leaves with v_B' - v_A' = e (v_A - v_B) at that speed: the
expected value is the e asked for. A frictionless head-on pair moves along the line of
centres only, as one body of the reduced mass m* on Hertz's spring k = (4/3) E* sqrt(R*):
so does a ball of mass m* and radius R* on a plane of the balls' material (the sphere-plane
contact has 1/E* = (1 - nu^2)/E + (1 - nu^2)/E = 2 (1 - nu^2)/E and the ball's own radius
as R*). With one damping law and coefficient, the pair's relative motion is that ball's
motion (BallPlane, a different kernel entry with its own geometry).
"""

from __future__ import annotations

import copy
import math
import pickle

import numpy as np
import pytest

import billiard_contact as bc

M, R = 0.17, 0.028575  # kg, m
E, NU = 5.4e9, 0.34  # resin: Pa, 1
ALPHA = 0.4
RTOL = 1e-10  # the step control's tolerance in these tests


def model(**kw):
    kw.setdefault("mass", M) if "a" not in kw else None
    kw.setdefault("radius", R) if "a" not in kw else None
    return bc.BallBall(mu=kw.pop("mu", 0.0), tangential="mindlin", youngs_modulus=E,
                       poisson_ratio=NU, **kw)


def hertz_contact_time(m_a, r_a, m_b, r_b, v_n):
    m_star = m_a * m_b / (m_a + m_b)
    r_star = 1 / (1 / r_a + 1 / r_b)
    e_star = E / (2 * (1 - NU**2))
    k = 4 / 3 * e_star * math.sqrt(r_star)
    delta_max = (5 * m_star * v_n**2 / (4 * k)) ** 0.4
    integral = 0.4 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)
    return 2 * delta_max / v_n * integral


def head_on(m, v, ra=R, rb=R):
    """A at the origin moving at v along +x into B at rest, touching."""
    return m.resolve_lab([0, 0, 0], [v, 0, 0], [0, 0, 0], [ra + rb, 0, 0], [0, 0, 0], [0, 0, 0],
                         rtol=RTOL)


def test_frictionless_equal_balls_exchange_velocities_in_hertz_time():
    v = 2.0
    out = head_on(model(), v)
    np.testing.assert_allclose(out["va"], [0, 0, 0], atol=1e-8 * v)
    np.testing.assert_allclose(out["vb"], [v, 0, 0], rtol=0, atol=1e-8 * v)
    assert out["impulse"] == pytest.approx(2 * (M / 2) * v, rel=1e-8)
    assert out["tangential_impulse"] == 0.0
    assert out["contact_time"] == pytest.approx(hertz_contact_time(M, R, M, R, v), rel=1e-6)


def test_frictionless_unequal_balls_leave_as_elastic_point_masses():
    ma, ra, mb, rb = 0.17, 0.028575, 0.21, 0.0305
    v = 1.5
    m = model(a=bc.Ball(ma, ra, ALPHA), b=bc.Ball(mb, rb, 0.38))
    out = head_on(m, v, ra, rb)
    np.testing.assert_allclose(out["va"], [(ma - mb) / (ma + mb) * v, 0, 0], atol=1e-8 * v)
    np.testing.assert_allclose(out["vb"], [2 * ma / (ma + mb) * v, 0, 0], atol=1e-8 * v)
    assert out["contact_time"] == pytest.approx(hertz_contact_time(ma, ra, mb, rb, v), rel=1e-6)


@pytest.mark.parametrize("cut_deg", [45.0, 60.0])
def test_gross_sliding_at_a_large_cut_is_the_rigid_answer(cut_deg):
    mu, v = 0.06, 3.0
    th = math.radians(cut_deg)
    assert math.tan(th) > 7 * mu  # slides throughout (module docstring)
    n = np.array([math.cos(th), math.sin(th), 0.0])  # from A's centre to B's
    va = np.array([v, 0.0, 0.0])
    out = model(mu=mu).resolve_lab([0, 0, 0], va, [0, 0, 0], 2 * R * n, [0, 0, 0], [0, 0, 0],
                                   rtol=RTOL)
    # The rigid answer: P = 2 m* v_n, J = mu P against the slip (the tangential part of
    # v_a, no spin); the torque r n x F on each ball.
    p = 2 * (M / 2) * (va @ n)
    slip = va - (va @ n) * n
    t = slip / np.linalg.norm(slip)
    impulse_on_a = -p * n - mu * p * t
    inertia = ALPHA * M * R**2
    assert out["impulse"] == pytest.approx(p, rel=1e-8)
    assert out["tangential_impulse"] == pytest.approx(mu * p, rel=1e-7)
    np.testing.assert_allclose(out["va"], va + impulse_on_a / M, rtol=0, atol=1e-8 * v)
    np.testing.assert_allclose(out["vb"], -impulse_on_a / M, rtol=0, atol=1e-8 * v)
    np.testing.assert_allclose(R * out["wa"], R * np.cross(R * n, -mu * p * t) / inertia,
                               rtol=0, atol=1e-7 * v)
    np.testing.assert_allclose(R * out["wb"], R * np.cross(-R * n, mu * p * t) / inertia,
                               rtol=0, atol=1e-7 * v)
    # The rigid closed form of the library (a different kernel) agrees.
    rigid = bc.BallBall(mass=M, radius=R, mu=mu).resolve_lab(
        [0, 0, 0], va, [0, 0, 0], 2 * R * n, [0, 0, 0], [0, 0, 0])
    assert not rigid["sticks"]
    for k in ("va", "vb"):
        np.testing.assert_allclose(out[k], rigid[k], rtol=0, atol=1e-7 * v)


def test_momentum_is_kept_and_rows_match_single_calls():
    rng = np.random.default_rng(5)
    n = 70  # past the rows that run on rayon's pool
    d = rng.normal(size=(n, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    pa = rng.uniform(-1, 1, size=(n, 3))
    pb = pa + 2 * R * d
    va = d * rng.uniform(0.2, 4, size=(n, 1)) + 0.5 * rng.normal(size=(n, 3))
    vb = 0.2 * rng.normal(size=(n, 3))
    wa, wb = 40 * rng.normal(size=(n, 3)), 40 * rng.normal(size=(n, 3))
    m = model(mu=0.1)
    out = m.resolve_lab(pa, va, wa, pb, vb, wb)
    np.testing.assert_allclose(out["va"] + out["vb"], va + vb, rtol=0, atol=1e-13 * 10)
    passing = np.einsum("ij,ij->i", va - vb, d) <= 0  # not approaching: unchanged
    assert passing.any() and not passing.all()
    np.testing.assert_array_equal(out["va"][passing], va[passing])
    assert np.all(out["impulse"][passing] == 0.0)
    for i in (0, 1, n - 1):
        one = m.resolve_lab(pa[i], va[i], wa[i], pb[i], vb[i], wb[i])
        for k in ("va", "wa", "vb", "wb", "impulse", "tangential_impulse", "contact_time"):
            np.testing.assert_array_equal(one[k], out[k][i])


def test_pickles_and_copies_with_the_same_results():
    m = model(mu=0.06, shear_stiffness_factor=3.0)
    args = ([0, 0, 0], [1.0, 0.3, 0], [0, 20.0, 5.0], [2 * R, 0, 0], [0, 0, 0], [0, 0, 0])
    for again in (pickle.loads(pickle.dumps(m)), copy.copy(m), copy.deepcopy(m)):
        assert repr(again) == repr(m) and again.tangential == "mindlin"
        for k, x in m.resolve_lab(*args).items():
            assert np.array_equal(again.resolve_lab(*args)[k], x), k


@pytest.mark.parametrize("kw, names", [
    (dict(tangential="mindlin", mu=0.1), "youngs_modulus, poisson_ratio"),
    (dict(tangential="mindlin", mu=0.1, youngs_modulus=E, poisson_ratio=0.6), "poisson_ratio"),
    (dict(tangential="mindlin", mu=0.1, youngs_modulus=E, poisson_ratio=NU, restitution=0.9),
     "restitution"),
    (dict(tangential="mindlin", mu=bc.SpeedDependentFriction(0.01, 0.1, 1.0),
          youngs_modulus=E, poisson_ratio=NU), "mu"),
    (dict(tangential="mindlin", mu=0.1, youngs_modulus=E, poisson_ratio=NU,
          shear_stiffness_factor=0.0), "shear_stiffness_factor"),
    (dict(tangential="rigid", mu=0.1, youngs_modulus=E, poisson_ratio=NU), "tangential"),
    (dict(tangential="hertz", mu=0.1), "tangential"),
])
def test_bad_keywords_name_themselves(kw, names):
    with pytest.raises(ValueError, match=rf"^{names} = "):
        bc.BallBall(mass=M, radius=R, **kw)


@pytest.mark.parametrize("damping", ["hunt-crossley", "kuwabara-kono"])
@pytest.mark.parametrize("unequal", [False, True])
def test_damped_head_on_pair_rebounds_with_the_calibrated_restitution(damping, unequal):
    e, v = 0.9, 2.0  # asked for, at the approach speed of the collision below
    if unequal:
        ma, ra, mb, rb = 0.17, 0.028575, 0.21, 0.0305
        kw = dict(a=bc.Ball(ma, ra, ALPHA), b=bc.Ball(mb, rb, 0.38))
    else:
        ma, ra, mb, rb = M, R, M, R
        kw = {}
    m = model(damping=damping, restitution=e, at_speed=v, **kw)
    assert m.restitution == e
    out = head_on(m, v, ra, rb)
    got = (out["vb"][0] - out["va"][0]) / v
    assert got == pytest.approx(e, abs=1e-6)
    # Momentum, and the impulse of the restitution: P = (1 + e) m* v.
    assert ma * out["va"][0] + mb * out["vb"][0] == pytest.approx(ma * v, rel=1e-12)
    assert out["impulse"] == pytest.approx((1 + e) * ma * mb / (ma + mb) * v, rel=1e-6)
    # Elsewhere the damped contact's restitution is its own, below 1.
    slow = head_on(m, 0.5 * v, ra, rb)
    e_slow = (slow["vb"][0] - slow["va"][0]) / (0.5 * v)
    assert e < e_slow < 1.0


@pytest.mark.parametrize("v", [0.5, 2.0, 6.0])
def test_kuwabara_kono_by_coefficient_is_its_plane_equivalent(v):
    gamma = 1e-5  # s (e of about 0.9 for pool balls: docs/contact-law.md's 5.6e-6 s at 0.95)
    pair = model(damping="kuwabara-kono", coefficient=gamma)
    out = head_on(pair, v)
    # The plane equivalent (module docstring): mass m* = M/2, radius R* = R/2, a plane of
    # the balls' material.
    plane = bc.BallPlane(mass=M / 2, radius=R / 2, mu=0.0, tangential="mindlin",
                         youngs_modulus=E, poisson_ratio=NU, plane_youngs_modulus=E,
                         plane_poisson_ratio=NU, damping="kuwabara-kono", coefficient=gamma)
    ref = plane.resolve([0, 0, -v], [0, 0, 0], [0, 0, 1], rtol=RTOL)
    e_pair = (out["vb"][0] - out["va"][0]) / v
    e_plane = ref["v"][2] / v
    assert 0.5 < e_plane < 0.99  # damped, and rebounding
    # The stiffness and mass agree to rounding (1/(2/R) against R/2), the stepping to its
    # tolerance.
    assert e_pair == pytest.approx(e_plane, abs=1e-8)
    assert out["impulse"] == pytest.approx(ref["impulse"], rel=1e-8)
    assert out["contact_time"] == pytest.approx(ref["contact_time"], rel=1e-8)


def test_damped_pair_pickles_and_copies_with_the_same_results():
    args = ([0, 0, 0], [1.0, 0.3, 0], [0, 20.0, 5.0], [2 * R, 0, 0], [0, 0, 0], [0, 0, 0])
    for m in (model(mu=0.06, damping="hunt-crossley", restitution=0.93, at_speed=1.0),
              model(mu=0.06, damping="kuwabara-kono", coefficient=5.6e-6,
                    shear_stiffness_factor=2.0)):
        assert "damping=" in repr(m)
        for again in (pickle.loads(pickle.dumps(m)), copy.copy(m), copy.deepcopy(m)):
            assert repr(again) == repr(m)
            for k, x in m.resolve_lab(*args).items():
                assert np.array_equal(again.resolve_lab(*args)[k], x), k


@pytest.mark.parametrize("kw, names", [
    (dict(restitution=0.9), "restitution"),
    (dict(damping="viscous", coefficient=0.1), "damping"),
    (dict(coefficient=0.1), "damping"),
    (dict(damping="hunt-crossley", coefficient=0.1, at_speed=1.0), "coefficient, at_speed"),
    (dict(damping="hunt-crossley", coefficient=-0.1), "coefficient"),
    (dict(damping="hunt-crossley", restitution=0.0, at_speed=1.0), "restitution"),
    (dict(damping="hunt-crossley", restitution=0.9, at_speed=-1.0), "at_speed"),
])
def test_bad_damping_keywords_name_themselves(kw, names):
    with pytest.raises(ValueError, match=rf"^{names} = "):
        model(mu=0.1, **kw)


def test_damping_without_mindlin_is_refused():
    with pytest.raises(ValueError, match=r"^tangential = "):
        bc.BallBall(mass=M, radius=R, mu=0.1, damping="hunt-crossley", coefficient=0.1)


def test_resolve_lab_refuses_a_method_and_untouching_balls():
    m = model(mu=0.1)
    with pytest.raises(ValueError, match=r"^method = "):
        m.resolve_lab([0, 0, 0], [1, 0, 0], [0, 0, 0], [2 * R, 0, 0], [0, 0, 0], [0, 0, 0],
                      method="rk4")
    with pytest.raises(ValueError, match=r"^pb = .*the balls must touch"):
        m.resolve_lab([0, 0, 0], [1, 0, 0], [0, 0, 0], [2 * R + 1e-6, 0, 0], [0, 0, 0],
                      [0, 0, 0])


def test_a_ball_without_inertia_is_refused_naming_it():
    # The compliant contact's bound (docs/tangential.md): alpha >= 1e-4 for each ball.
    light = bc.Ball(mass=M, radius=R, alpha=1e-5)
    solid = bc.Ball(mass=M, radius=R)
    for kw, name in [(dict(a=light, b=solid), "a.alpha = "), (dict(a=solid, b=light), "b.alpha = ")]:
        with pytest.raises(ValueError) as e:
            head_on(model(mu=0.1, **kw), 1.0)
        assert str(e.value).startswith(name) and "1e-4" in str(e.value), str(e.value)


# The pooltool plug-in with the compliant pair.

def pooltool_or_skip():
    from conftest import pooltool_or_skip as get

    return get()


def kissing(cut_deg, params, speed=2.0, spin=(0.0, 0.0, 0.0)):
    """Two balls on the table 1e-6 m apart (as pooltool's make_kiss leaves them), A moving
    along +x into B at the cut angle, A's rvw Fortran-ordered."""
    th = math.radians(cut_deg)
    d = np.array([math.cos(th), math.sin(th), 0.0])
    r1 = np.array([0.5, 0.5, params.R])
    rvw1 = np.array([r1, [speed, 0, 0], spin], order="F")
    rvw2 = np.array([r1 + (2 * params.R + 1e-6) * d, [0, 0, 0], [0, 0, 0]])
    return rvw1, rvw2


@pytest.mark.parametrize("cut_deg, spin", [(0.0, (0, 0, 0)), (30.0, (0, 70.0, 0)),
                                           (55.0, (-40.0, 10.0, 30.0))])
def test_plug_in_gives_the_bindings_answer(cut_deg, spin):
    pt = pooltool_or_skip()
    import pooltool.constants as const
    from pooltool.objects.ball.datatypes import Ball, BallParams, BallState

    from billiard_contact.pooltool import BilliardContact

    params = BallParams(m=M, R=R, u_b=0.06, e_b=0.93)
    params2 = BallParams(m=M, R=R, u_b=0.06, e_b=0.95)
    rvw1, rvw2 = kissing(cut_deg, params, spin=spin)
    b1 = Ball("1", state=BallState(rvw1.copy(order="K"), const.sliding), params=params)
    b2 = Ball("2", state=BallState(rvw2.copy(), const.sliding), params=params2)
    ours = BilliardContact(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU,
                           keep_vertical_velocity=True, rtol=RTOL)
    o1, o2 = ours.solve(b1, b2)
    # The binding called directly: touching along the line of centres, mu the balls' u_b,
    # the restitution the mean of their e_b, Hunt and Crossley's damping calibrated to it
    # at 1 m/s (the plug-in's documented choice).
    n = (rvw2[0] - rvw1[0]) / np.linalg.norm(rvw2[0] - rvw1[0])
    direct = model(mu=0.06, damping="hunt-crossley", restitution=(0.93 + 0.95) / 2,
                   at_speed=1.0).resolve_lab(rvw1[0], rvw1[1], rvw1[2], rvw1[0] + 2 * R * n,
                                        rvw2[1], rvw2[2], rtol=RTOL)
    # The plug-in moves both centres to touching about their midpoint, so its normal
    # differs from this one in the last bits, and the adaptive steps that follow may
    # differ: the two agree to the step control's tolerance (10 rtol), bit for bit head on.
    scale = 2.0 + R * np.abs(spin).max()
    tol = 0.0 if cut_deg == 0.0 else 10 * RTOL * scale
    for got, key in ((o1.state.rvw[1], "va"), (o2.state.rvw[1], "vb")):
        np.testing.assert_allclose(got, direct[key], rtol=0, atol=tol)
    for got, key in ((o1.state.rvw[2], "wa"), (o2.state.rvw[2], "wb")):
        np.testing.assert_allclose(R * got, R * direct[key], rtol=0, atol=tol)
    # Momentum, and positions kept.
    np.testing.assert_allclose(o1.state.rvw[1] + o2.state.rvw[1], rvw1[1] + rvw2[1],
                               rtol=0, atol=1e-13 * scale)
    np.testing.assert_array_equal(o1.state.rvw[0], rvw1[0])


def test_plug_in_installed_resolves_a_shot_with_the_compliant_pair():
    pt = pooltool_or_skip()
    import pooltool.constants as const

    from billiard_contact.pooltool import BilliardContact, install

    params = pt.BallParams(m=M, R=R, u_b=0.06, e_b=0.93)
    balls = {}
    for k in range(2):
        b = pt.Ball(id=str(k), params=params)
        b.state.rvw[0] = [0.5, 1.0 + k * (2 * R + 1e-6), R]
        balls[b.id] = b
    balls["0"].state.rvw[1] = [0, 2.0, 0]
    balls["0"].state.s = const.sliding
    system = pt.System(cue=pt.Cue(cue_ball_id="0"), table=pt.Table.default(), balls=balls)
    engine = pt.physics.PhysicsEngine()
    m = install(engine, cushion=False, tangential="mindlin", youngs_modulus=E, poisson_ratio=NU)
    assert isinstance(engine.resolver.ball_ball, BilliardContact) and m.tangential == "mindlin"
    shot = pt.simulate(system, engine=engine, t_final=0.01, max_events=20)
    events = [ev for ev in shot.events if ev.event_type == pt.EventType.BALL_BALL]
    assert len(events) == 1
    (a_in, b_in), (a_out, b_out) = ([x.initial.state.rvw for x in events[0].agents],
                                    [x.final.state.rvw for x in events[0].agents])
    # Head on, no slip at the contact: the binding's answer with the balls' e_b calibrated
    # at 1 m/s, called directly on the event's incoming state; momentum is kept and the
    # rebound is damped (B leaves slower than A came).
    direct = model(mu=0.06, damping="hunt-crossley", restitution=0.93, at_speed=1.0
                   ).resolve_lab(a_in[0], a_in[1], a_in[2], a_in[0] + [0, 2 * R, 0], b_in[1],
                                 b_in[2])
    # (pooltool 0.6's engine is 2D: the plug-in zeroes the vertical velocity that friction
    # on A's small backspin gives, about 2e-7 m/s here.)
    for got, key in ((a_out[1], "va"), (b_out[1], "vb")):
        np.testing.assert_allclose(got, [*direct[key][:2], 0.0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(a_out[1] + b_out[1], a_in[1] + b_in[1], rtol=0, atol=1e-12)
    assert 0.9 * a_in[1][1] < b_out[1][1] < 0.99 * a_in[1][1]
    assert pickle.loads(pickle.dumps(m)) == m


def test_plug_in_given_restitution_and_elastic_e_b():
    pooltool_or_skip()
    import pooltool.constants as const
    from pooltool.objects.ball.datatypes import Ball, BallParams, BallState

    from billiard_contact.pooltool import BilliardContact

    for e_b, given, kw in ((0.93, 0.8, dict(damping="hunt-crossley", restitution=0.8,
                                            at_speed=1.0)),
                           (1.0, None, {})):
        params = BallParams(m=M, R=R, u_b=0.06, e_b=e_b)
        rvw1, rvw2 = kissing(0.0, params)
        b1 = Ball("1", state=BallState(rvw1.copy(order="K"), const.sliding), params=params)
        b2 = Ball("2", state=BallState(rvw2.copy(), const.sliding), params=params)
        ours = BilliardContact(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU,
                               restitution=given, rtol=RTOL)
        o1, o2 = ours.solve(b1, b2)
        direct = model(mu=0.06, **kw).resolve_lab(rvw1[0], rvw1[1], rvw1[2],
                                                  rvw1[0] + [2 * R, 0, 0], rvw2[1], rvw2[2],
                                                  rtol=RTOL)
        np.testing.assert_array_equal(o1.state.rvw[1], direct["va"])
        np.testing.assert_array_equal(o2.state.rvw[1], direct["vb"])


@pytest.mark.parametrize("kw, match", [
    (dict(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU, restitution=1.5),
     "contact.restitution"),
    (dict(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU, method="rk4"), "method"),
    (dict(tangential="mindlin", youngs_modulus=E, poisson_ratio=NU,
          mu=bc.SpeedDependentFriction(0.01, 0.1, 1.0)), "mu"),
    (dict(tangential="mindlin"), "youngs_modulus, poisson_ratio"),
    (dict(youngs_modulus=E, poisson_ratio=NU), "youngs_modulus, poisson_ratio, shear"),
    (dict(tangential="coulomb"), "tangential"),
])
def test_plug_in_refuses_what_the_compliant_pair_cannot_do(kw, match):
    pooltool_or_skip()
    from billiard_contact.pooltool import BilliardContact

    with pytest.raises(ValueError, match=rf"^{match}"):
        BilliardContact(**kw)
