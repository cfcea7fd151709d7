//! dop853 on the default scene with the half-sine profile at the loosest tolerance of the
//! study's ladder whose final-state error is <= 1e-10 (target: <= 5 us per
//! contact), and the other methods at the settings that reach the same error, for scale.
//! One `solve` per iteration: closed form, integration with stick-event watch, and checks.

use billiard_contact::profile::ForceProfile;
use billiard_contact::profile::{HalfSine, Hertz, Profile, SinePower};
use billiard_contact::Scene;
use billiard_contact::{solve, Method, SolverSettings};
use criterion::{black_box, criterion_group, Criterion};

/// The loosest rtol = 10^-k (k = 3..13) at which `method` reaches `target`.
pub fn loosest(
    c: &billiard_contact::Collision,
    p: &Profile,
    method: Method,
    target: f64,
) -> Option<SolverSettings> {
    (3..=13).find_map(|k| {
        let r = 10f64.powi(-k);
        let s = SolverSettings::new(method, r, r, 1000).unwrap();
        let o = solve(c, p, &s, None).unwrap();
        (o.check.closed_form_error <= target).then_some(s)
    })
}

fn bench(cr: &mut Criterion) {
    let scene = Scene::default_scene();
    let (c, _) = scene.collision().unwrap();
    let tau = scene.profile.duration();
    let mut g = cr.benchmark_group("dop853");
    for p in [
        Profile::HalfSine(HalfSine::new(tau).unwrap()),
        Profile::SinePower(SinePower::new(tau, 1.5).unwrap()),
        Profile::Hertz(Hertz::new(tau).unwrap()),
    ] {
        for method in [Method::Dop853, Method::Dopri5] {
            let Some(s) = loosest(&c, &p, method, 1e-10) else {
                eprintln!("{method} never reaches 1e-10 on {}", p.name());
                continue;
            };
            let o = solve(&c, &p, &s, None).unwrap();
            eprintln!(
                "{method} {}: rtol {:e}, error {:.2e}, {} evaluations, {} steps",
                p.name(),
                s.rtol(),
                o.check.closed_form_error,
                o.stats.rhs_evaluations,
                o.stats.accepted_steps
            );
            let name = format!("{method}/{}/error<=1e-10 (rtol {:e})", p.name(), s.rtol());
            g.bench_function(name, |b| {
                b.iter(|| solve(black_box(&c), black_box(&p), &s, None).unwrap())
            });
        }
    }
    g.finish();
}

#[path = "closed_form.rs"]
#[allow(dead_code)]
pub mod closed_form;

/// Criterion's wall-clock numbers, then the target case's CPU time per contact (the
/// machine is shared: CPU time separates compute from waiting).
fn cpu_time() {
    let scene = Scene::default_scene();
    let (c, _) = scene.collision().unwrap();
    let p = Profile::HalfSine(HalfSine::new(scene.profile.duration()).unwrap());
    let s = loosest(&c, &p, Method::Dop853, 1e-10).expect("dop853 reaches 1e-10");
    let n = 200_000;
    let (wall, cpu) = closed_form::per_call(n, || {
        black_box(solve(black_box(&c), black_box(&p), &s, None).unwrap());
    });
    println!(
        "dop853 half-sine error <= 1e-10 (rtol {:e}): {:.2} us wall, {} CPU per contact ({n} solves)",
        s.rtol(),
        wall * 1e6,
        cpu.map(|c| format!("{:.2} us", c * 1e6))
            .unwrap_or_else(|| "n/a".into()),
    );
}

criterion_group!(benches, bench);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
    cpu_time();
}
