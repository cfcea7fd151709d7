//! The library's closed form against an independent first-principles resolution of the
//! collision (`common::resolve`: contact-point velocities, friction opposing the slip,
//! r x F torques, J = min(mu P, m S(0) / (2 (1 + 1/alpha))) from docs/model.md#when-sliding-stops-during-contact), and against
//! the paper's own special case, eqs 59-72, written out literally below.
//!
//! All comparisons are scaled by the reference scales of docs/model.md#scales-and-scaled-errors: speeds by v_ref, spins by
//! v_ref / r, impulses by m v_ref, energies by m v_ref^2.

use crate::common;

use billiard_contact::profile::HalfSine;
use billiard_contact::run_scene;
use billiard_contact::Scene;
use billiard_contact::{solve, ClosedForm, CmState, Collision};
use billiard_contact::{Method, SolverSettings};
use common::collision::CollisionSpec;
use common::{amax, resolve, theta_cm, Balls, Expected, Law, Pair, Rng, Rule};
use nalgebra::Vector3;
use std::path::Path;

/// Scaled agreement of the library's closed form with the independent one.
const CLOSED_FORM_TOL: f64 = 1e-12;
/// Relative agreement of p_stick (a ratio of the inputs, a few roundings).
const P_STICK_REL_TOL: f64 = 1e-13;
/// Agreement of scale definitions (max of norms computed in two ways).
const SCALE_REL_TOL: f64 = 1e-14;
/// Number of random states.
const STATES: usize = 20_000;
/// Contact duration of the half-sine used with `solve` (s); any value works.
const TAU: f64 = 2.5e-4;

/// The largest scaled difference between a library state and the reference pair.
fn state_error(b: &Balls, v_ref: f64, got: &CmState, want: &Pair) -> f64 {
    let spin = v_ref / b.r;
    (amax(&(got.u_cm - want.va)) / v_ref)
        .max(amax(&(got.omega_a - want.wa)) / spin)
        .max(amax(&(got.omega_b - want.wb)) / spin)
}

struct Case {
    balls: Balls,
    law: Law,
    pair: Pair,
}

/// A random case; the distribution covers approaching and separating balls, zero and
/// large friction, e in [0, 1] with both ends, explicit impulses over [m U0, 2 m U0] with
/// both ends, stick on and off, friction off, and sizes over orders of magnitude.
fn random_case(rng: &mut Rng) -> Case {
    let alpha = match rng.below(4) {
        0 => 0.4,
        1 => 2.0 / 3.0,
        _ => rng.range(0.05, 2.0 / 3.0),
    };
    let balls = Balls {
        m: rng.log_range(0.01, 10.0),
        r: rng.log_range(1e-3, 0.5),
        alpha,
    };
    let speed = rng.log_range(1e-3, 100.0);
    let u0 = match rng.below(10) {
        0 => -speed * rng.unit(),
        1 => 0.0,
        _ => speed * rng.range(1e-3, 1.0),
    };
    let mut u = Vector3::new(u0, rng.range(-speed, speed), rng.range(-speed, speed));
    if rng.below(6) == 0 {
        u.z = 0.0;
    }
    let spin = 3.0 * speed / balls.r;
    let (wa, wb) = match rng.below(5) {
        0 => (Vector3::zeros(), Vector3::zeros()),
        1 => (rng.vector(spin), Vector3::zeros()),
        _ => (rng.vector(spin), rng.vector(spin)),
    };
    let mu = match rng.below(20) {
        0 => 0.0,
        _ => rng.log_range(1e-3, 1.5),
    };
    let rule = if rng.below(3) == 0 && u0 > 0.0 {
        let x = match rng.below(5) {
            0 => 0.0,
            1 => 1.0,
            _ => rng.unit(),
        };
        Rule::Explicit(balls.m * u0 * (1.0 + x))
    } else {
        Rule::Restitution(match rng.below(5) {
            0 => 0.0,
            1 => 1.0,
            _ => rng.unit(),
        })
    };
    let mut law = Law::new(mu, rule);
    law.stick = rng.below(10) != 0;
    law.friction = rng.below(20) != 0;
    Case {
        balls,
        law,
        pair: Pair::cm(u, wa, wb),
    }
}

/// Compares a library closed form with the reference; returns the largest scaled error.
fn compare(case: &Case, c: &Collision, cf: &ClosedForm, want: &Expected) -> f64 {
    let b = &case.balls;
    let v = case.pair.v_ref(b.r);
    let imp = b.m * v;
    let energy = b.m * v * v;
    let ctx = || format!("{:?} {:?} {:?}", b, case.law, case.pair);
    assert!(
        (c.scales.speed - v).abs() <= SCALE_REL_TOL * v,
        "v_ref {} vs {v}: {}",
        c.scales.speed,
        ctx()
    );
    assert_eq!(c.collides(), want.collision, "{}", ctx());
    let errors = [
        state_error(b, v, &cf.result.out, &want.out),
        (cf.result.impulse - want.impulse).abs() / imp,
        (cf.result.tangential_impulse - want.tangential).abs() / imp,
        (cf.result.s_out - want.s_out).abs() / v,
        (c.s0 - want.s0).abs() / v,
        (cf.result.heat - want.heat).abs() / energy,
        (cf.result.heat_sliding - want.heat_sliding).abs() / energy,
    ];
    let worst = errors.iter().cloned().fold(0.0, f64::max);
    assert!(
        worst <= CLOSED_FORM_TOL,
        "errors {errors:?} > {CLOSED_FORM_TOL}: {}",
        ctx()
    );
    // Eq 50 holds for the reference itself: H - H_sfr = 2 U0 P - P^2 / m.
    let u0 = case.pair.u0();
    let balance = want.heat - want.heat_sliding - want.impulse * (2.0 * u0 - want.impulse / b.m);
    assert!(
        balance.abs() <= CLOSED_FORM_TOL * energy,
        "eq 50: {balance:e}"
    );
    // Sliding stops: the flag is ambiguous only where mu P and J_stick agree to round-off.
    let j_stick = want.s0 * b.m / (2.0 * (1.0 + 1.0 / b.alpha));
    let near_boundary = (case.law.mu * want.impulse - j_stick).abs() <= 1e-12 * imp;
    if !near_boundary {
        assert_eq!(cf.result.sticks, want.sticks, "sticks: {}", ctx());
    }
    match (cf.result.stick_impulse, want.p_stick) {
        (Some(got), Some(p)) => assert!(
            (got - p).abs() <= P_STICK_REL_TOL * p,
            "p_stick {got} vs {p}: {}",
            ctx()
        ),
        (None, None) => {}
        (got, p) => panic!("p_stick {got:?} vs {p:?}: {}", ctx()),
    }
    // theta: compare S0 (cos, sin) with the reference slip (well conditioned at small S0).
    match (c.theta(), theta_cm(&case.pair, b.r)) {
        (Some(th), Some(_)) => {
            let slip = case.pair.slip(b.r);
            let d = (c.s0 * th.cos() - slip.y)
                .abs()
                .max((c.s0 * th.sin() - slip.z).abs());
            assert!(d <= CLOSED_FORM_TOL * v, "theta {th}: {}", ctx());
            assert!(th > -std::f64::consts::PI && th <= std::f64::consts::PI);
        }
        (None, None) => {}
        (got, want) => panic!("theta {got:?} vs {want:?}: {}", ctx()),
    }
    worst
}

#[test]
fn closed_form_matches_first_principles_over_random_states() {
    let mut rng = Rng::new(0x5eed_0001);
    let (mut worst, mut n_stick, mut n_slide, mut n_none, mut n_explicit) = (0.0_f64, 0, 0, 0, 0);
    let mut n_rejected = 0;
    for _ in 0..STATES {
        let case = random_case(&mut rng);
        let lib = CollisionSpec::reference(&case.balls, &case.law, &case.pair).try_build();
        if let Rule::Explicit(_) = case.law.rule {
            n_explicit += 1;
        }
        let c = match lib {
            Ok(c) => c,
            Err(e) => panic!("{e}: {:?} {:?}", case.law, case.pair),
        };
        let want = resolve(&case.balls, &case.law, &case.pair);
        let cf = ClosedForm::new(&c);
        worst = worst.max(compare(&case, &c, &cf, &want));
        if !want.collision {
            n_none += 1;
            // No collision: the outgoing state is the incoming one, exactly.
            assert_eq!(cf.result.out, c.incoming);
            assert_eq!(cf.result.stick_impulse, None);
            assert!(!cf.result.sticks);
        } else if want.sticks {
            n_stick += 1;
        } else if want.tangential > 0.0 {
            n_slide += 1;
        }
        // An explicit impulse with U0 <= 0 is bad input.
        if case.pair.u0() <= 0.0 {
            n_rejected += 1;
            let mut bad = case.law;
            bad.rule = Rule::Explicit(case.balls.m);
            assert!(CollisionSpec::reference(&case.balls, &bad, &case.pair)
                .try_build()
                .is_err());
        }
    }
    eprintln!(
        "closed form vs first principles: largest scaled error {worst:.2e} over {STATES} states \
         ({n_stick} stick, {n_slide} slide, {n_none} no collision, {n_explicit} explicit P, \
         {n_rejected} rejected explicit P)"
    );
    // The distribution must reach every regime.
    for (what, n) in [
        ("stick", n_stick),
        ("slide", n_slide),
        ("no collision", n_none),
        ("explicit P", n_explicit),
    ] {
        assert!(n > STATES / 50, "only {n} {what} cases");
    }
}

/// `solve` with the closed-form method gives the same outcome, the stick time of the
/// half-sine, t = (2 tau / pi) asin(sqrt(p_stick / P)), and zero check errors.
#[test]
fn solve_closed_form_method_matches_first_principles() {
    let mut rng = Rng::new(0x5eed_0002);
    let settings = SolverSettings::default().with_method(Method::ClosedForm);
    let profile = HalfSine::new(TAU).unwrap();
    let mut worst = 0.0_f64;
    for _ in 0..STATES / 4 {
        let case = random_case(&mut rng);
        let c = CollisionSpec::reference(&case.balls, &case.law, &case.pair).build();
        let want = resolve(&case.balls, &case.law, &case.pair);
        let o = solve(&c, &profile, &settings, None).unwrap();
        worst = worst.max(compare(&case, &c, &o.exact, &want));
        let b = &case.balls;
        let v = case.pair.v_ref(b.r);
        worst = worst.max(state_error(b, v, &o.result.out, &want.out));
        assert!(state_error(b, v, &o.result.out, &want.out) <= CLOSED_FORM_TOL);
        assert!((o.result.tangential_impulse - want.tangential).abs() <= CLOSED_FORM_TOL * b.m * v);
        assert_eq!(o.result.collided(), want.collision);
        assert_eq!(o.result.theta.is_none(), want.s0 == 0.0);
        for x in [
            o.check.closed_form_error,
            o.check.momentum_error,
            o.check.angular_momentum_error,
            o.check.energy_balance_error,
            o.check.theta_drift,
        ] {
            assert!((0.0..=CLOSED_FORM_TOL).contains(&x), "check {x:e}");
        }
        if !want.collision {
            assert_eq!(o.result.stick_impulse, None);
            assert_eq!(o.stick_time, None);
            continue;
        }
        if o.result.sticks {
            let p_stick = want.p_stick.unwrap();
            let t_exact = TAU * common::half_sine_time(p_stick / want.impulse);
            let t = o.stick_time.expect("a stick time");
            assert!(
                (t - t_exact).abs() <= CLOSED_FORM_TOL * TAU,
                "{t} vs {t_exact}"
            );
        } else {
            assert_eq!(o.stick_time, None);
        }
    }
    eprintln!("solve(closed-form): largest scaled error {worst:.2e}");
}

fn cm_case(u: [f64; 3], wa: [f64; 3], wb: [f64; 3], mu: f64, rule: Rule, b: Balls) -> Case {
    Case {
        balls: b,
        law: Law::new(mu, rule),
        pair: Pair::cm(Vector3::from(u), Vector3::from(wa), Vector3::from(wb)),
    }
}

/// S(0) = 0 exactly (docs/model.md#no-initial-sliding): no friction, theta undefined, only U changes by -P/m;
/// the contract's stick fields: sticks, stick_time 0, stick_impulse 0.
#[test]
fn zero_slip_gets_no_friction_and_no_theta() {
    // r = 0.5 and binary fractions: 2V + r Omega_z and 2W - r Omega_y vanish exactly.
    let b = Balls {
        m: 0.17,
        r: 0.5,
        alpha: 0.4,
    };
    let cases = [
        // head-on stun shot
        cm_case(
            [0.75, 0.0, 0.0],
            [0.0; 3],
            [0.0; 3],
            0.06,
            Rule::Restitution(1.0),
            b,
        ),
        // spins about the line of centres only (they do not move the contact points)
        cm_case(
            [1.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
            [-7.0, 0.0, 0.0],
            0.2,
            Rule::Restitution(0.5),
            b,
        ),
        // side and vertical velocity exactly geared by spin: 2V + r Omega_z = 0.5 - 0.5,
        // 2W - r Omega_y = 0.25 - 0.25
        cm_case(
            [0.5, 0.25, 0.125],
            [1.0, 0.5, -0.25],
            [0.0, 0.0, -0.75],
            0.3,
            Rule::Explicit(0.17 * 0.5 * 1.5),
            b,
        ),
    ];
    let settings = SolverSettings::default().with_method(Method::ClosedForm);
    for case in &cases {
        assert_eq!(case.pair.slip(b.r), Vector3::zeros());
        let c = CollisionSpec::reference(&case.balls, &case.law, &case.pair).build();
        let want = resolve(&case.balls, &case.law, &case.pair);
        let cf = ClosedForm::new(&c);
        compare(case, &c, &cf, &want);
        assert_eq!(c.s0, 0.0);
        assert_eq!(c.theta(), None);
        assert_eq!(cf.result.tangential_impulse, 0.0);
        assert_eq!(cf.result.heat_sliding, 0.0);
        // Only U changes, by exactly -P/m; every spin and V, W are untouched.
        let mut expected = c.incoming;
        expected.u_cm.x -= want.impulse / b.m;
        assert_eq!(cf.result.out, expected);
        let o = solve(&c, &HalfSine::new(TAU).unwrap(), &settings, None).unwrap();
        assert!(o.result.sticks);
        assert_eq!(o.stick_time, Some(0.0));
        assert_eq!(o.result.stick_impulse, Some(0.0));
        assert_eq!(o.result.theta, None);
    }
}

/// A roundoff-sized S(0) gives a roundoff-sized tangential impulse, directed against the
/// slip (no threshold on S(0)); J = m S(0) / (2 (1 + 1/alpha)) since it sticks.
#[test]
fn tiny_slip_gives_tiny_correctly_directed_friction() {
    let b = Balls {
        m: 0.17,
        r: 0.028575,
        alpha: 0.4,
    };
    for (v, w) in [(1e-18, -2e-18), (-3e-300, 4e-300), (0.0, 1e-15)] {
        let case = cm_case(
            [1.0, v, w],
            [0.0; 3],
            [0.0; 3],
            0.06,
            Rule::Restitution(1.0),
            b,
        );
        let c = CollisionSpec::reference(&case.balls, &case.law, &case.pair).build();
        let cf = ClosedForm::new(&c);
        let want = resolve(&case.balls, &case.law, &case.pair);
        compare(&case, &c, &cf, &want);
        assert!(cf.result.sticks);
        // S(0) = 2 |(V, W)|, J = m S(0) / 7.
        let s0 = 2.0 * v.hypot(w);
        let j = b.m * s0 / 7.0;
        assert!((cf.result.tangential_impulse - j).abs() <= 1e-14 * j);
        // Velocity change along -(V, W) with magnitude J/m = S(0)/7 = (2/7)|(V, W)|:
        // (V, W) -> (5/7)(V, W).
        let (dv, dw) = (cf.result.out.u_cm.y - v, cf.result.out.u_cm.z - w);
        assert!((dv + 2.0 * v / 7.0).abs() <= 1e-14 * v.abs().max(w.abs()));
        assert!((dw + 2.0 * w / 7.0).abs() <= 1e-14 * v.abs().max(w.abs()));
    }
}

/// Paper, eqs 59-72: a ball rolling without slipping with lab velocity (u, v, 0) strikes a
/// ball at rest; P = m u (eq 60), s = sqrt(u^2 + v^2), valid while eq 57 holds
/// (u / s <= 1 / (2 mu (1 + 1/alpha))). Centre-of-mass outgoing velocity of A:
///   U = u/2 - u (66),  V = v/2 - mu u v / s (67),  W = mu u^2 / s (68);
/// lab velocities A (0, v - mu u v/s, mu u^2/s) (69), B (u, mu u v/s, -mu u^2/s) (70);
/// spin change of both balls (0, -mu u^2/(alpha r s), -mu u v/(alpha r s)) (71); A's spin
/// (-v/r, u/r - mu u^2/(alpha r s), -mu u v/(alpha r s)) (72).
struct Special {
    u: f64,
    v: f64,
    mu: f64,
    alpha: f64,
}

const SPECIAL: [Special; 9] = [
    Special {
        u: 1.0,
        v: 0.5,
        mu: 0.06,
        alpha: 0.4,
    },
    Special {
        u: 1.0,
        v: 0.0,
        mu: 0.06,
        alpha: 0.4,
    },
    Special {
        u: 2.0,
        v: -1.0,
        mu: 0.06,
        alpha: 0.4,
    },
    Special {
        u: 0.3,
        v: 2.0,
        mu: 0.06,
        alpha: 0.4,
    },
    Special {
        u: 1e-3,
        v: 1.0,
        mu: 0.06,
        alpha: 0.4,
    },
    Special {
        u: 1.299038105676658,
        v: 0.75,
        mu: 0.06,
        alpha: 0.4,
    },
    Special {
        u: 1.0,
        v: 0.5,
        mu: 0.12,
        alpha: 0.4,
    },
    Special {
        u: 0.8,
        v: -0.6,
        mu: 0.02,
        alpha: 0.4,
    },
    Special {
        u: 1.0,
        v: 0.3,
        mu: 0.06,
        alpha: 2.0 / 3.0,
    },
];

const M: f64 = 0.17;
const R: f64 = 0.028575;

fn special_scene(sp: &Special, method: &str) -> Scene {
    let (u, v) = (sp.u, sp.v);
    let text = format!(
        "name = \"paper special case\"\n\
         [balls]\nmass = {M:?}\nradius = {R:?}\nalpha = {:?}\n\
         [contact]\nmu = {:?}\nrestitution = 1.0\n\
         [contact.profile]\nshape = \"half-sine\"\nduration = 2.5e-4\n\
         [incoming.lab]\n\
         a = {{ position = [{:?}, 0.0, 0.0], velocity = [{u:?}, {v:?}, 0.0], \
         spin = [{:?}, {:?}, 0.0] }}\n\
         b = {{ position = [{R:?}, 0.0, 0.0], velocity = [0.0, 0.0, 0.0] }}\n\
         up = [0.0, 0.0, 1.0]\n\
         [solver]\nmethod = \"{method}\"\n",
        sp.alpha,
        sp.mu,
        -R,
        -v / R,
        u / R
    );
    Scene::parse(&text, Path::new("."), None).unwrap()
}

#[test]
fn paper_special_case_eqs_66_to_72() {
    let mut worst = 0.0_f64;
    for sp in &SPECIAL {
        let (u, v, mu, alpha) = (sp.u, sp.v, sp.mu, sp.alpha);
        let s = u.hypot(v);
        assert!(
            u / s <= 1.0 / (2.0 * mu * (1.0 + 1.0 / alpha)),
            "eq 57 must hold"
        );
        // Scales: v_ref = max(u/2, S0 = s, |U| = s/2, r |Omega^A| = s) = s.
        let (vel, spin) = (s, s / R);
        let d_omega = Vector3::new(
            0.0,
            -mu * u * u / (alpha * R * s),
            -mu * u * v / (alpha * R * s),
        );
        let cm_u = Vector3::new(u / 2.0 - u, v / 2.0 - mu * u * v / s, mu * u * u / s);
        let lab_a = Vector3::new(0.0, v - mu * u * v / s, mu * u * u / s);
        let lab_b = Vector3::new(u, mu * u * v / s, -mu * u * u / s);
        let spin_a = Vector3::new(
            -v / R,
            u / R - mu * u * u / (alpha * R * s),
            -mu * u * v / (alpha * R * s),
        );
        let spin_b = d_omega;

        // The library's closed form in the centre-of-mass frame (eqs 59, 61-65 inputs).
        let c = CollisionSpec::ball(M, R, alpha)
            .mu(mu)
            .restitution(1.0)
            .incoming(CmState::new(
                Vector3::new(u / 2.0, v / 2.0, 0.0),
                Vector3::new(-v / R, u / R, 0.0),
                Vector3::zeros(),
            ))
            .build();
        let cf = ClosedForm::new(&c);
        assert!(
            (cf.result.impulse - M * u).abs() <= CLOSED_FORM_TOL * M * vel,
            "eq 60"
        );
        assert!((c.s0 - s).abs() <= CLOSED_FORM_TOL * vel, "eq 63");
        let th = c.theta().unwrap();
        assert!((th.cos() - v / s).abs() <= CLOSED_FORM_TOL, "eq 64");
        assert!((th.sin() + u / s).abs() <= CLOSED_FORM_TOL, "eq 65");
        assert!(!cf.result.sticks);
        let errs = [
            amax(&(cf.result.out.u_cm - cm_u)) / vel,
            amax(&(cf.result.out.omega_a - spin_a)) / spin,
            amax(&(cf.result.out.omega_b - spin_b)) / spin,
        ];
        // And through the runner, in the lab frame (eqs 69, 70, 72, 71).
        let scene = special_scene(sp, "closed-form");
        let so = run_scene(&scene, &scene.solver, None).unwrap();
        let (a, b) = so.lab_out.unwrap();
        let lab_errs = [
            amax(&(a.velocity - lab_a)) / vel,
            amax(&(b.velocity - lab_b)) / vel,
            amax(&(a.spin - spin_a)) / spin,
            amax(&(b.spin - spin_b)) / spin,
        ];
        for e in errs.iter().chain(&lab_errs) {
            assert!(
                *e <= CLOSED_FORM_TOL,
                "(u, v) = ({u}, {v}), mu {mu}: {errs:?} {lab_errs:?}"
            );
            worst = worst.max(*e);
        }
        // Momentum: m (u, v, 0) before and after (remark after eq 70).
        let p = M * (a.velocity + b.velocity) - M * Vector3::new(u, v, 0.0);
        assert!(amax(&p) <= CLOSED_FORM_TOL * M * vel);
    }
    eprintln!("eqs 66-72: largest scaled error {worst:.2e}");
}

/// The special case past eq 57 (docs/model.md#when-sliding-stops-during-contact): with mu = 0.3 and alpha = 2/5, a fuller hit
/// (u / s > 1 / (7 mu)) sticks. Then J = m s / 7 along the slip direction (v, -u)/s, so
/// lab A leaves with (0, 6v/7, u/7), B with (u, v/7, -u/7), both spins change by
/// (0, -u/(7 alpha r), -v/(7 alpha r)) = (0, -5u/(14 r), -5v/(14 r)).
#[test]
fn paper_special_case_past_eq_57_sticks() {
    for (u, v) in [(1.0, 0.5), (1.0, 0.0), (2.0, -0.4), (0.7, 0.6)] {
        let sp = Special {
            u,
            v,
            mu: 0.3,
            alpha: 0.4,
        };
        let s: f64 = u.hypot(v);
        assert!(u / s > 1.0 / (7.0 * sp.mu), "must violate eq 57");
        let lab_a = Vector3::new(0.0, 6.0 * v / 7.0, u / 7.0);
        let lab_b = Vector3::new(u, v / 7.0, -u / 7.0);
        let spin_b = Vector3::new(0.0, -5.0 * u / (14.0 * R), -5.0 * v / (14.0 * R));
        let spin_a = Vector3::new(-v / R, u / R, 0.0) + spin_b;
        let scene = special_scene(&sp, "closed-form");
        let so = run_scene(&scene, &scene.solver, None).unwrap();
        assert!(so.outcome.result.sticks);
        let (a, b) = so.lab_out.unwrap();
        let (vel, spin) = (s, s / R);
        let errs = [
            amax(&(a.velocity - lab_a)) / vel,
            amax(&(b.velocity - lab_b)) / vel,
            amax(&(a.spin - spin_a)) / spin,
            amax(&(b.spin - spin_b)) / spin,
        ];
        for e in errs {
            assert!(e <= CLOSED_FORM_TOL, "(u, v) = ({u}, {v}): {errs:?}");
        }
        // p_stick = m s / (2 mu (1 + 1/alpha)) = m s / (7 mu), J = m s / 7.
        let o = &so.outcome;
        assert!((o.result.stick_impulse.unwrap() - M * s / (7.0 * sp.mu)).abs() <= 1e-13 * M * s);
        assert!((o.result.tangential_impulse - M * s / 7.0).abs() <= CLOSED_FORM_TOL * M * s);
        assert_eq!(o.result.s_out, 0.0);
    }
}

/// With the effect `stick = false` the paper's formulas apply literally (J = mu P), the slip
/// reverses where eq 57 fails, and the run says so.
#[test]
fn without_stick_effect_the_paper_formulas_apply_and_eq_57_is_flagged() {
    let b = Balls {
        m: 0.17,
        r: 0.028575,
        alpha: 0.4,
    };
    let mut case = cm_case(
        [1.0, 0.1, 0.0],
        [0.0; 3],
        [0.0; 3],
        0.06,
        Rule::Restitution(1.0),
        b,
    );
    case.law.stick = false;
    let c = CollisionSpec::reference(&case.balls, &case.law, &case.pair).build();
    let want = resolve(&case.balls, &case.law, &case.pair);
    let cf = ClosedForm::new(&c);
    compare(&case, &c, &cf, &want);
    // S(0) = 2 V = 0.2, P = 2 m U0, J = mu P: S_out = S(0) - 2 (1 + 1/alpha) mu P / m = 0.2 - 0.84.
    let s_out = 0.2 - 2.0 * 3.5 * 0.06 * 2.0 * 1.0;
    assert!((cf.result.s_out - s_out).abs() <= 1e-14);
    assert!(cf.violates_eq57());
    let o = solve(
        &c,
        &HalfSine::new(TAU).unwrap(),
        &SolverSettings::default().with_method(Method::ClosedForm),
        None,
    )
    .unwrap();
    assert!(!o.result.sticks);
    assert!(
        o.warnings.iter().any(|w| w.contains("eq 57")),
        "{:?}",
        o.warnings
    );
}
