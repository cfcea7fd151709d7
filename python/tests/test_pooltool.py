"""The pooltool model: against pooltool's own frictional_inelastic where the two models
coincide (e = 1, constant mu or mu frozen at the initial slip), and whole shots."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import pooltool_or_skip

pt = pooltool_or_skip()

import pooltool.constants as const  # noqa: E402
from pooltool.objects.ball.datatypes import Ball, BallParams, BallState  # noqa: E402
from pooltool.physics.resolve.ball_ball.friction import (  # noqa: E402
    AlciatoreBallBallFriction,
    AverageBallBallFriction,
)
from pooltool.physics.resolve.ball_ball.frictional_inelastic import (  # noqa: E402
    FrictionalInelastic,
)

import billiard_contact as bc  # noqa: E402
from billiard_contact.pooltool import MODEL_NAME, BilliardContact, install  # noqa: E402


def kissing_pairs(n, seed, params):
    """Balls on the table (centres R above it) 1e-6 m apart as make_kiss leaves them,
    approaching, with random horizontal velocities and 3D spins; every other pair's rvw
    Fortran-ordered."""
    rng = np.random.default_rng(seed)
    R = params.R
    out = []
    while len(out) < n:
        phi = rng.uniform(-np.pi, np.pi)
        d = np.array([np.cos(phi), np.sin(phi), 0.0])
        r1 = np.array([rng.uniform(0.2, 0.8), rng.uniform(0.2, 1.6), R])
        r2 = r1 + (2 * R + const.MIN_DIST) * d
        speed = 10 ** rng.uniform(-1.5, 0.8)
        v1 = np.r_[rng.normal(size=2), 0.0] * speed
        v2 = np.r_[rng.normal(size=2), 0.0] * speed * 0.3
        w1 = rng.normal(size=3) * speed / R
        w2 = rng.normal(size=3) * speed / R * 0.3
        if len(out) % 7 == 0:
            w1 = np.cross([0, 0, 1.0], v1) / R  # rolling cue ball
            w2 = np.zeros(3)
            v2 = np.zeros(3)
        if (v1 - v2) @ d <= 0:
            continue  # pooltool resolves only balls that approach
        order = "F" if len(out) % 2 else "C"
        rvw1 = np.array([r1, v1, w1], order=order)
        rvw2 = np.array([r2, v2, w2], order=order)
        out.append((rvw1, rvw2))
    return out


def resolve_both(reference, ours, rvw1, rvw2, params):
    b1 = Ball("1", state=BallState(rvw1.copy(order="K"), const.sliding), params=params)
    b2 = Ball("2", state=BallState(rvw2.copy(order="K"), const.sliding), params=params)
    c1, c2 = b1.copy(), b2.copy()
    reference.solve(b1, b2)
    ours.solve(c1, c2)
    return (b1, b2), (c1, c2)


def assert_agree(ref, got, rvw1, rvw2, R, tol=1e-12):
    """Horizontal velocities and all spins within tol, scaled by the pair's largest speed
    (velocities, R times spins)."""
    scale = max(np.abs(rvw1[1]).max(), np.abs(rvw2[1]).max(), R * np.abs(rvw1[2]).max(), R * np.abs(rvw2[2]).max())
    for r, g in zip(ref, got):
        dv = np.abs(r.state.rvw[1][:2] - g.state.rvw[1][:2]).max()
        dw = R * np.abs(r.state.rvw[2] - g.state.rvw[2]).max()
        assert max(dv, dw) <= tol * scale, (dv, dw, scale)
        assert g.state.s == const.sliding
        np.testing.assert_array_equal(g.state.rvw[0], r.state.rvw[0])  # positions kept


def test_agrees_with_frictional_inelastic_constant_mu():
    params = BallParams(e_b=1.0, u_b=0.06)
    reference = FrictionalInelastic(friction=AverageBallBallFriction())
    ours = BilliardContact(mu=0.06)
    pairs = kissing_pairs(2000, seed=1, params=params)
    for rvw1, rvw2 in pairs:
        ref, got = resolve_both(reference, ours, rvw1, rvw2, params)
        assert_agree(ref, got, rvw1, rvw2, params.R)
        for g in got:
            assert g.state.rvw[1][2] == 0.0  # vertical velocity dropped, as pooltool does


def test_agrees_with_frictional_inelastic_speed_dependent_mu_at_initial_slip():
    params = BallParams(e_b=1.0)
    a, b, c = 9.951e-3, 0.108, 1.088
    reference = FrictionalInelastic(friction=AlciatoreBallBallFriction(a=a, b=b, c=c))
    ours = BilliardContact(mu=bc.SpeedDependentFriction(a, b, c, evaluate="initial-slip"))
    for rvw1, rvw2 in kissing_pairs(1000, seed=2, params=params):
        ref, got = resolve_both(reference, ours, rvw1, rvw2, params)
        assert_agree(ref, got, rvw1, rvw2, params.R)


def test_speed_dependent_mu_along_the_contact_differs_from_frozen():
    """Integrated along the contact, mu(S) grows as S falls: more tangential impulse than
    mu(S(0)) frozen, where sliding does not stop (a check that the option does something)."""
    params = BallParams(e_b=1.0)
    sd = dict(a=9.951e-3, b=0.108, c=1.088)
    frozen = BilliardContact(mu=bc.SpeedDependentFriction(**sd, evaluate="initial-slip"))
    along = BilliardContact(mu=bc.SpeedDependentFriction(**sd))
    differs = 0
    for rvw1, rvw2 in kissing_pairs(200, seed=3, params=params):
        (f1, _), (a1, _) = resolve_both(frozen, along, rvw1, rvw2, params)
        differs += not np.allclose(f1.state.rvw[1], a1.state.rvw[1], rtol=1e-9, atol=1e-12)
    assert differs > 100


def test_vertical_velocity_option():
    params = BallParams(e_b=1.0)
    R = params.R
    # full follow (topspin) into a cut: friction on the contact point has a vertical part
    rvw1 = np.array([[0.5, 0.5, R], [1.0, 0.3, 0.0], [-15.0, 60.0, 0.0]])
    d = np.array([np.cos(0.4), np.sin(0.4), 0.0])
    rvw2 = np.array([rvw1[0] + (2 * R + 1e-6) * d, [0, 0, 0.0], [0, 0, 0.0]])
    keep = BilliardContact(mu=0.06, keep_vertical_velocity=True)
    drop = BilliardContact(mu=0.06)
    (k1, k2), (d1, d2) = resolve_both(keep, drop, rvw1, rvw2, params)
    assert abs(k1.state.rvw[1][2]) > 1e-4 and k1.state.rvw[1][2] == -k2.state.rvw[1][2]
    assert d1.state.rvw[1][2] == 0.0 and d2.state.rvw[1][2] == 0.0
    np.testing.assert_array_equal(k1.state.rvw[1][:2], d1.state.rvw[1][:2])


def test_restitution_defaults_to_the_balls_e_b():
    params = BallParams(e_b=0.9)
    pairs = kissing_pairs(20, seed=4, params=params)
    for rvw1, rvw2 in pairs:
        (a1, _), (b1, _) = resolve_both(
            BilliardContact(mu=0.06), BilliardContact(mu=0.06, restitution=0.9), rvw1, rvw2, params
        )
        np.testing.assert_array_equal(a1.state.rvw, b1.state.rvw)


def test_different_balls_are_refused():
    p1, p2 = BallParams(), BallParams(R=0.03)
    b1 = Ball("1", state=BallState(np.array([[0.5, 0.5, p1.R], [1, 0, 0], [0, 0, 0.0]]), 2), params=p1)
    b2 = Ball("2", state=BallState(np.array([[0.56, 0.5, p2.R], [0, 0, 0], [0, 0, 0.0]]), 2), params=p2)
    with pytest.raises(ValueError, match="identical balls"):
        BilliardContact(mu=0.06).solve(b1, b2)


def kinetic(ball):
    m, R = ball.params.m, ball.params.R
    v, w = ball.state.rvw[1], ball.state.rvw[2]
    return 0.5 * m * v @ v + 0.5 * 0.4 * m * R * R * w @ w


def check_ball_ball_events(system, minimum):
    events = [e for e in system.events if e.event_type == pt.EventType.BALL_BALL]
    assert len(events) >= minimum
    for e in events:
        before = sum(kinetic(a.initial) for a in e.agents)
        after = sum(kinetic(a.final) for a in e.agents)
        assert after <= before * (1 + 1e-12), (e, before, after)  # friction only takes
    for ball in system.balls.values():
        assert np.isfinite(ball.state.rvw).all()
    return events


def test_cut_shot_simulates():
    engine = pt.physics.PhysicsEngine()
    model = install(engine, mu=0.06)
    assert engine.resolver.ball_ball is model and model.model == MODEL_NAME
    table = pt.Table.default()
    balls = {"cue": pt.Ball.create("cue", xy=(0.5, 0.6)), "1": pt.Ball.create("1", xy=(0.7, 1.2))}
    system = pt.System(cue=pt.Cue(cue_ball_id="cue"), table=table, balls=balls)
    system.strike(V0=2.5, phi=pt.aim.at_ball(system, "1", cut=30), b=0.3)
    pt.simulate(system, engine=engine, inplace=True)
    event = check_ball_ball_events(system, 1)[0]
    final = {a.id: a.final for a in event.agents}
    cue, ob = final["cue"].state.rvw, final["1"].state.rvw
    # The object ball leaves along the line of centres, thrown by friction by a little
    # (about a degree for this cut: atan(mu) = 3.4 degrees bounds it).
    line = ob[0][:2] - cue[0][:2]
    v = ob[1][:2]
    throw = np.degrees(np.arctan2(line[0] * v[1] - line[1] * v[0], line @ v))
    assert 0.05 < abs(throw) < 3.5, throw


def test_nine_ball_break_simulates():
    engine = pt.physics.PhysicsEngine()
    install(engine)  # the default: speed-dependent mu along the contact, balls' e_b
    table = pt.Table.default()
    balls = pt.get_rack(pt.GameType.NINEBALL, table)
    assert len(balls) >= 10  # nine object balls and the cue ball
    system = pt.System(cue=pt.Cue(cue_ball_id="cue"), table=table, balls=balls)
    system.strike(V0=8.0, phi=pt.aim.at_ball(system, "1"))
    pt.simulate(system, engine=engine, inplace=True)
    check_ball_ball_events(system, 9)
    moved = [b for b in balls.values() if b.id != "cue" and not np.allclose(b.state.rvw[0], b.history[0].rvw[0])]
    assert len(moved) >= 5


def test_install_into_the_default_engine():
    from pooltool.evolution.event_based import simulate as sim

    before = sim.DEFAULT_ENGINE.resolver.ball_ball
    try:
        model = install(mu=0.05)
        assert sim.DEFAULT_ENGINE.resolver.ball_ball is model
        table = pt.Table.default()
        balls = {"cue": pt.Ball.create("cue", xy=(0.5, 0.6)), "1": pt.Ball.create("1", xy=(0.5, 1.2))}
        system = pt.System(cue=pt.Cue(cue_ball_id="cue"), table=table, balls=balls)
        system.strike(V0=1.5, phi=pt.aim.at_ball(system, "1"))
        pt.simulate(system, inplace=True)
        check_ball_ball_events(system, 1)
    finally:
        sim.DEFAULT_ENGINE.resolver.ball_ball = before
