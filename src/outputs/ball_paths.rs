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

use crate::base::error::Error;
use crate::base::number::shortest;
use crate::base::validate::finite_output;
use crate::table_phase::path::BallPathRow;
use std::io::Write;

/// Default number of intervals of the ball paths.
pub(crate) const DEFAULT_BALL_PATH_SAMPLES: u64 = 200;

/// The header cells.
pub(crate) fn header() -> Vec<String> {
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

/// Writes the ball paths as CSV to `out` and returns it (flushed).
pub(crate) fn write_ball_paths<W: Write>(out: W, rows: &[BallPathRow]) -> Result<W, Error> {
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
