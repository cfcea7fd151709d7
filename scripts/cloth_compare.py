"""The nine-ball break free and on the cloth (docs/cluster.md, "The cloth"): the cloth's
normal force on each ball against time, and what the cloth changes in each ball's outgoing
speed and vertical velocity. Both runs by the command line (`run SCENE --json`, `--trace`
on the cloth scene), so the figure shows what a user gets.

    python scripts/cloth_compare.py [--bin target/release/billiard-contact] [--out docs/cluster]

Writes docs/cluster/cloth_break.png and .svg. Needs numpy and matplotlib.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import subprocess
import tempfile

import numpy as np

FREE = "data/scenes/break_nine_ball.toml"
CLOTH = "data/scenes/break_nine_ball_cloth.toml"


def run_json(binary: str, scene: str) -> dict:
    out = subprocess.run([binary, "run", scene, "--json"], check=True, capture_output=True)
    return json.loads(out.stdout)


def cloth_forces(binary: str, scene: str) -> tuple[np.ndarray, dict[int, np.ndarray]]:
    """The trace's time (s) and each ball's cloth normal force (N)."""
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "trace.csv")
        subprocess.run([binary, "run", scene, "--trace", path], check=True, capture_output=True)
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    head, body = rows[0], rows[1:]
    t = np.array([float(r[0]) for r in body])
    forces = {}
    for k, name in enumerate(head):
        if name.endswith("_cloth_normal_force (N)"):
            ball = int(name[1:name.index("_")])
            forces[ball] = np.array([float(r[k]) if r[k] else np.nan for r in body])
    return t, forces


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default="target/release/billiard-contact")
    ap.add_argument("--out", default="docs/cluster")
    args = ap.parse_args()
    free, cloth = run_json(args.bin, FREE), run_json(args.bin, CLOTH)
    t, forces = cloth_forces(args.bin, CLOTH)
    # The cue ball's contact closes at its touch (the rack's own contacts close at 0).
    first = min(c["start"] for c in cloth["contacts"] if 0 in c["pair"])

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(13, 5.2), gridspec_kw={"width_ratios": [1.4, 1]})
    weight = 0.17 * 9.81
    for ball in sorted(forces):
        f = forces[ball]
        a.plot((t - first) * 1e6, f / weight, lw=1.6, label=f"ball {ball}")
    a.axhline(1.0, color="0.5", lw=0.8, ls=":")
    a.set_xlim(-100, (t[-1] - first) * 1e6)
    a.set_xlabel("t from the cue ball's touch (µs)")
    a.set_ylabel("cloth's normal force / the ball's weight")
    a.set_title("the cloth's push on each ball (1 = its weight; 0: lifted off the cloth)",
                fontsize=10)
    a.legend(ncol=2, fontsize=8, loc="upper right")
    a.grid(alpha=0.3)

    n = len(free["balls"])
    speed = lambda j: np.array([np.hypot(*bb["velocity"][:2]) for bb in j["balls"]])
    dv = speed(cloth) - speed(free)
    vz = np.array([bb["velocity"][2] for bb in cloth["balls"]])
    x = np.arange(n)
    b.bar(x - 0.2, dv * 1e3, width=0.4, label="horizontal speed, cloth - free (mm/s)")
    b.bar(x + 0.2, vz * 1e3, width=0.4, label="vertical velocity on the cloth (mm/s)")
    b.axhline(0.0, color="0.3", lw=0.8)
    b.set_xticks(x)
    b.set_xlabel("ball (0 the cue ball)")
    b.set_ylabel("mm/s")
    b.set_title("what the cloth changes in the outgoing velocities", fontsize=10)
    b.legend(fontsize=8, loc="lower left")
    b.grid(alpha=0.3, axis="y")

    ratio = (cloth["energy_out"] / cloth["energy_in"], free["energy_out"] / free["energy_in"])
    fig.suptitle(
        "nine-ball break at 8 m/s, free balls and on the cloth (slate bed, ball-cloth mu 0.2): "
        f"kinetic energy out/in {ratio[1]:.3f} free, {ratio[0]:.3f} on the cloth", fontsize=11)
    fig.tight_layout()
    os.makedirs(args.out, exist_ok=True)
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(args.out, f"cloth_break.{ext}"), dpi=110)
    print(f"wrote {args.out}/cloth_break.png and .svg")


if __name__ == "__main__":
    main()
