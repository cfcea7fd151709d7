//! The default scene (a ball rolling without slipping strikes a ball at rest at a 30 degree
//! cut, 1.5 m/s) with a constant force P / tau.
//!
//! Integrates eqs 14-19 with the scene's solver (dop853, rtol 1e-10), writes its trace
//! with the library's CSV writer to `target/traces/default_rectangle.csv`, prints the summary,
//! and fails unless the outgoing state is within 1.7e-15 (scaled) of the closed form.
//!
//! ```sh
//! cargo run --release --example default_rectangle
//! ```

mod common;

use billiard_contact::profile::{ForceProfile, Profile, Rectangle};
use billiard_contact::Error;
use billiard_contact::Scene;
use std::process::ExitCode;

/// Largest accepted distance from the closed form (velocities over v_ref, spins over
/// v_ref / r): a constant force makes the sliding equations' right-hand side constant,
/// so every method is exact up to round-off: 1.7e-16 with dop853. Ten times that.
const TOLERANCE: f64 = 1.7e-15;

pub fn run() -> Result<(), Error> {
    let duration = Scene::default_scene().profile.duration();
    common::run_default_with(
        Profile::Rectangle(Rectangle::new(duration)?),
        "default_rectangle",
        TOLERANCE,
    )
}

fn main() -> ExitCode {
    common::exit(run())
}
