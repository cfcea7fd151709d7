//! Hard cases of the sliding: S(0) = 0 and round-off-sized S(0), sliding that
//! stops exactly at the end of the pulse or just after the first step, extreme mu, alpha,
//! restitution and explicit impulses, theta near +-pi and slips along either axis.
//!
//! Every case runs every method (closed form, rk4, dopri5, dop853) at the default settings
//! and is checked against an independent closed form (tests/common: eqs 24-35, 49-50 and
//! the stick rule of docs/model.md#when-sliding-stops-during-contact, written out in the test, not the library's
//! `ClosedForm`) with the scaled tolerances of `common::state_tolerance` (closed form 1e-14,
//! dop853 1e-10, dopri5 1e-9, rk4 1e-9), the event rule of docs/model.md#locating-the-stop-of-sliding
//! (|p(t_stick) - p_stick| <= 1e-10 P) and the cost bound (at most 20 times the
//! right-hand-side evaluations of the default scene with the same settings; counts are
//! printed with `--nocapture`). The profile is the half-sine, whose p(t) = P sin^2(pi t / 2 tau)
//! is exact.

use crate::common::collision::CollisionSpec;
use crate::hard as common;

use billiard_contact::profile::HalfSine;
use billiard_contact::TraceRow;
use billiard_contact::{solve, CmState, ImpulseRule, Method, Sampling};
use common::*;
use nalgebra::Vector3;

/// Runs one case with every method and checks it.
#[allow(clippy::too_many_arguments)]
fn case(
    label: &str,
    alpha: f64,
    mu: f64,
    e_rest: f64,
    impulse: Option<f64>,
    incoming: CmState,
    sticks_decided: bool,
) {
    let rule = match impulse {
        Some(p) => ImpulseRule::explicit(p).unwrap(),
        None => ImpulseRule::restitution(e_rest).unwrap(),
    };
    let c = CollisionSpec::ball(M, R, alpha)
        .mu(mu)
        .impulse(rule)
        .incoming(incoming)
        .build();
    let exact = Exact::new(M, R, alpha, mu, e_rest, impulse, incoming);
    let profile = HalfSine::new(TAU).unwrap();
    let x = Expect {
        label,
        exact,
        phi: &half_sine_phi,
        sticks_decided,
    };
    for method in [
        Method::ClosedForm,
        Method::Rk4,
        Method::Dopri5,
        Method::Dop853,
    ] {
        let s = settings(method);
        let o = if method == Method::ClosedForm {
            solve(&c, &profile, &s, None).unwrap()
        } else {
            run_bounded(label, &c, &profile, &s, default_cost(&s))
        };
        check_outcome(&x, &o, TAU);
    }
}

fn cm(u: [f64; 3], wa: [f64; 3], wb: [f64; 3]) -> CmState {
    CmState::new(Vector3::from(u), Vector3::from(wa), Vector3::from(wb))
}

/// A stun cut with slip S(0) along the angle `phi` (rad) in the (y, z) plane: no spin,
/// (V, W) = S(0)/2 (cos phi, sin phi), U = u0.
fn slip_case(u0: f64, s0: f64, phi: f64) -> CmState {
    cm(
        [u0, 0.5 * s0 * phi.cos(), 0.5 * s0 * phi.sin()],
        [0.0; 3],
        [0.0; 3],
    )
}

#[test]
fn zero_slip_head_on_stun() {
    // S(0) = 0 exactly: only U changes, U -> U - P/m (docs/model.md#no-initial-sliding); theta null.
    case(
        "head-on stun, S(0) = 0",
        0.4,
        MU,
        1.0,
        None,
        cm([1.5, 0.0, 0.0], [0.0; 3], [0.0; 3]),
        true,
    );
}

#[test]
fn zero_slip_side_spin_gears_the_cut() {
    // 2V + r Omega_z = 0 and 2W - r Omega_y = 0 exactly in floating point (r = 2^-5):
    // V = 1/4, Omega_z = -16 (split between the balls), W = 1/8, Omega_y = 8.
    let r = 0.03125;
    let incoming = cm([1.0, 0.25, 0.125], [3.0, 5.0, -10.0], [-1.0, 3.0, -6.0]);
    assert_eq!(incoming.sliding_speed(r), 0.0);
    let rule = ImpulseRule::restitution(0.9).unwrap();
    let c = CollisionSpec::ball(M, r, 0.4)
        .mu(MU)
        .impulse(rule)
        .incoming(incoming)
        .build();
    let exact = Exact::new(M, r, 0.4, MU, 0.9, None, incoming);
    let profile = HalfSine::new(TAU).unwrap();
    let x = Expect {
        label: "geared cut, S(0) = 0",
        exact,
        phi: &half_sine_phi,
        sticks_decided: true,
    };
    for method in [
        Method::ClosedForm,
        Method::Rk4,
        Method::Dopri5,
        Method::Dop853,
    ] {
        let s = settings(method);
        let o = solve(&c, &profile, &s, None).unwrap();
        check_outcome(&x, &o, TAU);
        // Only U changes, exactly as eq 24 says.
        let mut want = incoming;
        want.u_cm.x -= 1.9 * incoming.u_cm.x;
        assert!((o.result.out.u_cm.x - want.u_cm.x).abs() <= state_tolerance(method));
        assert_eq!(o.result.out.u_cm.yz(), incoming.u_cm.yz());
        assert_eq!(o.result.out.omega_a, incoming.omega_a);
        assert_eq!(o.result.out.omega_b, incoming.omega_b);
        assert_eq!(o.result.theta, None);
    }
}

#[test]
fn round_off_slip_sticks_at_once() {
    // S(0) = 1e-300, 1e-15, 1e-9 of the normal speed, in several directions: sliding stops
    // at t -> 0+, no step-size underflow, theta finite, J along e0 and at most
    // m S(0) / (2 (1 + 1/alpha)) (checked in check_outcome).
    for frac in [1e-300, 1e-15, 1e-9] {
        for phi in [0.0, 0.7, -2.0, std::f64::consts::PI] {
            let label = format!("S(0) = {frac:e} U(0), direction {phi}");
            case(
                &label,
                0.4,
                MU,
                1.0,
                None,
                slip_case(1.2, 1.2 * frac, phi),
                true,
            );
        }
    }
    // The same with a large spin that nearly gears the slip away (S(0) the difference of
    // large terms): V = 0.5, Omega_z = -1/r (1 - 1e-15 relative).
    let r = R;
    let wz = -(2.0 * 0.5) / r;
    let incoming = cm([0.8, 0.5, 0.0], [0.0, 0.0, wz * (1.0 - 1e-15)], [0.0; 3]);
    case(
        "nearly geared by side spin",
        0.4,
        MU,
        1.0,
        None,
        incoming,
        true,
    );
}

#[test]
fn sliding_stops_at_the_end_of_the_pulse() {
    // p_stick = P (1 -+ 1e-12): S(0) = k mu p_stick with P = 2 m U(0).
    let u0 = 1.0;
    let p = 2.0 * M * u0;
    let k = 2.0 * (1.0 + 1.0 / 0.4) / M;
    for f in [1.0 - 1e-12, 1.0 + 1e-12, 1.0 - 1e-6, 1.0 + 1e-6] {
        let s0 = k * MU * p * f;
        let label = format!("p_stick = P ({f})");
        // Within the integrators' own accuracy of p (about 1e-12 P) both answers are
        // right; the state and the event rule are checked either way.
        let decided = (f - 1.0).abs() > 1e-9;
        case(&label, 0.4, MU, 1.0, None, slip_case(u0, s0, 0.3), decided);
    }
}

#[test]
fn sliding_stops_just_after_the_first_step() {
    let u0 = 1.0;
    let p = 2.0 * M * u0;
    let k = 2.0 * (1.0 + 1.0 / 0.4) / M;
    let profile = HalfSine::new(TAU).unwrap();
    for method in [Method::Rk4, Method::Dopri5, Method::Dop853] {
        // The first accepted step of a slide that does not stop.
        let c = CollisionSpec::ball(M, R, 0.4)
            .mu(MU)
            .restitution(1.0)
            .incoming(slip_case(u0, 10.0, 0.0))
            .build();
        let mut rows: Vec<TraceRow> = Vec::new();
        solve(
            &c,
            &profile,
            &settings(method),
            Some((&mut rows, Sampling::Steps)),
        )
        .unwrap();
        let h1 = rows[1].t / TAU;
        assert!(h1 > 0.0 && h1 < 1.0);
        for f in [1.0 + 1e-9, 1.0 - 1e-9, 1.0 + 1e-3] {
            let s0 = k * MU * p * half_sine_phi(h1) * f;
            let label = format!("p_stick = p(first step) ({f})");
            let incoming = slip_case(u0, s0, 0.0);
            let c = CollisionSpec::ball(M, R, 0.4)
                .mu(MU)
                .restitution(1.0)
                .incoming(incoming)
                .build();
            let s = settings(method);
            let o = run_bounded(&label, &c, &profile, &s, default_cost(&s));
            let x = Expect {
                label: &label,
                exact: Exact::new(M, R, 0.4, MU, 1.0, None, incoming),
                phi: &half_sine_phi,
                sticks_decided: true,
            };
            check_outcome(&x, &o, TAU);
            // f(t_stick) is not small here: the time itself to 1e-10 of the duration.
            let t = o.stick_time.unwrap();
            let want = TAU * half_sine_time(h1 * 0.0 + half_sine_phi(h1) * f);
            assert!(
                (t - want).abs() <= 1e-10 * TAU,
                "{label}: t_stick {t:e} vs {want:e}"
            );
        }
    }
}

#[test]
fn extreme_friction_coefficients() {
    // mu = 1e-12: slides throughout, J = mu P; mu = 10: sticks almost at once.
    for mu in [1e-12, 10.0] {
        for (label, incoming) in [
            ("stun cut 30 deg", slip_case(1.3, 1.5, 0.2)),
            (
                "draw, side spin",
                cm([1.0, 0.3, 0.1], [2.0, -30.0, 25.0], [0.0, 1.0, 0.0]),
            ),
        ] {
            let label = format!("{label}, mu = {mu:e}");
            case(&label, 0.4, mu, 1.0, None, incoming, true);
        }
    }
}

#[test]
fn extreme_moments_of_inertia() {
    // alpha = 1e-3 (mass at the centre: spin changes 1000 times faster) and 2/3 (shell).
    for alpha in [1e-3, 2.0 / 3.0] {
        for (label, s0) in [("slides", 2.0), ("sticks", 0.02)] {
            let label = format!("alpha = {alpha}, {label}");
            case(&label, alpha, MU, 1.0, None, slip_case(1.0, s0, 1.1), true);
        }
    }
}

#[test]
fn restitution_and_explicit_impulses() {
    for e in [0.0, 1.0] {
        for s0 in [2.0, 0.05] {
            let label = format!("e = {e}, S(0) = {s0}");
            case(&label, 0.4, MU, e, None, slip_case(0.9, s0, -0.4), true);
        }
    }
    let u0 = 0.9;
    for f in [1.0, 1.25, 1.5, 1.75, 2.0] {
        for s0 in [2.0, 0.05] {
            let label = format!("P = {f} m U(0), S(0) = {s0}");
            case(
                &label,
                0.4,
                MU,
                0.0,
                Some(f * M * u0),
                slip_case(u0, s0, 2.5),
                true,
            );
        }
    }
}

#[test]
fn theta_near_pi_and_slip_along_the_axes() {
    let pi = std::f64::consts::PI;
    let tiny = [0.0, 1e-300, 1e-16, 1e-9];
    for (s0, label) in [(2.0, "slides"), (0.05, "sticks")] {
        for d in tiny {
            for (phi, axis) in [
                (pi - d, "theta -> pi-"),
                (-pi + d, "theta -> -pi+"),
                (d, "along +y"),
                (-d, "along +y (below)"),
                (0.5 * pi + d, "along +z"),
                (-0.5 * pi - d, "along -z"),
            ] {
                let label = format!("{axis} ({d:e}), {label}");
                case(&label, 0.4, MU, 1.0, None, slip_case(1.0, s0, phi), true);
            }
        }
        // Slip exactly along -y, written with W = -0.0: theta must be +pi, not -pi.
        let incoming = cm([1.0, -0.5 * s0, -0.0], [0.0; 3], [0.0; 3]);
        case(
            "slip along -y, W = -0.0",
            0.4,
            MU,
            1.0,
            None,
            incoming,
            true,
        );
        // Almost parallel to an axis because one component is a round-off remainder.
        let incoming = cm([1.0, 0.5 * s0, 1e-17], [0.0; 3], [0.0; 3]);
        case("W = 1e-17", 0.4, MU, 1.0, None, incoming, true);
    }
}
