//! The trace CSV (docs/formats.md#trace-csv): one row per [`TraceRow`], streaming.

use crate::base::error::Error;
use crate::base::number::shortest;
use crate::base::validate::finite_output;
use crate::model::trace::{TraceRow, TraceSink};
use crate::scene::compliant::CompliantRow;
use crate::solve::plane::PlaneCollision;
use std::io::Write;

/// The header cells of the trace CSV.
pub(crate) const HEADER: [&str; 15] = [
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
pub(crate) const COMPRESSION_HEADER: &str = "delta (m)";

/// The header cells of the ball's columns of a plane scene (docs/plane.md), written last:
/// its velocity and spin in the lab axes, read from the equivalent pair's state.
pub(crate) const PLANE_HEADER: [&str; 6] = [
    "v_x (m/s)",
    "v_y (m/s)",
    "v_z (m/s)",
    "spin_x (rad/s)",
    "spin_y (rad/s)",
    "spin_z (rad/s)",
];

/// The header cells of a compliant run's columns (`contact.tangential = "mindlin"`,
/// docs/tangential.md#scenes), written last: the tangential force on ball A and the spring's
/// elastic displacement xi = -F_t / k_t, along y and z of the trace's frame, with Coulomb's
/// cap mu f between them.
pub(crate) const TANGENTIAL_HEADER: [&str; 5] =
    ["F_t_y (N)", "F_t_z (N)", "mu f (N)", "xi_y (m)", "xi_z (m)"];

/// Writes trace rows as CSV, streaming.
pub struct CsvTrace<W: Write> {
    out: csv::Writer<W>,
    rows: u64,
    /// Whether rows carry the compression column.
    compression: bool,
    /// The ball meeting a plane, whose columns follow (plane scenes).
    plane: Option<PlaneCollision>,
    /// Whether the tangential columns of a compliant run follow.
    tangential: bool,
}

impl<W: Write> CsvTrace<W> {
    /// A writer that starts with the header line.
    pub fn new(out: W) -> Result<Self, Error> {
        CsvTrace::with_columns(out, false)
    }

    /// A writer that starts with the header line, with the column `delta (m)` of a
    /// contact law when `compression` is true.
    pub fn with_columns(out: W, compression: bool) -> Result<Self, Error> {
        CsvTrace::start(out, compression, None)
    }

    /// [`CsvTrace::with_columns`] for the ball meeting `plane`: the rows are those of its
    /// equivalent pair, and the ball's velocity and spin columns follow (docs/plane.md).
    pub fn for_plane(out: W, compression: bool, plane: PlaneCollision) -> Result<Self, Error> {
        CsvTrace::start(out, compression, Some(plane))
    }

    /// The writer of a compliant run (`contact.tangential = "mindlin"`): the columns of a
    /// contact law (and of the ball meeting `plane`, for a plane scene), then the tangential
    /// force and the spring's displacement ([`CsvTrace::compliant_row`] writes them).
    pub fn for_compliant(out: W, plane: Option<PlaneCollision>) -> Result<Self, Error> {
        CsvTrace::start_with(out, true, plane, true)
    }

    fn start(out: W, compression: bool, plane: Option<PlaneCollision>) -> Result<Self, Error> {
        CsvTrace::start_with(out, compression, plane, false)
    }

    fn start_with(
        out: W,
        compression: bool,
        plane: Option<PlaneCollision>,
        tangential: bool,
    ) -> Result<Self, Error> {
        let mut out = csv::Writer::from_writer(out);
        for cell in HEADER {
            out.write_field(cell)?;
        }
        if compression {
            out.write_field(COMPRESSION_HEADER)?;
        }
        if plane.is_some() {
            for cell in PLANE_HEADER {
                out.write_field(cell)?;
            }
        }
        if tangential {
            for cell in TANGENTIAL_HEADER {
                out.write_field(cell)?;
            }
        }
        out.write_record(None::<&[u8]>)?;
        Ok(CsvTrace {
            out,
            rows: 0,
            compression,
            plane,
            tangential,
        })
    }

    /// One row of a compliant run with its tangential cells (a writer made by
    /// [`CsvTrace::for_compliant`]).
    pub fn compliant_row(&mut self, r: &CompliantRow) -> Result<(), Error> {
        self.cells(&r.row)?;
        let (f, xi) = (r.force, r.displacement);
        for (name, x) in TANGENTIAL_HEADER.iter().zip([f.x, f.y, r.cap, xi.x, xi.y]) {
            let x = finite_output(x, || format!("trace column {name} at t = {}", r.row.t))?;
            self.out.write_field(shortest(x + 0.0))?;
        }
        self.end_row()
    }

    fn end_row(&mut self) -> Result<(), Error> {
        self.out.write_record(None::<&[u8]>)?;
        self.rows += 1;
        Ok(())
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

impl<W: Write> CsvTrace<W> {
    /// The cells of `r` up to the tangential columns.
    fn cells(&mut self, r: &TraceRow) -> Result<(), Error> {
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
        if let Some(plane) = &self.plane {
            let (v, w) = (plane.velocity_of(&r.state), plane.spin_of(&r.state));
            for (name, x) in PLANE_HEADER.iter().zip(v.iter().chain(w.iter())) {
                let x = finite_output(*x, || format!("trace column {name} at t = {}", r.t))?;
                self.out.write_field(shortest(x + 0.0))?;
            }
        }
        Ok(())
    }
}

/// A trace CSV fed by a kernel's trace callback, which cannot fail: the first error is kept,
/// the rows after it are dropped, and [`StreamingCsv::finish`] returns it.
pub(crate) struct StreamingCsv<W: Write> {
    out: csv::Writer<W>,
    error: Option<Error>,
}

impl<W: Write> StreamingCsv<W> {
    /// A writer that starts with the header line `header`.
    pub(crate) fn new<T: AsRef<[u8]>>(
        out: W,
        header: impl IntoIterator<Item = T>,
    ) -> Result<Self, Error> {
        let mut out = csv::Writer::from_writer(out);
        out.write_record(header)?;
        Ok(StreamingCsv { out, error: None })
    }

    /// Writes one row, its cells written by `cells` (after an earlier error: nothing).
    pub(crate) fn row(&mut self, cells: impl FnOnce(&mut csv::Writer<W>) -> Result<(), Error>) {
        if self.error.is_none() {
            let written =
                cells(&mut self.out).and_then(|()| Ok(self.out.write_record(None::<&[u8]>)?));
            if let Err(e) = written {
                self.error = Some(e);
            }
        }
    }

    /// Flushes and returns the underlying writer, or the first error met.
    pub(crate) fn finish(self) -> Result<W, Error> {
        if let Some(e) = self.error {
            return Err(e);
        }
        self.out
            .into_inner()
            .map_err(|e| Error::io("trace", e.into_error()))
    }
}

/// A row without tangential cells: a compliant run's writer leaves them empty (its rows go
/// through [`CsvTrace::compliant_row`]).
impl<W: Write> TraceSink for CsvTrace<W> {
    fn row(&mut self, r: &TraceRow) -> Result<(), Error> {
        self.cells(r)?;
        if self.tangential {
            for _ in TANGENTIAL_HEADER {
                self.out.write_field("")?;
            }
        }
        self.end_row()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::state::CmState;
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
