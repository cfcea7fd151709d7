//! `resolve_lab_into`'s promise on failure: the index it returns is the first failing
//! row's own, and the rows before it are written. Checked where the closed form takes the
//! rows a block at a time (a bad row inside a block, behind rows already framed), row by
//! row (fewer rows than a block, an integrator), and in parallel (a bad row deep in a
//! later part of the split, two bad rows in different parts).

use billiard_contact::batch::{
    resolve_lab_into, BatchSetup, LabOutColumns, LabRows, PARALLEL_LAB_ROWS,
};
use billiard_contact::{Error, LabBall, LabScene, Method, Scene, SolverSettings};
use nalgebra::Vector3;

/// What makes a row bad: balls that do not touch (the frame fails), a reader that cannot
/// give the row (as one converting numbers would), or a speed that is not finite (the
/// frame is built; the method refuses the state).
#[derive(Clone, Copy, PartialEq)]
enum Bad {
    Apart,
    Unreadable,
    NotFinite,
}

/// Head-on rows: A at 1 + i/1000 m/s along +y onto B at rest, touching, the pair shifted by
/// i cm along x; the rows in `bad` are bad.
struct Rows {
    r: f64,
    n: usize,
    bad: Vec<(usize, Bad)>,
}

impl Rows {
    fn speed(i: usize) -> f64 {
        1.0 + i as f64 / 1000.0
    }
}

impl LabRows for Rows {
    fn len(&self) -> usize {
        self.n
    }

    fn row(&self, i: usize) -> Result<LabScene, Error> {
        let kind = self.bad.iter().find(|(k, _)| *k == i).map(|(_, b)| *b);
        if kind == Some(Bad::Unreadable) {
            return Err(Error::invalid("a_vx", "abc", "a number"));
        }
        // Three radii apart instead of two for a bad row.
        let gap = if kind == Some(Bad::Apart) { 3.0 } else { 2.0 };
        let x = 0.01 * i as f64;
        let v = if kind == Some(Bad::NotFinite) {
            f64::INFINITY
        } else {
            Rows::speed(i)
        };
        Ok(LabScene {
            a: LabBall {
                position: Vector3::new(x, 0.0, 0.0),
                velocity: Vector3::new(0.0, v, 0.0),
                spin: Vector3::zeros(),
            },
            b: LabBall {
                position: Vector3::new(x, gap * self.r, 0.0),
                velocity: Vector3::zeros(),
                spin: Vector3::zeros(),
            },
            up: Vector3::z(),
        })
    }
}

/// The columns of `n` rows, NaN until written (also for tests/lab_rows_methods.rs).
pub(crate) struct Out {
    pub(crate) va: Vec<[f64; 3]>,
    pub(crate) wa: Vec<[f64; 3]>,
    pub(crate) vb: Vec<[f64; 3]>,
    pub(crate) wb: Vec<[f64; 3]>,
    pub(crate) p: Vec<f64>,
    pub(crate) j: Vec<f64>,
    pub(crate) sticks: Vec<bool>,
    pub(crate) throw: Vec<f64>,
}

impl Out {
    pub(crate) fn new(n: usize) -> Self {
        let v = vec![[f64::NAN; 3]; n];
        Out {
            va: v.clone(),
            wa: v.clone(),
            vb: v.clone(),
            wb: v,
            p: vec![f64::NAN; n],
            j: vec![f64::NAN; n],
            sticks: vec![false; n],
            throw: vec![f64::NAN; n],
        }
    }

    pub(crate) fn columns(&mut self) -> LabOutColumns<'_> {
        LabOutColumns {
            va: &mut self.va,
            wa: &mut self.wa,
            vb: &mut self.vb,
            wb: &mut self.wb,
            impulse: &mut self.p,
            tangential_impulse: &mut self.j,
            sticks: &mut self.sticks,
            throw_angle_deg: &mut self.throw,
        }
    }
}

/// Resolves `n` rows with the bad ones `bad` and checks the error's index is `want`, the
/// error the bad row's own, and every row before it written: a head-on hit without spin
/// between equal balls is eq 52 with no friction at work, e = 1 in the default scene, so A
/// stops, B leaves with A's speed, P = m v and nothing turns.
fn check(method: Method, n: usize, bad: &[(usize, Bad)], want: usize) {
    let scene = Scene::default_scene();
    assert_eq!(scene.contact.impulse.restitution_coefficient(), Some(1.0));
    let m = scene.balls.a.mass();
    let settings = SolverSettings::default().with_method(method);
    let setup = BatchSetup::from_scene(&scene, settings);
    let rows = Rows {
        r: scene.balls.a.radius(),
        n,
        bad: bad.to_vec(),
    };
    let mut out = Out::new(n);
    let (at, e) = resolve_lab_into(&setup, &rows, out.columns()).unwrap_err();
    let case = format!(
        "{method:?}, {n} rows, bad {:?}",
        bad.iter().map(|b| b.0).collect::<Vec<_>>()
    );
    assert_eq!(at, want, "{case}");
    let kind = bad.iter().find(|b| b.0 == want).unwrap().1;
    match (kind, &e) {
        (Bad::Apart, Error::NotTouching { .. }) => {}
        (Bad::Unreadable, Error::InvalidParameter { field, .. }) if field == "a_vx" => {}
        (Bad::NotFinite, Error::InvalidParameter { value, .. }) if value == "inf" => {}
        _ => panic!("{case}: {e:?}"),
    }
    let tol = 1e-9;
    for i in 0..want {
        let v = Rows::speed(i);
        let close =
            |got: [f64; 3], want: [f64; 3]| (0..3).all(|k| (got[k] - want[k]).abs() <= tol * v);
        assert!(
            close(out.va[i], [0.0; 3]),
            "{case}: row {i} va {:?}",
            out.va[i]
        );
        assert!(
            close(out.vb[i], [0.0, v, 0.0]),
            "{case}: row {i} vb {:?}",
            out.vb[i]
        );
        assert!(
            close(out.wa[i], [0.0; 3]) && close(out.wb[i], [0.0; 3]),
            "{case}: row {i}"
        );
        assert!(
            (out.p[i] - m * v).abs() <= tol * m * v,
            "{case}: row {i} P {}",
            out.p[i]
        );
        assert!(
            out.j[i].abs() <= tol * m * v,
            "{case}: row {i} J {}",
            out.j[i]
        );
        assert!(
            out.throw[i].abs() <= 1e-9,
            "{case}: row {i} throw {}",
            out.throw[i]
        );
    }
}

#[test]
fn closed_form_blocks_report_the_failing_rows_own_index() {
    use Bad::*;
    // Bad row 13 of 20: the second block of eight, behind five rows framed in it.
    check(Method::ClosedForm, 20, &[(13, Apart)], 13);
    check(Method::ClosedForm, 20, &[(13, Unreadable)], 13);
    // First and last row of a block, first and last row of the call.
    for at in [0, 7, 8, 15, 16, 19] {
        check(Method::ClosedForm, 20, &[(at, Apart)], at);
    }
    // Two bad rows: the first is reported.
    check(Method::ClosedForm, 20, &[(17, Unreadable), (11, Apart)], 11);
    // A state the method refuses, found after the block's frames: alone, and before a row
    // whose frame fails later in the same block.
    check(Method::ClosedForm, 20, &[(10, NotFinite)], 10);
    check(Method::ClosedForm, 20, &[(13, Apart), (10, NotFinite)], 10);
    // Fewer rows than a block: row by row.
    check(Method::ClosedForm, 5, &[(3, Apart)], 3);
}

#[test]
fn integrator_rows_report_the_failing_rows_own_index() {
    check(Method::Dopri5, 12, &[(9, Bad::Apart)], 9);
    check(Method::Dopri5, 12, &[(4, Bad::NotFinite)], 4);
}

#[test]
fn parallel_rows_report_the_failing_rows_own_index() {
    use Bad::*;
    let n = PARALLEL_LAB_ROWS + 100;
    // Deep in a later part of the split, behind rows framed in its block.
    check(Method::ClosedForm, n, &[(1500, Apart)], 1500);
    check(Method::ClosedForm, n, &[(1501, NotFinite)], 1501);
    check(Method::ClosedForm, n, &[(n - 3, Unreadable)], n - 3);
    // Bad rows in two parts: the first is reported, whichever part finishes first.
    check(
        Method::ClosedForm,
        n,
        &[(n - 10, Apart), (1203, Unreadable)],
        1203,
    );
}

/// `LabRows::is_empty` (provided by the trait) says whether there is a row, for a reader of
/// its own and for a slice of scenes.
#[test]
fn is_empty_is_no_rows() {
    let rows = |n| Rows {
        r: 0.03,
        n,
        bad: vec![],
    };
    assert!(rows(0).is_empty());
    assert!(!rows(1).is_empty() && !rows(5).is_empty());
    let scene = rows(1).row(0).unwrap();
    assert!(LabRows::is_empty(&[][..] as &[LabScene]));
    assert!(!LabRows::is_empty(&[scene][..]));
}
