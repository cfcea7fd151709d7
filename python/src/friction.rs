//! `SpeedDependentFriction`, and the friction argument `mu` of `BallBall`.

use crate::errors::to_py;
use billiard_contact::{Error, Evaluate, Friction};
use pyo3::prelude::*;

/// The names `evaluate=` takes: the library's (scene files' `contact.mu.evaluate`) first,
/// then the names of the first release, kept as aliases.
pub(crate) const EVALUATE_NAMES: [(&str, Evaluate); 4] = [
    ("along-contact", Evaluate::AlongContact),
    ("initial", Evaluate::Initial),
    ("contact", Evaluate::AlongContact),
    ("initial-slip", Evaluate::Initial),
];

/// Ball-ball friction mu(S) = a + b exp(-c S), S the sliding speed of the contact
/// points (m/s); a, b dimensionless, c in s/m.
///
/// `evaluate="along-contact"` (default): mu at the current sliding speed all along the
/// contact (the sliding speed falls as the friction acts).
/// `evaluate="initial"`: mu frozen at the sliding speed before the collision, mu(S(0)),
/// and used as a constant coefficient (pooltool's convention).
/// The names are the scene files' (`contact.mu.evaluate`); "contact" and "initial-slip"
/// are accepted for them too.
#[pyclass(
    frozen,
    module = "billiard_contact._core",
    name = "SpeedDependentFriction"
)]
#[derive(Clone, Copy)]
pub struct SpeedDependentFriction {
    /// The law, evaluated as `evaluate=` says.
    pub(crate) friction: Friction,
    #[pyo3(get)]
    pub(crate) a: f64,
    #[pyo3(get)]
    pub(crate) b: f64,
    #[pyo3(get)]
    pub(crate) c: f64,
    pub(crate) evaluate: Evaluate,
}

#[pymethods]
impl SpeedDependentFriction {
    #[new]
    #[pyo3(signature = (a, b, c, evaluate = "along-contact".to_string()),
           text_signature = "(a, b, c, evaluate='along-contact')")]
    fn new(
        #[pyo3(from_py_with = crate::args::a_real)] a: f64,
        #[pyo3(from_py_with = crate::args::b_real)] b: f64,
        #[pyo3(from_py_with = crate::args::c_real)] c: f64,
        #[pyo3(from_py_with = crate::args::evaluate)] evaluate: String,
    ) -> PyResult<Self> {
        let evaluate = evaluate.as_str();
        let friction = Friction::speed_dependent(a, b, c).map_err(to_py)?;
        let Some(&(_, evaluate)) = EVALUATE_NAMES.iter().find(|(name, _)| *name == evaluate) else {
            let accepted: Vec<String> = EVALUATE_NAMES
                .iter()
                .map(|(name, _)| format!("\"{name}\""))
                .collect();
            return Err(to_py(Error::invalid(
                "evaluate",
                format!("\"{evaluate}\""),
                format!(
                    "{} (mu(S) along the contact) or {} (mu(S(0)) frozen, pooltool's \
                     convention); also {} and {}",
                    accepted[0], accepted[1], accepted[2], accepted[3]
                ),
            )));
        };
        Ok(SpeedDependentFriction {
            friction: friction.evaluated(evaluate),
            a,
            b,
            c,
            evaluate,
        })
    }

    /// Where mu(S) is evaluated: "along-contact" or "initial" (the library's names).
    #[getter]
    fn evaluate(&self) -> &'static str {
        self.evaluate.name()
    }

    /// mu at sliding speed `s` (m/s).
    fn mu(&self, #[pyo3(from_py_with = crate::args::s)] s: f64) -> f64 {
        self.friction.mu(s)
    }

    /// Equal when a, b, c and `evaluate` are (the same law, evaluated the same way).
    fn __eq__(&self, other: &Self) -> bool {
        (self.a, self.b, self.c, self.evaluate) == (other.a, other.b, other.c, other.evaluate)
    }

    /// Pickling and copying: `SpeedDependentFriction(a, b, c, evaluate)` again.
    fn __getnewargs__(&self) -> (f64, f64, f64, &'static str) {
        (self.a, self.b, self.c, self.evaluate())
    }

    pub(crate) fn __repr__(&self) -> String {
        format!(
            "SpeedDependentFriction(a={:?}, b={:?}, c={:?}, evaluate=\"{}\")",
            self.a,
            self.b,
            self.c,
            self.evaluate()
        )
    }
}

/// The friction argument of `BallBall`: a number or a `SpeedDependentFriction`.
#[derive(Clone, Copy)]
pub(crate) enum Mu {
    Constant(f64),
    Speed(SpeedDependentFriction),
}

impl<'a, 'py> FromPyObject<'a, 'py> for Mu {
    type Error = PyErr;
    fn extract(ob: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if let Ok(s) = ob.cast::<SpeedDependentFriction>() {
            return Ok(Mu::Speed(*s.get()));
        }
        match ob.extract::<f64>() {
            Ok(x) => Ok(Mu::Constant(x)),
            Err(_) => Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "mu: expected a number or SpeedDependentFriction, got {}",
                ob.get_type().name()?
            ))),
        }
    }
}
