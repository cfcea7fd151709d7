//! Solver settings: the method, its tolerances and step count, and what a run reports of
//! its work.

use crate::error::Error;
use serde::{Deserialize, Serialize};
use std::str::FromStr;

/// Integration methods.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// The exact solution (eqs 24-35 with the stick rule); no time stepping.
    ClosedForm,
    /// Classical Runge-Kutta, order 4, fixed step count (`ode_solvers::Rk4`).
    Rk4,
    /// Dormand-Prince 5(4), adaptive (`ode_solvers::Dopri5`; Hairer, Norsett, Wanner,
    /// Solving ODEs I, II.4-5).
    Dopri5,
    /// Dormand-Prince 8(5,3), adaptive (`ode_solvers::Dop853`, integrated in autonomous
    /// form because its nodes c12, c13 are wrong for time-dependent right-hand sides).
    Dop853,
}

impl Method {
    /// All methods, in the order of the tables.
    pub const ALL: [Method; 4] = [
        Method::ClosedForm,
        Method::Rk4,
        Method::Dopri5,
        Method::Dop853,
    ];

    /// The name used in scene files and on the command line.
    pub fn name(&self) -> &'static str {
        match self {
            Method::ClosedForm => "closed-form",
            Method::Rk4 => "rk4",
            Method::Dopri5 => "dopri5",
            Method::Dop853 => "dop853",
        }
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

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

/// Default relative tolerance.
pub const DEFAULT_RTOL: f64 = 1e-10;
/// Default number of RK4 steps over the contact.
pub const DEFAULT_STEPS: u32 = 1000;

/// Solver settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Method.
    pub method: Method,
    /// Relative tolerance (adaptive methods).
    pub rtol: f64,
    /// Absolute tolerance on the scaled variables (velocities over v_ref, spins times
    /// r / v_ref, heat over m v_ref^2): physical scales drop out.
    pub atol: f64,
    /// Steps over the whole contact (rk4).
    pub steps: u32,
    /// Step exactly to the profile's breakpoints (default true).
    pub breakpoints: bool,
    /// Integrate pulses with algebraic ends (`hertz`, `sine-power` with a fractional
    /// exponent) in a smoothed time variable, s = g(x) with Sidi's sin^m transform (default
    /// true); off, the steps are graded toward the ends instead (when `breakpoints` is on).
    /// No effect on other profiles (docs/model.md#the-smoothing-change-of-time-variable).
    pub time_transform: bool,
}

impl Default for SolverSettings {
    /// dop853, rtol 1e-10, atol = rtol, 1000 rk4 steps, breakpoints on, time transform on.
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
    /// Validated settings: rtol in [1e-15, 0.1], atol in (0, 0.1], steps in [1, 1e9];
    /// breakpoints and the time transform on.
    pub fn new(method: Method, rtol: f64, atol: f64, steps: u32) -> Result<Self, Error> {
        if !(rtol.is_finite() && (1e-15..=0.1).contains(&rtol)) {
            return Err(Error::invalid(
                "solver.rtol",
                rtol,
                "in [1e-15, 0.1] (double precision ends near 1e-15)",
            ));
        }
        if !(atol.is_finite() && atol > 0.0 && atol <= 0.1) {
            return Err(Error::invalid(
                "solver.atol",
                atol,
                "in (0, 0.1], on the scaled variables (speeds over v_ref)",
            ));
        }
        if !(1..=1_000_000_000).contains(&steps) {
            return Err(Error::invalid("solver.steps", steps, "in [1, 1e9]"));
        }
        Ok(SolverSettings {
            method,
            rtol,
            atol,
            steps,
            breakpoints: true,
            time_transform: true,
        })
    }

    /// The same settings with the smoothing time transform on or off (every value is valid:
    /// it only chooses how pulses with algebraic ends are stepped).
    ///
    /// ```
    /// use billiard_contact::SolverSettings;
    /// let graded = SolverSettings::default().with_time_transform(false);
    /// assert!(!graded.time_transform && SolverSettings::default().time_transform);
    /// ```
    pub fn with_time_transform(mut self, on: bool) -> Self {
        self.time_transform = on;
        self
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
    /// One row per accepted step (and the stick event).
    Steps,
    /// Rows at t = i duration / N, i = 0..=N (and the stick event).
    Uniform(u64),
}
