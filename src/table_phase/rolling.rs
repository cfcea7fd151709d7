//! Stages 3 and 4: sliding until rolling, then rolling (to rest with rolling resistance)
//! (docs/model.md#the-table-phase).
//!
//! On the cloth the normal force is m g and friction -mu_t m g u/|u| acts at the contact
//! point:
//!
//! ```text
//! dv/dt = -mu_t g u/|u|,   dw/dt = mu_t g (n x u/|u|) / (alpha r),
//! du/dt = -mu_t g (1 + 1/alpha) u/|u|
//! ```
//!
//! so u keeps its direction and its length falls at the constant rate
//! mu_t g (1 + 1/alpha): the ball rolls after t_slide = |u| / (mu_t g (1 + 1/alpha))
//! (2 |u| / (7 mu_t g) for a solid ball) on a parabolic path. The angular momentum about
//! the contact point, alpha m r^2 w + m r n x v, has a constant horizontal part through
//! flights, impacts and sliding (every cloth force acts at the contact point, gravity
//! along n), so the rolling velocity is
//!
//! ```text
//! v_roll = (v_h + alpha r w x n) / (1 + alpha)      = 5/7 v_h + 2/7 r w x n (solid ball)
//! ```
//!
//! whatever mu_t and e_t: the basis of the 30-degree rule.
//!
//! Optional, off by default: rolling resistance mu_r (a rolling ball decelerates at
//! mu_r g along its velocity and stays rolling, until rest) and spin decay about the
//! vertical mu_sp (on the cloth a torque mu_sp m g r opposes the spin about n, so
//! |w.n| falls at mu_sp g / (alpha r) until 0). Neither acts in flight; rolling
//! resistance does not act while sliding (sliding friction dominates).

use super::cloth::{cloth_slip, horizontal, roll_spin};
use super::segment::{BallMotion, Segment};
use super::track::Track;
use crate::model::params::Ball;
use nalgebra::Vector3;

/// The rolling velocity (v_h + alpha r w x n) / (1 + alpha) (m/s) a ball with `velocity`
/// (m/s) and `spin` (rad/s) reaches on the cloth, `up` the unit vertical n:
/// 5/7 v_h + 2/7 r w x n for a solid ball.
///
/// ```
/// use billiard_contact::{table_phase::rolling_velocity, Ball};
/// use nalgebra::Vector3;
/// let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
/// // A stun ball (no spin) ends rolling at 5/7 of its speed.
/// let v = rolling_velocity(&ball, &Vector3::z(), &Vector3::new(1.4, 0.0, 0.0), &Vector3::zeros());
/// assert!((v - Vector3::new(1.0, 0.0, 0.0)).norm() < 1e-15);
/// ```
pub fn rolling_velocity(
    ball: &Ball,
    up: &Vector3<f64>,
    velocity: &Vector3<f64>,
    spin: &Vector3<f64>,
) -> Vector3<f64> {
    let a = ball.alpha();
    (horizontal(velocity, up) + a * ball.radius() * spin.cross(up)) / (1.0 + a)
}

impl Track<'_> {
    /// Stage 3: the slide of a settled ball until its contact point stops slipping;
    /// returns its duration (s), 0 for a ball already rolling.
    pub(super) fn slide_until_rolling(&mut self) -> f64 {
        let (ball, n, g) = (self.ball, self.n, self.g);
        let mu = self.table.params.mu();
        let u = cloth_slip(ball, &n, &self.state.velocity, &self.state.spin);
        let s = u.norm();
        if s == 0.0 || s.is_nan() {
            return 0.0;
        }
        let dir = u / s;
        let slide_time = s / (mu * g * (1.0 + 1.0 / ball.alpha()));
        let mut end = self.run(Segment {
            phase: BallMotion::Sliding,
            t0: self.t,
            t1: self.t + slide_time,
            start: self.state,
            accel: -dir * (mu * g),
            spin_accel: n.cross(&dir) * (mu * g / (ball.alpha() * ball.radius())),
            spin_decay_rate: self.decay_rate,
        });
        // The slip is zero up to rounding: make it exactly rolling.
        end.spin = roll_spin(ball, &n, &end.velocity, &end.spin);
        self.state = end;
        self.impulse += -dir * (mu * ball.mass() * g * slide_time);
        slide_time
    }

    /// Stage 4: with rolling resistance mu_r, the roll of a moving ball to rest, decelerating
    /// at mu_r g; returns when (s) and where (m, lab) it rests. `None` without rolling
    /// resistance or for a ball at rest.
    pub(super) fn roll_to_rest(&mut self) -> Option<(f64, Vector3<f64>)> {
        let (ball, n, g) = (self.ball, self.n, self.g);
        let mu_r = self.table.params.rolling_resistance();
        let speed = self.state.velocity.norm();
        if !(speed > 0.0 && mu_r > 0.0) {
            return None;
        }
        let dir = self.state.velocity / speed;
        let dt = speed / (mu_r * g);
        let accel = -dir * (mu_r * g);
        let mut end = self.run(Segment {
            phase: BallMotion::Rolling,
            t0: self.t,
            t1: self.t + dt,
            start: self.state,
            accel,
            spin_accel: n.cross(&accel) / ball.radius(),
            spin_decay_rate: self.decay_rate,
        });
        end.velocity = Vector3::zeros();
        end.spin = n * end.spin.dot(&n);
        self.state = end;
        self.impulse += accel * (ball.mass() * dt);
        Some((self.t, end.position))
    }
}
