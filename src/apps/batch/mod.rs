//! Many collisions at once: one per row of a CSV file (streamed in chunks, so memory does
//! not grow with the number of rows) or of an in-memory slice, resolved in parallel over
//! rows with rayon.
//!
//! The balls, friction, impulse rule, profile and effects come from a scene (the built-in
//! default scene when none is given); a row may override some of them. Rows carry the
//! incoming state either in the paper's centre-of-mass frame or in the lab frame.
//!
//! # Input columns
//!
//! Header names as below; a trailing unit in parentheses (`u_x (m/s)`) is ignored; column
//! order is free; empty cells are "not given". Exactly one of the two frames:
//!
//! | columns | meaning |
//! |---|---|
//! | `u_x, u_y, u_z` | centre-of-mass frame: velocity of ball A (m/s), line of centres +x, B has -u |
//! | `omega_a_x .. omega_a_z`, `omega_b_x .. omega_b_z` | spins (rad/s), optional, default 0 |
//! | `a_px, a_py, a_pz`, `b_px, b_py, b_pz` | lab frame: centres (m), touching |
//! | `a_vx, a_vy, a_vz`, `b_vx, b_vy, b_vz` | lab velocities (m/s) |
//! | `a_wx, a_wy, a_wz`, `b_wx, b_wy, b_wz` | lab spins (rad/s), optional, default 0 |
//! | `up_x, up_y, up_z` | lab `up`, optional, default (0, 0, 1) |
//!
//! Optional in both: `id` (copied to the output), and per-row overrides of the scene:
//! `mass` (kg), `radius` (m), `alpha`, `mu` (constant), `restitution` or `impulse` (N s),
//! `duration` (s; the outgoing state does not depend on it, the stick time scales with it).
//! With a scene that gives the balls' material, each row's duration is its own Hertz contact
//! time (from its mass, radius and approach speed), and a `duration` column is refused.
//! With a scene whose force comes from a contact law (`[contact.law]`), each row realises its
//! own impulse, restitution and duration; `restitution`, `impulse` and `duration` columns are
//! refused, and the stick time is the row's own (docs/contact-law.md#batch-and-sweep).
//!
//! # Output columns
//!
//! `line` (the input line), `id` (when the input has it), `collision`, `impulse` (N s),
//! `s0` (m/s), `theta` (rad, empty when S(0) = 0), `sticks`, `stick_time` (s, empty when
//! sliding does not stop), `stick_impulse` (N s, empty when undefined), `tangential_impulse`
//! (N s), `s_out` (m/s), `heat`, `heat_sliding` (J), the outgoing centre-of-mass state
//! `u_x, u_y, u_z, omega_a_x .. omega_b_z`; with lab input also `a_vx .. a_wz, b_vx .. b_wz`
//! (outgoing lab velocities and spins) and `throw_angle_deg` (empty when undefined); with
//! a time-stepping method also `closed_form_error` and `rhs_evaluations`.

mod columns;
mod crlf;
pub(crate) mod cushion;
mod engine;
mod lab_rows;
mod stream;

pub use columns::{LAB_OUTPUT_COLUMNS, OUTPUT_COLUMNS};
pub use engine::{
    closed_form_into, resolve, resolve_slice, BatchInput, BatchOutput, BatchSetup, Overrides,
};
pub use lab_rows::{resolve_lab_into, LabOutColumns, LabRows, PARALLEL_LAB_ROWS};
pub use stream::{run_csv, BatchSummary, DEFAULT_CHUNK_ROWS, MAX_CHUNK_ROWS};
