//! The paths of both balls on the table (`--path FILE.csv`): lab-frame positions,
//! velocities and spins over time, from separation until both roll (until both rest with
//! rolling resistance).
//!
//! Columns (header cells `name (unit)`): `t (s)`, then for ball A `a_x (m)`, `a_y (m)`,
//! `a_z (m)`, `a_vx (m/s)`, `a_vy (m/s)`, `a_vz (m/s)`, `a_wx (rad/s)`, `a_wy (rad/s)`,
//! `a_wz (rad/s)`, `a_phase` (flight, sliding, rolling, rest), and the same for B. Rows are
//! at t = i T / N, i = 0..N (T the end time), plus every change of phase; at an impact with
//! the cloth two rows share the time, the state just before and just after it. The states
//! are exact (piecewise constant accelerations), not integrated.

use crate::error::Error;
use crate::formats::number::{finite_output, shortest};
use crate::model::state::LabBall;
use crate::table_phase::{BallMotion, RollOut, TableOutcome};
use std::io::Write;

/// Default number of intervals of the ball paths.
pub const DEFAULT_BALL_PATH_SAMPLES: u64 = 200;

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

/// The header cells.
pub fn header() -> Vec<String> {
    let mut h = vec!["t (s)".to_string()];
    for ball in ["a", "b"] {
        for (q, unit) in [
            ("x", "m"),
            ("y", "m"),
            ("z", "m"),
            ("vx", "m/s"),
            ("vy", "m/s"),
            ("vz", "m/s"),
            ("wx", "rad/s"),
            ("wy", "rad/s"),
            ("wz", "rad/s"),
        ] {
            h.push(format!("{ball}_{q} ({unit})"));
        }
        h.push(format!("{ball}_phase"));
    }
    h
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

/// Writes the ball paths as CSV to `out` and returns it (flushed).
pub fn write_ball_paths<W: Write>(out: W, rows: &[BallPathRow]) -> Result<W, Error> {
    let mut w = csv::Writer::from_writer(out);
    let head = header();
    w.write_record(&head)?;
    for row in rows {
        let mut cells = Vec::with_capacity(head.len());
        let cell = |v: f64, column: &str| {
            finite_output(v, || format!("path column {column} at t = {}", row.t)).map(shortest)
        };
        cells.push(cell(row.t, "t")?);
        for (name, (phase, s)) in [("a", row.a), ("b", row.b)] {
            for (q, v) in [
                ("x", s.position.x),
                ("y", s.position.y),
                ("z", s.position.z),
                ("vx", s.velocity.x),
                ("vy", s.velocity.y),
                ("vz", s.velocity.z),
                ("wx", s.spin.x),
                ("wy", s.spin.y),
                ("wz", s.spin.z),
            ] {
                cells.push(cell(v, &format!("{name}_{q}"))?);
            }
            cells.push(phase.name().to_string());
        }
        w.write_record(&cells)?;
    }
    w.into_inner()
        .map_err(|e| Error::io("path", e.into_error()))
}
