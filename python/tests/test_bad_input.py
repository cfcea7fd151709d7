"""Bad input raises ValueError with the command's one-line message, naming the field
(and the row, for arrays of states); nothing panics across the boundary."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import billiard_contact as bc
from conftest import SCENES, cli_error

M, R = 0.170097, 0.028575
DEFAULT = (SCENES[0].parent / "default.toml").read_text()


def scene_with(tmp_path, old: str, new: str):
    assert old in DEFAULT
    p = tmp_path / "bad.toml"
    p.write_text(DEFAULT.replace(old, new))
    return p


@pytest.mark.parametrize(
    "kwargs,old,new,field",
    [
        (dict(mass=-1.0), "mass = 0.17", "mass = -1.0", "balls.mass"),
        (dict(radius=0.0), "radius = 0.028575", "radius = 0.0", "balls.radius"),
        (dict(alpha=0.7), "alpha = 0.4", "alpha = 0.7", "balls.alpha"),
        (dict(mu=-0.1), "mu = 0.06", "mu = -0.1", "contact.mu"),
        (dict(mu=2e6), "mu = 0.06", "mu = 2e6", "contact.mu"),
        (dict(restitution=1.5), "restitution = 1.0", "restitution = 1.5", "contact.restitution"),
        (dict(mass=math.nan), "mass = 0.17", "mass = nan", "balls.mass"),
        (dict(radius=math.inf), "radius = 0.028575", "radius = inf", "balls.radius"),
        (dict(duration=-1e-4), "duration = 2.5e-4", "duration = -1e-4", "duration"),
    ],
)
def test_model_parameters_give_the_cli_message(cli, tmp_path, kwargs, old, new, field):
    params = dict(mass=0.17, radius=0.028575, alpha=0.4, mu=0.06, restitution=1.0)
    params.update(kwargs)
    with pytest.raises(ValueError) as e:
        bc.BallBall(**params)
    expected = cli_error(cli, "run", str(scene_with(tmp_path, old, new)))
    assert str(e.value) == expected
    assert field in str(e.value)


@pytest.mark.parametrize(
    "abc,field",
    [((-1.0, 0.1, 1.0), "contact.mu.a"), ((0.01, math.nan, 1.0), "contact.mu.b"), ((0.01, 0.1, -2.0), "contact.mu.c")],
)
def test_speed_dependent_friction_gives_the_cli_message(cli, tmp_path, abc, field):
    a, b, c = abc
    with pytest.raises(ValueError) as e:
        bc.SpeedDependentFriction(a=a, b=b, c=c)
    toml = lambda x: "nan" if math.isnan(x) else repr(x)
    bad = scene_with(
        tmp_path, "mu = 0.06",
        f'mu = {{ model = "speed-dependent", a = {toml(a)}, b = {toml(b)}, c = {toml(c)} }}',
    )
    assert str(e.value) == cli_error(cli, "run", str(bad))
    assert str(e.value).startswith(field)


def test_evaluate_names_the_choices():
    with pytest.raises(
        ValueError,
        match=r'^evaluate = "start": "along-contact" .* or "initial" .*; also "contact" and "initial-slip"$',
    ):
        bc.SpeedDependentFriction(a=0.01, b=0.1, c=1.0, evaluate="start")


def test_wrong_types_raise_type_error():
    with pytest.raises(TypeError, match="mu"):
        bc.BallBall(mass=M, radius=R, mu="0.06")
    with pytest.raises(TypeError):
        bc.BallBall(mass="heavy", radius=R, mu=0.06)


def test_run_errors_give_the_cli_message(cli, tmp_path):
    bad = scene_with(tmp_path, "restitution", "restitutoin")
    with pytest.raises(ValueError) as e:
        bc.run(str(bad))
    assert str(e.value) == cli_error(cli, "run", str(bad))
    assert "did you mean `restitution`" in str(e.value)
    default = str(SCENES[0].parent / "default.toml")
    with pytest.raises(ValueError) as e:
        bc.run(default, method="rk5")
    # The keyword is not the command's `--method` option (whose message clap words): the
    # library's message names the value and every accepted method.
    assert str(e.value) == 'solver.method = "rk5": one of closed-form, rk4, dopri5, dop853'
    assert "rk5" in cli_error(cli, "run", default, "--method", "rk5")
    with pytest.raises(ValueError) as e:
        bc.run(default, rtol=1.0)
    assert str(e.value) == cli_error(cli, "run", default, "--rtol", "1.0")
    missing = str(tmp_path / "missing.toml")
    with pytest.raises(ValueError) as e:
        bc.run(missing)
    assert str(e.value) == cli_error(cli, "run", missing)
    with pytest.raises(ValueError, match=r"^samples = 0: at least 1$"):
        bc.run(default, samples=0)


def test_run_toml_names_the_text_and_line():
    with pytest.raises(ValueError) as e:
        bc.run_toml(DEFAULT.replace("restitution", "restitutoin"))
    msg = str(e.value)
    assert msg.startswith("<toml text>: line ") and "contact.restitutoin: unknown key" in msg


def states(n):
    pa = np.tile([0.0, 0.0, R], (n, 1))
    pb = np.tile([2 * R, 0.0, R], (n, 1))
    va = np.tile([1.0, 0.2, 0.0], (n, 1))
    z = np.zeros((n, 3))
    return [pa, va, z.copy(), pb, z.copy(), z.copy()]


@pytest.mark.parametrize(
    "arg,row,col,value,message",
    [
        (1, 7, 1, math.nan, r"^row 7: va\[1\] = NaN: a finite number$"),
        (5, 0, 2, math.inf, r"^row 0: wb\[2\] = inf: a finite number$"),
        (3, 4999, 0, 3 * R, r"^row 4999: pb = \[0\.085725, 0, 0\.028575\] \(\|pb - pa\| = 0\.085725 m\): the balls must touch: \|pb - pa\| = 2r = 0\.05715 m within a relative 1e-9$"),
    ],
)
def test_bad_rows_are_named(arg, row, col, value, message):
    model = bc.BallBall(mass=M, radius=R, mu=0.06)
    a = states(5000)  # above the size resolved without the GIL on all cores
    a[arg][row, col] = value
    with pytest.raises(ValueError, match=message):
        model.resolve_lab(*a)
    few = [x[: row + 1] if len(x) > row else x for x in a]
    with pytest.raises(ValueError, match=message):
        model.resolve_lab(*few)


def test_the_first_bad_row_is_named():
    model = bc.BallBall(mass=M, radius=R, mu=0.06)
    a = states(10_000)
    for row in (9_000, 6_000, 3_001):
        a[1][row, 0] = math.nan
    with pytest.raises(ValueError, match=r"^row 3001: va\[0\] = NaN"):
        model.resolve_lab(*a)


def test_one_collision_is_not_called_a_row():
    model = bc.BallBall(mass=M, radius=R, mu=0.06)
    with pytest.raises(ValueError, match=r"^up = \[0, 0, 0\]: a non-zero direction$"):
        model.resolve_lab([0, 0, R], [1, 0, 0], [0, 0, 0], [2 * R, 0, R], [0, 0, 0], [0, 0, 0], up=[0, 0, 0])


def test_bad_shapes_and_methods():
    model = bc.BallBall(mass=M, radius=R, mu=0.06)
    a = states(4)
    with pytest.raises(ValueError, match=r"^wa has shape \(4, 2\): expected \(3,\) or \(N, 3\)$"):
        model.resolve_lab(a[0], a[1], np.zeros((4, 2)), a[3], a[4], a[5])
    with pytest.raises(ValueError, match=r"^pb has 5 rows but pa has 4"):
        model.resolve_lab(a[0], a[1], a[2], states(5)[3], a[4], a[5])
    with pytest.raises(ValueError, match=r"^vb has shape \(\): expected"):
        model.resolve_lab(a[0], a[1], a[2], a[3], 0.0, a[5])
    with pytest.raises(ValueError, match=r'^solver\.method = "euler": one of closed-form, rk4, dopri5, dop853$'):
        model.resolve_lab(*a, method="euler")
    with pytest.raises(ValueError, match=r"^solver\.rtol = 0: in \[1e-15, 0\.1\]"):
        model.resolve_lab(*a, method="dop853", rtol=0.0)
    with pytest.raises(TypeError, match=r"^wb has dtype <U\d+: expected real numbers"):
        model.resolve_lab(a[0], a[1], a[2], a[3], a[4], [[1, 2, "x"]] * 4)


TOUCHING = ([0.0, 0.0, R], [2 * R, 0.0, R])


@pytest.mark.parametrize(
    "arg,value,shown",
    [
        ("va", np.array([1.0, 0.0, 1e-3j]), "complex128"),
        ("wa", np.array([0, 0, 0], dtype=np.complex64), "complex64"),
        ("vb", np.array([0.0, 0.0, 0.0], dtype=object), "object"),
        ("pb", np.array(["0.05715", "0", "0.028575"]), "<U8"),
        ("wb", [0, 0, 1j], "complex128"),
        ("pa", [0, None, R], "object"),
        ("up", np.array([0, 0, 1], dtype="m8[s]"), "timedelta64[s]"),
        ("wa", np.zeros(3, dtype="V8"), "|V8"),
    ],
)
def test_non_real_arrays_raise_type_error_naming_the_argument(arg, value, shown):
    model = bc.BallBall(mass=M, radius=R, mu=0.06)
    pa, pb = TOUCHING
    args = dict(pa=pa, va=[1.0, 0, 0], wa=[0, 0, 0], pb=pb, vb=[0, 0, 0], wb=[0, 0, 0])
    args[arg] = value
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpy's ComplexWarning would mean a quiet cast
        with pytest.raises(TypeError) as e:
            model.resolve_lab(**args)
    assert str(e.value) == (
        f"{arg} has dtype {shown}: expected real numbers (a float, integer or bool array)"
    )
    # The same in a batch of rows.
    rows = {k: np.broadcast_to(np.asarray(v), (4, 3)) for k, v in args.items()}
    with pytest.raises(TypeError, match=f"^{arg} has dtype "):
        model.resolve_lab(**rows)


def test_what_numpy_cannot_convert_is_named():
    # A ragged list, or an object numpy cannot make an array of, raises numpy's own error
    # with the argument's name in front (found by the Python fuzz target: BallCushion's v
    # = [[1, 2, 3], [4, 5]] raised "setting an array element with a sequence..." alone).
    cushion = bc.BallCushion(mass=M, radius=R, height=1.4 * R, mu_cushion=0.2, mu_table=0.2, restitution=0.9)
    plane = bc.BallPlane(mass=M, radius=R, mu=0.2)
    model = bc.BallBall(mass=M, radius=R, mu=0.06)
    pa, pb = TOUCHING
    ragged = [[1, 2, 3], [4, 5]]
    for call, name in [
        (lambda: cushion.resolve(ragged, [0, 0, 0]), "v"),
        (lambda: cushion.resolve([0, 1, 0], ragged), "w"),
        (lambda: plane.resolve([0, 0, -1], [0, 0, 0], ragged), "normal"),
        (lambda: model.resolve_lab(pa, ragged, [0, 0, 0], pb, [0, 0, 0], [0, 0, 0]), "va"),
    ]:
        with pytest.raises(ValueError) as e:
            call()
        assert str(e.value).startswith(f"{name}: setting an array element with a sequence"), str(e.value)
        assert "\n" not in str(e.value)


@pytest.mark.parametrize("dtype", [bool, np.int8, np.uint16, np.int32, np.int64, np.float16, np.float32, ">f8", np.longdouble])
def test_bool_integer_and_other_float_arrays_are_accepted(dtype):
    model = bc.BallBall(mass=M, radius=R, mu=0.06)
    pa, pb = TOUCHING
    as_float = dict(pa=pa, va=[1.0, 0, 0], wa=[0.0, 1.0, 0], pb=pb, vb=[0.0, 0, 0], wb=[0.0, 0, 1.0])
    # The velocities and spins are 0 or 1: exact in every dtype.
    typed = {k: (np.asarray(v, dtype=dtype) if k[0] in "vw" else v) for k, v in as_float.items()}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = model.resolve_lab(**typed)
    want = model.resolve_lab(**as_float)
    for k in want:
        np.testing.assert_array_equal(got[k], want[k])


HEAVY = dict(mass=1e300, radius=R, mu=0.06, restitution=1.0)


def test_an_overflowing_collision_raises_value_error_naming_the_output():
    # m v = 1e310 overflows: the impulse, then the velocities, are infinite or NaN.
    model = bc.BallBall(**HEAVY)
    pa, pb = TOUCHING
    with pytest.raises(ValueError, match=r"^va\[0\] = -?inf: the result is not finite") as e:
        model.resolve_lab(pa, [1e10, 0, 0], [0, 0, 0], pb, [0, 0, 0], [0, 0, 0])
    assert "row" not in str(e.value)
    # Time stepping refuses such scales before it starts.
    with pytest.raises(ValueError, match=r"^incoming = .*finite"):
        model.resolve_lab(pa, [1e10, 0, 0], [0, 0, 0], pb, [0, 0, 0], [0, 0, 0], method="rk4")
    # The same collision at an ordinary speed is finite: the model itself is fine.
    out = model.resolve_lab(pa, [1.0, 0, 0], [0, 0, 0], pb, [0, 0, 0], [0, 0, 0])
    assert all(np.isfinite(out[k]).all() for k in ("va", "wa", "vb", "wb", "impulse"))


@pytest.fixture(params=[True, False], ids=["per-chunk", "one-pass"])
def output_check(request):
    """Both ways resolve_lab checks its outputs (once per chunk of 1024 rows, the default;
    one pass after all rows, the benchmark's comparison) give the same errors."""
    before = bc._core._check_outputs_per_chunk(request.param)
    yield request.param
    bc._core._check_outputs_per_chunk(before)


# with the GIL (one chunk, two), and on all cores (the bad row in the fifth chunk)
@pytest.mark.parametrize("n,bad", [(5, 3), (1500, 1100), (5000, 4321)])
def test_an_overflowing_row_is_named(n, bad, output_check):
    model = bc.BallBall(**HEAVY)
    pa = np.tile(TOUCHING[0], (n, 1))
    pb = np.tile(TOUCHING[1], (n, 1))
    va = np.tile([1.0, 0, 0], (n, 1))
    va[bad, 0] = 1e10
    va[n - 1, 0] = 1e10  # a later bad row: the first one is named
    zeros = np.zeros((n, 3))
    with pytest.raises(ValueError, match=rf"^row {bad}: va\[0\] = -?inf: the result is not finite"):
        model.resolve_lab(pa, va, zeros, pb, zeros, zeros)
    va[bad, 0] = va[n - 1, 0] = 1.0
    out = model.resolve_lab(pa, va, zeros, pb, zeros, zeros)
    np.testing.assert_array_equal(out["vb"][:, 0], np.ones(n))  # elastic, equal balls: exchange


@pytest.mark.parametrize("n", [1500, 5000])
def test_the_first_bad_row_is_named_whether_it_overflows_or_is_refused(n, output_check):
    """An overflowing row before a refused one (a NaN input) in the same chunk is named
    first, and a refused row before an overflowing one; in the one-pass check the library's
    refusal is found first (it stops before the pass)."""
    model = bc.BallBall(**HEAVY)
    pa = np.tile(TOUCHING[0], (n, 1))
    pb = np.tile(TOUCHING[1], (n, 1))
    va = np.tile([1.0, 0, 0], (n, 1))
    zeros = np.zeros((n, 3))
    va[1030, 0] = 1e10
    va[1040, 1] = np.nan
    expected = r"^row 1030: va\[0\] = -?inf: the result is not finite" if output_check else r"^row 1040: va\[1\] = NaN"
    with pytest.raises(ValueError, match=expected):
        model.resolve_lab(pa, va, zeros, pb, zeros, zeros)
    va[1030, 0], va[1020, 0] = 1.0, np.inf
    with pytest.raises(ValueError, match=r"^row 1020: va\[0\] = inf: a finite number"):
        model.resolve_lab(pa, va, zeros, pb, zeros, zeros)


_MODEL = dict(mass=M, radius=R, mu=0.06)
_PLANE = dict(mass=M, radius=R, mu=0.2)
_CUSHION = dict(mass=M, radius=R, mu_cushion=0.2, mu_table=0.2, restitution=0.85)
_ONE = (TOUCHING[0], [1.0, 0, 0], [0, 0, 0], TOUCHING[1], [0, 0, 0], [0, 0, 0])
_REAL = "a real number (float or int)"


@pytest.mark.parametrize(
    "call,name,expected,got",
    [
        (lambda: bc.Ball(mass="x", radius=R), "mass", _REAL, "str"),
        (lambda: bc.Ball(M, [R]), "radius", _REAL, "list"),
        (lambda: bc.Ball(M, R, alpha=None), "alpha", _REAL, "NoneType"),
        (lambda: bc.SpeedDependentFriction(a="0.01", b=0.1, c=1.0), "a", _REAL, "str"),
        (lambda: bc.SpeedDependentFriction(a=0.01, b=None, c=1.0), "b", _REAL, "NoneType"),
        (lambda: bc.SpeedDependentFriction(a=0.01, b=0.1, c=1j), "c", _REAL, "complex"),
        (lambda: bc.SpeedDependentFriction(0.01, 0.1, 1.0, evaluate=0), "evaluate", "a string", "int"),
        (lambda: bc.SpeedDependentFriction(0.01, 0.1, 1.0).mu("fast"), "s", _REAL, "str"),
        (lambda: bc.BallBall(mass="heavy", radius=R, mu=0.06), "mass", _REAL + " or None", "str"),
        (lambda: bc.BallBall(mass=M, radius=b"R", mu=0.06), "radius", _REAL + " or None", "bytes"),
        (lambda: bc.BallBall(alpha="0.4", **_MODEL), "alpha", _REAL + " or None", "str"),
        (lambda: bc.BallBall(a=(M, R), b=bc.Ball(M, R), mu=0.06), "a", "a Ball or None", "tuple"),
        (lambda: bc.BallBall(a=bc.Ball(M, R), b=M, mu=0.06), "b", "a Ball or None", "float"),
        (lambda: bc.BallBall(restitution="1", **_MODEL), "restitution", _REAL, "str"),
        (lambda: bc.BallBall(profile=1, **_MODEL), "profile", "a string", "int"),
        (lambda: bc.BallBall(duration="2e-4", **_MODEL), "duration", _REAL, "str"),
        (lambda: bc.BallBall(friction=1, **_MODEL), "friction", "True or False (a bool)", "int"),
        (lambda: bc.BallBall(stick="yes", **_MODEL), "stick", "True or False (a bool)", "str"),
        (lambda: bc.BallBall(**_MODEL).resolve_lab(*_ONE, method=4), "method", "a string or None", "int"),
        (lambda: bc.BallBall(**_MODEL).resolve_lab(*_ONE, rtol="1e-9"), "rtol", _REAL + " or None", "str"),
        (lambda: bc.BallBall(**_MODEL).resolve_lab(*_ONE, time_transform=1), "time_transform",
         "True, False or None", "int"),
        (lambda: bc.BallPlane(mass="x", radius=R, mu=0.2), "mass", _REAL, "str"),
        (lambda: bc.BallPlane(mass=M, radius=None, mu=0.2), "radius", _REAL, "NoneType"),
        (lambda: bc.BallPlane(alpha=[0.4], **_PLANE), "alpha", _REAL, "list"),
        (lambda: bc.BallPlane(mass=M, radius=R, mu="0.2"), "mu", _REAL, "str"),
        (lambda: bc.BallPlane(restitution="e", **_PLANE), "restitution", _REAL, "str"),
        (lambda: bc.BallPlane(**_PLANE).resolve([0, 0, -1], [0, 0, 0], [0, 0, 1], method=1), "method",
         "a string or None", "int"),
        (lambda: bc.BallPlane(**_PLANE).resolve([0, 0, -1], [0, 0, 0], [0, 0, 1], rtol=[1]), "rtol",
         _REAL + " or None", "list"),
        (lambda: bc.BallCushion(height="4 cm", **_CUSHION), "height", _REAL, "str"),
        (lambda: bc.BallCushion(mass=M, radius=R, height=0.037, mu_cushion=None, mu_table=0.2,
                                restitution=0.85), "mu_cushion", _REAL, "NoneType"),
        (lambda: bc.BallCushion(mass=M, radius=R, height=0.037, mu_cushion=0.2, mu_table="0.2",
                                restitution=0.85), "mu_table", _REAL, "str"),
        (lambda: bc.BallCushion(height=0.037, rule=1, **_CUSHION), "rule", "a string", "int"),
        (lambda: bc.BallCushion(height=0.037, **_CUSHION).resolve([0, 1, 0], [0, 0, 0], steps=1.5),
         "steps", "an integer or None", "float"),
        (lambda: bc.run(3), "path", "a path (str or os.PathLike)", "int"),
        (lambda: bc.run_toml(b"x"), "text", "a string", "bytes"),
        (lambda: bc.run_toml("", base_dir=1), "base_dir", "a path (str or os.PathLike)", "int"),
        (lambda: bc.run_toml("", samples=2.5), "samples", "an integer or None", "float"),
        (lambda: bc.run_toml("", steps="9"), "steps", "an integer or None", "str"),
        (lambda: bc.run_toml("", atol="x"), "atol", _REAL + " or None", "str"),
        (lambda: bc.run_toml("", trace=None), "trace", "True or False (a bool)", "NoneType"),
        (lambda: bc.run_toml("", time_transform="on"), "time_transform", "True, False or None", "str"),
    ],
)
def test_a_wrongly_typed_scalar_names_the_argument_and_the_type(call, name, expected, got):
    with pytest.raises(TypeError) as e:
        call()
    assert str(e.value) == f"{name}: expected {expected}, got {got}"


def test_numbers_of_other_types_are_taken():
    """numpy scalars, ints and bools of numpy are real numbers and flags as before."""
    ball = bc.Ball(np.float32(M), np.int64(1), alpha=np.float64(0.4))
    assert ball.mass == float(np.float32(M)) and ball.radius == 1.0
    model = bc.BallBall(mass=np.float64(M), radius=R, mu=np.float64(0.06), friction=np.bool_(True),
                        stick=np.True_, duration=np.float32(2e-4))
    model.resolve_lab(*_ONE, rtol=np.float64(1e-9), time_transform=np.False_, method="rk4")
    bc.BallPlane(mass=1, radius=1, mu=0, restitution=np.int8(1))
