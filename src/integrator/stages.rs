//! The stages of the contact and the stepping of one stage to the end of a segment: sliding
//! (watching for the stop), sliding with friction frozen along e0, and the normal force
//! alone (docs/model.md#time-stepping).

use super::record::Recorder;
use super::rhs::{
    Direction, NormalRhs, NormalState, SlidingRhs, SlidingState, NORMAL_DIM, SLIP_ROUND_OFF,
};
use super::stepping::Stepper;
use super::stop_event::{locate_stop, STOP_FLOOR};
use super::time_map::TimeMap;
use super::units::Units;
use crate::base::error::Error;
use crate::model::collision::Collision;
use crate::profile::force::ForceProfile;
use nalgebra::{SVector, Vector2};

/// Which equations the stepping integrates: the stage the contact is in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum ContactStage {
    /// Sliding with the direction from the current slip (eqs 14-19), watching for the stop.
    Sliding,
    /// Sliding with friction frozen along e0 (after the stop, effect `stick = false`).
    Frozen,
    /// Normal force only (eq 14); the tangential part of the state is frozen.
    Normal,
}

/// Why the stepping of a stage ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum StopReason {
    /// The end of the segment was reached.
    ReachedEnd,
    /// Sliding stopped inside the segment; the state returned with it is the located stop.
    SlidingStopped {
        /// Time t_stick (s) at which the profile's exact p(t) reaches the impulse the
        /// integrator delivered up to the stop.
        time: f64,
        /// That impulse p(t_stick) (N s).
        impulse: f64,
    },
}

/// The mutable side of a run: the stepper (method, carried step size, work) and the
/// recorder (trace, first error, measures).
pub(super) struct Run<'r> {
    pub(super) stepper: Stepper,
    pub(super) rec: Recorder<'r>,
}

/// A collision in the integrator's scaled variables: the right-hand sides and what the
/// stages share.
pub(super) struct Problem<'a, P: ForceProfile + ?Sized> {
    pub(super) c: &'a Collision,
    pub(super) profile: &'a P,
    pub(super) units: Units<'a, P>,
    /// The integration variable's map to the scaled time.
    pub(super) time_map: TimeMap,
    /// pi = P / (m v_ref).
    pi: f64,
    /// Initial sliding direction e0 (unit; zero without sliding).
    pub(super) e0: Vector2<f64>,
    /// Scaled incoming slip.
    pub(super) slip0: Vector2<f64>,
    /// The event function at or below which the slip counts as stopped ([`STOP_FLOOR`]).
    pub(super) stop_floor: f64,
}

impl<'a, P: ForceProfile + ?Sized> Problem<'a, P> {
    /// The scaled problem of collision `c` under force profile `profile`, integrated in the
    /// variable of `time_map`.
    pub(super) fn new(c: &'a Collision, profile: &'a P, time_map: TimeMap) -> Self {
        let sc = c.scales;
        let slip0 = c.incoming.slip_of(&c.balls) / sc.speed;
        Problem {
            c,
            profile,
            units: Units::new(c, profile, time_map),
            time_map,
            pi: c.impulse / sc.impulse,
            e0: c.direction.unwrap_or_else(Vector2::zeros),
            slip0,
            stop_floor: STOP_FLOOR * slip0.norm(),
        }
    }

    /// Eqs 14-19 with the friction direction taken by `direction`.
    pub(super) fn sliding_rhs(&self, direction: Direction) -> SlidingRhs<'a, P> {
        SlidingRhs {
            profile: self.profile,
            time_map: self.time_map,
            impulse: self.pi,
            friction: self.c.active_friction().unwrap_or(self.c.contact.friction),
            speed_scale: self.c.scales.speed,
            inv_alpha: self.c.balls.scaled_inverse_alphas(),
            e0: self.e0,
            direction,
            slip_floor: SLIP_ROUND_OFF * self.slip0.norm(),
        }
    }

    /// Steps `stage` from `y` towards the segment's end `stop`, until it is reached or
    /// sliding stops.
    pub(super) fn step(
        &self,
        stage: ContactStage,
        y: SlidingState,
        stop: f64,
        run: &mut Run<'_>,
    ) -> Result<(SlidingState, StopReason), Error> {
        match stage {
            ContactStage::Sliding => self.slide(y, stop, run),
            ContactStage::Frozen => Ok((self.slide_frozen(y, stop, run)?, StopReason::ReachedEnd)),
            ContactStage::Normal => Ok((self.press(y, stop, run)?, StopReason::ReachedEnd)),
        }
    }

    /// Sliding: stops at the end of the segment, or at the located stop of sliding.
    fn slide(
        &self,
        y: SlidingState,
        stop: f64,
        run: &mut Run<'_>,
    ) -> Result<(SlidingState, StopReason), Error> {
        let rhs = self.sliding_rhs(Direction::CurrentSlip);
        let mut prev = y;
        let mut crossed = None;
        let end = run
            .stepper
            .advance_checked(&rhs, y.0, stop, &mut run.rec, |rec, v| {
                let st = SlidingState(*v);
                // A slip within round-off of zero has stopped: a step that lands there (a
                // sample time, a breakpoint) is the stop itself.
                if rhs.event(&st) <= self.stop_floor {
                    crossed = Some(st);
                    return true;
                }
                rec.measure_sliding(&st, self.e0, &self.slip0, rhs.slip_floor);
                rec.emit_step(&self.units, &st);
                prev = st;
                false
            })?;
        let Some(cross) = crossed else {
            return Ok((SlidingState(end), StopReason::ReachedEnd));
        };
        let at = locate_stop(&rhs, &mut run.stepper, self.profile, &prev, &cross)?;
        // The event is pinned down by the impulse (docs/model.md#locating-the-stop-of-sliding):
        // the fraction q of P the integrator itself delivered up to the stop (-Delta U / pi),
        // and the time at which the exact p(t) reaches it. Where the method's own quadrature
        // of f is coarse (rk4 on a t^0.5 end) its internal time is off, not the impulse.
        let q = (-at.delta_u()[0] / self.pi).clamp(0.0, 1.0);
        let time = self.profile.time_at_cumulative(q) * self.profile.duration();
        let impulse = q * self.c.impulse;
        Ok((at, StopReason::SlidingStopped { time, impulse }))
    }

    /// Sliding after the stop with friction frozen along e0 (`stick = false`).
    fn slide_frozen(
        &self,
        y: SlidingState,
        stop: f64,
        run: &mut Run<'_>,
    ) -> Result<SlidingState, Error> {
        let rhs = self.sliding_rhs(Direction::Frozen);
        let end = run
            .stepper
            .advance_checked(&rhs, y.0, stop, &mut run.rec, |rec, v| {
                let st = SlidingState(*v);
                rec.measure_frozen(&st, self.e0, rhs.slip_floor);
                rec.emit_step(&self.units, &st);
                false
            })?;
        Ok(SlidingState(end))
    }

    /// The normal force alone (no friction, or stuck): only x and U move.
    fn press(&self, y: SlidingState, stop: f64, run: &mut Run<'_>) -> Result<SlidingState, Error> {
        let rhs = NormalRhs {
            profile: self.profile,
            time_map: self.time_map,
            impulse: self.pi,
        };
        let full = |v: &SVector<f64, NORMAL_DIM>| {
            let n = NormalState(*v);
            let mut st = y;
            st.set_x(n.x());
            st.set_delta_u_normal(n.delta_u());
            st
        };
        let y0 = NormalState::new(y.x(), y.delta_u()[0]);
        let end = run
            .stepper
            .advance_checked(&rhs, y0.0, stop, &mut run.rec, |rec, v| {
                if rec.takes_steps() {
                    rec.emit(&self.units, &full(v), None);
                }
                false
            })?;
        Ok(full(&end))
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::base::settings::SolverSettings;
    use crate::model::effects::Effects;
    use crate::model::params::{Ball, Contact, Friction, ImpulseRule};
    use crate::model::state::CmState;
    use crate::profile::half_sine::HalfSine;
    use nalgebra::Vector3;
    use std::f64::consts::PI;

    pub(crate) const M: f64 = 0.17;
    const R: f64 = 0.028575;
    const ALPHA: f64 = 0.4;
    const MU: f64 = 0.06;
    pub(crate) const TAU: f64 = 2.5e-4;

    /// A stun shot, U(0) = `u` (m/s), V(0) = `v` (m/s), no spin, e = 1: S(0) = 2V.
    pub(crate) fn stun(u: f64, v: f64) -> Collision {
        let ball = Ball::new(M, R, ALPHA).unwrap();
        let contact = Contact {
            friction: Friction::constant(MU).unwrap(),
            impulse: ImpulseRule::restitution(1.0).unwrap(),
        };
        let s = CmState::new(Vector3::new(u, v, 0.0), Vector3::zeros(), Vector3::zeros());
        Collision::new(ball, contact, Effects::default(), s).unwrap()
    }

    fn step_sliding(c: &Collision) -> (SlidingState, StopReason) {
        let profile = HalfSine::new(TAU).unwrap();
        let problem = Problem::new(c, &profile, TimeMap::Identity);
        let mut run = Run {
            stepper: Stepper::new(&SolverSettings::default()).unwrap(),
            rec: Recorder::new(None, c.theta()),
        };
        let y0 = SlidingState::initial(problem.slip0);
        problem
            .step(ContactStage::Sliding, y0, 1.0, &mut run)
            .unwrap()
    }

    /// A small cut sticks: the sliding stage stops at the stop of sliding and says so.
    /// Reference (eq 22): dS/dp = -2 mu (1 + 1/alpha) / m, so S(0) = 2V reaches 0 at
    /// p_stick = m 2V / (2 mu (1 + 1/alpha)); for the half-sine p(t) = P sin^2(pi t / (2 tau)),
    /// so t_stick = (2 tau / pi) asin(sqrt(p_stick / P)).
    #[test]
    fn sliding_stage_reports_the_stop() {
        let (u, v) = (0.5, 0.02);
        let (y, reason) = step_sliding(&stun(u, v));
        let big_p = 2.0 * M * u;
        let p_stick = M * 2.0 * v / (2.0 * MU * (1.0 + 1.0 / ALPHA));
        let t_stick = 2.0 * TAU / PI * (p_stick / big_p).sqrt().asin();
        let StopReason::SlidingStopped { time, impulse } = reason else {
            panic!("{reason:?}");
        };
        assert!(
            (impulse - p_stick).abs() < 1e-10 * big_p,
            "{impulse} vs {p_stick}"
        );
        assert!((time - t_stick).abs() < 1e-10 * TAU, "{time} vs {t_stick}");
        // The state returned is the located stop: inside the contact, slip ~ 0.
        assert!(y.x() < 1.0 && (y.x() * TAU - t_stick).abs() < 1e-6 * TAU);
        assert!(y.slip().norm() < 1e-9 * (2.0 * v) / c_speed(u, v));
    }

    /// v_ref of a stun shot: max(S(0), |U(0)|).
    fn c_speed(u: f64, v: f64) -> f64 {
        (2.0 * v).max(u.hypot(v))
    }

    /// A wide cut slides throughout (p_stick = 0.2 N s > P = 0.17 N s): the stage reaches
    /// the end of the segment.
    #[test]
    fn sliding_stage_without_stop_reaches_the_end() {
        let (y, reason) = step_sliding(&stun(0.5, 0.25));
        assert_eq!(reason, StopReason::ReachedEnd);
        assert_eq!(y.x(), 1.0);
        assert!(y.slip().norm() > 0.0);
    }
}
