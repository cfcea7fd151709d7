"""install(engine, cluster=True): a ball-ball event whose balls touch others is resolved for
the whole cluster by the library's Cluster, through pooltool's own resolver and events.
Expected values come from conservation (momentum; no energy gained), from the library's
Cluster called directly on the same state (the plug-in must pass it through unchanged), and
from the pair model where no other ball touches."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import pooltool_or_skip

pt = pooltool_or_skip()

import pooltool.constants as const  # noqa: E402
from pooltool.events import ball_ball_collision  # noqa: E402

import billiard_contact as bc  # noqa: E402
from billiard_contact.pooltool import CLUSTER_TOUCH_GAP, ClusterResolver, install  # noqa: E402


def system(xs, speed=2.0):
    """Balls on a line along x at the given centres (y = 0.5 m on the table), the first
    moving at `speed` along +x, the others at rest."""
    balls = {}
    for k, x in enumerate(xs):
        b = pt.Ball.create(f"b{k}", xy=(x, 0.5))
        if k == 0:
            b.state.rvw[1] = [speed, 0.0, 0.0]
            b.state.s = const.sliding
        balls[b.id] = b
    return pt.System(cue=pt.Cue(cue_ball_id="b0"), table=pt.Table.default(), balls=balls)


def engine(**kw):
    e = pt.physics.PhysicsEngine()
    install(e, cluster=True, **kw)
    return e


def test_install_keeps_the_strategies_and_adds_the_cluster_resolver():
    e = pt.physics.PhysicsEngine()
    ball_ball = install(e)  # without cluster=True: pooltool's resolver
    assert not isinstance(e.resolver, ClusterResolver)
    install(e, cluster=True, cluster_options=dict(mu=0.05))
    assert isinstance(e.resolver, ClusterResolver)
    assert type(e.resolver.ball_ball) is type(ball_ball)
    assert e.resolver.cluster_options == {"mu": 0.05}


def test_a_frozen_row_is_resolved_at_once_as_the_library_resolves_it():
    R = pt.Ball.create("x").params.R
    # The struck ball touches the third (a gap of 1e-7 m, under CLUSTER_TOUCH_GAP).
    xs = [0.3, 0.3 + 2 * R, 0.3 + 4 * R + 1e-7]
    shot = system(xs)
    before = np.array([shot.balls[k].state.rvw for k in ("b0", "b1", "b2")])
    e = engine()
    e.resolver.resolve(shot, ball_ball_collision(shot.balls["b0"], shot.balls["b1"], 0.0))
    after = np.array([shot.balls[k].state.rvw for k in ("b0", "b1", "b2")])
    p = shot.balls["b0"].params
    direct = bc.Cluster(balls=[bc.Ball(p.m, p.R, 0.4)] * 3, mu=p.u_b, youngs_modulus=5.4e9,
                        poisson_ratio=0.34, damping="hunt-crossley", restitution=p.e_b,
                        at_speed=1.0).resolve(before[:, 0], before[:, 1], before[:, 2])
    v_direct = direct["velocities"].copy()
    v_direct[:, 2] = 0.0  # a 2D engine keeps no vertical velocity
    np.testing.assert_array_equal(after[:, 1], v_direct)
    np.testing.assert_array_equal(after[:, 2], direct["spins"])
    np.testing.assert_array_equal(after[:, 0], before[:, 0])  # positions kept
    # Momentum along x is the cue ball's; no energy gained; most of it reaches the far ball
    # (a Hertz row is nearly Newton's cradle), which pooltool's pair model cannot give in
    # one event.
    assert after[:, 1, 0].sum() == pytest.approx(2.0, rel=1e-9)
    assert np.sum(after[:, 1] ** 2) <= 4.0
    assert after[2, 1, 0] > 0.9 * 2.0
    assert all(shot.balls[k].state.s == const.sliding for k in ("b0", "b1", "b2"))


def test_rtol_in_cluster_options_is_the_resolve_tolerance():
    """cluster_options={"rtol": ...} is not a Cluster keyword: the plug-in passes it to
    Cluster.resolve, so its result is the library's at that tolerance, bit for bit, and
    differs from the default tolerance's (a rolling cue ball: a three-dimensional cluster)."""
    R = pt.Ball.create("x").params.R
    xs = [0.3, 0.3 + 2 * R, 0.3 + 4 * R + 1e-7]
    results = {}
    for rtol in (None, 1e-10):
        shot = system(xs)
        shot.balls["b0"].state.rvw[2] = [0.0, 2.0 / R, 0.0]  # rolling along +x
        before = np.array([shot.balls[k].state.rvw for k in ("b0", "b1", "b2")])
        e = engine(cluster_options={} if rtol is None else {"rtol": rtol})
        e.resolver.resolve(shot, ball_ball_collision(shot.balls["b0"], shot.balls["b1"], 0.0))
        after = np.array([shot.balls[k].state.rvw for k in ("b0", "b1", "b2")])
        p = shot.balls["b0"].params
        direct = bc.Cluster(balls=[bc.Ball(p.m, p.R, 0.4)] * 3, mu=p.u_b,
                            youngs_modulus=5.4e9, poisson_ratio=0.34,
                            damping="hunt-crossley", restitution=p.e_b,
                            at_speed=1.0).resolve(before[:, 0], before[:, 1], before[:, 2],
                                                  rtol=rtol)
        np.testing.assert_array_equal(after[:, 2], direct["spins"])
        results[rtol] = after
    assert not np.array_equal(results[None][:, 2], results[1e-10][:, 2])


def test_a_pair_touching_no_other_ball_goes_to_the_pair_model():
    R = pt.Ball.create("x").params.R
    far = 0.3 + 4 * R + 10 * CLUSTER_TOUCH_GAP
    shots = [system([0.3, 0.3 + 2 * R + 1e-6, far]) for _ in range(2)]
    clustered, plain = engine(), pt.physics.PhysicsEngine()
    install(plain)
    for shot, e in zip(shots, (clustered, plain)):
        e.resolver.resolve(shot, ball_ball_collision(shot.balls["b0"], shot.balls["b1"], 0.0))
    for k in ("b0", "b1", "b2"):
        np.testing.assert_array_equal(shots[0].balls[k].state.rvw, shots[1].balls[k].state.rvw)
    assert shots[0].balls["b2"].state.rvw[1].tolist() == [0.0, 0.0, 0.0]


def test_a_pocketed_ball_is_not_part_of_the_cluster():
    R = pt.Ball.create("x").params.R
    shot = system([0.3, 0.3 + 2 * R, 0.3 + 4 * R])
    shot.balls["b2"].state.s = const.pocketed
    e = engine()
    e.resolver.resolve(shot, ball_ball_collision(shot.balls["b0"], shot.balls["b1"], 0.0))
    assert shot.balls["b2"].state.rvw[1].tolist() == [0.0, 0.0, 0.0]


def test_the_cloth_passes_through_cluster_options():
    """cluster_options={"cloth": ...}: the balls rest on pooltool's table (centres at z = R),
    and the plug-in's result is the library's Cluster with that cloth on the same state;
    along x only the cloth's friction acts from outside, so the x momentum falls by at most
    mu_c times the cloth's normal impulses."""
    R = pt.Ball.create("x").params.R
    xs = [0.3, 0.3 + 2 * R, 0.3 + 4 * R + 1e-7]
    shot = system(xs)
    before = np.array([shot.balls[k].state.rvw for k in ("b0", "b1", "b2")])
    assert np.all(before[:, 0, 2] == R)
    cloth = {"youngs_modulus": 5e10, "poisson_ratio": 0.25, "mu": 0.2}
    e = engine(cluster_options={"cloth": cloth})
    e.resolver.resolve(shot, ball_ball_collision(shot.balls["b0"], shot.balls["b1"], 0.0))
    after = np.array([shot.balls[k].state.rvw for k in ("b0", "b1", "b2")])
    p = shot.balls["b0"].params
    direct = bc.Cluster(balls=[bc.Ball(p.m, p.R, 0.4)] * 3, mu=p.u_b, youngs_modulus=5.4e9,
                        poisson_ratio=0.34, damping="hunt-crossley", restitution=p.e_b,
                        at_speed=1.0, cloth=cloth).resolve(before[:, 0], before[:, 1],
                                                           before[:, 2])
    v_direct = direct["velocities"].copy()
    v_direct[:, 2] = 0.0
    np.testing.assert_array_equal(after[:, 1], v_direct)
    np.testing.assert_array_equal(after[:, 2], direct["spins"])
    lost = 2.0 - after[:, 1, 0].sum()
    cap = 0.2 * sum(c["impulse"] for c in direct["cloth_contacts"]) / p.m
    assert 0.0 < lost <= cap * (1 + 1e-9)
