#!/usr/bin/env python3
"""The same contact, integrated by scipy's solve_ivp: a peer for the work-precision diagram.

Integrates the paper's equations 14-21 for the same scene, in the same scaled variables
(time over the duration, speeds over v_ref, spins over v_ref / r) as billiard-contact, with
scipy.integrate.solve_ivp (RK45, DOP853, LSODA) at rtol = 1e-3 ... 1e-13, atol = rtol, and
measures the same error (largest scaled deviation of the outgoing centre-of-mass state from
the closed form, which billiard-contact prints with `run --json --method closed-form`).
Sliding that stops is a terminal event on g = slip . e0; the rest of the pulse is normal
only. A tabulated pulse is integrated knot to knot (the same breakpoints as ours).

Rows are appended to DIR/work_precision.csv (method = scipy-RK45, scipy-DOP853,
scipy-LSODA; rows of an earlier run of this script for the same scene are replaced), then
`billiard-contact work-precision --out DIR --replot` redraws the figure with them, and the
ratio of times per contact at equal error is printed.

Not run by CI. Usage (after `billiard-contact work-precision --out DIR`):

    pip install scipy
    python3 benches/peers/scipy_contact.py --out DIR [--scene data/scenes/default.toml]
        [--bin target/release/billiard-contact] [--profiles half-sine,hertz,...]
        [--repeats 5] [--no-replot]

Only a constant mu is supported (the scene's `mu` a number).
"""

import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys
import time

try:
    import tomllib
except ImportError:  # Python < 3.11
    import tomli as tomllib

import numpy as np
from scipy import special
from scipy.integrate import solve_ivp

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
COLUMNS = ["profile", "method", "rtol", "steps", "error", "stick_time_error",
           "rhs_evaluations", "accepted_steps", "seconds_per_contact",
           "breakpoints", "scene", "rejected_steps", "samples", "solves_per_sample", "note"]


class Profile:
    """phi(s) (unit impulse over s in [0, 1]), its interior breakpoints, Phi^-1."""

    def __init__(self, name, phi, breakpoints=()):
        self.name = name
        self.phi = phi
        self.breakpoints = list(breakpoints)

    def cumulative(self, s):
        from scipy.integrate import quad
        cuts = [0.0] + [b for b in self.breakpoints if b < s] + [s]
        return sum(quad(self.phi, a, b, epsabs=1e-15, epsrel=1e-14, limit=200)[0]
                   for a, b in zip(cuts, cuts[1:]))

    def time_at(self, q):
        from scipy.optimize import brentq
        return brentq(lambda s: self.cumulative(s) - q, 0.0, 1.0, xtol=1e-15, rtol=1e-15)


def profiles(names):
    b_hz = special.beta(0.4, 0.5)

    def hertz(s):
        h = min(s, 1.0 - s)
        if h <= 0.0:
            return 0.0
        u = special.betaincinv(0.4, 0.5, min(2.0 * h, 1.0))
        return 0.5 * b_hz * u ** 0.6

    n = 1.5
    peak = math.pi / special.beta((n + 1) / 2, 0.5)
    with open(os.path.join(ROOT, "data", "profiles", "measured_pulse.csv")) as f:
        rows = [r for r in csv.DictReader(f)]
    t = np.array([float(r["time"]) for r in rows])
    fo = np.array([float(r["force"]) for r in rows])
    s_knots = t / t[-1]
    trapezoid = getattr(np, "trapezoid", None) or np.trapz
    area = trapezoid(fo, s_knots)
    phi_knots = fo / area
    table = {
        "half-sine": Profile("half-sine", lambda s: 0.5 * math.pi * math.sin(math.pi * min(max(s, 0.0), 1.0))),
        "hertz": Profile("hertz", hertz),
        "sine-power": Profile("sine-power",
                              lambda s: peak * math.sin(math.pi * min(max(s, 0.0), 1.0)) ** n),
        "rectangle": Profile("rectangle", lambda s: 1.0),
        "tabulated": Profile("tabulated", lambda s: float(np.interp(s, s_knots, phi_knots)),
                             s_knots[1:-1]),
    }
    return [table[p] for p in names]


class Problem:
    """The scene's collision in scaled variables, from billiard-contact's own JSON."""

    def __init__(self, scene_path, binary):
        with open(scene_path, "rb") as f:
            scene = tomllib.load(f)
        mu = scene["contact"]["mu"]
        if not isinstance(mu, (int, float)):
            sys.exit("scipy_contact.py: only a constant mu is supported")
        out = subprocess.run([binary, "run", scene_path, "--json", "--method", "closed-form"],
                             check=True, capture_output=True, text=True).stdout
        rep = json.loads(out)
        self.name = rep["name"]
        self.mu = float(mu)
        self.alpha = float(scene["balls"].get("alpha", 0.4))
        self.r = float(scene["balls"]["radius"])
        self.m = float(scene["balls"]["mass"])
        cm_in, cm_out = rep["cm_in"], rep["cm_out"]
        self.u = np.array(cm_in["u"])
        self.wa = np.array(cm_in["omega_a"])
        self.wb = np.array(cm_in["omega_b"])
        self.exact = (np.array(cm_out["u"]), np.array(cm_out["omega_a"]), np.array(cm_out["omega_b"]))
        self.impulse = rep["impulse"]
        self.sticks = rep["sticks"]
        self.stick_impulse = rep["stick_impulse"]
        om = self.wa + self.wb
        slip = np.array([2 * self.u[1] + self.r * om[2], 2 * self.u[2] - self.r * om[1]])
        s0 = math.hypot(*slip)
        self.v = max(abs(self.u[0]), s0, np.linalg.norm(self.u),
                     self.r * np.linalg.norm(self.wa), self.r * np.linalg.norm(self.wb))
        self.e0 = slip / s0 if s0 > 0 else np.zeros(2)
        self.slip0 = slip / self.v
        self.pi = self.impulse / (self.m * self.v)
        self.friction = s0 > 0 and self.mu > 0

    def rhs(self, phi, sliding):
        pi, mu, ia, e0 = self.pi, self.mu, 1.0 / self.alpha, self.e0

        def f(s, y):
            n = pi * phi(s)
            if not sliding:
                return [-n, 0, 0, 0, 0, 0, 0]
            sl = y[5:7]
            sp = math.hypot(sl[0], sl[1])
            e = (sl / sp) * (1.0 if sl @ e0 >= 0 else -1.0) if sp > 0 else e0
            fr = mu * n
            spin = 2 * fr * ia
            rate = 2 * fr * (1 + ia)
            return [-n, -fr * e[0], -fr * e[1], spin * e[1], -spin * e[0], -rate * e[0], -rate * e[1]]
        return f

    def solve(self, profile, method, rtol):
        """Outgoing state error, stick-time error, evaluations, accepted steps."""
        y = np.zeros(7)
        y[5:7] = self.slip0
        sliding = self.friction
        cuts = [0.0] + list(profile.breakpoints) + [1.0]
        nfev = steps = 0
        stick_s = None
        e0 = self.e0

        def event(s, yy):
            return yy[5] * e0[0] + yy[6] * e0[1]
        event.terminal = True
        event.direction = -1
        for a, b in zip(cuts, cuts[1:]):
            s = a
            while s < b:
                sol = solve_ivp(self.rhs(profile.phi, sliding), (s, b), y, method=method,
                                rtol=rtol, atol=rtol, events=event if sliding else None)
                if sol.status < 0:
                    raise RuntimeError(sol.message)
                nfev += sol.nfev
                steps += len(sol.t) - 1
                if sliding and sol.t_events and len(sol.t_events[0]):
                    s = float(sol.t_events[0][0])
                    y = sol.y_events[0][0].copy()
                    y[5:7] = 0.0
                    sliding = False
                    stick_s = s
                else:
                    s, y = b, sol.y[:, -1].copy()
        v, w = self.v, self.v / self.r
        u = self.u + v * y[0:3]
        half = np.array([0.0, y[3], y[4]]) * 0.5 * w
        wa, wb = self.wa + half, self.wb + half
        eu, ea, eb = self.exact
        err = max(np.max(np.abs(u - eu)) / v, np.max(np.abs(wa - ea)) / w, np.max(np.abs(wb - eb)) / w)
        stick_err = None
        if self.sticks:
            exact_s = profile.time_at(self.stick_impulse / self.impulse)
            stick_err = abs((stick_s if stick_s is not None else 1.0) - exact_s)
        return err, stick_err, nfev, steps


def timed(fn, repeats, sample_time=0.02):
    fn()
    t0 = time.perf_counter()
    fn()
    once = max(time.perf_counter() - t0, 1e-9)
    per = max(1, math.ceil(sample_time / once))
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(per):
            fn()
        times.append((time.perf_counter() - t0) / per)
    return statistics.median(times), len(times), per


def fmt(x):
    return "" if x is None else repr(float(x))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="directory holding work_precision.csv")
    ap.add_argument("--scene", default=os.path.join(ROOT, "data", "scenes", "default.toml"))
    ap.add_argument("--bin", default=os.path.join(ROOT, "target", "release", "billiard-contact"))
    ap.add_argument("--profiles", default="half-sine,hertz,sine-power,rectangle,tabulated")
    ap.add_argument("--methods", default="RK45,DOP853,LSODA")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--no-replot", action="store_true")
    args = ap.parse_args()
    path = os.path.join(args.out, "work_precision.csv")
    prob = Problem(args.scene, args.bin)
    rows = []
    started = time.perf_counter()
    for prof in profiles(args.profiles.split(",")):
        for method in args.methods.split(","):
            for k in range(3, 14):
                rtol = 10.0 ** -k
                note = ""
                try:
                    err, st_err, nfev, steps = prob.solve(prof, method, rtol)
                    secs, samples, per = timed(lambda: prob.solve(prof, method, rtol), args.repeats)
                except Exception as e:  # a method that gives up at a tolerance is a result
                    err = st_err = secs = None
                    nfev = steps = samples = per = 0
                    note = f"{type(e).__name__}: {e}"
                rows.append([prof.name, "scipy-" + method, fmt(rtol), "", fmt(err), fmt(st_err),
                             nfev, steps, fmt(secs), "true", prob.name, "", samples, per, note])
                print(f"{prof.name:11} scipy-{method:7} rtol {rtol:.0e}: error {err if err is None else f'{err:.2e}'}"
                      f", {nfev} f, {secs if secs is None else f'{secs * 1e6:.0f} us'}", file=sys.stderr)
    with open(path, newline="") as f:
        old = list(csv.reader(f))
    header, body = old[0], old[1:]
    if header[:9] != COLUMNS[:9]:
        sys.exit(f"{path}: not a work-precision CSV (header {header[:9]})")
    si, mi = header.index("scene") if "scene" in header else None, header.index("method")
    keep = [r for r in body if not (r[mi].startswith("scipy-") and (si is None or r[si] == prob.name))]
    width = len(header)
    new = [(r + [""] * width)[:width] if width >= len(COLUMNS) else r[:width] for r in rows]
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(keep + new)
    os.replace(tmp, path)
    print(f"appended {len(new)} rows to {path} in {time.perf_counter() - started:.1f} s", file=sys.stderr)
    ratios(keep, new, header, prob.name)
    if not args.no_replot:
        subprocess.run([args.bin, "work-precision", "--out", args.out, "--replot"], check=True,
                       stdout=subprocess.DEVNULL)
        print(f"redrew {os.path.join(args.out, 'work_precision.svg')} and .png", file=sys.stderr)


def ratios(ours, peers, header, scene):
    """Time per contact of the cheapest run reaching each error, scipy over ours."""
    ix = {c: header.index(c) for c in COLUMNS[:11] if c in header}

    def best(rows, profile, method, target):
        ts = [float(r[ix["seconds_per_contact"]]) for r in rows
              if r[ix["profile"]] == profile and r[ix["method"]] == method
              and r[ix["error"]] and float(r[ix["error"]]) <= target and r[ix["seconds_per_contact"]]
              and ("scene" not in ix or r[ix["scene"]] == scene)
              and ("breakpoints" not in ix or r[ix["breakpoints"]] != "false")]
        return min(ts) if ts else None

    print("\ntime per contact at equal error, scipy / billiard-contact (cheapest run reaching it):")
    print(f"{'profile':11} {'peer':13} {'ours':7} {'1e-6':>14} {'1e-9':>14} {'1e-12':>14}")
    profs = sorted({r[ix["profile"]] for r in peers}, key=lambda p: [r[ix["profile"]] for r in peers].index(p))
    for p in profs:
        for peer, mine in [("scipy-RK45", "dopri5"), ("scipy-DOP853", "dop853"), ("scipy-LSODA", "dop853")]:
            cells = []
            for target in (1e-6, 1e-9, 1e-12):
                a, b = best(peers, p, peer, target), best(ours, p, mine, target)
                cells.append(f"{a / b:10.0f}x" if a and b else "     -")
            print(f"{p:11} {peer:13} {mine:7} " + " ".join(f"{c:>14}" for c in cells))


if __name__ == "__main__":
    main()
