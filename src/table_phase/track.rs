//! One ball's motion under construction ([`Track`]): the stages (flight.rs, rolling.rs)
//! add to it, [`super::roll_out::roll_out`] runs them in order.

use super::cloth::Table;
use super::impact::ClothImpact;
use super::segment::{BallMotion, Segment};
use crate::model::params::Ball;
use crate::model::state::LabBall;
use nalgebra::Vector3;

/// One ball's motion under construction: where the stages have brought it so far. Each
/// stage appends its segments and impacts, adds the cloth's impulse and moves `state` and
/// `t` to its end.
pub(super) struct Track<'a> {
    /// The ball.
    pub(super) ball: &'a Ball,
    /// The cloth.
    pub(super) table: &'a Table,
    /// Unit vertical n (= `table.up`).
    pub(super) n: Vector3<f64>,
    /// Gravitational acceleration g (m/s^2).
    pub(super) g: f64,
    /// Rate (rad/s^2) at which |w.n| falls on the cloth: mu_sp g / (alpha r).
    pub(super) decay_rate: f64,
    /// State at `t` (lab).
    pub(super) state: LabBall,
    /// Time reached (s after separation).
    pub(super) t: f64,
    /// Segments so far.
    pub(super) segments: Vec<Segment>,
    /// Impacts with the cloth so far.
    pub(super) impacts: Vec<ClothImpact>,
    /// Impulse of the cloth so far (N s, lab), without the normal support (see `finish`).
    pub(super) impulse: Vector3<f64>,
}

impl<'a> Track<'a> {
    /// The ball at separation, at t = 0.
    pub(super) fn new(ball: &'a Ball, table: &'a Table, start: &LabBall) -> Self {
        let g = table.params.g();
        Track {
            ball,
            table,
            n: table.up,
            g,
            decay_rate: table.params.spin_decay() * g / (ball.alpha() * ball.radius()),
            state: *start,
            t: 0.0,
            segments: Vec::new(),
            impacts: Vec::new(),
            impulse: Vector3::zeros(),
        }
    }

    /// Appends `seg` (which starts at `t`) and moves `t` to its end; returns the state
    /// there.
    pub(super) fn run(&mut self, seg: Segment) -> LabBall {
        self.segments.push(seg);
        self.t = seg.t1;
        seg.at(&self.n, self.t)
    }

    /// The last, open-ended segment (rolling on, or at rest) and the cloth's normal
    /// support m g n over the time spent on the cloth.
    pub(super) fn finish(&mut self) {
        let (n, m, g) = (self.n, self.ball.mass(), self.g);
        let end_time = self.t;
        self.segments.push(Segment {
            phase: if self.state.velocity == Vector3::zeros() {
                BallMotion::Rest
            } else {
                BallMotion::Rolling
            },
            t0: end_time,
            t1: f64::INFINITY,
            start: self.state,
            accel: Vector3::zeros(),
            spin_accel: Vector3::zeros(),
            spin_decay_rate: self.decay_rate,
        });
        let airborne: f64 = self
            .segments
            .iter()
            .filter(|s| s.phase == BallMotion::Flight)
            .map(|s| s.t1 - s.t0)
            .sum();
        self.impulse += n * (m * g * (end_time - airborne));
    }
}
