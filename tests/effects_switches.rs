//! Switching effects off changes the outputs exactly as the physics says.
//!
//! Scene: centre-of-mass frame, m = 0.17 kg, r = 0.028575 m, alpha = 2/5, mu = 0.06, e = 1,
//! U(0) = (1, 0.1, 0) (a stun cut): P = 2 m U(0) = 0.34 N s, S(0) = 2 V = 0.2 m/s,
//! theta = 0, p_stick = m S(0) / (2 mu (1 + 1/alpha)) = 0.0809... N s < P: eq 57 fails.

use crate::scenes;

use billiard_contact::run_scene;
use billiard_contact::Report;
use billiard_contact::Sampling;
use billiard_contact::Scene;
use billiard_contact::TraceRow;
use scenes::{cue, lab_scene, M, R};
use std::path::Path;

const MU: f64 = 0.06;
/// Closed form arithmetic.
const EXACT: f64 = 1e-14;
/// Time stepping at the default rtol 1e-10 (scaled by v_ref = 1 m/s).
const STEPPED: f64 = 1e-9;

fn cm_scene(method: &str, effects: &str) -> Scene {
    let text = format!(
        r#"
[balls]
mass = {M}
radius = {R}
[contact]
mu = {MU}
restitution = 1.0
[contact.profile]
shape = "half-sine"
duration = 2.5e-4
[incoming.cm]
u = [1.0, 0.1, 0.0]
[solver]
method = "{method}"
[effects]
{effects}
"#
    );
    Scene::parse(&text, Path::new("."), None).unwrap()
}

/// Friction off: eq 14 alone. U -> U - P/m = -1, everything else unchanged, J = 0, no
/// sliding heat, no stick; the trace's S stays S(0).
#[test]
fn friction_off_is_eq_14_alone() {
    for (method, tol) in [
        ("closed-form", EXACT),
        ("dop853", STEPPED),
        ("rk4", STEPPED),
    ] {
        let s = cm_scene(method, "friction = false");
        let mut trace: Vec<TraceRow> = Vec::new();
        let so = run_scene(&s, &s.solver, Some((&mut trace, Sampling::Uniform(10)))).unwrap();
        let o = &so.outcome;
        assert!((o.result.out.u_cm.x - (1.0 - 2.0)).abs() <= tol, "{method}");
        assert_eq!(o.result.out.u_cm.y, 0.1, "{method}: V untouched");
        assert_eq!(o.result.out.u_cm.z, 0.0);
        assert_eq!(o.result.out.omega_a, nalgebra::Vector3::zeros());
        assert_eq!(o.result.out.omega_b, nalgebra::Vector3::zeros());
        assert_eq!(o.result.tangential_impulse, 0.0);
        assert_eq!(o.result.heat_sliding, 0.0);
        assert!(!o.result.sticks);
        assert_eq!(o.stick_time, None);
        assert_eq!(o.result.stick_impulse, None);
        assert!(o.warnings.is_empty());
        assert!(trace
            .iter()
            .all(|r| r.slip_speed == 0.2 && r.heat_sliding == 0.0));
        // Heat: only the normal impulse, 2 U(0) P - P^2/m = 0 for e = 1.
        assert!(o.result.heat.abs() <= tol * M);
        assert_eq!(s.effects.names(), vec!["normal-impulse"]);
    }
}

/// Stick off: the paper's eqs 24-33 literally, with P = 0.34 N s and theta = 0:
/// V = 0.1 - mu P / m = -0.02, Omega^{A,B}_z = -mu P / (alpha m r), S_out = S(0) -
/// 2 mu (1 + 1/alpha) P / m = -0.64 (negative: eq 57 fails), and a warning says so.
/// Stick on: J = m S(0) / (2 (1 + 1/alpha)), S_out = 0, no warning.
#[test]
fn stick_off_is_the_papers_formulas_with_the_eq57_warning() {
    let p = 2.0 * M * 1.0;
    for (method, tol) in [("closed-form", EXACT), ("dop853", STEPPED)] {
        let s = cm_scene(method, "stick = false");
        let o = run_scene(&s, &s.solver, None).unwrap().outcome;
        assert!(
            (o.result.out.u_cm.y - (0.1 - MU * p / M)).abs() <= tol,
            "{method}"
        );
        let dz = -MU * p / (0.4 * M * R);
        assert!(
            (o.result.out.omega_a.z - dz).abs() <= tol * dz.abs(),
            "{method}"
        );
        assert!((o.result.out.omega_b.z - dz).abs() <= tol * dz.abs());
        assert!(
            (o.result.s_out - (0.2 - 2.0 * MU * 3.5 * p / M)).abs() <= tol,
            "{method}"
        );
        assert!((o.result.tangential_impulse - MU * p).abs() <= tol * p);
        assert!(!o.result.sticks);
        assert_eq!(o.warnings.len(), 1, "{:?}", o.warnings);
        assert!(o.warnings[0].contains("eq 57"), "{}", o.warnings[0]);
        assert_eq!(s.effects.names(), vec!["normal-impulse", "friction"]);

        let s = cm_scene(method, "stick = true");
        let o = run_scene(&s, &s.solver, None).unwrap().outcome;
        assert!(o.result.sticks);
        assert_eq!(o.result.s_out, 0.0);
        assert!((o.result.tangential_impulse - M * 0.2 / 7.0).abs() <= tol * M);
        assert!(o.warnings.is_empty());
        assert_eq!(
            s.effects.names(),
            vec!["normal-impulse", "friction", "stick"]
        );
    }
}

/// Stick off, the trace: eq 48 literally, S(p) = S(0) - k mu p with k = 2 (1 + 1/alpha) / m
/// = 7 / m, runs through zero at p_stick = 0.0809 N s and on to -0.64 m/s at P, signed
/// along the initial sliding direction (docs/formats.md#trace-csv); theta stays that
/// direction's angle, 0. p(t) = P sin^2(pi t / (2 tau)) is the half-sine's impulse. Every
/// method at its default settings, sampled and by steps; the worst |S - S(p(t))| over the
/// rows, measured (m/s): closed form 3.3e-16, dop853 3.0e-12, dopri5 1.4e-11, rk4 2.9e-14;
/// held to about ten times that.
#[test]
fn stick_off_trace_runs_the_slip_through_zero() {
    let (s0, p_total, tau) = (0.2, 2.0 * M * 1.0, 2.5e-4);
    let exact = |t: f64| {
        let h = (0.5 * std::f64::consts::PI * t / tau).sin();
        s0 - 7.0 / M * MU * p_total * h * h
    };
    for (method, tol) in [
        ("closed-form", 4e-15),
        ("dop853", 3e-11),
        ("dopri5", 1.5e-10),
        ("rk4", 3e-13),
    ] {
        for sampling in [Sampling::Steps, Sampling::Uniform(10)] {
            let s = cm_scene(method, "stick = false");
            let mut trace: Vec<TraceRow> = Vec::new();
            run_scene(&s, &s.solver, Some((&mut trace, sampling))).unwrap();
            let mut worst = 0.0_f64;
            for r in &trace {
                worst = worst.max((r.slip_speed - exact(r.t)).abs());
                assert!(
                    r.theta.unwrap().abs() <= 1e-12,
                    "{method}: theta {:?}",
                    r.theta
                );
            }
            assert!(
                worst <= tol,
                "{method} {sampling:?}: |S - S(p)| up to {worst:e}"
            );
            let last = trace.last().unwrap();
            assert!(
                (last.t / tau - 1.0).abs() <= 1e-12 && last.slip_speed < -0.6,
                "{method}: ends at {last:?}"
            );
        }
    }
}

/// Table off: the run ends at separation: no `table` in the JSON or the summary, and the
/// effect is not named. On: both balls' roll-out with the contract's keys.
#[test]
fn table_off_ends_at_separation_and_on_adds_the_roll_out() {
    let (va, wa) = cue(1.5, 30f64.to_radians(), 1.0);
    let off = lab_scene(va, wa, "0.06", 1.0, "");
    let so = run_scene(&off, &off.solver, None).unwrap();
    assert!(so.table.is_none());
    let json: serde_json::Value =
        serde_json::from_str(&Report::new(&off, &so).to_json().unwrap()).unwrap();
    assert!(json.get("table").is_none());
    assert!(!json["effects"]
        .as_array()
        .unwrap()
        .iter()
        .any(|e| e == "table"));
    assert!(!Report::new(&off, &so).summary().contains("table"));

    let on = lab_scene(va, wa, "0.06", 1.0, "[effects]\ntable = true");
    let so_on = run_scene(&on, &on.solver, None).unwrap();
    // The contact itself is the same whether or not the table follows.
    assert_eq!(so_on.outcome, so.outcome);
    let json: serde_json::Value =
        serde_json::from_str(&Report::new(&on, &so_on).to_json().unwrap()).unwrap();
    assert!(json["effects"]
        .as_array()
        .unwrap()
        .iter()
        .any(|e| e == "table"));
    for ball in ["a", "b"] {
        let b = &json["table"][ball];
        for key in [
            "hop_time",
            "hop_height",
            "slide_time",
            "slide_displacement",
            "roll_time",
            "bounces",
        ] {
            assert!(!b[key].is_null(), "table.{ball}.{key}");
        }
        for key in ["velocity", "spin", "normal_impulse", "tangential_impulse"] {
            assert!(!b["impact"][key].is_null(), "table.{ball}.impact.{key}");
        }
        for key in ["velocity", "spin"] {
            assert_eq!(b["rolling"][key].as_array().unwrap().len(), 3);
        }
    }
    let text = Report::new(&on, &so_on).summary();
    assert!(text.contains("table") && text.contains("rolling"), "{text}");
}

/// A `[table]` section with the effect off is almost certainly a mistake: warn.
#[test]
fn table_section_without_the_effect_warns() {
    let (va, wa) = cue(1.5, 30f64.to_radians(), 1.0);
    let s = lab_scene(va, wa, "0.06", 1.0, "[table]\nmu = 0.3");
    let so = run_scene(&s, &s.solver, None).unwrap();
    assert!(so.table.is_none());
    assert!(so.outcome.warnings.iter().any(|w| w.contains("[table]")));
}
