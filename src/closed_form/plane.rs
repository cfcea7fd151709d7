//! A sphere against a plane, exactly, for constant friction (docs/plane.md).
//!
//! The ball (mass m, radius r, I = alpha m r^2) touches the plane at x - r n, n the unit
//! normal out of the plane, towards the ball. The contact point moves with
//! v + w x (-r n); its tangential part is the slip
//!
//! ```text
//! u = v_t - r (w x n)              (v_t = v - (v.n) n)
//! ```
//!
//! Under a normal impulse dp along n and friction mu dp against the slip,
//!
//! ```text
//! dv = (n - mu u/|u|) dp / m
//! dw = (-r n) x (-mu u/|u| dp) / I = r mu (n x u/|u|) dp / I
//! du = -mu (1/m + r^2/I) u/|u| dp = -(1 + 1/alpha) (mu / m) u/|u| dp
//! ```
//!
//! so the slip keeps its direction and falls linearly in p at the rate (1 + 1/alpha) mu / m:
//! the paper's eq 22 with the partner's share of the rate (its 1/m and r^2/I) gone, as for a
//! partner of infinite mass. It stops at p_stick = m |u| / ((1 + 1/alpha) mu), after a
//! tangential impulse J = m |u| / (1 + 1/alpha); the rest of the impulse is normal (the
//! stick rule). The normal velocity v.n = v_n(0) + p/m does not depend on the friction, so
//! Newton's, Poisson's and Stronge's restitution give the one impulse P = (1 + e) m |v_n(0)|.

use crate::model::params::Ball;
use nalgebra::Vector3;

/// The outcome of a sphere's impulse against a plane (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneImpact {
    /// Velocity after it (m/s).
    pub velocity: Vector3<f64>,
    /// Spin after it (rad/s).
    pub spin: Vector3<f64>,
    /// Normal impulse P (N s), along +n.
    pub normal_impulse: f64,
    /// Tangential impulse J >= 0 (N s), along -u/|u|.
    pub tangential_impulse: f64,
    /// Whether the slip stopped during the impulse (the stick rule bounded J).
    pub sticks: bool,
    /// The normal impulse at which the slip stops, or would stop after the contact (N s);
    /// `None` without friction or without an impulse. 0 when the ball arrives without slip.
    pub stick_impulse: Option<f64>,
    /// Slip u of the contact point before it (m/s, tangential).
    pub slip_before: Vector3<f64>,
}

/// The slip u = v_t - r (w x n) (m/s) of a ball of radius `radius` with `velocity` and
/// `spin` on a plane of unit normal `n` (module docs).
pub fn plane_slip(
    radius: f64,
    n: &Vector3<f64>,
    velocity: &Vector3<f64>,
    spin: &Vector3<f64>,
) -> Vector3<f64> {
    (velocity - n * velocity.dot(n)) - radius * spin.cross(n)
}

/// The normal impulse `normal_impulse` P >= 0 (N s) applied to `ball` with `velocity` and
/// `spin` against the plane of unit normal `n`, with Coulomb friction `mu` and the stick
/// rule (module docs). The caller fixes P from its restitution rule.
pub fn plane_impact(
    ball: &Ball,
    mu: f64,
    normal_impulse: f64,
    n: &Vector3<f64>,
    velocity: &Vector3<f64>,
    spin: &Vector3<f64>,
) -> PlaneImpact {
    let m = ball.mass();
    let u = plane_slip(ball.radius(), n, velocity, spin);
    let s = u.norm();
    let stop = m * s / (1.0 + 1.0 / ball.alpha());
    let coulomb = mu * normal_impulse;
    let (jt, sticks) = if s == 0.0 {
        (0.0, normal_impulse > 0.0)
    } else if coulomb >= stop {
        (stop, true)
    } else {
        (coulomb, false)
    };
    let stick_impulse = if normal_impulse > 0.0 && mu > 0.0 {
        Some(stop / mu)
    } else if normal_impulse > 0.0 && s == 0.0 {
        Some(0.0)
    } else {
        None
    };
    let mut v = *velocity + n * (normal_impulse / m);
    let mut w = *spin;
    if jt > 0.0 {
        let dir = u / s;
        v -= dir * (jt / m);
        w += n.cross(&dir) * (ball.radius() * jt / ball.inertia());
    }
    PlaneImpact {
        velocity: v,
        spin: w,
        normal_impulse,
        tangential_impulse: jt,
        sticks,
        stick_impulse,
        slip_before: u,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solid() -> Ball {
        Ball::new(0.17, 0.028575, 0.4).unwrap()
    }

    /// Gross sliding: a ball without spin at incidence angle a from the normal, speed 1,
    /// e = 1, mu = 0.1, tan a = 2 > (1 + 1/alpha) mu (1 + e) = 0.7: the slip never stops,
    /// J = mu P = mu (1 + e) m cos a, so the tangential velocity of the centre keeps
    /// 1 - mu (1 + e) / tan a of itself (0.9 here), the normal one reverses, and the spin
    /// is J r / I about n x t.
    #[test]
    fn gross_sliding_keeps_one_minus_mu_one_plus_e_over_tan() {
        let ball = solid();
        let (m, r) = (ball.mass(), ball.radius());
        let n = Vector3::new(0.0, 0.0, 1.0);
        let (c, s) = (1.0 / 5f64.sqrt(), 2.0 / 5f64.sqrt()); // tan a = 2
        let v = Vector3::new(s, 0.0, -c);
        let p = 2.0 * m * c;
        let out = plane_impact(&ball, 0.1, p, &n, &v, &Vector3::zeros());
        assert!(!out.sticks);
        assert!((out.velocity.x / s - (1.0 - 0.1 * 2.0 / 2.0)).abs() < 1e-15);
        assert!((out.velocity.z - c).abs() < 1e-15);
        let j = 0.1 * p;
        assert!((out.tangential_impulse - j).abs() < 1e-18);
        // n x t = z x x = +y.
        assert!((out.spin.y - j * r / (0.4 * m * r * r)).abs() < 1e-12);
        assert_eq!(out.spin.x, 0.0);
    }

    /// Below the threshold the slip stops: a ball without spin keeps 1/(1 + alpha) of its
    /// tangential velocity, 5/7 for a solid sphere, and leaves rolling (slip 0).
    #[test]
    fn sticking_keeps_five_sevenths() {
        let ball = solid();
        let m = ball.mass();
        let n = Vector3::new(0.0, 0.0, 1.0);
        let v = Vector3::new(0.3, 0.4, -1.0); // tan a = 0.5 < 0.7
        let out = plane_impact(&ball, 0.1, 2.0 * m, &n, &v, &Vector3::zeros());
        assert!(out.sticks);
        assert!((out.velocity.x - 0.3 * 5.0 / 7.0).abs() < 1e-15);
        assert!((out.velocity.y - 0.4 * 5.0 / 7.0).abs() < 1e-15);
        let u = plane_slip(ball.radius(), &n, &out.velocity, &out.spin);
        assert!(u.norm() < 1e-15, "{u}");
        // p_stick = m |u| / ((1 + 1/alpha) mu) = 0.17 (0.5) / (3.5 (0.1)).
        let p = out.stick_impulse.unwrap();
        assert!((p - 0.17 * 0.5 / 0.35).abs() < 1e-15);
    }

    /// Without friction the impulse is normal: Newton's rule, spin and tangential velocity
    /// unchanged.
    #[test]
    fn frictionless_is_newtons_rule() {
        let ball = solid();
        let n = Vector3::new(0.6, 0.0, 0.8);
        let v = Vector3::new(-1.0, 2.0, 0.5);
        let w = Vector3::new(3.0, -4.0, 5.0);
        let vn = v.dot(&n);
        let e = 0.7;
        let out = plane_impact(&ball, 0.0, (1.0 + e) * ball.mass() * -vn, &n, &v, &w);
        assert!((out.velocity.dot(&n) + e * vn).abs() < 1e-15);
        let t = |x: Vector3<f64>| x - n * x.dot(&n);
        assert!((t(out.velocity) - t(v)).norm() < 1e-15);
        assert_eq!(out.spin, w);
        assert_eq!(out.tangential_impulse, 0.0);
    }
}
