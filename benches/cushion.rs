//! One impact on a cushion (`resolve_cushion`, docs/cushion.md): the time per impact over a
//! representative set of shots (stun, follow, draw, side spin and follow with side;
//! incidence 10 to 80 degrees; 1 to 6 m/s), for several methods and tolerances, with the
//! largest rebound-velocity error of each against a reference at tolerance 1e-13.
//! `cargo bench --bench cushion`; docs/cushion.md quotes the numbers. The speed target:
//! an error of 1e-8 (relative to the speed) in at most 20 us an impact. The error is
//! |v' - v'_ref| / |v| over the shots, the reference dop853 at rtol = atol = 1e-13.

use billiard_contact::nalgebra::Vector3;
use billiard_contact::{
    resolve_cushion, Ball, Cushion, CushionRestitution, Method, SolverSettings,
};
use criterion::{black_box, criterion_group, criterion_main, Criterion};
use std::time::Duration;

const R: f64 = 0.028575;

/// The shots: (label, v, w).
fn shots() -> Vec<(String, Vector3<f64>, Vector3<f64>)> {
    let mut out = Vec::new();
    for speed in [1.0, 3.0, 6.0] {
        for incidence in [10.0f64, 30.0, 50.0, 80.0] {
            let i = incidence.to_radians();
            let v = Vector3::new(speed * i.sin(), speed * i.cos(), 0.0);
            let roll = Vector3::new(-v.y, v.x, 0.0) / R;
            let side = Vector3::new(0.0, 0.0, 0.5 * speed / R);
            for (kind, w) in [
                ("stun", Vector3::zeros()),
                ("follow", roll),
                ("draw", -roll),
                ("side", side),
                ("follow+side", roll - side),
            ] {
                out.push((format!("{kind} {incidence} deg {speed} m/s"), v, w));
            }
        }
    }
    out
}

/// CPU time of this thread (s) from /proc/thread-self/stat (Linux; utime + stime in clock
/// ticks of 10 ms), or None elsewhere: on a shared machine the wall-clock time of a loop
/// includes the time the thread waited for a core.
fn thread_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/thread-self/stat").ok()?;
    let after = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = after.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

fn settings(method: Method, tol: f64) -> SolverSettings {
    SolverSettings::default()
        .with_method(method)
        .with_rtol(tol)
        .unwrap()
        .with_atol(tol)
        .unwrap()
}

fn bench(c: &mut Criterion) {
    let ball = Ball::new(0.17, R, 0.4).unwrap();
    let cushion = Cushion::new(1.4 * R, 0.2, 0.2, 0.85, CushionRestitution::Stronge).unwrap();
    let shots = shots();
    let reference: Vec<_> = shots
        .iter()
        .map(|(_, v, w)| {
            resolve_cushion(
                &ball,
                &cushion,
                *v,
                *w,
                &settings(Method::Dop853, 1e-13),
                None,
            )
            .unwrap()
            .v
        })
        .collect();
    let mut group = c.benchmark_group("cushion");
    group
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(10);
    let mut rows = Vec::new();
    // The target's error 1e-8 is reached (largest error <= 1e-8) by dopri5 at 7e-9 and
    // dop853 at 2e-8 (dopri5 at 1e-8 lands at 1.25e-8); the loose ones show how the cost
    // falls with the tolerance.
    for (method, tol) in [
        (Method::Dop853, 1e-10),
        (Method::Dop853, 2e-8),
        (Method::Dop853, 1e-8),
        (Method::Dopri5, 1e-8),
        (Method::Dopri5, 7e-9),
        (Method::Dopri5, 1e-4),
        (Method::Dopri5, 1e-2),
    ] {
        let s = settings(method, tol);
        let mut worst = (0.0f64, String::new());
        let mut evals = 0u64;
        let mut slowest = (0.0f64, String::new());
        for ((label, v, w), r) in shots.iter().zip(&reference) {
            let t = std::time::Instant::now();
            let out = resolve_cushion(&ball, &cushion, *v, *w, &s, None).unwrap();
            let dt = t.elapsed().as_secs_f64();
            if dt > slowest.0 {
                slowest = (dt, label.clone());
            }
            evals += out.stats.rhs_evaluations;
            let e = (out.v - r).norm() / v.norm();
            if e > worst.0 {
                worst = (e, label.clone());
            }
        }
        let name = format!("{method} tol {tol:e}");
        let t0 = std::time::Instant::now();
        let cpu0 = thread_cpu_seconds();
        let mut n = 0;
        while t0.elapsed() < Duration::from_secs(3) {
            for (_, v, w) in &shots {
                black_box(resolve_cushion(&ball, &cushion, *v, *w, &s, None).unwrap());
            }
            n += 1;
        }
        let impacts = (n * shots.len()) as f64;
        let per = t0.elapsed().as_secs_f64() / impacts;
        let cpu = match (cpu0, thread_cpu_seconds()) {
            (Some(a), Some(b)) => format!("{:7.2} us CPU", (b - a) / impacts * 1e6),
            _ => "CPU time n/a".to_string(),
        };
        rows.push(format!(
            "{name:>18}: {:7.2} us an impact wall, {cpu} (mean over {} shots), {:6.0} \
             evaluations an impact, largest error {:.1e} ({}), slowest {:.0} us ({})",
            per * 1e6,
            shots.len(),
            evals as f64 / shots.len() as f64,
            worst.0,
            worst.1,
            slowest.0 * 1e6,
            slowest.1
        ));
        group.bench_function(&name, |b| {
            b.iter(|| {
                for (_, v, w) in &shots {
                    black_box(resolve_cushion(&ball, &cushion, *v, *w, &s, None).unwrap());
                }
            })
        });
    }
    group.finish();
    for r in rows {
        println!("{r}");
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
