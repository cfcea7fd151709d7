"""Twenty pooltool shots with the model, run one after the other, in a process pool and on
Dask's local cluster (python/examples/parallel_shots.py): the same events, exactly."""

from __future__ import annotations

import sys

import pytest

from conftest import REPO, pooltool_or_skip, required_or_skip

pt = pooltool_or_skip()

sys.path.insert(0, str(REPO / "python" / "examples"))
import parallel_shots as shots  # noqa: E402

from billiard_contact.pooltool import BilliardContact  # noqa: E402

N = 20


@pytest.fixture(scope="module")
def serial_run():
    model = BilliardContact()
    return model, shots.serial(N, model)


def test_the_shots_collide_and_differ(serial_run):
    model, serial = serial_run
    assert len(serial) == N
    for events in serial:
        kinds = [e[0] for e in events]
        assert kinds.count(str(pt.EventType.BALL_BALL)) >= 1, kinds
        times = [e[1] for e in events]
        assert times == sorted(times)
    assert len({repr(s) for s in serial}) == N  # twenty different shots
    # The comparison sees the model: other friction gives other events.
    assert shots.shot(1, BilliardContact(mu=0.02)) != serial[1]


def test_process_pool_equals_the_serial_run(serial_run):
    model, serial = serial_run
    assert shots.process_pool(N, model, workers=2) == serial


def test_dask_local_cluster_equals_the_serial_run(serial_run):
    required_or_skip("distributed")
    model, serial = serial_run
    assert shots.dask_cluster(N, model, workers=2) == serial


def test_dask_runs_two_models_and_one_scattered_twice(serial_run):
    """On one cluster, one after the other: the same model again and again, and another
    model in between, each equal to its serial run. Scattered under a hash of its pickle,
    the same model got the same key each time, and a run just after the previous one's
    release lost its model at times ("lost dependencies"); every scatter has a key of its
    own now."""
    required_or_skip("distributed")
    from distributed import Client, LocalCluster

    model, serial = serial_run
    other = BilliardContact(mu=0.02, restitution=0.9)
    k = 4
    other_serial = shots.serial(k, other)
    assert other_serial != serial[:k]
    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, Client(cluster) as client:
        first, second = shots.scatter_model(client, model), shots.scatter_model(client, model)
        assert first.key != second.key
        assert shots.scatter_model(client, other).key not in (first.key, second.key)
        del first, second
        for m, expected in [(model, serial[:k]), (model, serial[:k]), (other, other_serial),
                            (model, serial[:k]), (other, other_serial)]:
            assert shots.dask_cluster(k, m, client=client) == expected
