#!/usr/bin/env python3
"""The break resolved together and pair by pair (docs/cluster.md, "Together or pair by pair").

The same rack (data/scenes/break_nine_ball.toml and break_eight_ball.toml: a cue ball at
8 m/s into a tight rack, Hertz contacts with Hunt-Crossley damping calibrated to e = 0.93 at
1 m/s, mu = 0.06, the stick rule) resolved

- together: every ball at once by the cluster kernel (``billiard_contact.Cluster``), on the
  tight rack and on the same racks opened by the gaps below;
- pair by pair, as pooltool and other event-driven engines do: the balls fly straight (no
  cloth, as in the cluster kernel) to the next touch of two balls, and that pair alone is
  resolved by the project's two-ball law (the scene runner's ``solve_law`` through
  ``billiard_contact.run_toml``) with the SAME Hertz law, damping, materials, friction and
  stick rule; then the next touch, until no two balls will ever touch. The rack must then
  have gaps or an order: each neighbour pair is opened by ``gap`` (m) (pooltool leaves
  1e-6 m), exactly (ties broken by the pair's index, lowest or highest first) or with a
  random perturbation of every ball's position (uniform in a disc of radius 0.45 gap, so
  that the gaps lie in 0.1 gap .. 1.9 gap);
- optionally (``--pooltool``) by pooltool 0.6.0 itself on the same rack spaced by 1e-6 m:
  its default ball-ball model, the project's plug-in pair by pair, and the plug-in with
  ``cluster=True`` (python/billiard_contact/pooltool.py). pooltool's models use a constant
  restitution, not the Hunt-Crossley law, so these differ also by the law (see the docs).

Writes docs/cluster/break_compare.csv (one row per ball per run) and the figure
docs/cluster/break_compare.png and .svg.

Run with the venv that has pooltool-billiards 0.6.0, matplotlib and billiard_contact:
``python scripts/break_compare.py [--pooltool]``.
"""

import argparse
import csv
import math
import os
import sys
import time
import tomllib

import numpy as np

import billiard_contact as bc

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
OUT = os.path.join(ROOT, "docs", "cluster")
SCENES = {
    "nine-ball": os.path.join(ROOT, "data", "scenes", "break_nine_ball.toml"),
    "eight-ball": os.path.join(ROOT, "data", "scenes", "break_eight_ball.toml"),
}
#: Gaps between neighbours (m) of the pair-by-pair runs: pooltool's 1e-6 m and a decade
#: either side, and 0.1 mm (a rack a careful racker still calls tight).
GAPS = [1e-7, 1e-6, 1e-5, 1e-4]
#: Random perturbations per gap (each ball moved within a disc of 0.45 gap).
SEEDS = 12
#: Events closer in time than this (s) are simultaneous: the order between them is chosen
#: by the rule of the run. A touch is located to about 1e-16 s for 8 m/s and 1e-7 m.
TIE_TIME = 1e-13
#: Most pair events of one run; a run past it is reported, not used.
MAX_EVENTS = 20000
PAIR_TEMPLATE = """name = "pair"
[balls]
mass = {m!r}
radius = {r!r}
alpha = {alpha!r}
youngs_modulus = {E!r}
poisson_ratio = {nu!r}
[contact]
mu = {mu!r}
[contact.law]
model = "hertz"
damping = "hunt-crossley"
restitution = {e!r}
at_speed = {at!r}
[incoming.lab]
a = {{ position = [{pa}], velocity = [{va}], spin = [{wa}] }}
b = {{ position = [{pb}], velocity = [{vb}], spin = [{wb}] }}
up = [0.0, 0.0, 1.0]
[solver]
method = "dop853"
rtol = 1e-10
"""


def vec(x):
    return ", ".join(repr(float(c)) for c in x)


class Setup:
    """One scene: the balls' common parameters and the tight rack's state."""

    def __init__(self, path):
        with open(path, "rb") as f:
            sc = tomllib.load(f)
        balls = sc["balls"]
        b0 = balls[0]
        for b in balls:
            for k in ("mass", "radius", "youngs_modulus", "poisson_ratio"):
                assert b[k] == b0[k], f"{path}: balls differ in {k}"
        self.m, self.r = b0["mass"], b0["radius"]
        self.alpha = b0.get("alpha", 0.4)
        self.E, self.nu = b0["youngs_modulus"], b0["poisson_ratio"]
        self.mu = sc["contact"]["mu"]
        law = sc["contact"]["law"]
        assert law["model"] == "hertz" and law["damping"] == "hunt-crossley"
        self.e, self.at = law["restitution"], law["at_speed"]
        self.P = np.array([b["position"] for b in balls], float)
        self.V = np.array([b["velocity"] for b in balls], float)
        self.W = np.array([b.get("spin", [0.0, 0.0, 0.0]) for b in balls], float)
        self.n = len(balls)
        self.cluster = bc.Cluster(
            balls=[bc.Ball(self.m, self.r, self.alpha)] * self.n,
            mu=self.mu,
            youngs_modulus=self.E,
            poisson_ratio=self.nu,
            damping="hunt-crossley",
            restitution=self.e,
            at_speed=self.at,
        )

    def opened(self, gap, rng=None):
        """The rack with every neighbour pair opened by ``gap`` (m): the rack's lattice
        scaled about the head ball (ball 1) by (2r + gap) / 2r, the cue ball on its line at
        the same distance before the head ball; with ``rng`` every ball then moved within a
        disc of radius 0.45 gap in the table's plane."""
        P = self.P.copy()
        head = P[1].copy()
        s = (2 * self.r + gap) / (2 * self.r)
        P[1:] = head + (P[1:] - head) * s
        if rng is not None:
            for k in range(self.n):
                rho = 0.45 * gap * math.sqrt(rng.random())
                phi = 2 * math.pi * rng.random()
                P[k, :2] += rho * np.array([math.cos(phi), math.sin(phi)])
        return P

    def pair(self, pa, va, wa, pb, vb, wb):
        """The two-ball law on one pair: the centres put exactly at contact symmetrically
        about their midpoint (the law needs touching balls; the shift is a rounding of the
        located touch). Returns the outgoing (va, wa, vb, wb)."""
        d = pb - pa
        mid = 0.5 * (pa + pb)
        u = d / np.linalg.norm(d)
        pa, pb = mid - self.r * u, mid + self.r * u
        txt = PAIR_TEMPLATE.format(
            m=self.m, r=self.r, alpha=self.alpha, E=self.E, nu=self.nu, mu=self.mu,
            e=self.e, at=self.at, pa=vec(pa), va=vec(va), wa=vec(wa), pb=vec(pb),
            vb=vec(vb), wb=vec(wb),
        )
        out = bc.run_toml(txt)["lab_out"]
        return (
            np.array(out["a"]["velocity"]), np.array(out["a"]["spin"]),
            np.array(out["b"]["velocity"]), np.array(out["b"]["spin"]),
        )

    def together(self, P):
        out = self.cluster.resolve(P, self.V, self.W)
        return np.asarray(out["velocities"]), np.asarray(out["spins"]), len(out["contacts"])

    def pairwise(self, P, order="first", rng=None):
        """Event-driven pair by pair from positions P. ``order``: among simultaneous
        touches (within TIE_TIME) the lowest pair first ("first"), the highest ("last"),
        or a random one ("random", with rng)."""
        P, V, W = P.copy(), self.V.copy(), self.W.copy()
        d2 = (2 * self.r) ** 2
        events = 0
        iu, ju = np.triu_indices(self.n, 1)
        while True:
            dp = P[ju] - P[iu]
            dv = V[ju] - V[iu]
            b = np.einsum("ij,ij->i", dp, dv)
            c = np.einsum("ij,ij->i", dp, dp) - d2
            a = np.einsum("ij,ij->i", dv, dv)
            disc = b * b - a * c
            ok = (b < 0) & (disc >= 0)
            t = np.full(len(b), np.inf)
            # Touching (c <= 0 within rounding) and approaching: now.
            now = ok & (c <= 2e-9 * d2)
            t[now] = 0.0
            later = ok & ~now
            t[later] = c[later] / (-b[later] + np.sqrt(disc[later]))
            tmin = t.min()
            if not np.isfinite(tmin):
                break
            cand = np.nonzero(t <= tmin + TIE_TIME)[0]
            if order == "first":
                k = cand[0]
            elif order == "last":
                k = cand[-1]
            else:
                k = cand[rng.integers(len(cand))]
            P += V * t[k]
            i, j = iu[k], ju[k]
            V[i], W[i], V[j], W[j] = self.pair(P[i], V[i], W[i], P[j], V[j], W[j])
            events += 1
            if events > MAX_EVENTS:
                raise RuntimeError(f"more than {MAX_EVENTS} pair events")
        return V, W, events

    def energy(self, V, W):
        """Kinetic energy (J): translation and rotation (I = alpha m r^2)."""
        return 0.5 * self.m * float((V**2).sum()) + 0.5 * self.alpha * self.m * self.r**2 * float(
            (W**2).sum()
        )


def runs(name, setup, seeds, use_pooltool):
    """Every run of one scene: (label, kind, gap, seed, V, W, count)."""
    rows = []
    t0 = time.time()
    V, W, nc = setup.together(setup.P)
    rows.append(("together, tight rack", "together", 0.0, -1, V, W, nc))
    for gap in GAPS:
        V, W, nc = setup.together(setup.opened(gap))
        rows.append((f"together, gap {gap:g}", "together-gap", gap, -1, V, W, nc))
        for order in ("first", "last"):
            V, W, ne = setup.pairwise(setup.opened(gap), order)
            rows.append((f"pairs, gap {gap:g}, ties {order}", "pairs-even", gap, -1, V, W, ne))
        for s in range(seeds):
            rng = np.random.default_rng(1000 * s + 7)
            P = setup.opened(gap, rng)
            V, W, ne = setup.pairwise(P, "first")
            rows.append((f"pairs, gap {gap:g}, seed {s}", "pairs-random", gap, s, V, W, ne))
            V, W, nc = setup.together(P)
            rows.append((f"together, gap {gap:g}, seed {s}", "together-gap", gap, s, V, W, nc))
    print(f"{name}: {len(rows)} runs in {time.time() - t0:.1f} s", file=sys.stderr)
    if use_pooltool:
        rows += pooltool_runs(setup)
    return rows


#: Simulated time of the pooltool runs (s): the break's ball-ball events are over within
#: microseconds (pooltool's 1e-6 m gaps); the cloth (pooltool's sliding friction u_s = 0.2)
#: takes u_s g t = 0.01 m/s off a sliding ball by then.
POOLTOOL_T = 0.005


def pooltool_runs(setup):
    """pooltool 0.6.0 on the rack spaced by its own 1e-6 m, the cue ball 1e-6 m before the
    head ball at 8 m/s without spin: its default ball-ball model and the project's plug-in
    with cluster=True, the balls' e_b and u_b the scene's restitution and mu. The rack is
    turned by +90 degrees onto the table's long axis, centred on it (no cushion is reached
    in POOLTOOL_T), and the outgoing velocities turned back."""
    import pooltool as pt
    import pooltool.constants as const
    from billiard_contact.pooltool import install

    P = setup.opened(1e-6)
    P[0, 0] = P[1, 0] - 2 * setup.r - 1e-6
    rows = []
    for label, mode in (
        ("pooltool 0.6.0, default ball-ball model", "pooltool"),
        ("pooltool 0.6.0, plug-in cluster=True", "pooltool-cluster"),
    ):
        table = pt.Table.default()
        cx, cy = table.w / 2, table.l / 2
        balls = {}
        for k in range(setup.n):
            params = pt.BallParams(m=setup.m, R=setup.r, u_b=setup.mu, e_b=setup.e)
            ball = pt.Ball(id=str(k), params=params)
            ball.state.rvw[0] = [cx - P[k, 1], cy + P[k, 0], setup.r]
            if np.any(setup.V[k]):
                ball.state.rvw[1] = [-setup.V[k, 1], setup.V[k, 0], 0.0]
                ball.state.s = const.sliding
            balls[str(k)] = ball
        system = pt.System(cue=pt.Cue(cue_ball_id="0"), table=table, balls=balls)
        engine = pt.physics.PhysicsEngine()
        if mode == "pooltool-cluster":
            install(engine, cushion=False, cluster=True)
        out = pt.simulate(system, engine=engine, t_final=POOLTOOL_T, max_events=5000)
        nbb = sum(1 for e in out.events if e.event_type == pt.EventType.BALL_BALL)
        V = np.zeros((setup.n, 3))
        W = np.zeros((setup.n, 3))
        for k in range(setup.n):
            v, w = out.balls[str(k)].state.rvw[1], out.balls[str(k)].state.rvw[2]
            V[k] = [v[1], -v[0], v[2]]
            W[k] = [w[1], -w[0], w[2]]
        rows.append((label, mode, 1e-6, -1, V, W, nbb))
    return rows


#: How each kind of run is drawn: (legend, colour, marker, size, horizontal offset).
STYLE = {
    "together": ("together, tight rack (cluster kernel)", "black", "D", 46, 0.0),
    "together-gap": ("together, racks with the pairs' gaps", "0.6", ".", 20, -0.18),
    "pairs-random": ("pair by pair, random gaps", "tab:orange", "o", 9, 0.18),
    "pairs-even": ("pair by pair, even gaps, ties by index", "tab:red", "x", 22, 0.30),
    "pooltool": ("pooltool 0.6.0, its default model", "tab:blue", "^", 30, -0.30),
    "pooltool-cluster": ("pooltool 0.6.0 + plug-in, cluster=True", "tab:green", "s", 26, -0.40),
}


def plot(allrows, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(
        2, 3, figsize=(15, 8.5), gridspec_kw={"width_ratios": [2.2, 2.2, 1.1]}
    )
    for row, (name, (setup, rows)) in enumerate(allrows.items()):
        ax_s, ax_d, ax_e = axes[row]
        ke_in = setup.energy(setup.V, setup.W)
        seen = set()
        for label, kind, gap, seed, V, W, count in rows:
            leg, col, mk, size, dx = STYLE[kind]
            idx = np.arange(setup.n) + dx
            sp = np.hypot(V[:, 0], V[:, 1])
            ang = np.degrees(np.arctan2(V[:, 1], V[:, 0]))
            lab = leg if kind not in seen else None
            seen.add(kind)
            z = 3 if kind == "together" else 2
            ax_s.scatter(idx, sp, s=size, c=col, marker=mk, label=lab, zorder=z, linewidths=1)
            ax_d.scatter(idx, ang, s=size, c=col, marker=mk, zorder=z, linewidths=1)
            if kind == "together":
                ax_e.axhline(setup.energy(V, W) / ke_in, color=col, lw=1.5, zorder=1)
            else:
                ax_e.scatter(gap * (1.0 + 0.08 * dx), setup.energy(V, W) / ke_in, s=size,
                             c=col, marker=mk, zorder=z, linewidths=1)
        for ax in (ax_s, ax_d):
            ax.set_xticks(range(setup.n))
            ax.set_xticklabels(["cue"] + [str(k) for k in range(1, setup.n)])
            ax.grid(alpha=0.3)
            ax.set_xlabel("ball (1 = head ball, then row by row)")
        ax_s.set_ylabel("outgoing speed (m/s)")
        ax_s.set_title(f"{name} break, cue ball 8 m/s: speed of every ball")
        ax_d.set_ylabel("direction (degrees from the cue ball's line)")
        ax_d.set_ylim(-180, 180)
        ax_d.set_yticks(range(-180, 181, 45))
        ax_d.set_title("direction of every ball")
        ax_e.set_xscale("log")
        ax_e.set_xlabel("gap between neighbours (m)")
        ax_e.set_ylabel("kinetic energy out / in")
        ax_e.set_title(f"kinetic energy (in: {ke_in:.2f} J); line: tight", fontsize=10)
        ax_e.grid(alpha=0.3)
    fig.suptitle(
        "The same rack resolved together (cluster kernel) and pair by pair (the two-ball law, "
        "same Hertz / Hunt-Crossley law, mu = 0.06), gaps 1e-7 .. 1e-4 m",
        fontsize=11,
    )
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=9, frameon=False)
    fig.tight_layout(rect=(0, 0.06, 1, 0.97))
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out, f"break_compare.{ext}"), dpi=110)


def summary(name, setup, rows):
    """The numbers docs/cluster.md quotes, on stderr."""
    ke_in = setup.energy(setup.V, setup.W)
    tight = next(r for r in rows if r[1] == "together")
    Vt = tight[4]
    sp_t = np.hypot(Vt[:, 0], Vt[:, 1])
    print(f"== {name}: kinetic energy in {ke_in:.4f} J", file=sys.stderr)
    for kind in STYLE:
        sel = [r for r in rows if r[1] == kind]
        if not sel:
            continue
        ke = np.array([setup.energy(r[4], r[5]) / ke_in for r in sel])
        counts = [r[6] for r in sel]
        sp = np.array([np.hypot(r[4][:, 0], r[4][:, 1]) for r in sel])
        ang = np.array([np.degrees(np.arctan2(r[4][:, 1], r[4][:, 0])) for r in sel])
        dsp = np.abs(sp - sp_t).max(axis=1)
        # direction differences only for balls leaving at more than 0.1 m/s both ways
        dang = []
        for a, s_ in zip(ang, sp):
            d = (a - np.degrees(np.arctan2(Vt[:, 1], Vt[:, 0])) + 180) % 360 - 180
            ok = (s_ > 0.1) & (sp_t > 0.1)
            dang.append(np.abs(d[ok]).max() if ok.any() else 0.0)
        print(
            f"{kind:18s} n={len(sel):3d} KE out/in {ke.min():.4f}..{ke.max():.4f}; events/contacts "
            f"{min(counts)}..{max(counts)}; max |speed - together| per run "
            f"{dsp.min():.3f}..{dsp.max():.3f} m/s; max |direction - together| "
            f"{min(dang):.1f}..{max(dang):.1f} deg",
            file=sys.stderr,
        )
        for gap in sorted({r[2] for r in sel}):
            g = [setup.energy(r[4], r[5]) / ke_in for r in sel if r[2] == gap]
            d = [x for x, r in zip(dsp, sel) if r[2] == gap]
            print(f"    gap {gap:g}: KE out/in {min(g):.4f}..{max(g):.4f}; max |speed - "
                  f"together| {min(d):.4f}..{max(d):.4f} m/s", file=sys.stderr)
    print("    together, tight: speeds " + " ".join(f"{x:.3f}" for x in sp_t), file=sys.stderr)
    pr = [r for r in rows if r[1] == "pairs-random"]
    sp = np.array([np.hypot(r[4][:, 0], r[4][:, 1]) for r in pr])
    print("    pairs, random: speed min " + " ".join(f"{x:.3f}" for x in sp.min(0)), file=sys.stderr)
    print("    pairs, random: speed max " + " ".join(f"{x:.3f}" for x in sp.max(0)), file=sys.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", type=int, default=SEEDS)
    ap.add_argument("--pooltool", action="store_true", help="also run pooltool 0.6.0")
    ap.add_argument("--out", default=OUT)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    allrows = {}
    for name, path in SCENES.items():
        setup = Setup(path)
        allrows[name] = (setup, runs(name, setup, args.seeds, args.pooltool))
    with open(os.path.join(args.out, "break_compare.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow([
            "scene", "run", "kind", "gap (m)", "seed", "events or contacts", "ball",
            "vx (m/s)", "vy (m/s)", "speed (m/s)", "direction (deg)", "wz (rad/s)",
            "kinetic energy of the run (J)",
        ])
        for name, (setup, rows) in allrows.items():
            for label, kind, gap, seed, V, W, count in rows:
                ke = setup.energy(V, W)
                for k in range(setup.n):
                    sp = float(np.hypot(V[k, 0], V[k, 1]))
                    ang = math.degrees(math.atan2(V[k, 1], V[k, 0]))
                    w.writerow([
                        name, label, kind, gap, seed, count, k, f"{V[k, 0]:.9g}",
                        f"{V[k, 1]:.9g}", f"{sp:.9g}", f"{ang:.6f}", f"{W[k, 2]:.9g}",
                        f"{ke:.9g}",
                    ])
    for name, (setup, rows) in allrows.items():
        summary(name, setup, rows)
    plot(allrows, args.out)


if __name__ == "__main__":
    main()
