//! `resolve_lab_into` solves every row with the setup's method, whether the rows are taken
//! one by one or (the closed form's path) a block at a time: rk4's rows converge to the
//! first-principles resolution at its fourth order.

use crate::common::{resolve, Balls, Law, Pair, Rule};
use crate::lab_rows_errors::Out;
use billiard_contact::batch::{resolve_lab_into, BatchSetup};
use billiard_contact::{Friction, LabBall, LabScene, Method, Scene, SolverSettings};
use nalgebra::Vector3;

/// Rows: A at 1 + i/100 m/s along +y, with side spin, onto B at rest, touching.
fn rows(r: f64, n: usize) -> Vec<LabScene> {
    (0..n)
        .map(|i| LabScene {
            a: LabBall {
                position: Vector3::new(0.1 * i as f64, 0.0, 0.0),
                velocity: Vector3::new(0.0, 1.0 + i as f64 / 100.0, 0.0),
                spin: Vector3::new(0.0, 0.0, 20.0),
            },
            b: LabBall {
                position: Vector3::new(0.1 * i as f64, 2.0 * r, 0.0),
                velocity: Vector3::zeros(),
                spin: Vector3::zeros(),
            },
            up: Vector3::z(),
        })
        .collect()
}

/// Largest error of A's and B's outgoing velocities over the rows (m/s), against the
/// first-principles resolution (tests/common), for rk4 with `steps` steps.
fn rk4_error(steps: u32, n: usize) -> f64 {
    let scene = Scene::default_scene();
    let b = Balls {
        m: scene.balls.a.mass(),
        r: scene.balls.a.radius(),
        alpha: 0.4,
    };
    let settings = SolverSettings::default()
        .with_method(Method::Rk4)
        .with_steps(steps)
        .unwrap();
    let setup = BatchSetup::from_scene(&scene, settings);
    let rows = rows(b.r, n);
    let mut out = Out::new(n);
    resolve_lab_into(&setup, rows.as_slice(), out.columns()).unwrap();
    let mu = 0.06;
    assert_eq!(scene.contact.friction, Friction::constant(mu).unwrap());
    let mut worst = 0.0f64;
    for (i, row) in rows.iter().enumerate() {
        let pair = Pair {
            n: Vector3::y(),
            va: row.a.velocity,
            wa: row.a.spin,
            vb: row.b.velocity,
            wb: row.b.spin,
        };
        let want = resolve(&b, &Law::new(mu, Rule::Restitution(1.0)), &pair).out;
        let e = (Vector3::from(out.va[i]) - want.va)
            .amax()
            .max((Vector3::from(out.vb[i]) - want.vb).amax());
        worst = worst.max(e);
    }
    worst
}

/// The rows slide throughout (S(0) = 0.57 m/s, p_stick = m S(0) / (7 mu) = 0.23 N s above
/// P = m v), so the right-hand side is smooth and rk4's error falls 16-fold per halving of
/// the step: measured ratios 16.2 and 16.05 for 4, 8 and 16 steps, both for 4 rows (row by
/// row) and 16 (two blocks of the closed form's block path, which must not take over the
/// rows of another method).
#[test]
fn rk4_rows_converge_at_fourth_order() {
    for n in [4, 16] {
        let e = [4, 8, 16].map(|s| rk4_error(s, n));
        for k in 0..2 {
            let ratio = e[k] / e[k + 1];
            assert!((14.0..18.0).contains(&ratio), "{n} rows: errors {e:?}");
        }
    }
}
