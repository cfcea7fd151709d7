//! Stick times under the half-sine pulse against the exact time.
//!
//! f(t) = (pi P / (2 tau)) sin(pi t / tau) gives p(t) = (P/2)(1 - cos(pi t/tau)) =
//! P sin^2(pi t / (2 tau)) (the second form keeps its digits at small t). Sliding stops at
//! p_stick = m S(0) / (2 mu (1 + 1/alpha)) (docs/model.md#when-sliding-stops-during-contact), so at
//! t_stick = (2 tau / pi) asin(sqrt(p_stick / P)) (docs/model.md#the-exact-state-during-the-contact).
//! |p(t_stick) - p_stick| <= 1e-10 P always; |t - t_stick| <= 1e-10 tau wherever
//! f(t_stick) >= 1e-3 P / tau.

use crate::common::collision::CollisionSpec;
use billiard_contact::profile::HalfSine;
use billiard_contact::TraceRow;
use billiard_contact::{solve, CmState};
use billiard_contact::{Method, Sampling, SolverSettings};
use nalgebra::Vector3;
use std::f64::consts::PI;

const TAU: f64 = 2.5e-4;
const M: f64 = 0.17;
const R: f64 = 0.028575;
const ALPHA: f64 = 0.4;
/// Event accuracy (docs/model.md#locating-the-stop-of-sliding), in the impulse (always) and in time (where f is not small).
const STICK_IMPULSE_TOL: f64 = 1e-10;
const STICK_TIME_TOL: f64 = 1e-10;
/// Where the time criterion applies: f(t_stick) >= 1e-3 P / tau.
const FORCE_FLOOR: f64 = 1e-3;
/// The closed-form method takes the time from the profile's exact inverse.
const CLOSED_FORM_TIME_TOL: f64 = 1e-13;

/// Exact stick time over tau for p_stick / P = q.
fn t_exact(q: f64) -> f64 {
    2.0 / PI * q.sqrt().asin()
}

/// p(t)/P of the half-sine at s = t / tau.
fn p_fraction(s: f64) -> f64 {
    let h = (0.5 * PI * s).sin();
    h * h
}

/// Normalised force f tau / P at s.
fn force(s: f64) -> f64 {
    0.5 * PI * (PI * s).sin()
}

struct Shot {
    what: String,
    incoming: CmState,
    mu: f64,
    e: f64,
}

impl Shot {
    /// (S(0), P, p_stick) from the definitions: S(0) = |(2V + r Omega_z, 2W - r Omega_y)|
    /// (eqs 5-6), P = (1 + e) m U(0).
    fn exact(&self) -> (f64, f64, f64) {
        let s = &self.incoming;
        let o = s.omega_a + s.omega_b;
        let s0 = (2.0 * s.u_cm.y + R * o.z).hypot(2.0 * s.u_cm.z - R * o.y);
        let p = (1.0 + self.e) * M * s.u_cm.x;
        (s0, p, M * s0 / (2.0 * self.mu * (1.0 + 1.0 / ALPHA)))
    }
}

/// Stun cuts (no spin, B at rest): A at speed v and cut angle c has U(0) = v cos(c)/2 and
/// S(0) = v sin(c), so p_stick / P = tan(c) / (mu (1 + e)(1 + 1/alpha)): with mu = 0.06,
/// e = 1 that is tan(c) / 0.42, and every cut below 22.8 degrees sticks, the thinner the
/// later.
fn stun_cuts() -> Vec<Shot> {
    let mut v = Vec::new();
    for (deg, mu, e) in [
        (0.05, 0.06, 1.0),
        (0.5, 0.06, 1.0),
        (5.0, 0.06, 1.0),
        (12.0, 0.06, 1.0),
        (20.0, 0.06, 1.0),
        (22.7, 0.06, 1.0),
        (10.0, 0.06, 0.5),
        (30.0, 0.2, 1.0),
        (60.0, 0.5, 0.8),
    ] {
        let c: f64 = f64::to_radians(deg);
        let speed = 1.7;
        v.push(Shot {
            what: format!("stun cut {deg} deg, mu {mu}, e {e}"),
            incoming: CmState::new(
                Vector3::new(0.5 * speed * c.cos(), 0.5 * speed * c.sin(), 0.0),
                Vector3::zeros(),
                Vector3::zeros(),
            ),
            mu,
            e,
        });
    }
    v
}

/// Spinning states whose side and vertical velocities are chosen so that the stop falls at
/// a prescribed fraction q of the impulse: the slip S(0) (cos phi, sin phi) =
/// (2V + r Omega_z, 2W - r Omega_y) with S(0) = 2 mu (1 + 1/alpha) q P / m.
fn spinning(q_targets: &[f64]) -> Vec<Shot> {
    // (U(0), Omega^A, Omega^B, phi, mu, e)
    let states = [
        (
            1.2,
            Vector3::new(5.0, -10.0, 20.0),
            Vector3::new(-3.0, 8.0, 2.0),
            2.0,
            0.06,
            0.9,
        ),
        (
            0.4,
            Vector3::new(0.0, -30.0, 4.0),
            Vector3::new(1.0, 0.0, -6.0),
            -0.7,
            0.3,
            1.0,
        ),
    ];
    let mut v = Vec::new();
    for (i, &(u0, wa, wb, phi, mu, e)) in states.iter().enumerate() {
        for &q in q_targets {
            let p = (1.0 + e) * M * u0;
            let s0 = 2.0 * mu * (1.0 + 1.0 / ALPHA) * q * p / M;
            let o: Vector3<f64> = wa + wb;
            let vy = 0.5 * (s0 * f64::cos(phi) - R * o.z);
            let wz = 0.5 * (s0 * f64::sin(phi) + R * o.y);
            v.push(Shot {
                what: format!("spinning state {i}, stop at q = {q}"),
                incoming: CmState::new(Vector3::new(u0, vy, wz), wa, wb),
                mu,
                e,
            });
        }
    }
    v
}

fn dop853() -> SolverSettings {
    SolverSettings::new(Method::Dop853, 1e-12, 1e-12, 1).unwrap()
}

/// Runs a shot and checks the stop; returns (time error / tau or 0 where the time
/// criterion does not apply, impulse error / P).
fn check(shot: &Shot, settings: &SolverSettings) -> (f64, f64) {
    let c = CollisionSpec::ball(M, R, ALPHA)
        .mu(shot.mu)
        .restitution(shot.e)
        .incoming(shot.incoming)
        .build();
    let (_, p, p_stick) = shot.exact();
    assert!(p_stick < p, "{}: must stick", shot.what);
    let q = p_stick / p;
    let o = solve(&c, &HalfSine::new(TAU).unwrap(), settings, None).unwrap();
    assert!(o.result.sticks, "{}", shot.what);
    let t = o.stick_time.unwrap() / TAU;
    let dp = (p_fraction(t) - q).abs();
    assert!(
        dp <= STICK_IMPULSE_TOL,
        "{} ({}): p(t_stick)/P = {}, p_stick/P = {q}",
        shot.what,
        settings.method(),
        p_fraction(t)
    );
    // The reported stick impulse is the impulse at the reported time.
    assert!((o.result.stick_impulse.unwrap() / p - q).abs() <= STICK_IMPULSE_TOL);
    let exact = t_exact(q);
    let dt = (t - exact).abs();
    if force(exact) >= FORCE_FLOOR {
        assert!(
            dt <= STICK_TIME_TOL,
            "{} ({}): t/tau = {t}, exact {exact}, error {dt:e}",
            shot.what,
            settings.method()
        );
        (dt, dp)
    } else {
        (0.0, dp)
    }
}

#[test]
fn stun_cut_stick_times_match_the_half_sine_formula() {
    let (mut wt, mut wp) = (0.0_f64, 0.0_f64);
    for shot in stun_cuts() {
        let (_, p, p_stick) = shot.exact();
        eprintln!(
            "{}: stops at q = {:.3e}, t/tau = {:.4}",
            shot.what,
            p_stick / p,
            t_exact(p_stick / p)
        );
        let (dt, dp) = check(&shot, &dop853());
        wt = wt.max(dt);
        wp = wp.max(dp);
    }
    eprintln!(
        "stun cuts, dop853 rtol 1e-12: largest |t - t_exact| {wt:.2e} tau, \
         |p - p_stick| {wp:.2e} P"
    );
}

#[test]
fn stops_early_middle_and_late_in_the_pulse() {
    let targets = [1e-10, 1e-6, 1e-3, 0.05, 0.3, 0.5, 0.7, 0.95, 0.9999];
    for settings in [
        dop853(),
        SolverSettings::new(Method::Dopri5, 1e-12, 1e-12, 1).unwrap(),
    ] {
        let (mut wt, mut wp) = (0.0_f64, 0.0_f64);
        for shot in spinning(&targets) {
            let (dt, dp) = check(&shot, &settings);
            wt = wt.max(dt);
            wp = wp.max(dp);
        }
        eprintln!(
            "spinning states, {} rtol 1e-12: largest |t - t_exact| {wt:.2e} tau, \
             |p - p_stick| {wp:.2e} P",
            settings.method()
        );
    }
}

/// The closed-form method reports the exact time from the profile's inverse.
#[test]
fn closed_form_method_reports_the_exact_stick_time() {
    let settings = SolverSettings::default().with_method(Method::ClosedForm);
    for shot in stun_cuts()
        .into_iter()
        .chain(spinning(&[1e-10, 0.2, 0.5, 0.999]))
    {
        let (_, p, p_stick) = shot.exact();
        let o = solve(
            &CollisionSpec::ball(M, R, ALPHA)
                .mu(shot.mu)
                .restitution(shot.e)
                .incoming(shot.incoming)
                .build(),
            &HalfSine::new(TAU).unwrap(),
            &settings,
            None,
        )
        .unwrap();
        let t = o.stick_time.unwrap() / TAU;
        let exact = t_exact(p_stick / p);
        assert!(
            (t - exact).abs() <= CLOSED_FORM_TIME_TOL * exact.max(1e-3),
            "{}: {t} vs {exact}",
            shot.what
        );
    }
}

/// The stop appears in the trace once, at the reported time, with S = 0 from there on and
/// the impulse p_stick; before it S > 0; times increase. With samples, every other row is at
/// i tau / N; a stop within 1e-9 tau of a sample time (docs/formats.md#trace-csv: "written
/// once") takes that sample's place, so the trace has N + 1 rows, else N + 2. The shots
/// stopping at q = 0.5 stop at t = tau / 2 (the half-sine's p(t) = P sin^2(pi t / (2 tau))),
/// the middle one of the 40 sample times; the integrators locate it within round-off of it,
/// before or after.
#[test]
fn the_stop_is_one_trace_row() {
    let samples = 40u64;
    let sample_t = |i: u64| i as f64 * TAU / samples as f64;
    let methods = [
        SolverSettings::default().with_method(Method::ClosedForm),
        SolverSettings::new(Method::Rk4, 1e-10, 1e-10, 1000).unwrap(),
        SolverSettings::new(Method::Dopri5, 1e-12, 1e-12, 1).unwrap(),
        dop853(),
    ];
    let mut on_samples = 0;
    for settings in &methods {
        for shot in spinning(&[0.3, 0.5])
            .into_iter()
            .chain(stun_cuts().into_iter().take(4))
        {
            let (_, p, p_stick) = shot.exact();
            let what = format!("{} with {}", shot.what, settings.method());
            for sampling in [Sampling::Steps, Sampling::Uniform(samples)] {
                let mut rows: Vec<TraceRow> = Vec::new();
                let o = solve(
                    &CollisionSpec::ball(M, R, ALPHA)
                        .mu(shot.mu)
                        .restitution(shot.e)
                        .incoming(shot.incoming)
                        .build(),
                    &HalfSine::new(TAU).unwrap(),
                    settings,
                    Some((&mut rows, sampling)),
                )
                .unwrap();
                let t_stick = o.stick_time.unwrap();
                let at: Vec<&TraceRow> = rows.iter().filter(|r| r.t == t_stick).collect();
                assert_eq!(at.len(), 1, "{what}: stop rows {}", at.len());
                assert_eq!(at[0].slip_speed, 0.0);
                assert!((at[0].impulse - p_stick).abs() <= STICK_IMPULSE_TOL * p);
                for r in &rows {
                    if r.t < t_stick {
                        assert!(r.slip_speed > 0.0, "{what}: S = 0 before the stop");
                    } else {
                        // 0.0 itself: a -0.0 would be written "-0.0" in the CSV.
                        assert_eq!(r.slip_speed.to_bits(), 0, "{what}: S after the stop");
                    }
                }
                assert!(
                    rows.windows(2).all(|w| w[0].t < w[1].t),
                    "{what}: time increases"
                );
                if sampling == Sampling::Steps {
                    continue;
                }
                let on_sample = (0..=samples).any(|i| (t_stick - sample_t(i)).abs() <= 1e-9 * TAU);
                on_samples += usize::from(on_sample);
                let want = samples + if on_sample { 1 } else { 2 };
                assert_eq!(rows.len() as u64, want, "{what}: rows");
                // Every sample time once, in order, but the one the stop takes the place of.
                let mut i = 0;
                for r in &rows {
                    if r.t == t_stick {
                        i += u64::from(on_sample);
                        continue;
                    }
                    assert_eq!(r.t, sample_t(i), "{what}: row {i}");
                    i += 1;
                }
                assert_eq!(i, samples + 1, "{what}: samples");
            }
        }
    }
    // The two q = 0.5 shots under each method.
    assert_eq!(on_samples, 2 * methods.len());
}
