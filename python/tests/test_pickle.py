"""Every public class pickles, copies and deep-copies; the copy gives bit-identical
results, in this process and in worker processes (concurrent.futures)."""

from __future__ import annotations

import copy
import pickle
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import billiard_contact as bc

M, R = 0.170097, 0.028575
FRICTION = bc.SpeedDependentFriction(a=9.951e-3, b=0.108, c=1.088, evaluate="initial")

MODELS = [
    bc.BallBall(mass=M, radius=R, mu=0.06, restitution=0.93),
    bc.BallBall(mass=M, radius=R, alpha=0.38, mu=FRICTION, restitution=1.0,
                profile="hertz", duration=2e-4, friction=True, stick=False),
    bc.BallBall(a=bc.Ball(M, R), b=bc.Ball(0.16, 0.0286, 0.39), mu=0.05, restitution=0.9),
    bc.BallBall(mass=M, radius=R, mu=0.06, friction=False),
    bc.BallBall(a=bc.Ball(M, R), b=bc.Ball(0.16, 0.0286, 0.39), mu=0.06, tangential="mindlin",
                youngs_modulus=5.4e9, poisson_ratio=0.34, shear_stiffness_factor=2.0),
]
COPIES = [
    lambda x: pickle.loads(pickle.dumps(x)),
    lambda x: pickle.loads(pickle.dumps(x, protocol=2)),
    copy.copy,
    copy.deepcopy,
]


def shots(model, n, seed):
    """n touching pairs with random velocities and spins."""
    rng = np.random.default_rng(seed)
    d = rng.normal(size=(n, 3))
    d[:, 2] *= 0.1
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    pa = rng.uniform(-1, 1, size=(n, 3))
    pb = pa + (model.a.radius + model.b.radius) * d
    va = -d * rng.uniform(0.1, 5, size=(n, 1)) + rng.normal(size=(n, 3))
    return pa, va, rng.normal(size=(n, 3)) * 50, pb, rng.normal(size=(n, 3)) * 0.2, \
        rng.normal(size=(n, 3)) * 50


def assert_same(x, y):
    assert x.keys() == y.keys()
    for k in x:
        a, b = np.asarray(x[k]), np.asarray(y[k])
        assert a.dtype == b.dtype and a.shape == b.shape
        # NaN throw angles compare equal to NaN at the same places; everything else ==.
        assert np.array_equal(a, b, equal_nan=a.dtype.kind == "f"), k


@pytest.mark.parametrize("copier", COPIES)
def test_small_classes_round_trip(copier):
    ball = bc.Ball(0.16, 0.0286, 0.39)
    assert copier(ball) == ball and repr(copier(ball)) == repr(ball)
    assert copier(FRICTION) == FRICTION and repr(copier(FRICTION)) == repr(FRICTION)
    assert copier(FRICTION).mu(0.3) == FRICTION.mu(0.3)


@pytest.mark.parametrize("copier", COPIES)
@pytest.mark.parametrize("k", range(len(MODELS)))
def test_models_round_trip_bit_identical(copier, k):
    model = MODELS[k]
    again = copier(model)
    assert type(again) is bc.BallBall and repr(again) == repr(model)
    pa, va, wa, pb, vb, wb = shots(model, 300, k)
    assert_same(again.resolve_lab(pa, va, wa, pb, vb, wb), model.resolve_lab(pa, va, wa, pb, vb, wb))
    one = (pa[0], va[0], wa[0], pb[0], vb[0], wb[0])
    assert_same(again.resolve_lab(*one), model.resolve_lab(*one))
    # The compliant pair steps with its own method (rtol= its tolerance).
    stepping = {"rtol": 1e-9} if model.tangential == "mindlin" else {"method": "dop853"}
    assert_same(again.resolve_lab(*one, **stepping), model.resolve_lab(*one, **stepping))


def _resolve(job):
    model, arrays = job
    return model.resolve_lab(*arrays)


def test_process_pool_equals_in_process():
    model = MODELS[1]
    jobs = [(model, shots(model, 50, seed)) for seed in range(4)]
    with ProcessPoolExecutor(max_workers=2) as pool:
        remote = list(pool.map(_resolve, jobs))
    for job, r in zip(jobs, remote):
        assert_same(r, _resolve(job))


def test_dask_if_installed():
    dask = pytest.importorskip("dask")
    model = MODELS[0]
    arrays = shots(model, 40, 7)
    got = dask.delayed(_resolve)((model, arrays)).compute(scheduler="processes")
    assert_same(got, _resolve((model, arrays)))
