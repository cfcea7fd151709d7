//! The integration methods, by the names scene files and the command line give them.

use serde::{Deserialize, Serialize};

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
