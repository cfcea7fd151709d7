"""A pooltool ball-ball collision model backed by billiard-contact.

Install it into an engine (one line), or into pooltool's default engine, the one
``pt.simulate`` uses without ``engine=`` and the one the GUI uses::

    import pooltool as pt
    from billiard_contact.pooltool import install

    engine = pt.physics.PhysicsEngine(); install(engine)   # then pt.simulate(system, engine=engine)
    install()                                               # pooltool's default engine (and GUI)

or set ``engine.resolver.ball_ball = BilliardContact(...)`` yourself. Written for pooltool
0.6 (``pip install pooltool-billiards==0.6.0``).

What the model does with pooltool's balls (``ball.state.rvw``: position, velocity, spin;
lab frame, z up; any memory order):

- Geometry. pooltool's ``make_kiss`` leaves the balls ``const.MIN_DIST`` (1e-6 m) apart
  before ``solve``. The collision is resolved along the actual line of centres: both
  centres are moved along it, symmetrically about their midpoint, to touching (|pb - pa| =
  2R) for the library, which requires touching balls. The balls keep their own positions.
- Parameters. Mass and radius are the balls' (``ball.params.m``, ``ball.params.R``; both
  balls must have the same, as the model is for identical balls); ``restitution=None``
  takes the mean of the balls' ``e_b`` as pooltool does.
- Vertical velocity. pooltool 0.6 is two-dimensional and its ``frictional_inelastic``
  model zeroes the vertical velocity after a collision; so does this one unless
  ``keep_vertical_velocity=True`` (the library resolves the collision in 3D, and a ball
  hit with follow or draw spin gets a small vertical velocity from friction).
- Friction. ``mu`` is a number or a ``SpeedDependentFriction(a, b, c)`` (default: the
  fit a + b exp(-c S) that pooltool's default resolver uses, a = 9.951e-3, b = 0.108,
  c = 1.088). ``SpeedDependentFriction(..., evaluate="along-contact")`` (default)
  evaluates mu at the current sliding speed all along the contact;
  ``evaluate="initial"`` freezes mu at the sliding speed before the collision, pooltool's
  convention: mu(S(0)) is computed from the incoming state and used as a constant
  coefficient (the first release's names "contact" and "initial-slip" work too).
- Motion state. Both balls leave the collision ``const.sliding``.

Differences from pooltool's ``frictional_inelastic``: that model's tangential impulse is
mu e m dv_n (e the restitution), this one's mu (1 + e)/2 m dv_n (Coulomb friction over the
whole normal impulse, the paper's model); the two agree when e = 1 (the tests compare them
to 1e-12). The library stops sliding when the contact points stop slipping (the same rule
as pooltool's no-slip branch).

This model is not registered with pooltool's serialisation (its registry of ball-ball
models is a closed enumeration), so a resolver using it cannot be saved to
``resolver.yaml``; install it in code.
"""

from __future__ import annotations

import math
from typing import Any, Optional, Union

import attrs
import numpy as np
import pooltool.constants as const
from pooltool.objects.ball.datatypes import Ball, BallState
from pooltool.physics.resolve.ball_ball.core import CoreBallBallCollision

from billiard_contact import BallBall, SpeedDependentFriction

__all__ = ["BilliardContact", "install", "MODEL_NAME"]

MODEL_NAME = "billiard_contact"
"""The value of ``BilliardContact.model`` (pooltool identifies models by this attribute)."""

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
        keep_vertical_velocity: keep the vertical velocity the collision gives (off: zeroed,
            as pooltool 0.6's models do).
        method: ``None`` (the closed form) or a time-stepping method of the library
            ("rk4", "dopri5", "dop853"); ``rtol`` its tolerance.
    """

    mu: Union[float, SpeedDependentFriction] = DEFAULT_MU
    restitution: Optional[float] = None
    alpha: float = 0.4
    keep_vertical_velocity: bool = False
    method: Optional[str] = None
    rtol: Optional[float] = None

    model: str = attrs.field(default=MODEL_NAME, init=False, repr=False)
    _models: dict = attrs.field(factory=dict, init=False, repr=False, eq=False)

    def _ball_ball(self, m: float, radius: float, e: float) -> BallBall:
        key = (m, radius, e)
        model = self._models.get(key)
        if model is None:
            model = BallBall(
                mass=m, radius=radius, alpha=self.alpha, mu=self.mu, restitution=e
            )
            self._models[key] = model
        return model

    def solve(self, ball1: Ball, ball2: Ball) -> tuple[Ball, Ball]:
        """Resolves the collision of two touching (or 1e-6 m apart) balls, in place."""
        p1, p2 = ball1.params, ball2.params
        if p1.m != p2.m or p1.R != p2.R:
            raise ValueError(
                f"balls {ball1.id!r} and {ball2.id!r}: mass {p1.m} and {p2.m} kg, radius "
                f"{p1.R} and {p2.R} m: the model is for identical balls"
            )
        e = self.restitution
        if e is None:
            e = (p1.e_b + p2.e_b) / 2
        model = self._ball_ball(p1.m, p1.R, e)
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
        s = p1.R / dist
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
        if not self.keep_vertical_velocity:
            va[2] = 0.0
            vb[2] = 0.0
        ball1.state = BallState(np.array([r1, va, out["wa"]]), const.sliding)
        ball2.state = BallState(np.array([r2, vb, out["wb"]]), const.sliding)
        return ball1, ball2


def install(engine: Any = None, **options: Any) -> BilliardContact:
    """Makes ``BilliardContact(**options)`` the ball-ball model of ``engine`` (a
    ``pooltool.physics.PhysicsEngine``), or of pooltool's default engine when ``engine`` is
    None (used by ``pt.simulate`` without ``engine=`` and by the GUI). Returns the model.
    """
    model = BilliardContact(**options)
    if engine is None:
        from pooltool.evolution.event_based import simulate as _simulate

        engine = _simulate.DEFAULT_ENGINE
    engine.resolver.ball_ball = model
    return model
