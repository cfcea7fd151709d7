//! Stage 2, the impact with the cloth: impulsive, applied at the contact point, with the
//! ball-cloth stick rule (docs/model.md#ball-cloth-impact): the sphere-plane closed form
//! with Newton's rule.
//!
//! ```text
//! P_n = (1 + e_t) m |v.n|                         normal impulse (0 when v.n >= 0)
//! J_t = min(mu_t P_n, m |u| / (1 + 1/alpha))       Coulomb, with the one-body stick rule
//! v'  = v + (P_n n - J_t u/|u|) / m
//! w'  = w + r J_t (n x u/|u|) / (alpha m r^2)
//! u'  = u (1 - J_t (1 + 1/alpha) / (m |u|))        (the slip keeps its direction)
//! ```
//!
//! J_t = m |u| / (1 + 1/alpha) brings the slip exactly to zero: the tangential impulse
//! changes the centre's velocity by -J_t u/(m |u|) and the contact point's velocity
//! relative to the centre by -J_t u/(alpha m |u|). Only one body's surface moves, hence
//! the factor (1 + 1/alpha) where the ball-ball rule has 2 (1 + 1/alpha).

use super::cloth::roll_spin;
use super::params::TableParams;
use crate::closed_form::plane::plane_impact;
use crate::model::params::Ball;
use nalgebra::Vector3;

/// One impact with the cloth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClothImpact {
    /// When it happens (s after separation).
    pub time: f64,
    /// Velocity after it (m/s, lab).
    pub velocity: Vector3<f64>,
    /// Spin after it (rad/s, lab).
    pub spin: Vector3<f64>,
    /// Normal impulse (1 + e_t) m |v.n| (N s), along +n.
    pub normal_impulse: f64,
    /// Tangential impulse J_t >= 0 (N s), along -u/|u|.
    pub tangential_impulse: f64,
    /// Whether the impact stopped the slip (the stick rule bounded J_t).
    pub sticks: bool,
    /// Slip u of the contact point before it (m/s, lab, horizontal).
    pub slip_before: Vector3<f64>,
}

/// The impact of a ball with `velocity` (m/s) and `spin` (rad/s) on the cloth at `time`
/// (s), `up` the unit vertical (module docs). A ball not moving down gets zero impulses.
pub fn cloth_impact(
    ball: &Ball,
    params: &TableParams,
    up: &Vector3<f64>,
    time: f64,
    velocity: &Vector3<f64>,
    spin: &Vector3<f64>,
) -> ClothImpact {
    let m = ball.mass();
    let vn = velocity.dot(up);
    let normal = if vn < 0.0 {
        (1.0 + params.restitution()) * m * -vn
    } else {
        0.0
    };
    let hit = plane_impact(ball, params.mu(), normal, up, velocity, spin);
    let (v, mut w, sticks) = (hit.velocity, hit.spin, hit.sticks);
    let jt = hit.tangential_impulse;
    let u = hit.slip_before;
    if sticks && u.norm() > 0.0 {
        // The slip is zero up to rounding: make it exactly rolling (w.n is unchanged).
        w = roll_spin(ball, up, &v, &w);
    }
    ClothImpact {
        time,
        velocity: v,
        spin: w,
        normal_impulse: normal,
        tangential_impulse: jt,
        sticks,
        slip_before: u,
    }
}
