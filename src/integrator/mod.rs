//! The time-stepping integrator of eqs 14-19: solver settings, the scaled right-hand sides,
//! the stepping driver and the location of the stop of sliding.
//!
//! | file | what it holds |
//! |---|---|
//! | `rhs` | eqs 14-19 in scaled, autonomous form, and the states they act on |
//! | `driver` | `integrate`: segments between breakpoints and samples, the result |
//! | `stages` | the stages of the contact (sliding, frozen, normal) and why a stage's stepping stops |
//! | `stepping` | one call of an `ode_solvers` method over a span, with the named step-control constants |
//! | `stop_event` | location of the stop of sliding (regula falsi, Illinois) |
//! | `law` | a contact law's normal force from the compression: its states, right-hand sides, events and runs |
//! | `time_map` | the integration variable: the scaled time, or the variable in which the impulse follows the half-sine's |
//! | `units` | scaled states back to physical ones and trace rows |
//! | `record` | trace rows, the first error, theta drift and slip consistency of a run |

pub(crate) mod calibrate;
pub(crate) mod driver;
pub(crate) mod law;
pub(crate) mod record;
pub(crate) mod rhs;
pub(crate) mod stages;
pub(crate) mod stepping;
pub(crate) mod stop_event;
pub(crate) mod time_map;
pub(crate) mod units;
