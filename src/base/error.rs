//! The crate's one error type.
//!
//! Every variant carries the physical or file context a user needs to fix the
//! problem: the field, the value and the accepted range; the file and line; the
//! method, the scaled time and the cause. Bad input and failed runs are told
//! apart by [`Error::is_bad_input`], which the command line maps to exit codes
//! 2 and 1.

use crate::base::number::readable_numbers;
use std::path::PathBuf;

/// Errors of the library and the command line.
///
/// Match on the variant to tell the cases apart; the message ([`std::fmt::Display`]) is one
/// line meant for people. [`Error::is_bad_input`] sorts the variants into the user's input
/// (exit code 2) and failed runs (exit code 1). New variants may be added.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter outside its accepted range: from a validating constructor or setter
    /// (ball, contact, profile, solver settings, table) or from a scene file's value.
    #[error("{field} = {value}: {expected}")]
    InvalidParameter {
        /// Dotted name of the field, as in the scene file (e.g. `balls.mass`).
        field: String,
        /// The offending value as given.
        value: String,
        /// What is accepted, and why when it is not obvious.
        expected: String,
    },

    /// A lab-frame scene whose balls do not touch: the distance of the centres is not
    /// r_A + r_B (2r for identical balls) within a relative `tolerance` (the message names
    /// the field `incoming.lab.b.position`, and a unit slip that explains the distance: a
    /// radius or positions in millimetres).
    #[error(
        "incoming.lab.b.position = [{}, {}, {}] (|p_B - p_A| = {distance} m): the balls must \
         touch: |p_B - p_A| = {contact_term} = {contact_distance} m within a relative \
         {tolerance:e}{}",
        .position_b[0], .position_b[1], .position_b[2],
        crate::base::plausible::not_touching_hint(*.distance, *.contact_distance, .contact_term)
    )]
    NotTouching {
        /// Position of ball B (m, lab frame), as given.
        position_b: [f64; 3],
        /// |p_B - p_A| (m).
        distance: f64,
        /// r_A + r_B (m), the distance of touching balls.
        contact_distance: f64,
        /// How the message names that distance: "2r" for identical balls, "r_A + r_B".
        contact_term: &'static str,
        /// |p_B - p_A| - (r_A + r_B) (m): positive when the balls are apart, negative when
        /// they overlap.
        gap: f64,
        /// Accepted relative difference of the distance from r_A + r_B.
        tolerance: f64,
    },

    /// A scene file that is not valid TOML or does not match the scene format.
    #[error("{path}: {msg}", msg = one_line(message))]
    Scene {
        /// The scene file.
        path: PathBuf,
        /// What is wrong, with the line where the parser knows it.
        message: String,
    },

    /// A tabulated profile with a bad point: a line of its CSV file, or a point given to
    /// [`crate::profile::Tabulated::new`] (line 0).
    #[error("{path}:{line}: {message}")]
    ProfileTable {
        /// The CSV file (or the name the caller gave the table).
        path: PathBuf,
        /// 1-based line number in the file (0 when the table as a whole is at fault).
        line: u64,
        /// What is wrong with that line.
        message: String,
    },

    /// A batch input CSV with a bad line (including a row whose run failed).
    #[error("{path}:{line}: {message}")]
    BatchInput {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line number.
        line: u64,
        /// What is wrong with that line.
        message: String,
    },

    /// Reading or writing a file (or a stream: `stdout`, a trace writer) failed.
    #[error("{path}: {source}")]
    Io {
        /// The file concerned, or the stream when it has no path.
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

    /// Drawing a figure failed (the plotting backend's error, typically the file it
    /// renders to).
    #[error("{path}: {message}")]
    Plot {
        /// The figure's file (`plot` when the caller did not say).
        path: PathBuf,
        /// What went wrong, with the backend's cause.
        message: String,
    },

    /// The worker threads of a batch could not be started (`--threads`).
    #[error("thread pool: {source}")]
    ThreadPool {
        /// The cause reported by the thread pool.
        #[from]
        source: rayon::ThreadPoolBuildError,
    },

    /// An adaptive method (`dopri5`, `dop853`) needed a step below its floor of about
    /// 10 eps |t|: the force profile or the state changes faster than double precision
    /// can resolve there.
    #[error(
        "{method} failed at t/duration = {scaled_time:.6e}: step size underflow (segment from \
         t/duration = {segment_start:.6e})"
    )]
    StepSizeTooSmall {
        /// The method.
        method: crate::base::method::Method,
        /// Scaled time t/duration where the method gave up.
        scaled_time: f64,
        /// Scaled time of the start of the segment it was integrating.
        segment_start: f64,
    },

    /// An adaptive method took its maximum number of steps in one segment without reaching
    /// its end (a tolerance too tight for the profile).
    #[error(
        "{method} failed at t/duration = {scaled_time:.6e}: more than {steps} steps (segment \
         from t/duration = {segment_start:.6e})"
    )]
    TooManySteps {
        /// The method.
        method: crate::base::method::Method,
        /// Scaled time t/duration where the method gave up.
        scaled_time: f64,
        /// Scaled time of the start of the segment it was integrating.
        segment_start: f64,
        /// The step limit.
        steps: u32,
    },

    /// An adaptive method's stiffness test fired: explicit steps are limited by stability,
    /// not accuracy (a friction law too steep for the method).
    #[error(
        "{method} failed at t/duration = {scaled_time:.6e}: the problem became stiff (segment \
         from t/duration = {segment_start:.6e})"
    )]
    Stiff {
        /// The method.
        method: crate::base::method::Method,
        /// Scaled time t/duration where the method gave up.
        scaled_time: f64,
        /// Scaled time of the start of the segment it was integrating.
        segment_start: f64,
    },

    /// A cluster's run (docs/cluster.md) that ended before every contact opened: its step
    /// control stalled (`step-too-small`) or it reached its work bound (`work-bound`).
    #[error(
        "the cluster's run stopped ({stop}) at t = {} after {steps} steps with \
         contacts still compressed or closing; a looser rtol, or fewer balls at once",
        crate::base::number::si(*.time, "s", 5)
    )]
    ClusterStopped {
        /// Why it stopped, as the report names it.
        stop: &'static str,
        /// Time the run covered (s).
        time: f64,
        /// Accepted steps.
        steps: u64,
    },

    /// A computed quantity is NaN or infinite (an integrated state, a report or trace
    /// value): the run failed.
    #[error("non-finite result: {field} = {value}")]
    NonFinite {
        /// Name of the output field.
        field: String,
        /// Its value.
        value: f64,
    },
}

/// A value echoed in a message, kept to one line: control characters (a newline or tab
/// inside a scene's string) are written as their escapes (`\n`, `\t`).
fn one_line(s: &str) -> String {
    s.chars()
        .flat_map(|c| {
            let escaped: Vec<char> = if c.is_control() {
                c.escape_debug().collect()
            } else {
                vec![c]
            };
            escaped
        })
        .collect()
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
            value: readable_numbers(&one_line(&value.to_string())),
            expected: readable_numbers(&expected.into()),
        }
    }

    /// The error with `from` in its field and value named `to` instead (a law's keys
    /// `contact.law.` given in another section, `cloth.`); other errors as they are.
    pub(crate) fn moved(self, from: &str, to: &str) -> Self {
        match self {
            Error::InvalidParameter {
                field,
                value,
                expected,
            } => Error::InvalidParameter {
                field: field.replace(from, to),
                value: value.replace(from, to),
                expected,
            },
            e => e,
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
    /// itself failed (exit code 1). I/O errors count as input (a path that cannot be read
    /// or written) unless interrupted or out of memory; a figure that cannot be drawn and
    /// worker threads that cannot be started count as input too (the output path, the
    /// `--threads` asked for).
    pub fn is_bad_input(&self) -> bool {
        match self {
            Error::InvalidParameter { .. }
            | Error::NotTouching { .. }
            | Error::Scene { .. }
            | Error::ProfileTable { .. }
            | Error::BatchInput { .. }
            | Error::Plot { .. }
            | Error::ThreadPool { .. } => true,
            Error::Io { source, .. } => !matches!(
                source.kind(),
                std::io::ErrorKind::Interrupted | std::io::ErrorKind::OutOfMemory
            ),
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::base::method::Method;

    /// A value with a newline and a tab (a scene string `"new\nton"`) is echoed on one line,
    /// its control characters written as escapes; other characters are kept as given.
    #[test]
    fn an_echoed_value_stays_one_line() {
        let e = Error::invalid(
            "cushion.rule",
            "\"new\nton\tx é\"",
            "\"stronge\" or \"newton\"",
        );
        assert_eq!(
            e.to_string(),
            r#"cushion.rule = "new\nton\tx é": "stronge" or "newton""#
        );
    }

    /// Exit codes: the variants that replaced an InvalidParameter or an Io (kind Other)
    /// stay bad input (2); the integrator's failures stay failed runs (1).
    #[test]
    fn exit_codes_of_the_new_variants() {
        let plot = Error::Plot {
            path: "fig.png".into(),
            message: "drawing the figure: backend".into(),
        };
        assert!(plot.is_bad_input());
        assert_eq!(plot.to_string(), "fig.png: drawing the figure: backend");
        for e in [
            Error::StepSizeTooSmall {
                method: Method::Dopri5,
                scaled_time: 0.5,
                segment_start: 0.25,
            },
            Error::TooManySteps {
                method: Method::Dop853,
                scaled_time: 0.5,
                segment_start: 0.25,
                steps: 100_000,
            },
            Error::Stiff {
                method: Method::Dop853,
                scaled_time: 0.5,
                segment_start: 0.25,
            },
        ] {
            assert!(!e.is_bad_input(), "{e}");
            let m = e.to_string();
            assert!(m.contains("failed at t/duration = 5.000000e-1"), "{m}");
            assert!(m.contains("segment from t/duration = 2.500000e-1"), "{m}");
            assert!(!m.contains('\n'), "{m}");
        }
    }

    /// A second global thread pool is refused: ThreadPool, bad input as the `--threads`
    /// failure it stands for, with rayon's message.
    #[test]
    fn thread_pool_failure() {
        // The first call may or may not find the global pool initialised (another test
        // may have used it); the second always does.
        let _ = rayon::ThreadPoolBuilder::new().build_global();
        let source = rayon::ThreadPoolBuilder::new()
            .build_global()
            .expect_err("the global pool exists");
        let message = source.to_string();
        let e = Error::from(source);
        assert!(matches!(e, Error::ThreadPool { .. }));
        assert_eq!(e.to_string(), format!("thread pool: {message}"));
        assert!(e.is_bad_input());
    }
}
