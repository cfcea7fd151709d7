"""billiard-contact: the contact phase of billiard-ball collisions with spin and friction.

After C. S. Peskin, *Collision of Billiard Balls in 3D with Spin and Friction* (2020): the
exact closed form (with sliding that stops during contact) and time-stepping integrators.
SI units throughout (kg, m, s, m/s, rad/s, N s, J).

- ``run(path, ...)`` / ``run_toml(text, ...)``: a scene, as ``billiard-contact run SCENE
  --json``; returns the same JSON object as a dict (``report["trace"]`` with ``samples``).
- ``BallBall(mass=, radius=, alpha=0.4, mu=, restitution=1.0)``: two identical balls;
  ``BallBall(a=Ball(mass, radius, alpha), b=Ball(...), mu=, ...)``: balls of different
  mass, size or inertia; ``model.resolve_lab(pa, va, wa, pb, vb, wb, up=(0, 0, 1))``
  resolves one collision or N (arrays of shape (3,) or (N, 3)).
- ``SpeedDependentFriction(a=, b=, c=)``: mu(S) = a + b exp(-c S).
- ``BallPlane(mass=, radius=, alpha=0.4, mu=, restitution=1.0)``: a ball against a plane;
  ``plane.resolve(v, w, normal)`` resolves one impact or N (arrays of shape (3,) or (N, 3)).
- ``BallCushion(mass=, radius=, alpha=0.4, height=, mu_cushion=, mu_table=, restitution=)``:
  a ball on the cloth against a cushion (Mathavan 2010), ``cushion.resolve(v, w)`` in the
  cushion's frame (x along it, y towards it, z up).
- ``Cluster(balls=[Ball(...), ...], mu=, youngs_modulus=, poisson_ratio=, damping=None,
  restitution=, at_speed=)``: N balls resolved together (a break, a frozen combination,
  Newton's cradle); ``cluster.resolve(positions, velocities, spins)`` on (N, 3) arrays.
- ``billiard_contact.pooltool``: ball-ball and ball-linear-cushion models for pooltool's
  ``Resolver``.

Bad input raises ``ValueError`` with the command line's one-line message (the field, the
value, what is accepted); a failed run raises ``RuntimeError``.
"""

from billiard_contact._core import (
    TRACE_COLUMNS,
    Ball,
    BallBall,
    BallCushion,
    BallPlane,
    Cluster,
    SpeedDependentFriction,
    __version__,
    run,
    run_toml,
)

__all__ = [
    "TRACE_COLUMNS",
    "Ball",
    "BallBall",
    "BallCushion",
    "BallPlane",
    "Cluster",
    "SpeedDependentFriction",
    "__version__",
    "run",
    "run_toml",
]
