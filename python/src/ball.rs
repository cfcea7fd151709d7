//! `Ball`: one ball of a `BallBall` pair given ball by ball (`a=Ball(...), b=Ball(...)`),
//! for balls of different mass, size or inertia (docs/unequal-balls.md).

use crate::errors::to_py;
use pyo3::prelude::*;

/// One ball: mass (kg), radius (m), alpha (I = alpha m r^2, in [1e-12, 2/3]; 0.4 a solid
/// ball). Give two to BallBall(a=..., b=...) for balls of different mass, size or
/// inertia.
///
/// Bad values raise ValueError with the library's message, e.g. "ball.mass = -1: > 0 kg".
#[pyclass(frozen, module = "billiard_contact._core", name = "Ball")]
#[derive(Clone, Copy)]
pub struct Ball {
    pub(crate) ball: billiard_contact::Ball,
}

#[pymethods]
impl Ball {
    #[new]
    #[pyo3(signature = (mass, radius, alpha = 0.4))]
    fn new(
        #[pyo3(from_py_with = crate::args::mass)] mass: f64,
        #[pyo3(from_py_with = crate::args::radius)] radius: f64,
        #[pyo3(from_py_with = crate::args::alpha)] alpha: f64,
    ) -> PyResult<Self> {
        let ball =
            billiard_contact::Ball::in_section("ball", mass, radius, alpha).map_err(to_py)?;
        Ok(Ball { ball })
    }

    /// Mass m (kg).
    #[getter]
    fn mass(&self) -> f64 {
        self.ball.mass()
    }

    /// Radius r (m).
    #[getter]
    fn radius(&self) -> f64 {
        self.ball.radius()
    }

    /// I = alpha m r^2.
    #[getter]
    fn alpha(&self) -> f64 {
        self.ball.alpha()
    }

    fn __eq__(&self, other: &Self) -> bool {
        self.ball == other.ball
    }

    /// Pickling and copying: `Ball(mass, radius, alpha)` again (the same numbers, so the
    /// same ball bit for bit).
    fn __getnewargs__(&self) -> (f64, f64, f64) {
        (self.ball.mass(), self.ball.radius(), self.ball.alpha())
    }

    pub(crate) fn __repr__(&self) -> String {
        format!(
            "Ball(mass={:?}, radius={:?}, alpha={:?})",
            self.ball.mass(),
            self.ball.radius(),
            self.ball.alpha()
        )
    }
}
