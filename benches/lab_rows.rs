//! Lab-frame rows into columns (`batch::resolve_lab_into`, the path of the Python bindings'
//! `resolve_lab`): per row on one core, its parts (the closed-form kernel alone, the change of
//! frame), and the cut-over of the threads (`PARALLEL_LAB_ROWS`): the pool against this
//! thread from 256 to 65536 rows. Prints wall and CPU time per row; not a test.

use billiard_contact::batch::{resolve_lab_into, BatchSetup, LabOutColumns, PARALLEL_LAB_ROWS};
use billiard_contact::details::ClosedFormBatch;
use billiard_contact::{Frame, LabBall, LabScene, Method, Scene, SolverSettings};
use nalgebra::Vector3;
use std::hint::black_box;

#[path = "closed_form.rs"]
#[allow(dead_code)]
mod closed_form;
use closed_form::{per_call, states};

/// The varied centre-of-mass states of the closed-form bench, turned about `up` = +z by
/// row-dependent angles and moving with a common lab velocity: balls on a table.
fn lab_rows(n: usize, r: f64) -> Vec<LabScene> {
    states(n)
        .into_iter()
        .enumerate()
        .map(|(i, s)| {
            let (sin, cos) = (i as f64 * 0.7).sin_cos();
            let turn =
                |v: Vector3<f64>| Vector3::new(cos * v.x - sin * v.y, sin * v.x + cos * v.y, v.z);
            let pa = Vector3::new(0.5, 0.7, r);
            let v_cm = Vector3::new(0.1, -0.2, 0.0);
            LabScene {
                a: LabBall {
                    position: pa,
                    velocity: v_cm + turn(s.u_cm),
                    spin: turn(s.omega_a),
                },
                b: LabBall {
                    position: pa + turn(Vector3::x()) * 2.0 * r,
                    velocity: v_cm - turn(s.u_cm),
                    spin: turn(s.omega_b),
                },
                up: Vector3::z(),
            }
        })
        .collect()
}

/// Output columns of n rows.
struct Columns {
    v: [Vec<[f64; 3]>; 4],
    s: [Vec<f64>; 3],
    sticks: Vec<bool>,
}

impl Columns {
    fn new(n: usize) -> Self {
        let v = || vec![[0.0; 3]; n];
        Columns {
            v: [v(), v(), v(), v()],
            s: [vec![0.0; n], vec![0.0; n], vec![0.0; n]],
            sticks: vec![false; n],
        }
    }

    fn out(&mut self) -> LabOutColumns<'_> {
        let [va, wa, vb, wb] = &mut self.v;
        let [p, j, t] = &mut self.s;
        LabOutColumns {
            va,
            wa,
            vb,
            wb,
            impulse: p,
            tangential_impulse: j,
            sticks: &mut self.sticks,
            throw_angle_deg: t,
        }
    }
}

/// Best of five (wall, CPU) per row over `passes` calls of `f` on `n` rows.
fn best(n: usize, passes: u64, mut f: impl FnMut()) -> (f64, f64) {
    (0..5)
        .map(|_| {
            let (wall, cpu) = per_call(passes, &mut f);
            (
                wall * 1e9 / n as f64,
                cpu.unwrap_or(f64::NAN) * 1e9 / n as f64,
            )
        })
        .fold((f64::INFINITY, f64::INFINITY), |a, b| {
            (a.0.min(b.0), a.1.min(b.1))
        })
}

fn main() {
    let scene = Scene::default_scene();
    let settings = SolverSettings::default().with_method(Method::ClosedForm);
    let setup = BatchSetup::from_scene(&scene, settings);
    let r = scene.balls.a.radius();
    let n = 1024; // below the cut-over: this thread only
    let rows = lab_rows(n, r);
    let kernel = ClosedFormBatch::new(setup.balls, setup.contact, setup.effects);
    let cms: Vec<_> = rows
        .iter()
        .map(|l| Frame::new(l, r).unwrap().to_cm(l))
        .collect();
    let mut cols = Columns::new(n);
    let show = |what: &str, (wall, cpu): (f64, f64)| {
        println!("{what:<58} {wall:7.1} ns wall {cpu:7.1} ns CPU per row")
    };
    show(
        "closed-form kernel alone (centre-of-mass states)",
        best(n, 2000, || {
            for s in black_box(&cms) {
                black_box(kernel.resolve(s).unwrap());
            }
        }),
    );
    show(
        "frame: new, to_cm, outgoing (with the throw angle)",
        best(n, 2000, || {
            for (l, s) in black_box(&rows).iter().zip(&cms) {
                let f = Frame::new(l, r).unwrap();
                black_box(f.to_cm(l));
                black_box(f.outgoing(l, s, true));
            }
        }),
    );
    show(
        "resolve_lab_into, 1024 rows, this thread",
        best(n, 2000, || {
            resolve_lab_into(&setup, black_box(&rows[..]), cols.out()).unwrap()
        }),
    );

    // The cut-over: n rows on this thread against two halves given to the pool
    // (rayon::join, as resolve_lab_into splits them from PARALLEL_LAB_ROWS on). One thread:
    // resolve_lab_into in a pool of one thread, where its split runs in order.
    println!("cut-over (PARALLEL_LAB_ROWS = {PARALLEL_LAB_ROWS}): one thread against the pool");
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    for n in [128, 256, 512, 1024, 2048, 4096, 16384, 65536] {
        let rows = lab_rows(n, r);
        let mut cols = Columns::new(n);
        let passes = (4_000_000 / n as u64).max(20);
        let serial = best(n, passes, || {
            one.install(|| resolve_lab_into(&setup, black_box(&rows[..]), cols.out()).unwrap())
        });
        let split = best(n, passes, || {
            let (head, tail) = cols.out().split_at(n / 2);
            let (a, b) = rayon::join(
                || resolve_lab_into(&setup, black_box(&rows[..n / 2]), head),
                || resolve_lab_into(&setup, black_box(&rows[n / 2..]), tail),
            );
            a.and(b).unwrap()
        });
        println!(
            "{n:>6} rows: one thread {:6.1} ns, two halves on the pool {:6.1} ns wall per row",
            serial.0, split.0
        );
    }
}
