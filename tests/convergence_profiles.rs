//! Every profile and every time-stepping method converges to the closed form.
//!
//! The outgoing state of a collision depends on the profile only through the impulse P
//! (docs/model.md#the-exact-state-during-the-contact: while sliding the state is the closed form at p(t); after sticking only U
//! changes), so the reference for every profile is the same first-principles resolution
//! (`common::resolve`). Stick events are checked against each profile's p(t) computed in
//! `common` (closed forms and quadratures that do not use the crate's profile code).

use crate::common;

use billiard_contact::profile::{ForceProfile, HalfSine, Hertz, Rectangle, SinePower, Tabulated};
use billiard_contact::{solve, Outcome};
use billiard_contact::{Method, SolverSettings};
use common::collision::CollisionSpec;
use common::{amax, resolve, Balls, Expected, Law, Pair, Rule, Table};
use nalgebra::{SVector, Vector3};
use ode_solvers::{Dop853, OutputType, System};
use std::f64::consts::PI;
use std::path::PathBuf;

/// Each tolerance is ten times the worst scaled error measured over the subjects and cases
/// below (`cargo test --release --test suite convergence_profiles:: -- --nocapture` prints each
/// subject's worst), so that a regression of two orders of magnitude fails.
///
/// Dop853 at rtol 1e-12 (the promise: within 1e-10 of the closed form, scaled). With the
/// time transform on (the default) every pulse is stepped like the half-sine: measured
/// worst 1.07e-13. The t^(3/2) ends stepped through graded breakpoints (transform off):
/// 3.53e-11.
const DOP853_RTOL: f64 = 1e-12;
const DOP853_TOL: f64 = 1e-12;
const DOP853_GRADED_TOL: f64 = 4e-10;
/// Dopri5 at rtol 1e-12: measured worst 2.17e-13 with the transform, 3.08e-11 with the
/// t^(3/2) ends stepped through graded breakpoints (transform off, docs/model.md#breakpoints).
const DOPRI5_RTOL: f64 = 1e-12;
const DOPRI5_TOL: f64 = 3e-12;
const DOPRI5_GRADED_TOL: f64 = 4e-10;
/// RK4 with 1000 steps: Simpson-like quadrature of f, error O(h^4) on smooth pulses and on
/// algebraic ends smoothed by the time transform (measured worst 5.15e-14: round-off over
/// 1000 steps), O(h^2.5) at the t^(3/2) ends of hertz and sine-power stepped without it
/// (measured worst 2.96e-9).
const RK4_STEPS: u32 = 1000;
const RK4_SMOOTH_TOL: f64 = 5e-13;
const RK4_TOL: f64 = 3e-8;
/// Profiles whose force is piecewise linear (rectangle, tabulated) are integrated exactly
/// by every method (stepping to the breakpoints): round-off only. Measured worst 2.17e-15
/// (dop853), 8.7e-16 (dopri5), 2.83e-15 (rk4 with 1 to 50 steps); rk4's 1000 steps
/// accumulate 4.94e-14.
const EXACT_TOL: f64 = 3e-14;
const RK4_EXACT_TOL: f64 = 5e-13;
/// Stick event: the promise is |t - t_exact| <= 1e-10 tau where the force is not small
/// (docs/model.md#locating-the-stop-of-sliding); measured worst 1.99e-14 tau (sin^0.7).
const STICK_TIME_TOL: f64 = 2e-13;
/// Stick event: the promise is |p(t_stick) - p_stick| <= 1e-10 P
/// (docs/model.md#locating-the-stop-of-sliding); measured worst 2.85e-14 P (sin^0.7).
const STICK_IMPULSE_TOL: f64 = 3e-13;
/// Observed order of RK4 on the half-sine: 4 within this margin.
const ORDER_MARGIN: f64 = 0.3;
/// Smallest observed order of RK4 on algebraic ends with the time transform.
const TRANSFORMED_ORDER: f64 = 3.8;

const TAU: f64 = 2.5e-4;
const BALLS: Balls = Balls {
    m: 0.17,
    r: 0.028575,
    alpha: 0.4,
};

fn table_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data/profiles/measured_pulse.csv")
}

/// A profile of the crate with its independent reference p(t)/P and inverse.
struct Subject {
    name: &'static str,
    profile: Box<dyn ForceProfile>,
    fraction: Box<dyn Fn(f64) -> f64>,
    time: Box<dyn Fn(f64) -> f64>,
    /// Piecewise-linear force: every method is exact.
    exact: bool,
    /// Ends with f ~ t^(3/2): also run with the time transform off (graded breakpoints),
    /// where they lower the observed order.
    graded_also: bool,
}

fn subjects() -> Vec<Subject> {
    let table = std::rc::Rc::new(Table::read(&table_path()));
    let t2 = table.clone();
    vec![
        Subject {
            name: "half-sine",
            profile: Box::new(HalfSine::new(TAU).unwrap()),
            fraction: Box::new(common::half_sine_fraction),
            time: Box::new(common::half_sine_time),
            exact: false,
            graded_also: false,
        },
        Subject {
            name: "hertz",
            profile: Box::new(Hertz::new(TAU).unwrap()),
            fraction: Box::new(|s| common::invert(common::hertz_time, s)),
            time: Box::new(common::hertz_time),
            exact: false,
            graded_also: true,
        },
        Subject {
            name: "sine-power 1.5",
            profile: Box::new(SinePower::new(TAU, 1.5).unwrap()),
            fraction: Box::new(|s| common::sine_power_fraction(1.5, s)),
            time: Box::new(|q| common::invert(|s| common::sine_power_fraction(1.5, s), q)),
            exact: false,
            graded_also: true,
        },
        // f ~ t^0.7: a sin^5 transform (the smallest m with 1.7 (m + 1) >= 9).
        Subject {
            name: "sine-power 0.7",
            profile: Box::new(SinePower::new(TAU, 0.7).unwrap()),
            fraction: Box::new(|s| common::sine_power_fraction(0.7, s)),
            time: Box::new(|q| common::invert(|s| common::sine_power_fraction(0.7, s), q)),
            exact: false,
            graded_also: false,
        },
        Subject {
            name: "rectangle",
            profile: Box::new(Rectangle::new(TAU).unwrap()),
            fraction: Box::new(|s| s.clamp(0.0, 1.0)),
            time: Box::new(|q| q),
            exact: true,
            graded_also: false,
        },
        Subject {
            name: "tabulated",
            profile: Box::new(Tabulated::from_csv_file(&table_path(), Some(TAU)).unwrap()),
            fraction: Box::new(move |s| table.fraction(s)),
            time: Box::new(move |q| t2.time(q)),
            exact: true,
            graded_also: false,
        },
    ]
}

/// Generic 3D states: spins on both balls, side and vertical velocity.
struct Case {
    name: &'static str,
    pair: Pair,
    law: Law,
}

fn cases() -> Vec<Case> {
    let v = Vector3::new;
    vec![
        // S0 = 1.28 m/s, p_stick = 0.52 N s > P = 0.32 N s: slides throughout.
        Case {
            name: "slides",
            pair: Pair::cm(v(1.0, 0.3, -0.2), v(5.0, -10.0, 20.0), v(-3.0, 8.0, 2.0)),
            law: Law::new(0.06, Rule::Restitution(0.9)),
        },
        // S0 = 0.07 m/s: sliding stops at p ~ 0.08 P, early in the pulse.
        Case {
            name: "sticks early",
            pair: Pair::cm(v(1.0, 0.05, 0.02), v(3.0, 1.0, -2.0), v(0.0, -1.0, 0.5)),
            law: Law::new(0.06, Rule::Restitution(1.0)),
        },
        // S0 = 0.43 m/s: sliding stops near p = P/2.
        Case {
            name: "sticks mid-pulse",
            pair: Pair::cm(v(1.0, 0.2, 0.05), v(0.0, 0.0, 0.0), v(0.0, 2.0, 1.0)),
            law: Law::new(0.06, Rule::Restitution(1.0)),
        },
        // Larger friction, explicit impulse: S0 = 1.36 m/s, stops at about 0.94 P.
        Case {
            name: "sticks late, explicit P",
            pair: Pair::cm(v(0.8, -0.6, 0.4), v(-4.0, 12.0, 6.0), v(2.0, 0.0, -9.0)),
            law: Law::new(0.2, Rule::Explicit(0.17 * 0.8 * 1.3)),
        },
    ]
}

/// Scaled distance of an outcome from the reference (docs/model.md#scales-and-scaled-errors).
fn error(case: &Case, o: &Outcome, want: &Expected) -> f64 {
    let v = case.pair.v_ref(BALLS.r);
    let spin = v / BALLS.r;
    (amax(&(o.result.out.u_cm - want.out.va)) / v)
        .max(amax(&(o.result.out.omega_a - want.out.wa)) / spin)
        .max(amax(&(o.result.out.omega_b - want.out.wb)) / spin)
}

fn settings(method: Method, rtol: f64, steps: u32) -> SolverSettings {
    SolverSettings::new(method, rtol, rtol, steps).unwrap()
}

/// Runs one (profile, case, settings), checks the outgoing state within `tol` and the
/// stick event against the profile's reference; returns (state error, stick time error / tau).
fn check_run(sub: &Subject, case: &Case, s: &SolverSettings, tol: f64) -> (f64, f64, f64) {
    let c = CollisionSpec::reference(&BALLS, &case.law, &case.pair).build();
    let want = resolve(&BALLS, &case.law, &case.pair);
    let o = solve(&c, sub.profile.as_ref(), s, None).unwrap();
    let err = error(case, &o, &want);
    let what = format!(
        "{} / {} / {} rtol {:e}",
        sub.name,
        case.name,
        s.method(),
        s.rtol()
    );
    assert!(err <= tol, "{what}: scaled error {err:e} > {tol:e}");
    // The run's own check agrees with the independent error (same scales).
    assert!(
        (o.check.closed_form_error - err).abs() <= 1e-13,
        "{what}: check.closed_form_error {:e} vs {err:e}",
        o.check.closed_form_error
    );
    assert_eq!(o.result.sticks, want.sticks, "{what}: sticks");
    let (mut t_err, mut p_err) = (0.0, 0.0);
    if want.sticks {
        let p_stick = want.p_stick.unwrap();
        let q = p_stick / want.impulse;
        let t = o.stick_time.expect("stick time") / TAU;
        // The impulse actually delivered by the profile up to the reported stop.
        let p_at = (sub.fraction)(t) * want.impulse;
        p_err = (p_at - p_stick).abs() / want.impulse;
        assert!(
            p_err <= STICK_IMPULSE_TOL,
            "{what}: p(t_stick) = {p_at:e}, p_stick = {p_stick:e}"
        );
        t_err = (t - (sub.time)(q)).abs();
        assert!(
            t_err <= STICK_TIME_TOL,
            "{what}: stick time error {t_err:e} tau"
        );
        assert!(
            (o.result.stick_impulse.unwrap() - p_stick).abs() <= STICK_IMPULSE_TOL * want.impulse
        );
    } else {
        assert_eq!(o.stick_time, None);
    }
    (err, t_err, p_err)
}

/// The settings a subject runs with: `base` (time transform on, the default), and with the
/// transform off (graded breakpoints) for the subjects with t^(3/2) ends.
fn variants(sub: &Subject, base: SolverSettings) -> Vec<SolverSettings> {
    let mut v = vec![base];
    if sub.graded_also {
        v.push(base.with_time_transform(false));
    }
    v
}

/// One adaptive method at `base` over every subject (with the transform off too where
/// [`variants`] says) and every case: prints each (subject, transform)'s largest scaled
/// state error and stick time error, and holds each run to `tol(subject, transform)`.
fn sweep(base: SolverSettings, tol: impl Fn(&Subject, bool) -> f64) {
    for sub in subjects() {
        for s in variants(&sub, base) {
            let (mut worst, mut worst_t, mut worst_p) = (0.0_f64, 0.0_f64, 0.0_f64);
            for case in cases() {
                let (e, t, p) = check_run(&sub, &case, &s, tol(&sub, s.time_transform()));
                worst = worst.max(e);
                worst_t = worst_t.max(t);
                worst_p = worst_p.max(p);
            }
            eprintln!(
                "{} rtol {:e}, {} (time transform {}): largest scaled error {worst:.2e}, \
                 stick time {worst_t:.2e} tau, p(t_stick) {worst_p:.2e} P",
                s.method(),
                s.rtol(),
                sub.name,
                s.time_transform()
            );
        }
    }
}

/// The requirement on every profile, and the proof that our use of `ode_solvers`' Dop853
/// (whose nodes c12, c13 are wrong for right-hand sides that read the time) is right: at
/// rtol 1e-12 every profile, sliding or sticking early, mid-pulse or late, with the time
/// transform on (and, for t^(3/2) ends, off), lands within 1e-10 (scaled) of the closed
/// form, and the stop within 1e-10 of the duration.
#[test]
fn dop853_at_rtol_1e_12_is_within_1e_10_of_the_closed_form() {
    sweep(
        settings(Method::Dop853, DOP853_RTOL, 1),
        |sub, transform| {
            if sub.exact {
                EXACT_TOL
            } else if transform {
                DOP853_TOL
            } else {
                DOP853_GRADED_TOL
            }
        },
    );
}

#[test]
fn dopri5_converges_to_the_closed_form() {
    sweep(
        settings(Method::Dopri5, DOPRI5_RTOL, 1),
        |sub, transform| {
            if sub.exact {
                EXACT_TOL
            } else if transform {
                DOPRI5_TOL
            } else {
                DOPRI5_GRADED_TOL
            }
        },
    );
}

#[test]
fn rk4_with_1000_steps_converges_to_the_closed_form() {
    for sub in subjects() {
        for s in variants(&sub, settings(Method::Rk4, 1e-10, RK4_STEPS)) {
            let mut worst = 0.0_f64;
            for case in cases() {
                let c = CollisionSpec::reference(&BALLS, &case.law, &case.pair).build();
                let want = resolve(&BALLS, &case.law, &case.pair);
                let o = solve(&c, sub.profile.as_ref(), &s, None).unwrap();
                let err = error(&case, &o, &want);
                let tol = if sub.exact {
                    RK4_EXACT_TOL
                } else if s.time_transform() {
                    RK4_SMOOTH_TOL
                } else {
                    RK4_TOL
                };
                assert!(
                    err <= tol,
                    "{} / {} (time transform {}): {err:e} > {tol:e}",
                    sub.name,
                    case.name,
                    s.time_transform()
                );
                assert_eq!(o.result.sticks, want.sticks);
                worst = worst.max(err);
            }
            eprintln!(
                "rk4 {RK4_STEPS} steps, {} (time transform {}): largest scaled error {worst:.2e}",
                sub.name,
                s.time_transform()
            );
        }
    }
}

/// Minus the least-squares slope of log(error) against log(steps), over the errors above
/// round-off (1e-13; at least two).
fn fitted_order(points: &[(u32, f64)]) -> f64 {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.1 > 1e-13)
        .map(|&(n, e)| (f64::from(n).ln(), e.ln()))
        .collect();
    assert!(pts.len() >= 2, "too few errors above round-off: {points:?}");
    let k = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / k;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / k;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    -sxy / sxx
}

/// Ends where f ~ t^n with fractional n cost rk4 its order (a step h at an end errs like
/// h^(n+1): order 2.5 for n = 3/2, and for n = 0.3 it hardly converges); in the smoothed
/// time variable (docs/model.md#the-smoothing-change-of-time-variable) it is the
/// half-sine's 4 again. Measured over 4..256 steps: 4.0 with the transform, sliding or
/// sticking; graded breakpoints without the transform 2.7-2.8 on hertz and sin^1.5, 3.5 on
/// sin^2.3, 1.0 on sin^0.7, 0.3 on sin^0.3.
#[test]
fn rk4_keeps_its_order_on_algebraic_ends_with_the_time_transform() {
    let steps = [4u32, 8, 16, 32, 64, 128, 256];
    for n in [None, Some(1.5), Some(0.7), Some(2.3), Some(0.3)] {
        let profile: Box<dyn ForceProfile> = match n {
            None => Box::new(Hertz::new(TAU).unwrap()),
            Some(n) => Box::new(SinePower::new(TAU, n).unwrap()),
        };
        let name = n.map_or("hertz".to_string(), |n| format!("sine-power {n}"));
        for case in cases() {
            let c = CollisionSpec::reference(&BALLS, &case.law, &case.pair).build();
            let want = resolve(&BALLS, &case.law, &case.pair);
            let run = |transform: bool| -> Vec<(u32, f64)> {
                steps
                    .iter()
                    .map(|&k| {
                        let s = settings(Method::Rk4, 1e-10, k).with_time_transform(transform);
                        let o = solve(&c, profile.as_ref(), &s, None).unwrap();
                        (k, error(&case, &o, &want))
                    })
                    .collect()
            };
            let (on, off) = (fitted_order(&run(true)), fitted_order(&run(false)));
            eprintln!(
                "rk4 {name} {}: order {on:.2} (transform), {off:.2} (graded)",
                case.name
            );
            assert!(on >= TRANSFORMED_ORDER, "{name} {}: order {on}", case.name);
            // Without the transform the order is about n + 1 (a little above, before the
            // asymptotic regime).
            let end = n.unwrap_or(1.5);
            assert!(off <= end + 1.5, "{name} {}: graded order {off}", case.name);
        }
    }
}

/// In the smoothed time variable the impulse follows the half-sine's, and eqs 14-19 see
/// the force only through the impulse (docs/model.md#the-smoothing-change-of-time-variable):
/// an adaptive method takes the half-sine's steps on a hertz or sin^n pulse, the same number
/// of evaluations, and lands as close to the closed form (the same error up to round-off:
/// measured equal to the last bit on these cases). Each run's own distance to the
/// independent resolution is held to the tolerance's level as well (ten times the worst
/// measured, 0.22 rtol).
#[test]
fn algebraic_ends_cost_what_the_half_sine_costs_with_the_transform() {
    let half_sine = HalfSine::new(TAU).unwrap();
    let pulses: Vec<(&str, Box<dyn ForceProfile>)> = vec![
        ("hertz", Box::new(Hertz::new(TAU).unwrap())),
        (
            "sine-power 1.5",
            Box::new(SinePower::new(TAU, 1.5).unwrap()),
        ),
        (
            "sine-power 0.3",
            Box::new(SinePower::new(TAU, 0.3).unwrap()),
        ),
    ];
    let mut worst = std::collections::BTreeMap::new();
    for case in cases() {
        let c = CollisionSpec::reference(&BALLS, &case.law, &case.pair).build();
        let want = resolve(&BALLS, &case.law, &case.pair);
        for method in [Method::Dopri5, Method::Dop853] {
            for rtol in [1e-6, 1e-10] {
                let s = settings(method, rtol, 1000);
                let base = solve(&c, &half_sine, &s, None).unwrap();
                let base_err = error(&case, &base, &want);
                for (name, pulse) in &pulses {
                    let o = solve(&c, pulse.as_ref(), &s, None).unwrap();
                    let err = error(&case, &o, &want);
                    let what = format!("{name} {method:?} rtol {rtol:e} {}", case.name);
                    assert_eq!(o.stats, base.stats, "{what}");
                    assert!(
                        (err - base_err).abs() <= 1e-14,
                        "{what}: {err:e} vs {base_err:e}"
                    );
                    // Measured worst 0.22 rtol (dopri5 at 1e-10).
                    assert!(err <= 2.0 * rtol, "{what}: {err:e}");
                    let w = worst
                        .entry(format!("{method:?} rtol {rtol:e}"))
                        .or_insert(0.0_f64);
                    *w = w.max(err / rtol);
                }
            }
        }
    }
    for (k, w) in worst {
        eprintln!("{k}: largest scaled error {w:.2e} rtol");
    }
}

/// Classical RK4 on the half-sine: doubling the steps divides the error by 2^4, sliding
/// or sticking (the stop is located by re-stepping with the same method).
#[test]
fn rk4_observed_order_is_four_on_the_half_sine() {
    let profile = HalfSine::new(TAU).unwrap();
    for case in cases() {
        let c = CollisionSpec::reference(&BALLS, &case.law, &case.pair).build();
        let want = resolve(&BALLS, &case.law, &case.pair);
        let errs: Vec<f64> = [16, 32, 64, 128]
            .iter()
            .map(|&n| {
                let o = solve(&c, &profile, &settings(Method::Rk4, 1e-10, n), None).unwrap();
                error(&case, &o, &want)
            })
            .collect();
        let orders: Vec<f64> = errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
        eprintln!(
            "rk4 half-sine {}: errors {errs:?}, orders {orders:.2?}",
            case.name
        );
        for p in orders {
            assert!((p - 4.0).abs() <= ORDER_MARGIN, "{}: order {p}", case.name);
        }
    }
}

/// A constant force makes the sliding right-hand side constant: RK4 is exact with any
/// number of steps, one included, and so is the located stop (g is affine in t).
#[test]
fn rk4_is_exact_for_the_rectangle() {
    let profile = Rectangle::new(TAU).unwrap();
    let mut worst = 0.0_f64;
    for case in cases() {
        let c = CollisionSpec::reference(&BALLS, &case.law, &case.pair).build();
        let want = resolve(&BALLS, &case.law, &case.pair);
        for n in [1, 2, 3, 7, 50] {
            let o = solve(&c, &profile, &settings(Method::Rk4, 1e-10, n), None).unwrap();
            let err = error(&case, &o, &want);
            assert!(err <= EXACT_TOL, "{} with {n} steps: {err:e}", case.name);
            if want.sticks {
                let t = o.stick_time.unwrap() / TAU;
                let q = want.p_stick.unwrap() / want.impulse;
                assert!(
                    (t - q).abs() <= EXACT_TOL,
                    "{} stop at {t} vs {q}",
                    case.name
                );
            }
            worst = worst.max(err);
        }
    }
    eprintln!("rk4 rectangle, 1 to 50 steps: largest scaled error {worst:.2e}");
}

/// Why the engine integrates in autonomous form. `ode_solvers`' Dop853 evaluates stages 12
/// and 13 at wrong times: the quadrature y' = f(x) of the half-sine force, written with the
/// time argument, misses the exact y(1) = 1 by far more than the tolerance (at 1e-8, by
/// ~5e-6 after thousands of steps; at 1e-12 the step size collapses and it gives up), while
/// the same problem with time as a state (x' = 1, what the engine does) meets the tolerance
/// in a few steps. If a future ode_solvers fixes its nodes the first assertion fails and
/// this note can go.
#[test]
fn ode_solvers_dop853_needs_the_autonomous_form() {
    struct NonAutonomous;
    impl System<f64, SVector<f64, 1>> for NonAutonomous {
        fn system(&self, x: f64, _y: &SVector<f64, 1>, dy: &mut SVector<f64, 1>) {
            dy[0] = 0.5 * PI * (PI * x).sin();
        }
    }
    struct Autonomous;
    impl System<f64, SVector<f64, 2>> for Autonomous {
        fn system(&self, _x: f64, y: &SVector<f64, 2>, dy: &mut SVector<f64, 2>) {
            dy[0] = 1.0;
            dy[1] = 0.5 * PI * (PI * y[0]).sin();
        }
    }
    /// The engine's step control, stiffness detection off (the wrong nodes trip it first),
    /// sparse output (the dense output of ode_solvers 0.6 is broken).
    fn solver<const N: usize, F: System<f64, SVector<f64, N>>>(
        f: F,
        y0: SVector<f64, N>,
        tol: f64,
    ) -> Dop853<f64, SVector<f64, N>, F> {
        Dop853::from_param(
            f,
            0.0,
            1.0,
            1.0,
            y0,
            tol,
            tol,
            0.9,
            0.0,
            0.333,
            6.0,
            1.0,
            0.0,
            100_000,
            u32::MAX,
            OutputType::Sparse,
        )
    }
    for tol in [1e-8, 1e-12] {
        let mut na = solver(NonAutonomous, SVector::from([0.0]), tol);
        let na_result = na.integrate();
        let err_na = (na.y_out().last().unwrap()[0] - 1.0).abs();
        let mut au = solver(Autonomous, SVector::from([0.0, 0.0]), tol);
        let au_stats = au.integrate().unwrap();
        let err_au = (au.y_out().last().unwrap()[1] - 1.0).abs();
        eprintln!(
            "ode_solvers Dop853 at tol {tol:e}: non-autonomous {na_result:?}, error {err_na:.2e}; \
             autonomous {au_stats:?}, error {err_au:.2e}"
        );
        assert!(
            err_au <= 10.0 * tol,
            "autonomous form at {tol:e}: {err_au:e}"
        );
        assert!(
            na_result.is_err() || err_na >= 100.0 * tol,
            "non-autonomous form now accurate at {tol:e}: {err_na:e}"
        );
    }
}

/// The references in `common` against known values, so the tests above rest on checked
/// ground: the Hertz quadrature against the Beta function and a direct integration of the
/// Hertz equation, the sin^n quadrature against its Beta total and the half-sine.
#[test]
fn independent_references_agree_with_known_values() {
    // F(1) = (2/5) B(2/5, 1/2); contact time (4/5) B(2/5, 1/2) = 2.9432752... (docs/model.md).
    let b = common::beta_fn(0.4, 0.5);
    assert!((common::hertz_half() - 0.4 * b).abs() <= 1e-14);
    assert!((0.8 * b - 2.943_275_2).abs() <= 1e-7);
    // delta'' = -delta^(3/2), delta(0) = 0, delta'(0) = 1 by classical RK4: at each time the
    // impulse fraction (1 - delta')/2 must be reached at that time.
    let delta_max = 1.25_f64.powf(0.4);
    let total = 2.0 * delta_max * common::hertz_half();
    let n = 20_000;
    let h = total / n as f64;
    let rhs = |y: [f64; 2]| [y[1], -y[0].max(0.0).powf(1.5)];
    let mut y = [0.0, 1.0];
    let mut worst = 0.0_f64;
    for i in 1..=n {
        let k1 = rhs(y);
        let k2 = rhs([y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]]);
        let k3 = rhs([y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]]);
        let k4 = rhs([y[0] + h * k3[0], y[1] + h * k3[1]]);
        for j in 0..2 {
            y[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
        }
        if i % 500 == 0 && i < n {
            let s = i as f64 / n as f64;
            let q = 0.5 * (1.0 - y[1]);
            // Compare in impulse (the time is ill-conditioned where the force is small).
            worst = worst.max((common::invert(common::hertz_time, s) - q).abs());
        }
    }
    eprintln!("Hertz reference against the Hertz ODE (RK4, {n} steps): {worst:.2e} in p/P");
    assert!(worst <= 1e-12, "Hertz reference vs ODE: {worst:e}");
    assert!(
        (y[1] + 1.0).abs() <= 1e-9,
        "the balls leave with the reversed speed"
    );
    // sin^n: total, symmetry, n = 1 is the half-sine, the peak c for n = 1.5.
    assert!((common::sine_power_fraction(1.5, 0.5) - 0.5).abs() <= 1e-15);
    for s in [0.05, 0.3, 0.5, 0.77, 0.99] {
        let d = common::sine_power_fraction(1.0, s) - common::half_sine_fraction(s);
        assert!(d.abs() <= 1e-15, "sin^1 at {s}: {d:e}");
    }
    let c = PI / common::beta_fn(1.25, 0.5);
    assert!((c - 1.797_210_4).abs() <= 1e-7);
    // The table: p(1) = P, non-decreasing, inverse round trip.
    let table = Table::read(&table_path());
    assert_eq!(table.fraction(1.0), 1.0);
    let mut last = 0.0;
    for i in 0..=100 {
        let s = i as f64 / 100.0;
        let q = table.fraction(s);
        assert!(q >= last);
        last = q;
        if q > 0.0 && q < 1.0 {
            assert!((table.fraction(table.time(q)) - q).abs() <= 1e-15);
        }
    }
}
