//! The crate's one error type.
//!
//! Every variant carries the physical or file context a user needs to fix the
//! problem: the field, the value and the accepted range; the file and line; the
//! integrator, the scaled time and the cause. Bad input and failed runs are told
//! apart by [`Error::is_bad_input`], which the command line maps to exit codes
//! 2 and 1.

use std::path::PathBuf;

/// Errors of the library and the command line.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter outside its physical range.
    #[error("{field} = {value}: {expected}")]
    InvalidParameter {
        /// Dotted name of the field, as in the scene file (e.g. `balls.mass`).
        field: String,
        /// The offending value as given.
        value: String,
        /// What is accepted, and why when it is not obvious.
        expected: String,
    },

    /// A scene file that is not valid TOML or does not match the scene format.
    #[error("{path}: {message}")]
    Scene {
        /// The scene file.
        path: PathBuf,
        /// What is wrong, with the line where the parser knows it.
        message: String,
    },

    /// A tabulated profile CSV with a bad line.
    #[error("{path}:{line}: {message}")]
    ProfileTable {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line number in the file (0 when the file as a whole is at fault).
        line: u64,
        /// What is wrong with that line.
        message: String,
    },

    /// A batch input CSV with a bad line.
    #[error("{path}:{line}: {message}")]
    BatchInput {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line number.
        line: u64,
        /// What is wrong with that line.
        message: String,
    },

    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The cause.
        #[source]
        source: std::io::Error,
    },

    /// Writing CSV failed.
    #[error("writing CSV: {source}")]
    Csv {
        /// The cause.
        #[from]
        source: csv::Error,
    },

    /// Serialising the JSON report failed.
    #[error("writing JSON: {source}")]
    Json {
        /// The cause.
        #[from]
        source: serde_json::Error,
    },

    /// The ODE integrator gave up.
    #[error("{method} failed at t/duration = {scaled_time:.6e}: {source}")]
    Integration {
        /// Method name (`rk4`, `dopri5`, `dop853`).
        method: &'static str,
        /// Scaled time t/duration of the segment start where it failed.
        scaled_time: f64,
        /// The cause reported by `ode_solvers`.
        #[source]
        source: ode_solvers::dop_shared::IntegrationError,
    },

    /// A computed quantity is NaN or infinite: the run failed.
    #[error("non-finite result: {field} = {value}")]
    NonFinite {
        /// Name of the output field.
        field: String,
        /// Its value.
        value: f64,
    },
}

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub fn invalid(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        expected: impl Into<String>,
    ) -> Self {
        Error::InvalidParameter {
            field: field.into(),
            value: value.to_string(),
            expected: expected.into(),
        }
    }

    /// Shorthand for [`Error::Io`].
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source,
        }
    }

    /// [`Error::Io`] whose message says what was being done: `what` (e.g. "cannot read the
    /// scene file"), then the system's cause.
    pub fn io_doing(path: impl Into<PathBuf>, what: &str, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source: std::io::Error::new(source.kind(), format!("{what}: {source}")),
        }
    }

    /// True when the error is the user's input (exit code 2), false when the run
    /// itself failed (exit code 1).
    pub fn is_bad_input(&self) -> bool {
        match self {
            Error::InvalidParameter { .. }
            | Error::Scene { .. }
            | Error::ProfileTable { .. }
            | Error::BatchInput { .. } => true,
            Error::Io { source, .. } => !matches!(
                source.kind(),
                std::io::ErrorKind::Interrupted | std::io::ErrorKind::OutOfMemory
            ),
            _ => false,
        }
    }
}

/// Checks that `value` is finite, naming `field` otherwise.
pub fn finite(field: &str, value: f64) -> Result<f64, Error> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(field, value, "a finite number"))
    }
}
