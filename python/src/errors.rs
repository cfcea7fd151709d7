//! Library errors as Python exceptions.

use billiard_contact::Error;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::PyErr;

/// Bad input (the command line's exit code 2) is ValueError, a failed run (exit code 1:
/// the integrator gave up, a non-finite result) RuntimeError; the message is the
/// library's one line, as the command line prints it after `error: `.
pub fn to_py(e: Error) -> PyErr {
    if e.is_bad_input() {
        PyValueError::new_err(e.to_string())
    } else {
        PyRuntimeError::new_err(e.to_string())
    }
}

/// A scene error of text given without a file names `<toml text>` instead of the built-in
/// scene.
pub fn unwrap_scene_message(e: Error) -> Error {
    match e {
        Error::Scene { message, .. } => Error::Scene {
            path: "<toml text>".into(),
            message,
        },
        other => other,
    }
}
