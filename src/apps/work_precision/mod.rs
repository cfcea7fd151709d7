//! The work-precision study: what accuracy costs in time, per force profile and method.
//!
//! For each profile (the scene's collision with its profile replaced, the duration kept) and
//! each method (the closed form; rk4 over a ladder of step counts; dopri5 and dop853 over a
//! ladder of tolerances with atol = rtol on the scaled variables), one run measures
//!
//! - `error`: the largest scaled deviation of the outgoing state from the closed form
//!   ([`Checks::closed_form_error`](crate::details::Checks::closed_form_error), with the scales of
//!   docs/model.md#scales-and-scaled-errors);
//! - `stick_time_error`: |t_stick - t_stick exact| / duration where sliding stops (`None`
//!   otherwise; a stop the integrator missed counts as a stop at the end of the contact);
//! - the work done ([`Stats`](crate::Stats));
//! - `seconds_per_contact`: the median, over timed samples after a warm-up, of the wall time
//!   of one [`solve`](crate::solve) (the whole call: closed form, integration and checks), in this process.
//!
//! Profiles with breakpoints (the knots of a tabulated profile) are run again with
//! [`SolverSettings::breakpoints`](crate::SolverSettings::breakpoints) off, so the study shows what stepping exactly to them
//! saves; profiles with algebraic ends (`hertz`, `sine-power` 1.5) are run again with
//! [`SolverSettings::time_transform`](crate::SolverSettings::time_transform) off (steps graded toward the ends instead), so it
//! shows what the smoothing change of time variable saves. By default the study also runs a
//! companion scene in which sliding stops during the contact
//! (`data/scenes/stun_cut_sticks.toml`), which exercises the stick event.
//!
//! [`write_csv`] writes the rows with the columns of [`COLUMNS`] first (the format of
//! docs/formats.md#work-precision-csv) and the extra columns of docs/formats.md after; [`read_csv`] reads such a file back, including rows
//! appended by the peers' script (`benches/peers/scipy_contact.py`), for the figure.

pub(crate) mod csv;
pub(crate) mod order;
pub(crate) mod plan;
pub(crate) mod run;
#[cfg(test)]
pub(crate) mod tests;

pub use csv::{read_csv, write_csv, COLUMNS};
pub use order::{markdown, summary};
pub use plan::{StudyForce, StudyOptions, StudyRow};
pub use run::run_study;
