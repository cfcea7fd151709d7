//! What the per-profile examples share: run the default scene with a given profile, write
//! the trace with the library's CSV writer, print the summary, and check the result.

use billiard_contact::formats::atomic_file::AtomicFile;
use billiard_contact::formats::report::summary;
use billiard_contact::formats::trace::CsvTrace;
use billiard_contact::profile::Profile;
use billiard_contact::run_scene;
use billiard_contact::Error;
use billiard_contact::Sampling;
use billiard_contact::Scene;
use std::path::Path;
use std::process::ExitCode;

/// theta must stay constant while sliding (eq 23), to this (scaled by v_ref).
pub const THETA_TOLERANCE: f64 = 1e-12;

/// Runs the default scene with `profile` (its solver: dop853, rtol 1e-10), writes the trace
/// to `target/traces/<stem>.csv`, prints the summary, and fails unless the outgoing state is
/// within `tolerance` (scaled) of the closed form and theta stays constant.
pub fn run_default_with(profile: Profile, stem: &str, tolerance: f64) -> Result<(), Error> {
    let mut scene = Scene::default_scene();
    let label = profile.name();
    scene.profile = profile;
    scene.name = format!("{}, {label} pulse", scene.name);

    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/traces");
    std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
    let path = dir.join(format!("{stem}.csv"));
    let mut trace = CsvTrace::new(AtomicFile::create(&path)?)?;
    let result = run_scene(&scene, &scene.solver, Some((&mut trace, Sampling::Steps)))?;
    let rows = trace.rows();
    trace.finish()?.commit()?;

    print!("{}", summary(&scene, &result));
    println!("  trace: {rows} rows in {}", path.display());

    let check = &result.outcome.check;
    if check.closed_form_error > tolerance {
        return Err(Error::invalid(
            "check.closed_form_error",
            check.closed_form_error,
            format!("<= {tolerance:e} for the {label} pulse"),
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
        "  ok: closed-form error {:.1e} <= {tolerance:e}, theta drift {:.1e}",
        check.closed_form_error, check.theta_drift
    );
    Ok(())
}

/// Exit status of an example's `run`.
pub fn exit(result: Result<(), Error>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
