//! Both balls on the table ([`TableOutcome`]): their roll-outs, the directions and
//! deflections they end up with, and the self-checks (docs/model.md#checks-of-the-table-phase).

use super::cloth::{horizontal, Table};
use super::roll_out::{roll_out, RollOut};
use crate::base::error::Error;
use crate::model::params::{kinetic_energy, Ball, BallPair};
use crate::model::state::LabBall;
use nalgebra::Vector3;
use serde::Serialize;

/// Evaluation points inside each segment for the energy check (plus both ends).
const ENERGY_POINTS: u32 = 16;

/// Self-checks of a table phase, scaled like the contact's checks
/// (docs/model.md#scales-and-scaled-errors).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct TableChecks {
    /// Largest increase of a ball's energy (kinetic + gravitational) between consecutive
    /// evaluation points (segment ends, impacts, 16 points inside each segment), over
    /// m v_ref^2 (dimensionless); 0 when it never increases.
    pub energy_increase: f64,
    /// Largest component of m (v_end - v_0) - (table impulse - m g n t_end) over both
    /// balls, over m v_ref (dimensionless): linear momentum changes only by the cloth's
    /// impulses and gravity.
    pub momentum_error: f64,
}

/// Both balls on the table.
#[derive(Debug, Clone, PartialEq)]
pub struct TableOutcome {
    /// The cloth.
    pub table: Table,
    /// Unit horizontal line of centres, A to B (lab, dimensionless).
    pub line: Vector3<f64>,
    /// Ball A.
    pub a: RollOut,
    /// Ball B.
    pub b: RollOut,
    /// Incoming lab velocities of A and B (m/s, before the collision), for deflections.
    pub incoming: [Vector3<f64>; 2],
    /// Self-checks.
    pub check: TableChecks,
}

impl TableOutcome {
    /// Runs the table phase for balls starting at `a`, `b` (lab, at separation) with
    /// incoming velocities `incoming` (m/s, before the collision); `speed_scale` (m/s)
    /// scales the checks. Each ball rolls out with its own mass, radius and alpha.
    pub fn new(
        balls: &BallPair,
        table: Table,
        a: &LabBall,
        b: &LabBall,
        incoming: [Vector3<f64>; 2],
        speed_scale: f64,
    ) -> Result<Self, Error> {
        let ra = roll_out(&balls.a, &table, a)?;
        let rb = roll_out(&balls.b, &table, b)?;
        let line = horizontal(&(b.position - a.position), &table.up).normalize();
        let mut out = TableOutcome {
            table,
            line,
            a: ra,
            b: rb,
            incoming,
            check: TableChecks::default(),
        };
        out.check = out.checks(balls, speed_scale);
        Ok(out)
    }

    /// The later of the two balls' end times (s): the path runs until both roll (or rest).
    pub fn end_time(&self) -> f64 {
        self.a.end_time.max(self.b.end_time)
    }

    /// The signed angle (degrees, counter-clockwise about up) from `from` to `to`, both
    /// projected on the cloth; `None` when either is zero there.
    pub fn angle_deg(&self, from: &Vector3<f64>, to: &Vector3<f64>) -> Option<f64> {
        let n = self.table.up;
        let f = horizontal(from, &n);
        let t = horizontal(to, &n);
        if f.norm() == 0.0 || t.norm() == 0.0 {
            return None;
        }
        Some(f.cross(&t).dot(&n).atan2(f.dot(&t)).to_degrees())
    }

    /// Direction of travel once rolling (degrees, counter-clockwise about up from the line
    /// of centres A to B): the object ball's throw after the roll-out.
    pub fn direction_deg(&self, r: &RollOut) -> Option<f64> {
        self.angle_deg(&self.line, &r.rolling.velocity)
    }

    /// Deflection (degrees, counter-clockwise about up) from a ball's incoming direction of
    /// travel to its rolling direction: the cue ball's deflection. `which` is 0 for A, 1
    /// for B. `None` for a ball that came in at rest or whose rolling velocity is zero (a
    /// ball that rolls and then rests with rolling resistance has one).
    pub fn deflection_deg(&self, which: usize, r: &RollOut) -> Option<f64> {
        self.angle_deg(&self.incoming[which], &r.rolling.velocity)
    }

    /// The checks, scaled by the pair mass M (m for identical balls) and `speed_scale`.
    fn checks(&self, balls: &BallPair, speed_scale: f64) -> TableChecks {
        let n = self.table.up;
        let g = self.table.params.g();
        let mut increase: f64 = 0.0;
        let mut momentum: f64 = 0.0;
        for (ball, r) in [(&balls.a, &self.a), (&balls.b, &self.b)] {
            let m = ball.mass();
            increase = increase.max(self.largest_energy_increase(ball, r));
            let (_, end) = r.at(&n, r.end_time, true);
            let dp = m * (end.velocity - r.start.velocity)
                - (r.table_impulse - n * (m * g * r.end_time));
            momentum = momentum.max(dp.amax());
        }
        let m = balls.pair_mass();
        let ev = m * speed_scale * speed_scale;
        let pv = m * speed_scale;
        TableChecks {
            energy_increase: if increase <= 0.0 { 0.0 } else { increase / ev },
            momentum_error: if momentum == 0.0 { 0.0 } else { momentum / pv },
        }
    }

    /// The largest increase (J) of one ball's energy between consecutive evaluation points
    /// of its roll-out (0 when it never increases); the open-ended last segment, which starts
    /// at the end time (`Track::finish`), is followed for 1 s.
    fn largest_energy_increase(&self, ball: &Ball, r: &RollOut) -> f64 {
        let n = self.table.up;
        let energy = |s: &LabBall| {
            kinetic_energy(ball, &s.velocity, &s.spin)
                + self.table.potential_energy(ball, &s.position)
        };
        let mut increase: f64 = 0.0;
        let mut last = energy(&r.start);
        for seg in &r.segments {
            let t1 = if seg.t1.is_finite() {
                seg.t1
            } else {
                seg.t0 + 1.0
            };
            for i in 0..=ENERGY_POINTS {
                let t = seg.t0 + (t1 - seg.t0) * f64::from(i) / f64::from(ENERGY_POINTS);
                let e = energy(&seg.at(&n, t));
                increase = increase.max(e - last);
                last = e;
            }
        }
        increase
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table_phase::params::TableParams;

    /// The energy check's scale: a roll-out whose recorded start has lost its motion gains,
    /// at the first evaluation point (the true start), exactly the start's kinetic energy
    /// m |v|^2 / 2 + alpha m r^2 |w|^2 / 2 (the position, so the potential energy, is the
    /// same); the check reports it over M v_ref^2, M the pair mass. Every later point loses
    /// energy, so that is the largest increase. The roll-out's open-ended last segment, made
    /// to gain energy, is followed for 1 s past its start, the end time.
    #[test]
    fn checks_are_scaled_by_pair_mass_and_speed() {
        let (m, r, alpha) = (0.17, 0.028575, 0.4);
        let ball = Ball::new(m, r, alpha).unwrap();
        let balls = BallPair::from(ball);
        let pa = Vector3::new(0.2, 0.3, r);
        let pb = pa + Vector3::new(2.0 * r, 0.0, 0.0);
        let table = Table::new(TableParams::default(), Vector3::z(), [pa, pb], [r, r]).unwrap();
        let (v, w) = (Vector3::new(0.3, 0.9, 0.0), Vector3::new(-20.0, 5.0, 8.0));
        let a = LabBall {
            position: pa,
            velocity: v,
            spin: w,
        };
        let b = LabBall {
            position: pb,
            velocity: Vector3::new(1.2, 0.1, 0.0),
            spin: Vector3::zeros(),
        };
        let speed = 1.5;
        let mut out = TableOutcome::new(
            &balls,
            table,
            &a,
            &b,
            [Vector3::x(), Vector3::zeros()],
            speed,
        )
        .unwrap();
        assert!(out.check.energy_increase < 1e-15, "{:?}", out.check);
        out.a.start.velocity = Vector3::zeros();
        out.a.start.spin = Vector3::zeros();
        let kinetic = 0.5 * m * v.norm_squared() + 0.5 * alpha * m * r * r * w.norm_squared();
        let want = kinetic / (m * speed * speed);
        let got = out.checks(&balls, speed).energy_increase;
        assert!((got / want - 1.0).abs() < 1e-12, "{got} vs {want}");
        // The momentum check likewise (with the start restored): 1 mN s of table impulse
        // that the motion does not show is reported over M v_ref.
        out.a.start = a;
        assert!(out.check.momentum_error < 1e-15, "{:?}", out.check);
        out.a.table_impulse.x += 1e-3;
        let want = 1e-3 / (m * speed);
        let got = out.checks(&balls, speed).momentum_error;
        assert!((got / want - 1.0).abs() < 1e-10, "{got} vs {want}");
        // The open-ended last segment, which starts at the end time, is followed for 1 s.
        // Make A's a defect: from rest, the centre accelerating at a = 0.5 m/s^2 along the
        // cloth (the height, so the potential energy, stays). Over L = 1 s its
        // ENERGY_POINTS = 16 points have speeds a L i / 16 and energies m (a L i / 16)^2 / 2,
        // whose largest step is the last: m a^2 L^2 (16^2 - 15^2) / (2 16^2) = m a^2 L^2 31/512.
        // The real roll-out only loses energy, so that is the largest increase.
        out.a.table_impulse.x -= 1e-3;
        let end = out.a.end_time;
        let last = out.a.segments.last_mut().unwrap();
        assert!(last.t1.is_infinite() && last.t0 == end);
        last.start.velocity = Vector3::zeros();
        last.start.spin = Vector3::zeros();
        (last.accel, last.spin_accel, last.spin_decay_rate) =
            (0.5 * Vector3::x(), Vector3::zeros(), 0.0);
        let l = 1.0;
        let want = m * 0.25 * l * l * 31.0 / 512.0 / (m * speed * speed);
        let got = out.checks(&balls, speed).energy_increase;
        assert!((got / want - 1.0).abs() < 1e-12, "{got} vs {want}");
    }
}
