"""A struck row of balls 1e-6 m apart, simulated by pooltool with the plug-in installed pair
by pair: each collision is one event, and pooltool's collision time for two balls without
relative acceleration is the root of the quadratic their distance obeys.

Expected values come from outside the plug-in: Newton's restitution for a head-on impact of
equal balls without slip at the contact (the normal impulse (1 + e) (m/2) v, Peskin 2020,
eqs 24-35 with no tangential impulse: v1' = (1 - e) v / 2, v2' = (1 + e) v / 2), momentum
conservation, the library's two-ball law called directly on the event's recorded incoming
states (``bc.BallBall.resolve_lab``, not through the plug-in), and uniform relative motion
(two balls with the same acceleration close their gap at their constant relative speed).
"""

from __future__ import annotations

import numpy as np
import pytest

from conftest import pooltool_or_skip

pt = pooltool_or_skip()

import pooltool.constants as const  # noqa: E402
from pooltool.evolution.event_based import solve as pt_solve  # noqa: E402

import billiard_contact as bc  # noqa: E402
from billiard_contact.pooltool import COLLISION_TIME_CORRECTED, install  # noqa: E402

R = 0.028575  # m
M = 0.17  # kg
E_B = 0.93
GAP = 1e-6  # m, pooltool's const.MIN_DIST
SPEED = 8.0  # m/s
#: pooltool's default ball-ball friction fit, the plug-in's default mu.
MU = bc.SpeedDependentFriction(a=9.951e-3, b=0.108, c=1.088)
#: Ball 0 catches ball 1 again only after about 1e-4 s in the three-ball row (after the
#: second collision ball 1 keeps (1 - e)/2 of its 7.72 m/s, 0.27 m/s, against ball 0's
#: 0.28 m/s: 1e-6 m closes at about 0.01 m/s); both models record that later contact.
#: Until this time each pair meets once.
T_ONE_CONTACT_EACH = 2e-5  # s


def row(n: int, speed: float = SPEED):
    """n balls along +y on the table, GAP apart, the first sliding at `speed` without spin."""
    params = pt.BallParams(m=M, R=R, u_b=0.06, e_b=E_B)
    balls = {}
    for k in range(n):
        b = pt.Ball(id=str(k), params=params)
        b.state.rvw[0] = [0.5, 1.0 + k * (2 * R + GAP), R]
        balls[b.id] = b
    balls["0"].state.rvw[1] = [0.0, speed, 0.0]
    balls["0"].state.s = const.sliding
    return pt.System(cue=pt.Cue(cue_ball_id="0"), table=pt.Table.default(), balls=balls)


def plug_in_engine():
    engine = pt.physics.PhysicsEngine()
    install(engine, cushion=False)
    return engine


def ball_ball_events(shot):
    return [ev for ev in shot.events if ev.event_type == pt.EventType.BALL_BALL]


def direct(rvw_a, rvw_b):
    """The two-ball law called directly on the incoming states, at touching along their
    line of centres; vertical velocity dropped as in a 2D engine."""
    model = bc.BallBall(mass=M, radius=R, alpha=0.4, mu=MU, restitution=E_B)
    n = rvw_b[0] - rvw_a[0]
    n = n / np.linalg.norm(n)
    out = model.resolve_lab(rvw_a[0], rvw_a[1], rvw_a[2], rvw_a[0] + 2 * R * n, rvw_b[1], rvw_b[2])
    va, vb = np.array(out["va"]), np.array(out["vb"])
    va[2] = vb[2] = 0.0
    return (va, np.array(out["wa"])), (vb, np.array(out["wb"])), n


@pytest.mark.parametrize("n", [2, 3])
def test_each_pair_of_a_struck_row_collides_once(n):
    shot = pt.simulate(row(n), engine=plug_in_engine(), t_final=T_ONE_CONTACT_EACH, max_events=20)
    # (pooltool stops at the first event past t_final)
    events = [ev for ev in ball_ball_events(shot) if ev.time <= T_ONE_CONTACT_EACH]
    assert [ev.ids for ev in events] == [(str(k), str(k + 1)) for k in range(n - 1)]
    times = [ev.time for ev in events]
    assert all(t1 > t0 for t0, t1 in zip(times, times[1:]))
    # The first contact: the gap closed at 8 m/s (the cloth slows the ball by 2.5e-7 m/s
    # in that time).
    assert times[0] == pytest.approx(GAP / SPEED, rel=1e-6)
    for ev in events:
        (a_in, b_in), (a_out, b_out) = (
            [x.initial.state.rvw for x in ev.agents],
            [x.final.state.rvw for x in ev.agents],
        )
        (va, wa), (vb, wb), normal = direct(a_in, b_in)
        scale = np.abs(a_in[1]).max()
        # The plug-in's answer is the law's, called directly.
        np.testing.assert_allclose(a_out[1], va, rtol=0, atol=1e-12 * scale)
        np.testing.assert_allclose(b_out[1], vb, rtol=0, atol=1e-12 * scale)
        np.testing.assert_allclose(R * a_out[2], R * wa, rtol=0, atol=1e-12 * scale)
        np.testing.assert_allclose(R * b_out[2], R * wb, rtol=0, atol=1e-12 * scale)
        # Momentum, and the balls separating along their line of centres.
        p_in = M * (a_in[1] + b_in[1])
        p_out = M * (a_out[1] + b_out[1])
        assert np.abs(p_out - p_in).max() <= 1e-12 * np.abs(p_in).max()
        assert (b_out[1] - a_out[1]) @ normal > 0.0
    # The first collision in closed form: head-on, equal masses, no slip at the contact.
    first = events[0]
    v_in = first.agents[0].initial.state.rvw[1][1]
    v1, v2 = (x.final.state.rvw[1][1] for x in first.agents)
    assert v1 == pytest.approx((1 - E_B) / 2 * v_in, rel=1e-12)
    assert v2 == pytest.approx((1 + E_B) / 2 * v_in, rel=1e-12)


@pytest.mark.parametrize("n", [2, 3])
def test_a_struck_row_runs_to_its_final_time(n):
    """The whole run of the report (0.002 s, 20 events at most): no ball-ball event repeats
    at the same time, the run ends on its final time rather than on max_events (which stops
    every ball), and the last ball leaves with most of the struck ball's speed."""
    max_events = 20
    shot = pt.simulate(row(n), engine=plug_in_engine(), t_final=0.002, max_events=max_events)
    keys = [(ev.ids, ev.time) for ev in ball_ball_events(shot)]
    assert len(keys) == len(set(keys))
    assert len(shot.events) < max_events
    assert shot.t >= 0.002  # pooltool stops at the first event past t_final
    # e^(n-1)-ish of 8 m/s, less the cloth's friction over 2 ms (about 2 m/s^2 * 2e-3 s):
    # the velocities were not zeroed.
    assert shot.balls[str(n - 1)].state.rvw[1][1] > 7.0


@pytest.mark.skipif(not COLLISION_TIME_CORRECTED, reason="pooltool needs no correction")
def test_pooltools_own_collision_time_repeats_the_event(monkeypatch):
    """The defect the correction removes: with pooltool 0.6.0's own collision time, the two
    balls leaving the first collision (both sliding along +y, the same acceleration) get a
    collision time of 0, and the event repeats until max_events, which stops the balls."""
    monkeypatch.setattr(
        pt_solve, "ball_ball_collision_time", pt_solve.ball_ball_collision_time.original
    )
    shot = pt.simulate(row(2), engine=plug_in_engine(), t_final=0.002, max_events=20)
    events = ball_ball_events(shot)
    assert len(events) > 10 and len({ev.time for ev in events}) == 1
    assert np.all(shot.balls["1"].state.rvw[1] == 0.0)


def rolling_pair(y0, v0, y1, v1):
    params = pt.BallParams(m=M, R=R)
    balls = {}
    for k, (y, v) in enumerate([(y0, v0), (y1, v1)]):
        b = pt.Ball(id=str(k), params=params)
        b.state.rvw[0] = [0.5, y, R]
        b.state.rvw[1] = [0.0, v, 0.0]
        b.state.rvw[2] = [-v / R, 0.0, 0.0]  # rolling: the contact with the cloth at rest
        b.state.s = const.rolling
        balls[b.id] = b
    return pt.System(cue=pt.Cue(cue_ball_id="0"), table=pt.Table.default(), balls=balls)


@pytest.mark.skipif(not COLLISION_TIME_CORRECTED, reason="pooltool needs no correction")
def test_balls_rolling_along_one_line_meet_when_their_gap_closes():
    """Two balls rolling along one line have the same deceleration (the same rolling
    resistance), so their gap closes at the constant relative speed: 0.2 m between the
    centres at 2 and 0.5 m/s meet after (0.2 - 2R) / 1.5 s. pooltool's default model, with
    the correction in place (pooltool 0.6.0 alone puts this event at t = 0)."""
    shot = pt.simulate(rolling_pair(1.0, 2.0, 1.2, 0.5), t_final=0.5, max_events=20)
    events = ball_ball_events(shot)
    assert len(events) == 1
    assert events[0].time == pytest.approx((0.2 - 2 * R) / 1.5, rel=1e-9)
    # Rolling apart along one line: no contact at all.
    shot = pt.simulate(rolling_pair(1.0, 0.5, 1.2, 2.0), t_final=0.5, max_events=20)
    assert ball_ball_events(shot) == []
