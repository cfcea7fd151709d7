//! The speed targets in one command: `cargo bench --bench targets`. Prints each target, the
//! measured value (thread CPU time, the best of five passes: the machine is shared and its
//! speed drifts) and whether it is met. Never an assert: a slow machine is not a failure.

use billiard_contact::batch::{closed_form_into, BatchSetup};
use billiard_contact::details::ClosedFormBatch;
use billiard_contact::profile::ForceProfile;
use billiard_contact::profile::{HalfSine, Profile};
use billiard_contact::{solve, Method, Scene, SolverSettings};
use std::hint::black_box;

#[path = "dop853.rs"]
#[allow(dead_code)]
mod dop853;
use dop853::closed_form::{per_call, states};

/// Best of five passes of `per_call` (CPU time when the platform has it, else wall time).
fn best(n: u64, mut f: impl FnMut()) -> f64 {
    (0..5)
        .map(|_| {
            let (wall, cpu) = per_call(n, &mut f);
            cpu.unwrap_or(wall)
        })
        .fold(f64::INFINITY, f64::min)
}

fn report(what: &str, target: f64, measured: f64, unit: &str, scale: f64) {
    let met = if measured <= target { "met" } else { "NOT met" };
    println!(
        "{what}: target <= {:.1} {unit}, measured {:.1} {unit}: {met}",
        target * scale,
        measured * scale
    );
}

fn main() {
    let scene = Scene::default_scene();

    // The closed form per collision, batch of 4096 states, one core.
    let setup = BatchSetup::from_scene(
        &scene,
        SolverSettings::default().with_method(Method::ClosedForm),
    );
    let input = states(4096);
    let (c0, _) = scene.collision().unwrap();
    let first = ClosedFormBatch::new(c0.balls, c0.contact, c0.effects)
        .resolve(&c0.incoming)
        .unwrap();
    let mut out = vec![first; input.len()];
    let per_pass = best(400, || {
        closed_form_into(&setup, black_box(&input), &mut out).unwrap()
    });
    report(
        "closed form per collision (closed_form_into, 4096 states, one core)",
        50e-9,
        per_pass / input.len() as f64,
        "ns",
        1e9,
    );

    // dop853 per contact, default scene, half-sine, loosest rtol with error <= 1e-10.
    let p = Profile::HalfSine(HalfSine::new(scene.profile.duration()).unwrap());
    let s = dop853::loosest(&c0, &p, Method::Dop853, 1e-10).expect("dop853 reaches 1e-10");
    let per_contact = best(20_000, || {
        black_box(solve(black_box(&c0), black_box(&p), &s, None).unwrap());
    });
    report(
        &format!(
            "dop853 per contact, half-sine, error <= 1e-10 (rtol {:e})",
            s.rtol()
        ),
        5e-6,
        per_contact,
        "us",
        1e6,
    );
}
