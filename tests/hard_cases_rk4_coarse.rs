//! Hard cases of a coarse fixed step (rk4) crossing the stop of sliding with a
//! speed-dependent mu(S) = a + b exp(-c S), small alpha and a tabulated profile.
//!
//! With alpha ~ 1e-3 the slip falls k = 2 (1 + 1/alpha) / m times faster than the velocities,
//! and in the rk4 step that crosses the stop the stages overshoot it, where the exponential
//! of mu(S) taken past the stop grows from stage to stage. The cases below, from the
//! properties' distribution, overshoot far enough to overflow it or to leave a huge finite
//! slip, at 200 steps and at the default 1000; dopri5, dop853 and the closed form solve them
//! all.
//!
//! Each runs rk4 at 200 and 1000 steps and must succeed with the checks of the properties
//! (tests/properties_invariants.rs): the closed form and the angular momentum to the rk4
//! tolerance for a speed-dependent mu (1e-6 scaled; sliding stops, and the tangential state
//! at the stop follows from slip = 0 by the linear invariants the method keeps exactly, so
//! both are at round-off), theta constant along the trace before the stop, and the heat of
//! eq 50 and the stop of sliding at p_stick to the properties' 1e-6 and 1e-5 P at their
//! 1000 steps, and to 1e-5 and 1e-3 P at 200 steps, where they carry the error of the
//! coarse steps of the nonlinear S(p) before the stop (observed 1.2e-6 and 4.6e-4 P).

use crate::common::collision::CollisionSpec;
use crate::common::Rule;
use billiard_contact::profile::Profile;
use billiard_contact::profile::Tabulated;
use billiard_contact::TraceRow;
use billiard_contact::{solve, CmState, Method, Sampling, SolverSettings};
use nalgebra::Vector3;
use std::path::Path;

/// A case in the properties' units (m = r = v = tau = 1): speeds in v, spins in v / r.
struct Case {
    label: &'static str,
    alpha: f64,
    /// (a, b, c) of mu(S) = a + b exp(-c S).
    abc: (f64, f64, f64),
    /// Restitution e, or the explicit impulse as a multiple of m U(0).
    rule: Result<f64, f64>,
    u: [f64; 3],
    wa: [f64; 3],
    wb: [f64; 3],
    table: &'static [(f64, f64)],
}

const CASES: [Case; 4] = [
    // At 200 steps the stages overshoot the stop far enough to overflow exp(c |S|).
    Case {
        label: "property shrink",
        alpha: 0.002486152814618681,
        abc: (0.01019252881235684, 0.14250342279068048, 1.8479772916612367),
        rule: Ok(0.5541030969904558),
        u: [0.9867187461257426, 0.47299132548819633, 0.5696613682229499],
        wa: [0.0, -0.19281050744941372, 2.308752391775525],
        wb: [0.0, -2.421142919945334, 1.7149797698368976],
        table: &[
            (0.0, 0.0),
            (0.23869660872979728, 0.0),
            (0.42393777546040745, 1.2704679712475544),
        ],
    },
    // At 200 steps the stages overshoot the stop far enough to overflow exp(c |S|).
    Case {
        label: "scan 1315",
        alpha: 0.0015158299564082482,
        abc: (0.016080941389545307, 0.1336822322424679, 2.4774380031065415),
        rule: Ok(0.29270020169183986),
        u: [0.880132817596365, -0.09778946037101832, -0.1767971350781985],
        wa: [2.7463775960568375, 0.28548281449274526, 1.493299389216533],
        wb: [-1.327834252171221, -2.897190895075357, 2.4490941458807223],
        table: &[
            (0.0, 0.0),
            (0.8809535717955935, 0.0),
            (1.7518553744061478, 6.778037660413688),
            (2.478306699415518, 5.782584974911829),
            (2.743567626218059, 8.423978888272975),
            (3.3345620082794794, 9.97813751744708),
        ],
    },
    // At 200 steps a finite overshoot: the stop must still be located at p_stick.
    Case {
        label: "scan 1360",
        alpha: 0.0023151728694572184,
        abc: (0.03303194739415778, 0.14421788718464112, 1.4307060446148228),
        rule: Ok(0.8936784630028417),
        u: [0.7849618477226235, -0.7725807751698635, 0.2734149041082201],
        wa: [-1.0322015410472407, 1.9415084880236346, -0.5224025812866415],
        wb: [
            -2.777419980819503,
            -0.8017763909396423,
            -0.05920777416829992,
        ],
        table: &[
            (0.0, 0.0),
            (0.4522257506152193, 0.0),
            (1.3402925920826019, 0.0),
            (1.8625988735350116, 0.0),
            (2.15422926391175, 0.0),
            (2.3142570445240325, 2.9616189183900277),
        ],
    },
    // A finite overshoot at the default 1000 steps, with an explicit impulse.
    Case {
        label: "scan 19642",
        alpha: 0.0011521690497064002,
        abc: (
            0.004723558686490714,
            0.13992538658605685,
            2.9132999521346217,
        ),
        rule: Err(1.9889757693279928),
        u: [0.3845351579808361, 0.18723121020241296, -0.0650837842348464],
        wa: [0.990766747842488, 2.1818851901776064, 2.051555580026222],
        wb: [-1.645744068729738, -2.8850485950645286, 1.95294500137905],
        table: &[
            (0.0, 0.0),
            (0.3560890616806248, 0.0),
            (1.1941406709611901, 0.0),
            (1.6614454924010413, 3.941673908538611),
            (1.95730375577189, 0.9027545653095326),
        ],
    },
];

/// The properties' tolerance for rk4 with a speed-dependent mu (scaled).
const TOL: f64 = 1e-6;

/// `heat_tol`: eq 50 (scaled); `stick_tol`: |p_stick error| / P.
fn check(k: &Case, steps: u32, heat_tol: f64, stick_tol: f64) {
    let c = CollisionSpec::ball(1.0, 1.0, k.alpha)
        .speed_dependent(k.abc.0, k.abc.1, k.abc.2)
        .rule(match k.rule {
            Ok(e) => Rule::Restitution(e),
            Err(f) => Rule::Explicit(f * k.u[0]),
        })
        .incoming(CmState::new(
            Vector3::from(k.u),
            Vector3::from(k.wa),
            Vector3::from(k.wb),
        ))
        .build();
    let profile =
        Profile::Tabulated(Tabulated::new(k.table, Some(1.0), Path::new("coarse.csv")).unwrap());
    let settings = SolverSettings::default()
        .with_method(Method::Rk4)
        .with_steps(steps)
        .unwrap();
    let mut rows: Vec<TraceRow> = Vec::new();
    let o = solve(&c, &profile, &settings, Some((&mut rows, Sampling::Steps)))
        .unwrap_or_else(|e| panic!("{}, rk4 {steps} steps: {e}", k.label));
    let at = format!("{}, rk4 {steps} steps", k.label);
    let ch = o.check;
    assert!(o.result.out.is_finite(), "{at}");
    assert!(
        ch.closed_form_error <= TOL,
        "{at}: closed form {:e}",
        ch.closed_form_error
    );
    assert!(
        ch.energy_balance_error <= heat_tol,
        "{at}: eq 50 {:e}",
        ch.energy_balance_error
    );
    assert!(
        ch.angular_momentum_error <= TOL,
        "{at}: {:e}",
        ch.angular_momentum_error
    );
    assert!(
        ch.theta_drift <= TOL,
        "{at}: theta drift {:e}",
        ch.theta_drift
    );
    assert!(
        o.result.s_out >= 0.0 && o.result.heat_sliding >= 0.0,
        "{at}"
    );
    // All four stick well inside the pulse.
    let p_stick = o.exact.result.stick_impulse.unwrap();
    assert!(o.exact.result.sticks && o.result.sticks, "{at}");
    let reported = o.result.stick_impulse.unwrap();
    assert!(
        (reported - p_stick).abs() <= stick_tol * c.impulse,
        "{at}: stick impulse {reported:e} vs p_stick {p_stick:e} (P = {:e})",
        c.impulse
    );
    // theta_constant_while_sliding: the trace's slip before the stop stays along e0.
    let e0 = c.direction.unwrap();
    let t_stop = o.stick_time.unwrap();
    for row in rows.iter().filter(|r| r.t < t_stop) {
        let slip = row.state.slip(1.0);
        let size = row.state.u_cm.yz().amax() + row.state.omega_sum().yz().amax();
        let bound = 1e-8 * c.scales.speed.max(size) + 8.0 * f64::EPSILON * size;
        assert!(
            (slip.x * e0.y - slip.y * e0.x).abs() <= bound,
            "{at}: t = {:e}",
            row.t
        );
        assert!(slip.dot(&e0) >= -bound, "{at}: t = {:e}", row.t);
    }
}

#[test]
fn rk4_200_steps_crossing_the_stop() {
    for k in &CASES {
        check(k, 200, 1e-5, 1e-3);
    }
}

#[test]
fn rk4_1000_steps_crossing_the_stop() {
    for k in &CASES {
        check(k, 1000, TOL, 1e-5);
    }
}

/// The adaptive methods on the same cases, to their usual accuracy.
#[test]
fn adaptive_methods_agree() {
    for k in &CASES {
        let c = CollisionSpec::ball(1.0, 1.0, k.alpha)
            .speed_dependent(k.abc.0, k.abc.1, k.abc.2)
            .rule(match k.rule {
                Ok(e) => Rule::Restitution(e),
                Err(f) => Rule::Explicit(f * k.u[0]),
            })
            .incoming(CmState::new(
                Vector3::from(k.u),
                Vector3::from(k.wa),
                Vector3::from(k.wb),
            ))
            .build();
        let profile = Profile::Tabulated(
            Tabulated::new(k.table, Some(1.0), Path::new("coarse.csv")).unwrap(),
        );
        for method in [Method::Dopri5, Method::Dop853] {
            let settings = SolverSettings::default().with_method(method);
            let o = solve(&c, &profile, &settings, None).unwrap();
            assert!(o.check.closed_form_error <= 1e-8, "{} {method}", k.label);
            let (p, ps) = (
                o.result.stick_impulse.unwrap(),
                o.exact.result.stick_impulse.unwrap(),
            );
            assert!((p - ps).abs() <= 1e-7 * c.impulse, "{} {method}", k.label);
        }
    }
}
