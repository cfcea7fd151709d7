//! Trace rows of a run: what the solvers report at each step, and the sinks they go to
//! (the CSV writer is `outputs::trace_csv`).
//!
//! Columns (header cells `name (unit)`, docs/formats.md#trace-csv): `t (s)`, `f (N)`, `p (N s)`,
//! `U (m/s)`, `V (m/s)`, `W (m/s)`, `omega_a_x (rad/s)` .. `omega_b_z (rad/s)`, `S (m/s)`,
//! `theta (rad)`, `H_sfr (J)`, and with a contact law (docs/contact-law.md) `delta (m)`.
//! The state is the paper's centre-of-mass frame. After sticking, S is 0 and theta is the
//! last sliding value; theta is empty when S(0) = 0.

use crate::base::error::Error;
use crate::model::state::CmState;

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
    /// The row's cells in the order of the trace CSV's columns (docs/formats.md#trace-csv), in its units; `None` for an empty cell
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

/// Sends every row to two sinks (e.g. the CSV file and the rows a figure is drawn from).
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
pub(crate) struct Tee<'a>(pub &'a mut dyn TraceSink, pub &'a mut dyn TraceSink);

impl TraceSink for Tee<'_> {
    fn row(&mut self, row: &TraceRow) -> Result<(), Error> {
        self.0.row(row)?;
        self.1.row(row)
    }
}
