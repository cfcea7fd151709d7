"""Many pooltool shots with billiard-contact's ball-ball model, in parallel.

    python python/examples/parallel_shots.py [--shots 20] [--workers 2]

Each shot is a function of its number alone (the rack's jitter and the cue's speed, aim and
spin are drawn from a generator seeded with it), so a shot gives the same events wherever it
runs. The model is built once and sent to the workers: it pickles (the library's models
inside it are rebuilt from their parameters), so every worker resolves collisions with the
same numbers. Three ways to run the same shots, whose results are equal event for event:

- ``serial``: one after the other, in this process;
- ``process_pool``: ``concurrent.futures.ProcessPoolExecutor`` (spawned workers);
- ``dask_cluster``: Dask's ``distributed.LocalCluster`` (``pip install dask distributed``),
  one single-threaded worker process per core; a real cluster's scheduler address works
  the same way through ``distributed.Client``.

Running this file times the three and prints the speed-ups over the serial run, with the
workers' start-up inside the timing (cold) and done beforehand (warm): a spawned worker
imports pooltool and loads its compiled kernels, about as long as a few shots take.
"""

from __future__ import annotations

import argparse
import multiprocessing
import os
import random
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from typing import Any, Optional

import numpy as np
import pooltool as pt

from billiard_contact.pooltool import BilliardContact

#: One event: its type, its time, its agents' ids and the final position, velocity and spin
#: of each ball among them (floats, compared exactly).
Event = tuple[str, float, tuple[str, ...], tuple[tuple[float, ...], ...]]


def make_engine() -> Any:
    """A fresh engine of pooltool's default strategies: 0.6's PhysicsEngine, or the
    SimulationEngine of the releases after it."""
    engine_type = getattr(pt.physics, "PhysicsEngine", None)
    if engine_type is None:
        engine_type = pt.evolution.SimulationEngine
    return engine_type()


def shot(i: int, model: Optional[BilliardContact] = None) -> list[Event]:
    """Shot number i on a nine-ball rack, with ``model`` (default ``BilliardContact()``)
    as the ball-ball model: every third a full-speed break, the others slower shots at the
    1 ball with cut, follow or draw and side spin. Returns its events."""
    rng = np.random.default_rng(i)
    engine = make_engine()
    engine.resolver.ball_ball = model if model is not None else BilliardContact()
    table = pt.Table.default()
    random.seed(i)  # pooltool jitters the rack with both generators
    np.random.seed(i)
    balls = _numbered_by_position(pt.get_rack(pt.GameType.NINEBALL, table))
    system = pt.System(cue=pt.Cue(cue_ball_id="cue"), table=table, balls=balls)
    if i % 3 == 0:
        speed, cut = 8.0, rng.uniform(-2, 2)
    else:
        speed, cut = rng.uniform(1.0, 5.0), rng.uniform(-40, 40)
    system.strike(
        V0=speed,
        phi=pt.aim.at_ball(system, "1", cut=cut),
        a=rng.uniform(-0.3, 0.3),
        b=rng.uniform(-0.4, 0.4),
    )
    pt.simulate(system, engine=engine, inplace=True)
    return [_event(e) for e in system.events]


def _numbered_by_position(rack: dict[str, Any]) -> dict[str, Any]:
    """The rack's object balls numbered 1, 2, ... by position (y, then x): the apex ball is
    "1". pooltool draws the numbers from a set of strings, whose order changes from one
    process to the next (Python's string hashing is seeded per process), so its numbering
    would differ between workers even with the same seeds; the positions do not."""
    import attrs

    objects = sorted(
        (b for k, b in rack.items() if k != "cue"),
        key=lambda b: (float(b.state.rvw[0][1]), float(b.state.rvw[0][0])),
    )
    balls = {"cue": rack["cue"]}
    for k, b in enumerate(objects, start=1):
        balls[str(k)] = attrs.evolve(b, id=str(k))
    return balls


def _event(e: Any) -> Event:
    ids = tuple(a.id for a in e.agents)
    finals = tuple(
        tuple(float(x) for x in a.final.state.rvw.ravel())
        for a in e.agents
        if a.final is not None and hasattr(a.final, "params") and hasattr(a.final, "state")
    )
    return (str(e.event_type), float(e.time), ids, finals)


def serial(n: int, model: BilliardContact) -> list[list[Event]]:
    return [shot(i, model) for i in range(n)]


def process_pool(
    n: int, model: BilliardContact, workers: int = 2, pool: Optional[ProcessPoolExecutor] = None
) -> list[list[Event]]:
    """The shots in a pool of ``workers`` processes (started with "spawn": fresh
    interpreters, as on macOS and Windows, with no threads copied from this one), or in
    ``pool`` when given (workers already started)."""
    if pool is not None:
        return list(pool.map(shot, range(n), [model] * n))
    with ProcessPoolExecutor(max_workers=workers, mp_context=_spawn()) as pool:
        return list(pool.map(shot, range(n), [model] * n))


def _spawn() -> Any:
    return multiprocessing.get_context("spawn")


def dask_cluster(
    n: int, model: BilliardContact, workers: int = 2, client: Any = None
) -> list[list[Event]]:
    """The shots on Dask's local cluster, ``workers`` worker processes of one thread, or on
    the cluster of ``client`` when given (a ``distributed.Client``)."""
    if client is not None:
        return _on_dask(client, n, model)
    from distributed import Client, LocalCluster

    with LocalCluster(
        n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, Client(cluster) as client:
        return _on_dask(client, n, model)


def _on_dask(client: Any, n: int, model: BilliardContact) -> list[list[Event]]:
    import cloudpickle

    # This module may not be importable in the workers (a script, or a folder not on
    # their path): send its functions by value.
    cloudpickle.register_pickle_by_value(sys.modules[__name__])
    model_future = scatter_model(client, model)
    futures = client.map(shot, range(n), model=model_future, pure=False)
    return client.gather(futures)


def scatter_model(client: Any, model: BilliardContact) -> Any:
    """The model on every worker of ``client``'s cluster, under a key of its own.

    ``client.scatter`` names data by a hash of its pickle by default, so the same model
    scattered twice gets the same key: when the first future is released (its run is over)
    just before the second scatter, the scheduler's release of that key can reach the
    workers after the new data, which is then deleted, and the next shots fail with
    "lost dependencies". ``hash=False`` gives every scatter a fresh key; the model is small
    (its parameters, and the library's models rebuilt from them)."""
    return client.scatter(model, broadcast=True, hash=False)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shots", type=int, default=20)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    n, w = args.shots, args.workers
    model = BilliardContact()
    shot(0, model)  # pooltool's numba kernels compiled (or loaded) here first
    timings = []

    def timed(name: str, run: Any) -> None:
        start = time.perf_counter()
        result = run()
        timings.append((name, time.perf_counter() - start, result))

    timed("serial", lambda: serial(n, model))
    # Cold: the workers start (a fresh interpreter imports pooltool and loads its numba
    # kernels) inside the timing. Warm: started, and one shot each done, beforehand.
    timed("process pool, cold", lambda: process_pool(n, model, w))
    with ProcessPoolExecutor(max_workers=w, mp_context=_spawn()) as pool:
        list(pool.map(shot, range(w), [model] * w))
        timed("process pool, warm", lambda: process_pool(n, model, pool=pool))
    from distributed import Client, LocalCluster

    timed("dask cluster, cold", lambda: dask_cluster(n, model, w))
    with LocalCluster(
        n_workers=w, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, Client(cluster) as client:
        _on_dask(client, w, model)
        timed("dask cluster, warm", lambda: dask_cluster(n, model, client=client))
    serial_s, serial_result = timings[0][1], timings[0][2]
    events = sum(len(s) for s in serial_result)
    print(f"{n} shots, {events} events, {w} workers, load average {os.getloadavg()[0]:.1f}")
    for name, t, result in timings:
        same = "the same events" if result == serial_result else "DIFFERENT EVENTS"
        print(f"{name:>20}: {t:6.2f} s, speed-up {serial_s / t:4.2f}x, {same}")


if __name__ == "__main__":
    main()
