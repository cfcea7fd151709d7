//! The table phase against closed forms derived by hand and written down beside each test.
//!
//! Notation: lab frame, up n = +z, cloth at z = 0, m = 0.17 kg, r = 0.028575 m, solid ball
//! alpha = 2/5, slip of the contact point u = v_h - r (w x n).

use crate::scenes;

use billiard_contact::run_scene;
use billiard_contact::table_phase::{
    cloth_impact, roll_out, BallMotion, Table, TableParams, TableSettings,
};
use billiard_contact::Ball;
use billiard_contact::LabBall;
use nalgebra::Vector3;
use scenes::{cue, lab_scene, M, R};

/// Relative tolerance of closed-form arithmetic (a few dozen operations).
const EXACT: f64 = 1e-13;
/// Angles from the closed-form contact (degrees).
const ANGLE_EXACT_DEG: f64 = 1e-10;
/// Angles from the time-stepped contact at rtol 1e-10 (degrees).
const ANGLE_STEPPED_DEG: f64 = 1e-6;

fn ball() -> Ball {
    Ball::new(M, R, 0.4).unwrap()
}

fn table(mu: f64, e: f64) -> Table {
    Table {
        params: TableParams::default()
            .with_mu(mu)
            .and_then(|p| p.with_restitution(e))
            .unwrap(),
        up: Vector3::z(),
        height: 0.0,
    }
}

fn on_cloth(v: [f64; 3], w: [f64; 3]) -> LabBall {
    LabBall {
        position: Vector3::new(0.0, 0.0, R),
        velocity: Vector3::from(v),
        spin: Vector3::from(w),
    }
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()).max(1e-300)
}

/// Impact that slips: v = (1, 0, -0.5), w = 0, mu_t = 0.2, e_t = 0.
/// P_n = m 0.5; slip u = (1, 0, 0); the stick bound m |u| / (1 + 1/alpha) = m / 3.5 exceeds
/// mu_t P_n = 0.1 m, so J_t = 0.1 m: v' = (1 - 0.1, 0, 0),
/// w' = r J_t (z x x) / (alpha m r^2) = 0.1 / (0.4 r) y, slip after 1 - 0.1 * 3.5 = 0.65.
#[test]
fn impact_that_slips() {
    let b = ball();
    let t = table(0.2, 0.0);
    let imp = cloth_impact(
        &b,
        &t.params,
        &t.up,
        0.0,
        &Vector3::new(1.0, 0.0, -0.5),
        &Vector3::zeros(),
    );
    assert!(!imp.sticks);
    assert!(close(imp.normal_impulse, 0.5 * M, EXACT));
    assert!(close(imp.tangential_impulse, 0.1 * M, EXACT));
    assert!(close(imp.velocity.x, 0.9, EXACT));
    assert_eq!(imp.velocity.y, 0.0);
    assert_eq!(imp.velocity.z, 0.0);
    assert!(close(imp.spin.y, 0.1 / (0.4 * R), EXACT));
    let slip_after = imp.velocity.x - R * imp.spin.y; // u_x = v_x - r w_y (w x z = (w_y, -w_x, 0))
    assert!(close(slip_after, 0.65, EXACT));
}

/// Impact that sticks: v = (0.1, 0, -0.5), mu_t = 1: mu_t P_n = 0.5 m exceeds the bound
/// m 0.1 / 3.5, so J_t = m 0.1 / 3.5 and the ball leaves the impact rolling at
/// v' = 0.1 (1 - 1/3.5) = 5/7 0.1: the 5/7 rule, impulsively. Nothing is left to slide.
#[test]
fn impact_that_sticks_rolls_at_once() {
    let b = ball();
    let t = table(1.0, 0.0);
    let imp = cloth_impact(
        &b,
        &t.params,
        &t.up,
        0.0,
        &Vector3::new(0.1, 0.0, -0.5),
        &Vector3::zeros(),
    );
    assert!(imp.sticks);
    assert!(close(imp.tangential_impulse, M * 0.1 / 3.5, EXACT));
    assert!(close(imp.velocity.x, 5.0 / 7.0 * 0.1, EXACT));
    assert!(close(imp.spin.y, imp.velocity.x / R, EXACT));
    let r = roll_out(&b, &t, &on_cloth([0.1, 0.0, -0.5], [0.0; 3])).unwrap();
    assert_eq!(r.slide_time, 0.0);
    assert!(close(r.rolling.velocity.x, 5.0 / 7.0 * 0.1, EXACT));
}

/// Impact of a ball already rolling: v = (1, 0, -0.5), w = (0, 1/r, 0), so the contact
/// point's slip v_x - r w_y is 0 and no friction acts: J_t = 0, the spin is unchanged, and
/// with e_t = 0.5 the ball leaves with v' = (1, 0, 0.25), P_n = 1.5 m 0.5. (v_x is written
/// r (1/r), 1 to an ulp, so that the slip is 0 exactly.)
#[test]
fn impact_without_slip_is_purely_normal() {
    let b = ball();
    let t = table(0.2, 0.5);
    let vx = R * (1.0 / R);
    let imp = cloth_impact(
        &b,
        &t.params,
        &t.up,
        0.0,
        &Vector3::new(vx, 0.0, -0.5),
        &Vector3::new(0.0, 1.0 / R, 0.0),
    );
    assert!(imp.sticks);
    assert_eq!(imp.tangential_impulse, 0.0);
    assert!(close(imp.normal_impulse, 0.75 * M, EXACT));
    assert_eq!(imp.velocity.x, vx);
    assert_eq!(imp.velocity.y, 0.0);
    assert!(close(imp.velocity.z, 0.25, EXACT));
    assert_eq!(imp.spin, Vector3::new(0.0, 1.0 / R, 0.0));
}

/// A ball with no vertical velocity: hop_time = hop_height = 0 and an impact with zero
/// impulses at t = 0 (docs/model.md#the-table-phase, step 2).
#[test]
fn no_vertical_velocity_means_an_empty_impact() {
    let r = roll_out(
        &ball(),
        &table(0.2, 0.0),
        &on_cloth([1.0, 0.2, 0.0], [3.0, 0.0, 5.0]),
    )
    .unwrap();
    assert_eq!(r.hop_time, 0.0);
    assert_eq!(r.hop_height, 0.0);
    assert_eq!(r.impacts.len(), 1);
    assert_eq!(r.impacts[0].time, 0.0);
    assert_eq!(r.impacts[0].normal_impulse, 0.0);
    assert_eq!(r.impacts[0].tangential_impulse, 0.0);
    assert_eq!(r.bounces, 0);
}

/// A stun ball (w = 0) at v on the cloth: the slip is v, it falls at mu g (1 + 1/alpha)
/// = 7/2 mu g, so the ball rolls after 2 |v| / (7 mu g) at 5/7 v, having moved
/// |v| t - mu g t^2 / 2 along v (parabolic path, here straight), spinning n x v_roll / r.
#[test]
fn five_sevenths_rule_and_time_to_roll() {
    let (mu, g) = (0.2, 9.81);
    let v = Vector3::new(1.4, 0.3, 0.0);
    let s = v.norm();
    let r = roll_out(
        &ball(),
        &table(mu, 0.0),
        &on_cloth([v.x, v.y, 0.0], [0.0; 3]),
    )
    .unwrap();
    let t = 2.0 * s / (7.0 * mu * g);
    assert!(close(r.slide_time, t, EXACT));
    assert!((r.rolling.velocity - v * (5.0 / 7.0)).amax() <= EXACT * s);
    let along = s * t - 0.5 * mu * g * t * t;
    assert!((r.slide_displacement - v / s * along).amax() <= EXACT * along);
    let w = Vector3::z().cross(&r.rolling.velocity) / R;
    assert!((r.rolling.spin - w).amax() <= EXACT * w.norm());
}

/// Draw: v = (1, 0, 0) with back spin w = (0, -k / r, 0), k = 2. Slip u = v - r w x z =
/// (1 + k, 0, 0); time to roll 2 (1 + k) / (7 mu g); rolling velocity 5/7 v + 2/7 r w x z =
/// (5 - 2 k) / 7 = 1/7 m/s forward.
#[test]
fn draw_ball_time_to_roll_and_rolling_speed() {
    let (mu, g, k) = (0.2, 9.81, 2.0);
    let r = roll_out(
        &ball(),
        &table(mu, 0.0),
        &on_cloth([1.0, 0.0, 0.0], [0.0, -k / R, 0.0]),
    )
    .unwrap();
    assert!(close(r.slide_time, 2.0 * (1.0 + k) / (7.0 * mu * g), EXACT));
    assert!(close(r.rolling.velocity.x, (5.0 - 2.0 * k) / 7.0, EXACT));
    assert!(r.rolling.velocity.y.abs() <= EXACT);
}

/// Hop: v = (1, 0, 0.3) leaves the cloth for 2 v_z / g, rising v_z^2 / (2 g), lands at
/// x = v_x t_hop and hits the cloth with P_n = m v_z (e_t = 0). Energy (kinetic +
/// gravitational) is the same at the top of the hop as at the start.
#[test]
fn hop_time_height_and_landing() {
    let g = 9.81;
    let tab = table(0.2, 0.0);
    let b = ball();
    let r = roll_out(&b, &tab, &on_cloth([1.0, 0.0, 0.3], [0.0; 3])).unwrap();
    assert!(close(r.hop_time, 0.6 / g, EXACT));
    assert!(close(r.hop_height, 0.09 / (2.0 * g), EXACT));
    let imp = r.impacts[0];
    assert!(close(imp.time, 0.6 / g, EXACT));
    assert!(close(imp.normal_impulse, M * 0.3, EXACT));
    let (phase, top) = r.at(&tab.up, 0.3 / g, true);
    assert_eq!(phase, BallMotion::Flight);
    assert!(close(top.position.z - R, 0.09 / (2.0 * g), EXACT));
    let e = |s: &LabBall| {
        0.5 * M * s.velocity.norm_squared()
            + 0.5 * b.inertia() * s.spin.norm_squared()
            + M * g * (s.position.z - R)
    };
    assert!(close(e(&top), e(&r.start), EXACT));
    let (_, land) = r.at(&tab.up, imp.time, false);
    assert!(close(land.position.x, 0.6 / g, EXACT));
}

/// Bounces: e_t = 0.5 and v_z = -0.1 at t = 0: after impact k the ball goes up at
/// 0.1 * 0.5^k; it bounces while that is >= 1e-3 m/s, i.e. for k <= ln(1e-2)/ln(0.5) = 6.6:
/// 6 bounces, settling at t = sum_{k=1..6} 2 * 0.1 * 0.5^k / g.
#[test]
fn bounces_until_vertical_speed_below_a_millimetre_per_second() {
    let g = 9.81;
    let r = roll_out(
        &ball(),
        &table(0.2, 0.5),
        &on_cloth([0.5, 0.0, -0.1], [0.0; 3]),
    )
    .unwrap();
    assert_eq!(r.bounces, 6);
    assert_eq!(r.impacts.len(), 7);
    let settle: f64 = (1..=6).map(|k| 2.0 * 0.1 * 0.5f64.powi(k) / g).sum();
    assert!(close(r.settle_time, settle, EXACT));
    for (k, imp) in r.impacts.iter().enumerate() {
        // Impact k + 1 meets the cloth at 0.1 * 0.5^k and leaves at 0.1 * 0.5^(k+1).
        assert!(close(
            imp.normal_impulse,
            1.5 * M * 0.1 * 0.5f64.powi(k as i32),
            1e-12
        ));
    }
}

/// The paper's special case on the table, frictionless elastic half-ball hit (30 degree
/// cut, mu = 0, e = 1): A keeps its rolling spin w = (-v, u, 0)/r and leaves with the
/// tangential part of its velocity, (0, v) in the frame of the line of centres
/// (u = s cos 30, v = s sin 30). Rolling velocity 5/7 (0, v) + 2/7 r w x z = (2/7 u, v):
/// the deflection from the original line (u, v) is atan2(v, 2u/7) - 30 deg, and
/// tan(atan2(1/2, 2 sqrt3/14) - 30 deg) = 5 sqrt3 / 13: 33.67 degrees (the 30-degree rule).
#[test]
fn half_ball_hit_rolling_cue_ball_deflects_33_7_degrees() {
    let expected = (5.0 * 3f64.sqrt() / 13.0).atan().to_degrees();
    assert!((expected - 33.67).abs() < 0.01);
    let (va, wa) = cue(1.5, 30f64.to_radians(), 1.0);
    for (method, tol) in [
        ("closed-form", ANGLE_EXACT_DEG),
        ("dop853", ANGLE_STEPPED_DEG),
    ] {
        // The cloth's friction and restitution do not change the rolling velocity (the
        // angular momentum about the contact point is conserved): try several.
        for cloth in ["mu = 0.2", "mu = 0.5\nrestitution = 0.5"] {
            let s = lab_scene(
                va,
                wa,
                "0.0",
                1.0,
                &format!(
                    "[solver]\nmethod = \"{method}\"\n[effects]\ntable = true\n[table]\n{cloth}"
                ),
            );
            let so = run_scene(&s, &s.solver, None).unwrap();
            let t = so.table.unwrap();
            let d = t.deflection_deg(0, &t.a).unwrap();
            // Counter-clockwise about up (+z) from the incoming (u, v), v > 0: positive.
            assert!(
                (d - expected).abs() <= tol,
                "{method} {cloth}: {d} vs {expected}"
            );
        }
    }
}

/// The same with ball-ball friction mu = 0.06 (sliding throughout: p_stick = m s / (7 mu) >
/// P = m u). Eqs 69 and 72: A leaves with v_A = (0, v - mu u v / s, mu u^2 / s) and
/// w_A = (-v/r, u/r - mu u^2/(alpha r s), -mu u v/(alpha r s)). Rolling velocity
/// 5/7 v_A,h + 2/7 r w_A x z, with r w x z = (r w_y, -r w_x):
///   x: 2/7 (u - mu u^2 / (alpha s)) = 2/7 u - 5/7 mu u^2 / s        (alpha = 2/5)
///   y: 5/7 (v - mu u v / s) + 2/7 v = v - 5/7 mu u v / s
/// The hop and landing (A moves up at mu u^2 / s) do not change it.
#[test]
fn half_ball_hit_friction_corrected_deflection() {
    let (s, mu) = (1.5, 0.06);
    let cut = 30f64.to_radians();
    let (u, v) = (s * cut.cos(), s * cut.sin());
    let fx = 2.0 / 7.0 * u - 5.0 / 7.0 * mu * u * u / s;
    let fy = v - 5.0 / 7.0 * mu * u * v / s;
    let expected = fy.atan2(fx).to_degrees() - 30.0;
    // About 36 degrees: friction adds some 2.2 degrees to the frictionless 33.7.
    assert!((expected - 35.9).abs() < 0.1, "{expected}");
    let (va, wa) = cue(s, cut, 1.0);
    for (method, tol) in [
        ("closed-form", ANGLE_EXACT_DEG),
        ("dop853", ANGLE_STEPPED_DEG),
    ] {
        let sc = lab_scene(
            va,
            wa,
            "0.06",
            1.0,
            &format!("[solver]\nmethod = \"{method}\"\n[effects]\ntable = true"),
        );
        let so = run_scene(&sc, &sc.solver, None).unwrap();
        let t = so.table.unwrap();
        assert!(t.a.hop_time > 0.0, "A hops (eq 69: upward mu u^2 / s)");
        assert!(close(t.a.hop_time, 2.0 * mu * u * u / s / 9.81, 1e-8));
        let d = t.deflection_deg(0, &t.a).unwrap();
        // Counter-clockwise about up (+z): positive.
        assert!((d - expected).abs() <= tol, "{method}: {d} vs {expected}");
    }
}

/// Stun shot (no spin), frictionless elastic contact at cut phi: A leaves along the tangent
/// line with s sin(phi) and no spin, so it rolls along the tangent line (90 degrees from the
/// line of centres) at 5/7 s sin(phi).
#[test]
fn stun_shot_cue_ball_leaves_along_the_tangent_line() {
    for cut_deg in [15.0f64, 30.0, 45.0, 60.0] {
        let s = 2.0;
        let (va, wa) = cue(s, cut_deg.to_radians(), 0.0);
        let sc = lab_scene(
            va,
            wa,
            "0.0",
            1.0,
            "[solver]\nmethod = \"closed-form\"\n[effects]\ntable = true",
        );
        let t = run_scene(&sc, &sc.solver, None).unwrap().table.unwrap();
        let dir = t.direction_deg(&t.a).unwrap();
        assert!((dir - 90.0).abs() <= ANGLE_EXACT_DEG, "{cut_deg}: {dir}");
        let speed = t.a.rolling.velocity.norm();
        assert!(close(
            speed,
            5.0 / 7.0 * s * cut_deg.to_radians().sin(),
            1e-12
        ));
    }
}

/// A rolling cue ball's path curves from the tangent line toward the 30-degree-rule region:
/// for 3/4, 1/2 and 1/4 ball hits (sin(phi) = 1/4, 1/2, 3/4, frictionless elastic contact)
/// its direction of travel starts at 90 - phi degrees from the original line (the tangent
/// line) and turns monotonically to atan2(sin phi, 2/7 cos phi) - phi: 27.6, 33.7 and 27.3
/// degrees, all within [27, 34] (the 30-degree rule). The turn is a parabola: the
/// acceleration while sliding is constant.
#[test]
fn rolling_cue_ball_path_curves_toward_the_30_degree_rule() {
    for sin_phi in [0.25f64, 0.5, 0.75] {
        let phi = sin_phi.asin();
        let final_deg = sin_phi.atan2(2.0 / 7.0 * phi.cos()).to_degrees() - phi.to_degrees();
        assert!((27.0..=34.0).contains(&final_deg), "{final_deg}");
        let (va, wa) = cue(1.5, phi, 1.0);
        let sc = lab_scene(
            va,
            wa,
            "0.0",
            1.0,
            "[solver]\nmethod = \"closed-form\"\n[effects]\ntable = true",
        );
        let t = run_scene(&sc, &sc.solver, None).unwrap().table.unwrap();
        let up = Vector3::z();
        let original = Vector3::from(va);
        let n = 200;
        let mut last = f64::INFINITY;
        for i in 0..=n {
            let time = t.a.roll_time * f64::from(i) / f64::from(n);
            let (phase, st) = t.a.at(&up, time, true);
            if i < n {
                assert_eq!(phase, BallMotion::Sliding);
            }
            let dev = t.angle_deg(&original, &st.velocity).unwrap().abs();
            if i == 0 {
                assert!((dev - (90.0 - phi.to_degrees())).abs() < 1e-9, "{dev}");
            }
            assert!(dev <= last + 1e-12, "direction turns monotonically");
            last = dev;
        }
        assert!((last - final_deg).abs() < 1e-9, "{last} vs {final_deg}");
        // Parabola: equal second differences of the position.
        let p = |time: f64| t.a.at(&up, time, true).1.position;
        let h = t.a.roll_time / 4.0;
        let d1 = p(2.0 * h) - 2.0 * p(h) + p(0.0);
        let d2 = p(4.0 * h) - 2.0 * p(3.0 * h) + p(2.0 * h);
        assert!((d1 - d2).amax() <= 1e-12 * d1.norm().max(1e-12));
    }
}

/// Over a sweep of shots, cloths and both balls: the energy (kinetic + gravitational,
/// evaluated here from the path, not by the library's check) never increases, and each ball's
/// horizontal momentum changes only by the cloth's friction, which acts against the slip at
/// landing (its direction is kept by impacts and sliding alike, with e_t = 0):
/// m (v_roll - v_sep)_h = -(J_t + mu_t m g t_slide) u/|u|.
#[test]
fn energy_never_increases_and_momentum_changes_only_by_the_cloth() {
    let g = 9.81;
    let b = ball();
    for (cut, k, mu, side) in [
        (10.0f64, 3.0, "0.06", 0.0),
        (30.0, 1.0, "0.2", 20.0),
        (45.0, -2.0, "0.06", -30.0),
        (5.0, -1.0, "0.3", 0.0),
        (
            60.0,
            0.0,
            "{ model = \"speed-dependent\", a = 9.951e-3, b = 0.108, c = 1.088 }",
            10.0,
        ),
    ] {
        let (va, mut wa) = cue(3.0, cut.to_radians(), k);
        wa[2] = side;
        for cloth in [
            "mu = 0.2",
            "mu = 0.4\nrestitution = 0.6",
            "mu = 0.2\nrolling_resistance = 0.01\nspin_decay = 0.044",
        ] {
            let sc = lab_scene(
                va,
                wa,
                mu,
                0.93,
                &format!("[effects]\ntable = true\n[table]\n{cloth}"),
            );
            let so = run_scene(&sc, &sc.solver, None).unwrap();
            let t = so.table.unwrap();
            assert!(
                t.check.energy_increase <= 1e-13,
                "{cut} {cloth}: {:?}",
                t.check
            );
            assert!(
                t.check.momentum_error <= 1e-13,
                "{cut} {cloth}: {:?}",
                t.check
            );
            let rows = billiard_contact::table_phase::ball_path_rows(&t, 400);
            let e = |s: &LabBall| {
                0.5 * M * s.velocity.norm_squared()
                    + 0.5 * b.inertia() * s.spin.norm_squared()
                    + M * g * (s.position.z - R)
            };
            let scale = 0.5 * M * 9.0 * 10.0;
            for pair in rows.windows(2) {
                for (x, y) in [(pair[0].a.1, pair[1].a.1), (pair[0].b.1, pair[1].b.1)] {
                    assert!(
                        e(&y) <= e(&x) + 1e-13 * scale,
                        "{cut} {cloth} at {}",
                        pair[1].t
                    );
                }
            }
            if !cloth.contains("restitution") && !cloth.contains("rolling") {
                for r in [&t.a, &t.b] {
                    let u = r.impacts[0].slip_before;
                    if u.norm() == 0.0 {
                        continue;
                    }
                    let applied = -u.normalize()
                        * (r.impacts[0].tangential_impulse + 0.2 * M * g * r.slide_time);
                    let mut dp = M * (r.rolling.velocity - r.start.velocity);
                    dp.z = 0.0;
                    assert!(
                        (dp - applied).amax() <= 1e-13 * M * 3.0,
                        "{dp} vs {applied}"
                    );
                }
            }
        }
    }
}

/// The table needs a level line of centres and balls on the cloth; clear errors otherwise.
#[test]
fn table_requires_a_lab_scene_with_both_balls_on_the_cloth() {
    use billiard_contact::Scene;
    use std::path::Path;
    let base = lab_scene(
        [1.0, 0.0, 0.0],
        [0.0; 3],
        "0.06",
        1.0,
        "[effects]\ntable = true",
    );
    assert!(base.cloth().unwrap().is_some());
    let cm = r#"
[balls]
mass = 0.17
radius = 0.028575
[contact]
mu = 0.06
[contact.profile]
shape = "half-sine"
duration = 2.5e-4
[incoming.cm]
u = [1.0, 0.0, 0.0]
[effects]
table = true
"#;
    let e = Scene::parse(cm, Path::new("."), None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("effects.table") && e.contains("[incoming.lab]"),
        "{e}"
    );
    // B above A: the line of centres is tilted.
    let dz = ((2.0 * R) * (2.0 * R) - 0.04 * 0.04).sqrt();
    let tilted = cm.replace(
        "[incoming.cm]\nu = [1.0, 0.0, 0.0]",
        &format!(
            "[incoming.lab]\na = {{ position = [0.0, 0.0, {R:?}], velocity = [1.0, 0.0, 0.5] }}\n\
             b = {{ position = [0.04, 0.0, {:?}], velocity = [0.0, 0.0, 0.0] }}",
            R + dz
        ),
    );
    let e = Scene::parse(&tilted, Path::new("."), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("horizontal line of centres"), "{e}");
    let text = cm.replace(
        "[incoming.cm]\nu = [1.0, 0.0, 0.0]",
        "[incoming.lab]\na = { position = [-0.028575, 0.0, 0.1], velocity = [1.0, 0.0, 0.0] }\nb = { position = [0.028575, 0.0, 0.1], velocity = [0.0, 0.0, 0.0] }",
    ) + "[table]\nheight = 0.0\n";
    let e = Scene::parse(&text, Path::new("."), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("above the cloth"), "{e}");
    // The same centres 0.1 m up on a cloth at height 0.1 - R: each centre is R above it.
    let raised = text.replace("height = 0.0", &format!("height = {:?}", 0.1 - R));
    Scene::parse(&raised, Path::new("."), None).expect("centres R above a raised cloth");
    let bad = cm.replace("table = true", "table = true\n[table]\nrestitution = 1.0");
    let e = Scene::parse(&bad, Path::new("."), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("table.restitution"), "{e}");
}

/// Rolling resistance: a ball rolling at v decelerates at mu_r g and stays rolling, so it
/// rests after v / (mu_r g), having rolled v^2 / (2 mu_r g). Spin decay: |w.n| falls at
/// mu_sp g / (alpha r) and reaches 0 after |w.n| alpha r / (mu_sp g), while the horizontal
/// motion is untouched (the torque is about n).
#[test]
fn rolling_resistance_and_spin_decay() {
    let (g, mu_r, mu_sp) = (9.81, 0.01, 0.044);
    let tab = Table {
        params: TableParams::new(TableSettings {
            g,
            rolling_resistance: mu_r,
            spin_decay: mu_sp,
            ..TableSettings::default()
        })
        .unwrap(),
        up: Vector3::z(),
        height: 0.0,
    };
    let v = 1.2;
    let wz = 20.0;
    // Rolling along +x: w = z x v / r = (0, v / r, 0), plus side spin wz.
    let r = roll_out(&ball(), &tab, &on_cloth([v, 0.0, 0.0], [0.0, v / R, wz])).unwrap();
    assert_eq!(r.slide_time, 0.0);
    let (t_rest, p_rest) = r.rest.unwrap();
    assert!(close(t_rest, v / (mu_r * g), EXACT));
    assert!(close(p_rest.x, v * v / (2.0 * mu_r * g), EXACT));
    let t_spin = wz * 0.4 * R / (mu_sp * g);
    assert!(t_spin < t_rest);
    let (_, half) = r.at(&tab.up, 0.5 * t_spin, true);
    assert!(close(half.spin.z, 0.5 * wz, 1e-12));
    assert!(
        close(half.spin.y, half.velocity.x / R, 1e-12),
        "still rolling"
    );
    let (phase, late) = r.at(&tab.up, 0.5 * (t_spin + t_rest), true);
    assert_eq!(phase, BallMotion::Rolling);
    assert_eq!(late.spin.z, 0.0);
}

/// The table does not care which lab axis is up: the half-ball hit of the 33.7 degree test
/// rotated by -90 degrees about x (up = +y; (x, y, z) -> (x, z, -y) for positions, velocities
/// and spins alike) deflects the same.
#[test]
fn any_up_direction_gives_the_same_roll_out() {
    use billiard_contact::Scene;
    use std::path::Path;
    let (va, wa) = cue(1.5, 30f64.to_radians(), 1.0);
    let rot = |v: [f64; 3]| [v[0], v[2], -v[1]];
    let (p_a, p_b) = (rot([-R, 0.0, R]), rot([R, 0.0, R]));
    let (va, wa) = (rot(va), rot(wa));
    let text = format!(
        r#"
[balls]
mass = {M}
radius = {R}
[contact]
mu = 0.0
[contact.profile]
shape = "half-sine"
duration = 2.5e-4
[incoming.lab]
a = {{ position = {p_a:?}, velocity = {va:?}, spin = {wa:?} }}
b = {{ position = {p_b:?}, velocity = [0.0, 0.0, 0.0] }}
up = [0.0, 1.0, 0.0]
[solver]
method = "closed-form"
[effects]
table = true
"#
    );
    let s = Scene::parse(&text, Path::new("."), None).unwrap();
    let t = run_scene(&s, &s.solver, None).unwrap().table.unwrap();
    assert!((t.table.height - 0.0).abs() < 1e-15);
    let d = t.deflection_deg(0, &t.a).unwrap();
    let expected = (5.0 * 3f64.sqrt() / 13.0).atan().to_degrees();
    // A proper rotation keeps the sense about up: positive as with up = +z.
    assert!((d - expected).abs() <= ANGLE_EXACT_DEG, "{d}");
    assert!(t.a.rolling.velocity.y.abs() <= 1e-15, "rolls on the cloth");
}

/// The rolling velocity a ball reaches on the cloth: friction at the contact point exerts
/// no torque about that point, so the angular momentum about it, m v_h + I w x n / r per
/// unit r (I = alpha m r^2), is kept while the ball slides, and rolling (w x n = v_h / r)
/// ends at v_h (1 + alpha) = v_h(0) + alpha r w(0) x n. A solid ball at 1.4 m/s along x
/// (and 0.3 m/s up: only the horizontal part counts) with 20 rad/s of follow spin about y
/// (w x n = (20, 0, 0) rad/s): (1.4 + 0.4 r 20) / 1.4 = 1.16328... m/s along x; with draw
/// (-20 rad/s), (1.4 - 0.4 r 20) / 1.4. Side spin about z adds nothing (z x z = 0).
#[test]
fn rolling_velocity_keeps_the_angular_momentum_about_the_contact_point() {
    use billiard_contact::table_phase::rolling_velocity;
    let v = Vector3::new(1.4, 0.0, 0.3);
    for (wy, wz) in [(20.0, 0.0), (-20.0, 0.0), (20.0, 35.0)] {
        let got = rolling_velocity(&ball(), &Vector3::z(), &v, &Vector3::new(0.0, wy, wz));
        let want = (1.4 + 0.4 * R * wy) / 1.4;
        assert!(
            (got - Vector3::new(want, 0.0, 0.0)).amax() <= EXACT * want,
            "w = (0, {wy}, {wz}): {got:?} vs {want}"
        );
    }
}
