//! The default scene (a ball rolling without slipping strikes a ball at rest at a 30 degree
//! cut, 1.5 m/s) with a constant force P / tau.
//!
//! Integrates eqs 14-19 with the scene's solver (dop853, rtol 1e-10), writes its trace
//! with the library's CSV writer to `target/traces/default_rectangle.csv`, prints the summary,
//! and fails unless the outgoing state is within 1e-13 (scaled) of the closed form.
//!
//! ```sh
//! cargo run --release --example default_rectangle
//! ```

use billiard_contact::integrate::Sampling;
use billiard_contact::output::AtomicFile;
use billiard_contact::profile::{ForceProfile, Profile, Rectangle};
use billiard_contact::report::summary;
use billiard_contact::runner::run_scene;
use billiard_contact::scene::Scene;
use billiard_contact::trace::CsvTrace;
use billiard_contact::Error;
use std::path::Path;
use std::process::ExitCode;

/// Largest accepted distance from the closed form (velocities over v_ref, spins over
/// v_ref / r): a constant force makes the sliding equations' right-hand side constant,
/// so every method is exact up to round-off.
const TOLERANCE: f64 = 1e-13;
/// theta must stay constant while sliding (eq 23), to this (scaled by v_ref).
const THETA_TOLERANCE: f64 = 1e-12;

fn run() -> Result<(), Error> {
    let mut scene = Scene::default_scene();
    let duration = scene.profile.duration();
    let profile = Profile::Rectangle(Rectangle::new(duration));
    scene.profile = profile;
    scene.name = format!("{}, rectangle pulse", scene.name);

    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/traces");
    std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
    let path = dir.join("default_rectangle.csv");
    let mut trace = CsvTrace::new(AtomicFile::create(&path)?)?;
    let result = run_scene(&scene, &scene.solver, Some((&mut trace, Sampling::Steps)))?;
    let rows = trace.rows();
    trace.finish()?.commit()?;

    print!("{}", summary(&scene, &result));
    println!("  trace: {rows} rows in {}", path.display());

    let check = &result.outcome.check;
    if check.closed_form_error > TOLERANCE {
        return Err(Error::invalid(
            "check.closed_form_error",
            check.closed_form_error,
            format!("<= {TOLERANCE:e} for the rectangle pulse"),
        ));
    }
    if check.theta_drift > THETA_TOLERANCE {
        return Err(Error::invalid(
            "check.theta_drift",
            check.theta_drift,
            format!("<= {THETA_TOLERANCE:e}"),
        ));
    }
    println!(
        "  ok: closed-form error {:.1e} <= {TOLERANCE:e}, theta drift {:.1e}",
        check.closed_form_error, check.theta_drift
    );
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
