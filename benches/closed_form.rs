//! The closed form per collision in a batch, on one core (target: <= 50 ns).
//!
//! What the 50 ns covers (docs/formats.md): the outgoing state, impulse, S(0), theta, stick flag
//! and p_stick of states already in memory: `batch::closed_form_into` over 4096 states of
//! the default scene's balls (validation of the state, eqs 24-35 with the stick rule,
//! theta by atan2). `resolve` adds the stick time and the output record per row.

use billiard_contact::batch::{closed_form_into, resolve, BatchInput, BatchSetup};
use billiard_contact::details::ClosedFormBatch;
use billiard_contact::Scene;
use billiard_contact::{CmState, Method, SolverSettings};
use criterion::{black_box, criterion_group, Criterion, Throughput};
use nalgebra::Vector3;

/// Deterministic, varied incoming states: speeds 0.2-3 m/s, cut angles to 60 degrees, spins
/// up to 60 rad/s; some slide through, some stick, a few separate.
pub fn states(n: usize) -> Vec<CmState> {
    let mut x = 0x9E37_79B9_7F4A_7C15_u64;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| {
            let speed = 0.2 + 2.8 * next();
            let cut = (next() * 60.0 - 2.0).to_radians();
            let u = Vector3::new(speed * cut.cos(), speed * cut.sin(), 0.1 * (next() - 0.5));
            let wa = Vector3::new(
                60.0 * (next() - 0.5),
                60.0 * (next() - 0.5),
                30.0 * (next() - 0.5),
            );
            CmState::new(u, wa, Vector3::zeros())
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let scene = Scene::default_scene();
    let setup = BatchSetup::from_scene(
        &scene,
        SolverSettings::default().with_method(Method::ClosedForm),
    );
    let n = 4096;
    let input = states(n);
    let (c0, _) = scene.collision().unwrap();
    let mut out = vec![
        ClosedFormBatch::new(c0.balls, c0.contact, c0.effects)
            .resolve(&c0.incoming)
            .unwrap();
        n
    ];
    let mut g = c.benchmark_group("closed_form");
    g.throughput(Throughput::Elements(n as u64));
    g.bench_function("closed_form_into/4096 states, one core", |b| {
        b.iter(|| closed_form_into(&setup, black_box(&input), &mut out).unwrap())
    });
    let rows: Vec<BatchInput> = input.iter().map(|s| BatchInput::cm(*s)).collect();
    g.bench_function("resolve/4096 rows, one core (with stick time)", |b| {
        b.iter(|| {
            for r in black_box(&rows) {
                black_box(resolve(&setup, r).unwrap());
            }
        })
    });
    g.finish();
}

/// Nanoseconds this thread has spent on a CPU (Linux: /proc/thread-self/schedstat), so
/// that a shared, loaded machine can still tell compute time from waiting time.
pub fn thread_cpu_ns() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    s.split_whitespace().next()?.parse().ok()
}

/// Wall and CPU time per call of `f` (called `n` times).
pub fn per_call(n: u64, mut f: impl FnMut()) -> (f64, Option<f64>) {
    let (c0, t0) = (thread_cpu_ns(), std::time::Instant::now());
    for _ in 0..n {
        f();
    }
    let wall = t0.elapsed().as_secs_f64() / n as f64;
    let cpu = match (c0, thread_cpu_ns()) {
        (Some(a), Some(b)) => Some((b - a) as f64 * 1e-9 / n as f64),
        _ => None,
    };
    (wall, cpu)
}

/// Criterion's wall-clock numbers, then the same loop's CPU time per collision.
fn cpu_time() {
    let scene = Scene::default_scene();
    let setup = BatchSetup::from_scene(&scene, SolverSettings::default());
    let input = states(4096);
    let (c0, _) = scene.collision().unwrap();
    let first = ClosedFormBatch::new(c0.balls, c0.contact, c0.effects)
        .resolve(&c0.incoming)
        .unwrap();
    let mut out = vec![first; input.len()];
    let passes = 2000;
    let (wall, cpu) = per_call(passes, || {
        closed_form_into(&setup, black_box(&input), &mut out).unwrap()
    });
    let n = input.len() as f64;
    println!(
        "closed_form_into: {:.1} ns wall, {} CPU per collision ({} passes over {} states)",
        wall * 1e9 / n,
        cpu.map(|c| format!("{:.1} ns", c * 1e9 / n))
            .unwrap_or_else(|| "n/a".into()),
        passes,
        input.len()
    );
}

criterion_group!(benches, bench);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
    cpu_time();
}
