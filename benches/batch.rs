//! Batch throughput: in-memory slices at 1 and 2 threads and 1e3 .. 1e5 rows (closed form),
//! dop853 rows at 1 and 2 threads, and the streamed CSV path (parse, resolve, write).

use billiard_contact::batch::{resolve_slice, run_csv, BatchInput, BatchSetup, DEFAULT_CHUNK_ROWS};
use billiard_contact::Scene;
use billiard_contact::{Method, SolverSettings};
use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::path::Path;

#[path = "closed_form.rs"]
#[allow(dead_code)]
mod closed_form;

fn setup(method: Method) -> BatchSetup {
    let s = SolverSettings::new(method, 1e-9, 1e-9, 1000).unwrap();
    BatchSetup::from_scene(&Scene::default_scene(), s)
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

fn csv_text(rows: usize) -> String {
    let mut s = String::from("u_x,u_y,u_z,omega_a_x,omega_a_y,omega_a_z\n");
    for st in closed_form::states(rows) {
        let (u, w) = (st.u_cm, st.omega_a);
        s += &format!("{},{},{},{},{},{}\n", u.x, u.y, u.z, w.x, w.y, w.z);
    }
    s
}

fn bench(c: &mut Criterion) {
    let cf = setup(Method::ClosedForm);
    let mut g = c.benchmark_group("batch_closed_form");
    for rows in [1_000usize, 10_000, 100_000] {
        let input: Vec<BatchInput> = closed_form::states(rows)
            .into_iter()
            .map(BatchInput::cm)
            .collect();
        g.throughput(Throughput::Elements(rows as u64));
        for threads in [1, 2] {
            let p = pool(threads);
            g.bench_with_input(
                BenchmarkId::new(format!("{threads} threads"), rows),
                &input,
                |b, input| b.iter(|| p.install(|| black_box(resolve_slice(&cf, input)))),
            );
        }
    }
    g.finish();

    let d = setup(Method::Dop853);
    let mut g = c.benchmark_group("batch_dop853");
    g.sample_size(20);
    let rows = 2_000;
    let input: Vec<BatchInput> = closed_form::states(rows)
        .into_iter()
        .map(BatchInput::cm)
        .collect();
    g.throughput(Throughput::Elements(rows as u64));
    for threads in [1, 2] {
        let p = pool(threads);
        g.bench_with_input(
            BenchmarkId::new(format!("{threads} threads"), rows),
            &input,
            |b, input| b.iter(|| p.install(|| black_box(resolve_slice(&d, input)))),
        );
    }
    g.finish();

    let mut g = c.benchmark_group("batch_csv_closed_form");
    g.sample_size(10);
    for rows in [10_000usize, 100_000] {
        let text = csv_text(rows);
        g.throughput(Throughput::Elements(rows as u64));
        for threads in [1, 2] {
            let p = pool(threads);
            g.bench_with_input(
                BenchmarkId::new(format!("{threads} threads"), rows),
                &text,
                |b, text| {
                    b.iter(|| {
                        p.install(|| {
                            run_csv(
                                &cf,
                                text.as_bytes(),
                                Path::new("bench.csv"),
                                std::io::sink(),
                                DEFAULT_CHUNK_ROWS,
                                |_, _| {},
                            )
                            .unwrap()
                        })
                    })
                },
            );
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
