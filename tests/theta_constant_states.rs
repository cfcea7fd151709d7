//! theta stays constant while the balls slide (eq 23), to 1e-12, over many states, every
//! profile and every time-stepping method.
//!
//! The right-hand side takes the friction direction from the current slip at every
//! evaluation (docs/formats.md), so a constant theta is a property the run must show, not one it
//! assumes. Two measurements: the run's own `check.theta_drift` (max |slip x e0| / v_ref
//! over accepted steps while sliding), and, independently, every trace row before the stop:
//! the slip recomputed from the row's velocities and spins, (2V + r Omega_z, 2W - r Omega_y)
//! (eqs 5-6), and the row's own (S, theta) columns, both against the incoming direction.

use crate::common;

use billiard_contact::profile::{HalfSine, Hertz, Profile, Rectangle, SinePower, Tabulated};
use billiard_contact::Effects;
use billiard_contact::TraceRow;
use billiard_contact::{solve, Ball, CmState, Collision, Contact, Friction, ImpulseRule};
use billiard_contact::{Method, Sampling, SolverSettings};
use common::Rng;
use nalgebra::Vector3;
use std::path::PathBuf;

/// Theta constant to 1e-12 (scaled by v_ref).
const THETA_TOL: f64 = 1e-12;
const STATES: usize = 400;
const TAU: f64 = 2.5e-4;

fn profiles() -> Vec<Profile> {
    let table = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data/profiles/measured_pulse.csv");
    vec![
        Profile::HalfSine(HalfSine::new(TAU).unwrap()),
        Profile::Hertz(Hertz::new(TAU).unwrap()),
        Profile::SinePower(SinePower::new(TAU, 1.5).unwrap()),
        Profile::Rectangle(Rectangle::new(TAU).unwrap()),
        Profile::Tabulated(Tabulated::from_csv_file(&table, Some(TAU)).unwrap()),
    ]
}

/// A random approaching collision: sizes over orders of magnitude, constant or
/// speed-dependent friction, stick on or off, e in [0, 1].
fn random_collision(rng: &mut Rng) -> Collision {
    let r = rng.log_range(1e-3, 0.3);
    let speed = rng.log_range(1e-2, 30.0);
    // Half the states with small side speeds and spins, so that about half of them stick.
    let side = if rng.below(2) == 0 {
        0.03 * speed
    } else {
        speed
    };
    let u = Vector3::new(
        speed * rng.range(0.05, 1.0),
        rng.range(-side, side),
        rng.range(-side, side),
    );
    let spin = 2.0 * side / r;
    let friction = if rng.below(4) == 0 {
        Friction::speed_dependent(9.951e-3, 0.108, 1.088).unwrap()
    } else {
        Friction::constant(rng.log_range(0.01, 0.8)).unwrap()
    };
    Collision::new(
        Ball::new(rng.log_range(0.05, 5.0), r, rng.range(0.1, 2.0 / 3.0)).unwrap(),
        Contact {
            friction,
            impulse: ImpulseRule::restitution(rng.unit()).unwrap(),
        },
        Effects {
            friction: true,
            stick: rng.below(5) != 0,
            table: false,
        },
        CmState::new(u, rng.vector(spin), rng.vector(spin)),
    )
    .unwrap()
}

/// Independent drift measurements over the rows before the stop: the slip recomputed from
/// the state, and the (S, theta) columns, against e0; both over v_ref.
fn row_drift(c: &Collision, rows: &[TraceRow], stop: Option<f64>) -> (f64, f64) {
    let r = c.balls.a.radius();
    let v_ref = c.scales.speed;
    let e0 = c.direction.expect("sliding");
    let th0 = c.theta().unwrap();
    let (mut from_state, mut from_columns) = (0.0_f64, 0.0_f64);
    for row in rows.iter().filter(|row| stop.is_none_or(|t| row.t < t)) {
        let s = &row.state;
        let o = s.omega_a + s.omega_b;
        let slip = (2.0 * s.u_cm.y + r * o.z, 2.0 * s.u_cm.z - r * o.y);
        from_state = from_state.max((slip.0 * e0.y - slip.1 * e0.x).abs() / v_ref);
        let th = row.theta.expect("theta while sliding");
        from_columns = from_columns.max((row.slip_speed * (th - th0).sin()).abs() / v_ref);
    }
    (from_state, from_columns)
}

#[test]
fn theta_is_constant_while_sliding() {
    let mut rng = Rng::new(0x7e7a_0001);
    let profiles = profiles();
    let methods = [
        SolverSettings::new(Method::Dop853, 1e-12, 1e-12, 1).unwrap(),
        SolverSettings::new(Method::Dop853, 1e-6, 1e-6, 1).unwrap(),
        SolverSettings::new(Method::Dopri5, 1e-9, 1e-9, 1).unwrap(),
        SolverSettings::new(Method::Rk4, 1e-10, 1e-10, 200).unwrap(),
    ];
    let (mut own, mut state, mut columns) = (0.0_f64, 0.0_f64, 0.0_f64);
    let (mut n_stick, mut n_rows) = (0, 0);
    for i in 0..STATES {
        let c = random_collision(&mut rng);
        let profile = &profiles[i % profiles.len()];
        let settings = &methods[(i / profiles.len()) % methods.len()];
        let mut rows: Vec<TraceRow> = Vec::new();
        let o = solve(&c, profile, settings, Some((&mut rows, Sampling::Steps))).unwrap();
        let what = format!(
            "state {i}, {}, {} rtol {:e}",
            profile.name(),
            settings.method(),
            settings.rtol()
        );
        assert!(
            o.check.theta_drift <= THETA_TOL,
            "{what}: theta_drift {:e}",
            o.check.theta_drift
        );
        let stop = o.stick_time.filter(|_| c.effects.stick);
        let (a, b) = row_drift(&c, &rows, stop);
        assert!(
            a <= THETA_TOL,
            "{what}: slip from the state drifts by {a:e}"
        );
        assert!(b <= THETA_TOL, "{what}: (S, theta) columns drift by {b:e}");
        // theta is reported unchanged.
        assert_eq!(o.result.theta, c.theta());
        own = own.max(o.check.theta_drift);
        state = state.max(a);
        columns = columns.max(b);
        n_stick += usize::from(o.result.sticks);
        n_rows += rows.len();
    }
    eprintln!(
        "theta over {STATES} states ({n_stick} stick, {n_rows} trace rows): check.theta_drift \
         {own:.2e}, from the state {state:.2e}, from the columns {columns:.2e}"
    );
    assert!(
        n_stick > STATES / 10 && n_stick < STATES - STATES / 10,
        "{n_stick} stick"
    );
}

/// Slip exactly along a tilted direction at a small fraction of v_ref, where rounding in
/// the velocities and spins is largest relative to the slip, up to the stop.
#[test]
fn theta_is_constant_for_small_oblique_slip() {
    for (k, phi) in [0.3_f64, 1.9, -2.6].iter().enumerate() {
        let (r, s0) = (0.028575, 1e-3 * (k + 1) as f64);
        let wa = Vector3::new(10.0, -35.0, 12.0);
        let wb = Vector3::new(-4.0, 9.0, 30.0);
        let o = wa + wb;
        // 2V + r Omega_z = S0 cos(phi), 2W - r Omega_y = S0 sin(phi).
        let u = Vector3::new(
            1.3,
            0.5 * (s0 * phi.cos() - r * o.z),
            0.5 * (s0 * phi.sin() + r * o.y),
        );
        let c = Collision::new(
            Ball::new(0.17, r, 0.4).unwrap(),
            Contact {
                friction: Friction::constant(0.06).unwrap(),
                impulse: ImpulseRule::restitution(1.0).unwrap(),
            },
            Effects::default(),
            CmState::new(u, wa, wb),
        )
        .unwrap();
        for settings in [
            SolverSettings::new(Method::Dop853, 1e-12, 1e-12, 1).unwrap(),
            SolverSettings::new(Method::Dopri5, 1e-12, 1e-12, 1).unwrap(),
            SolverSettings::new(Method::Rk4, 1e-10, 1e-10, 1000).unwrap(),
        ] {
            let mut rows: Vec<TraceRow> = Vec::new();
            let out = solve(
                &c,
                &HalfSine::new(TAU).unwrap(),
                &settings,
                Some((&mut rows, Sampling::Uniform(50))),
            )
            .unwrap();
            assert!(out.result.sticks);
            let (a, b) = row_drift(&c, &rows, out.stick_time);
            assert!(out.check.theta_drift <= THETA_TOL && a <= THETA_TOL && b <= THETA_TOL);
        }
    }
}
