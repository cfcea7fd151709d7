//! Balls of different mass, radius and alpha: the closed form (docs/unequal-balls.md)
//! against the independent first-principles resolution of `common::unequal`, conservation
//! of momentum and of angular momentum about a fixed point, the energy balance
//! H - H_sfr = m* v_n^2 (1 - e^2) / 2, and the two limits: identical balls given as a pair
//! are the identical-ball closed form to the last bit, and a very heavy B is a fixed sphere.
//!
//! Scales: v_ref is the largest of |u|, S(0), r_A |Omega^A|, r_B |Omega^B| before and after;
//! spins are compared over v_ref / min(r_A, r_B), impulses over m* v_ref, energies over
//! m* v_ref^2.

use crate::common;

use billiard_contact::details::ClosedFormBatch;
use billiard_contact::{
    Ball, BallPair, ClosedForm, CmState, Collision, Contact, Effects, Frame, Friction, ImpulseRule,
    LabBall, LabScene,
};
use common::unequal::{
    angular_momentum, cm_pair, half_relative, momentum, resolve_unequal, slip, Sphere, UnequalLaw,
};
use common::{amax, norm, Pair, Rng};
use nalgebra::Vector3;

/// Scaled agreement with the independent resolution.
const TOL: f64 = 1e-12;
/// Conservation and energy balance: round-off of a few dozen operations.
const ROUND_OFF: f64 = 1e-13;
const PAIRS: usize = 20_000;

/// A random pair of balls: mass ratio in [0.5, 2], radius ratio in [0.8, 1.25], alphas in
/// (0, 2/3].
fn random_spheres(rng: &mut Rng) -> (Sphere, Sphere) {
    let a = Sphere {
        m: rng.range(0.1, 0.3),
        r: rng.range(0.025, 0.035),
        alpha: (2.0 / 3.0) * (1.0 - rng.unit()),
    };
    let b = Sphere {
        m: a.m * rng.log_range(0.5, 2.0),
        r: a.r * rng.log_range(0.8, 1.25),
        alpha: (2.0 / 3.0) * (1.0 - rng.unit()),
    };
    (a, b)
}

fn pair_of(a: &Sphere, b: &Sphere) -> BallPair {
    BallPair::new(
        Ball::new(a.m, a.r, a.alpha).unwrap(),
        Ball::new(b.m, b.r, b.alpha).unwrap(),
    )
}

fn contact(law: &UnequalLaw) -> Contact {
    Contact {
        friction: Friction::constant(law.mu).unwrap(),
        impulse: ImpulseRule::restitution(law.e).unwrap(),
    }
}

fn effects(law: &UnequalLaw) -> Effects {
    Effects {
        stick: law.stick,
        ..Effects::default()
    }
}

/// v_ref over the incoming and outgoing pairs (n = e_x).
fn v_ref(a: &Sphere, b: &Sphere, pairs: &[&Pair]) -> f64 {
    pairs.iter().fold(0.0_f64, |acc, p| {
        acc.max(norm(&half_relative(p)))
            .max(norm(&slip(a, b, p)))
            .max(a.r * norm(&p.wa))
            .max(b.r * norm(&p.wb))
    })
}

#[test]
fn closed_form_equals_the_first_principles_resolution_on_20000_random_pairs() {
    let mut rng = Rng::new(0x5eed_0011);
    let (mut worst, mut sticking, mut separating) = (0.0_f64, 0, 0);
    for i in 0..PAIRS {
        let (a, b) = random_spheres(&mut rng);
        let law = UnequalLaw {
            mu: rng.range(0.0, 0.3),
            e: rng.range(0.0, 1.0),
            stick: i % 7 != 0,
        };
        let mut u = rng.vector(1.0);
        u.x = rng.range(-0.2, 1.5);
        // Some states start without slip or slide little, so that sliding stops often.
        let (wa, wb) = if i % 11 == 0 {
            (Vector3::zeros(), Vector3::zeros())
        } else {
            (rng.vector(40.0), rng.vector(40.0))
        };
        let mut pair = cm_pair(&a, &b, u, wa, wb);
        if i % 11 == 0 {
            pair.va.y = 0.0;
            pair.va.z = 0.0;
            pair.vb.y = 0.0;
            pair.vb.z = 0.0;
        }
        let want = resolve_unequal(&a, &b, &law, &pair);
        let balls = pair_of(&a, &b);
        let state = CmState::new(half_relative(&pair), pair.wa, pair.wb);
        let c = Collision::new(balls, contact(&law), effects(&law), state).unwrap();
        let got = ClosedForm::new(&c).result;
        let v = v_ref(&a, &b, &[&pair, &want.out]);
        let w = v / a.r.min(b.r);
        let m_star = a.m * b.m / (a.m + b.m);
        let err = (amax(&(got.out.u_cm - half_relative(&want.out))) / v)
            .max(amax(&(got.out.omega_a - want.out.wa)) / w)
            .max(amax(&(got.out.omega_b - want.out.wb)) / w)
            .max((got.impulse - want.impulse).abs() / (m_star * v))
            .max((got.tangential_impulse - want.tangential).abs() / (m_star * v))
            .max((got.s0 - want.s0).abs() / v)
            .max((got.heat - want.heat).abs() / (m_star * v * v))
            .max((got.heat_sliding - want.heat_sliding).abs() / (m_star * v * v));
        assert!(
            err <= TOL,
            "pair {i}: scaled error {err:e} ({a:?}, {b:?}, {law:?})"
        );
        worst = worst.max(err);
        // The stick decision, away from its boundary mu P = J_stick.
        let margin = (law.mu * want.impulse - law.mu * want.p_stick).abs() / (m_star * v);
        if margin > 1e-9 {
            assert_eq!(got.sticks, want.sticks, "pair {i}");
        }
        if want.impulse > 0.0 && law.mu > 0.0 && want.s0 > 0.0 {
            let ps = got.stick_impulse.unwrap();
            assert!(
                (ps - want.p_stick).abs() <= 1e-13 * want.p_stick,
                "pair {i}"
            );
        }
        sticking += usize::from(want.sticks);
        separating += usize::from(want.impulse == 0.0);
        // The batch kernel: the same formulas with precomputed reciprocals.
        let k = ClosedFormBatch::new(balls, contact(&law), effects(&law))
            .resolve(&state)
            .unwrap();
        let kernel = (amax(&(k.out.u_cm - got.out.u_cm)) / v)
            .max(amax(&(k.out.omega_a - got.out.omega_a)) / w)
            .max(amax(&(k.out.omega_b - got.out.omega_b)) / w);
        assert!(kernel <= 1e-14, "pair {i}: batch kernel {kernel:e}");
        assert_eq!(k.sticks, got.sticks, "pair {i}");
    }
    assert!(
        sticking > 2_000 && separating > 1_000,
        "{sticking} {separating}"
    );
    println!("largest scaled error against first principles: {worst:e}");
}

/// A lab scene: A at `pa`, B touching it along the unit `n`, both moving and spinning.
fn lab(a: &Sphere, b: &Sphere, pa: Vector3<f64>, n: Vector3<f64>, p: &Pair) -> LabScene {
    let ball = |position, velocity, spin| LabBall {
        position,
        velocity,
        spin,
    };
    LabScene {
        a: ball(pa, p.va, p.wa),
        b: ball(pa + (a.r + b.r) * n, p.vb, p.wb),
        up: Vector3::new(0.1, -0.2, 1.0),
    }
}

#[test]
fn momentum_angular_momentum_and_energy_balance_hold_in_the_lab_frame() {
    let mut rng = Rng::new(0xba1a_0011);
    let (mut worst_p, mut worst_l, mut worst_h) = (0.0_f64, 0.0_f64, 0.0_f64);
    for i in 0..2_000 {
        let (a, b) = random_spheres(&mut rng);
        let law = UnequalLaw {
            mu: rng.range(0.0, 0.3),
            e: rng.range(0.0, 1.0),
            stick: true,
        };
        let n = rng.vector(1.0).normalize();
        let pa = rng.vector(0.5);
        let mut p = Pair {
            n,
            va: rng.vector(1.0),
            vb: rng.vector(1.0),
            wa: rng.vector(40.0),
            wb: rng.vector(40.0),
        };
        // Approaching: (v_A - v_B).n > 0.
        if (p.va - p.vb).dot(&n) < 0.0 {
            std::mem::swap(&mut p.va, &mut p.vb);
        }
        let scene = lab(&a, &b, pa, n, &p);
        let balls = pair_of(&a, &b);
        let frame = Frame::of_pair(&scene, &balls).unwrap();
        let c = Collision::new(balls, contact(&law), effects(&law), frame.to_cm(&scene)).unwrap();
        let r = ClosedForm::new(&c).result;
        let (oa, ob) = frame.to_lab(&r.out);
        let out = Pair {
            n,
            va: oa.velocity,
            vb: ob.velocity,
            wa: oa.spin,
            wb: ob.spin,
        };
        let contact_point = pa + a.r * n;
        let o = rng.vector(1.0);
        let m_star = a.m * b.m / (a.m + b.m);
        let v = amax(&p.va)
            .max(amax(&p.vb))
            .max(a.r * amax(&p.wa))
            .max(b.r * amax(&p.wb))
            .max(amax(&out.va).max(amax(&out.vb)));
        let dp = amax(&(momentum(&a, &b, &out) - momentum(&a, &b, &p))) / ((a.m + b.m) * v);
        let lever = (a.r + b.r) + norm(&(contact_point - o));
        let dl = amax(
            &(angular_momentum(&a, &b, &out, contact_point, o)
                - angular_momentum(&a, &b, &p, contact_point, o)),
        ) / ((a.m + b.m) * v * lever);
        // Energy balance: the heat not made by sliding is the normal loss.
        let vn = (p.va - p.vb).dot(&n);
        let normal_loss = m_star * vn * vn * (1.0 - law.e * law.e) / 2.0;
        let dh = ((r.heat - r.heat_sliding) - normal_loss).abs() / ((a.m + b.m) * v * v);
        // The heat reported is the lab loss of kinetic energy.
        let lab_loss = common::unequal::kinetic_energy(&a, &b, &p)
            - common::unequal::kinetic_energy(&a, &b, &out);
        let dk = (r.heat - lab_loss).abs() / ((a.m + b.m) * v * v);
        assert!(dp <= ROUND_OFF && dl <= ROUND_OFF, "{i}: {dp:e} {dl:e}");
        assert!(dh <= ROUND_OFF && dk <= 1e-12, "{i}: {dh:e} {dk:e}");
        worst_p = worst_p.max(dp);
        worst_l = worst_l.max(dl);
        worst_h = worst_h.max(dh.max(dk));
    }
    println!("largest momentum {worst_p:e}, angular momentum {worst_l:e}, energy {worst_h:e}");
}

#[test]
fn identical_balls_given_as_a_pair_are_the_identical_closed_form_to_the_last_bit() {
    let mut rng = Rng::new(0x1de0_0011);
    for i in 0..5_000 {
        let ball = Ball::new(
            rng.range(0.1, 0.3),
            rng.range(0.02, 0.04),
            rng.range(0.1, 2.0 / 3.0),
        )
        .unwrap();
        let law = UnequalLaw {
            mu: rng.range(0.0, 0.3),
            e: rng.range(0.0, 1.0),
            stick: i % 3 != 0,
        };
        let mut u = rng.vector(1.0);
        u.x = rng.range(-0.2, 1.5);
        let s = CmState::new(u, rng.vector(40.0), rng.vector(40.0));
        let one = Collision::new(ball, contact(&law), effects(&law), s).unwrap();
        let two =
            Collision::new(BallPair::new(ball, ball), contact(&law), effects(&law), s).unwrap();
        assert_eq!(one.scales, two.scales);
        let (x, y) = (ClosedForm::new(&one).result, ClosedForm::new(&two).result);
        assert_eq!(x, y, "{i}");
    }
}

/// B with m_B / m_A = 1e6 and alpha_B = 2/3 barely moves or turns: A strikes a fixed sphere.
/// For B fixed the contact point of B is at rest, the normal impulse is P = (1 + e) m_A v_n,
/// and a tangential impulse J changes A's slip by J (1/m_A + r_A^2/I_A) = J (1 + 1/alpha_A)
/// / m_A, so J = min(mu P, S(0) m_A / (1 + 1/alpha_A)); A's velocity changes by
/// -(P n + J t) / m_A and its spin by -J (n x t) / (alpha_A m_A r_A).
#[test]
fn a_very_heavy_ball_b_is_a_fixed_sphere() {
    let mut rng = Rng::new(0xf1ed_0011);
    let mut worst: f64 = 0.0;
    for i in 0..2_000 {
        let a = Sphere {
            m: 0.17,
            r: 0.028575,
            alpha: rng.range(0.2, 2.0 / 3.0),
        };
        let b = Sphere {
            m: 1e6 * a.m,
            r: a.r * rng.range(0.8, 1.25),
            alpha: 2.0 / 3.0,
        };
        let law = UnequalLaw {
            mu: rng.range(0.0, 0.3),
            e: rng.range(0.0, 1.0),
            stick: true,
        };
        let mut va = rng.vector(1.0);
        va.x = rng.range(0.1, 1.5);
        let wa = rng.vector(40.0);
        // B at rest, not spinning; the centre-of-mass state of this lab pair.
        let u = 0.5 * va;
        let state = CmState::new(u, wa, Vector3::zeros());
        let c = Collision::new(pair_of(&a, &b), contact(&law), effects(&law), state).unwrap();
        let got = ClosedForm::new(&c).result.out;
        let (wa_out, wb_out) = (got.omega_a, got.omega_b);
        // A's lab velocity after: v_cm + 2 m_B/(m_A + m_B) u' with v_cm = m_A v_A/(m_A + m_B).
        let total = a.m + b.m;
        let va_out = a.m / total * va + 2.0 * b.m / total * got.u_cm;
        // The fixed-sphere limit.
        let n = Vector3::x();
        let p_big = (1.0 + law.e) * a.m * va.x;
        let g = {
            let rel = va + wa.cross(&(a.r * n));
            rel - n * rel.dot(&n)
        };
        let s0 = norm(&g);
        let t = g / s0;
        let j = (law.mu * p_big).min(s0 * a.m / (1.0 + 1.0 / a.alpha));
        let va_want = va - (p_big * n + j * t) / a.m;
        let wa_want = wa - j * n.cross(&t) / (a.alpha * a.m * a.r);
        let v = norm(&va).max(a.r * norm(&wa));
        // Corrections of order m_A / m_B = 1e-6.
        let err = (amax(&(va_out - va_want)) / v).max(amax(&(wa_out - wa_want)) * a.r / v);
        assert!(err <= 1e-5, "{i}: {err:e}");
        // B turns by J r_B / I_B: of order 1e-6 of A's spin change.
        assert!(amax(&wb_out) * b.r / v <= 1e-5, "{i}");
        worst = worst.max(err);
    }
    println!("largest scaled distance from the fixed-sphere limit: {worst:e}");
}
