//! The `batch` command's numbers (docs/formats.md#batch-csv), through the binary: every
//! output column of centre-of-mass and lab rows against the first-principles resolution
//! (`common::resolve`) and each profile's own p(t) for the stick time, with `--scene`, every
//! per-row override (each with a value different from the scene's, so an ignored override
//! fails), `--chunk`, a time-stepping `--method` and `--rtol`. Also the closed-form fast path
//! `batch::closed_form_into`, and the speed-dependent closed form at S(0) = 0 through the
//! batch kernel.

use crate::cli_common;
use crate::common;

use cli_common::{command, fresh_dir};

use billiard_contact::batch::{closed_form_into, BatchSetup};
use billiard_contact::{CmState, ContactResult, Method, Scene, SolverSettings};
use common::{resolve, sine_power_fraction, Balls, Expected, Law, Pair, Rule};
use nalgebra::Vector3;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

/// Closed-form rows against first principles (scaled by v_ref, m v_ref, m v_ref^2): measured
/// worst 2.1e-16 over the rows below (`--nocapture` prints it).
const CLOSED_FORM_TOL: f64 = 2e-15;
/// dop853 rows at `--rtol 1e-12`: measured worst 1.7e-13.
const DOP853_TOL: f64 = 2e-12;
/// Stick times over the duration: measured worst 1.1e-16 (closed form), 3.3e-16 (dop853).
const STICK_TIME_TOL: f64 = 3e-15;

/// Runs `batch INPUT --out OUTPUT ARGS`, returns the output rows as column -> cell maps.
fn batch(dir: &Path, input: &str, args: &[&str]) -> Vec<HashMap<String, String>> {
    let (inp, out) = (dir.join("in.csv"), dir.join("out.csv"));
    std::fs::write(&inp, input).unwrap();
    let o = command()
        .arg("batch")
        .arg(&inp)
        .arg("--out")
        .arg(&out)
        .args(args)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "batch {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let text = std::fs::read_to_string(&out).unwrap();
    let mut r = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    r.records()
        .map(|rec| {
            let rec = rec.unwrap();
            header
                .iter()
                .cloned()
                .zip(rec.iter().map(String::from))
                .collect()
        })
        .collect()
}

fn num(row: &HashMap<String, String>, col: &str) -> f64 {
    let cell = row
        .get(col)
        .unwrap_or_else(|| panic!("no column {col}: {row:?}"));
    cell.parse()
        .unwrap_or_else(|_| panic!("{col} = {cell:?} is not a number"))
}

/// The scene given with `--scene`: every value differs from the built-in default scene's
/// (0.17 kg, 0.028575 m, alpha 0.4, mu 0.06, e = 1, half-sine of 2.5e-4 s).
const SCENE: &str = "name = \"batch values\"\n\
    [balls]\nmass = 0.2\nradius = 0.03\nalpha = 0.5\n\
    [contact]\nmu = 0.1\nrestitution = 0.8\n\
    [contact.profile]\nshape = \"sine-power\"\nexponent = 2.0\nduration = 1e-3\n\
    [incoming.cm]\nu = [1.0, 0.0, 0.0]\n";

/// One row: its input cells, and the reference's balls, law and stick-time profile.
struct Row {
    cells: String,
    balls: Balls,
    law: Law,
    pair: Pair,
    /// Contact duration (s).
    tau: f64,
}

/// The reference p(t)/P inverse of sin^2 (the scene's profile): s at which Phi(s) = q.
fn sin2_time(q: f64) -> f64 {
    common::invert(|s| sine_power_fraction(2.0, s), q)
}

/// Rows in the centre-of-mass frame under `SCENE`: the scene's own values, then each
/// override alone with a value that changes the answer, then all of them together.
fn cm_rows() -> Vec<Row> {
    let scene_balls = Balls {
        m: 0.2,
        r: 0.03,
        alpha: 0.5,
    };
    let scene_law = Law::new(0.1, Rule::Restitution(0.8));
    // A cut with side spin: S(0) = 0.47 m/s, sliding stops mid-pulse with the scene's values.
    let (u, wa, wb) = (
        Vector3::new(0.8, 0.15, -0.05),
        Vector3::new(3.0, -2.0, 4.0),
        Vector3::new(0.0, 1.0, -1.0),
    );
    // (override cells: mass, radius, alpha, mu, restitution, impulse, duration)
    type Cells = [Option<f64>; 7];
    let one = |k: usize, x: f64| {
        let mut c: Cells = [None; 7];
        c[k] = Some(x);
        c
    };
    let variants: Vec<Cells> = vec![
        [None; 7],
        one(0, 0.5),
        one(1, 0.05),
        one(2, 0.3),
        one(3, 0.02),
        one(4, 0.3),
        one(5, 0.25),
        one(6, 3e-4),
        [
            Some(0.3),
            Some(0.04),
            Some(0.35),
            Some(0.3),
            None,
            Some(0.4),
            Some(5e-4),
        ],
    ];
    variants
        .iter()
        .map(|c| {
            let balls = Balls {
                m: c[0].unwrap_or(scene_balls.m),
                r: c[1].unwrap_or(scene_balls.r),
                alpha: c[2].unwrap_or(scene_balls.alpha),
            };
            let rule = match (c[4], c[5]) {
                (Some(e), _) => Rule::Restitution(e),
                (_, Some(p)) => Rule::Explicit(p),
                _ => scene_law.rule,
            };
            let law = Law::new(c[3].unwrap_or(scene_law.mu), rule);
            let cell = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x:?}"));
            let nums: Vec<String> = [u, wa, wb]
                .iter()
                .flat_map(|v| v.iter().map(|x| format!("{x:?}")))
                .chain(c.iter().map(|x| cell(*x)))
                .collect();
            Row {
                cells: nums.join(","),
                balls,
                law,
                pair: Pair::cm(u, wa, wb),
                tau: c[6].unwrap_or(1e-3),
            }
        })
        .collect()
}

const CM_HEADER: &str = "u_x,u_y,u_z,omega_a_x,omega_a_y,omega_a_z,omega_b_x,omega_b_y,omega_b_z,\
    mass,radius,alpha,mu,restitution,impulse,duration";

/// Every column of a centre-of-mass row against the reference; returns the worst scaled
/// difference and the worst stick time difference over the duration.
fn check_cm_row(row: &HashMap<String, String>, want: &Expected, r: &Row, tol: f64) -> (f64, f64) {
    let (b, pair) = (&r.balls, &r.pair);
    let v = pair.v_ref(b.r);
    let (imp, energy, spin) = (b.m * v, b.m * v * v, v / b.r);
    assert_eq!(row["collision"], want.collision.to_string());
    assert_eq!(row["sticks"], want.sticks.to_string(), "{row:?}");
    let u_out = 0.5 * (want.out.va - want.out.vb);
    let mut cells = vec![
        ("impulse", want.impulse, imp),
        ("s0", want.s0, v),
        ("s_out", want.s_out, v),
        ("tangential_impulse", want.tangential, imp),
        ("heat", want.heat, energy),
        ("heat_sliding", want.heat_sliding, energy),
    ];
    let names = [
        ["u_x", "u_y", "u_z"],
        ["omega_a_x", "omega_a_y", "omega_a_z"],
        ["omega_b_x", "omega_b_y", "omega_b_z"],
    ];
    for (k, vec) in [u_out, want.out.wa, want.out.wb].iter().enumerate() {
        for j in 0..3 {
            cells.push((names[k][j], vec[j], if k == 0 { v } else { spin }));
        }
    }
    let mut worst = 0.0_f64;
    for (col, x, scale) in cells {
        let d = (num(row, col) - x).abs() / scale;
        assert!(d <= tol, "{col}: {} vs {x} ({d:e})", num(row, col));
        worst = worst.max(d);
    }
    // theta (eqs 5-6): the angle of the incoming slip (2V + r Omega_z, 2W - r Omega_y).
    let slip = pair.slip(b.r);
    let th = num(row, "theta");
    assert!((th - slip.z.atan2(slip.y)).abs() <= 4.0 * f64::EPSILON * PI);
    let mut dt = 0.0;
    if want.sticks {
        let q = want.p_stick.unwrap() / want.impulse;
        let d = (num(row, "stick_impulse") - want.p_stick.unwrap()).abs() / want.impulse;
        assert!(d <= tol, "stick_impulse {d:e}");
        dt = (num(row, "stick_time") / r.tau - sin2_time(q)).abs();
        assert!(dt <= STICK_TIME_TOL, "stick_time {dt:e} of the duration");
    } else {
        assert_eq!(row["stick_time"], "");
    }
    (worst, dt)
}

/// Centre-of-mass rows under `--scene`, with each override, in the closed form and with
/// dop853 at `--rtol 1e-12`, in one chunk and in chunks of one row.
#[test]
fn cm_rows_with_every_override_match_first_principles() {
    let dir = fresh_dir("cli_batch_values-cm");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let rows = cm_rows();
    let mut input = format!("{CM_HEADER}\n");
    for r in &rows {
        input += &r.cells;
        input.push('\n');
    }
    let s = scene.to_str().unwrap();
    let runs: [(&[&str], f64); 3] = [
        (&["--scene", s], CLOSED_FORM_TOL),
        (
            &["--scene", s, "--chunk", "1", "--threads", "2"],
            CLOSED_FORM_TOL,
        ),
        (
            &["--scene", s, "--method", "dop853", "--rtol", "1e-12"],
            DOP853_TOL,
        ),
    ];
    let mut outputs = Vec::new();
    for (args, tol) in runs {
        let out = batch(&dir, &input, args);
        assert_eq!(out.len(), rows.len());
        let (mut worst, mut worst_t) = (0.0_f64, 0.0_f64);
        let mut sticks = 0;
        for (row, r) in out.iter().zip(&rows) {
            let want = resolve(&r.balls, &r.law, &r.pair);
            let (w, t) = check_cm_row(row, &want, r, tol);
            worst = worst.max(w);
            worst_t = worst_t.max(t);
            sticks += usize::from(want.sticks);
        }
        eprintln!("batch {args:?}: worst scaled {worst:.2e}, stick time {worst_t:.2e}");
        // Both kinds of rows are there.
        assert!(sticks > 0 && sticks < rows.len(), "{sticks} sticking rows");
        let stepping = args.contains(&"dop853");
        for row in &out {
            assert_eq!(row.contains_key("closed_form_error"), stepping);
            if stepping {
                // The run's own check against the closed form, and its cost.
                assert!(num(row, "closed_form_error") <= DOP853_TOL);
                assert!(num(row, "rhs_evaluations") >= 12.0);
            }
        }
        outputs.push(std::fs::read_to_string(dir.join("out.csv")).unwrap());
    }
    // --chunk 1 on two threads writes the same file as one chunk.
    assert_eq!(outputs[0], outputs[1]);
}

/// `--rtol` reaches the integrator: dop853 at 1e-4 lands farther from the reference and
/// costs fewer evaluations than at 1e-12 (atol = rtol, docs/formats.md#batch-csv).
#[test]
fn batch_rtol_reaches_the_integrator() {
    let dir = fresh_dir("cli_batch_values-rtol");
    let r = &cm_rows()[0];
    let input = format!("{CM_HEADER}\n{}\n", r.cells);
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let s = scene.to_str().unwrap();
    let run = |rtol: &str| {
        let out = batch(
            &dir,
            &input,
            &["--scene", s, "--method", "dop853", "--rtol", rtol],
        );
        (
            num(&out[0], "closed_form_error"),
            num(&out[0], "rhs_evaluations"),
        )
    };
    let (coarse, fine) = (run("1e-4"), run("1e-12"));
    assert!(coarse.0 > 100.0 * fine.0.max(1e-16), "{coarse:?} {fine:?}");
    assert!(coarse.0 <= 1e-3, "{coarse:?}");
    assert!(coarse.1 < fine.1, "{coarse:?} {fine:?}");
}

/// Lab rows through the command (the built-in scene): outgoing lab velocities and spins,
/// the throw angle, and the centre-of-mass columns, against first principles in the lab
/// frame with a line of centres that is not an axis.
#[test]
fn lab_rows_match_first_principles() {
    let dir = fresh_dir("cli_batch_values-lab");
    let r = 0.028575;
    let n = Vector3::new(0.6, 0.8, 0.0);
    let (pa, pb) = (
        Vector3::new(0.1, 0.2, r),
        Vector3::new(0.1, 0.2, r) + 2.0 * r * n,
    );
    let (va, wa) = (Vector3::new(1.0, 0.9, 0.0), Vector3::new(-20.0, 30.0, 5.0));
    let (vb, wb) = (Vector3::new(0.0, -0.1, 0.0), Vector3::new(0.0, 0.0, -3.0));
    let cells: Vec<String> = [pa, va, wa, pb, vb, wb]
        .iter()
        .flat_map(|v| v.iter().map(|x| format!("{x:?}")))
        .collect();
    let input = format!(
        "id,a_px,a_py,a_pz,a_vx,a_vy,a_vz,a_wx,a_wy,a_wz,b_px,b_py,b_pz,b_vx,b_vy,b_vz,\
         b_wx,b_wy,b_wz\nshot,{}\n",
        cells.join(",")
    );
    let balls = Balls {
        m: 0.17,
        r,
        alpha: 0.4,
    };
    let pair = Pair { n, va, wa, vb, wb };
    let want = resolve(&balls, &Law::new(0.06, Rule::Restitution(1.0)), &pair);
    let v = pair.v_ref(r);
    for (method, tol) in [("closed-form", CLOSED_FORM_TOL), ("dop853", DOP853_TOL)] {
        let out = batch(&dir, &input, &["--method", method, "--rtol", "1e-12"]);
        let row = &out[0];
        assert_eq!(row["id"], "shot");
        let expect = [want.out.va, want.out.wa, want.out.vb, want.out.wb];
        for (k, name) in ["a_v", "a_w", "b_v", "b_w"].iter().enumerate() {
            let scale = if k % 2 == 0 { v } else { v / r };
            for (j, axis) in ["x", "y", "z"].iter().enumerate() {
                let got = num(row, &format!("{name}{axis}"));
                assert!(
                    (got - expect[k][j]).abs() <= tol * scale,
                    "{method} {name}{axis}: {got} vs {}",
                    expect[k][j]
                );
            }
        }
        for (col, x, scale) in [
            ("impulse", want.impulse, balls.m * v),
            ("s0", want.s0, v),
            ("s_out", want.s_out, v),
            ("tangential_impulse", want.tangential, balls.m * v),
            ("heat_sliding", want.heat_sliding, balls.m * v * v),
        ] {
            assert!((num(row, col) - x).abs() <= tol * scale, "{method} {col}");
        }
        // Throw (docs/model.md#throw-angle): from the horizontal line of centres to B's
        // velocity change, counter-clockwise about up = +z.
        let dvb = want.out.vb - vb;
        let throw = n.cross(&dvb).z.atan2(n.dot(&dvb)).to_degrees();
        let got = num(row, "throw_angle_deg");
        assert!(
            (got - throw).abs() <= 1e3 * tol,
            "{method} throw {got} vs {throw}"
        );
        assert!(throw.abs() > 0.3, "a throw worth checking: {throw}");
    }
}

/// The closed-form fast path: every field of each result against first principles, for
/// rows that slide, stick, start without slip and separate; a wrong-length output refused.
#[test]
fn closed_form_into_matches_first_principles() {
    let scene = Scene::default_scene();
    let setup = BatchSetup::from_scene(&scene, SolverSettings::default());
    let balls = Balls {
        m: 0.17,
        r: 0.028575,
        alpha: 0.4,
    };
    let law = Law::new(0.06, Rule::Restitution(1.0));
    let v = Vector3::new;
    let states = [
        CmState::new(v(1.0, 0.3, -0.2), v(5.0, -10.0, 20.0), v(-3.0, 8.0, 2.0)),
        CmState::new(v(1.0, 0.05, 0.02), v(3.0, 1.0, -2.0), v(0.0, -1.0, 0.5)),
        CmState::new(v(0.7, 0.0, 0.0), v(9.0, 0.0, 0.0), v(-2.0, 0.0, 0.0)),
        CmState::new(v(-0.4, 0.2, 0.0), v(1.0, 2.0, 3.0), v(0.0, 0.0, 0.0)),
    ];
    let mut out = vec![blank(); states.len()];
    closed_form_into(&setup, &states, &mut out).unwrap();
    for (k, (s, r)) in states.iter().zip(&out).enumerate() {
        let pair = Pair::cm(s.u_cm, s.omega_a, s.omega_b);
        let want = resolve(&balls, &law, &pair);
        check_result(r, &want, &balls, &pair, &format!("state {k}"));
    }
    let mut short = vec![blank(); 1];
    let err = closed_form_into(&setup, &states, &mut short).unwrap_err();
    assert!(err.to_string().contains("out"), "{err}");
}

/// An output slot for `closed_form_into` (every number NaN: a slot left unwritten fails).
fn blank() -> ContactResult {
    let nan = Vector3::repeat(f64::NAN);
    ContactResult {
        impulse: f64::NAN,
        s0: f64::NAN,
        theta: None,
        s_out: f64::NAN,
        sticks: false,
        stick_impulse: None,
        tangential_impulse: f64::NAN,
        heat: f64::NAN,
        heat_sliding: f64::NAN,
        out: CmState::new(nan, nan, nan),
    }
}

/// A result of the closed form against the reference (scaled, CLOSED_FORM_TOL).
fn check_result(r: &ContactResult, want: &Expected, b: &Balls, pair: &Pair, what: &str) {
    let v = pair.v_ref(b.r);
    let u = 0.5 * (want.out.va - want.out.vb);
    let d = [
        common::amax(&(r.out.u_cm - u)) / v,
        common::amax(&(r.out.omega_a - want.out.wa)) * b.r / v,
        common::amax(&(r.out.omega_b - want.out.wb)) * b.r / v,
        (r.impulse - want.impulse).abs() / (b.m * v),
        (r.s0 - want.s0).abs() / v,
        (r.s_out - want.s_out).abs() / v,
        (r.tangential_impulse - want.tangential).abs() / (b.m * v),
        (r.heat - want.heat).abs() / (b.m * v * v),
        (r.heat_sliding - want.heat_sliding).abs() / (b.m * v * v),
    ];
    assert!(
        d.iter().all(|x| *x <= CLOSED_FORM_TOL),
        "{what}: scaled differences {d:?}"
    );
    assert_eq!(r.sticks, want.sticks, "{what}");
    match (r.theta, common::theta_cm(pair, b.r)) {
        (Some(got), Some(th)) => assert!((got - th).abs() <= 4.0 * f64::EPSILON * PI, "{what}"),
        (got, th) => assert_eq!(got, th, "{what}"),
    }
    if want.collision && want.s0 > 0.0 {
        let ps = want.p_stick.unwrap();
        assert!(
            (r.stick_impulse.unwrap() - ps).abs() <= CLOSED_FORM_TOL * ps,
            "{what}"
        );
    }
}

/// Speed-dependent mu with S(0) = 0 through the batch kernel (the rows of a batch and the
/// fast path): no slip, so no direction and no friction impulse: theta empty, the spins and
/// the tangential velocity unchanged, U reversed by P / m (eq 24), no sliding heat. Rows
/// with slip check the same kernel against the speed-dependent closed form of
/// tests/common/hard.rs.
#[test]
fn speed_dependent_closed_form_at_zero_slip_through_the_batch_kernel() {
    let dir = fresh_dir("cli_batch_values-zero-slip");
    let scene_path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data/scenes/cut_speed_dependent.toml");
    let s = scene_path.to_str().unwrap();
    // S(0) = 0: V = W = 0, spins only about the line of centres.
    let input = "id,u_x,u_y,u_z,omega_a_x,omega_b_x\nstun,0.7,0,0,12.0,-3.0\n";
    let out = batch(&dir, input, &["--scene", s]);
    let row = &out[0];
    let (m, e) = (0.17, 0.93);
    let p = (1.0 + e) * m * 0.7;
    assert_eq!(num(row, "s0"), 0.0);
    assert_eq!(row["theta"], "");
    assert!((num(row, "impulse") - p).abs() <= 1e-15 * p);
    assert!((num(row, "u_x") - (0.7 - p / m)).abs() <= 1e-15);
    for (col, x) in [
        ("u_y", 0.0),
        ("u_z", 0.0),
        ("omega_a_x", 12.0),
        ("omega_a_y", 0.0),
        ("omega_a_z", 0.0),
        ("omega_b_x", -3.0),
        ("omega_b_y", 0.0),
        ("omega_b_z", 0.0),
        ("tangential_impulse", 0.0),
        ("heat_sliding", 0.0),
        ("s_out", 0.0),
    ] {
        assert_eq!(num(row, col), x, "{col}");
    }
    // The same state through the fast path.
    let scene = Scene::load(&scene_path).unwrap();
    let setup = BatchSetup::from_scene(
        &scene,
        SolverSettings::default().with_method(Method::ClosedForm),
    );
    let st = CmState::new(
        Vector3::new(0.7, 0.0, 0.0),
        Vector3::new(12.0, 0.0, 0.0),
        Vector3::new(-3.0, 0.0, 0.0),
    );
    let mut r = [blank()];
    closed_form_into(&setup, &[st], &mut r).unwrap();
    assert_eq!(r[0].theta, None);
    assert!(r[0].out.is_finite());
    assert_eq!(r[0].out.omega_a, st.omega_a);
    assert_eq!(r[0].out.omega_b, st.omega_b);
    assert_eq!((r[0].out.u_cm.y, r[0].out.u_cm.z), (0.0, 0.0));
    assert_eq!(r[0].tangential_impulse, 0.0);
}
