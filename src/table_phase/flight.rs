//! Stages 1 and 2: the hop and the bounces (docs/model.md#the-table-phase).
//!
//! A ball moving up (v.n > 0) leaves the cloth, flies under gravity (a = -g n, spin
//! unchanged) and lands after t_hop = 2 (v.n) / g, having risen h = (v.n)^2 / (2 g). It
//! then hits the cloth (at once when v.n <= 0): see impact.rs. With e_t > 0 it bounces (a
//! flight of 2 e_t |v.n| / g, then another impact) until its vertical speed after an impact
//! falls below [`SETTLE_SPEED`]; the cloth absorbs the rest and the ball is settled.

use super::impact::cloth_impact;
use super::segment::{BallMotion, Segment};
use super::track::Track;
use crate::base::error::Error;
use nalgebra::Vector3;

/// Vertical speed (m/s) below which a bouncing ball counts as settled on the cloth.
pub const SETTLE_SPEED: f64 = 1e-3;
/// Most bounces one ball may make before the run is refused as unphysical.
pub const MAX_BOUNCES: u32 = 10_000;

impl Track<'_> {
    /// Stage 1: the hop of a ball moving up, to its landing; returns its duration (s) and
    /// the centre's highest rise (m), both 0 for a ball not moving up.
    pub(super) fn hop(&mut self) -> (f64, f64) {
        let vn0 = self.state.velocity.dot(&self.n);
        if vn0 > 0.0 {
            let dt = self.fly();
            (dt, vn0 * vn0 / (2.0 * self.g))
        } else {
            (0.0, 0.0)
        }
    }

    /// Stage 2: impacts with the cloth, with a flight between two, until the ball's
    /// vertical speed after an impact is below [`SETTLE_SPEED`]; returns the number of
    /// bounces. More than [`MAX_BOUNCES`] is refused as a bad `table.restitution`.
    pub(super) fn bounce_until_settled(&mut self) -> Result<u32, Error> {
        let mut bounces = 0u32;
        loop {
            let vn = self.impact();
            if vn >= SETTLE_SPEED {
                bounces += 1;
                if bounces > MAX_BOUNCES {
                    return Err(Error::invalid(
                        "table.restitution",
                        self.table.params.restitution(),
                        format!("a restitution that settles within {MAX_BOUNCES} bounces"),
                    ));
                }
                self.fly();
            } else {
                // Settled: the residual vertical speed (< SETTLE_SPEED) is absorbed by the cloth.
                self.impulse -= self.n * (self.ball.mass() * vn);
                self.state.velocity -= self.n * vn;
                return Ok(bounces);
            }
        }
    }

    /// One impact with the cloth now, recorded, its impulse added; returns the vertical
    /// speed v.n (m/s) after it.
    fn impact(&mut self) -> f64 {
        let n = self.n;
        let imp = cloth_impact(
            self.ball,
            &self.table.params,
            &n,
            self.t,
            &self.state.velocity,
            &self.state.spin,
        );
        self.impacts.push(imp);
        if imp.tangential_impulse > 0.0 {
            self.impulse -= imp.slip_before.normalize() * imp.tangential_impulse;
        }
        self.impulse += n * imp.normal_impulse;
        self.state.velocity = imp.velocity;
        self.state.spin = imp.spin;
        self.state.velocity.dot(&n)
    }

    /// A flight under gravity from the cloth back to it; returns its duration (s). The
    /// landing is exact: the centre r above the cloth, the vertical velocity reversed.
    fn fly(&mut self) -> f64 {
        let n = self.n;
        let vn = self.state.velocity.dot(&n);
        let dt = 2.0 * vn / self.g;
        let mut land = self.run(Segment {
            phase: BallMotion::Flight,
            t0: self.t,
            t1: self.t + dt,
            start: self.state,
            accel: -n * self.g,
            spin_accel: Vector3::zeros(),
            spin_decay_rate: 0.0,
        });
        let cloth_level = self.table.height + self.ball.radius();
        land.position += n * (cloth_level - land.position.dot(&n));
        land.velocity += n * (-vn - land.velocity.dot(&n));
        self.state = land;
        dt
    }
}
