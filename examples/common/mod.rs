//! What the examples share: run the default scene with a given profile, write the trace
//! with the library's CSV writer, print the summary, and check the result against the
//! closed form run separately and against eq 23 over the trace, both computed here from
//! the runs' states (never from the checks the library reports about its own run).

use billiard_contact::profile::Profile;
use billiard_contact::Error;
use billiard_contact::Report;
use billiard_contact::Sampling;
use billiard_contact::Scene;
use billiard_contact::{run_scene, BallPair, CmState, Method, SceneOutcome};
use billiard_contact::{CsvTrace, TraceRow, TraceSink};
use std::path::Path;
use std::process::ExitCode;

/// theta must stay constant while sliding (eq 23), to this (scaled by v_ref): the default
/// scene's traces reach 1.5e-16 (half-sine, Hertz, sine-power) and 2.0e-16 (rectangle,
/// tabulated). Ten times the larger.
pub const THETA_TOLERANCE: f64 = 2e-15;

/// The slip (2V + r_A Omega^A_z + r_B Omega^B_z, 2W - r_A Omega^A_y - r_B Omega^B_y) of
/// eqs 5-6 (docs/unequal-balls.md for r_A != r_B), written out here.
fn slip(s: &CmState, balls: &BallPair) -> [f64; 2] {
    let (ra, rb) = (balls.a.radius(), balls.b.radius());
    let (a, b) = (s.omega_a, s.omega_b);
    [
        2.0 * s.u_cm.y + ra * a.z + rb * b.z,
        2.0 * s.u_cm.z - ra * a.y - rb * b.y,
    ]
}

/// v_ref = max(S(0), |U(0)|, r_A |Omega^A(0)|, r_B |Omega^B(0)|) (m/s) of the incoming
/// state (docs/model.md#checks).
fn reference_speed(incoming: &CmState, balls: &BallPair) -> f64 {
    let [sx, sy] = slip(incoming, balls);
    sx.hypot(sy)
        .max(incoming.u_cm.norm())
        .max(balls.a.radius() * incoming.omega_a.norm())
        .max(balls.b.radius() * incoming.omega_b.norm())
}

/// The scene run again with the closed form (eqs 24-35, 52, 56), the reference of every
/// time-stepping method.
pub fn closed_form_of(scene: &Scene) -> Result<SceneOutcome, Error> {
    run_scene(scene, &scene.solver.with_method(Method::ClosedForm), None)
}

/// Largest distance of `run`'s outgoing state from `exact`'s, velocities over v_ref and
/// spins over v_ref / r_A.
pub fn distance_from(scene: &Scene, run: &SceneOutcome, exact: &SceneOutcome) -> f64 {
    let (a, b) = (run.outcome.result.out, exact.outcome.result.out);
    let v = reference_speed(&run.cm_in, &scene.balls);
    let w = v / scene.balls.a.radius();
    ((a.u_cm - b.u_cm).amax() / v)
        .max((a.omega_a - b.omega_a).amax() / w)
        .max((a.omega_b - b.omega_b).amax() / w)
}

/// Largest |slip x e0| / v_ref over the trace's rows, e0 the direction of the incoming slip:
/// eq 23 holds theta constant while sliding, and a stuck slip is zero.
fn theta_drift(scene: &Scene, incoming: &CmState, rows: &[TraceRow]) -> f64 {
    let [x0, y0] = slip(incoming, &scene.balls);
    let s0 = x0.hypot(y0);
    if s0 == 0.0 {
        return 0.0;
    }
    let v = reference_speed(incoming, &scene.balls);
    rows.iter()
        .map(|row| {
            let [x, y] = slip(&row.state, &scene.balls);
            (x * y0 - y * x0).abs() / s0 / v
        })
        .fold(0.0, f64::max)
}

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
    let mut rows: Vec<TraceRow> = Vec::new();
    let result = run_scene(&scene, &scene.solver, Some((&mut rows, Sampling::Steps)))?;
    let mut trace = CsvTrace::new(Vec::new())?;
    for row in &rows {
        trace.row(row)?;
    }
    std::fs::write(&path, trace.finish()?).map_err(|e| Error::io(&path, e))?;

    print!("{}", Report::new(&scene, &result).summary());
    println!("  trace: {} rows in {}", rows.len(), path.display());

    let distance = distance_from(&scene, &result, &closed_form_of(&scene)?);
    if distance.is_nan() || distance > tolerance {
        return Err(Error::invalid(
            "distance from the closed form",
            distance,
            format!("<= {tolerance:e} for the {label} pulse"),
        ));
    }
    let drift = theta_drift(&scene, &result.cm_in, &rows);
    if drift.is_nan() || drift > THETA_TOLERANCE {
        return Err(Error::invalid(
            "theta drift over the trace",
            drift,
            format!("<= {THETA_TOLERANCE:e}"),
        ));
    }
    println!(
        "  ok: distance from the closed form {distance:.1e} <= {tolerance:e}, \
         theta drift over the trace {drift:.1e} (scaled)"
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
