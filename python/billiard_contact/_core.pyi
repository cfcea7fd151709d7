"""Type stubs of the Rust extension billiard_contact._core (SI units throughout)."""

from os import PathLike
from typing import Any, Literal, NotRequired, Optional, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str

TRACE_COLUMNS: list[str]
"""The trace CSV's column names without units, in order: "t" (s), "f" (N), "p" (N s),
"U", "V", "W" (m/s), "omega_a_x" .. "omega_b_z" (rad/s), "S" (m/s), "theta" (rad),
"H_sfr" (J)."""

Method = Literal["closed-form", "rk4", "dopri5", "dop853"]
ArrayLike3 = Union[npt.ArrayLike, Sequence[float]]

def run(
    path: Union[str, PathLike[str]],
    method: Optional[Method] = None,
    rtol: Optional[float] = None,
    samples: Optional[int] = None,
    *,
    atol: Optional[float] = None,
    steps: Optional[int] = None,
    trace: bool = False,
    time_transform: Optional[bool] = None,
) -> dict[str, Any]:
    """Runs a scene file (TOML) as ``billiard-contact run SCENE --json`` does.

    Returns the command's JSON object as a dict, with exactly its keys and values
    (``collision``, ``impulse`` (N s), ``s0`` (m/s), ``theta`` (rad or None), ``s_out``,
    ``sticks``, ``stick_time`` (s), ``stick_impulse``, ``tangential_impulse``, ``heat``,
    ``heat_sliding`` (J), ``cm_in``, ``cm_out``, ``lab_out`` (lab scenes),
    ``throw_angle_deg``, ``check``, ``solver``, ``effects``, ``warnings``, ``name``,
    ``profile``, ``duration`` (s), ``table`` with the table effect).

    method, rtol, atol, steps override the scene's ``[solver]`` as ``--method``,
    ``--rtol`` (which sets atol too unless atol is given), ``--atol``, ``--steps`` do;
    time_transform (True/False) as ``--time-transform``: whether the time-stepping methods
    integrate hertz and sine-power pulses in the smoothing change of time variable (None:
    the scene's ``[solver] time_transform``, by default the library's True).
    samples=N adds ``report["trace"]``: a dict of numpy arrays keyed by ``TRACE_COLUMNS``,
    and ``"delta"`` (the compression, m; the CSV's ``delta (m)``) when the scene has a
    contact law, at t = i duration / N (i = 0..N) plus the stop of sliding, in the paper's
    centre-of-mass frame; ``theta`` is NaN where the CSV cell is empty (S(0) = 0).
    trace=True (without samples): one row per accepted step. An option the run does not
    use (rtol or atol with rk4 or a profile's closed form, time_transform with the closed
    form or a contact law) gives a ``UserWarning``, as the command warns on stderr; so do
    the scene's own warnings (a mass, radius or duration far outside any ball game, with the
    likely unit slip; ``[solver] time_transform`` under a contact law).

    A cushion scene (a ``[cushion]`` table) gives the command's cushion report
    (``target`` "cushion", ``ball_out``, the impulses, works and events); samples and
    trace are refused for it, steps is for rk4 only.

    Raises ValueError (bad input, the command's one-line message) or RuntimeError (the run
    failed: the integrator gave up, a non-finite result).
    """

def run_toml(
    text: str,
    base_dir: Union[str, PathLike[str]] = ".",
    method: Optional[Method] = None,
    rtol: Optional[float] = None,
    samples: Optional[int] = None,
    *,
    atol: Optional[float] = None,
    steps: Optional[int] = None,
    trace: bool = False,
    time_transform: Optional[bool] = None,
) -> dict[str, Any]:
    """As ``run``, for scene text; relative profile files resolve against base_dir."""

Evaluate = Literal["along-contact", "initial"]
"""Where mu(S) is evaluated: the library's names (scene files' ``contact.mu.evaluate``)."""
EvaluateAlias = Literal["contact", "initial-slip"]
"""The first release's names, accepted for ``"along-contact"`` and ``"initial"``."""

class SpeedDependentFriction:
    """Ball-ball friction mu(S) = a + b exp(-c S), S the sliding speed of the contact
    points (m/s); a, b dimensionless (>= 0, <= 1e6), c in s/m (>= 0).

    evaluate="along-contact" (default): mu at the current sliding speed all along the
    contact. evaluate="initial": mu(S(0)) at the sliding speed before the collision, then
    used as a constant coefficient (pooltool's convention). The names are the scene files'
    (``contact.mu.evaluate``); "contact" and "initial-slip" are accepted for them too.
    """

    def __init__(
        self,
        a: float,
        b: float,
        c: float,
        evaluate: Union[Evaluate, EvaluateAlias] = "along-contact",
    ) -> None: ...
    @property
    def a(self) -> float: ...
    @property
    def b(self) -> float: ...
    @property
    def c(self) -> float:
        """Decay rate (s/m)."""
    @property
    def evaluate(self) -> Evaluate:
        """The library's name of the convention (also when an alias was given)."""
    def mu(self, s: float) -> float:
        """mu at sliding speed s (m/s)."""

class Ball:
    """One ball: mass (kg), radius (m), alpha (I = alpha m r^2, in [1e-12, 2/3]; 0.4 a
    solid ball). Give two to BallBall(a=..., b=...) for balls of different mass, size or
    inertia.

    Bad values raise ValueError with the library's message, e.g. "ball.mass = -1: > 0 kg".
    """

    def __init__(self, mass: float, radius: float, alpha: float = 0.4) -> None: ...
    @property
    def mass(self) -> float:
        """Mass (kg)."""
    @property
    def radius(self) -> float:
        """Radius (m)."""
    @property
    def alpha(self) -> float:
        """I = alpha m r^2."""

class LabResult(TypedDict):
    """Outgoing state of resolve_lab. For N collisions: arrays of shape (N, 3) and (N,);
    for one: arrays of shape (3,) and numpy scalars (shape ())."""

    va: npt.NDArray[np.float64]
    """Velocity of A after the collision (m/s)."""
    wa: npt.NDArray[np.float64]
    """Spin of A (rad/s)."""
    vb: npt.NDArray[np.float64]
    """Velocity of B (m/s)."""
    wb: npt.NDArray[np.float64]
    """Spin of B (rad/s)."""
    impulse: Union[npt.NDArray[np.float64], np.float64]
    """Normal impulse P (N s); 0 where the balls do not approach."""
    tangential_impulse: Union[npt.NDArray[np.float64], np.float64]
    """Friction impulse J >= 0 (N s)."""
    sticks: Union[npt.NDArray[np.bool_], np.bool_]
    """Whether sliding stopped during the contact (True also where S(0) = 0)."""
    throw_angle_deg: Union[npt.NDArray[np.float64], np.float64]
    """Angle (degrees, counter-clockwise about up) from the horizontal line of centres to
    B's horizontal velocity change; NaN where the library gives none (B's horizontal
    velocity change vanishes, or the line of centres is vertical)."""

class BallBall:
    """Two balls and their contact.

    Two identical balls: mass (kg), radius (m), alpha (I = alpha m r^2, in [1e-12, 2/3];
    0.4 a solid ball). Balls of different mass, size or inertia: a=Ball(...) and
    b=Ball(...) instead (not both forms). mu (ball-ball friction: a number >= 0, or
    SpeedDependentFriction), restitution e in [0, 1] (normal impulse P = (1 + e) m* v_n,
    m* = m_A m_B / (m_A + m_B) the reduced mass and v_n the relative approach speed:
    (1 + e) m U(0) for identical balls); profile ("half-sine", "hertz",
    "sine-power", "rectangle") and duration (s) of the normal force, used by the
    time-stepping methods (the closed form does not depend on them); friction and stick
    switch those effects.

    tangential="mindlin" with the balls' material (youngs_modulus in Pa, poisson_ratio)
    resolves each collision compliantly instead (docs/tangential.md#two-spheres): Hertz's
    normal force and Mindlin's tangential spring (its stiffness times
    shear_stiffness_factor, default 1) under Coulomb's cap; mu a number. Hertz's force is
    elastic (restitution 1) unless damping is "hunt-crossley" or "kuwabara-kono"
    (docs/contact-law.md), with its coefficient (s/m or s; restitution left at 1) or
    calibrated so that a head-on impact at the relative approach speed at_speed (m/s)
    rebounds with restitution, on the pair's Hertz stiffness and reduced mass, as BallPlane.
    resolve_lab then takes rtol= (no method, up or time_transform) and returns "va", "wa",
    "vb", "wb", "impulse", "tangential_impulse" (|J_t|), "contact_time" (s) and
    "rebound_angle" (rad; NaN for a pair that does not approach, which passes unchanged).

    Bad values raise ValueError with the command line's message, e.g.
    "balls.mass = -1: > 0 kg".
    """

    def __init__(
        self,
        *,
        mass: Optional[float] = None,
        radius: Optional[float] = None,
        alpha: Optional[float] = None,
        a: Optional[Ball] = None,
        b: Optional[Ball] = None,
        mu: Union[float, SpeedDependentFriction],
        restitution: float = 1.0,
        profile: Literal["half-sine", "hertz", "sine-power", "rectangle"] = "half-sine",
        duration: float = 2.5e-4,
        friction: bool = True,
        stick: bool = True,
        tangential: Literal["rigid", "mindlin"] = "rigid",
        youngs_modulus: Optional[float] = None,
        poisson_ratio: Optional[float] = None,
        shear_stiffness_factor: Optional[float] = None,
        damping: Optional[Literal["hunt-crossley", "kuwabara-kono"]] = None,
        coefficient: Optional[float] = None,
        at_speed: Optional[float] = None,
    ) -> None: ...
    @property
    def tangential(self) -> Literal["rigid", "mindlin"]:
        """The tangential law: "rigid" (the stick rule) or "mindlin" (the compliant pair)."""
    @property
    def mass(self) -> Optional[float]:
        """Mass (kg) of both balls; None when A and B differ."""
    @property
    def radius(self) -> Optional[float]:
        """Radius (m) of both balls; None when A and B differ."""
    @property
    def alpha(self) -> Optional[float]:
        """I = alpha m r^2, alpha of both balls; None when A and B differ."""
    @property
    def a(self) -> Ball:
        """Ball A."""
    @property
    def b(self) -> Ball:
        """Ball B."""
    @property
    def mu(self) -> Union[float, SpeedDependentFriction]: ...
    @property
    def restitution(self) -> float: ...
    def resolve_lab(
        self,
        pa: ArrayLike3,
        va: ArrayLike3,
        wa: ArrayLike3,
        pb: ArrayLike3,
        vb: ArrayLike3,
        wb: ArrayLike3,
        up: Optional[ArrayLike3] = None,
        method: Optional[Method] = None,
        rtol: Optional[float] = None,
        time_transform: Optional[bool] = None,
    ) -> LabResult:
        """Resolves collisions given in the lab frame.

        pa, va, wa, pb, vb, wb: positions (m), velocities (m/s), spins (rad/s) of balls A
        and B, each of shape (3,) or (N, 3), any memory order (lists work too; a (3,) input
        is used for every row; float, integer and bool arrays are converted to float64,
        complex, object, string and other non-real dtypes raise TypeError naming the
        argument). up: away from the table, default (0, 0, 1). The centres must
        touch: |pb - pa| = 2 radius (r_A + r_B) within a relative 1e-9.

        method None is the closed form; "rk4", "dopri5", "dop853" integrate (rtol, default
        1e-10, sets atol too; time_transform, default the library's True: the smoothing
        change of time variable for "hertz" and "sine-power" profiles). N >= 2048 rows run
        on all cores without the GIL.

        Raises ValueError naming the row and field ("row 7: va[1] = NaN: a finite number"),
        also when a result would not be finite ("va[0] = -inf: the result is not finite
        ...": masses, speeds or spins so large that the collision overflows); no output is
        inf or NaN but the throw angle where it is undefined.
        """

class PlaneResult(TypedDict):
    """Outgoing state of BallPlane.resolve. For N impacts: arrays of shape (N, 3) and (N,);
    for one: arrays of shape (3,) and numpy scalars (shape ())."""

    v: npt.NDArray[np.float64]
    """Velocity after the impact (m/s)."""
    w: npt.NDArray[np.float64]
    """Spin after the impact (rad/s)."""
    impulse: Union[npt.NDArray[np.float64], np.float64]
    """Normal impulse P = (1 + e) m |v.n| (N s), along the normal; 0 where the ball does
    not approach (v.n >= 0)."""
    tangential_impulse: Union[npt.NDArray[np.float64], np.float64]
    """Friction impulse J = min(mu P, m |u| / (1 + 1/alpha)) >= 0 (N s), against the slip
    u = v_t - r (w x n) of the contact point."""
    sticks: Union[npt.NDArray[np.bool_], np.bool_]
    """Whether the slip stopped during the impact (the ball leaves rolling; True also for a
    ball that arrives without slip and is hit)."""
    stick_impulse: Union[npt.NDArray[np.float64], np.float64]
    """Normal impulse at which the slip stops, or would stop after the impact,
    m |u| / ((1 + 1/alpha) mu) (N s); NaN without friction or without an impulse."""

class CompliantPlaneResult(TypedDict):
    """Outgoing state of BallPlane(tangential="mindlin").resolve; shapes as PlaneResult's."""

    v: npt.NDArray[np.float64]
    """Velocity after the contact (m/s)."""
    w: npt.NDArray[np.float64]
    """Spin after the contact (rad/s)."""
    impulse: Union[npt.NDArray[np.float64], np.float64]
    """Normal impulse (N s); 0 where the ball does not approach."""
    tangential_impulse: Union[npt.NDArray[np.float64], np.float64]
    """Length of the tangential impulse (N s)."""
    contact_time: Union[npt.NDArray[np.float64], np.float64]
    """Time from first touch until the normal force returns to 0 (s)."""
    rebound_angle: Union[npt.NDArray[np.float64], np.float64]
    """The contact point's rebound angle atan2(u'.s, v'.n) (rad), s the incoming slip's
    direction: negative when its tangential velocity reversed; NaN where there was no
    contact."""

class BallPlane:
    """A ball against a plane (docs/plane.md): the ball's mass (kg), radius (m) and alpha
    (I = alpha m r^2, in [1e-12, 2/3]; 0.4 a solid ball), Coulomb friction mu >= 0 between
    ball and plane, restitution e in [0, 1] (P = (1 + e) m |v.n|: Newton's, Poisson's and
    Stronge's rules agree for a sphere on a plane).

    tangential "rigid" (default): the stick rule, the surfaces stick once the slip stops;
    "mindlin": Hertz's normal force and Mindlin's tangential spring under Coulomb's cap
    (docs/tangential.md), from the ball's material (youngs_modulus in Pa, poisson_ratio)
    and the plane's (plane_youngs_modulus, plane_poisson_ratio; a plane without them is
    rigid); elastic (restitution 1) unless damping is "hunt-crossley" or "kuwabara-kono",
    with its coefficient (s/m or s) or calibrated so that a normal impact at at_speed (m/s)
    has the restitution.

    Bad values raise ValueError naming the keyword, e.g. "mass = -1: > 0 kg".
    """

    def __init__(
        self,
        *,
        mass: float,
        radius: float,
        alpha: float = 0.4,
        mu: float,
        restitution: float = 1.0,
        tangential: Literal["rigid", "mindlin"] = "rigid",
        youngs_modulus: Optional[float] = None,
        poisson_ratio: Optional[float] = None,
        plane_youngs_modulus: Optional[float] = None,
        plane_poisson_ratio: Optional[float] = None,
        damping: Optional[Literal["hunt-crossley", "kuwabara-kono"]] = None,
        coefficient: Optional[float] = None,
        at_speed: Optional[float] = None,
    ) -> None: ...
    @property
    def tangential(self) -> Literal["rigid", "mindlin"]: ...
    @property
    def mass(self) -> float:
        """Mass (kg)."""
    @property
    def radius(self) -> float:
        """Radius (m)."""
    @property
    def alpha(self) -> float:
        """I = alpha m r^2."""
    @property
    def mu(self) -> float: ...
    @property
    def restitution(self) -> float: ...
    def resolve(
        self,
        v: ArrayLike3,
        w: ArrayLike3,
        normal: ArrayLike3,
        method: Optional[Method] = None,
        rtol: Optional[float] = None,
    ) -> Union[PlaneResult, CompliantPlaneResult]:
        """Resolves impacts of the ball on the plane.

        With tangential="mindlin": the compliant kernel (its own Dormand-Prince 5(4) at
        rtol, default 1e-10; method must be None), a CompliantPlaneResult.

        v, w: velocity (m/s) and spin (rad/s) before; normal: the plane's normal, out of the
        plane towards the ball, any non-zero length; each (3,) or (N, 3), any memory order
        (a (3,) input, say one normal, is used for every row; dtypes as resolve_lab's). A
        ball that does not approach the plane (v.n >= 0) passes unchanged: impulse 0,
        sticks False.

        method None: the direct closed form (N >= 2048 rows on all cores without the
        GIL); "closed-form", "rk4", "dopri5", "dop853": the library's PlaneCollision and
        solve_plane by that method (a half-sine pulse; rtol as resolve_lab's), the same
        answer to the method's accuracy.

        Raises ValueError naming the row and the argument ("row 3: normal = [0, 0, 0]:
        a non-zero, finite direction ...", "row 7: v[1] = NaN: a finite number"), also when
        a result would not be finite ("row 2: v[0] = NaN: the result is not finite ...").
        """

class CushionResult(TypedDict):
    """Outgoing state of BallCushion.resolve, in the cushion's frame (x along the cushion, y
    towards it, z up). For N impacts: arrays of shape (N, 3) and (N,), "events" a list of N
    lists; for one: arrays of shape (3,), numpy scalars and one list."""

    v: npt.NDArray[np.float64]
    """Velocity after the impact (m/s)."""
    w: npt.NDArray[np.float64]
    """Spin after the impact (rad/s)."""
    impulse: Union[npt.NDArray[np.float64], np.float64]
    """The cushion's normal impulse P_I (N s)."""
    impulse_compression: Union[npt.NDArray[np.float64], np.float64]
    """P_I at the end of compression (N s)."""
    impulse_table: Union[npt.NDArray[np.float64], np.float64]
    """The cloth's normal impulse P_C (N s)."""
    work_compression: Union[npt.NDArray[np.float64], np.float64]
    """Work of the ball on the cushion's normal force during compression, >= 0 (J)."""
    work_restitution: Union[npt.NDArray[np.float64], np.float64]
    """Work the cushion's normal force gives back during restitution, >= 0 (J)."""
    energy_lost: Union[npt.NDArray[np.float64], np.float64]
    """Kinetic energy in minus out, translation and spin (J)."""
    lifts_off: Union[npt.NDArray[np.bool_], np.bool_]
    """Whether the ball left the cloth during the impact."""
    events: Union[list[tuple[str, str, float]], list[list[tuple[str, str, float]]]]
    """The slip events in order: (contact, change, P_I at it): contact "cushion" or "table",
    change "sticks", "reverses", "restarts", "lifts-off" or "touches-down"."""
    steps: Union[npt.NDArray[np.uint64], int]
    """Accepted steps of the integration."""
    evaluations: Union[npt.NDArray[np.uint64], int]
    """Evaluations of the right-hand side, event location included."""

class BallCushion:
    """A ball on the cloth against a cushion (Mathavan, Jackson and Parkin 2010), in the
    cushion's frame: x along the cushion, y towards it, z up.

    mass (kg), radius (m), alpha (I = alpha m r^2, in [1e-12, 2/3]; 0.4 a solid ball);
    height (m) of the cushion's contact above the cloth, in (radius, 2 radius);
    mu_cushion and mu_table (>= 0): friction of the ball on the cushion and on the cloth;
    restitution e in [0, 1]; rule "stronge" (the work of restitution e^2 that of
    compression, as pooltool's mathavan_2010) or "newton" (the normal velocity at the
    cushion ends at -e times its start).

    Bad values raise ValueError naming the keyword, e.g. "height = 0.02: in (radius,
    2 radius) = ...".
    """

    def __init__(
        self,
        *,
        mass: float,
        radius: float,
        alpha: float = 0.4,
        height: float,
        mu_cushion: float,
        mu_table: float,
        restitution: float,
        rule: Literal["stronge", "newton"] = "stronge",
    ) -> None: ...
    @property
    def mass(self) -> float:
        """Mass (kg)."""
    @property
    def radius(self) -> float:
        """Radius (m)."""
    @property
    def alpha(self) -> float:
        """I = alpha m r^2."""
    @property
    def height(self) -> float:
        """Height of the cushion's contact above the cloth (m)."""
    @property
    def mu_cushion(self) -> float: ...
    @property
    def mu_table(self) -> float: ...
    @property
    def restitution(self) -> float: ...
    @property
    def rule(self) -> Literal["stronge", "newton"]: ...
    def resolve(
        self,
        v: ArrayLike3,
        w: ArrayLike3,
        method: Optional[Literal["dop853", "dopri5", "rk4"]] = None,
        rtol: Optional[float] = None,
        steps: Optional[int] = None,
    ) -> CushionResult:
        """Resolves impacts on the cushion, in its frame.

        v, w: velocity (m/s) and spin (rad/s) before, each (3,) or (N, 3) (a (3,) input is
        used for every row; dtypes as resolve_lab's). The ball must be on the cloth
        (v_z = 0) and approach the cushion (v_y > 0): else ValueError naming the row and v.

        method "dop853" (default), "dopri5" or "rk4" (the impact has no closed form); rtol
        (default 1e-10, atol with it); steps of rk4. 64 rows or more run on all cores
        without the GIL.
        """

class ClusterContact(TypedDict):
    """One contact of Cluster.resolve that carried force, from its closing to its opening."""

    pair: tuple[int, int]
    """The balls' indices (i, j), i < j."""
    impulse: float
    """Normal impulse on ball j (on ball i, minus it) (N s)."""
    friction_impulse: npt.NDArray[np.float64]
    """Friction impulse on ball i (on ball j, minus it), (3,) (N s)."""
    normal: npt.NDArray[np.float64]
    """Unit normal from ball i to ball j at the closing, (3,)."""
    start: float
    """Time it closed, from the start of the run (s)."""
    duration: float
    """How long it carried force (s)."""
    heat: float
    """Energy it dissipated: damping and sliding friction (J)."""
    stick_time: Optional[float]
    """Time from its closing at which its slip last stopped (s), or None."""

class ClothContact(TypedDict):
    """A ball's contact with the cloth during Cluster.resolve (docs/cluster.md, "The cloth")."""

    ball: int
    """The ball's index."""
    impulse: float
    """Normal impulse of the cloth on the ball, upward (N s): its weight's m g t while it
    rests, more while it is pressed into the cloth."""
    friction_impulse: npt.NDArray[np.float64]
    """The cloth's friction impulse on the ball, (3,) (N s)."""
    start: float
    """Time it closed (s; 0 for a ball resting from the start)."""
    duration: float
    """How long it lasted (s): to the run's end, or until the ball left the cloth."""
    heat: float
    """Energy its friction dissipated (J)."""
    stick_time: Optional[float]
    """Time from its closing at which its slip last stopped (s), or None."""

class ClothSpec(TypedDict, total=False):
    """The cloth= keyword of Cluster: the scene's [cloth] keys."""

    youngs_modulus: float
    """The bed's Young's modulus (Pa; required; slate about 5e10)."""
    poisson_ratio: float
    """The bed's Poisson's ratio (required; slate about 0.25)."""
    mu: float
    """Ball-cloth friction (default 0.2)."""
    height: float
    """The cloth's z (m; default the first ball's z minus its radius)."""
    gravity: float
    """Gravity along -z (m/s^2; default 9.81)."""
    damping: Optional[Literal["hunt-crossley", "kuwabara-kono"]]
    """Damping of each ball's contact with the bed (default None: elastic)."""
    coefficient: float
    """Its coefficient (s/m or s), or instead restitution with at_speed."""
    restitution: float
    """The restitution a ball dropped at at_speed has (calibrated on each ball's mass)."""
    at_speed: float
    """The drop speed (m/s) of that restitution."""

class ClusterResult(TypedDict):
    """Outgoing state of Cluster.resolve: a row per ball, in the order of Cluster.balls."""

    velocities: npt.NDArray[np.float64]
    """(N, 3) velocities after the last contact opened (m/s)."""
    spins: npt.NDArray[np.float64]
    """(N, 3) spins (rad/s)."""
    positions: npt.NDArray[np.float64]
    """(N, 3) centres when the run ended (m)."""
    contacts: list[ClusterContact]
    """Every contact that carried force, in the order they opened again (ended)."""
    time: float
    """Time the run covered (s)."""
    steps: int
    """Accepted steps."""
    evaluations: int
    """Evaluations of the right-hand side."""
    cloth_contacts: NotRequired[list[ClothContact]]
    """With a cloth: each ball's contact with it."""
    cloth_held: NotRequired[float]
    """With a cloth: the energy (J) its spring and gravity hold at the end; the kinetic
    energy in is the kinetic energy out plus every contact's heat plus this."""

class Cluster:
    """N balls resolved together (docs/cluster.md): every pair that touches or comes to
    touch is a contact with its own compression, normal law and Coulomb friction with the
    stick rule.

    balls: 2 to 22 Ball; mu >= 0 at every contact; the normal law from the balls' material
    (youngs_modulus in Pa, poisson_ratio) or one stiffness (N/m^1.5) for every pair;
    damping None, "hunt-crossley" or "kuwabara-kono" with its coefficient (s/m or s) or
    the restitution of a head-on impact at at_speed (m/s); stick (the stick rule);
    tangential "rigid" or "mindlin" (Mindlin's spring at every contact); cloth None or a
    ClothSpec dict (every ball resting on the cloth).
    The keywords are the scene file's names ([balls], [contact.law] and [cloth]).

    Bad values raise ValueError naming the keyword.
    """

    def __init__(
        self,
        *,
        balls: Sequence[Ball],
        mu: float,
        youngs_modulus: Optional[float] = None,
        poisson_ratio: Optional[float] = None,
        stiffness: Optional[float] = None,
        damping: Optional[Literal["hunt-crossley", "kuwabara-kono"]] = None,
        coefficient: Optional[float] = None,
        restitution: Optional[float] = None,
        at_speed: Optional[float] = None,
        stick: bool = True,
        tangential: Literal["rigid", "mindlin"] = "rigid",
        cloth: Optional[ClothSpec] = None,
    ) -> None: ...
    @property
    def balls(self) -> list[Ball]: ...
    @property
    def mu(self) -> float: ...
    def resolve(
        self,
        positions: npt.ArrayLike,
        velocities: npt.ArrayLike,
        spins: npt.ArrayLike,
        rtol: Optional[float] = None,
    ) -> ClusterResult:
        """Resolves the balls from this state to the end of every contact.

        positions (m), velocities (m/s), spins (rad/s): (N, 3), a row per ball. Balls may
        touch (within 1e-9 of r_i + r_j) or come to touch; one pair at least approaches.
        rtol: the step control's relative tolerance (default 1e-8). A run that cannot
        finish raises RuntimeError; nothing partial is returned.
        """
