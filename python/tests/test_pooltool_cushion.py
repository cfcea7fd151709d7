"""The ball-cushion model for pooltool (BilliardContactCushion) in real pooltool 0.6
simulations: shots into the rails, with what each impact must conserve."""

from __future__ import annotations

import copy
import math
import pickle

import numpy as np
import pytest

from conftest import pooltool_or_skip

pt = pooltool_or_skip()

import billiard_contact as bc  # noqa: E402
from billiard_contact.pooltool import BilliardContact, BilliardContactCushion, install  # noqa: E402


def engine_with(model: BilliardContactCushion):
    engine = pt.physics.PhysicsEngine()
    engine.resolver.ball_linear_cushion = model
    return engine


def rail_shot(engine, V0=2.0, phi=60.0, a=0.2, b=0.1):
    """The cue ball alone, from the table's centre, struck at the angle phi (degrees)."""
    table = pt.Table.default()
    ball = pt.Ball.create("cue", xy=(table.w / 2, table.l / 2))
    system = pt.System(cue=pt.Cue(cue_ball_id="cue"), table=table, balls={"cue": ball})
    system.strike(V0=V0, phi=phi, a=a, b=b)
    pt.simulate(system, engine=engine, inplace=True)
    return system


def cushion_events(system):
    return [e for e in system.events if e.event_type == pt.EventType.BALL_LINEAR_CUSHION]


def frame_of(event, system):
    """The impact's frame: y the cushion's normal towards the cushion, x = y x z."""
    ball = event.agents[0].initial
    seg = system.table.cushion_segments.linear[event.agents[1].id]
    n = np.asarray(seg.get_normal_xy(ball.xyz), dtype=float)
    v = ball.state.rvw[1]
    if n[0] * v[0] + n[1] * v[1] < 0:
        n = -n
    y = np.array([n[0], n[1], 0.0]) / math.hypot(n[0], n[1])
    return np.cross(y, [0.0, 0.0, 1.0]), y


def test_a_perfect_frictionless_rail_reflects_and_conserves_energy():
    """e = 1, no friction on the cushion or the cloth (during the impact): every impact
    keeps the velocity along the rail and the spin, reverses the normal velocity, so the
    kinetic energy is that before."""
    model = BilliardContactCushion(restitution=1.0, mu_cushion=0.0, mu_table=0.0)
    system = rail_shot(engine_with(model))
    events = cushion_events(system)
    assert len(events) >= 3
    for e in events:
        before, after = e.agents[0].initial.state.rvw, e.agents[0].final.state.rvw
        x, y = frame_of(e, system)
        assert np.dot(before[1], y) > 0
        np.testing.assert_allclose(np.dot(after[1], x), np.dot(before[1], x), atol=1e-12)
        np.testing.assert_allclose(np.dot(after[1], y), -np.dot(before[1], y), rtol=1e-9)
        np.testing.assert_allclose(after[2], before[2], atol=1e-9)
        assert after[1][2] == 0.0
        # pooltool's make_kiss moves the ball to 1e-6 m from the cushion, solve does not
        assert np.linalg.norm(after[0] - before[0]) < 1e-5


def test_a_shot_into_the_rails_loses_energy_at_every_impact():
    """pooltool's ball parameters (e_c = 0.85, f_c = 0.2, u_s = 0.2): each impact leaves the
    cushion with less kinetic energy (translation and spin, I = 2/5 m R^2) than it came
    with; the ball leaves the cushion (normal velocity away from it); the motion stays on
    the table (v_z = 0) and the simulation ends with the ball at rest."""
    engine = pt.physics.PhysicsEngine()
    install(engine, cushion=True)
    assert isinstance(engine.resolver.ball_linear_cushion, BilliardContactCushion)
    system = rail_shot(engine, V0=4.0, phi=35.0, a=-0.3, b=0.3)
    events = cushion_events(system)
    assert len(events) >= 2
    p = system.balls["cue"].params

    def energy(rvw):
        return 0.5 * p.m * np.dot(rvw[1], rvw[1]) + 0.2 * p.m * p.R**2 * np.dot(rvw[2], rvw[2])

    for e in events:
        before, after = e.agents[0].initial.state.rvw, e.agents[0].final.state.rvw
        _, y = frame_of(e, system)
        assert np.dot(after[1], y) < 0 < np.dot(before[1], y)
        assert energy(after) < energy(before)
        assert after[1][2] == 0.0
        # the library's own answer for this impact, in its frame
        x, _ = frame_of(e, system)
        lib = bc.BallCushion(mass=p.m, radius=p.R, height=system.table.cushion_segments.linear[
            e.agents[1].id].height, mu_cushion=p.f_c, mu_table=p.u_s, restitution=p.e_c)
        z = np.array([0.0, 0.0, 1.0])
        out = lib.resolve([np.dot(before[1], x), np.dot(before[1], y), 0.0],
                          [np.dot(before[2], x), np.dot(before[2], y), before[2][2]])
        np.testing.assert_allclose(after[1], out["v"][0] * x + out["v"][1] * y, atol=1e-12)
        np.testing.assert_allclose(after[2], out["w"][0] * x + out["w"][1] * y + out["w"][2] * z,
                                   atol=1e-9)
    final = system.balls["cue"].state
    assert final.s == pt.constants.stationary


def test_install_puts_the_cushion_model_and_keeps_the_previous_as_fallback():
    engine = pt.physics.PhysicsEngine()
    previous = engine.resolver.ball_linear_cushion
    circular = engine.resolver.ball_circular_cushion
    install(engine, cushion=True, cushion_options=dict(rule="newton"))
    model = engine.resolver.ball_linear_cushion
    assert isinstance(model, BilliardContactCushion) and model.rule == "newton"
    assert model.fallback is previous and engine.resolver.ball_circular_cushion is circular
    install(engine, cushion=True)  # again: the fallback stays pooltool's
    assert engine.resolver.ball_linear_cushion.fallback is previous
    other = pt.physics.PhysicsEngine()
    install(other, cushion=False)
    assert not isinstance(other.resolver.ball_linear_cushion, BilliardContactCushion)
    assert isinstance(other.resolver.ball_ball, BilliardContact)


def test_a_cushion_the_library_does_not_model_goes_to_the_fallback():
    """A cushion lower than the ball's centre (h < R): the fallback's answer, or an error
    without one."""
    engine = pt.physics.PhysicsEngine()
    previous = engine.resolver.ball_linear_cushion
    low = BilliardContactCushion(height=0.02, fallback=previous)
    system = rail_shot(engine_with(low))
    reference = rail_shot(engine_with(previous))
    assert [e.time for e in cushion_events(system)] == [e.time for e in cushion_events(reference)]
    with pytest.raises(ValueError, match="not an impact the library models"):
        rail_shot(engine_with(BilliardContactCushion(height=0.02)))


def test_the_model_pickles_and_copies():
    model = BilliardContactCushion(restitution=0.9, fallback=pt.physics.PhysicsEngine().resolver.ball_linear_cushion)
    system = rail_shot(engine_with(model))
    for again in (pickle.loads(pickle.dumps(model)), copy.deepcopy(model)):
        assert again == model
        other = rail_shot(engine_with(again))
        assert [e.time for e in other.events] == [e.time for e in system.events]
