//! States of the two balls: the centre-of-mass state of the paper and a lab-frame ball.

use crate::model::params::BallPair;
use nalgebra::{Vector2, Vector3};
use serde::{Deserialize, Serialize};

/// The centre-of-mass state of the paper: ball A at x = -r, ball B at x = +r, line of
/// centres along +x, contact at the origin.
///
/// Ball A moves with `u_cm` = (U, V, W), ball B with -(U, V, W); U > 0 means the balls
/// approach. For balls of different mass or size (A at x = -r_A, B at x = +r_B) `u_cm` is
/// half the relative velocity (v_A - v_B) / 2, which is A's velocity when the balls are
/// identical (docs/unequal-balls.md).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CmState {
    /// Velocity of ball A, (U, V, W) (m/s).
    #[serde(rename = "u")]
    pub u_cm: Vector3<f64>,
    /// Angular velocity of ball A (rad/s).
    pub omega_a: Vector3<f64>,
    /// Angular velocity of ball B (rad/s).
    pub omega_b: Vector3<f64>,
}

impl CmState {
    /// A state from ball A's velocity and both spins.
    #[inline]
    pub fn new(u_cm: Vector3<f64>, omega_a: Vector3<f64>, omega_b: Vector3<f64>) -> Self {
        CmState {
            u_cm,
            omega_a,
            omega_b,
        }
    }

    /// Omega = Omega^A + Omega^B (eq 4).
    #[inline]
    pub fn omega_sum(&self) -> Vector3<f64> {
        self.omega_a + self.omega_b
    }

    /// The slip (S cos theta, S sin theta) = (2V + r Omega_z, 2W - r Omega_y) of eqs 5-6 (m/s):
    /// the surface of B slides relative to A along -slip (eq 3).
    #[inline]
    pub fn slip(&self, radius: f64) -> Vector2<f64> {
        self.slip_with(radius, 1.0)
    }

    /// The slip of balls of radii r_A = `radius_a` and r_B = `ratio` r_A: the tangential part
    /// of (v_A - v_B) + Omega^A x (r_A e_x) + Omega^B x (r_B e_x),
    /// (2V + r_A (Omega^A_z + ratio Omega^B_z), 2W - r_A (Omega^A_y + ratio Omega^B_y))
    /// (docs/unequal-balls.md); `ratio` = 1 gives eqs 5-6 bit for bit.
    #[inline]
    pub fn slip_with(&self, radius_a: f64, ratio: f64) -> Vector2<f64> {
        let (a, b) = (self.omega_a, self.omega_b);
        Vector2::new(
            2.0 * self.u_cm.y + radius_a * (a.z + ratio * b.z),
            2.0 * self.u_cm.z - radius_a * (a.y + ratio * b.y),
        )
    }

    /// The slip of the pair `balls` ([`CmState::slip_with`]).
    #[inline]
    pub fn slip_of(&self, balls: &BallPair) -> Vector2<f64> {
        self.slip_with(balls.a.radius(), balls.radius_ratio())
    }

    /// Sliding speed S >= 0 (m/s), eqs 5-6.
    #[inline]
    pub fn sliding_speed(&self, radius: f64) -> f64 {
        planar_length(self.slip(radius))
    }

    /// Sliding direction theta (rad, in (-pi, pi]) of eqs 5-6; `None` when S = 0.
    pub fn theta(&self, radius: f64) -> Option<f64> {
        direction_angle(self.slip(radius))
    }

    /// Sliding speed S >= 0 (m/s) of the pair `balls`.
    pub fn sliding_speed_of(&self, balls: &BallPair) -> f64 {
        planar_length(self.slip_of(balls))
    }

    /// Sliding direction theta (rad) of the pair `balls`; `None` when S = 0.
    pub fn theta_of(&self, balls: &BallPair) -> Option<f64> {
        direction_angle(self.slip_of(balls))
    }

    /// Kinetic energy of both balls in the centre-of-mass frame (J), eq 37: M |u|^2 (M the
    /// pair mass, m for identical balls) plus (I_A |Omega^A|^2 + I_B |Omega^B|^2) / 2.
    pub fn kinetic_energy(&self, balls: &BallPair) -> f64 {
        let i = balls.a.inertia();
        let ratio = balls.b.inertia() / i;
        balls.pair_mass() * self.u_cm.norm_squared()
            + 0.5 * i * (self.omega_a.norm_squared() + ratio * self.omega_b.norm_squared())
    }

    /// Angular momentum about the contact point (kg m^2/s), eq 36; the total momentum is
    /// zero in this frame, so it is the same about every point. A at -r_A e_x carries
    /// momentum M u, B at +r_B e_x carries -M u.
    pub fn angular_momentum(&self, balls: &BallPair) -> Vector3<f64> {
        let (ra, rb) = (balls.a.radius(), balls.b.radius());
        let m = balls.pair_mass();
        let ex = Vector3::x();
        let ratio = balls.b.inertia() / balls.a.inertia();
        balls.a.inertia() * (self.omega_a + ratio * self.omega_b)
            + (-ra * ex).cross(&(m * self.u_cm))
            + (rb * ex).cross(&(-m * self.u_cm))
    }

    /// True when every component is finite. Branch-free: x * 0 is 0 for a finite x and NaN
    /// for an infinite or NaN one, so the sum of the nine products is 0 exactly when all
    /// are finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        let zero = |v: &Vector3<f64>| v.x * 0.0 + v.y * 0.0 + v.z * 0.0;
        zero(&self.u_cm) + zero(&self.omega_a) + zero(&self.omega_b) == 0.0
    }
}

/// |v| of a plane vector (the slip): sqrt(x^2 + y^2) where the squares can neither
/// overflow nor lose precision to underflow, `hypot` (slower by about 20 ns) elsewhere, so
/// that a tiny S(0) keeps its full relative precision (there is no threshold on S(0):
/// docs/model.md#no-initial-sliding).
#[inline]
pub(crate) fn planar_length(v: Vector2<f64>) -> f64 {
    let m = v.x.abs().max(v.y.abs());
    if (1e-150..=1e150).contains(&m) {
        (v.x * v.x + v.y * v.y).sqrt()
    } else {
        v.x.hypot(v.y)
    }
}

/// The angle theta (rad, in (-pi, pi]) of a plane vector (the slip), eqs 5-6: atan2 of the
/// portable `libm` port (FreeBSD msun, error below 1 ulp), about 60 instructions cheaper
/// than the system's correctly rounded one, which matters to the closed form in batches.
#[inline]
pub(crate) fn slip_angle(v: Vector2<f64>) -> f64 {
    let t = libm::atan2(v.y, v.x);
    // atan2 returns -pi for a slip along -y whose second component is -0.0 or a negative
    // round-off remainder; both are the direction +pi, and the interval is open at -pi.
    if t == -std::f64::consts::PI {
        std::f64::consts::PI
    } else {
        t
    }
}

/// The angle of a slip ([`slip_angle`]); `None` for a zero slip.
fn direction_angle(s: Vector2<f64>) -> Option<f64> {
    if s.x == 0.0 && s.y == 0.0 {
        None
    } else {
        Some(slip_angle(s))
    }
}

/// One ball in the lab frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LabBall {
    /// Centre position (m).
    pub position: Vector3<f64>,
    /// Centre velocity (m/s).
    pub velocity: Vector3<f64>,
    /// Angular velocity (rad/s).
    pub spin: Vector3<f64>,
}

/// Velocity and spin of a ball after the collision, lab frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LabMotion {
    /// Centre velocity (m/s).
    pub velocity: Vector3<f64>,
    /// Angular velocity (rad/s).
    pub spin: Vector3<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::Ball;

    /// U = (1, 0.3, -0.1) m/s, Omega^A = (0, 10, 20), Omega^B = (0, -5, 5) rad/s.
    fn slipping_state() -> CmState {
        CmState::new(
            Vector3::new(1.0, 0.3, -0.1),
            Vector3::new(0.0, 10.0, 20.0),
            Vector3::new(0.0, -5.0, 5.0),
        )
    }

    /// Eqs 5-6 for identical balls: S cos(theta) = 2 V + r Omega_z, S sin(theta) =
    /// 2 W - r Omega_y with Omega = Omega^A + Omega^B. U = (1, 0.3, -0.1) m/s,
    /// Omega^A = (0, 10, 20), Omega^B = (0, -5, 5) rad/s, r = 0.028575 m: the slip is
    /// (0.6 + 25 r, -0.2 - 5 r) = (1.314375, -0.342875) m/s.
    #[test]
    fn sliding_speed_and_direction_of_eqs_5_6() {
        let r = 0.028575;
        let st = slipping_state();
        let (sy, sz): (f64, f64) = (1.314375, -0.342875);
        let s = (sy * sy + sz * sz).sqrt();
        assert!(
            (st.sliding_speed(r) - s).abs() <= 1e-15 * s,
            "{}",
            st.sliding_speed(r)
        );
        let theta = st.theta(r).unwrap();
        assert!((theta - f64::atan2(sz, sy)).abs() <= 1e-15, "{theta}");
    }

    /// The slip of unequal balls, written out: the tangential part of (v_A - v_B) +
    /// Omega^A x (r_A e_x) + Omega^B x (r_B e_x), with Omega x (r e_x) = (0, r Omega_z,
    /// -r Omega_y) and v_A - v_B = 2 U. `slipping_state` with r_A = 0.03 m, r_B = 0.02 m:
    /// (0.6 + 0.03 * 20 + 0.02 * 5, -0.2 - 0.03 * 10 - 0.02 * (-5)) = (1.3, -0.4) m/s.
    #[test]
    fn sliding_speed_and_direction_of_unequal_balls() {
        let st = slipping_state();
        let balls = BallPair::new(
            Ball::new(0.17, 0.03, 0.4).unwrap(),
            Ball::new(0.1, 0.02, 0.4).unwrap(),
        );
        let (sy, sz): (f64, f64) = (1.3, -0.4);
        let s = (sy * sy + sz * sz).sqrt();
        let got = st.sliding_speed_of(&balls);
        assert!((got - s).abs() <= 1e-15 * s, "{got}");
        let theta = st.theta_of(&balls).unwrap();
        assert!((theta - f64::atan2(sz, sy)).abs() <= 1e-15, "{theta}");
    }

    #[test]
    fn is_finite_catches_every_component() {
        let ok = CmState::new(
            Vector3::new(1.0, -2.0, 1e300),
            Vector3::new(0.0, -0.0, 5e-324),
            Vector3::new(-1e308, 3.0, 4.0),
        );
        assert!(ok.is_finite());
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for i in 0..9 {
                let mut s = ok;
                match i / 3 {
                    0 => s.u_cm[i % 3] = bad,
                    1 => s.omega_a[i % 3] = bad,
                    _ => s.omega_b[i % 3] = bad,
                }
                assert!(!s.is_finite(), "{bad} at {i}");
            }
        }
    }
}
