//! The compliant impact of two spheres with a damped normal force
//! (docs/tangential.md#two-spheres): Hunt and Crossley's and Kuwabara and Kono's damping on
//! the pair's Hertz stiffness. The references come from outside the kernel: the contact-law
//! module's own head-on stepping (`solve_law`, which integrates the normal law with its own
//! integrator; its calibration `ContactLaw::calibrated` aims at the restitution), the
//! sphere-plane kernel for two identical balls (an exact equivalence: docs/tangential.md),
//! and the energy balance of the kinetic energies.

use crate::common::compliant::tight;
use billiard_contact::nalgebra::Vector3;
use billiard_contact::*;

fn body(ball: Ball, material: Material, v: Vector3<f64>, w: Vector3<f64>) -> CompliantSphere {
    CompliantSphere {
        ball,
        material,
        velocity: v,
        spin: w,
    }
}

/// Two unequal resin balls (0.17 kg, 28.575 mm, alpha 0.4; 0.20 kg, 30 mm, alpha 0.38).
fn unequal() -> BallPair {
    BallPair::new(
        Ball::new(0.17, 0.028575, 0.4).unwrap(),
        Ball::new(0.20, 0.030, 0.38).unwrap(),
    )
}

fn resin() -> Material {
    Material::new(5.4e9, 0.34).unwrap()
}

/// The pair's law of `damping` calibrated to `e` at the relative approach speed `v` (m/s),
/// on Hertz's stiffness of the pair (reduced mass m*).
fn law(pair: &BallPair, damping: Damping, e: f64, v: f64) -> ContactLaw {
    let k = HertzContact::of_pair(pair, &resin(), v / 2.0)
        .unwrap()
        .stiffness;
    ContactLaw::calibrated(k, damping, e, v, pair.reduced_mass()).unwrap()
}

/// Without friction the damped pair is the contact law's head-on impact: the relative normal
/// velocity reverses to the calibrated restitution (to 1e-8: the calibration is good to
/// 1e-10, the kernel's stepping at rtol 1e-11 to about 1e-9), and the contact time, the
/// largest compression and the peak force are those of `solve_law` on the same law and the
/// centre-of-mass state U(0) = v/2 (to 1e-7: two integrators, each at its tolerance). The
/// tangential motion and the spins are untouched; momentum is kept to 1e-12.
#[test]
fn damped_pair_frictionless_is_the_contact_law_head_on() {
    let pair = unequal();
    let v = 2.0;
    let n = Vector3::new(1.0, -0.3, 0.2).normalize();
    let side = Vector3::new(0.3, 1.0, 0.0).cross(&n);
    for damping in [Damping::HuntCrossley, Damping::KuwabaraKono] {
        for e in [0.5, 0.9] {
            let law = law(&pair, damping, e, v);
            // A moves towards B at v along n, with a tangential velocity and spins that stay.
            let (wa, wb) = (Vector3::new(3.0, -7.0, 11.0), Vector3::new(-2.0, 0.0, 5.0));
            let a = body(pair.a, resin(), v * n + 0.4 * side, wa);
            let b = body(pair.b, resin(), Vector3::zeros(), wb);
            let out = resolve_sphere_sphere_compliant_damped(
                &a,
                &b,
                (law.damping(), law.coefficient()),
                n,
                0.0,
                1.0,
                &tight(),
            )
            .unwrap();
            let g_out = out.ball_a.velocity - out.velocity_b;
            let realised = -g_out.dot(&n) / v;
            assert!((realised - e).abs() < 1e-8, "{damping:?} {e}: {realised}");
            assert!((g_out - g_out.dot(&n) * n - 0.4 * side).norm() < 1e-14 * v);
            assert_eq!((out.ball_a.spin, out.spin_b), (wa, wb));
            let p_in = pair.a.mass() * a.velocity;
            let p_out = pair.a.mass() * out.ball_a.velocity + pair.b.mass() * out.velocity_b;
            assert!((p_out - p_in).norm() < 1e-12 * pair.a.mass() * v);

            // The contact-law module's head-on run of the same law.
            let contact = Contact {
                friction: Friction::constant(0.0).unwrap(),
                impulse: ImpulseRule::ELASTIC,
            };
            let s = CmState::new(Vector3::new(v / 2.0, 0.0, 0.0), wa, wb);
            let c = Collision::new(pair, contact, Effects::default(), s).unwrap();
            let o = solve_law(&c, &law, &tight(), None).unwrap();
            let l = o.law.unwrap();
            let rel = |x: f64, y: f64| ((x - y) / y).abs();
            let k = &out.ball_a;
            assert!((l.restitution - realised).abs() < 1e-8, "{}", l.restitution);
            assert!(
                rel(k.contact_time, l.duration) < 1e-7,
                "{} {}",
                k.contact_time,
                l.duration
            );
            assert!(rel(k.max_compression, l.max_compression) < 1e-7);
            // The kernel's largest force is the largest at its steps: under damping the force
            // peaks before the largest compression, between two steps (up to 0.05 of the
            // contact time apart), so it is sampled from below (5e-5 low here).
            let f = k.max_normal_force;
            assert!(
                f <= l.peak_force * (1.0 + 1e-9) && rel(f, l.peak_force) < 1e-3,
                "{f}"
            );
            assert!(
                rel(k.normal_impulse, l.impulse) < 1e-8,
                "{} {}",
                k.normal_impulse,
                l.impulse
            );
        }
    }
}

/// Two identical balls (m, R, E) are exactly a sphere of half their mass and radius and of
/// modulus E/2 on a rigid plane: the same stiffness (4/3) E* sqrt(R*), the same mass of the
/// relative motion and the same tangential mass (docs/tangential.md#two-spheres), so the
/// same damping coefficient gives the same impact. With friction and spin, for both laws,
/// the relative outgoing velocity and the spin sum agree to 1e-8 of the speed.
#[test]
fn damped_pair_of_identical_balls_is_the_damped_plane_equivalent() {
    let ball = Ball::new(0.17, 0.028575, ALPHA_SOLID).unwrap();
    let half = Ball::new(0.085, 0.028575 / 2.0, ALPHA_SOLID).unwrap();
    let pair = BallPair::identical(ball);
    let n = Vector3::x();
    for damping in [Damping::HuntCrossley, Damping::KuwabaraKono] {
        let law = law(&pair, damping, 0.7, 2.0);
        for (deg, wa, wb) in [
            (15.0f64, Vector3::zeros(), Vector3::zeros()),
            (
                40.0,
                Vector3::new(0.0, 10.0, 30.0),
                Vector3::new(5.0, 0.0, -20.0),
            ),
        ] {
            let t = deg.to_radians();
            let g = 2.0 * Vector3::new(t.cos(), t.sin(), 0.0);
            let a = body(ball, resin(), g / 2.0, wa);
            let b = body(ball, resin(), -g / 2.0, wb);
            let d = (law.damping(), law.coefficient());
            let p =
                resolve_sphere_sphere_compliant_damped(&a, &b, d, n, 0.2, 1.0, &tight()).unwrap();
            let half_resin = Material::new(5.4e9 / 2.0, 0.34).unwrap();
            let plane = resolve_sphere_plane_compliant_damped(
                &half,
                half_resin,
                None,
                d,
                0.2,
                g,
                2.0 * (wa + wb),
                -n,
                &tight(),
            )
            .unwrap();
            let g_out = p.ball_a.velocity - p.velocity_b;
            let w_out = 2.0 * (p.ball_a.spin + p.spin_b);
            assert!(
                (g_out - plane.velocity).norm() < 1e-8 * 2.0,
                "{damping:?} {deg}"
            );
            assert!((w_out - plane.spin).norm() * half.radius() < 1e-8 * 2.0);
            // It rebounds off the plane (normal -x), slower than it came: damped.
            assert!(
                plane.velocity.x < 0.0 && -plane.velocity.x < g.x,
                "{}",
                plane.velocity
            );
        }
    }
}

/// The kinetic energy lost is the tangential force's work plus the normal force's loss,
/// (1/2) m* ((g.n)^2 - (g'.n)^2): two unequal balls of two materials, damped and with
/// friction and spin, to 1e-8 of the incoming energy. The kinetic energies come from the
/// stepped velocities and spins, the work from the quadrature of -F_t.u the kernel carries
/// beside them.
#[test]
fn damped_pair_energy_is_the_normal_loss_plus_the_tangential_work() {
    let pair = unequal();
    let steel = Material::new(2.0e11, 0.29).unwrap();
    let k = HertzContact::of_pair(&pair, &resin(), 1.0)
        .unwrap()
        .stiffness;
    let m = pair.reduced_mass();
    for damping in [Damping::None, Damping::HuntCrossley, Damping::KuwabaraKono] {
        let law = match damping {
            Damping::None => ContactLaw::new(k, damping, 0.0).unwrap(),
            _ => ContactLaw::calibrated(k, damping, 0.8, 2.0, m).unwrap(),
        };
        for (mu, deg) in [(0.05, 30.0f64), (0.3, 10.0), (1.0, 60.0)] {
            let t = deg.to_radians();
            let a = body(
                pair.a,
                resin(),
                2.0 * Vector3::new(t.cos(), t.sin(), 0.1),
                Vector3::new(0.0, 40.0, -25.0),
            );
            let b = body(
                pair.b,
                steel,
                Vector3::zeros(),
                Vector3::new(-10.0, 0.0, 15.0),
            );
            let d = (law.damping(), law.coefficient());
            let out =
                resolve_sphere_sphere_compliant_damped(&a, &b, d, Vector3::x(), mu, 1.0, &tight())
                    .unwrap();
            let o = &out.ball_a;
            let (gn, gn_out) = (a.velocity.x, o.velocity.x - out.velocity_b.x);
            let normal_loss = 0.5 * m * (gn * gn - gn_out * gn_out);
            let lost = o.kinetic_energy_in - o.kinetic_energy_out;
            let balance = lost - normal_loss - o.tangential_work;
            assert!(
                balance.abs() < 1e-8 * o.kinetic_energy_in,
                "{damping:?} {mu} {deg}: {balance:e}"
            );
            assert!(o.tangential_work > 0.0, "{damping:?} {mu} {deg}");
            if damping == Damping::None {
                assert!(normal_loss.abs() < 1e-8 * o.kinetic_energy_in);
            } else {
                assert!(normal_loss > 0.0);
            }
        }
    }
}
