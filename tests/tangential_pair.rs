//! The compliant impact of two spheres (docs/tangential.md#two-spheres): Hertz's normal force
//! and Mindlin's tangential spring between balls of their own mass, radius, alpha and
//! material. The references, written here: Hertz's impact of two spheres (reduced mass,
//! effective radius and modulus), the rigid closed form with the stick rule (eqs 24-35 of
//! the paper with P = (1 + e) m* 2U(0), docs/unequal-balls.md) that a stiffer and stiffer
//! spring must approach, conservation of momentum, the energy, and two exact equivalences
//! with the sphere-plane kernel.

use crate::common::compliant::{hertz, sphere, tight};
use billiard_contact::nalgebra::Vector3;
use billiard_contact::*;

fn body(ball: Ball, e: f64, nu: f64, v: Vector3<f64>, w: Vector3<f64>) -> CompliantSphere {
    CompliantSphere {
        ball,
        material: Material::new(e, nu).unwrap(),
        velocity: v,
        spin: w,
    }
}

/// Two unequal balls: a resin ball (0.17 kg, 28.575 mm) and a heavier, larger steel-like one.
fn unequal(
    va: Vector3<f64>,
    wa: Vector3<f64>,
    vb: Vector3<f64>,
    wb: Vector3<f64>,
) -> [CompliantSphere; 2] {
    [
        body(Ball::new(0.17, 0.028575, 0.4).unwrap(), 5.4e9, 0.34, va, wa),
        body(Ball::new(0.28, 0.0305, 0.35).unwrap(), 2.0e11, 0.29, vb, wb),
    ]
}

fn momentum(s: &[CompliantSphere; 2]) -> Vector3<f64> {
    s[0].ball.mass() * s[0].velocity + s[1].ball.mass() * s[1].velocity
}

/// Hertz's impact of two spheres (Johnson, Contact Mechanics, 11.1), from the balls and
/// materials: 1/E* = sum (1 - nu^2)/E, 1/R* = 1/r_a + 1/r_b, m* = m_a m_b / (m_a + m_b);
/// delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5), F_max = (4/3) E* sqrt(R*)
/// delta_max^1.5, contact time 2.868265699 (m*^2 / (E*^2 R* v))^(1/5).
fn hertz_pair(a: &CompliantSphere, b: &CompliantSphere, v: f64) -> (f64, f64, f64) {
    let c = |s: &CompliantSphere| {
        let nu = s.material.poisson_ratio();
        (1.0 - nu * nu) / s.material.youngs_modulus()
    };
    let es = 1.0 / (c(a) + c(b));
    let r = 1.0 / (1.0 / a.ball.radius() + 1.0 / b.ball.radius());
    let m = a.ball.mass() * b.ball.mass() / (a.ball.mass() + b.ball.mass());
    hertz(m, r, es, v)
}

/// Without friction the tangential spring does nothing: the normal impact is Hertz's of the
/// pair (compression, peak force and contact time to 1e-6), elastic (the relative normal
/// velocity reverses to 1e-8, e = 1), the tangential velocities and the spins are kept, and
/// the shear stiffness factor changes nothing (bit for bit).
#[test]
fn tangential_pair_frictionless_is_hertz_elastic() {
    let n = Vector3::new(1.0, 0.2, -0.1).normalize();
    let [a, b] = unequal(
        Vector3::new(1.2, 0.4, 0.3),
        Vector3::new(5.0, -20.0, 30.0),
        Vector3::new(-0.3, 0.1, 0.0),
        Vector3::new(-8.0, 0.0, 12.0),
    );
    let g = a.velocity - b.velocity;
    let v = g.dot(&n);
    let out = resolve_sphere_sphere_compliant(&a, &b, n, 0.0, 1.0, &tight()).unwrap();
    let (d, f, t) = hertz_pair(&a, &b, v);
    let rel = |x: f64, y: f64| ((x - y) / y).abs();
    let o = &out.ball_a;
    assert!(
        rel(o.max_compression, d) < 1e-6,
        "{} {d}",
        o.max_compression
    );
    assert!(
        rel(o.max_normal_force, f) < 1e-6,
        "{} {f}",
        o.max_normal_force
    );
    assert!(rel(o.contact_time, t) < 1e-6, "{} {t}", o.contact_time);
    let g_out = o.velocity - out.velocity_b;
    assert!(rel(-g_out.dot(&n), v) < 1e-8, "{}", g_out.dot(&n));
    let tang = |x: Vector3<f64>| x - x.dot(&n) * n;
    assert!((tang(g_out) - tang(g)).norm() < 1e-14 * g.norm());
    assert_eq!((o.spin, out.spin_b), (a.spin, b.spin));
    let stiff = resolve_sphere_sphere_compliant(&a, &b, n, 0.0, 1e4, &tight()).unwrap();
    // Bit for bit (the normalised angles are NaN without friction, so not compared).
    let key = |o: &CompliantPairOutcome| {
        (
            o.ball_a.velocity,
            o.ball_a.spin,
            o.velocity_b,
            o.spin_b,
            o.ball_a.contact_time,
            o.ball_a.trace.clone(),
        )
    };
    assert!(
        key(&stiff) == key(&out),
        "the shear factor changed a frictionless run"
    );
}

/// The rigid closed form of the same collision (docs/unequal-balls.md): n = +x from A to B,
/// the centre-of-mass state u = (v_A - v_B) / 2 with v_A = 2 m_B / M u, v_B = -2 m_A / M u,
/// e = 1, the stick rule. Returns the lab velocities given to the compliant solver and the
/// rigid outgoing state.
fn rigid(a: &Ball, b: &Ball, mu: f64, s: CmState) -> ([Vector3<f64>; 2], CmState) {
    let pair = BallPair::new(*a, *b);
    let contact = Contact {
        friction: Friction::constant(mu).unwrap(),
        impulse: ImpulseRule::restitution(1.0).unwrap(),
    };
    let c = Collision::new(pair, contact, Effects::default(), s).unwrap();
    let out = ClosedForm::new(&c).result;
    let total = a.mass() + b.mass();
    let va = 2.0 * b.mass() / total * s.u_cm;
    let vb = -2.0 * a.mass() / total * s.u_cm;
    ([va, vb], out.out)
}

/// The distance of a compliant outcome from the rigid one, over the speed scale: the
/// centre-of-mass velocity u and both spins times their radii.
fn distance(a: &Ball, b: &Ball, out: &CompliantPairOutcome, rigid: &CmState, scale: f64) -> f64 {
    let u = (out.ball_a.velocity - out.velocity_b) / 2.0;
    let du = (u - rigid.u_cm).norm();
    let dwa = a.radius() * (out.ball_a.spin - rigid.omega_a).norm();
    let dwb = b.radius() * (out.spin_b - rigid.omega_b).norm();
    du.max(dwa).max(dwb) / scale
}

/// As the shear stiffness grows the compliant pair approaches the rigid stick rule. Two
/// unequal resin balls (0.17 and 0.20 kg, alpha 0.4 and 0.38) meeting at U(0) = 1 m/s with
/// slip that stops a third of the way into the rigid impulse (mu = 0.2): the factor on k_t
/// runs 1, 10, ..., 1e4 and the distance from the closed form (u and r Omega of both balls,
/// over |U(0)|) falls at least as fast as factor^(-1/2), from above 1e-2 at Mindlin's
/// stiffness; linear momentum is kept to 1e-12 and the energy never grows in every run. The
/// stored tangential energy at a stiffness k_t is of order (mu F_n)^2 / k_t, so the
/// amplitude of the velocity it leaves goes as k_t^(-1/2).
#[test]
fn tangential_pair_converges_to_the_rigid_stick_rule() {
    let a = Ball::new(0.17, 0.028575, 0.4).unwrap();
    let b = Ball::new(0.20, 0.0300, 0.38).unwrap();
    let resin = (5.4e9, 0.34);
    let mu = 0.2;
    let s = CmState::new(
        Vector3::new(1.0, 0.3, -0.1),
        Vector3::new(0.0, 0.0, 10.0),
        Vector3::new(3.0, -4.0, 0.0),
    );
    let ([va, vb], rigid_out) = rigid(&a, &b, mu, s);
    let rigid_sticks = {
        let pair = BallPair::new(a, b);
        let contact = Contact {
            friction: Friction::constant(mu).unwrap(),
            impulse: ImpulseRule::restitution(1.0).unwrap(),
        };
        ClosedForm::new(&Collision::new(pair, contact, Effects::default(), s).unwrap())
            .result
            .sticks
    };
    assert!(rigid_sticks, "the rigid reference must stick");
    let pa = body(a, resin.0, resin.1, va, s.omega_a);
    let pb = body(b, resin.0, resin.1, vb, s.omega_b);
    let p_in = momentum(&[pa, pb]);
    let mut rows = Vec::new();
    for factor in [1.0, 10.0, 100.0, 1e3, 1e4] {
        let out =
            resolve_sphere_sphere_compliant(&pa, &pb, Vector3::x(), mu, factor, &tight()).unwrap();
        let d = distance(&a, &b, &out, &rigid_out, s.u_cm.x);
        let p_out = a.mass() * out.ball_a.velocity + b.mass() * out.velocity_b;
        let scale = a.mass() * va.norm() + b.mass() * vb.norm();
        assert!(
            (p_out - p_in).norm() < 1e-12 * scale,
            "{factor}: {:e}",
            (p_out - p_in).norm()
        );
        let o = &out.ball_a;
        assert!(o.kinetic_energy_out <= o.kinetic_energy_in * (1.0 + 1e-9));
        println!("factor {factor:8.0e}: distance {d:.3e}, steps {}", o.steps);
        rows.push((factor, d));
    }
    assert!(rows[0].1 > 1e-2, "{rows:?}");
    for w in rows.windows(2) {
        let rate = (w[0].1 / w[1].1).log10() / (w[1].0 / w[0].0).log10();
        println!("rate {:.3} between {:.0e} and {:.0e}", rate, w[0].0, w[1].0);
        assert!(rate > 0.45, "{rows:?}");
    }
}

/// Two identical balls (m, R, alpha, E, nu) are exactly a sphere on a rigid plane: the
/// relative motion g = v_A - v_B has the reduced mass m/2, the effective radius R/2 and the
/// effective moduli E* = E / (2 (1 - nu^2)), G* = G / (2 (2 - nu)), which are those of a
/// ball of mass m/2, radius R/2, the same alpha and modulus E/2 (same nu) on a rigid plane;
/// the slip's spin term R (w_A + w_B) moves as (R/2) w' of that ball with w' = 2 (w_A +
/// w_B) (its rate per force, R/2 over alpha (m/2) (R/2)^2, is four times R/I). So the
/// pair's outgoing relative velocity and 2 (w_A + w_B) are the plane run's velocity and
/// spin, to the stepping's tolerance (1e-8 of the speed), at incidences where the spring
/// sticks and slides in turn (Chung and Ooi's aluminium alloy, R = 0.1 m, mu = 0.4).
#[test]
fn tangential_pair_of_identical_balls_is_the_plane_equivalent() {
    let ball = sphere(2700.0, 0.1);
    let (e, nu, mu) = (7.0e10, 0.33, 0.4);
    let half = Ball::new(ball.mass() / 2.0, 0.05, ALPHA_SOLID).unwrap();
    let n = Vector3::x();
    for (deg, wa, wb) in [
        (10.0, Vector3::zeros(), Vector3::zeros()),
        (
            25.0,
            Vector3::new(0.0, 0.0, 3.0),
            Vector3::new(0.0, 1.0, 3.0),
        ),
        (45.0, Vector3::new(2.0, -5.0, 0.0), Vector3::zeros()),
    ] {
        let t = f64::to_radians(deg);
        let g = 0.4 * Vector3::new(t.cos(), t.sin(), 0.0);
        let a = body(ball, e, nu, g / 2.0, wa);
        let b = body(ball, e, nu, -g / 2.0, wb);
        let pair = resolve_sphere_sphere_compliant(&a, &b, n, mu, 1.0, &tight()).unwrap();
        let plane = resolve_sphere_plane_compliant(
            &half,
            Material::new(e / 2.0, nu).unwrap(),
            None,
            mu,
            g,
            2.0 * (wa + wb),
            -n,
            &tight(),
        )
        .unwrap();
        let g_out = pair.ball_a.velocity - pair.velocity_b;
        let w_out = 2.0 * (pair.ball_a.spin + pair.spin_b);
        assert!((g_out - plane.velocity).norm() < 1e-8 * g.norm(), "{deg}");
        assert!(
            (w_out - plane.spin).norm() * 0.05 < 1e-8 * g.norm(),
            "{deg}"
        );
        let dpsi = pair.ball_a.normalised_rebound - plane.normalised_rebound;
        assert!(dpsi.abs() < 1e-6, "{deg}: {dpsi:e}");
    }
}

/// The energy is never created and the momentum is kept (to 1e-12), over unequal balls of
/// two materials with spins of every sense at several incidences and frictions.
#[test]
fn tangential_pair_energy_never_grows() {
    for mu in [0.05, 0.3, 1.0] {
        for deg in [5.0f64, 30.0, 60.0, 80.0] {
            let t = deg.to_radians();
            let [a, b] = unequal(
                Vector3::new(t.cos(), t.sin(), 0.2),
                Vector3::new(0.0, 40.0, -25.0),
                Vector3::zeros(),
                Vector3::new(-10.0, 0.0, 15.0),
            );
            let n = Vector3::x();
            let out = resolve_sphere_sphere_compliant(&a, &b, n, mu, 1.0, &tight()).unwrap();
            let o = &out.ball_a;
            assert!(
                o.kinetic_energy_out <= o.kinetic_energy_in * (1.0 + 1e-9),
                "{mu} {deg}"
            );
            let p_out = a.ball.mass() * o.velocity + b.ball.mass() * out.velocity_b;
            let p_in = momentum(&[a, b]);
            assert!((p_out - p_in).norm() < 1e-12 * a.ball.mass() * a.velocity.norm());
        }
    }
}

/// Bad inputs are refused with one line naming the field.
#[test]
fn tangential_pair_refuses_bad_inputs() {
    let v = Vector3::new(1.0, 0.0, 0.0);
    let [a, b] = unequal(v, Vector3::zeros(), Vector3::zeros(), Vector3::zeros());
    let s = SolverSettings::default();
    let field = |r: Result<CompliantPairOutcome, Error>| match r {
        Err(Error::InvalidParameter { field, .. }) => field,
        other => panic!("{:?}", other.map(|o| o.velocity_b)),
    };
    let x = Vector3::x();
    assert_eq!(
        field(resolve_sphere_sphere_compliant(&a, &b, x, -0.1, 1.0, &s)),
        "friction.mu"
    );
    assert_eq!(
        field(resolve_sphere_sphere_compliant(
            &a,
            &b,
            Vector3::zeros(),
            0.1,
            1.0,
            &s
        )),
        "contact.normal"
    );
    assert_eq!(
        field(resolve_sphere_sphere_compliant(&a, &b, x, 0.1, 0.0, &s)),
        "contact.shear_stiffness_factor"
    );
    assert_eq!(
        field(resolve_sphere_sphere_compliant(&a, &b, -x, 0.1, 1.0, &s)),
        "incoming.velocity_a"
    );
    let mut nan = b;
    nan.spin.y = f64::NAN;
    assert_eq!(
        field(resolve_sphere_sphere_compliant(&a, &nan, x, 0.1, 1.0, &s)),
        "incoming.spin_b"
    );
    // A kinetic energy past a double's range: ball B of 1e282 kg spinning at 1e34 rad/s
    // (I w^2 / 2 ~ 1e345 J).
    let mut heavy = b;
    heavy.ball = Ball::new(1e282, b.ball.radius(), 0.4).unwrap();
    heavy.spin = Vector3::new(1e34, 0.0, 0.0);
    assert_eq!(
        field(resolve_sphere_sphere_compliant(&a, &heavy, x, 0.1, 1.0, &s)),
        "incoming.spin_b"
    );
    // Either ball's alpha below the compliant contact's 1e-4 (docs/tangential.md).
    let light = |mut s: CompliantSphere| {
        s.ball = Ball::new(s.ball.mass(), s.ball.radius(), 1e-5).unwrap();
        s
    };
    assert_eq!(
        field(resolve_sphere_sphere_compliant(
            &light(a),
            &b,
            x,
            0.1,
            1.0,
            &s
        )),
        "balls.a.alpha"
    );
    assert_eq!(
        field(resolve_sphere_sphere_compliant(
            &a,
            &light(b),
            x,
            0.1,
            1.0,
            &s
        )),
        "balls.b.alpha"
    );
}

/// A rolling cue ball's cut shot (docs/throw.md#tangential-compliance): the slip holds the
/// whole cue-ball speed and never stops, so the compliant contact is the rigid closed form
/// (gross sliding, eqs 24-35) for every shear stiffness: two resin pool balls, mu = 0.06,
/// 1.341 m/s at cuts of 3, 10 and 20 degrees, the outgoing state to 1e-8 of the speed.
#[test]
fn tangential_pair_rolling_cut_shot_is_the_rigid_contact() {
    let ball = Ball::new(0.17, 0.028575, ALPHA_SOLID).unwrap();
    let v = 1.341;
    for cut in [3.0f64, 10.0, 20.0] {
        let c = cut.to_radians();
        // In the frame (n = x from A to B, z up): the cue ball's velocity makes the angle
        // `cut` with the line of centres, u = (v_A - v_B) / 2 with B at rest.
        let vel = v * Vector3::new(c.cos(), -c.sin(), 0.0);
        let u = vel / 2.0;
        // Rolling on the cloth (its contact at -r z at rest): w = (z x v) / r.
        let w = Vector3::z().cross(&vel) / ball.radius();
        let s = CmState::new(u, w, Vector3::zeros());
        let ([va, vb], rigid_out) = rigid(&ball, &ball, 0.06, s);
        let pa = body(ball, 5.4e9, 0.34, va, w);
        let pb = body(ball, 5.4e9, 0.34, vb, Vector3::zeros());
        for factor in [1.0, 100.0] {
            let out =
                resolve_sphere_sphere_compliant(&pa, &pb, Vector3::x(), 0.06, factor, &tight())
                    .unwrap();
            let d = distance(&ball, &ball, &out, &rigid_out, v);
            assert!(d < 1e-8, "cut {cut}, factor {factor}: {d:e}");
        }
    }
}
