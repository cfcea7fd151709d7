//! Trace rows of a run and their CSV form.
//!
//! Columns (header cells `name (unit)`, docs/formats.md#trace-csv): `t (s)`, `f (N)`, `p (N s)`,
//! `U (m/s)`, `V (m/s)`, `W (m/s)`, `omega_a_x (rad/s)` .. `omega_b_z (rad/s)`, `S (m/s)`,
//! `theta (rad)`, `H_sfr (J)`, and with a contact law (docs/contact-law.md) `delta (m)`.
//! The state is the paper's centre-of-mass frame. After sticking, S is 0 and theta is the
//! last sliding value; theta is empty when S(0) = 0.

use crate::error::Error;
use crate::formats::number::{finite_output, shortest};
use crate::model::state::CmState;
use std::io::Write;

/// One row of a trace.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraceRow {
    /// Time t (s).
    pub t: f64,
    /// Normal force f(t) (N).
    pub force: f64,
    /// Cumulative normal impulse p(t) (N s).
    pub impulse: f64,
    /// Centre-of-mass state.
    pub state: CmState,
    /// Sliding speed S (m/s), signed along e0 (negative only with `stick = false`).
    pub slip_speed: f64,
    /// Sliding direction theta (rad); `None` when undefined (S(0) = 0).
    pub theta: Option<f64>,
    /// Sliding heat H_sfr so far (J).
    pub heat_sliding: f64,
    /// Compression delta (m) of a contact law; `None` for a prescribed profile.
    pub compression: Option<f64>,
}

impl TraceRow {
    /// The row's cells in the order of [`HEADER`], in its units; `None` for an empty cell
    /// (theta when undefined).
    pub fn values(&self) -> [Option<f64>; 15] {
        let s = &self.state;
        [
            Some(self.t),
            Some(self.force),
            Some(self.impulse),
            Some(s.u_cm.x),
            Some(s.u_cm.y),
            Some(s.u_cm.z),
            Some(s.omega_a.x),
            Some(s.omega_a.y),
            Some(s.omega_a.z),
            Some(s.omega_b.x),
            Some(s.omega_b.y),
            Some(s.omega_b.z),
            Some(self.slip_speed),
            self.theta,
            Some(self.heat_sliding),
        ]
    }
}

/// Receives trace rows as they are produced (streaming: nothing is kept in memory).
pub trait TraceSink {
    /// Takes one row.
    fn row(&mut self, row: &TraceRow) -> Result<(), Error>;
}

/// Rows closer than this fraction of the contact time are one row. A located event and a
/// sample time that it falls on differ by round-off (1e-16 to 1e-11 of the contact time);
/// sample times are a contact time / N apart, far more for any N below 1e9.
const COINCIDENT: f64 = 1e-9;

/// Of two rows closer in time than [`COINCIDENT`] contact times, writes one: the stop of
/// sliding's when either is it, else the later. The stop of sliding (and under a contact law
/// the end of the contact) is located as an event, and where it falls on a sample time the
/// two times agree only to round-off, in either order (docs/formats.md#trace-csv: a stop that
/// falls on a sample time is written once).
#[derive(Debug, Clone, Copy)]
pub(crate) struct CoincidentRows {
    /// Rows closer than this (s) are one.
    window: f64,
    /// The row held back until the next shows whether it coincides, and whether it is the
    /// stop's.
    held: Option<(TraceRow, bool)>,
}

impl CoincidentRows {
    /// Merges the rows of a contact of `contact_time` (s).
    pub(crate) fn new(contact_time: f64) -> Self {
        CoincidentRows {
            window: COINCIDENT * contact_time,
            held: None,
        }
    }

    /// Takes `row` (`stop`: the row of the stop of sliding), writing the row held before it
    /// to `sink` when the two are clear of each other.
    pub(crate) fn offer(
        &mut self,
        sink: &mut dyn TraceSink,
        row: TraceRow,
        stop: bool,
    ) -> Result<(), Error> {
        self.held = match self.held.take() {
            Some(held) if row.t - held.0.t > self.window => {
                sink.row(&held.0)?;
                Some((row, stop))
            }
            Some(held) if held.1 => Some(held),
            _ => Some((row, stop)),
        };
        Ok(())
    }

    /// Writes the row held back, if any.
    pub(crate) fn finish(&mut self, sink: &mut dyn TraceSink) -> Result<(), Error> {
        match self.held.take() {
            Some((row, _)) => sink.row(&row),
            None => Ok(()),
        }
    }
}

/// Collects rows in memory (tests, examples, small runs).
impl TraceSink for Vec<TraceRow> {
    fn row(&mut self, row: &TraceRow) -> Result<(), Error> {
        self.push(*row);
        Ok(())
    }
}

/// The header cells of the trace CSV.
pub const HEADER: [&str; 15] = [
    "t (s)",
    "f (N)",
    "p (N s)",
    "U (m/s)",
    "V (m/s)",
    "W (m/s)",
    "omega_a_x (rad/s)",
    "omega_a_y (rad/s)",
    "omega_a_z (rad/s)",
    "omega_b_x (rad/s)",
    "omega_b_y (rad/s)",
    "omega_b_z (rad/s)",
    "S (m/s)",
    "theta (rad)",
    "H_sfr (J)",
];

/// The header cell of the compression column, written after [`HEADER`] with a contact law.
pub const COMPRESSION_HEADER: &str = "delta (m)";

/// Writes trace rows as CSV, streaming.
pub struct CsvTrace<W: Write> {
    out: csv::Writer<W>,
    rows: u64,
    /// Whether rows carry the compression column.
    compression: bool,
}

impl<W: Write> CsvTrace<W> {
    /// A writer that starts with the header line.
    pub fn new(out: W) -> Result<Self, Error> {
        CsvTrace::with_columns(out, false)
    }

    /// A writer that starts with the header line, with the column `delta (m)` of a
    /// contact law when `compression` is true.
    pub fn with_columns(out: W, compression: bool) -> Result<Self, Error> {
        let mut out = csv::Writer::from_writer(out);
        for cell in HEADER {
            out.write_field(cell)?;
        }
        if compression {
            out.write_field(COMPRESSION_HEADER)?;
        }
        out.write_record(None::<&[u8]>)?;
        Ok(CsvTrace {
            out,
            rows: 0,
            compression,
        })
    }

    /// Rows written so far.
    pub fn rows(&self) -> u64 {
        self.rows
    }

    /// Flushes and returns the underlying writer.
    pub fn finish(self) -> Result<W, Error> {
        self.out
            .into_inner()
            .map_err(|e| Error::io("trace", e.into_error()))
    }
}

impl<W: Write> TraceSink for CsvTrace<W> {
    fn row(&mut self, r: &TraceRow) -> Result<(), Error> {
        for (name, v) in HEADER.iter().zip(r.values()) {
            match v {
                Some(v) => {
                    let v = finite_output(v, || format!("trace column {name} at t = {}", r.t))?;
                    // + 0.0: a zero is written 0.0, never -0.0 (a contact law's p(0) and
                    // H_sfr(0) come out as -0.0).
                    self.out.write_field(shortest(v + 0.0))?;
                }
                None => self.out.write_field("")?,
            }
        }
        if self.compression {
            let delta = r.compression.unwrap_or(0.0);
            let delta = finite_output(delta, || format!("trace column delta at t = {}", r.t))?;
            self.out.write_field(shortest(delta + 0.0))?;
        }
        self.out.write_record(None::<&[u8]>)?;
        self.rows += 1;
        Ok(())
    }
}

/// Sends every row to two sinks (e.g. the CSV file and the rows a figure is drawn from).
pub struct Tee<'a>(pub &'a mut dyn TraceSink, pub &'a mut dyn TraceSink);

impl TraceSink for Tee<'_> {
    fn row(&mut self, row: &TraceRow) -> Result<(), Error> {
        self.0.row(row)?;
        self.1.row(row)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    /// `rows()` counts the rows written, one line each after the header.
    #[test]
    fn counts_the_rows_written() {
        let mut trace = CsvTrace::new(Vec::new()).unwrap();
        assert_eq!(trace.rows(), 0);
        let zero = Vector3::zeros();
        for k in 0..3 {
            let row = TraceRow {
                t: k as f64 * 1e-4,
                force: 10.0,
                impulse: k as f64 * 1e-3,
                state: CmState::new(Vector3::x(), zero, zero),
                slip_speed: 0.5,
                theta: Some(0.25),
                heat_sliding: 0.0,
                compression: None,
            };
            trace.row(&row).unwrap();
        }
        assert_eq!(trace.rows(), 3);
        let text = String::from_utf8(trace.finish().unwrap()).unwrap();
        assert_eq!(text.lines().count(), 4);
    }

    /// Zeros are written 0.0 whatever their sign: -0.0 in a CSV reads as a value below 0.
    #[test]
    fn negative_zero_is_written_as_zero() {
        let mut trace = CsvTrace::with_columns(Vec::new(), true).unwrap();
        let z = Vector3::new(-0.0, -0.0, -0.0);
        let row = TraceRow {
            t: 0.0,
            force: -0.0,
            impulse: -0.0,
            state: CmState::new(z, z, z),
            slip_speed: -0.0,
            theta: Some(-0.0),
            heat_sliding: -0.0,
            compression: Some(-0.0),
        };
        trace.row(&row).unwrap();
        let text = String::from_utf8(trace.finish().unwrap()).unwrap();
        let cells: Vec<&str> = text.lines().nth(1).unwrap().split(',').collect();
        assert_eq!(cells, vec!["0.0"; 16], "{text}");
    }
}
