"""Times BallCushion.resolve against pooltool's mathavan_2010 solve, at equal accuracy, in
one run.

    python python/bench/bench_cushion.py [--impacts 2000] [--repeats 7] [--figure DIR]

Both integrate the same equations (Mathavan, Jackson and Parkin 2010: a ball on the cloth
against a cushion, friction at both contacts, Stronge's energetic restitution) in the
cushion's normal impulse: pooltool's ``solve`` (numba) with fixed steps of delta_p (its
``Mathavan2010Linear`` defaults: max_steps=1000, delta_p=0.001), the library with an
adaptive dop853 (or dopri5) and event location at every change of slip.

Accuracy: each against its own converged answer (the library at rtol 1e-12; pooltool with
delta_p 1e-7 and 2e5 steps on a subset), as the largest error of the outgoing state over
the impacts, |v' - v'_ref| + R |w' - w'_ref| over |v| + R |w|. For pooltool at its defaults
and at ten and a hundred times finer steps, the library's setting (dop853 or dopri5, rtol 1e-2 to 1e-10)
is the fastest of those whose error is at most pooltool's (a setting at which the library fails on
an impact is reported and skipped); both are timed at those settings, per impact: pooltool
one call per impact as its engine makes them, the library on (N, 3) arrays (all cores,
without the GIL) and one call per impact on (3,) arrays; the library at its default rtol
1e-10 too. The two converged answers are compared first (the same physics: they should
agree to pooltool's accuracy or better).

With ``--figure DIR`` it also writes the work-precision diagram of both, DIR/work_precision.csv,
.png and .svg (matplotlib): time per impact against the largest error, pooltool at 100, 1000,
10 000 and 100 000 steps (delta_p 1e-2 to 1e-5), the library with dopri5 and dop853 at rtol
1e-2 to 1e-10, one impact a call and on arrays.

Not a test: nothing fails when the target (ratio >= 100) is missed.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import time

import numpy as np

import billiard_contact as bc

M, R, H = 0.170097, 0.028575, 0.64 * 2 * 0.028575  # pooltool's ball and cushion height
E, MU_CUSHION, MU_TABLE = 0.85, 0.2, 0.2  # pooltool's e_c, f_c, u_s


def impacts(n: int, seed: int = 3):
    """Balls on the cloth meeting the cushion (y into it) at 0.5-3 m/s, 5-85 degrees from
    the cushion's line, with top or back spin and side spin up to rolling's."""
    rng = np.random.default_rng(seed)
    speed = rng.uniform(0.5, 3.0, n)
    angle = np.radians(rng.uniform(5, 85, n))
    v = np.column_stack([speed * np.cos(angle), speed * np.sin(angle), np.zeros(n)])
    # rolling spin (v = w x r n_up: w = (-v_y, v_x, 0)/R) scaled by -1..1, and side spin
    roll = rng.uniform(-1, 1, (n, 1))
    w = np.column_stack([-v[:, 1], v[:, 0], np.zeros(n)]) / R * roll
    w[:, 2] = rng.uniform(-1, 1, n) * speed / R
    return v, w


def error(v, w, v_ref, w_ref, v_in, w_in):
    scale = np.linalg.norm(v_in, axis=1) + R * np.linalg.norm(w_in, axis=1)
    e = np.linalg.norm(v - v_ref, axis=1) + R * np.linalg.norm(w - w_ref, axis=1)
    return float(np.max(e / scale))


def best_and_median(fn, repeats):
    fn()
    t = []
    for _ in range(repeats):
        s = time.perf_counter()
        fn()
        t.append(time.perf_counter() - s)
    return min(t), statistics.median(t)


RTOLS = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10)

# pooltool's step counts of the work-precision diagram: (max_steps, delta_p).
PT_LADDER = ((100, 1e-2), (1000, 1e-3), (10_000, 1e-4), (100_000, 1e-5))


def figure(args, model, v, w, one, ladder, pooltool, pt_ref, sub, n, k):
    """The work-precision diagram: DIR/work_precision.csv, .png, .svg."""
    import csv

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = []
    for max_steps, delta_p in PT_LADDER:
        pt_out = pooltool(sub, max_steps, delta_p)
        err = error(pt_out[0], pt_out[1], *pt_ref, v[sub], w[sub])
        reps = max(1, min(args.repeats, int(3e5 / max_steps)))
        t, _ = best_and_median(lambda: pooltool(range(k), max_steps, delta_p), reps)
        rows.append(("pooltool mathavan_2010", f"{max_steps} steps", err, t / k * 1e6, "", ""))
    for method, rtol, err, t_arr in ladder:
        f = model.resolve

        def singles():
            for a, b in one:
                f(a, b, method=method, rtol=rtol)

        t_one, _ = best_and_median(singles, args.repeats)
        evals = np.median(model.resolve(v, w, method=method, rtol=rtol)["evaluations"])
        rows.append((f"billiard_contact {method}", f"rtol {rtol:g}", err, t_one / k * 1e6,
                     t_arr / n * 1e6, f"{evals:.0f}"))
    os.makedirs(args.figure, exist_ok=True)
    path = os.path.join(args.figure, "work_precision.csv")
    with open(path, "w", newline="") as fh:
        out = csv.writer(fh)
        out.writerow(["solver", "setting", "largest_error", "us_per_impact_call",
                      "us_per_impact_arrays", "median_evaluations"])
        for r in rows:
            out.writerow([r[0], r[1], f"{r[2]:.3e}", f"{r[3]:.3f}",
                          f"{r[4]:.3f}" if r[4] != "" else "", r[5]])
    print(f"wrote {path}")
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    styles = {"pooltool mathavan_2010": ("k", "s"), "billiard_contact dopri5": ("tab:blue", "o"),
              "billiard_contact dop853": ("tab:red", "^")}
    for solver, (colour, marker) in styles.items():
        sel = [r for r in rows if r[0] == solver]
        ax.loglog([r[2] for r in sel], [r[3] for r in sel], color=colour, marker=marker,
                  label=f"{solver}, one impact a call" if "billiard" in solver
                  else f"{solver} (Euler, 100 to 100 000 steps)")
        if "billiard" in solver:
            ax.loglog([r[2] for r in sel], [r[4] for r in sel], color=colour, marker=marker,
                      linestyle="--", mfc="none",
                      label=f"{solver}, {n} impacts in arrays (both cores)")
        if solver.startswith("pooltool"):
            for r in sel:
                ax.annotate(r[1], (r[2], r[3]), textcoords="offset points", xytext=(6, 4),
                            fontsize=8)
    ax.set_xlabel("largest error of the rebound (|dv| + R |dw|) / (|v| + R |w|)")
    ax.set_ylabel("time per impact (us)")
    ax.set_title("Cushion impact (Mathavan et al. 2010): cost against accuracy, "
                 f"{n} impacts", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(args.figure, f"work_precision.{ext}"), dpi=110)
    print(f"wrote {args.figure}/work_precision.png, .svg")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--impacts", type=int, default=2000)
    ap.add_argument("--reference-impacts", type=int, default=100)
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--figure", metavar="DIR", help="write the work-precision diagram here")
    args = ap.parse_args()
    from pooltool.physics.resolve.ball_cushion.mathavan_2010.model import solve as pt_solve

    print(f"billiard_contact {bc.__version__}, {os.cpu_count()} CPUs, "
          f"load average {os.getloadavg()[0]:.2f}")
    n = args.impacts
    v, w = impacts(n)
    model = bc.BallCushion(mass=M, radius=R, alpha=0.4, height=H, mu_cushion=MU_CUSHION,
                           mu_table=MU_TABLE, restitution=E)

    def pooltool(rows, max_steps=1000, delta_p=0.001):
        out_v, out_w = np.empty((len(rows), 3)), np.empty((len(rows), 3))
        for k, i in enumerate(rows):
            vx, vy, wx, wy, wz = pt_solve(M, R, H, E, MU_TABLE, MU_CUSHION, v[i, 0], v[i, 1],
                                          w[i, 0], w[i, 1], w[i, 2], max_steps, delta_p)
            out_v[k] = (vx, vy, 0.0)
            out_w[k] = (wx, wy, wz)
        return out_v, out_w

    # Accuracy of each against its own converged answer.
    sub = np.arange(min(args.reference_impacts, n))
    ref = model.resolve(v, w, rtol=1e-12)
    pt_ref = pooltool(sub, max_steps=200_000, delta_p=1e-7)
    models_differ = error(ref["v"][sub], ref["w"][sub], *pt_ref, v[sub], w[sub])
    print(f"the two converged answers (library rtol 1e-12, pooltool delta_p 1e-7) differ by "
          f"at most {models_differ:.2e} on {len(sub)} impacts")
    k = min(n, 300)
    one = [(np.ascontiguousarray(v[i]), np.ascontiguousarray(w[i])) for i in range(k)]
    # The library's ladder: the largest error of each setting and its time on arrays.
    ladder = []
    for method in ("dop853", "dopri5"):
        for rtol in RTOLS:
            try:
                out = model.resolve(v, w, method=method, rtol=rtol)
            except RuntimeError as e:
                print(f"  library {method} rtol {rtol:g} fails: {e}")
                continue
            err = error(out["v"], out["w"], ref["v"], ref["w"], v, w)
            t, _ = best_and_median(lambda: model.resolve(v, w, method=method, rtol=rtol), 3)
            ladder.append((method, rtol, err, t))
    levels = (("its defaults", 1000, 1e-3), ("ten times finer", 10_000, 1e-4),
              ("a hundred times finer", 100_000, 1e-5))
    for label, max_steps, delta_p in levels:
        pt_out = pooltool(sub, max_steps, delta_p)
        pt_err = error(pt_out[0], pt_out[1], *pt_ref, v[sub], w[sub])
        print(f"pooltool mathavan_2010 at {label} (max_steps={max_steps}, delta_p={delta_p:g}): "
              f"largest error {pt_err:.2e}")
        chosen = None
        for method, rtol, err, t in ladder:
            if err <= pt_err and (chosen is None or t < chosen[2]):
                chosen = (method, rtol, t, err)
        if chosen is None:
            print("  no setting of the library reaches that accuracy on every impact")
            continue
        method, rtol, _, err = chosen
        work = model.resolve(v, w, method=method, rtol=rtol)
        print(f"  equal accuracy: the library with {method}, rtol {rtol:g} (largest error "
              f"{err:.2e} <= {pt_err:.2e}); accepted steps median "
              f"{np.median(work['steps']):.0f}, largest {work['steps'].max()}; evaluations "
              f"median {np.median(work['evaluations']):.0f}, largest {work['evaluations'].max()}")
        rows = range(k)
        t_pt, m_pt = best_and_median(lambda: pooltool(rows, max_steps, delta_p), args.repeats)
        t_arr, m_arr = best_and_median(lambda: model.resolve(v, w, method=method, rtol=rtol),
                                       args.repeats)
        f = model.resolve

        def singles():
            for a, b in one:
                f(a, b, method=method, rtol=rtol)

        t_one, m_one = best_and_median(singles, args.repeats)
        pt_us, arr_us, one_us = t_pt / k * 1e6, t_arr / n * 1e6, t_one / k * 1e6
        line = lambda what, b, m: print(f"  {what:<56} best {b:9.3f} us  median {m:9.3f} us")
        line("pooltool mathavan_2010 solve, per impact", pt_us, m_pt / k * 1e6)
        line(f"BallCushion.resolve, {n} impacts in arrays, per impact", arr_us, m_arr / n * 1e6)
        line("BallCushion.resolve, one impact a call", one_us, m_one / k * 1e6)
        ratio = pt_us / arr_us
        print(f"  {'ratio, arrays (target >= 100)':<56} {ratio:9.1f} x: "
              f"{'met' if ratio >= 100 else 'NOT met'}")
        print(f"  {'ratio, one impact a call':<56} {pt_us / one_us:9.1f} x")
    if args.figure:
        figure(args, model, v, w, one, ladder, pooltool, pt_ref, sub, n, k)
    t_def, m_def = best_and_median(lambda: model.resolve(v, w), args.repeats)
    print(f"BallCushion.resolve at its default (dop853, rtol 1e-10), arrays: best "
          f"{t_def / n * 1e6:.3f} us an impact, median {m_def / n * 1e6:.3f} us")


if __name__ == "__main__":
    main()
