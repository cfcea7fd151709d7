//! The driver of a time-stepping run: segments between breakpoints and samples, the stages
//! of the contact, the result.
//!
//! The integration runs in the scaled variables of [`crate::integrator::rhs`], stepping in
//! the integration variable x of a [`TimeMap`] (the scaled time itself, or a smoothing
//! change of variable for pulses with algebraic ends). It proceeds in segments ending at the
//! profile's breakpoints (kinks or jumps of f: the integrators step exactly to them), at the
//! graded ends of [`GRADED_ENDS`] for algebraic ends without the time transform, and, with
//! `--samples N`, at the sample times i/N, each mapped to x. While the balls slide,
//! every accepted step evaluates the event function g = slip . e0; the step that makes it
//! non-positive has crossed the stop. The stop is then located inside that step by
//! re-integrating from the step's start, with the same method, to trial times chosen by
//! regula falsi (Illinois) in the impulse fraction q = Phi(s): g is affine in q while mu is
//! constant, so the iteration converges in one or two trials, and the located state is the
//! integrator's own. After the stop the rest of the pulse is integrated with the normal
//! equation alone (sticking), or with friction frozen along e0 (effect `stick = false`).

use super::record::Recorder;
use super::rhs::SlidingState;
use super::stages::{ContactStage, Problem, Run, StopReason};
use super::stepping::Stepper;
use super::time_map::{TimeMap, GRADED_ENDS};
use crate::base::error::Error;
use crate::base::settings::{Sampling, SolverSettings, Stats};
use crate::model::collision::Collision;
use crate::model::state::CmState;
use crate::model::trace::TraceSink;
use crate::profile::force::ForceProfile;
use nalgebra::Vector2;

/// The result of a time-stepping run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Integrated {
    /// Outgoing centre-of-mass state.
    pub out: CmState,
    /// Integrated sliding heat H_sfr (J).
    pub heat_sliding: f64,
    /// Signed outgoing sliding speed along e0 (m/s); 0 after sticking.
    pub s_out: f64,
    /// Whether sliding stopped during the contact.
    pub sticks: bool,
    /// Time (s) at which sliding stopped.
    pub stick_time: Option<f64>,
    /// Impulse p(t_stick) (N s) at which sliding stopped.
    pub stick_impulse: Option<f64>,
    /// Largest |slip x e0| / v_ref over accepted steps while sliding.
    pub theta_drift: f64,
    /// Largest |slip - (2V + r Omega_z, 2W - r Omega_y)| / v_ref over accepted steps: the
    /// carried slip against the one recomputed from velocities and spins.
    pub slip_consistency: f64,
    /// Work done.
    pub stats: Stats,
}

/// Where sliding stopped, if it did.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Stop {
    /// Whether the surfaces stick (the stop with effect `stick = true`, or S(0) = 0).
    pub(super) sticks: bool,
    /// Time (s) of the stop.
    pub(super) time: Option<f64>,
    /// Impulse (N s) at the stop.
    pub(super) impulse: Option<f64>,
}

/// Integrates a collision that happens (U(0) > 0) with the given settings (not
/// `closed-form`), optionally writing a trace.
///
/// Errors: [`Error::InvalidParameter`] for a collision without impulse (`collision.impulse`)
/// or the method `closed-form` (`solver.method`); the solver's failures
/// ([`Error::StepSizeTooSmall`], [`Error::TooManySteps`], [`Error::Stiff`]); a non-finite
/// state ([`Error::NonFinite`]); and the trace sink's errors.
pub fn integrate<P: ForceProfile + ?Sized>(
    c: &Collision,
    profile: &P,
    settings: &SolverSettings,
    trace: Option<(&mut dyn TraceSink, Sampling)>,
) -> Result<Integrated, Error> {
    if !c.collides() {
        return Err(Error::invalid(
            "collision.impulse",
            c.impulse,
            "> 0 N s: integrate needs balls that approach (U(0) > 0)",
        ));
    }
    let time_map = TimeMap::for_run(profile, settings);
    let problem = Problem::new(c, profile, time_map);
    let sampling = trace.as_ref().map_or(Sampling::Steps, |t| t.1);
    let mut run = Run {
        stepper: Stepper::new(settings)?,
        rec: Recorder::new(trace, c.theta()),
    };
    if sampling != Sampling::Steps {
        run.rec.merge_coincident(profile.duration());
    }
    let mut y = SlidingState::initial(problem.slip0);
    let (mut stage, mut stop) = initial_stage(c);
    run.rec.emit(&problem.units, &y, Some(0.0));

    let (kinks, graded): (&[f64], &[f64]) = match settings.breakpoints() {
        false => (&[], &[]),
        true if time_map.is_identity() && profile.end_power().is_some() => {
            (profile.breakpoints(), &GRADED_ENDS)
        }
        true => (profile.breakpoints(), &[]),
    };
    let mut segments = Segments::new([kinks, graded], sampling, time_map, profile);
    let mut x = 0.0;
    while x < 1.0 {
        let end = segments.end_after(x);
        while y.x() < end {
            let (next, reason) = problem.step(stage, y, end, &mut run)?;
            y = next;
            if let StopReason::SlidingStopped { time, impulse } = reason {
                (stop.time, stop.impulse) = (Some(time), Some(impulse));
                if c.effects.stick {
                    stop.sticks = true;
                    y.set_slip(Vector2::zeros());
                    stage = ContactStage::Normal;
                } else {
                    stage = ContactStage::Frozen;
                }
                run.rec.emit_stop(&problem.units, &y, time);
            }
        }
        x = end;
        if let Some(t) = segments.sample_reached(x, profile.duration()) {
            run.rec.emit(&problem.units, &y, Some(t));
        }
    }
    run.rec.finish();
    run.rec.take_error()?;
    Ok(result(&problem, &y, stop, &run))
}

/// The stage the contact starts in, and the stop when there is no sliding to stop.
pub(super) fn initial_stage(c: &Collision) -> (ContactStage, Stop) {
    match c.active_friction() {
        Some(_) if c.s0 > 0.0 => (ContactStage::Sliding, Stop::default()),
        // S(0) = 0: the surfaces do not slide at all (docs/model.md#no-initial-sliding).
        Some(_) => (
            ContactStage::Normal,
            Stop {
                sticks: true,
                time: Some(0.0),
                impulse: Some(0.0),
            },
        ),
        None => (ContactStage::Normal, Stop::default()),
    }
}

/// The run's result from the final scaled state `y`.
pub(super) fn result<P: ForceProfile + ?Sized>(
    problem: &Problem<'_, P>,
    y: &SlidingState,
    stop: Stop,
    run: &Run<'_>,
) -> Integrated {
    let c = problem.c;
    let s_out = if c.active_friction().is_none() {
        c.s0
    } else if stop.sticks {
        0.0
    } else {
        problem.units.slip_along_e0(y)
    };
    Integrated {
        out: problem.units.state(y),
        heat_sliding: problem.units.heat(y),
        s_out,
        sticks: stop.sticks,
        stick_time: stop.time,
        stick_impulse: stop.impulse,
        theta_drift: run.rec.theta_drift,
        slip_consistency: run.rec.slip_consistency,
        stats: run.stepper.stats,
    }
}

/// The ends of the segments: the breakpoints (the profile's kinks, the graded ends) and the
/// sample times, given in scaled time and mapped to the integration variable.
struct Segments<'a, P: ForceProfile + ?Sized> {
    /// Sorted lists of breakpoints in scaled time.
    lists: [&'a [f64]; 2],
    /// The pulse, whose cumulative impulse the time map may follow.
    profile: &'a P,
    /// Index, in each list, of the next breakpoint not yet passed.
    next: [usize; 2],
    /// The map from the integration variable to the scaled time.
    time_map: TimeMap,
    /// Number of sample intervals N (0: no samples).
    samples: u64,
    /// Index i of the next sample time i / N.
    next_sample: u64,
    /// The integration variable of the sample time among the current segment's candidate
    /// ends.
    sample_x: Option<f64>,
}

impl<'a, P: ForceProfile + ?Sized> Segments<'a, P> {
    fn new(lists: [&'a [f64]; 2], sampling: Sampling, time_map: TimeMap, profile: &'a P) -> Self {
        Segments {
            lists,
            profile,
            next: [0; 2],
            time_map,
            samples: match sampling {
                Sampling::Uniform(n) => n.max(1),
                Sampling::Steps => 0,
            },
            next_sample: 1,
            sample_x: None,
        }
    }

    /// The end of the segment that starts at integration variable `x`: the next breakpoint
    /// after it, the next sample time or the end of the contact, whichever comes first.
    fn end_after(&mut self, x: f64) -> f64 {
        let map = self.time_map;
        let mut end = 1.0_f64;
        for (list, next) in self.lists.iter().zip(self.next.iter_mut()) {
            while *next < list.len() && map.at_time(self.profile, list[*next]) <= x {
                *next += 1;
            }
            if let Some(&b) = list.get(*next) {
                end = end.min(map.at_time(self.profile, b));
            }
        }
        let profile = self.profile;
        self.sample_x = (self.samples > 0)
            .then(|| map.at_time(profile, self.next_sample as f64 / self.samples as f64));
        if let Some(xs) = self.sample_x {
            end = end.min(xs);
        }
        end
    }

    /// After the segment ending at `end`: the time (s) of the sample row due there, for a
    /// contact of `duration` (s), if any.
    fn sample_reached(&mut self, end: f64, duration: f64) -> Option<f64> {
        if self.sample_x != Some(end) {
            return None;
        }
        let t = self.next_sample as f64 * duration / self.samples as f64;
        self.next_sample += 1;
        Some(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::base::method::Method;
    use crate::integrator::stages::tests::{stun, TAU};
    use crate::profile::half_sine::HalfSine;

    fn dopri5() -> SolverSettings {
        SolverSettings::new(Method::Dopri5, 1e-10, 1e-10, 1000).unwrap()
    }

    #[test]
    fn refuses_balls_that_do_not_approach() {
        let c = stun(-0.5, 0.1);
        assert!(!c.collides());
        let p = HalfSine::new(TAU).unwrap();
        match integrate(&c, &p, &dopri5(), None) {
            Err(Error::InvalidParameter { field, .. }) => assert_eq!(field, "collision.impulse"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn refuses_the_closed_form() {
        let p = HalfSine::new(TAU).unwrap();
        let s = SolverSettings::new(Method::ClosedForm, 1e-10, 1e-10, 1000).unwrap();
        match integrate(&stun(0.5, 0.1), &p, &s, None) {
            Err(Error::InvalidParameter { field, value, .. }) => {
                assert_eq!(
                    (field.as_str(), value.as_str()),
                    ("solver.method", "closed-form")
                );
            }
            other => panic!("{other:?}"),
        }
    }

    /// A profile whose force is NaN in the second half of the contact.
    struct Broken;
    impl ForceProfile for Broken {
        fn duration(&self) -> f64 {
            TAU
        }
        fn shape(&self, s: f64) -> f64 {
            if s > 0.5 {
                f64::NAN
            } else {
                1.0
            }
        }
        fn cumulative(&self, s: f64) -> f64 {
            s.clamp(0.0, 1.0)
        }
    }

    /// rk4 accepts the NaN state: NonFinite. The adaptive methods reject every step whose
    /// stages reach the NaN (its error estimate is NaN) and shrink the step towards
    /// s = 1/2 until it underflows: StepSizeTooSmall there.
    #[test]
    fn a_nan_force_is_an_error() {
        let rk4 = SolverSettings::new(Method::Rk4, 1e-10, 1e-10, 1000).unwrap();
        match integrate(&stun(0.5, 0.1), &Broken, &rk4, None) {
            Err(Error::NonFinite { field, value }) => {
                assert_eq!(field, "state");
                assert!(value.is_nan());
            }
            other => panic!("{other:?}"),
        }
        for method in [Method::Dopri5, Method::Dop853] {
            let s = SolverSettings::new(method, 1e-10, 1e-10, 1000).unwrap();
            match integrate(&stun(0.5, 0.1), &Broken, &s, None) {
                Err(Error::StepSizeTooSmall {
                    method: m,
                    scaled_time,
                    segment_start,
                }) => {
                    assert_eq!(m, method);
                    assert!((scaled_time - 0.5).abs() < 1e-12, "{scaled_time}");
                    assert!(segment_start < scaled_time);
                }
                other => panic!("{method}: {other:?}"),
            }
        }
    }

    /// Sticking from the start (S(0) = 0): no sliding stage, the stop at t = 0.
    #[test]
    fn no_initial_sliding_sticks_at_zero() {
        let p = HalfSine::new(TAU).unwrap();
        let r = integrate(&stun(0.5, 0.0), &p, &dopri5(), None).unwrap();
        assert!(r.sticks);
        assert_eq!((r.stick_time, r.stick_impulse), (Some(0.0), Some(0.0)));
        assert_eq!(r.s_out, 0.0);
    }
}
