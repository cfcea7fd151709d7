//! A ball's motion as segments of constant accelerations: what the ball does on each
//! ([`BallMotion`]) and its exact state anywhere on it ([`Segment::at`]).

use crate::model::state::LabBall;
use nalgebra::Vector3;
use serde::Serialize;

/// What a ball is doing on the table: in the air, sliding, rolling or at rest.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BallMotion {
    /// In the air (hop or bounce).
    Flight,
    /// On the cloth, the contact point slipping.
    Sliding,
    /// On the cloth, rolling without slipping.
    Rolling,
    /// At rest (spin about the vertical may still decay).
    Rest,
}

impl BallMotion {
    /// The name used in the path CSV (`flight`, `sliding`, `rolling`, `rest`).
    pub fn name(&self) -> &'static str {
        match self {
            BallMotion::Flight => "flight",
            BallMotion::Sliding => "sliding",
            BallMotion::Rolling => "rolling",
            BallMotion::Rest => "rest",
        }
    }
}

/// A stretch of motion with constant accelerations: the exact state anywhere on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// What the ball does during the segment.
    pub phase: BallMotion,
    /// Start time (s after separation).
    pub t0: f64,
    /// End time (s after separation); infinite for the last segment.
    pub t1: f64,
    /// State at `t0` (lab).
    pub start: LabBall,
    /// Acceleration of the centre (m/s^2, lab).
    pub accel: Vector3<f64>,
    /// Angular acceleration perpendicular to `up` (rad/s^2, lab).
    pub spin_accel: Vector3<f64>,
    /// Rate (rad/s^2) at which |w.n| falls to 0 (spin decay about the vertical).
    pub spin_decay_rate: f64,
}

impl Segment {
    /// The state at time `t` (s, clamped to the segment), `up` the unit vertical.
    pub fn at(&self, up: &Vector3<f64>, t: f64) -> LabBall {
        let dt = (t.min(self.t1) - self.t0).max(0.0);
        let s = &self.start;
        let mut spin = s.spin + self.spin_accel * dt;
        if self.spin_decay_rate > 0.0 {
            let wn = s.spin.dot(up);
            let decayed = wn.signum() * (wn.abs() - self.spin_decay_rate * dt).max(0.0);
            spin += up * (decayed - wn);
        }
        LabBall {
            position: s.position + s.velocity * dt + self.accel * (0.5 * dt * dt),
            velocity: s.velocity + self.accel * dt,
            spin,
        }
    }

    /// Whether `t` (s) lies in [t0, t1].
    pub fn contains(&self, t: f64) -> bool {
        t >= self.t0 && t <= self.t1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `contains` is the closed interval [t0, t1] of its docs, open-ended for the last
    /// segment (t1 infinite).
    #[test]
    fn contains_is_the_closed_interval() {
        let still = LabBall {
            position: Vector3::zeros(),
            velocity: Vector3::zeros(),
            spin: Vector3::zeros(),
        };
        let seg = |t0: f64, t1: f64| Segment {
            phase: BallMotion::Sliding,
            t0,
            t1,
            start: still,
            accel: Vector3::zeros(),
            spin_accel: Vector3::zeros(),
            spin_decay_rate: 0.0,
        };
        let s = seg(0.125, 0.375);
        for (t, inside) in [
            (0.0, false),
            (0.124, false),
            (0.125, true),
            (0.25, true),
            (0.375, true),
            (0.376, false),
            (f64::NAN, false),
        ] {
            assert_eq!(s.contains(t), inside, "t = {t}");
        }
        let last = seg(0.375, f64::INFINITY);
        assert!(last.contains(0.375) && last.contains(1e9) && !last.contains(0.374));
    }
}
