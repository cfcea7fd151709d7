//! An independent first-principles resolution of a collision of two balls of different
//! mass, radius and moment of inertia, in any frame (docs/unequal-balls.md derives the
//! closed form the crate uses; nothing here calls the crate).
//!
//! A's centre is at -r_A n from the contact point, B's at +r_B n. The impulses are applied
//! as forces at the contact point: the linear impulse changes each centre's velocity by
//! impulse / m, and its moment about each centre, r x F, each spin by that moment / I. The
//! slip's response to a tangential impulse is measured by applying a unit impulse, not
//! taken from a formula.
#![allow(dead_code)]

use super::{norm, Pair};
use nalgebra::Vector3;

/// One ball: mass (kg), radius (m), I = alpha m r^2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    pub m: f64,
    pub r: f64,
    pub alpha: f64,
}

impl Sphere {
    pub fn inertia(&self) -> f64 {
        self.alpha * self.m * self.r * self.r
    }
}

/// The contact law: constant mu, restitution e (P = (1 + e) m* v_n), the stick rule.
#[derive(Debug, Clone, Copy)]
pub struct UnequalLaw {
    pub mu: f64,
    pub e: f64,
    pub stick: bool,
}

/// The outcome.
#[derive(Debug, Clone, Copy)]
pub struct UnequalExpected {
    pub impulse: f64,
    pub s0: f64,
    pub tangential: f64,
    pub sticks: bool,
    pub p_stick: f64,
    /// Loss of kinetic energy (J) and its sliding part (J).
    pub heat: f64,
    pub heat_sliding: f64,
    pub out: Pair,
}

/// Velocity of A's surface relative to B's at the contact point, tangential part.
pub fn slip(a: &Sphere, b: &Sphere, p: &Pair) -> Vector3<f64> {
    let point_a = p.va + p.wa.cross(&(a.r * p.n));
    let point_b = p.vb + p.wb.cross(&(-b.r * p.n));
    let rel = point_a - point_b;
    rel - p.n * rel.dot(&p.n)
}

/// Applies the impulse `imp` (N s) to B at the contact point and `-imp` to A.
pub fn apply(a: &Sphere, b: &Sphere, p: &Pair, imp: Vector3<f64>) -> Pair {
    let arm_a = a.r * p.n; // contact point from A's centre
    let arm_b = -b.r * p.n; // contact point from B's centre
    Pair {
        n: p.n,
        va: p.va - imp / a.m,
        vb: p.vb + imp / b.m,
        wa: p.wa + arm_a.cross(&(-imp)) / a.inertia(),
        wb: p.wb + arm_b.cross(&imp) / b.inertia(),
    }
}

/// Kinetic energy of both balls (J).
pub fn kinetic_energy(a: &Sphere, b: &Sphere, p: &Pair) -> f64 {
    0.5 * a.m * p.va.norm_squared()
        + 0.5 * b.m * p.vb.norm_squared()
        + 0.5 * a.inertia() * p.wa.norm_squared()
        + 0.5 * b.inertia() * p.wb.norm_squared()
}

/// Linear momentum (N s).
pub fn momentum(a: &Sphere, b: &Sphere, p: &Pair) -> Vector3<f64> {
    a.m * p.va + b.m * p.vb
}

/// Angular momentum (kg m^2/s) about the fixed point `o`, the contact point at `contact`:
/// each ball's I omega plus (x - o) x m v of its centre.
pub fn angular_momentum(
    a: &Sphere,
    b: &Sphere,
    p: &Pair,
    contact: Vector3<f64>,
    o: Vector3<f64>,
) -> Vector3<f64> {
    let xa = contact - a.r * p.n - o;
    let xb = contact + b.r * p.n - o;
    a.inertia() * p.wa + b.inertia() * p.wb + xa.cross(&(a.m * p.va)) + xb.cross(&(b.m * p.vb))
}

/// Resolves the collision. Normal: the relative normal velocity (v_A - v_B).n changes by
/// -P (1/m_A + 1/m_B) (the normal impulse exerts no torque), so restitution
/// (v_A - v_B).n' = -e (v_A - v_B).n needs P = (1 + e) v_n / (1/m_A + 1/m_B). Tangential:
/// the slip responds to an impulse J t (t the unit slip) by -J k t, k measured; Coulomb
/// friction J = mu p while sliding, and after the slip reaches 0 (J = S(0) / k) nothing.
pub fn resolve_unequal(a: &Sphere, b: &Sphere, law: &UnequalLaw, p: &Pair) -> UnequalExpected {
    let vn = (p.va - p.vb).dot(&p.n);
    let impulse = if vn > 0.0 {
        (1.0 + law.e) * vn / (1.0 / a.m + 1.0 / b.m)
    } else {
        0.0
    };
    let g = slip(a, b, p);
    let s0 = norm(&g);
    let t = if s0 > 0.0 { g / s0 } else { Vector3::zeros() };
    // Slip response per unit tangential impulse (t is perpendicular to n).
    let probe = Pair {
        va: Vector3::zeros(),
        vb: Vector3::zeros(),
        wa: Vector3::zeros(),
        wb: Vector3::zeros(),
        ..*p
    };
    let k = -slip(a, b, &apply(a, b, &probe, t)).dot(&t);
    let j_stick = s0 / k;
    let p_stick = j_stick / law.mu;
    let (tangential, sticks) = if impulse == 0.0 || law.mu == 0.0 {
        (0.0, false)
    } else if s0 == 0.0 {
        (0.0, law.stick)
    } else if law.stick && law.mu * impulse >= j_stick {
        (j_stick, true)
    } else {
        (law.mu * impulse, false)
    };
    let out = apply(a, b, p, impulse * p.n + tangential * t);
    // Sliding heat: the integral of S dJ with S = S(0) - k J.
    let heat_sliding = tangential * s0 - 0.5 * k * tangential * tangential;
    UnequalExpected {
        impulse,
        s0,
        tangential,
        sticks,
        p_stick,
        heat: kinetic_energy(a, b, p) - kinetic_energy(a, b, &out),
        heat_sliding,
        out,
    }
}

/// The centre-of-mass description of a pair along n = e_x: u = (v_A - v_B) / 2.
pub fn half_relative(p: &Pair) -> Vector3<f64> {
    0.5 * (p.va - p.vb)
}

/// A pair with n = e_x whose centre of mass is at rest and whose half relative velocity is
/// `u`: v_A = 2 m_B/(m_A + m_B) u, v_B = -2 m_A/(m_A + m_B) u.
pub fn cm_pair(
    a: &Sphere,
    b: &Sphere,
    u: Vector3<f64>,
    wa: Vector3<f64>,
    wb: Vector3<f64>,
) -> Pair {
    let total = a.m + b.m;
    Pair {
        n: Vector3::x(),
        va: 2.0 * b.m / total * u,
        vb: -2.0 * a.m / total * u,
        wa,
        wb,
    }
}
