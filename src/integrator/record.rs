//! What a run records besides the state: trace rows, the first error, and the measures of
//! the accepted steps (theta drift, slip consistency).

use super::rhs::SlidingState;
use super::units::Units;
use crate::base::error::Error;
use crate::base::settings::Sampling;
use crate::model::state::slip_angle;
use crate::model::trace::{CoincidentRows, TraceRow, TraceSink};
use crate::profile::force::ForceProfile;
use nalgebra::{SVector, Vector2};

/// Mutable bookkeeping of a run.
pub(super) struct Recorder<'a> {
    sink: Option<&'a mut dyn TraceSink>,
    /// A row per accepted step (else only at the sample times and events).
    steps_mode: bool,
    /// Integration variable of the last row written (-1 before the first).
    last_row_x: f64,
    /// The first error met while observing (a non-finite state, a failed write).
    error: Option<Error>,
    /// Largest |slip x e0| / v_ref over accepted steps while sliding.
    pub(super) theta_drift: f64,
    /// Largest disagreement of the carried slip with the recomputed one (scaled).
    pub(super) slip_consistency: f64,
    /// The slip angle the trace rows carry (rad).
    theta_last: Option<f64>,
    /// Rows closer in time than its window written as one (sample rows against the located
    /// stop of sliding, or a contact law's end); `None`: every row as it comes.
    coincident: Option<CoincidentRows>,
}

impl<'a> Recorder<'a> {
    /// A recorder writing to `sink` (if any) with `sampling`; `theta` is the initial slip
    /// angle (rad).
    pub(super) fn new(
        trace: Option<(&'a mut dyn TraceSink, Sampling)>,
        theta: Option<f64>,
    ) -> Self {
        let (sink, sampling) = match trace {
            Some((s, m)) => (Some(s), m),
            None => (None, Sampling::Steps),
        };
        Recorder {
            sink,
            steps_mode: sampling == Sampling::Steps,
            last_row_x: -1.0,
            error: None,
            theta_drift: 0.0,
            slip_consistency: 0.0,
            theta_last: theta,
            coincident: None,
        }
    }

    /// From now on, of two rows that coincide in a contact of `contact_time` (s) only one is
    /// written: the stop of sliding's, else the later ([`CoincidentRows`]).
    /// [`Recorder::finish`] writes the last.
    pub(super) fn merge_coincident(&mut self, contact_time: f64) {
        self.coincident = Some(CoincidentRows::new(contact_time));
    }

    /// Writes the row held back by [`Recorder::merge_coincident`], if any.
    pub(super) fn finish(&mut self) {
        if let (Some(rows), Some(sink)) = (self.coincident.as_mut(), self.sink.as_deref_mut()) {
            if let Err(e) = rows.finish(sink) {
                self.error.get_or_insert(e);
            }
        }
    }

    /// Records a non-finite accepted state as the run's error; true when it was one (the
    /// observer then stops the solver).
    pub(super) fn flag_non_finite<const N: usize>(&mut self, v: &SVector<f64, N>) -> bool {
        match v.iter().copied().find(|x| !x.is_finite()) {
            None => false,
            Some(bad) => {
                self.error = Some(Error::NonFinite {
                    field: "state".to_string(),
                    value: bad,
                });
                true
            }
        }
    }

    /// Whether an error was recorded.
    pub(super) fn has_error(&self) -> bool {
        self.error.is_some()
    }

    /// The recorded error, if any, as an `Err` (and forgotten).
    pub(super) fn take_error(&mut self) -> Result<(), Error> {
        match self.error.take() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Writes the row of `y` at `time` (s; default from its integration variable), unless a
    /// row at or after it was written already or an error was recorded.
    pub(super) fn emit<P: ForceProfile + ?Sized>(
        &mut self,
        units: &Units<'_, P>,
        y: &SlidingState,
        time: Option<f64>,
    ) {
        self.emit_with(y.x(), |theta| units.row(y, time, theta));
    }

    /// [`Recorder::emit`] for the row of the stop of sliding, at `time` (s).
    pub(super) fn emit_stop<P: ForceProfile + ?Sized>(
        &mut self,
        units: &Units<'_, P>,
        y: &SlidingState,
        time: f64,
    ) {
        self.emit_stop_with(y.x(), |theta| units.row(y, Some(time), theta));
    }

    /// Writes the row `row` builds from the slip angle, for the state at integration
    /// variable `x`, unless a row at or after it was written already or an error was
    /// recorded.
    pub(super) fn emit_with(&mut self, x: f64, row: impl FnOnce(Option<f64>) -> TraceRow) {
        self.write(x, false, row);
    }

    /// [`Recorder::emit_with`] for the row of the stop of sliding.
    pub(super) fn emit_stop_with(&mut self, x: f64, row: impl FnOnce(Option<f64>) -> TraceRow) {
        self.write(x, true, row);
    }

    fn write(&mut self, x: f64, stop: bool, row: impl FnOnce(Option<f64>) -> TraceRow) {
        if self.error.is_some() || x <= self.last_row_x {
            return;
        }
        let theta = self.theta_last;
        if let Some(sink) = self.sink.as_deref_mut() {
            let written = match self.coincident.as_mut() {
                Some(rows) => rows.offer(sink, row(theta), stop),
                None => sink.row(&row(theta)),
            };
            if let Err(e) = written {
                self.error = Some(e);
            }
        }
        self.last_row_x = x;
    }

    /// Whether the trace takes a row per accepted step.
    pub(super) fn takes_steps(&self) -> bool {
        self.steps_mode
    }

    /// Writes the row of an accepted step when the trace takes one per step.
    pub(super) fn emit_step<P: ForceProfile + ?Sized>(
        &mut self,
        units: &Units<'_, P>,
        y: &SlidingState,
    ) {
        if self.steps_mode {
            self.emit(units, y, None);
        }
    }

    /// Measures an accepted step while sliding: the drift of the slip off e0, the
    /// consistency of the carried slip with `slip0` plus the changes, and (for a trace) the
    /// slip angle, kept from the last step whose slip is above `slip_floor`: near the stop
    /// the slip's direction is round-off.
    pub(super) fn measure_sliding(
        &mut self,
        st: &SlidingState,
        e0: Vector2<f64>,
        slip0: &Vector2<f64>,
        slip_floor: f64,
    ) {
        let slip = st.slip();
        self.theta_drift = self.theta_drift.max((slip.x * e0.y - slip.y * e0.x).abs());
        self.slip_consistency = self.slip_consistency.max(consistency(st, slip0));
        if self.sink.is_some() && slip.norm() > slip_floor {
            self.theta_last = Some(slip_angle(slip));
        }
    }

    /// Measures an accepted step after the stop with friction frozen along e0 (for a trace
    /// only): past the stop the signed slip S < 0 runs along -e0, and theta is the angle of
    /// slip / S, measured once the slip is clear of round-off (`slip_floor`) again (an angle
    /// kept from near the stop is noise).
    pub(super) fn measure_frozen(&mut self, st: &SlidingState, e0: Vector2<f64>, slip_floor: f64) {
        let slip = st.slip();
        if self.sink.is_some() && slip.norm() > slip_floor {
            let along = if slip.dot(&e0) < 0.0 { -slip } else { slip };
            self.theta_last = Some(slip_angle(along));
        }
    }
}

/// |carried slip - (2 dV + dOmega_z, 2 dW - dOmega_y) - slip0|, scaled.
fn consistency(st: &SlidingState, slip0: &Vector2<f64>) -> f64 {
    let [_, dv, dw] = st.delta_u();
    let [doy, doz] = st.delta_omega_yz();
    let recomputed = slip0 + Vector2::new(2.0 * dv + doz, 2.0 * dw - doy);
    (st.slip() - recomputed).amax()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The check compares the carried slip with the one recomputed from the carried changes
    /// (eqs 20-21: slip = slip(0) + (2 dV + dOmega_z, 2 dW - dOmega_y)). With slip(0) =
    /// (0.3, -0.1), dV = 0.05, dW = -0.02, dOmega_y = 0.04 and dOmega_z = 0.1 the slip is
    /// (0.5, -0.18); carried so, the check is zero, and a carried slip off by 0.25 in one
    /// component reads 0.25.
    #[test]
    fn consistency_reads_the_carried_slip_against_the_recomputed_one() {
        let slip0 = Vector2::new(0.3, -0.1);
        let mut y = SVector::<f64, 9>::zeros();
        (y[2], y[3], y[4], y[5]) = (0.05, -0.02, 0.04, 0.1);
        (y[6], y[7]) = (0.5, -0.18);
        let st = SlidingState(y);
        assert_eq!(st.slip(), Vector2::new(0.5, -0.18));
        assert_eq!(st.delta_u(), [0.0, 0.05, -0.02]);
        assert_eq!(st.delta_omega_yz(), [0.04, 0.1]);
        assert!(consistency(&st, &slip0) < 1e-15);
        y[7] += 0.25;
        let off = consistency(&SlidingState(y), &slip0);
        assert!((off - 0.25).abs() < 1e-15, "{off}");
    }

    /// A sink that keeps the rows' times and thetas and fails on demand.
    #[derive(Default)]
    struct Rows {
        got: Vec<(f64, Option<f64>)>,
        fail: bool,
    }

    impl TraceSink for Rows {
        fn row(&mut self, row: &TraceRow) -> Result<(), Error> {
            if self.fail {
                return Err(Error::io("trace", std::io::Error::other("disk full")));
            }
            self.got.push((row.t, row.theta));
            Ok(())
        }
    }

    fn row_at(t: f64) -> impl FnOnce(Option<f64>) -> TraceRow {
        move |theta| TraceRow {
            t,
            force: 0.0,
            impulse: 0.0,
            state: crate::model::state::CmState::new(
                nalgebra::Vector3::zeros(),
                nalgebra::Vector3::zeros(),
                nalgebra::Vector3::zeros(),
            ),
            slip_speed: 0.0,
            theta,
            heat_sliding: 0.0,
            compression: None,
        }
    }

    /// A state whose carried slip is `slip` and whose changes are zero.
    fn with_slip(slip: Vector2<f64>) -> SlidingState {
        let mut y = SVector::<f64, 9>::zeros();
        (y[6], y[7]) = (slip.x, slip.y);
        SlidingState(y)
    }

    /// A row at or before the last one written is not written; after a failed write no
    /// row is offered, and the failure is the run's error.
    #[test]
    fn rows_only_move_forward_and_stop_at_an_error() {
        let mut sink = Rows::default();
        let mut rec = Recorder::new(Some((&mut sink, Sampling::Steps)), Some(0.5));
        rec.emit_with(1.0, row_at(1.0));
        rec.emit_with(1.0, row_at(1.5));
        rec.emit_with(0.5, row_at(2.0));
        rec.emit_with(2.0, row_at(3.0));
        assert!(rec.take_error().is_ok());
        drop(rec);
        assert_eq!(sink.got, vec![(1.0, Some(0.5)), (3.0, Some(0.5))]);
        sink.fail = true;
        let mut rec = Recorder::new(Some((&mut sink, Sampling::Steps)), None);
        rec.emit_with(1.0, row_at(1.0));
        assert!(rec.has_error());
        drop(rec);
        sink.fail = false;
        let mut rec = Recorder::new(Some((&mut sink, Sampling::Steps)), None);
        rec.emit_with(1.0, row_at(1.0));
        rec.error = Some(Error::io("trace", std::io::Error::other("earlier")));
        rec.emit_with(2.0, row_at(2.0));
        drop(rec);
        assert_eq!(sink.got.len(), 3, "{:?}", sink.got);
    }

    /// The measures of a sliding step: the drift |slip x e0| (largest so far), and the
    /// rows' theta, the slip's angle atan2(S_y, S_x) taken only while |slip| is above the
    /// floor (below it the angle kept is the last one above).
    #[test]
    fn measure_sliding_keeps_the_largest_drift_and_the_angle_above_the_floor() {
        let mut sink = Rows::default();
        let e0 = Vector2::new(0.6, 0.8);
        let mut rec = Recorder::new(Some((&mut sink, Sampling::Steps)), Some(0.8f64.atan2(0.6)));
        let slip0 = Vector2::new(0.6, 0.8);
        // Along e0: no drift.
        rec.measure_sliding(&with_slip(slip0), e0, &slip0, 1e-3);
        assert_eq!(rec.theta_drift, 0.0);
        // Off e0 by 0.01 across it: drift 0.01; the angle is the slip's.
        let off = Vector2::new(0.3 - 0.008, 0.4 + 0.006);
        rec.measure_sliding(&with_slip(off), e0, &slip0, 1e-3);
        assert!(
            (rec.theta_drift - 0.01).abs() < 1e-15,
            "{}",
            rec.theta_drift
        );
        // The carried slip differs from slip0 with zero changes by 0.8 - 0.406 = 0.394 at most.
        assert!(
            (rec.slip_consistency - 0.394).abs() < 1e-15,
            "{}",
            rec.slip_consistency
        );
        rec.emit_with(1.0, row_at(1.0));
        // Below the floor: the angle stays; a smaller drift leaves the largest.
        let tiny = Vector2::new(-2e-4, 1e-4);
        rec.measure_sliding(&with_slip(tiny), e0, &slip0, 1e-3);
        assert!((rec.theta_drift - 0.01).abs() < 1e-15);
        rec.emit_with(2.0, row_at(2.0));
        drop(rec);
        let want = 0.406f64.atan2(0.292);
        assert_eq!(sink.got, vec![(1.0, Some(want)), (2.0, Some(want))]);
    }
}
