//! Hertz from the balls' material (docs/model.md#hertz-from-the-material): the contact time,
//! compression, peak force and contact radius against the textbook formulas written out in
//! `common::hertz_identical` (and, for unequal balls, below); the v^(-1/5) law; scenes that
//! give the material instead of a duration, their errors, and the time-stepped solution with
//! the material's pulse against the closed form.

use crate::common;

use billiard_contact::batch::{resolve_slice, BatchInput, BatchSetup};
use billiard_contact::Report;
use billiard_contact::{
    run_scene, Ball, CmState, Error, HertzContact, Material, Method, Scene, SolverSettings,
};
use common::{amax, hertz_identical, resolve, Balls, Law, Pair, Rule};
use nalgebra::Vector3;
use std::path::Path;

/// Relative agreement of the material's quantities with the formulas.
const FORMULA_TOL: f64 = 1e-12;
/// Dop853 at rtol 1e-12 within 1e-10 of the closed form (scaled), as for every profile.
const DOP853_TOL: f64 = 1e-10;
/// Stick time: within 1e-10 of the duration of the exact p(t) (docs/formats.md).
const STICK_TIME_TOL: f64 = 1e-10;

const M: f64 = 0.17;
const R: f64 = 0.028575;
/// Phenolic resin.
const E: f64 = 5.4e9;
const NU: f64 = 0.34;
/// Where sliding stops in the batch rows (V(0) = 0.04 U(0), no spin, mu = 0.06, e = 1):
/// p_stick / P = (m S(0) / (2 mu (1 + 1/alpha))) / (2 m U(0)) with S(0) = 0.08 U(0).
const STOP_FRACTION: f64 = 0.04 * 2.0 / (2.0 * 0.06 * 3.5) / 2.0;

fn rel(got: f64, want: f64) -> f64 {
    ((got - want) / want).abs()
}

fn pool_ball() -> Ball {
    Ball::new(M, R, 0.4).unwrap()
}

/// The pool-ball example: two 0.17 kg balls of radius 28.575 mm, E = 5.4 GPa, nu = 0.34,
/// meeting at 1 m/s: tau = 402 us, delta_max = 137 um, F_max = 777 N, a = 1.40 mm.
#[test]
fn pool_balls_at_one_metre_per_second() {
    let h = HertzContact::identical(&pool_ball(), &Material::new(E, NU).unwrap(), 0.5).unwrap();
    let want = hertz_identical(M, R, E, NU, 1.0);
    assert!(rel(h.duration, want.duration) <= FORMULA_TOL, "{h:?}");
    assert!(rel(h.max_compression, want.max_compression) <= FORMULA_TOL);
    assert!(rel(h.peak_force, want.peak_force) <= FORMULA_TOL);
    assert!(rel(h.contact_radius, want.contact_radius) <= FORMULA_TOL);
    // The rounded values of the example.
    assert_eq!((h.duration * 1e6).round(), 402.0);
    assert_eq!((h.max_compression * 1e6).round(), 137.0);
    assert_eq!(h.peak_force.round(), 777.0);
    assert_eq!((h.contact_radius * 1e5).round(), 140.0);
    assert_eq!(h.approach_speed, 1.0);
}

/// delta_max ~ v^(4/5) and tau = 2.943 delta_max / v ~ v^(-1/5), F_max ~ v^(6/5),
/// a ~ v^(2/5): over four decades of speed (1 cm/s to 100 m/s) the products with the
/// inverse powers are constant, and every value matches the formulas.
#[test]
fn contact_time_falls_as_the_fifth_root_of_the_speed() {
    let mat = Material::new(E, NU).unwrap();
    let at_one = hertz_identical(M, R, E, NU, 1.0);
    for k in 0..=40 {
        let v = 10f64.powf(-2.0 + 0.1 * f64::from(k));
        let h = HertzContact::identical(&pool_ball(), &mat, v / 2.0).unwrap();
        let want = hertz_identical(M, R, E, NU, v);
        assert!(rel(h.duration, want.duration) <= FORMULA_TOL, "v = {v}");
        assert!(rel(h.max_compression, want.max_compression) <= FORMULA_TOL);
        assert!(rel(h.peak_force, want.peak_force) <= FORMULA_TOL);
        assert!(rel(h.contact_radius, want.contact_radius) <= FORMULA_TOL);
        assert!(
            rel(h.duration * v.powf(0.2), at_one.duration) <= FORMULA_TOL,
            "v = {v}"
        );
        assert!(rel(h.max_compression * v.powf(-0.8), at_one.max_compression) <= FORMULA_TOL);
        assert!(rel(h.peak_force * v.powf(-1.2), at_one.peak_force) <= FORMULA_TOL);
        assert!(rel(h.contact_radius * v.powf(-0.4), at_one.contact_radius) <= FORMULA_TOL);
    }
}

/// Unequal balls and materials: 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b,
/// 1/R = 1/r_a + 1/r_b, m* = m_a m_b / (m_a + m_b), and the same k, delta_max, tau, F_max, a.
#[test]
fn unequal_balls_use_the_general_formulas() {
    let (ma, ra, ea, nua): (f64, f64, f64, f64) = (0.17, 0.028575, 5.4e9, 0.34);
    let (mb, rb, eb, nub): (f64, f64, f64, f64) = (0.21, 0.0305, 2.0e11, 0.29);
    let v: f64 = 2.3;
    let e_star = 1.0 / ((1.0 - nua * nua) / ea + (1.0 - nub * nub) / eb);
    let radius = ra * rb / (ra + rb);
    let m_star = ma * mb / (ma + mb);
    let k = 4.0 / 3.0 * e_star * radius.sqrt();
    let delta = (5.0 * m_star * v * v / (4.0 * k)).powf(0.4);
    let tau = 0.8 * common::beta_fn(0.4, 0.5) * delta / v;
    let h = HertzContact::between(
        (
            &Ball::new(ma, ra, 0.4).unwrap(),
            &Material::new(ea, nua).unwrap(),
        ),
        (
            &Ball::new(mb, rb, 0.4).unwrap(),
            &Material::new(eb, nub).unwrap(),
        ),
        v,
    )
    .unwrap();
    assert!(rel(h.effective_modulus, e_star) <= FORMULA_TOL);
    assert!(rel(h.effective_radius, radius) <= FORMULA_TOL);
    assert!(rel(h.reduced_mass, m_star) <= FORMULA_TOL);
    assert!(rel(h.duration, tau) <= FORMULA_TOL);
    assert!(rel(h.max_compression, delta) <= FORMULA_TOL);
    assert!(rel(h.peak_force, k * delta.powf(1.5)) <= FORMULA_TOL);
    assert!(rel(h.contact_radius, (radius * delta).sqrt()) <= FORMULA_TOL);
}

/// A scene in the centre-of-mass frame with the material, shape `shape` and no duration.
fn scene_text(shape: &str, u: [f64; 3], extra: &str) -> String {
    format!(
        "name = \"material\"\n[balls]\nmass = {M}\nradius = {R}\nyoungs_modulus = {E:e}\n\
         poisson_ratio = {NU}\n[contact]\nmu = 0.06\n{extra}\n[contact.profile]\n\
         shape = \"{shape}\"\n[incoming.cm]\nu = [{}, {}, {}]\n",
        u[0], u[1], u[2]
    )
}

fn parse(text: &str) -> Result<Scene, Error> {
    Scene::parse(text, Path::new("."), None)
}

/// The JSON report carries the computed duration and the `hertz` object.
#[test]
fn a_scene_with_the_material_reports_its_hertz_contact() {
    let scene = parse(&scene_text("hertz", [0.5, 0.1, 0.0], "")).unwrap();
    let out = run_scene(&scene, &scene.solver, None).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&Report::new(&scene, &out).to_json().unwrap()).unwrap();
    let want = hertz_identical(M, R, E, NU, 1.0);
    let num = |v: &serde_json::Value| v.as_f64().unwrap();
    assert!(rel(num(&json["duration"]), want.duration) <= FORMULA_TOL);
    let h = &json["hertz"];
    assert!(rel(num(&h["max_compression"]), want.max_compression) <= FORMULA_TOL);
    assert!(rel(num(&h["peak_force"]), want.peak_force) <= FORMULA_TOL);
    assert!(rel(num(&h["contact_radius"]), want.contact_radius) <= FORMULA_TOL);
    // sine-power takes the same duration; a scene with a duration has no `hertz` object.
    let sp = parse(&scene_text("sine-power", [0.5, 0.1, 0.0], "")).unwrap();
    assert!(
        rel(
            billiard_contact::profile::ForceProfile::duration(&sp.profile),
            want.duration
        ) <= FORMULA_TOL
    );
    let plain = Scene::default_scene();
    let out = run_scene(&plain, &plain.solver, None).unwrap();
    let text = Report::new(&plain, &out).to_json().unwrap();
    assert!(!text.contains("\"hertz\""), "{text}");
}

/// The bad combinations, each one line naming the fields.
#[test]
fn bad_material_scenes_are_refused_naming_the_fields() {
    let message = |text: &str| parse(text).unwrap_err().to_string();
    let both = scene_text("hertz", [0.5, 0.1, 0.0], "")
        .replace("shape = \"hertz\"", "shape = \"hertz\"\nduration = 2.5e-4");
    let e = message(&both);
    // Both fields with the values the scene gives (E = 5.4e9 Pa, nu = 0.34).
    assert!(
        e.contains("contact.profile.duration")
            && e.contains("balls.youngs_modulus = 5400000000")
            && e.contains("balls.poisson_ratio = 0.34"),
        "{e}"
    );
    // A shape whose duration the material does not set: the material is what is refused
    // (not the duration beside it).
    let half_sine = scene_text("half-sine", [0.5, 0.1, 0.0], "").replace(
        "shape = \"half-sine\"",
        "shape = \"half-sine\"\nduration = 2.5e-4",
    );
    match parse(&half_sine) {
        Err(Error::InvalidParameter {
            field, expected, ..
        }) => assert!(
            field == "balls.youngs_modulus" && expected.contains("\"hertz\" or \"sine-power\""),
            "{field}: {expected}"
        ),
        other => panic!("{other:?}"),
    }
    let e =
        message(&scene_text("hertz", [0.5, 0.1, 0.0], "").replace("poisson_ratio = 0.34\n", ""));
    assert!(
        e.contains("balls.poisson_ratio") && e.contains("missing"),
        "{e}"
    );
    let e = message(&scene_text("hertz", [0.5, 0.1, 0.0], "").replace("0.34", "0.7"));
    assert!(
        e.contains("balls.poisson_ratio") && e.contains("0.7"),
        "{e}"
    );
    let e = message(&scene_text("hertz", [-0.5, 0.1, 0.0], ""));
    assert!(e.contains("incoming") && e.contains("approach"), "{e}");
    let plain = scene_text("hertz", [0.5, 0.1, 0.0], "")
        .replace("youngs_modulus = 5.4e9\n", "")
        .replace("poisson_ratio = 0.34\n", "");
    let e = message(&plain);
    assert!(
        e.contains("contact.profile.duration") && e.contains("missing"),
        "{e}"
    );
}

/// Dop853 at rtol 1e-12 with the material's pulse (hertz and sine-power; time transform on
/// and off) lands within 1e-10 of the first-principles resolution, sliding throughout or
/// sticking (early and late, also with e < 1), and stops where the exact Hertz p(t) reaches
/// p_stick, with t scaled by the material's own contact time.
#[test]
fn time_stepping_with_the_material_pulse_matches_the_closed_form() {
    let balls = Balls {
        m: M,
        r: R,
        alpha: 0.4,
    };
    let cases = [
        ([0.5, 0.3, 0.0], 1.0),   // p_stick > P: slides throughout
        ([0.8, 0.02, 0.0], 1.0),  // sticks early
        ([0.3, 0.05, 0.02], 0.8), // sticks late, e < 1
        ([2.0, 0.1, -0.05], 0.9),
    ];
    let mut worst = (0.0_f64, 0.0_f64);
    for (u, e) in cases {
        let pair = Pair::cm(Vector3::from(u), Vector3::zeros(), Vector3::zeros());
        let want = resolve(&balls, &Law::new(0.06, Rule::Restitution(e)), &pair);
        let tau = hertz_identical(M, R, E, NU, 2.0 * u[0]).duration;
        for shape in ["hertz", "sine-power"] {
            let scene = parse(&scene_text(shape, u, &format!("restitution = {e}"))).unwrap();
            for transform in [true, false] {
                let s = SolverSettings::new(Method::Dop853, 1e-12, 1e-12, 1000)
                    .unwrap()
                    .with_time_transform(transform);
                let out = run_scene(&scene, &s, None).unwrap().outcome;
                let what = format!("{shape} u = {u:?} e = {e} transform {transform}");
                let v = pair.v_ref(R);
                let err = (amax(&(out.result.out.u_cm - want.out.va)) / v)
                    .max(amax(&(out.result.out.omega_a - want.out.wa)) / (v / R))
                    .max(amax(&(out.result.out.omega_b - want.out.wb)) / (v / R));
                assert!(err <= DOP853_TOL, "{what}: {err:e}");
                assert_eq!(out.result.sticks, want.sticks, "{what}");
                if let Some(p_stick) = want.p_stick.filter(|_| want.sticks) {
                    let q = p_stick / want.impulse;
                    let s_exact = match shape {
                        "hertz" => common::hertz_time(q),
                        _ => common::invert(|s| common::sine_power_fraction(1.5, s), q),
                    };
                    let dt = (out.stick_time.unwrap() / tau - s_exact).abs();
                    assert!(dt <= STICK_TIME_TOL, "{what}: stick time {dt:e} tau");
                    worst.1 = worst.1.max(dt);
                }
                worst.0 = worst.0.max(err);
            }
        }
    }
    eprintln!(
        "material pulses, dop853 rtol 1e-12: largest scaled error {:.2e}, stick time {:.2e} tau",
        worst.0, worst.1
    );
}

/// A batch under an elastic Hertz law with the material: the law's stiffness, and so the
/// contact time, follows each row's own radius. A row at r = 0.04 m stops sliding at its
/// own textbook contact time times the stop's fraction of the Hertz pulse (the elastic law
/// is the Hertz profile), like the row at the scene's radius.
#[test]
fn batch_rows_under_a_law_take_the_stiffness_of_their_radius() {
    let text = format!(
        "[balls]\nmass = {M}\nradius = {R}\nyoungs_modulus = {E:e}\npoisson_ratio = {NU}\n\
         [contact]\nmu = 0.06\n[contact.law]\nmodel = \"hertz\"\n\
         [incoming.cm]\nu = [0.5, 0.02, 0.0]\n"
    );
    let scene = parse(&text).unwrap();
    let u0 = 0.5;
    // Measured at the default settings: closed form 2.7e-11, dop853 1.3e-9 (relative).
    for (method, tol) in [(Method::ClosedForm, 3e-10), (Method::Dop853, 1.5e-8)] {
        let setup = BatchSetup::from_scene(&scene, SolverSettings::default().with_method(method));
        for r in [R, 0.04] {
            let mut row = BatchInput::cm(CmState::new(
                Vector3::new(u0, 0.04 * u0, 0.0),
                Vector3::zeros(),
                Vector3::zeros(),
            ));
            row.overrides.radius = Some(r);
            let t = resolve_slice(&setup, &[row])[0]
                .as_ref()
                .unwrap()
                .stick_time
                .unwrap();
            let want =
                hertz_identical(M, r, E, NU, 2.0 * u0).duration * common::hertz_time(STOP_FRACTION);
            assert!(
                (t - want).abs() <= tol * want,
                "{method}: radius {r}: {t} vs {want}"
            );
        }
    }
}

/// A batch with the material: each row's stick time is its own contact time times the
/// stick fraction. Rows at approach speeds v and 10^4 v with the same slip ratio stop at
/// the same fraction of their pulses, so their stick times differ by (10^4)^(-1/5); a
/// `duration` column is refused.
#[test]
fn batch_rows_take_their_own_contact_time() {
    let scene = parse(&scene_text("hertz", [0.5, 0.1, 0.0], "")).unwrap();
    for method in [Method::ClosedForm, Method::Dop853] {
        let s = SolverSettings::default().with_method(method);
        let setup = BatchSetup::from_scene(&scene, s);
        let rows: Vec<BatchInput> = [0.005, 50.0]
            .iter()
            .map(|&u0| {
                BatchInput::cm(CmState::new(
                    Vector3::new(u0, 0.04 * u0, 0.0),
                    Vector3::zeros(),
                    Vector3::zeros(),
                ))
            })
            .collect();
        let out = resolve_slice(&setup, &rows);
        let t: Vec<f64> = out
            .iter()
            .map(|o| o.as_ref().unwrap().stick_time.unwrap())
            .collect();
        for (k, &u0) in [0.005, 50.0].iter().enumerate() {
            let want =
                hertz_identical(M, R, E, NU, 2.0 * u0).duration * common::hertz_time(STOP_FRACTION);
            assert!(
                (t[k] - want).abs() <= 1e-9 * want,
                "{method}: row {k}: {} vs {want}",
                t[k]
            );
        }
        assert!(rel(t[1] / t[0], 1e4f64.powf(-0.2)) <= 1e-9, "{method}");
        // Balls that touch without approaching (U(0) = 0) or that recede (U(0) < 0) do not
        // collide: the row passes through unchanged, with no stick time. The material's
        // contact time exists only for U(0) > 0, so it must not be asked for here.
        for u0 in [0.0, -0.3] {
            let cm = CmState::new(
                Vector3::new(u0, 0.1, 0.0),
                Vector3::zeros(),
                Vector3::new(0.0, 0.0, 5.0),
            );
            let got = resolve_slice(&setup, &[BatchInput::cm(cm)]);
            let o = got[0]
                .as_ref()
                .unwrap_or_else(|e| panic!("{method}: U(0) = {u0}: {e}"));
            assert!(!o.result.collided(), "{method}: U(0) = {u0}");
            assert_eq!(o.result.out, cm, "{method}: U(0) = {u0}");
            assert_eq!(o.stick_time, None, "{method}: U(0) = {u0}");
        }
        let mut bad = rows[0];
        bad.overrides.duration = Some(2.5e-4);
        let e = resolve_slice(&setup, &[bad])[0]
            .as_ref()
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("duration") && e.contains("balls.youngs_modulus"),
            "{e}"
        );
    }
}

/// Speeds so extreme that the contact's numbers leave the normal positive range are refused
/// naming `contact.profile.duration`: at 1e200 m/s, v^2 overflows and the compression, force
/// and time come out infinite; at 1e-300 m/s, v^2 underflows and the compression is 0.
#[test]
fn contacts_out_of_range_are_refused() {
    let (ball, material) = (pool_ball(), Material::new(5.4e9, 0.34).unwrap());
    for v in [1e200, 1e-300] {
        match HertzContact::between((&ball, &material), (&ball, &material), v) {
            Err(billiard_contact::Error::InvalidParameter { field, .. }) => {
                assert_eq!(field, "contact.profile.duration", "v = {v:e}")
            }
            other => panic!("v = {v:e}: {other:?}"),
        }
    }
}
