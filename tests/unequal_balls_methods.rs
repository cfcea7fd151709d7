//! Balls of different mass, radius and alpha through every method and every force profile,
//! against the closed form (itself checked against first principles in
//! unequal_balls_closed_form.rs): dop853 at rtol 1e-12 within 1e-10 (scaled), dopri5 and
//! rk4 at their usual settings, sliding throughout, sliding that stops during the contact
//! (also with speed-dependent mu) and friction that keeps acting past the stop
//! (`stick = false`). The runs' own conservation checks hold to round-off.

use crate::common;

use billiard_contact::profile::ForceProfile;
use billiard_contact::profile::{HalfSine, Hertz, Rectangle, SinePower, Tabulated};
use billiard_contact::{solve, CmState, Effects, Friction, Method, SolverSettings};
use common::amax;
use common::collision::CollisionSpec;
use nalgebra::Vector3;
use std::path::PathBuf;

const TAU: f64 = 2.5e-4;

fn profiles() -> Vec<(&'static str, Box<dyn ForceProfile>)> {
    let table = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data/profiles/measured_pulse.csv");
    vec![
        ("half-sine", Box::new(HalfSine::new(TAU).unwrap())),
        ("hertz", Box::new(Hertz::new(TAU).unwrap())),
        (
            "sine-power 1.5",
            Box::new(SinePower::new(TAU, 1.5).unwrap()),
        ),
        ("rectangle", Box::new(Rectangle::new(TAU).unwrap())),
        (
            "tabulated",
            Box::new(Tabulated::from_csv_file(&table, Some(TAU)).unwrap()),
        ),
    ]
}

/// The bar-table pair, each (mass (kg), radius (m), alpha): a heavier, larger cue ball A and
/// an object ball B of another alpha.
const BALL_A: (f64, f64, f64) = (0.184, 0.030163, 0.4);
const BALL_B: (f64, f64, f64) = (0.17, 0.028575, 0.35);

struct Case {
    name: &'static str,
    state: CmState,
    friction: Friction,
    stick: bool,
    /// Whether the closed form says sliding stops during the contact.
    sticks: bool,
}

fn cases() -> Vec<Case> {
    let v = Vector3::new;
    let constant = Friction::constant(0.06).unwrap();
    vec![
        Case {
            name: "slides throughout",
            state: CmState::new(v(1.0, 0.3, -0.2), v(5.0, -10.0, 20.0), v(-3.0, 8.0, 2.0)),
            friction: constant,
            stick: true,
            sticks: false,
        },
        Case {
            name: "sticks early",
            state: CmState::new(v(1.0, 0.05, 0.02), v(3.0, 1.0, -2.0), v(0.0, -1.0, 0.5)),
            friction: constant,
            stick: true,
            sticks: true,
        },
        Case {
            name: "sticks mid-pulse",
            state: CmState::new(v(1.0, 0.2, 0.05), v(0.0, 0.0, 0.0), v(0.0, 2.0, 1.0)),
            friction: constant,
            stick: true,
            sticks: true,
        },
        Case {
            name: "speed-dependent mu, sticks",
            state: CmState::new(v(1.0, 0.2, 0.05), v(0.0, 0.0, 0.0), v(0.0, 2.0, 1.0)),
            friction: Friction::speed_dependent(9.951e-3, 0.108, 1.088).unwrap(),
            stick: true,
            sticks: true,
        },
        Case {
            name: "no stick rule: friction past the stop",
            state: CmState::new(v(1.0, 0.2, 0.05), v(0.0, 0.0, 0.0), v(0.0, 2.0, 1.0)),
            friction: constant,
            stick: false,
            sticks: false,
        },
    ]
}

/// Runs every profile and case with `settings`; returns the largest scaled distance from
/// the closed form and the largest stick-time difference (over tau).
fn run_all(settings: &SolverSettings, tol: f64, stick_tol: f64) -> (f64, f64) {
    let exact = settings.with_method(Method::ClosedForm);
    let (mut worst, mut worst_t) = (0.0_f64, 0.0_f64);
    for (pname, profile) in profiles() {
        for case in cases() {
            let c = CollisionSpec::balls(BALL_A, BALL_B)
                .friction(case.friction)
                .restitution(0.95)
                .effects(Effects {
                    stick: case.stick,
                    ..Effects::default()
                })
                .incoming(case.state)
                .build();
            let want = solve(&c, profile.as_ref(), &exact, None).unwrap();
            assert_eq!(want.result.sticks, case.sticks, "{}", case.name);
            let got = solve(&c, profile.as_ref(), settings, None).unwrap();
            let sc = c.scales;
            let err = (amax(&(got.result.out.u_cm - want.result.out.u_cm)) / sc.speed)
                .max(amax(&(got.result.out.omega_a - want.result.out.omega_a)) / sc.spin)
                .max(amax(&(got.result.out.omega_b - want.result.out.omega_b)) / sc.spin)
                .max((got.result.heat - want.result.heat).abs() / sc.energy)
                .max((got.result.heat_sliding - want.result.heat_sliding).abs() / sc.energy);
            let what = format!("{pname} / {} / {}", case.name, settings.method());
            assert!(err <= tol, "{what}: {err:e}");
            assert_eq!(got.result.sticks, want.result.sticks, "{what}");
            if let (Some(a), Some(b)) = (got.stick_time, want.stick_time) {
                let dt = (a - b).abs() / TAU;
                assert!(dt <= stick_tol, "{what}: stick time {dt:e} tau");
                worst_t = worst_t.max(dt);
            }
            // Angular momentum holds to round-off for every method; A's momentum change
            // against the applied impulses P e_x + J e (J along e0, so a drift of the
            // direction shows), the energy balance and the carried slip within the
            // method's tolerance.
            let ch = got.check;
            for (name, x, bound) in [
                ("momentum", ch.momentum_error, tol),
                ("angular momentum", ch.angular_momentum_error, 1e-13),
                ("energy balance", ch.energy_balance_error, tol),
                ("slip consistency", ch.slip_consistency, tol),
            ] {
                assert!(x <= bound, "{what}: {name} {x:e}");
            }
            worst = worst.max(err);
        }
    }
    (worst, worst_t)
}

#[test]
fn dop853_at_rtol_1e_12_is_within_1e_10_of_the_closed_form() {
    let s = SolverSettings::new(Method::Dop853, 1e-12, 1e-12, 1).unwrap();
    let (e, t) = run_all(&s, 1e-10, 1e-10);
    println!("dop853 rtol 1e-12: largest scaled error {e:e}, stick time {t:e} tau");
}

#[test]
fn dopri5_at_rtol_1e_10_is_close_to_the_closed_form() {
    let s = SolverSettings::new(Method::Dopri5, 1e-10, 1e-10, 1).unwrap();
    let (e, t) = run_all(&s, 1e-8, 1e-8);
    println!("dopri5 rtol 1e-10: largest scaled error {e:e}, stick time {t:e} tau");
}

#[test]
fn rk4_with_2000_steps_is_close_to_the_closed_form() {
    let s = SolverSettings::new(Method::Rk4, 1e-10, 1e-10, 2000).unwrap();
    let (e, t) = run_all(&s, 1e-6, 1e-6);
    println!("rk4 2000 steps: largest scaled error {e:e}, stick time {t:e} tau");
}
