"""pooltool ball-ball and ball-cushion collision models backed by billiard-contact.

Install it into an engine (one line), or into pooltool's default engine, the one
``pt.simulate`` uses without ``engine=`` and the one the GUI uses::

    import pooltool as pt
    from billiard_contact.pooltool import install

    engine = pt.physics.PhysicsEngine(); install(engine)   # then pt.simulate(system, engine=engine)
    install()                                               # pooltool's default engine (and GUI)

or set ``engine.resolver.ball_ball = BilliardContact(...)`` yourself. Written for pooltool
0.6 (``pip install pooltool-billiards==0.6.0``) and for the API of pooltool's main branch
after it, where the engine is ``pooltool.evolution.SimulationEngine(is_3d=...)`` and every
strategy declares the dimensionality it is safe in (``dim``): ``install`` takes either
engine, and the model declares ``Dim.BOTH`` where pooltool has ``Dim``.

What the model does with pooltool's balls (``ball.state.rvw``: position, velocity, spin;
lab frame, z up; any memory order):

- Geometry. pooltool's ``make_kiss`` leaves the balls ``const.MIN_DIST`` (1e-6 m) apart
  before ``solve``. The collision is resolved along the actual line of centres: both
  centres are moved along it, symmetrically about their midpoint, to touching (|pb - pa| =
  R1 + R2) for the library, which requires touching balls. The balls keep their own
  positions.
- Parameters. Mass and radius are each ball's own (``ball.params.m``, ``ball.params.R``;
  ``alpha``, the same for both, 0.4 by default); balls of different mass or radius are
  resolved as ``BallBall(a=Ball(m1, R1, alpha), b=Ball(m2, R2, alpha))``.
  ``restitution=None`` takes the mean of the balls' ``e_b`` as pooltool does. For balls of
  different radius the model does its own ``make_kiss`` (pooltool's spaces the centres by
  twice the first ball's radius): the same construction, moving the balls back or on along
  their paths to R1 + R2 + ``const.MIN_DIST`` apart. For different masses it does its own
  continually-touching adjustment (pooltool's moves velocity, which keeps momentum only for
  equal masses): the same 10 % of the chaser's momentum along the line of centres. Equal
  balls get pooltool's own methods unchanged.
- Vertical velocity. pooltool 0.6 is two-dimensional and its ``frictional_inelastic``
  model zeroes the vertical velocity after a collision; so does this one in a 2D engine
  unless ``keep_vertical_velocity=True`` (the library resolves the collision in 3D, and a
  ball hit with follow or draw spin gets a small vertical velocity from friction). In a 3D
  engine (``is_3d=True``, which ``install`` reads from ``engine.is_3d``, pooltool after 0.6)
  it is kept unless ``keep_vertical_velocity=False``, and a ball leaving upwards is
  ``const.airborne``, as pooltool's 3D cue strike leaves it, when it would rise at least
  ``min_bounce_height`` (0.005 m, pooltool's ball-table models' rule for settling a
  bounce; a ball-ball collision rarely lifts a ball that far); a smaller or downward
  vertical velocity of a ball on the table is zeroed (the table takes it).
- Continually touching. After every ball-ball model's ``solve``, pooltool's
  ``CoreBallBallCollision.resolve`` calls ``resolve_continually_touching``: when the two
  balls leave along nearly the same direction (cosine above 0.9) with line-of-centres
  speeds within 0.01 m/s, the slower ball takes 10 % of the faster one's speed along the
  line of centres, so that they separate instead of colliding again microseconds later
  (pooltool's remedy for a row of frozen balls, Newton's cradle, whose pairwise collisions
  would otherwise stall the simulation). It keeps momentum but not energy: moving 0.1 u
  from a ball at u to one at about u changes the kinetic energy by about m (0.1 u)^2 > 0,
  a relative gain of about 1 % when both move at u. ``continually_touching=False`` skips
  it: the library's result is final (and never gains energy).
- Friction. ``mu`` is a number or a ``SpeedDependentFriction(a, b, c)`` (default: the
  fit a + b exp(-c S) that pooltool's default resolver uses, a = 9.951e-3, b = 0.108,
  c = 1.088). ``SpeedDependentFriction(..., evaluate="along-contact")`` (default)
  evaluates mu at the current sliding speed all along the contact;
  ``evaluate="initial"`` freezes mu at the sliding speed before the collision, pooltool's
  convention: mu(S(0)) is computed from the incoming state and used as a constant
  coefficient (the first release's names "contact" and "initial-slip" work too).
- Motion state. Both balls leave the collision ``const.sliding`` (or airborne, above).
- Compliant contact. ``tangential="mindlin"`` with ``youngs_modulus`` and
  ``poisson_ratio`` (``install(engine, tangential="mindlin", youngs_modulus=5.4e9,
  poisson_ratio=0.34)``) resolves each collision with the library's compliant pair,
  ``BallBall(tangential="mindlin", ...)``: Hertz's normal force and Mindlin's tangential
  spring under Coulomb's cap (docs/tangential.md). The restitution (``restitution``, or by
  default the mean of the balls' ``e_b``) is, as for ``ClusterResolver``'s contact law,
  Hunt and Crossley's damping calibrated to it once at a relative approach speed of
  ``MINDLIN_AT_SPEED`` (1 m/s): ``BallBall(..., damping="hunt-crossley", restitution=e,
  at_speed=1.0)``; at other approach speeds the restitution is the damped contact's own
  (not a calibration per collision). A restitution of 1 is elastic Hertz. It takes a
  constant mu (by default the mean of the balls' ``u_b``).

Differences from pooltool's ``frictional_inelastic``: that model's tangential impulse is
mu e m dv_n (e the restitution), this one's mu (1 + e)/2 m dv_n (Coulomb friction over the
whole normal impulse, the paper's model); the two agree when e = 1 (the tests compare them
to 1e-12). The library stops sliding when the contact points stop slipping (the same rule
as pooltool's no-slip branch).

The ball-cushion model, ``BilliardContactCushion``, which ``install`` also puts in place
(``cushion=False`` does not), resolves impacts on linear cushion segments with the library's
``BallCushion`` (Mathavan, Jackson and Parkin 2010): the ball's velocity and spin are mapped
into Mathavan's frame (y along the segment's normal, turned to point along the ball's
velocity as pooltool's ``mathavan_2010`` turns it; z up; x = y x z), resolved there with the
ball's ``e_c``, ``f_c``, ``u_s`` and the segment's ``height`` (or the model's own values),
and mapped back; the ball leaves ``sliding``. A cushion outside R < height < 2R, a ball that
does not approach the cushion or one in the air goes to ``fallback`` (``install`` keeps the
engine's previous model there); circular segments (the pockets' jaws) keep the engine's
model.

``install(engine, cluster=True)`` makes the engine's resolver a ``ClusterResolver``: a
ball-ball event whose balls touch others (a rack, frozen balls) is resolved for all of
them together by the library's ``Cluster`` (``CLUSTER_TOUCH_GAP``; docs/python.md).

Collision time. Importing this module corrects pooltool 0.6.0's ball-ball collision
time (``COLLISION_TIME_CORRECTED``; process-wide, for every engine): two balls with exactly
the same acceleration on the cloth (both rolling, or both sliding with the slip along the
velocity, moving in the same direction) have a squared distance quadratic in time, not
quartic, and pooltool's quartic solver answers such an equation with roots 0, so the pair
collides again at the same time until ``max_events`` stops every ball. A struck row of balls
along a table axis does this once a collision's outgoing velocities are exact, as this
model's are. The correction solves the quadratic for such a pair and leaves every other pair
to pooltool's own function.

These models are not registered with pooltool's serialisation (its registries of models
are closed enumerations), so a resolver using them cannot be saved to ``resolver.yaml``;
install them in code.
"""

from __future__ import annotations

import math
from typing import Any, Optional, Union

import attrs
import numpy as np
import pooltool.constants as const
from pooltool.objects.ball.datatypes import Ball, BallState
from pooltool.physics.resolve.ball_ball.core import CoreBallBallCollision
from pooltool.physics.resolve.ball_cushion.core import CoreBallLCushionCollision
from pooltool.physics.resolve.resolver import Resolver

from billiard_contact import Ball as _LibBall
from billiard_contact import BallBall, BallCushion, Cluster, SpeedDependentFriction


def _first_found(*names: str) -> Any:
    """The first of ``"module:attribute"`` that imports (pooltool moves names between
    releases), or None."""
    import importlib

    for name in names:
        module, _, attribute = name.partition(":")
        try:
            return getattr(importlib.import_module(module), attribute)
        except (ImportError, AttributeError):
            continue
    return None


def _degenerate_collision_time(c: float, d: float, e: float) -> float:
    """The first time t > 0 (s) at which two balls without relative acceleration touch:
    the root of c t^2 + d t + e = 0 (c = |relative velocity|^2, d = 2 relative velocity .
    offset, e = |offset|^2 - (2R)^2, pooltool's coefficients in the plane), np.inf when
    there is none. A root at t = 0 (touching now) is a collision only when the balls close
    (d < 0)."""
    if not c > 0.0:
        return np.inf  # no relative motion: the distance never changes
    disc = d * d - 4.0 * c * e
    if disc < 0.0:
        return np.inf  # the paths pass each other farther apart than touching
    # The two roots without cancellation: q = -(d + sign(d) sqrt(disc)) / 2.
    q = -0.5 * (d + math.copysign(math.sqrt(disc), d))
    roots = [q / c] + ([e / q] if q != 0.0 else [])
    times = [t for t in roots if t > 0.0 or (t == 0.0 and d < 0.0)]
    return min(times, default=np.inf)


def _correct_collision_time() -> bool:
    """pooltool 0.6.0 predicts a ball-ball collision from the quartic in time of the
    squared distance between the centres (``solve.ball_ball_collision_coeffs``). Two balls
    with exactly the same acceleration on the cloth (both rolling, or both sliding with the
    slip along the velocity, in the same direction of motion: the quartic's t^4 and t^3
    coefficients are then exactly zero) leave a quadratic, for which its quartic solver
    returns four roots 0: the collision time is 0, and the event repeats at the same time
    until ``max_events`` (a row of balls struck along a table axis does this once the
    collision's outgoing velocities are exact, as this module's are; pooltool's own model
    escapes by rounding noise, but not two balls rolling along one line, which collide at
    once across any gap). This replaces ``solve.ball_ball_collision_time``, the function
    pooltool's event loop calls, by one that solves that quadratic
    (``_degenerate_collision_time``) and passes every other pair to pooltool's own function
    unchanged. It does so only where pooltool's quartic solver has that defect (probed on
    t^2 - 3t + 2, roots 1 and 2); it is process-wide, idempotent, and returns whether the
    correction is in place."""
    solve = _first_found("pooltool.evolution.event_based:solve")
    quartic = _first_found("pooltool.ptmath.roots:quartic")
    original = getattr(solve, "ball_ball_collision_time", None)
    coeffs = getattr(solve, "ball_ball_collision_coeffs", None)
    if original is None or coeffs is None or quartic is None:
        return False  # not pooltool 0.6's event loop
    if getattr(original, "_billiard_contact_corrected", False):
        return True
    try:
        probe = np.asarray(quartic.solve(0.0, 0.0, 1.0, -3.0, 2.0))
    except Exception:  # a solver that refuses a degenerate quartic: nothing to correct
        return False
    if not (probe.shape == (4,) and np.all(probe == 0)):
        return False

    def ball_ball_collision_time(*args: Any, **kwargs: Any) -> float:
        a, b, c, d, e = coeffs(*args, **kwargs)
        if a == 0.0 and b == 0.0:
            return _degenerate_collision_time(float(c), float(d), float(e))
        return original(*args, **kwargs)

    ball_ball_collision_time._billiard_contact_corrected = True  # type: ignore[attr-defined]
    ball_ball_collision_time.original = original  # type: ignore[attr-defined]
    solve.ball_ball_collision_time = ball_ball_collision_time
    return True


#: pooltool after 0.6: strategies declare the dimensionality they are safe in (None: 0.6).
Dim = _first_found("pooltool.physics.dimensionality:Dim")
#: pooltool after 0.6: the motion state of a ball off the table (None: 0.6, all on it).
_AIRBORNE = getattr(const, "airborne", None)

__all__ = [
    "BilliardContact",
    "BilliardContactCushion",
    "install",
    "MODEL_NAME",
    "CUSHION_MODEL_NAME",
    "MINDLIN_AT_SPEED",
    "COLLISION_TIME_CORRECTED",
]

#: Whether pooltool's ball-ball collision time is corrected for balls without relative
#: acceleration (``_correct_collision_time``, applied when this module is imported; False
#: where pooltool's own solver needs no correction).
COLLISION_TIME_CORRECTED = _correct_collision_time()

MODEL_NAME = "billiard_contact"
"""The value of ``BilliardContact.model`` (pooltool identifies models by this attribute)."""

#: The relative approach speed (m/s) at which ``tangential="mindlin"`` calibrates Hunt and
#: Crossley's damping to the restitution, once a pair of balls (``ClusterResolver``'s
#: ``at_speed`` too): a typical collision speed on a pool table.
MINDLIN_AT_SPEED = 1.0

#: pooltool's default ball-ball friction fit (TP A-14), evaluated along the contact.
DEFAULT_MU = SpeedDependentFriction(a=9.951e-3, b=0.108, c=1.088)


@attrs.define
class BilliardContact(CoreBallBallCollision):
    """Ball-ball collisions resolved by billiard-contact (Peskin 2020), for pooltool.

    Attributes:
        mu: ball-ball friction, a number or ``SpeedDependentFriction`` (see the module's
            documentation for ``evaluate="along-contact"`` and ``"initial"``).
        restitution: e in [0, 1] (normal impulse (1 + e) m U(0)); ``None``: the mean of
            the two balls' ``params.e_b``.
        alpha: moment of inertia factor, I = alpha m R^2 (0.4: solid ball).
        is_3d: the engine is 3D (``SimulationEngine(is_3d=True)``, pooltool after 0.6;
            ``install`` sets it from the engine): the vertical velocity is kept by default
            and a ball leaving the table is airborne.
        min_bounce_height: (3D engines) a ball on the table that the collision would lift
            by less (m; v_z^2 / 2g) stays on it, with no vertical velocity, as pooltool's
            ball-table models settle such a bounce; ``install`` takes the engine's
            ``resolver.ball_table.min_bounce_height`` (pooltool's default 0.005).
        keep_vertical_velocity: keep the vertical velocity the collision gives; ``None``
            (default): kept in a 3D engine, zeroed in a 2D one as pooltool 0.6's models do.
        method: ``None`` (the closed form) or a time-stepping method of the library
            ("rk4", "dopri5", "dop853"); ``rtol`` its tolerance.
        continually_touching: apply pooltool's ``resolve_continually_touching`` after the
            solve (pooltool calls it after every ball-ball model's ``solve``, in
            ``CoreBallBallCollision.resolve``). On by default, as in pooltool; it moves 10 %
            of the faster ball's momentum along the line of centres to the slower ball when
            the two leave with nearly the same velocity, which keeps momentum but can add
            kinetic energy (see the module's documentation). ``False``: the library's
            result is final.
        dim: (pooltool after 0.6 only) ``Dim.BOTH``: the library resolves collisions in
            3D, so the model is safe in 2D and 3D engines.
        tangential: "rigid" (default: the paper's closed form with the stick rule) or
            "mindlin": the compliant pair (``BallBall(tangential="mindlin", ...)``, Hertz's
            normal force and Mindlin's tangential spring under Coulomb's cap,
            docs/tangential.md), which needs ``youngs_modulus`` (Pa) and ``poisson_ratio``
            of the balls' material. ``restitution`` (None: the mean of the balls' ``e_b``)
            in (0, 1] is Hunt and Crossley's damping calibrated to it at the relative
            approach speed ``MINDLIN_AT_SPEED`` (1 m/s; 1: elastic Hertz); mu a number, or
            by default the mean of the balls' ``params.u_b``; ``method`` None (``rtol``
            sets the step control's tolerance).
        youngs_modulus, poisson_ratio: the balls' material, with ``tangential="mindlin"``.
        shear_stiffness_factor: the factor on Mindlin's tangential stiffness (None: 1,
            Mindlin's; larger: stiffer, towards the rigid stick rule), with
            ``tangential="mindlin"``.
    """

    mu: Union[float, SpeedDependentFriction] = DEFAULT_MU
    restitution: Optional[float] = None
    alpha: float = 0.4
    keep_vertical_velocity: Optional[bool] = None
    method: Optional[str] = None
    rtol: Optional[float] = None
    continually_touching: bool = True
    is_3d: bool = False
    min_bounce_height: float = 0.005
    tangential: str = "rigid"
    youngs_modulus: Optional[float] = None
    poisson_ratio: Optional[float] = None
    shear_stiffness_factor: Optional[float] = None

    if Dim is not None:
        dim: Dim = attrs.field(default=Dim.BOTH, init=False, repr=False)
    model: str = attrs.field(default=MODEL_NAME, init=False, repr=False)
    _models: dict = attrs.field(factory=dict, init=False, repr=False, eq=False)

    def __attrs_post_init__(self) -> None:
        if self.tangential not in ("rigid", "mindlin"):
            raise ValueError(
                f'tangential = "{self.tangential}": "rigid" (the stick rule) or "mindlin" '
                f"(Mindlin's tangential spring)"
            )
        compliant = (self.youngs_modulus, self.poisson_ratio, self.shear_stiffness_factor)
        if self.tangential != "mindlin":
            if compliant != (None, None, None):
                raise ValueError(
                    'youngs_modulus, poisson_ratio, shear_stiffness_factor: given with '
                    'tangential="rigid"; they belong to tangential="mindlin" (the rigid '
                    "stick rule uses none)"
                )
            return
        if isinstance(self.mu, SpeedDependentFriction) and self.mu is not DEFAULT_MU:
            raise ValueError(
                'mu = SpeedDependentFriction with tangential="mindlin": a number (the '
                "compliant pair takes a constant Coulomb coefficient; by default the mean "
                "of the balls' u_b)"
            )
        if self.method is not None:
            raise ValueError(
                f'method = "{self.method}" with tangential="mindlin": None (the compliant '
                f"contact steps with its own Dormand-Prince 5(4); rtol sets its tolerance)"
            )
        # The material, the factor and a given restitution are checked now (BallBall's
        # messages), not at the first collision.
        e = 1.0 if self.restitution is None else self.restitution
        BallBall(mass=1.0, radius=1.0, mu=0.0, **self._compliant_keywords(e))

    def _compliant_keywords(self, e: float) -> dict:
        """BallBall's keywords for the compliant pair with restitution ``e``: elastic Hertz
        at 1, else Hunt and Crossley's damping calibrated to e at ``MINDLIN_AT_SPEED``."""
        kw = dict(
            tangential="mindlin",
            youngs_modulus=self.youngs_modulus,
            poisson_ratio=self.poisson_ratio,
            shear_stiffness_factor=self.shear_stiffness_factor,
            restitution=e,
        )
        if e != 1.0:
            kw.update(damping="hunt-crossley", at_speed=MINDLIN_AT_SPEED)
        return kw

    def _ball_ball(
        self, m1: float, r1: float, m2: float, r2: float, e: float, mu: Any
    ) -> BallBall:
        # mu changes between collisions only when taken from the balls' u_b (a number).
        key = (m1, r1, m2, r2, e, mu if self.tangential == "mindlin" else None)
        model = self._models.get(key)
        if model is None:
            kw: dict = dict(mu=mu, restitution=e)
            if self.tangential == "mindlin":
                kw.update(self._compliant_keywords(e))
            if (m1, r1) == (m2, r2):
                model = BallBall(mass=m1, radius=r1, alpha=self.alpha, **kw)
            else:
                model = BallBall(
                    a=_LibBall(m1, r1, self.alpha), b=_LibBall(m2, r2, self.alpha), **kw
                )
            self._models[key] = model
        return model

    def make_kiss(self, ball1: Ball, ball2: Ball) -> tuple[Ball, Ball]:
        """Places the balls ``const.MIN_DIST`` apart before ``solve``: pooltool's own
        ``make_kiss`` for balls of the same radius; for different radii the same
        construction with the sum of the radii (pooltool's uses twice the first's)."""
        R1, R2 = ball1.params.R, ball2.params.R
        if R1 == R2:
            return super().make_kiss(ball1, ball2)
        r1, r2 = ball1.state.rvw[0], ball2.state.rvw[0]
        v1, v2 = ball1.state.rvw[1], ball2.state.rvw[1]
        target = R1 + R2 + const.MIN_DIST
        c = r2 - r1
        along_paths = not (
            ball1.state.s in const.nontranslating and ball2.state.s in const.nontranslating
        )
        t = _time_to_distance(c, v2 - v1, target) if along_paths else None
        if t is not None:
            n1, n2 = r1 + t * v1, r2 + t * v2
            # Balls moving nearly together move far for a small change of distance: then,
            # as pooltool does, move them along the line of centres instead.
            if np.linalg.norm((n1 + n2 - r1 - r2) / 2) > 5 * const.MIN_DIST:
                t = None
        if t is None:
            u = c / np.linalg.norm(c)
            gap = target - np.linalg.norm(c)
            n1, n2 = r1 - gap / 2 * u, r2 + gap / 2 * u
        ball1.state.rvw[0] = n1
        ball2.state.rvw[0] = n2
        return ball1, ball2

    def resolve_continually_touching(self, ball1: Ball, ball2: Ball) -> tuple[Ball, Ball]:
        """pooltool's adjustment for balls leaving with nearly the same velocity (its own
        method for equal masses; for different masses the same rule moving momentum, not
        velocity), or nothing when ``continually_touching`` is off."""
        if not self.continually_touching:
            return ball1, ball2
        m1, m2 = ball1.params.m, ball2.params.m
        if m1 == m2:
            return super().resolve_continually_touching(ball1, ball2)
        v1, v2 = ball1.state.rvw[1], ball2.state.rvw[1]
        s1, s2 = np.linalg.norm(v1), np.linalg.norm(v2)
        if not (s1 > 0 and s2 > 0):
            return ball1, ball2
        c = ball2.state.rvw[0] - ball1.state.rvw[0]
        u = c / np.linalg.norm(c)
        u1, u2 = float(np.dot(v1, u)), float(np.dot(v2, u))
        if abs(u2 - u1) < 0.01 and np.dot(v1, v2) / (s1 * s2) > 0.9:
            # The chased ball takes 10 % of the chaser's momentum along the line of centres.
            dp = 0.1 * (m1 * u1 if u1 > u2 else m2 * u2)
            sign = 1.0 if u1 > u2 else -1.0
            ball1.state.rvw[1] = v1 - sign * dp / m1 * u
            ball2.state.rvw[1] = v2 + sign * dp / m2 * u
        return ball1, ball2

    def solve(self, ball1: Ball, ball2: Ball) -> tuple[Ball, Ball]:
        """Resolves the collision of two touching (or 1e-6 m apart) balls, in place."""
        p1, p2 = ball1.params, ball2.params
        e, mu = self.restitution, self.mu
        if e is None:
            e = (p1.e_b + p2.e_b) / 2
        if self.tangential == "mindlin" and mu is DEFAULT_MU:
            mu = _mean([p1.u_b, p2.u_b])
        model = self._ball_ball(p1.m, p1.R, p2.m, p2.R, e, mu)
        rvw1 = ball1.state.rvw
        rvw2 = ball2.state.rvw
        r1 = rvw1[0]
        r2 = rvw2[0]
        # Move both centres to touching along the line of centres, about their midpoint.
        dx, dy, dz = (float(r2[0] - r1[0]), float(r2[1] - r1[1]), float(r2[2] - r1[2]))
        dist = math.sqrt(dx * dx + dy * dy + dz * dz)
        if not dist > 0.0:
            raise ValueError(
                f"balls {ball1.id!r} and {ball2.id!r} have the same centre: no line of centres"
            )
        s = 0.5 * (p1.R + p2.R) / dist
        mx, my, mz = (
            0.5 * float(r1[0] + r2[0]),
            0.5 * float(r1[1] + r2[1]),
            0.5 * float(r1[2] + r2[2]),
        )
        pa = (mx - s * dx, my - s * dy, mz - s * dz)
        pb = (mx + s * dx, my + s * dy, mz + s * dz)
        out = model.resolve_lab(
            pa, rvw1[1], rvw1[2], pb, rvw2[1], rvw2[2], method=self.method, rtol=self.rtol
        )
        va, vb = out["va"], out["vb"]
        keep = self.keep_vertical_velocity
        if not (self.is_3d if keep is None else keep):
            va[2] = 0.0
            vb[2] = 0.0
        s1, s2 = self._state(va, r1, p1), self._state(vb, r2, p2)  # (may zero v_z)
        ball1.state = BallState(np.array([r1, va, out["wa"]]), s1)
        ball2.state = BallState(np.array([r2, vb, out["wb"]]), s2)
        return ball1, ball2

    def _state(self, v: np.ndarray, r: np.ndarray, params: Any) -> int:
        """Sliding; in a 3D engine airborne when the ball leaves the table. A ball on the
        table keeps no vertical velocity that would lift it less than
        ``min_bounce_height`` (v_z^2 / 2g, the rule of pooltool's ball-table models, which
        would zero it on landing), nor any downward one (the table's reaction, which the
        two-ball collision leaves out, takes it)."""
        if not (self.is_3d and _AIRBORNE is not None and v[2] != 0.0):
            return const.sliding
        if r[2] > params.R + const.MIN_DIST:
            return _AIRBORNE
        if v[2] > 0.0 and v[2] * v[2] / (2 * params.g) >= self.min_bounce_height:
            return _AIRBORNE
        v[2] = 0.0
        return const.sliding


#: The ball-cushion model's name (``BilliardContactCushion.model``).
CUSHION_MODEL_NAME = "billiard_contact_cushion"


@attrs.define
class BilliardContactCushion(CoreBallLCushionCollision):
    """Ball-linear-cushion impacts resolved by billiard-contact (Mathavan, Jackson and
    Parkin 2010, the library's ``BallCushion``), for pooltool.

    The ball's state is mapped into the cushion's frame of Mathavan's paper: y along the
    segment's normal towards the cushion (``cushion.get_normal_xy``, turned to point along
    the ball's velocity, as pooltool's own ``mathavan_2010`` does), z up, x = y x z along the
    cushion; the library resolves the impact there, and the outgoing velocity and spin are
    mapped back.

    Attributes:
        restitution: e in [0, 1]; ``None``: the ball's ``params.e_c``.
        mu_cushion: friction of the ball on the cushion; ``None``: ``params.f_c``.
        mu_table: friction of the ball on the cloth; ``None``: ``params.u_s``.
        height: the cushion's contact height above the cloth (m); ``None``: the segment's
            ``height``. It must lie between R and 2R; a cushion outside that range (or a
            ball that does not approach it) is left to ``fallback``.
        alpha: I = alpha m R^2 (0.4: solid ball).
        rule: "stronge" (the work of restitution e^2 that of compression, as pooltool's
            ``mathavan_2010``) or "newton".
        method, rtol: the library's integrator ("dop853" by default, "dopri5", "rk4") and
            its tolerance (default 1e-10).
        is_3d: keep the vertical velocity the impact gives (a 3D engine); in a 2D engine
            (pooltool 0.6) it is zeroed, as the ball-ball model does.
        fallback: the strategy for impacts the library does not model (``install`` keeps
            the engine's previous one); ``None`` raises instead.
    """

    restitution: Optional[float] = None
    mu_cushion: Optional[float] = None
    mu_table: Optional[float] = None
    height: Optional[float] = None
    alpha: float = 0.4
    rule: str = "stronge"
    method: Optional[str] = None
    rtol: Optional[float] = None
    is_3d: bool = False
    fallback: Any = None

    if Dim is not None:
        dim: Dim = attrs.field(default=Dim.BOTH, init=False, repr=False)
    model: str = attrs.field(default=CUSHION_MODEL_NAME, init=False, repr=False)
    _models: dict = attrs.field(factory=dict, init=False, repr=False, eq=False)

    def _ball_cushion(self, m: float, R: float, h: float, e: float, mu_i: float, mu_c: float):
        key = (m, R, h, e, mu_i, mu_c)
        model = self._models.get(key)
        if model is None:
            model = BallCushion(
                mass=m, radius=R, alpha=self.alpha, height=h, mu_cushion=mu_i,
                mu_table=mu_c, restitution=e, rule=self.rule,
            )
            self._models[key] = model
        return model

    def solve(self, ball: Ball, cushion: Any) -> tuple[Ball, Any]:
        """Resolves the impact of a ball touching (or 1e-6 m from) a linear cushion."""
        p = ball.params
        h = cushion.height if self.height is None else self.height
        rvw = ball.state.rvw
        v, w = rvw[1], rvw[2]
        normal = np.asarray(cushion.get_normal_xy(ball.xyz), dtype=float)
        if normal[0] * v[0] + normal[1] * v[1] < 0:
            normal = -normal
        ny = math.hypot(normal[0], normal[1])
        y = (normal[0] / ny, normal[1] / ny)
        x = (y[1], -y[0])  # x = y x z
        vc = (x[0] * v[0] + x[1] * v[1], y[0] * v[0] + y[1] * v[1], 0.0)
        on_cloth = v[2] == 0.0 and (_AIRBORNE is None or ball.state.s != _AIRBORNE)
        if not (vc[1] > 0.0 and p.R < h < 2 * p.R and on_cloth):
            if self.fallback is None:
                raise ValueError(
                    f"ball {ball.id!r} on cushion {cushion.id!r}: not an impact the library "
                    f"models (normal speed {vc[1]} m/s, height {h} m for R = {p.R} m, vertical "
                    f"velocity {v[2]} m/s) and no fallback"
                )
            return self.fallback.solve(ball, cushion)
        wc = (x[0] * w[0] + x[1] * w[1], y[0] * w[0] + y[1] * w[1], float(w[2]))
        e = p.e_c if self.restitution is None else self.restitution
        mu_i = p.f_c if self.mu_cushion is None else self.mu_cushion
        mu_c = p.u_s if self.mu_table is None else self.mu_table
        out = self._ball_cushion(p.m, p.R, h, e, mu_i, mu_c).resolve(
            vc, wc, method=self.method, rtol=self.rtol
        )
        (a, b, c), (wa, wb, wz) = out["v"], out["w"]
        v_out = np.array([a * x[0] + b * y[0], a * x[1] + b * y[1], c if self.is_3d else 0.0])
        w_out = np.array([wa * x[0] + wb * y[0], wa * x[1] + wb * y[1], wz])
        state = const.sliding
        if self.is_3d and _AIRBORNE is not None and v_out[2] > 0.0:
            state = _AIRBORNE
        ball.state = BallState(np.array([rvw[0], v_out, w_out]), state)
        return ball, cushion

    def __attrs_post_init__(self) -> None:
        if self.rule not in ("stronge", "newton"):
            raise ValueError(f'rule = "{self.rule}": "stronge" or "newton"')


#: Balls whose surfaces are at most this far apart (m) count as touching when a ball-ball
#: event gathers its cluster: ten times the 1e-6 m gap pooltool leaves between two balls it
#: resolves (``const.MIN_DIST``), so a rack that pooltool has spaced that way is one cluster.
CLUSTER_TOUCH_GAP = 1e-5


@attrs.define
class ClusterResolver(Resolver):
    """pooltool's resolver, but a ball-ball event whose two balls touch others (surfaces
    within ``touch_gap``, default ``CLUSTER_TOUCH_GAP``, through any chain of touching balls:
    a rack, a frozen combination, a row of frozen balls) resolves all of them together with
    the library's ``Cluster`` instead of the pair alone; a pair that touches no other ball,
    and a cluster the library refuses (balls overlapping), go to ``ball_ball`` as before.

    ``cluster_options`` are ``Cluster``'s keywords (docs/python.md): by default resin balls
    (``youngs_modulus=5.4e9``, ``poisson_ratio=0.34``), Hunt-Crossley damping calibrated to
    the mean of the balls' ``e_b`` at ``at_speed=1.0`` m/s, and mu the mean of their
    ``u_b``; ``"rtol"`` among them is the tolerance of ``Cluster.resolve`` (default 1e-8;
    pooltool's balls roll, so its clusters are three-dimensional: a rolling break was
    resolved to about 6e-7 of the cue ball's speed at 1e-8 and 5e-8 at 1e-9). Every ball of
    the cluster leaves with the library's velocity and spin
    (``sliding``; in a 2D engine without vertical velocity) and keeps its position, as the
    two-ball model does; only the event's two balls are in the event's record (pooltool's
    events name two agents).
    """

    cluster_options: dict = attrs.field(factory=dict)
    touch_gap: float = CLUSTER_TOUCH_GAP
    is_3d: bool = False
    _models: dict = attrs.field(factory=dict, init=False, repr=False, eq=False)

    def resolve(self, shot: Any, event: Any) -> None:
        ids = getattr(event, "ids", ())
        if str(getattr(event, "event_type", "")).lower().endswith("ball_ball") and len(ids) == 2:
            members = self._cluster_of(shot, ids)
            if len(members) > 2 and self._resolve_cluster(shot, members, event.time):
                for agent in event.agents:
                    agent.set_final(shot.balls[agent.id])
                return
        super().resolve(shot, event)

    def _cluster_of(self, shot: Any, ids: tuple) -> list:
        """The balls touching the event's pair, through chains of touching balls (pocketed
        balls left out), the pair first."""
        free = [k for k, b in shot.balls.items() if b.state.s != const.pocketed]
        pos = {k: np.asarray(shot.balls[k].state.rvw[0], float) for k in free}
        rad = {k: shot.balls[k].params.R for k in free}
        members, todo = list(ids), list(ids)
        while todo:
            i = todo.pop()
            for j in free:
                if j in members:
                    continue
                if np.linalg.norm(pos[j] - pos[i]) - rad[i] - rad[j] <= self.touch_gap:
                    members.append(j)
                    todo.append(j)
        return members

    def _model(self, balls: list) -> Cluster:
        params = [b.params for b in balls]
        key = tuple((p.m, p.R, p.e_b, p.u_b) for p in params)
        model = self._models.get(key)
        if model is None:
            kw = {
                "youngs_modulus": 5.4e9,
                "poisson_ratio": 0.34,
                "damping": "hunt-crossley",
                "restitution": _mean([p.e_b for p in params]),
                "at_speed": MINDLIN_AT_SPEED,
                "mu": _mean([p.u_b for p in params]),
            }
            kw.update(self.cluster_options)
            kw.pop("rtol", None)  # resolve's, not Cluster's
            alpha = kw.pop("alpha", 0.4)
            if kw.get("restitution") == 1.0 and "coefficient" not in self.cluster_options:
                kw.pop("restitution")
                kw.pop("at_speed", None)
                kw["damping"] = None
            lib_balls = [_LibBall(p.m, p.R, alpha) for p in params]
            model = Cluster(balls=lib_balls, **kw)
            self._models[key] = model
        return model

    def _resolve_cluster(self, shot: Any, members: list, time: float) -> bool:
        balls = [shot.balls[k] for k in members]
        rvw = np.array([np.asarray(b.state.rvw, float) for b in balls])
        try:
            out = self._model(balls).resolve(
                rvw[:, 0], rvw[:, 1], rvw[:, 2], rtol=self.cluster_options.get("rtol")
            )
        except ValueError:
            return False  # overlapping balls: the pair alone, as pooltool would
        for b, r, v, w in zip(balls, rvw[:, 0], out["velocities"], out["spins"]):
            v = np.array(v)
            if not self.is_3d:
                v[2] = 0.0
            if np.array_equal(v, b.state.rvw[1]) and np.array_equal(w, b.state.rvw[2]):
                continue  # a ball the cluster did not move keeps its state
            b.state = BallState(np.array([r, v, w]), const.sliding, time)
        return True


def _mean(xs: list) -> float:
    """The mean; the value itself when all are equal (a mean of equal numbers may round)."""
    return float(xs[0]) if all(x == xs[0] for x in xs) else float(np.mean(xs))


def _time_to_distance(c: np.ndarray, b: np.ndarray, target: float) -> Optional[float]:
    """The time t of least |t| at which |c + t b| = target (c: the centres' offset, b: the
    relative velocity), or None when there is none (no relative motion, or the paths never
    come that far apart or close)."""
    a = float(np.dot(b, b))
    half_b = float(np.dot(b, c))
    cc = float(np.dot(c, c)) - target * target
    disc = half_b * half_b - a * cc
    if not (a > 0.0 and disc >= 0.0):
        return None
    # The two roots without cancellation: q = -(half_b + sign(half_b) sqrt(disc)).
    q = -(half_b + math.copysign(math.sqrt(disc), half_b))
    roots = [x for x in (q / a, cc / q if q != 0.0 else None) if x is not None]
    return min(roots, key=abs)


def install(
    engine: Any = None,
    *,
    cushion: bool = True,
    cushion_options: Optional[dict] = None,
    cluster: bool = False,
    cluster_options: Optional[dict] = None,
    **options: Any,
) -> BilliardContact:
    """Makes ``BilliardContact(**options)`` the ball-ball model of ``engine`` (pooltool
    0.6's ``pooltool.physics.PhysicsEngine`` or, after 0.6, a
    ``pooltool.evolution.SimulationEngine``), or of pooltool's default engine when
    ``engine`` is None (used by ``pt.simulate`` without ``engine=`` and by the GUI).
    Returns the model.

    With ``cushion=True`` (the default) the ball-linear-cushion model becomes
    ``BilliardContactCushion(**cushion_options)``, which leaves what the library does not
    model (a cushion outside R < height < 2R, a ball in the air) to the engine's previous
    model (its ``fallback``); circular cushion segments (the pockets' jaws) keep the
    engine's model. ``cushion=False`` leaves the cushions to the engine.

    With ``cluster=True`` the engine's resolver becomes a ``ClusterResolver`` with the same
    strategies: a ball-ball event whose balls touch others (a rack, frozen balls) is
    resolved for all of them at once by the library's ``Cluster(**cluster_options)``.

    ``is_3d`` is the engine's (``engine.is_3d``; False for 0.6's engine, which has none):
    in a 3D engine the vertical velocity is kept unless ``keep_vertical_velocity=False``
    is given. ``install(engine, continually_touching=False)`` skips pooltool's
    ``resolve_continually_touching`` after each collision.
    """
    if engine is None:
        engine = _first_found("pooltool.evolution.event_based.simulate:DEFAULT_ENGINE")
    resolver = getattr(engine, "resolver", None)
    if resolver is None or not hasattr(resolver, "ball_ball"):
        raise TypeError(
            f"install(engine): expected a pooltool engine (PhysicsEngine or SimulationEngine, "
            f"with resolver.ball_ball), got {type(engine).__name__}"
        )
    options.setdefault("is_3d", bool(getattr(engine, "is_3d", False)))
    settle = getattr(getattr(resolver, "ball_table", None), "min_bounce_height", None)
    if isinstance(settle, (int, float)):
        options.setdefault("min_bounce_height", float(settle))
    model = BilliardContact(**options)
    resolver.ball_ball = model
    if cushion and hasattr(resolver, "ball_linear_cushion"):
        previous = resolver.ball_linear_cushion
        if isinstance(previous, BilliardContactCushion):
            previous = previous.fallback
        cushion_kwargs = dict(cushion_options or {})
        cushion_kwargs.setdefault("is_3d", options["is_3d"])
        cushion_kwargs.setdefault("fallback", previous)
        resolver.ball_linear_cushion = BilliardContactCushion(**cushion_kwargs)
    if cluster:
        fields = {f.name: getattr(resolver, f.name) for f in attrs.fields(type(resolver))
                  if f.init and f.name not in ("cluster_options", "touch_gap", "is_3d")}
        engine.resolver = ClusterResolver(
            **fields, cluster_options=dict(cluster_options or {}), is_3d=options["is_3d"]
        )
    return model
