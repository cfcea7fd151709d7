//! The cluster kernel (docs/cluster.md): a 16-ball break (cue ball at 8 m/s into a tight
//! rack, Hertz with Hunt-Crossley damping calibrated to e = 0.95 at 1 m/s, mu = 0.06 at
//! every contact) at rtol 1e-8 (target <= 5 ms); racks of N = 2, 4, 8, 16, 22 balls, whose
//! time over (steps x mean pressing contacts) is the cost per contact per step (printed with
//! a self-timed median before criterion's runs); the 16-ball break with a trace of a row per
//! step; two balls through the cluster path against
//! `solve_law` at the same tolerance (target <= 3x).

use billiard_contact::nalgebra::Vector3;
use billiard_contact::*;
use criterion::{black_box, criterion_group, Criterion};

const M: f64 = 0.17;
const R: f64 = 0.028575;

fn law() -> ContactLaw {
    let e_star = 5.4e9 / (2.0 * (1.0 - 0.34 * 0.34));
    let k = 4.0 / 3.0 * e_star * (R / 2.0).sqrt();
    ContactLaw::calibrated(k, Damping::HuntCrossley, 0.95, 1.0, 0.5 * M).unwrap()
}

fn at(p: Vector3<f64>, v: Vector3<f64>) -> ClusterBall {
    ClusterBall {
        ball: Ball::new(M, R, 0.4).unwrap(),
        position: p,
        velocity: v,
        spin: Vector3::zeros(),
    }
}

/// A cue ball at `speed` (m/s) into a tight triangle of `n - 1` balls (rows filled in
/// order), slightly off the apex's centre line so that the rack is not symmetric.
fn rack(n: usize, speed: f64) -> Cluster {
    let mut balls = vec![at(
        Vector3::new(-2.0 * R, 0.0, 0.0),
        Vector3::new(speed, 0.02 * speed, 0.0),
    )];
    let dx = R * 3f64.sqrt();
    'rows: for row in 0.. {
        for k in 0..=row {
            if balls.len() == n {
                break 'rows;
            }
            let y = (k as f64 - row as f64 / 2.0) * 2.0 * R;
            balls.push(at(Vector3::new(row as f64 * dx, y, 0.0), Vector3::zeros()));
        }
    }
    Cluster::new(balls, ClusterLaw::Same(law()), 0.06).unwrap()
}

fn bench(cr: &mut Criterion) {
    let s = ClusterSettings {
        rtol: 1e-8,
        stick: true,
    };
    eprintln!(
        "N | stop | steps | evaluations | mean contacts | time per run | per contact per step"
    );
    for n in [2, 4, 8, 16, 22] {
        let c = rack(n, 8.0);
        let o = resolve_cluster(&c, &s).unwrap();
        // The contacts pressing on average over the run: their durations over its time.
        let mean: f64 = o.contacts.iter().map(|k| k.duration).sum::<f64>() / o.time;
        // A self-timed estimate next to criterion's: the median of 31 runs.
        let mut t: Vec<f64> = (0..31)
            .map(|_| {
                let t0 = std::time::Instant::now();
                black_box(resolve_cluster(black_box(&c), &s).unwrap());
                t0.elapsed().as_secs_f64()
            })
            .collect();
        t.sort_by(f64::total_cmp);
        let run = t[t.len() / 2];
        eprintln!(
            "{n} | {:?} | {} | {} | {mean:.1} | {:.3} ms | {:.2} us",
            o.stop,
            o.stats.steps,
            o.stats.evaluations,
            run * 1e3,
            run / (o.stats.steps as f64 * mean) * 1e6
        );
        cr.bench_function(&format!("cluster_break_n{n}_rtol1e-8"), |b| {
            b.iter(|| resolve_cluster(black_box(&c), &s).unwrap())
        });
    }
    // The 16-ball break with a trace taking a row per accepted step (the rows' forces
    // evaluated apart, counted nowhere): the cost of a trace when one is asked for.
    let c = rack(16, 8.0);
    cr.bench_function("cluster_break_n16_rtol1e-8_traced", |b| {
        b.iter(|| {
            let mut rows = 0usize;
            let mut sink = |r: &ClusterTraceRow<'_>| rows += r.contacts.len();
            let trace = ClusterTrace {
                sampling: ClusterSampling::Steps,
                sink: &mut sink,
            };
            resolve_cluster_traced(black_box(&c), &s, trace).unwrap();
            rows
        })
    });
    // Two balls: the cluster path and solve_law (dopri5, the same rtol).
    let c = rack(2, 1.0);
    let contact = Contact {
        friction: Friction::constant(0.06).unwrap(),
        impulse: ImpulseRule::ELASTIC,
    };
    let st = CmState::new(
        Vector3::new(0.5, 0.01, 0.0),
        Vector3::zeros(),
        Vector3::zeros(),
    );
    let col = Collision::new(
        Ball::new(M, R, 0.4).unwrap(),
        contact,
        Effects::default(),
        st,
    )
    .unwrap();
    let ss = SolverSettings::new(Method::Dopri5, 1e-8, 1e-8, details::DEFAULT_STEPS).unwrap();
    cr.bench_function("cluster_two_balls_rtol1e-8", |b| {
        b.iter(|| resolve_cluster(black_box(&c), &s).unwrap())
    });
    let l = law();
    cr.bench_function("solve_law_two_balls_dopri5_rtol1e-8", |b| {
        b.iter(|| solve_law(black_box(&col), &l, &ss, None).unwrap())
    });
}

criterion_group!(benches, bench);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
}
