//! The time-stepping integrator of eqs 14-19: solver settings, the scaled right-hand sides,
//! the stepping driver and the location of the stop of sliding.

mod driver;
pub(crate) mod rhs;
mod settings;

pub use driver::{integrate, Integrated};
pub use settings::{Method, Sampling, SolverSettings, Stats, DEFAULT_RTOL, DEFAULT_STEPS};
