#!/usr/bin/env python3
"""Compare pooltool's mathavan_2010 cushion model with billiard-contact's kernel.

pooltool (0.6.0) steps Mathavan, Jackson and Parkin's equations with explicit Euler steps in
the cushion's normal impulse (`pooltool.physics.resolve.ball_cushion.mathavan_2010.model.
solve`); this script runs it with increasing step counts and, in the same run, our kernel
(dop853 at rtol 1e-12, through `cargo run --release --example cushion_grid`) over a grid of
incidence angles, speeds and spins, and writes docs/cushion/mathavan_comparison.csv and a
figure of pooltool's difference from our rebound against its step count
(docs/cushion/mathavan_comparison.png, .svg). docs/cushion.md explains the differences.

Frames and parameters map one to one: both put x along the cushion, y into it, z up;
pooltool's h is the contact height (sin theta = (h - R) / R), mu_w the cushion's friction,
mu_s the cloth's, ee the restitution (Stronge's energetic rule in both). pooltool's step is
dP = M v_y / steps in compression (`max_steps`; its `delta_p` floor set to 1e-15 here), and
its restitution step target_work / steps (its own choice of units).

Run with a Python that has pooltool-billiards 0.6.0 and matplotlib (docs/python.md says how
to install pooltool 0.6.0): `python scripts/compare_mathavan.py` (pooltool is imported in a
child process, of --python when given).
"""

import argparse
import csv
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
OUT = os.path.join(ROOT, "docs", "cushion")

M, R = 0.17, 0.028575
H = 1.4 * R  # contact height: sin theta = 0.4
MU_CUSHION, MU_TABLE, E = 0.2, 0.2, 0.85
STEPS = [100, 300, 1000, 3000, 10000, 30000, 100000]


def grid():
    cases = []
    for incidence in [15, 30, 45, 60, 75]:
        for speed in [1.0, 3.0]:
            a = math.radians(incidence)
            vx, vy = speed * math.sin(a), speed * math.cos(a)
            roll = (-vy / R, vx / R, 0.0)  # rolling on the cloth: v + w x (0, 0, -R) = 0
            side = 0.5 * speed / R
            for kind, w in [
                ("stun", (0.0, 0.0, 0.0)),
                ("follow", roll),
                ("draw", tuple(-x for x in roll)),
                ("side+", (0.0, 0.0, side)),
                ("side-", (0.0, 0.0, -side)),
            ]:
                cases.append((f"{kind} {incidence}deg {speed:g}m/s", vx, vy, w))
    return cases


POOLTOOL_CHILD = r"""
import json, sys
from pooltool.physics.resolve.ball_cushion.mathavan_2010.model import solve
job = json.load(sys.stdin)
out = []
for (vx, vy, w) in job["cases"]:
    row = []
    for n in job["steps"]:
        try:
            r = solve(job["M"], job["R"], job["h"], job["e"], job["mu_s"], job["mu_w"],
                      vx, vy, w[0], w[1], w[2], max_steps=n, delta_p=1e-15)
            row.append([float(x) for x in r])
        except RuntimeError as e:  # its step budget ran out before the phase's end
            row.append(None)
    out.append(row)
print()
print(json.dumps(out))
"""


def run_pooltool(python, cases):
    job = {
        "M": M, "R": R, "h": H, "e": E, "mu_s": MU_TABLE, "mu_w": MU_CUSHION,
        "steps": STEPS, "cases": [(vx, vy, w) for _, vx, vy, w in cases],
    }
    p = subprocess.run([python, "-c", POOLTOOL_CHILD], input=json.dumps(job),
                       capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"pooltool failed:\n{p.stderr}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def run_ours(cases):
    rows = ["m,r,h,mu_cushion,mu_table,e,vx,vy,wx,wy,wz"]
    for _, vx, vy, w in cases:
        rows.append(",".join(repr(x) for x in (M, R, H, MU_CUSHION, MU_TABLE, E, vx, vy, *w)))
    p = subprocess.run(["cargo", "run", "--quiet", "--release", "--example", "cushion_grid"],
                       cwd=ROOT, input="\n".join(rows) + "\n", capture_output=True,
                       text=True, check=True)
    out = []
    for line in p.stdout.strip().splitlines()[1:]:
        f = line.split(",")
        if f[0] == "error":
            sys.exit(f"our kernel failed: {line}")
        out.append({"v": [float(f[0]), float(f[1])], "vz": float(f[2]),
                    "w": [float(x) for x in f[3:6]], "lifts_off": f[7] == "true",
                    "events": f[8]})
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--python", default=sys.executable,
                    help="a Python with pooltool-billiards 0.6.0 (default: this one)")
    args = ap.parse_args()
    cases = grid()
    pt = run_pooltool(args.python, cases)
    ours = run_ours(cases)
    os.makedirs(OUT, exist_ok=True)
    table = []
    for (label, vx, vy, w), prow, o in zip(cases, pt, ours):
        speed = math.hypot(vx, vy)
        for n, r in zip(STEPS, prow):
            if r is None:
                table.append({"case": label, "steps": n, "err_v": float("nan"),
                              "err_w": float("nan"), "our_events": o["events"],
                              "lifts_off": o["lifts_off"]})
                continue
            dv = math.hypot(r[0] - o["v"][0], r[1] - o["v"][1]) / speed
            dw = math.sqrt(sum((r[2 + i] - o["w"][i]) ** 2 for i in range(3))) * R / speed
            table.append({"case": label, "steps": n, "err_v": dv, "err_w": dw,
                          "our_events": o["events"], "lifts_off": o["lifts_off"]})
    path = os.path.join(OUT, "mathavan_comparison.csv")
    with open(path, "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(table[0]))
        wr.writeheader()
        wr.writerows(table)
    # Summary: per step count, the median and largest difference; the cases whose
    # difference does not shrink.
    print(f"{len(cases)} cases; difference of pooltool's rebound from ours, over the speed")
    print(f"{'steps':>7} {'median |dv|':>12} {'max |dv|':>10} {'median r|dw|':>13} {'max r|dw|':>10}")
    summary = []
    for n in STEPS:
        ev = sorted(t["err_v"] for t in table if t["steps"] == n and t["err_v"] == t["err_v"])
        ew = sorted(t["err_w"] for t in table if t["steps"] == n and t["err_w"] == t["err_w"])
        failed = sum(1 for t in table if t["steps"] == n and t["err_v"] != t["err_v"])
        if failed:
            print(f"{n:7d}: pooltool failed (restitution not reached) in {failed} cases")
        summary.append((n, ev[len(ev) // 2], ev[-1], ew[len(ew) // 2], ew[-1]))
        print(f"{n:7d} {ev[len(ev)//2]:12.2e} {ev[-1]:10.2e} {ew[len(ew)//2]:13.2e} {ew[-1]:10.2e}")
    last = [t for t in table if t["steps"] == STEPS[-1]]
    stuck = [t for t in last if t["err_v"] > 1e-3]
    failed = [t for t in last if t["err_v"] != t["err_v"]]
    print(f"cases where pooltool's restitution never reached its target at {STEPS[-1]} steps:")
    for t in failed:
        print(f"  {t['case']:24s} ours: {t['our_events'] or '-'}"
              f"{' (lifts off)' if t['lifts_off'] else ''}")
    print(f"cases still differing by more than 1e-3 at {STEPS[-1]} steps: {len(stuck)}")
    for t in sorted(stuck, key=lambda t: -t["err_v"])[:12]:
        print(f"  {t['case']:24s} |dv| {t['err_v']:.2e}  ours: {t['our_events'] or '-'}"
              f"{' (lifts off)' if t['lifts_off'] else ''}")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    kinds = {}
    for t in table:
        if t["err_v"] == t["err_v"]:
            kinds.setdefault(t["case"], []).append((t["steps"], t["err_v"]))
    for with_events in (False, True):
        for label, pts in kinds.items():
            xs, ys = zip(*pts)
            events = next(t["our_events"] for t in table if t["case"] == label)
            if bool(events) != with_events:
                continue
            ax.loglog(xs, [max(y, 1e-12) for y in ys],
                      color="tab:red" if events else "tab:blue",
                      alpha=0.8 if events else 0.35, lw=0.8)
    ax.loglog([s[0] for s in summary], [s[1] for s in summary], "k-o", lw=2,
              label="median over the grid")
    ax.loglog(STEPS, [1.0 / n for n in STEPS], "k--", lw=1, label="1 / steps (Euler)")
    ax.plot([], [], color="tab:blue", label="cases where both contacts slide throughout (ours)")
    ax.plot([], [], color="tab:red", label="cases with a slip event (ours)")
    ax.set_xlabel("pooltool mathavan_2010: Euler steps per phase")
    ax.set_ylabel("|v_pooltool - v_ours| / |v_in|")
    ax.set_title("Rebound velocity: pooltool's Euler steps against our kernel")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(OUT, f"mathavan_comparison.{ext}"), dpi=110)
    print(f"wrote {path} and the figure")


if __name__ == "__main__":
    main()
