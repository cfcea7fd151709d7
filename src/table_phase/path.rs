//! Both balls' motion sampled over time, from separation until both roll (until both rest
//! with rolling resistance): the rows of the ball path CSV and of the top view. The states
//! are exact (piecewise constant accelerations), not integrated.

use crate::model::state::LabBall;
use crate::table_phase::outcome::TableOutcome;
use crate::table_phase::roll_out::RollOut;
use crate::table_phase::segment::BallMotion;

/// One row of the ball paths: the time and both balls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallPathRow {
    /// Time since separation (s).
    pub t: f64,
    /// Ball A: phase and state.
    pub a: (BallMotion, LabBall),
    /// Ball B: phase and state.
    pub b: (BallMotion, LabBall),
}

/// The rows of the ball paths with `samples` (>= 1) uniform intervals plus the phase
/// changes.
pub fn ball_path_rows(t: &TableOutcome, samples: u64) -> Vec<BallPathRow> {
    let end = t.end_time();
    let n = samples.max(1);
    let mut times: Vec<f64> = (0..=n).map(|i| end * i as f64 / n as f64).collect();
    let boundaries = |r: &RollOut| -> Vec<f64> { r.segments.iter().map(|s| s.t0).collect() };
    times.extend(boundaries(&t.a));
    times.extend(boundaries(&t.b));
    times.extend(t.a.impact_times());
    times.extend(t.b.impact_times());
    times.retain(|x| *x <= end);
    times.sort_by(f64::total_cmp);
    times.dedup();
    let up = t.table.up;
    let jumps = |r: &RollOut, time: f64| r.impact_times().any(|x| x == time);
    let mut rows = Vec::with_capacity(times.len() + t.a.impacts.len() + t.b.impacts.len());
    for time in times {
        if jumps(&t.a, time) || jumps(&t.b, time) {
            rows.push(BallPathRow {
                t: time,
                a: before(&t.a, &up, time),
                b: before(&t.b, &up, time),
            });
        }
        rows.push(BallPathRow {
            t: time,
            a: t.a.at(&up, time, true),
            b: t.b.at(&up, time, true),
        });
    }
    rows
}

/// The state just before `time`: the separation state at t = 0.
fn before(r: &RollOut, up: &nalgebra::Vector3<f64>, time: f64) -> (BallMotion, LabBall) {
    if time == 0.0 {
        let phase = r.segments[0].phase;
        return (phase, r.start);
    }
    r.at(up, time, false)
}
