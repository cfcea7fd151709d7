//! The default scene (a ball rolling without slipping strikes a ball at rest at a 30 degree
//! cut, 1.5 m/s) with the tabulated force curve `data/profiles/measured_pulse.csv`,
//! stretched to the scene's duration and rescaled to the impulse.
//!
//! Integrates eqs 14-19 with the scene's solver (dop853, rtol 1e-10), writes its trace
//! with the library's CSV writer to `target/traces/default_tabulated.csv`, prints the summary,
//! and fails unless the outgoing state is within 8.9e-15 (scaled) of the closed form.
//!
//! ```sh
//! cargo run --release --example default_tabulated
//! ```

mod common;

use billiard_contact::profile::{ForceProfile, Profile, Tabulated};
use billiard_contact::Error;
use billiard_contact::Scene;
use std::path::Path;
use std::process::ExitCode;

/// Largest accepted distance from the closed form (velocities over v_ref, spins over
/// v_ref / r): the force is linear between the table's points, which are breakpoints
/// the integrator steps to, so the result is exact up to round-off: 8.9e-16 with dop853.
/// Ten times that.
const TOLERANCE: f64 = 8.9e-15;

pub fn run() -> Result<(), Error> {
    let duration = Scene::default_scene().profile.duration();
    let table = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/profiles/measured_pulse.csv");
    common::run_default_with(
        Profile::Tabulated(Tabulated::from_csv_file(&table, Some(duration))?),
        "default_tabulated",
        TOLERANCE,
    )
}

fn main() -> ExitCode {
    common::exit(run())
}
