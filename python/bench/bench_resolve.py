"""Times BallBall.resolve_lab and pooltool's frictional_inelastic kernel in one run.

    python python/bench/bench_resolve.py [--rows 100000] [--repeats 7]

Prints each measured value with its target and whether it is met:
- resolve_lab on --rows lab states (closed form, all cores), ns per collision (target <= 80);
- the same with the outputs checked finite as before, in one pass over all rows after they
  are written, against the default check, once per chunk of 1024 rows while they are in
  cache (timed alternately, so both see the same machine);
- resolve_lab on single (3,) arrays, us per call (target <= 1.5);
- pooltool's frictional_inelastic numba kernel (_resolve_ball_ball) on the same states, one
  call per collision as pooltool makes it, us per collision;
- the ratio kernel / resolve_lab per collision (goal >= 40).
Best and median of --repeats timed runs after a warm-up (this machine is shared: the
load average is printed; read the best as the machine's speed, the median as typical).
Not a test: nothing fails when a target is missed.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np

import billiard_contact as bc

M, R, MU = 0.170097, 0.028575, 0.06


def states(n: int, seed: int = 1):
    """Touching balls on the table (z up), approaching, random horizontal velocities and
    3D spins: the states pooltool hands its ball-ball model."""
    rng = np.random.default_rng(seed)
    phi = rng.uniform(-np.pi, np.pi, n)
    d = np.stack([np.cos(phi), np.sin(phi), np.zeros(n)], 1)
    pa = np.column_stack([rng.uniform(0.1, 1.0, n), rng.uniform(0.1, 2.0, n), np.full(n, R)])
    pb = pa + 2 * R * d
    va = np.column_stack([rng.normal(size=(n, 2)), np.zeros(n)])
    vb = np.column_stack([0.2 * rng.normal(size=(n, 2)), np.zeros(n)])
    approach = np.einsum("ij,ij->i", va - vb, d)
    va[approach < 0] -= 2 * approach[approach < 0, None] * d[approach < 0]
    wa = rng.normal(size=(n, 3)) * 30
    wb = rng.normal(size=(n, 3)) * 5
    return pa, va, wa, pb, vb, wb


CPU: dict[str, float] = {}


def timed(fn, repeats: int, name: str = "") -> tuple[float, float]:
    """Best and median wall time of `fn`; the best CPU time (all threads) goes to CPU[name]."""
    fn()  # warm-up (JIT, caches, thread pool)
    t, cpu = [], []
    for _ in range(repeats):
        start, start_cpu = time.perf_counter(), time.process_time()
        fn()
        t.append(time.perf_counter() - start)
        cpu.append(time.process_time() - start_cpu)
    CPU[name] = min(cpu)
    return min(t), statistics.median(t)


def line(what: str, best: float, median: float, unit: str, target: float | None) -> None:
    verdict = "" if target is None else ("  target <= %g %s: %s" % (target, unit, "met" if best <= target else "NOT met"))
    print(f"{what:<58} best {best:9.3f} {unit}  median {median:9.3f} {unit}{verdict}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rows", type=int, default=100_000)
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--single-calls", type=int, default=20_000)
    ap.add_argument("--kernel-calls", type=int, default=20_000)
    args = ap.parse_args()

    print(f"billiard_contact {bc.__version__}, numpy {np.__version__}, {os.cpu_count()} CPUs, "
          f"load average {os.getloadavg()[0]:.2f}")
    model = bc.BallBall(mass=M, radius=R, alpha=0.4, mu=MU, restitution=1.0)
    pa, va, wa, pb, vb, wb = states(args.rows)

    best, med = timed(lambda: model.resolve_lab(pa, va, wa, pb, vb, wb), args.repeats, "array")
    array_ns = best / args.rows * 1e9
    line(f"resolve_lab, {args.rows} states, per collision", array_ns, med / args.rows * 1e9, "ns", 80)

    # The finite check of the outputs: per chunk (default) against one pass after all rows
    # (before), alternating repeats so that both see the same load.
    check = bc._core._check_outputs_per_chunk
    run = lambda: model.resolve_lab(pa, va, wa, pb, vb, wb)
    times = {True: [], False: []}
    cpus = {True: [], False: []}
    for per_chunk in (True, False):
        check(per_chunk)
        run()  # warm-up
    for _ in range(args.repeats):
        for per_chunk in (False, True):
            check(per_chunk)
            start, start_cpu = time.perf_counter(), time.process_time()
            run()
            times[per_chunk].append(time.perf_counter() - start)
            cpus[per_chunk].append(time.process_time() - start_cpu)
    check(True)
    for per_chunk, what in ((False, "before: one pass after all rows"), (True, "after: once per 1024-row chunk")):
        t = times[per_chunk]
        line(f"resolve_lab, finite check {what}", min(t) / args.rows * 1e9,
             statistics.median(t) / args.rows * 1e9, "ns", None)
        print(f"{'  its CPU time (all threads), best and median':<58} {min(cpus[per_chunk]) / args.rows * 1e9:9.1f} ns"
              f"  {statistics.median(cpus[per_chunk]) / args.rows * 1e9:9.1f} ns")

    one = [np.ascontiguousarray(x[0]) for x in (pa, va, wa, pb, vb, wb)]
    f = model.resolve_lab
    k = args.single_calls

    def singles():
        for _ in range(k):
            f(*one)

    best, med = timed(singles, args.repeats)
    line("resolve_lab, one collision on (3,) arrays, per call", best / k * 1e6, med / k * 1e6, "us", 1.5)

    try:
        from pooltool.physics.resolve.ball_ball.frictional_inelastic import _resolve_ball_ball
    except ImportError:
        print("pooltool is not installed: no kernel timing, no ratio "
              "(pip install panda3d==1.10.16; pip install --no-deps pooltool-billiards==0.6.0 ...)")
        return
    n = min(args.kernel_calls, args.rows)
    rvw1 = [np.array([pa[i], va[i], wa[i]]) for i in range(n)]
    rvw2 = [np.array([pb[i], vb[i], wb[i]]) for i in range(n)]

    def kernel():
        for a, b in zip(rvw1, rvw2):
            _resolve_ball_ball(a.copy(), b.copy(), R, MU, 1.0)

    best, med = timed(kernel, args.repeats, "kernel")
    kernel_us = best / n * 1e6
    line(f"pooltool frictional_inelastic kernel, {n} calls, per call", kernel_us, med / n * 1e6, "us", None)
    ratio = kernel_us * 1e3 / array_ns
    print(f"{'ratio: kernel per collision / resolve_lab per collision':<58} {ratio:9.1f} x"
          f"  goal >= 40 x: {'met' if ratio >= 40 else 'NOT met'}")
    # CPU time (all threads): the work done, less sensitive to other processes' load
    # than wall time; the arrays' CPU time adds up both worker threads.
    array_cpu_ns = CPU["array"] / args.rows * 1e9
    kernel_cpu_us = CPU["kernel"] / n * 1e6
    print(f"{'CPU time: resolve_lab per collision (all threads)':<58} {array_cpu_ns:9.1f} ns")
    print(f"{'CPU time: pooltool kernel per call':<58} {kernel_cpu_us:9.3f} us")
    print(f"{'CPU-time ratio (one core against one core)':<58} {kernel_cpu_us * 1e3 / array_cpu_ns:9.1f} x")


if __name__ == "__main__":
    main()
