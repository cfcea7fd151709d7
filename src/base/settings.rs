//! Solver settings: the method, its tolerances and step count, and what a run reports of
//! its work.

use crate::base::error::Error;
use crate::base::method::Method;
use serde::Serialize;
use std::str::FromStr;

impl FromStr for Method {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self, Error> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                Error::invalid(
                    "solver.method",
                    format!("\"{s}\""),
                    "one of closed-form, rk4, dopri5, dop853",
                )
            })
    }
}

/// Default relative tolerance of the adaptive methods, 1e-10 (also the default atol).
pub const DEFAULT_RTOL: f64 = 1e-10;
/// Default number of rk4 steps over the contact, 1000.
pub const DEFAULT_STEPS: u32 = 1000;

/// Accepted relative tolerances: double precision ends near 1e-15, and a tolerance above
/// 0.1 asks for no accuracy at all.
const RTOL_RANGE: std::ops::RangeInclusive<f64> = 1e-15..=0.1;
/// Largest absolute tolerance, on the scaled variables (which are at most about 1).
const ATOL_MAX: f64 = 0.1;
/// Accepted rk4 step counts: at least one step; at most 1e7 (about 2 s a run). Past about
/// 1e4 steps rk4's error is rounding, which grows with the steps: on the default scene
/// the scaled difference from the closed form is 2.8e-14 at 1e3 steps, 1.6e-12 at 1e5 and
/// 2.2e-10 at 1e7, so a larger count only costs time and accuracy.
pub const MAX_STEPS: u32 = 10_000_000;
const STEPS_RANGE: std::ops::RangeInclusive<u32> = 1..=MAX_STEPS;

/// Solver settings: the method, its tolerances and step count, and whether it steps to the
/// profile's breakpoints. Built validated ([`SolverSettings::new`], the `with_` setters), so
/// every value a run sees is in range.
///
/// ```
/// use billiard_contact::{Method, SolverSettings};
/// let s = SolverSettings::default().with_method(Method::Dopri5).with_rtol(1e-8)?;
/// assert_eq!((s.method(), s.rtol(), s.atol(), s.steps()), (Method::Dopri5, 1e-8, 1e-10, 1000));
/// assert!(s.with_rtol(0.5).is_err()); // rtol in [1e-15, 0.1]
/// # Ok::<(), billiard_contact::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    method: Method,
    rtol: f64,
    atol: f64,
    steps: u32,
    breakpoints: bool,
    time_transform: bool,
}

impl Default for SolverSettings {
    /// dop853, rtol 1e-10 ([`DEFAULT_RTOL`]), atol = rtol, 1000 rk4 steps
    /// ([`DEFAULT_STEPS`]; used only by rk4), breakpoints on, time transform on.
    fn default() -> Self {
        SolverSettings {
            method: Method::Dop853,
            rtol: DEFAULT_RTOL,
            atol: DEFAULT_RTOL,
            steps: DEFAULT_STEPS,
            breakpoints: true,
            time_transform: true,
        }
    }
}

impl SolverSettings {
    /// Validated settings: rtol in [1e-15, 0.1], atol in (0, 0.1], steps in [1, 1e7];
    /// breakpoints and the time transform on. Errors are [`Error::InvalidParameter`] naming
    /// `solver.rtol`, `solver.atol` or `solver.steps`.
    pub fn new(method: Method, rtol: f64, atol: f64, steps: u32) -> Result<Self, Error> {
        Ok(SolverSettings {
            method,
            rtol: check_rtol(rtol)?,
            atol: check_atol(atol)?,
            steps: check_steps(steps)?,
            breakpoints: true,
            time_transform: true,
        })
    }

    /// The method (default dop853).
    pub fn method(&self) -> Method {
        self.method
    }

    /// Relative tolerance of the adaptive methods (default 1e-10).
    pub fn rtol(&self) -> f64 {
        self.rtol
    }

    /// Absolute tolerance of the adaptive methods on the scaled variables (velocities over
    /// v_ref, spins times r / v_ref, heat over m v_ref^2), so that physical scales drop out
    /// (default 1e-10, as rtol).
    pub fn atol(&self) -> f64 {
        self.atol
    }

    /// rk4 steps over the whole contact (default 1000); each segment between breakpoints
    /// takes its share, rounded up.
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// Whether the methods step exactly to the profile's breakpoints (default true).
    pub fn breakpoints(&self) -> bool {
        self.breakpoints
    }

    /// Whether pulses with algebraic ends (`hertz`, `sine-power` with a fractional
    /// exponent) are integrated in a smoothed time variable, s = g(x) under which the
    /// impulse follows the half-sine's (default true); off, the steps are graded toward the ends instead (when
    /// the breakpoints are on). No effect on other profiles
    /// (docs/model.md#the-smoothing-change-of-time-variable).
    pub fn time_transform(&self) -> bool {
        self.time_transform
    }

    /// The same settings with `method`.
    pub fn with_method(self, method: Method) -> Self {
        SolverSettings { method, ..self }
    }

    /// The same settings with relative tolerance `rtol`, in [1e-15, 0.1] (atol unchanged).
    pub fn with_rtol(self, rtol: f64) -> Result<Self, Error> {
        Ok(SolverSettings {
            rtol: check_rtol(rtol)?,
            ..self
        })
    }

    /// The same settings with absolute tolerance `atol`, in (0, 0.1].
    pub fn with_atol(self, atol: f64) -> Result<Self, Error> {
        Ok(SolverSettings {
            atol: check_atol(atol)?,
            ..self
        })
    }

    /// The same settings with `steps` rk4 steps over the contact, in [1, 1e7].
    pub fn with_steps(self, steps: u32) -> Result<Self, Error> {
        Ok(SolverSettings {
            steps: check_steps(steps)?,
            ..self
        })
    }

    /// The same settings, stepping to the profile's breakpoints or not.
    pub fn with_breakpoints(self, breakpoints: bool) -> Self {
        SolverSettings {
            breakpoints,
            ..self
        }
    }

    /// The same settings with the smoothing time transform on or off (both are valid: it
    /// only chooses how pulses with algebraic ends are stepped).
    ///
    /// ```
    /// use billiard_contact::SolverSettings;
    /// let graded = SolverSettings::default().with_time_transform(false);
    /// assert!(!graded.time_transform() && SolverSettings::default().time_transform());
    /// ```
    pub fn with_time_transform(self, time_transform: bool) -> Self {
        SolverSettings {
            time_transform,
            ..self
        }
    }
}

fn check_rtol(rtol: f64) -> Result<f64, Error> {
    accepted(
        rtol.is_finite() && RTOL_RANGE.contains(&rtol),
        "solver.rtol",
        rtol,
        "in [1e-15, 0.1] (double precision ends near 1e-15)",
    )
}

fn check_atol(atol: f64) -> Result<f64, Error> {
    accepted(
        atol.is_finite() && atol > 0.0 && atol <= ATOL_MAX,
        "solver.atol",
        atol,
        "in (0, 0.1], on the scaled variables (speeds over v_ref)",
    )
}

fn check_steps(steps: u32) -> Result<u32, Error> {
    check_steps_as("solver.steps", steps)
}

/// Checks an rk4 step count given as `field` (the scene's key or a command-line option).
pub(crate) fn check_steps_as(field: &str, steps: u32) -> Result<u32, Error> {
    accepted(
        STEPS_RANGE.contains(&steps),
        field,
        steps,
        "in [1, 1e7] (past about 1e4 steps rk4's error is rounding, which grows with the \
         steps)",
    )
}

/// `value` when it is `ok`, else [`Error::InvalidParameter`] naming `field` and what is
/// `expected`.
fn accepted<T: std::fmt::Display>(
    ok: bool,
    field: &str,
    value: T,
    expected: &str,
) -> Result<T, Error> {
    if ok {
        Ok(value)
    } else {
        Err(Error::invalid(field, value, expected))
    }
}

/// Work done by an integration.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Stats {
    /// Right-hand-side evaluations, including those of event location.
    pub rhs_evaluations: u64,
    /// Accepted steps.
    pub accepted_steps: u64,
    /// Rejected steps (adaptive methods).
    pub rejected_steps: u64,
}

/// Which rows a trace receives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sampling {
    /// The start, one row per step of the integration and the stop of sliding (the step
    /// that crossed the stop, and those that locate it, count as accepted steps but have no
    /// row: docs/formats.md#trace-csv).
    Steps,
    /// Rows at t = i duration / N, i = 0..=N (and the stick event); N at most
    /// [`MAX_SAMPLES`](crate::details::MAX_SAMPLES).
    Uniform(u64),
}

/// The most rows a uniform trace (and a ball-path file) may ask for: 1e6 rows, a CSV of
/// about 300 MB; the rows of a figure are held in memory. Far more than a figure or a fit
/// can use.
pub const MAX_SAMPLES: u64 = 1_000_000;

/// Checks a sample count given as `field`: in [1, [`MAX_SAMPLES`]].
pub(crate) fn check_samples(field: &str, n: u64) -> Result<u64, Error> {
    if n == 0 {
        return Err(Error::invalid(field, 0, "at least 1"));
    }
    accepted(
        n <= MAX_SAMPLES,
        field,
        n,
        "at most 1e6 (1e6 rows of CSV are about 300 MB)",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field_of(r: Result<SolverSettings, Error>) -> String {
        match r {
            Err(Error::InvalidParameter { field, .. }) => field,
            other => panic!("{other:?}"),
        }
    }

    /// The names the Python package (and any caller of `str::parse`) gives the methods.
    #[test]
    fn methods_parse_from_their_names() {
        for (name, m) in [
            ("closed-form", Method::ClosedForm),
            ("rk4", Method::Rk4),
            ("dopri5", Method::Dopri5),
            ("dop853", Method::Dop853),
        ] {
            assert_eq!(name.parse::<Method>().unwrap(), m);
        }
        let e = "rk5".parse::<Method>().unwrap_err().to_string();
        assert!(e.contains("solver.method") && e.contains("\"rk5\""), "{e}");
    }

    #[test]
    fn defaults() {
        let d = SolverSettings::default();
        assert_eq!(
            (d.method(), d.rtol(), d.atol(), d.steps(), d.breakpoints()),
            (Method::Dop853, 1e-10, 1e-10, 1000, true)
        );
        assert_eq!(
            SolverSettings::new(Method::Dop853, 1e-10, 1e-10, 1000).unwrap(),
            d
        );
    }

    /// The setters accept the ends of the ranges and refuse what lies beyond, naming the
    /// field; a refused value leaves nothing half-changed (the setters consume a copy).
    #[test]
    fn setters_validate() {
        let d = SolverSettings::default();
        for rtol in [0.0, 1e-16, 0.2, f64::NAN, f64::INFINITY] {
            assert_eq!(field_of(d.with_rtol(rtol)), "solver.rtol", "{rtol}");
        }
        for atol in [0.0, -1e-10, 0.2, f64::NAN] {
            assert_eq!(field_of(d.with_atol(atol)), "solver.atol", "{atol}");
        }
        for steps in [0, 10_000_001, u32::MAX] {
            assert_eq!(field_of(d.with_steps(steps)), "solver.steps", "{steps}");
        }
        let s = d
            .with_rtol(1e-15)
            .and_then(|s| s.with_atol(0.1))
            .and_then(|s| s.with_steps(10_000_000))
            .unwrap()
            .with_method(Method::Rk4)
            .with_breakpoints(false)
            .with_time_transform(false);
        assert_eq!(
            (s.method(), s.rtol(), s.atol(), s.steps(), s.breakpoints()),
            (Method::Rk4, 1e-15, 0.1, 10_000_000, false)
        );
        assert!(!s.time_transform() && d.time_transform());
        // new refuses what the setters refuse, with the same message.
        let by_new = SolverSettings::new(Method::Rk4, 0.2, 1e-10, 1000).unwrap_err();
        assert_eq!(
            by_new.to_string(),
            d.with_rtol(0.2).unwrap_err().to_string()
        );
        assert_eq!(
            by_new.to_string(),
            "solver.rtol = 0.2: in [1e-15, 0.1] (double precision ends near 1e-15)"
        );
    }
}
