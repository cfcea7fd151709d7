//! Solver settings: how the bindings build them from Python keywords, with the library's own
//! override rule (the one `billiard-contact run` applies).

use billiard_contact::SolverOverrides;
use billiard_contact::{Error, Method, SolverSettings};
use pyo3::exceptions::PyUserWarning;
use pyo3::prelude::*;

/// A method name as the command line takes it (`closed-form`, `rk4`, `dopri5`, `dop853`).
pub fn method(name: &str) -> Result<Method, Error> {
    name.parse::<Method>()
}

/// The overrides of `billiard-contact run`: `--method`, `--rtol` (which carries atol with
/// it unless atol is given), `--atol`, `--steps`, `--time-transform` (`None`: the
/// scene's, by default the library's); applied to the scene's `[solver]` with
/// [`SolverOverrides::apply`].
pub fn overrides(
    method_name: Option<&str>,
    rtol: Option<f64>,
    atol: Option<f64>,
    steps: Option<u32>,
    time_transform: Option<bool>,
) -> Result<SolverOverrides, Error> {
    Ok(SolverOverrides {
        method: method_name.map(method).transpose()?,
        rtol,
        atol,
        steps,
        time_transform,
    })
}

/// The warnings for the keywords of `overrides` a run with `settings` does not use
/// ([`SolverOverrides::unused`], the rule `billiard-contact` warns by), named as keywords.
pub fn unused(overrides: &SolverOverrides, settings: &SolverSettings, law: bool) -> Vec<String> {
    overrides
        .unused(settings, law)
        .into_iter()
        .map(|(field, why)| format!("{field}= has no effect with {why}"))
        .collect()
}

/// Each message as a Python `UserWarning`, attributed to the caller.
pub fn warn_all(py: Python<'_>, messages: &[String]) -> PyResult<()> {
    let category = py.get_type::<PyUserWarning>();
    for m in messages {
        let text = std::ffi::CString::new(m.as_str()).unwrap_or_default();
        PyErr::warn(py, &category, &text, 1)?;
    }
    Ok(())
}

/// Settings for a batch: the closed form unless a method is named; `rtol` (default the
/// library's, 1e-10) sets atol too, as `billiard-contact batch --rtol` does;
/// `time_transform` as `--time-transform` (default the library's).
pub fn for_batch(
    method_name: Option<&str>,
    rtol: Option<f64>,
    time_transform: Option<bool>,
) -> Result<SolverSettings, Error> {
    SolverOverrides {
        method: Some(
            method_name
                .map(method)
                .transpose()?
                .unwrap_or(Method::ClosedForm),
        ),
        rtol,
        atol: None,
        steps: None,
        time_transform,
    }
    .apply(&SolverSettings::default())
}
