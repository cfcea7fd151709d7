//! The closed form per collision in a batch, on one core (issue 3 target: <= 50 ns).
//!
//! What the 50 ns covers (CONTRACTS.md): the outgoing state, impulse, S(0), theta, stick flag
//! and p_stick of states already in memory: `batch::closed_form_into` over 4096 states of
//! the default scene's balls (validation of the state, eqs 24-35 with the stick rule,
//! theta by atan2). `resolve` adds the stick time and the output record per row.

use billiard_contact::batch::{closed_form_into, resolve, BatchInput, BatchSetup};
use billiard_contact::scene::Scene;
use billiard_contact::{ClosedForm, CmState, Method, SolverSettings};
use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
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
        SolverSettings {
            method: Method::ClosedForm,
            ..Default::default()
        },
    );
    let n = 4096;
    let input = states(n);
    let (c0, _) = scene.collision().unwrap();
    let mut out = vec![(ClosedForm::new(&c0), None); n];
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

criterion_group!(benches, bench);
criterion_main!(benches);
