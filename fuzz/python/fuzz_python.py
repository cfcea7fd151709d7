#!/usr/bin/env python
"""Coverage-guided fuzzing (atheris, libFuzzer) of the Python package's input surface.

The constructors ``Ball``, ``SpeedDependentFriction``, ``BallBall``, ``BallPlane`` and
``BallCushion`` get keywords drawn from the input (mass, radius, alpha, a=/b= balls, mu as a number or a speed-dependent
friction, restitution, profile, duration, friction, stick; plausible values, edge values,
wrong types), then ``BallBall.resolve_lab`` gets arrays of arbitrary dtypes (every float and
integer width, bool, complex, object, strings, byte-swapped), shapes ((3,), (N, 3), wrong
ones, empty), memory layouts (Fortran order, strided, negative strides), lists and scalars,
with a method, rtol and time_transform; ``BallPlane.resolve`` (rigid, or with
``tangential="mindlin"`` and the materials) and ``BallCushion.resolve`` get velocities, spins
(and normals) the same way; ``Cluster`` gets 2 to 5 balls (sometimes 0, 1, 23 or a
non-ball), a normal law from materials or a stiffness, a damping with its coefficient or
restitution, and ``resolve`` a struck line or zig-zag of touching (or nearly touching) balls
with spins. The promise checked on every call:

- it returns, and every output is finite (``throw_angle_deg`` may be NaN where the library
  documents it has none), ``sticks`` is boolean, the shapes are (N, 3) and (N,) or (3,)
  and scalars; a plane's or a cushion's impulses are >= 0, the plane's friction impulse at
  most mu times its normal impulse, and neither creates kinetic energy (the cushion with
  Stronge's rule; Newton's may, with friction: Kane and Levinson's paradox); a cluster
  keeps its momentum (to 1e-9), its contacts push, stay within Coulomb's cone and make
  heat >= 0, and the kinetic energy out plus the heat is the energy in (to 1e3 rtol); or
- it raises ValueError or TypeError whose message names the argument (a keyword of the
  call, or ``row i:`` and a field of the row).

Anything else (another exception, a non-finite output, a wrong shape, a crash of the
extension) is a finding: the input is written as ``crash-*`` by libFuzzer. Known problems
of a package without the checks of the Python package's own branch (a non-finite output
that should be a ValueError; a complex array whose imaginary part is dropped) are counted
in ``$FUZZ_PY_KNOWN`` (default target/fuzz-python-known.txt) instead, so the campaign goes
on past them; ``FUZZ_PY_STRICT=1`` makes them findings too.

Run (after installing the package and atheris into a Python, see docs/testing.md):

    python fuzz/python/fuzz_python.py fuzz/corpus/python -max_total_time=600 \
        -timeout=10 -rss_limit_mb=2048

The extension is instrumented for coverage when built with the sanitizer-coverage flags
(``fuzz/python/build``); without them libFuzzer is guided by the Python code alone.
"""

from __future__ import annotations

import ctypes
import glob
import inspect
import math
import os
import re
import sys
import warnings

import atheris
import numpy as np

bc = None  # billiard_contact, imported in main() once libFuzzer is loaded

warnings.simplefilter("ignore")

STRICT = os.environ.get("FUZZ_PY_STRICT") == "1"
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
KNOWN_LOG = os.environ.get("FUZZ_PY_KNOWN", os.path.join(ROOT, "target", "fuzz-python-known.txt"))
known_counts: dict[str, int] = {}

M, R = 0.17, 0.028575
EDGE = [
    0.0, -0.0, 1.0, -1.0, 0.4, 2 / 3, 0.5, 1e-12, 1e-300, 5e-324, 1e300, 1.7976931348623157e308,
    -1e300, math.nan, math.inf, -math.inf, 1e6, 1e6 + 1, 2.5e-4, M, R, 0.06, 1e-9, 1e9,
]
PROFILES = ["half-sine", "hertz", "sine-power", "rectangle", "tabulated", "", "HERTZ", "x"]
METHODS = [None, "closed-form", "rk4", "dopri5", "dop853", "euler", ""]
EVALUATES = ["along-contact", "initial", "contact", "initial-slip", "start", ""]
DTYPES = [
    np.float64, np.float32, np.float16, np.longdouble, np.int8, np.int16, np.int32,
    np.int64, np.uint8, np.uint64, np.bool_, np.complex128, np.complex64, object,
    np.dtype(">f8"), np.dtype("<f4"), "U8", "S8", "m8[s]", "M8[s]",
]
ARRAY_ARGS = ["pa", "va", "wa", "pb", "vb", "wb", "up"]
CTOR_ARGS = ["mass", "radius", "alpha", "a", "b", "mu", "restitution", "profile", "duration",
             "friction", "stick"]
OUT_VECTORS = ["va", "wa", "vb", "wb"]
OUT_SCALARS = ["impulse", "tangential_impulse", "sticks", "throw_angle_deg"]


class Finding(Exception):
    """A broken promise."""


def known(kind: str, detail: str) -> None:
    """A problem the Python package's own branch fixes: a finding when STRICT, else counted."""
    if STRICT:
        raise Finding(f"{kind}: {detail}")
    n = known_counts.get(kind, 0) + 1
    known_counts[kind] = n
    if n in (1, 10, 100, 1000, 10000, 100000):
        with open(KNOWN_LOG, "a") as f:
            f.write(f"{kind} (seen {n}x): {' '.join(detail.split())[:2000]}\n")


def names_an_argument(msg: str, names: list[str]) -> bool:
    """Whether the message names one of the call's arguments (`balls.mass`, `contact.mu.a`,
    `argument 'rtol'`, `va[1]`, ...): the name as a word, dots and brackets as separators."""
    for n in names:
        if re.search(rf"(?<![A-Za-z0-9_]){re.escape(n)}(?![A-Za-z0-9_])", msg):
            # A single letter must be a field (`contact.mu.a`, `balls.b`), quoted, the first
            # word (`v has shape (3, 1)`) or an array's element (`row 3: w[0] = inf`).
            if len(n) > 1 or re.search(rf"(\.{n}\b|'{n}'|\b{n} =|^{n}\b|\b{n}\[)", msg):
                return True
    return False


def refusal(e: BaseException, names: list[str], what: str) -> None:
    """An exception of a call: a ValueError/TypeError naming an argument, else a finding."""
    if isinstance(e, (ValueError, TypeError)):
        msg = str(e)
        if "\n" in msg or not msg.strip():
            raise Finding(f"{what}: a refusal not of one line: {msg!r}") from e
        if not names_an_argument(msg, names):
            # A scalar keyword of another type names itself and the type expected
            # ("mass: expected a real number (float or int), got str"): PyO3's own
            # extraction ("must be real number, not str") is a finding.
            raise Finding(f"{what}: the refusal names no argument: {type(e).__name__}: {msg}") from e
        return
    raise Finding(f"{what}: {type(e).__name__}: {e}") from e


def draw_float(fdp: atheris.FuzzedDataProvider, plausible: float) -> float:
    k = fdp.ConsumeIntInRange(0, 7)
    if k <= 2:
        return plausible
    if k == 3:
        return plausible * fdp.ConsumeFloatInRange(0.0, 4.0)
    if k == 4:
        return EDGE[fdp.ConsumeIntInRange(0, len(EDGE) - 1)]
    if k == 5:
        return fdp.ConsumeRegularFloat()
    return fdp.ConsumeFloat()


def draw_value(fdp: atheris.FuzzedDataProvider, plausible: float):
    """A keyword's value: mostly a float near the plausible one, sometimes another type."""
    k = fdp.ConsumeIntInRange(0, 15)
    if k <= 10:
        return draw_float(fdp, plausible)
    if k == 11:
        return fdp.ConsumeIntInRange(-(2**70), 2**70)
    if k == 12:
        kind = [np.float32, np.int64, np.float16, np.bool_][fdp.ConsumeIntInRange(0, 3)]
        x = draw_float(fdp, plausible)
        try:
            return kind(x)
        except (OverflowError, ValueError):
            return np.float32(x)
    if k == 13:
        return fdp.ConsumeUnicodeNoSurrogates(6)
    if k == 14:
        return complex(plausible, fdp.ConsumeRegularFloat())
    return [None, [plausible], (plausible,), np.array([plausible]), True, object()][
        fdp.ConsumeIntInRange(0, 5)
    ]


def pick(fdp: atheris.FuzzedDataProvider, choices: list):
    return choices[fdp.ConsumeIntInRange(0, len(choices) - 1)]


def draw_ball(fdp: atheris.FuzzedDataProvider):
    kw = {"mass": draw_value(fdp, M), "radius": draw_value(fdp, R)}
    if fdp.ConsumeBool():
        kw["alpha"] = draw_value(fdp, 0.4)
    try:
        return bc.Ball(**kw)
    except Exception as e:  # noqa: BLE001
        refusal(e, ["mass", "radius", "alpha"], f"Ball({kw})")
        return None


def draw_friction(fdp: atheris.FuzzedDataProvider):
    kw = {"a": draw_value(fdp, 0.01), "b": draw_value(fdp, 0.1), "c": draw_value(fdp, 1.0)}
    if fdp.ConsumeBool():
        kw["evaluate"] = pick(fdp, EVALUATES) if fdp.ConsumeIntInRange(0, 7) else 3
    try:
        f = bc.SpeedDependentFriction(**kw)
    except Exception as e:  # noqa: BLE001
        refusal(e, ["a", "b", "c", "evaluate"], f"SpeedDependentFriction({kw})")
        return None
    s = draw_float(fdp, 0.5)
    try:
        mu = f.mu(s)
    except Exception as e:  # noqa: BLE001
        refusal(e, ["s"], f"{f!r}.mu({s})")
        return f
    if math.isfinite(s) and s >= 0 and not math.isfinite(mu):
        raise Finding(f"{f!r}.mu({s}) = {mu}")
    return f


def draw_model(fdp: atheris.FuzzedDataProvider):
    kw = {}
    form = fdp.ConsumeIntInRange(0, 7)
    if form <= 4 or form == 7:  # identical balls (7: and a=/b= too, refused)
        for name, p in (("mass", M), ("radius", R), ("alpha", 0.4)):
            if name == "alpha" and fdp.ConsumeBool():
                continue
            if fdp.ConsumeIntInRange(0, 15) or name == "alpha":
                kw[name] = draw_value(fdp, p)
    if form >= 5:
        for name in ("a", "b"):
            if fdp.ConsumeIntInRange(0, 15):
                ball = draw_ball(fdp)
                if ball is None:
                    return None, kw
                kw[name] = ball
    k = fdp.ConsumeIntInRange(0, 15)
    if k <= 10:
        kw["mu"] = draw_value(fdp, 0.06)
    elif k <= 14:
        f = draw_friction(fdp)
        if f is None:
            return None, kw
        kw["mu"] = f
    for name, p in (("restitution", 1.0), ("duration", 2.5e-4)):
        if fdp.ConsumeBool():
            kw[name] = draw_value(fdp, p)
    if fdp.ConsumeBool():
        kw["profile"] = pick(fdp, PROFILES) if fdp.ConsumeIntInRange(0, 15) else 1.0
    for name in ("friction", "stick"):
        if fdp.ConsumeIntInRange(0, 3) == 0:
            kw[name] = pick(fdp, [True, False, 0, 1, None, "yes"])
    try:
        return bc.BallBall(**kw), kw
    except Exception as e:  # noqa: BLE001
        refusal(e, CTOR_ARGS, f"BallBall({kw})")
        return None, kw


def unit(fdp: atheris.FuzzedDataProvider) -> np.ndarray:
    v = np.array([fdp.ConsumeFloatInRange(-1, 1) for _ in range(3)])
    n = np.linalg.norm(v)
    return v / n if n > 1e-3 else np.array([1.0, 0.0, 0.0])


def draw_states(fdp: atheris.FuzzedDataProvider, n: int, model) -> dict[str, np.ndarray]:
    """Plausible collisions of n rows (touching, approaching), some entries then spoiled."""
    try:
        ra, rb = model.a.radius, model.b.radius
    except Exception:  # noqa: BLE001
        ra = rb = R
    rows = max(n, 1)
    pa = np.zeros((rows, 3))
    pb = np.zeros((rows, 3))
    va = np.zeros((rows, 3))
    for i in range(rows):
        d = unit(fdp)
        d[2] *= 0.1 if fdp.ConsumeBool() else 1.0
        d /= np.linalg.norm(d)
        pa[i] = [fdp.ConsumeFloatInRange(-2, 2), fdp.ConsumeFloatInRange(-1, 1), ra]
        pb[i] = pa[i] + (ra + rb) * d
        va[i] = d * fdp.ConsumeFloatInRange(-1, 8)
    s = {
        "pa": pa, "va": va, "pb": pb,
        "wa": np.array([[fdp.ConsumeFloatInRange(-400, 400) for _ in range(3)] for _ in range(rows)]),
        "vb": np.zeros((rows, 3)),
        "wb": np.zeros((rows, 3)),
        "up": np.tile([0.0, 0.0, 1.0], (rows, 1)),
    }
    for _ in range(fdp.ConsumeIntInRange(0, 3)):
        name = pick(fdp, ARRAY_ARGS)
        i, k = fdp.ConsumeIntInRange(0, rows - 1), fdp.ConsumeIntInRange(0, 2)
        s[name][i, k] = draw_float(fdp, s[name][i, k])
    return s


def as_argument(fdp: atheris.FuzzedDataProvider, a: np.ndarray, single: bool):
    """The array as the call gets it: a dtype, a shape, a layout, or a list."""
    x = a[0] if single else a
    k = fdp.ConsumeIntInRange(0, 15)
    if k <= 6:
        return x
    if k == 7:
        return x.tolist()
    if k == 8:
        dt = pick(fdp, DTYPES)
        try:
            y = x.astype(dt)
        except (TypeError, ValueError, OverflowError):
            return x
        if np.dtype(dt).kind == "c" and fdp.ConsumeBool():
            y = y + 1j * fdp.ConsumeRegularFloat()
        return y
    if k == 9:
        return np.asfortranarray(x)
    if k == 10:  # strided and reversed views of a larger buffer
        big = np.repeat(x, 2, axis=0)
        return big[::-2][::-1] if big.ndim == 2 else big[::2]
    if k == 11:
        return x[..., ::-1]
    if k == 12:  # a wrong shape
        shapes = [(2,), (4,), (1, 3, 1), (3, 1), (0, 3), (0,), (), (1, 4)]
        shape = pick(fdp, shapes)
        return np.resize(x, shape) if shape else np.float64(x.flat[0])
    if k == 13:
        return x.reshape(-1)[: fdp.ConsumeIntInRange(0, 6)].tolist()
    if k == 14:
        return pick(fdp, [None, "abc", 1.0, [[1, 2, 3], [4, 5]], {"x": 1}, [None, 1, 2]])
    y = x.copy()
    y.setflags(write=False)
    return y


def complex_imaginary(x) -> bool:
    return isinstance(x, np.ndarray) and x.dtype.kind == "c" and bool(np.any(x.imag != 0))


def check_outputs(out, n: int, single: bool, what: str) -> None:
    if not isinstance(out, dict) or set(out) != set(OUT_VECTORS + OUT_SCALARS):
        raise Finding(f"{what}: keys {sorted(out) if isinstance(out, dict) else type(out)}")
    for name in OUT_VECTORS:
        v = np.asarray(out[name])
        want = (3,) if single else (n, 3)
        if v.shape != want or v.dtype != np.float64:
            raise Finding(f"{what}: {name} has shape {v.shape} {v.dtype}, expected {want}")
    for name in OUT_SCALARS:
        v = np.asarray(out[name])
        want = () if single else (n,)
        if v.shape != want:
            raise Finding(f"{what}: {name} has shape {v.shape}, expected {want}")
    if np.asarray(out["sticks"]).dtype != np.bool_:
        raise Finding(f"{what}: sticks is {np.asarray(out['sticks']).dtype}")
    bad = []
    for name in OUT_VECTORS + ["impulse", "tangential_impulse"]:
        if not np.all(np.isfinite(out[name])):
            bad.append(name)
    throw = np.asarray(out["throw_angle_deg"])
    if np.any(np.isinf(throw)) or np.any(np.abs(throw[np.isfinite(throw)]) > 180):
        bad.append("throw_angle_deg")
    if np.any(np.asarray(out["impulse"]) < 0) or np.any(np.asarray(out["tangential_impulse"]) < 0):
        raise Finding(f"{what}: a negative impulse: {out['impulse']}, {out['tangential_impulse']}")
    if bad:
        known("non-finite output (should be a ValueError)", f"{bad} of {what}")


def resolve(fdp: atheris.FuzzedDataProvider, model) -> None:
    method = pick(fdp, METHODS) if fdp.ConsumeIntInRange(0, 3) else None
    stepping = method in ("rk4", "dopri5", "dop853")
    if stepping:
        n = fdp.ConsumeIntInRange(0, 4)
    else:
        n = pick(fdp, [0, 1, 2, 3, 7, 64]) if fdp.ConsumeIntInRange(0, 63) else 2048
    single = n == 0 and fdp.ConsumeBool()
    rows = max(n, 1)
    states = draw_states(fdp, rows, model)
    args = {name: as_argument(fdp, states[name], single) for name in ARRAY_ARGS}
    if fdp.ConsumeIntInRange(0, 3):
        del args["up"]
    kw = {}
    if method is not None or fdp.ConsumeBool():
        kw["method"] = method
    if fdp.ConsumeIntInRange(0, 3) == 0:
        r = draw_value(fdp, 1e-8)
        if stepping and isinstance(r, float) and 0 < r < 1e-12:
            r = 1e-12  # the work of one input stays bounded
        kw["rtol"] = r
    if fdp.ConsumeIntInRange(0, 3) == 0:
        kw["time_transform"] = pick(fdp, [True, False, None, 1, "no"])
    what = f"resolve_lab({args}, {kw}) of {model!r}"
    try:
        out = model.resolve_lab(**args, **kw)
    except Exception as e:  # noqa: BLE001
        refusal(e, ARRAY_ARGS + ["method", "rtol", "time_transform", "row"], what)
        return
    if any(complex_imaginary(a) for a in args.values()):
        known("complex input accepted, imaginary part dropped (should be a TypeError)", what)
    shapes = [np.shape(a) for a in args.values()]
    multi = [s[0] for s in shapes if len(s) == 2]
    check_outputs(out, multi[0] if multi else 1, not multi, what)


PLANE_ARGS = ["mass", "radius", "alpha", "mu", "restitution"]
PLANE_OUT = {"v": 3, "w": 3, "impulse": 0, "tangential_impulse": 0, "sticks": 0,
             "stick_impulse": 0}
CUSHION_ARGS = ["mass", "radius", "alpha", "height", "mu_cushion", "mu_table", "restitution",
                "rule"]
CUSHION_OUT = {"v": 3, "w": 3, "impulse": 0, "impulse_compression": 0, "impulse_table": 0,
               "work_compression": 0, "work_restitution": 0, "energy_lost": 0, "lifts_off": 0,
               "events": None, "steps": 0, "evaluations": 0}
RULES = ["stronge", "newton", "Stronge", "poisson", ""]
MINDLIN_ARGS = ["tangential", "youngs_modulus", "poisson_ratio", "plane_youngs_modulus",
                "plane_poisson_ratio", "restitution", "damping", "coefficient", "at_speed"]
MINDLIN_OUT = {"v": 3, "w": 3, "impulse": 0, "tangential_impulse": 0, "contact_time": 0,
               "rebound_angle": None}
CLUSTER_ARGS = ["balls", "mu", "youngs_modulus", "poisson_ratio", "stiffness", "damping",
                "coefficient", "restitution", "at_speed", "stick", "cloth"]


def draw_keywords(fdp: atheris.FuzzedDataProvider, plausible: dict, optional: set) -> dict:
    """Keywords near their plausible values; an optional one sometimes left out, a required
    one rarely (the refusal must name it)."""
    kw = {}
    for name, p in plausible.items():
        if name in optional and fdp.ConsumeBool():
            continue
        if fdp.ConsumeIntInRange(0, 31) == 0:
            continue
        kw[name] = draw_value(fdp, p)
    return kw


def kinetic(m: float, r: float, alpha: float, v, w) -> np.ndarray:
    v, w = np.asarray(v, float), np.asarray(w, float)
    return 0.5 * m * np.sum(v * v, axis=-1) + 0.5 * alpha * m * r * r * np.sum(w * w, axis=-1)


def energy_in(model, args: dict, out: dict):
    """The kinetic energy brought in, row by row as the call used the inputs (a (3,) input
    serves every row), or None when the inputs are not real numbers."""
    try:
        v0 = np.broadcast_to(np.asarray(args["v"], float), np.shape(out["v"]))
        w0 = np.broadcast_to(np.asarray(args["w"], float), np.shape(out["w"]))
    except (TypeError, ValueError):
        return None
    return kinetic(model.mass, model.radius, model.alpha, v0, w0)


def check_shapes(out, spec: dict, n: int, single: bool, what: str) -> None:
    if not isinstance(out, dict) or set(out) != set(spec):
        raise Finding(f"{what}: keys {sorted(out) if isinstance(out, dict) else type(out)}")
    for name, width in spec.items():
        if width is None:
            continue
        v = np.asarray(out[name])
        want = ((3,) if single else (n, 3)) if width == 3 else (() if single else (n,))
        if v.shape != want:
            raise Finding(f"{what}: {name} has shape {v.shape}, expected {want}")
        if width == 3 and v.dtype != np.float64:
            raise Finding(f"{what}: {name} is {v.dtype}")


def draw_rows(fdp: atheris.FuzzedDataProvider, n: int, names: list, plausible) -> dict:
    """n plausible rows of each named (n, 3) argument, some entries then spoiled."""
    s = {name: np.array([plausible(fdp, name) for _ in range(n)]) for name in names}
    for _ in range(fdp.ConsumeIntInRange(0, 3)):
        name = pick(fdp, names)
        i, k = fdp.ConsumeIntInRange(0, n - 1), fdp.ConsumeIntInRange(0, 2)
        s[name][i, k] = draw_float(fdp, s[name][i, k])
    return s


def plane_row(fdp: atheris.FuzzedDataProvider, name: str) -> list:
    if name == "normal":
        return list(unit(fdp))
    scale = 8.0 if name == "v" else 400.0
    return [fdp.ConsumeFloatInRange(-scale, scale) for _ in range(3)]


def cushion_row(fdp: atheris.FuzzedDataProvider, name: str) -> list:
    if name == "v":  # on the cloth, towards the cushion (x along it, y towards it)
        return [fdp.ConsumeFloatInRange(-6, 6), fdp.ConsumeFloatInRange(-0.5, 6), 0.0]
    return [fdp.ConsumeFloatInRange(-300, 300) for _ in range(3)]


def tolerance(call: dict, floor: float) -> float:
    """The relative energy a run may gain by its stepping error: `floor`, or 100 times a
    looser rtol the call asked for."""
    r = call.get("rtol")
    return max(floor, 100 * r) if isinstance(r, float) and math.isfinite(r) else floor


def draw_rtol(fdp: atheris.FuzzedDataProvider, call: dict, bounded: bool) -> None:
    """Sometimes an rtol in `call`; a stepping run's kept >= 1e-12 (bounded work)."""
    if fdp.ConsumeIntInRange(0, 3) == 0:
        r = draw_value(fdp, 1e-8)
        if bounded and isinstance(r, float) and 0 < r < 1e-12:
            r = 1e-12  # the work of one input stays bounded
        call["rtol"] = r


def resolved(model, args: dict, call: dict, names: list, spec: dict, what: str):
    """`model.resolve(**args, **call)` checked: a refusal naming an argument (None), or the
    outputs of the keys and shapes of `spec`, finite where `spec` gives a width, with the
    number of rows (None for a single impact)."""
    try:
        out = model.resolve(**args, **call)
    except Exception as e:  # noqa: BLE001
        refusal(e, names + ["method", "rtol", "row"], what)
        return None
    if any(complex_imaginary(a) for a in args.values()):
        known("complex input accepted, imaginary part dropped (should be a TypeError)", what)
    shapes = [np.shape(a) for a in args.values()]
    multi = [sh[0] for sh in shapes if len(sh) == 2]
    rows = multi[0] if multi else None
    check_shapes(out, spec, 1 if rows is None else rows, rows is None, what)
    for name, width in spec.items():
        if width is not None and name not in ("sticks", "lifts_off", "steps", "evaluations",
                                              "stick_impulse"):
            if not np.all(np.isfinite(out[name])):
                raise Finding(f"{what}: {name} is not finite: {out[name]}")
    return out, rows


def constructed(cls, kw: dict, names: list):
    """`cls(**kw)` and its repr, or None after a refusal that names a keyword."""
    try:
        model = cls(**kw)
    except Exception as e:  # noqa: BLE001
        refusal(e, names, f"{cls.__name__}({kw})")
        return None
    repr(model)
    return model


def momentum_rounding(model, args: dict, out, rtol: float = 0.0) -> np.ndarray | float:
    """The rounding of a ball's momentum, 64 eps m (|v| + r |w|) per row: a stepped tangential
    impulse comes from the change of that momentum and is known only to it (J = 2.6e-14 N s
    of a ball at 270 m/s of slip was 1e-17 N s above mu P). With `rtol`, the stepping's error
    too, 100 rtol of that momentum: the step control holds the velocities to rtol of their
    scale, and a grazing impact's J is a small part of it (J = 1.2e-5 N s of a ball at 14
    m/s and 400 rad/s, stepped by dop853 at its default rtol 1e-10, was 2e-7 of it above mu P,
    1e-12 of m (|v| + r |w|))."""
    try:
        v0 = np.broadcast_to(np.asarray(args["v"], float), np.shape(out["v"]))
        w0 = np.broadcast_to(np.asarray(args["w"], float), np.shape(out["w"]))
        scale = model.mass * (np.linalg.norm(v0, axis=-1) + model.radius * np.linalg.norm(w0, axis=-1))
    except (TypeError, ValueError):
        return 0.0
    return (64 * np.finfo(float).eps + 100 * rtol) * scale


def surface_plane(fdp: atheris.FuzzedDataProvider) -> None:
    kw = draw_keywords(fdp, {"mass": M, "radius": R, "alpha": 0.4, "mu": 0.2,
                             "restitution": 0.8}, {"alpha", "restitution"})
    if fdp.ConsumeIntInRange(0, 2) == 0:
        kw.pop("restitution", None) if fdp.ConsumeIntInRange(0, 3) else None
        kw["tangential"] = pick(fdp, ["mindlin", "mindlin", "mindlin", "rigid", "Mindlin", 1.0])
        kw.update(draw_keywords(fdp, {"youngs_modulus": 5.4e9, "poisson_ratio": 0.34,
                                      "plane_youngs_modulus": 2e11, "plane_poisson_ratio": 0.3},
                                {"plane_youngs_modulus", "plane_poisson_ratio"}))
        if fdp.ConsumeIntInRange(0, 2) == 0:
            kw["damping"] = pick(fdp, ["hunt-crossley", "kuwabara-kono", None, "x"])
            kw.update(draw_keywords(fdp, {"coefficient": 0.05, "at_speed": 3.9,
                                          "restitution": 0.8},
                                    {"coefficient", "at_speed", "restitution"}))
    model = constructed(bc.BallPlane, kw, PLANE_ARGS + MINDLIN_ARGS)
    if model is None:
        return
    if model.tangential == "mindlin":
        surface_plane_mindlin(fdp, model, kw)
        return
    method = pick(fdp, METHODS) if fdp.ConsumeIntInRange(0, 3) == 0 else None
    stepping = method in ("rk4", "dopri5", "dop853", "closed-form")
    n = fdp.ConsumeIntInRange(1, 4) if stepping else pick(fdp, [1, 2, 3, 7, 64, 2048])
    single = n == 1 and fdp.ConsumeBool()
    rows = draw_rows(fdp, n, ["v", "w", "normal"], plane_row)
    args = {name: as_argument(fdp, a, single) for name, a in rows.items()}
    call = {} if method is None else {"method": method}
    draw_rtol(fdp, call, stepping)
    what = f"BallPlane({kw}).resolve({args}, {call})"
    got = resolved(model, args, call, ["v", "w", "normal"] + PLANE_ARGS, PLANE_OUT, what)
    if got is None:
        return
    out, _ = got
    p, j = np.asarray(out["impulse"]), np.asarray(out["tangential_impulse"])
    if np.any(p < 0) or np.any(j < 0):
        raise Finding(f"{what}: a negative impulse: {p}, {j}")
    # Coulomb: J <= mu P (to rounding; a stepping method to its tolerance).
    stepped = call.get("method") in ("rk4", "dopri5", "dop853")
    r = call.get("rtol")
    rtol = r if isinstance(r, float) and math.isfinite(r) and r > 0 else 1e-10  # the default
    rounding = (momentum_rounding(model, args, out, rtol if stepped else 0.0)
                if "method" in call else 0.0)
    if np.any(j > model.mu * p * (1 + tolerance(call, 1e-9)) + rounding + 1e-300):
        raise Finding(f"{what}: friction impulse {j} above mu P = {model.mu * p}")
    # No energy created (e <= 1); both states as the call used them, rows broadcast.
    k0 = energy_in(model, args, out)
    if k0 is None:
        return
    k1 = kinetic(model.mass, model.radius, model.alpha, out["v"], out["w"])
    if np.any(k1 > k0 * (1 + tolerance(call, 1e-9)) + 1e-300):
        raise Finding(f"{what}: kinetic energy created: {k0} -> {k1}")


def surface_plane_mindlin(fdp: atheris.FuzzedDataProvider, model, kw: dict) -> None:
    """The compliant plane: elastic or damped, so no energy created (to its tolerance); the
    tangential impulse within Coulomb's mu P (the spring's force is capped at mu F_n at every
    instant)."""
    n = pick(fdp, [1, 1, 2, 3])
    single = n == 1 and fdp.ConsumeBool()
    rows = draw_rows(fdp, n, ["v", "w", "normal"], plane_row)
    args = {name: as_argument(fdp, a, single) for name, a in rows.items()}
    call = {}
    if fdp.ConsumeIntInRange(0, 7) == 0:
        call["method"] = pick(fdp, [None, "dop853"])
    draw_rtol(fdp, call, True)
    what = f"BallPlane({kw}).resolve({args}, {call})"
    got = resolved(model, args, call, ["v", "w", "normal"] + PLANE_ARGS + MINDLIN_ARGS,
                   MINDLIN_OUT, what)
    if got is None:
        return
    out, _ = got
    p, j = np.asarray(out["impulse"]), np.asarray(out["tangential_impulse"])
    if np.any(p < 0) or np.any(j < 0):
        raise Finding(f"{what}: a negative impulse: {p}, {j}")
    # The compliant kernel's J is a stepped one (with mu below 1e-20 stepped as none, J = 5e-16
    # N s of rounding against mu P = 2e-323 N s).
    rounding = momentum_rounding(model, args, out)
    if np.any(j > model.mu * p * (1 + tolerance(call, 1e-6)) + rounding + 1e-300):
        raise Finding(f"{what}: friction impulse {j} above mu P = {model.mu * p}")
    k0 = energy_in(model, args, out)
    if k0 is None:
        return
    k1 = kinetic(model.mass, model.radius, model.alpha, out["v"], out["w"])
    if np.any(k1 > k0 * (1 + tolerance(call, 1e-6)) + 1e-300):
        raise Finding(f"{what}: kinetic energy created: {k0} -> {k1}")


def cluster_states(fdp: atheris.FuzzedDataProvider, balls: list, cloth: bool = False) -> dict:
    """Balls in a touching line along x (or a zig-zag), the first struck along +x, some
    entries spoiled; sometimes gaps, spins and sideways velocities. On a cloth every centre
    starts at z = r (the cloth at height 0)."""
    n = len(balls)
    radii = [b.radius if isinstance(b, bc.Ball) else R for b in balls]
    p = np.zeros((n, 3))
    if cloth:
        p[:, 2] = radii
    for i in range(1, n):
        d = radii[i - 1] + radii[i]
        angle = fdp.ConsumeFloatInRange(-1.0, 1.0) if fdp.ConsumeIntInRange(0, 2) == 0 else 0.0
        gap = fdp.ConsumeFloatInRange(0.0, 0.01) if fdp.ConsumeIntInRange(0, 3) == 0 else 0.0
        p[i] = p[i - 1] + (d + gap) * np.array([math.cos(angle), math.sin(angle), 0.0])
    v = np.zeros((n, 3))
    v[0, 0] = fdp.ConsumeFloatInRange(0.01, 8.0)
    w = np.zeros((n, 3))
    for i in range(n):
        if fdp.ConsumeIntInRange(0, 3) == 0:
            v[i] += [fdp.ConsumeFloatInRange(-1, 1) for _ in range(3)]
        if fdp.ConsumeIntInRange(0, 2) == 0:
            w[i] = [fdp.ConsumeFloatInRange(-300, 300) for _ in range(3)]
    s = {"positions": p, "velocities": v, "spins": w}
    for _ in range(fdp.ConsumeIntInRange(0, 2) if fdp.ConsumeIntInRange(0, 3) == 0 else 0):
        name = pick(fdp, list(s))
        i, k = fdp.ConsumeIntInRange(0, n - 1), fdp.ConsumeIntInRange(0, 2)
        s[name][i, k] = draw_float(fdp, s[name][i, k])
    return s


def surface_cluster(fdp: atheris.FuzzedDataProvider) -> None:
    """bc.Cluster: a refusal naming an argument, or velocities and spins whose momentum is
    the incoming one (to the step control's rounding), contacts that push (P >= 0), within
    Coulomb's cone, with heat >= 0, and kinetic energy out plus heat = energy in."""
    n = pick(fdp, [2, 2, 3, 3, 4, 5]) if fdp.ConsumeIntInRange(0, 15) else pick(fdp, [0, 1, 23])
    balls = []
    for _ in range(n):
        if fdp.ConsumeIntInRange(0, 31) == 0:
            balls.append(pick(fdp, [1.0, None, "ball"]))
        elif fdp.ConsumeIntInRange(0, 3) == 0:
            balls.append(draw_ball(fdp) or bc.Ball(mass=M, radius=R))
        else:
            balls.append(bc.Ball(mass=M, radius=R))
    kw = {"balls": balls}
    kw.update(draw_keywords(fdp, {"mu": 0.06}, set()))
    if fdp.ConsumeIntInRange(0, 3):
        kw.update(draw_keywords(fdp, {"youngs_modulus": 5.4e9, "poisson_ratio": 0.34}, set()))
    else:
        kw.update(draw_keywords(fdp, {"stiffness": 4.5e8}, set()))
    k = fdp.ConsumeIntInRange(0, 3)
    if k:
        kw["damping"] = pick(fdp, ["hunt-crossley", "kuwabara-kono", None, "x"])
        if k == 1:
            kw.update(draw_keywords(fdp, {"coefficient": 0.05}, set()))
        else:
            kw.update(draw_keywords(fdp, {"restitution": 0.93, "at_speed": 1.0}, set()))
    if fdp.ConsumeIntInRange(0, 7) == 0:
        kw["stick"] = pick(fdp, [False, True, 1.0])
    if fdp.ConsumeIntInRange(0, 3) == 0:
        # The cloth: the bed's material, mu and gravity, sometimes a key spoiled or unknown.
        cloth = {"youngs_modulus": 5e10, "poisson_ratio": 0.25, "height": 0.0}
        cloth.update(draw_keywords(fdp, {"mu": 0.2}, set()))
        if fdp.ConsumeIntInRange(0, 7) == 0:
            key = pick(fdp, ["youngs_modulus", "poisson_ratio", "gravity", "height", "muu"])
            cloth[key] = draw_float(fdp, cloth.get(key, 1.0))
        if fdp.ConsumeIntInRange(0, 15) == 0:
            cloth.pop(pick(fdp, ["youngs_modulus", "poisson_ratio"]))
        kw["cloth"] = cloth if fdp.ConsumeIntInRange(0, 31) else pick(fdp, [1.0, "cloth", [1]])
    what = f"Cluster({kw})"
    model = constructed(bc.Cluster, kw, CLUSTER_ARGS)
    if model is None:
        return
    sticks = kw.get("stick", True) is not False
    cloth = kw.get("cloth")
    states = cluster_states(fdp, model.balls, cloth is not None)
    call = {}
    draw_rtol(fdp, call, True)
    if isinstance(call.get("rtol"), float) and 0 < call["rtol"] < 1e-10:
        call["rtol"] = 1e-10  # the work of one input stays bounded
    resolved_and_checked(model, kw, states, call, what, sticks)
    # Then the same balls on a damped bed, from the bytes left (drawn last, so that the
    # inputs kept before the cloth's damping existed keep their meaning).
    if isinstance(cloth, dict) and fdp.remaining_bytes() > 0:
        cloth = dict(cloth)
        cloth["damping"] = pick(fdp, ["hunt-crossley", "kuwabara-kono", None, "viscous"])
        if fdp.ConsumeBool():
            cloth.update(draw_keywords(fdp, {"restitution": 0.5, "at_speed": 1.0}, set()))
        else:
            base = 0.5 if cloth["damping"] == "hunt-crossley" else 2e-5
            cloth.update(draw_keywords(fdp, {"coefficient": base}, set()))
        kw = dict(kw, cloth=cloth)
        what = f"Cluster({kw})"
        model = constructed(bc.Cluster, kw, CLUSTER_ARGS)
        if model is not None:
            resolved_and_checked(model, kw, states, call, what, sticks)


def resolved_and_checked(model, kw: dict, states: dict, call: dict, what: str,
                         sticks: bool) -> None:
    """`model.resolve(**states, **call)` and its promises (the cluster surface's)."""
    cloth = kw.get("cloth")
    what += f".resolve({states}, {call})"
    try:
        out = model.resolve(**states, **call)
    except RuntimeError as e:
        if "the cluster's run stopped" not in str(e):
            raise Finding(f"{what}: {type(e).__name__}: {e}") from e
        # A stiffness so large (E = 1e60 Pa) that the compression is lost in the rounding of
        # the positions, or a tight rack, stops the run: counted until refused up front.
        known("cluster: the run stopped (work bound or step too small)", what)
        return
    except Exception as e:  # noqa: BLE001
        refusal(e, ["positions", "velocities", "spins", "balls", "rtol", "coefficient", "cloth"],
                what)
        return
    nb = len(model.balls)
    for name in ("velocities", "spins", "positions"):
        a = np.asarray(out[name])
        if a.shape != (nb, 3) or not np.all(np.isfinite(a)):
            raise Finding(f"{what}: {name} {a!r}")
    m = np.array([b.mass for b in model.balls])
    r = np.array([b.radius for b in model.balls])
    inertia = np.array([b.alpha for b in model.balls]) * m * r * r
    v0, w0 = states["velocities"], states["spins"]
    v1, w1 = out["velocities"], out["spins"]
    scale = float(np.sum(m * np.linalg.norm(v0, axis=1)))
    # The scale the steps hold a friction impulse to: the momenta and the spins' contact-point
    # speeds, m (|v| + r |w|) in and out, as the Rust target (on the momentum alone, five
    # slow balls at 1 cm/s spinning at 300 rad/s were allowed 1.7e-9 N s, and a contact of
    # 6.3e-7 N s ended 1.6e-8 N s past mu P: 4e-9 of the 4.5 N s their spins carry).
    friction_scale = float(np.sum(m * (np.linalg.norm(v0, axis=1) + np.linalg.norm(v1, axis=1)
                                       + r * (np.linalg.norm(w0, axis=1)
                                              + np.linalg.norm(w1, axis=1)))))
    # On a cloth the momentum changes by the cloth's impulses (up, and its friction) and the
    # weights' over the run; each cloth friction within mu_c of its normal impulse.
    external = np.zeros(3)
    if cloth is not None:
        # A key given as None is its default (as the package reads it), and a NumPy scalar
        # its value as a double (a float16 mu made the harness's own cap float16).
        g = 9.81 if cloth.get("gravity") is None else float(cloth["gravity"])
        mu_cloth = 0.2 if cloth.get("mu") is None else float(cloth["mu"])
        for c in out["cloth_contacts"]:
            external += np.asarray(c["friction_impulse"]) + np.array([0.0, 0.0, c["impulse"]])
            scale += abs(c["impulse"]) + float(np.linalg.norm(c["friction_impulse"]))
            # A stepped state, as the balls' friction impulses: within rtol of the friction
            # scale a step (100 steps' worth); the cloth's impulses are small beside the
            # balls' (mu_c m g over 50 us: 1.9e-6 N s of 1.2 N s was 4.9e-7 past mu P; three
            # resin balls, the first spinning at 413 rad/s, a cloth contact 4.6e-8 N s past
            # it, within the 2 N s of that spin's m r |w|).
            cap = mu_cloth * max(c["impulse"], 0.0)
            rtol_c = call.get("rtol") if isinstance(call.get("rtol"), float) else 1e-8
            allowed = cap * (1 + 1e-6) + 100 * rtol_c * (scale + friction_scale)
            if np.linalg.norm(c["friction_impulse"]) > allowed:
                raise Finding(f"{what}: cloth friction above mu P: {c}")
        external[2] -= float(np.sum(m)) * g * out["time"]
    if np.any(np.abs(m @ v1 - m @ v0 - external) > 1e-9 * scale + 1e-300):
        raise Finding(f"{what}: momentum {m @ v0} -> {m @ v1} (outside {external})")
    k0 = 0.5 * float(np.sum(m * np.sum(v0 * v0, 1)) + np.sum(inertia * np.sum(w0 * w0, 1)))
    k1 = 0.5 * float(np.sum(m * np.sum(v1 * v1, 1)) + np.sum(inertia * np.sum(w1 * w1, 1)))
    heat = 0.0
    # The energy balance to 1e3 rtol (1e-5 at the default 1e-8), as the Rust target holds it:
    # heavy Kuwabara-Kono damping (gamma = 0.05 s) balanced to 2e-6 of the energy. A long run
    # adds up its steps' errors: a quarter of rtol a step past 4000 steps (five spinning
    # rubber balls on the cloth, 17.7 s in 21,027 steps at rtol 1e-8, hopping 574 times, were
    # 1.2e-5 of the energy off their balance with the cloth's and gravity's store, 0.057
    # rtol a step; at rtol 1e-10, 57,942 steps, 0.026 rtol a step).
    r = call.get("rtol")
    rtol = r if isinstance(r, float) and math.isfinite(r) and r > 0 else 1e-8
    tol = max(1e-5, 1e3 * rtol, 0.25 * rtol * out["steps"])
    # Each pair's heat over its records, summed once (a run can hold 18,000 records: summed
    # per record, the check took 107 s of a 0.45 s run).
    pair_heats: dict = {}
    for d in out["contacts"]:
        key = tuple(d["pair"])
        pair_heats[key] = pair_heats.get(key, 0.0) + d["heat"]
    for c in out["contacts"]:
        i, j = c["pair"]
        # The impulse is a state of the stepping: a contact that closes at zero compression
        # between balls moving together carries rounding (-1.3e-17 N s of 0.3 N s of
        # momentum), so it is >= 0 to the rounding of the momentum.
        if not (0 <= i < j < nb) or not c["impulse"] >= -1e-12 * scale:
            raise Finding(f"{what}: contact {c}")
        # Without the stick rule friction keeps its direction past the stop of the slip and
        # works against the reversed slip (the two-ball law's stick=False, eq 57): heat < 0.
        # A Kuwabara-Kono contact opens at zero force while its surfaces still overlap; a
        # pair that closes again before they part starts its next record with that overlap,
        # whose heat can then be negative: the promise is the pair's, over its records (as
        # the Rust target holds it).
        if kw.get("damping") == "kuwabara-kono":
            pair_heat = pair_heats[(i, j)]
            if sticks and not pair_heat >= -tol * k0:
                raise Finding(f"{what}: a pair's heat below zero ({pair_heat}): {c}")
        elif sticks and not c["heat"] >= -tol * k0:
            raise Finding(f"{what}: a contact's heat below zero: {c}")
        cap = model.mu * max(c["impulse"], 0.0)
        excess = np.linalg.norm(c["friction_impulse"]) - cap - 1e-12 * scale
        # The friction impulse is a stepped state: its error is rtol on the momentum scale
        # a step, as the Rust target allows (100 steps' worth).
        if excess > 1e-6 * cap + 100 * rtol * (scale + friction_scale):
            raise Finding(f"{what}: friction outside Coulomb's cone: {c}")
        heat += c["heat"]
    if cloth is not None:
        # What the cloth and gravity hold at the end: each ball's V(delta_out) - V(delta_s),
        # V(delta) = (2/5) k max(delta, 0)^(5/2) - m g delta, delta = r - (z - height) +
        # delta_s its compression of the cloth (a ball resting at its input height compresses
        # it by delta_s, k delta_s^(3/2) = m g), k = (4/3) E* sqrt(r) with 1/E* the sum of
        # (1 - nu^2) / E of the bed and of the balls' material (none when one stiffness is
        # given: the ball counts as rigid against the bed). K_in = K_out + heat + held, both
        # ways, to tol of the energy with the cloth's store under the weights, sum m g
        # delta_s, through which the balls' vertical motion passes (as the Rust target).
        heat += sum(c["heat"] for c in out["cloth_contacts"])
        bed = (1 - float(cloth["poisson_ratio"]) ** 2) / float(cloth["youngs_modulus"])
        ball = 0.0
        if kw.get("youngs_modulus") is not None and kw.get("poisson_ratio") is not None:
            ball = (1 - float(kw["poisson_ratio"]) ** 2) / float(kw["youngs_modulus"])
        height = 0.0 if cloth.get("height") is None else float(cloth["height"])
        held = store = 0.0
        for i in range(nb):
            radius = model.balls[i].radius
            k = 4.0 / 3.0 / (bed + ball) * math.sqrt(radius)
            weight = m[i] * g
            ds = (weight / k) ** (2.0 / 3.0)
            store += weight * ds

            def v(d: float) -> float:
                return 0.4 * k * max(d, 0.0) ** 2.5 - weight * d

            held += v(radius - (float(out["positions"][i][2]) - height) + ds) - v(ds)
        big = max(k0, k1, abs(heat)) + store
        if (sticks and k1 > k0 + tol * (k0 + store)) or abs(k0 - k1 - heat - held) > tol * big:
            raise Finding(f"{what}: energy {k0} -> {k1} with heat {heat} and {held} held by "
                          f"the cloth (store {store})")
        return
    big = max(k0, k1, abs(heat))
    if (sticks and k1 > k0 * (1 + tol)) or abs(k0 - k1 - heat) > tol * big + 1e-300:
        raise Finding(f"{what}: energy {k0} -> {k1} with heat {heat}")


def surface_cushion(fdp: atheris.FuzzedDataProvider) -> None:
    kw = draw_keywords(fdp, {"mass": M, "radius": R, "alpha": 0.4, "height": 1.4 * R,
                             "mu_cushion": 0.2, "mu_table": 0.2, "restitution": 0.9},
                       {"alpha"})
    if fdp.ConsumeIntInRange(0, 3) == 0:
        kw["rule"] = pick(fdp, RULES) if fdp.ConsumeIntInRange(0, 7) else 1.0
    model = constructed(bc.BallCushion, kw, CUSHION_ARGS)
    if model is None:
        return
    n = pick(fdp, [1, 1, 2, 3, 64]) if fdp.ConsumeIntInRange(0, 15) else 1
    single = n == 1 and fdp.ConsumeBool()
    rows = draw_rows(fdp, n, ["v", "w"], cushion_row)
    args = {name: as_argument(fdp, a, single) for name, a in rows.items()}
    call = {}
    if fdp.ConsumeIntInRange(0, 3) == 0:
        call["method"] = pick(fdp, [None, "dop853", "dopri5", "rk4", "closed-form", ""])
    draw_rtol(fdp, call, True)
    if fdp.ConsumeIntInRange(0, 7) == 0:
        call["steps"] = pick(fdp, [None, 1, 10, 1000, 0, -1, 10**12, 2.5, "x"])
    what = f"BallCushion({kw}).resolve({args}, {call})"
    # A refusal of the impact may name a keyword of the model (friction that wedges the
    # ball names mu_cushion).
    got = resolved(model, args, call, ["v", "w", "steps"] + CUSHION_ARGS, CUSHION_OUT, what)
    if got is None:
        return
    out, rows = got
    events = out["events"]
    if not isinstance(events, list) or (rows is not None and len(events) != rows):
        raise Finding(f"{what}: events {events!r}")
    for name in ("impulse", "impulse_compression", "impulse_table", "work_compression",
                 "work_restitution"):
        if np.any(np.asarray(out[name]) < 0):
            raise Finding(f"{what}: {name} < 0: {out[name]}")
    if model.rule == "stronge":
        k0 = energy_in(model, args, out)
        if k0 is not None and np.any(np.asarray(out["energy_lost"]) < -tolerance(call, 1e-7) * k0 - 1e-300):
            raise Finding(f"{what}: energy created: lost {out['energy_lost']} of {k0}")


def load_package() -> None:
    """Imports billiard_contact once libFuzzer runs (the first input): atheris loads its
    libFuzzer with local symbols, made global here (RTLD_NOLOAD only promotes the loaded
    copy) so that an extension instrumented for coverage links its hooks to it."""
    global bc
    for core in glob.glob(os.path.join(os.path.dirname(atheris.__file__), "core_with_libfuzzer*.so")):
        try:
            ctypes.CDLL(core, mode=os.RTLD_GLOBAL | os.RTLD_NOLOAD)
        except OSError:
            pass
    with atheris.instrument_imports(include=["billiard_contact"]):
        import billiard_contact

    bc = billiard_contact


def test_one_input(data: bytes) -> None:
    if bc is None:
        load_package()
    fdp = atheris.FuzzedDataProvider(data)
    surface = fdp.ConsumeIntInRange(0, 13)
    if surface in (12, 13):
        surface_cluster(fdp)
        return
    if surface in (8, 9):
        surface_plane(fdp)
        return
    if surface in (10, 11):
        surface_cushion(fdp)
        return
    if surface == 0:
        draw_ball(fdp)
        return
    if surface == 1:
        draw_friction(fdp)
        return
    model, _ = draw_model(fdp)
    if model is None:
        return
    if surface == 2:
        for attr in ("mass", "radius", "alpha", "a", "b", "mu", "restitution"):
            getattr(model, attr)
        repr(model)
        return
    resolve(fdp, model)


def main() -> None:
    # The harness's own branches guide too (which refusal, which output check).
    here = sys.modules[__name__]
    for name, f in list(vars(here).items()):
        if inspect.isfunction(f) and f.__module__ == __name__ and name != "main":
            setattr(here, name, atheris.instrument_func(f))
    atheris.Setup(sys.argv, here.test_one_input)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
