//! One ball from separation until it rolls (and, with rolling resistance, until it
//! rests): [`roll_out`] runs the stages in order on a [`Track`](super::track::Track), the motion built so far.
//!
//! 1. The hop ([`Track::hop`], flight.rs), when the ball leaves the cloth moving up.
//! 2. Impacts with the cloth, bouncing until settled ([`Track::bounce_until_settled`],
//!    flight.rs; one impact in impact.rs).
//! 3. Sliding until rolling ([`Track::slide_until_rolling`], rolling.rs).
//! 4. Rolling to rest with rolling resistance ([`Track::roll_to_rest`], rolling.rs), then
//!    the open-ended last segment and the cloth's support ([`Track::finish`]).

use super::cloth::Table;
use super::impact::ClothImpact;
use super::segment::{BallMotion, Segment};
use super::track::Track;
use crate::base::error::Error;
use crate::model::params::Ball;
use crate::model::state::LabBall;
use nalgebra::Vector3;

/// One ball's motion on the table after separation.
#[derive(Debug, Clone, PartialEq)]
pub struct RollOut {
    /// State at separation (lab).
    pub start: LabBall,
    /// Duration of the initial hop (s): 2 v.n / g, 0 for a ball not moving up.
    pub hop_time: f64,
    /// Highest rise of the centre during the hop (m): (v.n)^2 / (2 g).
    pub hop_height: f64,
    /// Impacts with the cloth in order (the first is the reported `impact`).
    pub impacts: Vec<ClothImpact>,
    /// Times the ball left the cloth again after an impact (restitution > 0).
    pub bounces: u32,
    /// Time (s) from which the ball stays on the cloth.
    pub settle_time: f64,
    /// Duration of the slide until rolling (s), from `settle_time`.
    pub slide_time: f64,
    /// Displacement of the centre during the slide (m, lab).
    pub slide_displacement: Vector3<f64>,
    /// Time (s) at which the ball starts to roll: settle_time + slide_time.
    pub roll_time: f64,
    /// State when it starts to roll (lab).
    pub rolling: LabBall,
    /// With rolling resistance: when (s) and where (m, lab) the ball comes to rest.
    pub rest: Option<(f64, Vector3<f64>)>,
    /// Total impulse of the cloth on the ball up to `end_time` (N s, lab): impacts,
    /// friction, rolling resistance and the normal support while on the cloth.
    pub table_impulse: Vector3<f64>,
    /// The time (s) the roll-out is followed to: `rest` when there is one, else `roll_time`.
    pub end_time: f64,
    /// The motion, segment by segment (the last one open-ended).
    pub segments: Vec<Segment>,
}

impl RollOut {
    /// The state at time `t` >= 0 (s); `after` picks the state just after an impact at `t`.
    pub fn at(&self, up: &Vector3<f64>, t: f64, after: bool) -> (BallMotion, LabBall) {
        let seg = if after {
            self.segments.iter().rev().find(|s| s.t0 <= t)
        } else {
            self.segments.iter().find(|s| s.t1 >= t)
        }
        .unwrap_or(&self.segments[self.segments.len() - 1]);
        (seg.phase, seg.at(up, t))
    }

    /// Impact times (s): where velocity and spin jump.
    pub fn impact_times(&self) -> impl Iterator<Item = f64> + '_ {
        self.impacts.iter().map(|i| i.time)
    }
}

/// Follows one ball from separation (`start`, lab) until it rolls (and, with rolling
/// resistance, until it rests): the stages of the module docs, in order.
///
/// ```
/// use billiard_contact::{table_phase::{roll_out, Table, TableParams}, Ball, LabBall};
/// use nalgebra::Vector3;
/// let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
/// let up = Vector3::z();
/// let table = Table { params: TableParams::default(), up, height: 0.0 };
/// let start = LabBall { position: Vector3::new(0.0, 0.0, 0.028575),
///                       velocity: Vector3::new(1.4, 0.0, 0.0), spin: Vector3::zeros() };
/// let r = roll_out(&ball, &table, &start).unwrap();
/// // A stun ball rolls after 2 v / (7 mu g) at 5/7 of its speed.
/// assert!((r.slide_time - 2.0 * 1.4 / (7.0 * 0.2 * 9.81)).abs() < 1e-15);
/// assert!((r.rolling.velocity.x - 1.0).abs() < 1e-14);
/// ```
pub fn roll_out(ball: &Ball, table: &Table, start: &LabBall) -> Result<RollOut, Error> {
    let mut track = Track::new(ball, table, start);
    let (hop_time, hop_height) = track.hop();
    let bounces = track.bounce_until_settled()?;
    let settle_time = track.t;
    let slide_start = track.state.position;
    let slide_time = track.slide_until_rolling();
    let slide_displacement = track.state.position - slide_start;
    let roll_time = track.t;
    let rolling = track.state;
    let rest = track.roll_to_rest();
    let end_time = track.t;
    track.finish();
    Ok(RollOut {
        start: *start,
        hop_time,
        hop_height,
        impacts: track.impacts,
        bounces,
        settle_time,
        slide_time,
        slide_displacement,
        roll_time,
        rolling,
        rest,
        table_impulse: track.impulse,
        end_time,
        segments: track.segments,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table_phase::params::TableParams;

    /// A pool ball (0.17 kg, 28.575 mm, solid) and a level cloth at height 0, up = z.
    fn pool_ball_on_level_cloth(params: TableParams) -> (Ball, Table) {
        let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
        let table = Table {
            params,
            up: Vector3::z(),
            height: 0.0,
        };
        (ball, table)
    }

    /// A ball left at rest on the cloth (velocity and spin 0, centre at r above it) does
    /// not hop, bounce, slide or roll: with rolling resistance it has no rest to reach
    /// (the rolling stage needs a speed to find a direction), the roll-out ends at t = 0
    /// and the ball stays where it was.
    #[test]
    fn a_ball_at_rest_stays_at_rest() {
        let params = TableParams::default()
            .with_rolling_resistance(0.01)
            .unwrap();
        let (ball, table) = pool_ball_on_level_cloth(params);
        let up = table.up;
        let start = LabBall {
            position: Vector3::new(0.1, -0.2, 0.028575),
            velocity: Vector3::zeros(),
            spin: Vector3::zeros(),
        };
        let r = roll_out(&ball, &table, &start).unwrap();
        assert_eq!((r.hop_time, r.bounces, r.slide_time), (0.0, 0, 0.0));
        assert_eq!(r.rest, None);
        assert_eq!(r.end_time, 0.0);
        for t in [0.0, 1.0] {
            let (_, s) = r.at(&up, t, false);
            assert_eq!(s.position, start.position, "t = {t}");
            assert_eq!(s.velocity, Vector3::zeros(), "t = {t}");
        }
    }

    /// The bounce limit is inclusive: a ball dropped straight down at v0 onto a cloth of
    /// restitution e leaves it at v0 e^k after the k-th impact and bounces while that is at
    /// least `SETTLE_SPEED`, so it bounces n times when SETTLE_SPEED e^-n <= v0 <
    /// SETTLE_SPEED e^-(n+1). Half a factor of e inside each range (5e-5 relative at
    /// e = 0.9999, far above the round-off of 10^4 products): n = `MAX_BOUNCES` is accepted,
    /// one more is refused.
    #[test]
    fn bounce_limit_is_inclusive() {
        use crate::table_phase::flight::{MAX_BOUNCES, SETTLE_SPEED};
        let e: f64 = 0.9999;
        let params = TableParams::default().with_restitution(e).unwrap();
        let (ball, table) = pool_ball_on_level_cloth(params);
        let dropped_to_bounce = |n: u32| {
            let v0 = SETTLE_SPEED * e.powf(-(n as f64 + 0.5));
            let start = LabBall {
                position: Vector3::new(0.0, 0.0, 0.028575),
                velocity: Vector3::new(0.0, 0.0, -v0),
                spin: Vector3::zeros(),
            };
            roll_out(&ball, &table, &start)
        };
        assert_eq!(dropped_to_bounce(MAX_BOUNCES).unwrap().bounces, MAX_BOUNCES);
        let err = dropped_to_bounce(MAX_BOUNCES + 1).unwrap_err().to_string();
        assert!(err.contains("table.restitution"), "{err}");
    }
}
