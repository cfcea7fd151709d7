//! Resolving a collision under a contact law (docs/contact-law.md): the law decides the
//! impulse, the contact time and the restitution; the closed form at the realised impulse is
//! the reference the run is checked against (the outgoing state is a function of the impulse
//! alone, whatever f(t) was: docs/model.md#the-closed-form).
//!
//! `closed-form` integrates only the normal law (delta and U, with dop853 at the run's
//! tolerances) and applies the closed form at its impulse; `rk4`, `dopri5` and `dop853`
//! integrate everything.

use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::settings::{Sampling, SolverSettings};
use crate::closed_form::kernel::ClosedForm;
use crate::integrator::law::{
    integrate_law, normal_run, normal_settings, HeadOn, LawScales, NormalPoint,
};
use crate::model::collision::Collision;
use crate::model::contact_law::ContactLaw;
use crate::model::params::{Contact, ImpulseRule};
use crate::model::trace::{CoincidentRows, TraceRow, TraceSink};
use crate::profile::rectangle::Rectangle;
use crate::solve::outcome::{
    closed_form_checks, eq57_warning, exact_row, solve, take_run, LawOutcome, Outcome,
};

/// Default number of trace rows of the closed-form method without `--samples`.
const CLOSED_FORM_TRACE_SAMPLES: u64 = crate::solve::outcome::CLOSED_FORM_TRACE_SAMPLES;

/// Resolves a collision under `law` with `settings.method()`, optionally streaming a trace
/// (with the compression column). Balls that do not approach keep their state.
///
/// ```
/// # use billiard_contact::*;
/// # use nalgebra::Vector3;
/// let ball = Ball::new(0.17, 0.028575, 0.4)?;
/// let contact = Contact { friction: Friction::constant(0.06)?, impulse: ImpulseRule::ELASTIC };
/// let s = CmState::new(Vector3::new(0.5, 0.1, 0.0), Vector3::zeros(), Vector3::zeros());
/// let c = Collision::new(ball, contact, Effects::default(), s)?;
/// let law = ContactLaw::new(4.5e8, Damping::HuntCrossley, 0.1)?;
/// let o = solve_law(&c, &law, &SolverSettings::default(), None)?;
/// // beta v = 0.1 (v = 2 U(0) = 1 m/s): e = 0.93748 solves -beta e v - ln(1 - beta e v) =
/// // beta v - ln(1 + beta v) (docs/contact-law.md#the-laws).
/// let e = o.law.unwrap().restitution;
/// assert!((e - 0.937475579950).abs() < 1e-9);
/// assert!(o.check.closed_form_error < 1e-9);
/// # Ok::<(), billiard_contact::Error>(())
/// ```
pub fn solve_law(
    c: &Collision,
    law: &ContactLaw,
    settings: &SolverSettings,
    trace: Option<(&mut dyn TraceSink, Sampling)>,
) -> Result<Outcome, Error> {
    if !c.collides() {
        let outcome = solve(c, &Rectangle::new(1.0)?, settings, None)?;
        if let Some((sink, _)) = trace {
            sink.row(&TraceRow {
                t: 0.0,
                force: 0.0,
                impulse: 0.0,
                state: c.incoming,
                slip_speed: c.s0,
                theta: c.theta(),
                heat_sliding: 0.0,
                compression: Some(0.0),
            })?;
        }
        return Ok(outcome);
    }
    let scales = LawScales::for_collision(c, law)?;
    let normal = normal_settings(settings);
    let head = normal_run(&scales, &normal, None, None)?;
    if settings.method() == Method::ClosedForm {
        return closed_form(c, &scales, &normal, head, trace);
    }
    let run = integrate_law(c, law, settings, trace)?;
    let real = realised(c, run.impulse)?;
    let mut outcome = outcome_of(&real, settings.method(), &scales, &head);
    take_run(&mut outcome, &real, &run.run);
    outcome.result.impulse = run.impulse;
    outcome.law = Some(LawOutcome {
        restitution: scales.restitution(run.impulse),
        impulse: run.impulse,
        duration: run.duration,
        ..law_outcome(&scales, &head)
    });
    Ok(outcome)
}

/// The closed form at the impulse of the normal law's run `head` (with `normal`, a stepping
/// method); the stick time where that run's impulse reaches p_stick.
fn closed_form(
    c: &Collision,
    scales: &LawScales,
    normal: &SolverSettings,
    head: HeadOn,
    trace: Option<(&mut dyn TraceSink, Sampling)>,
) -> Result<Outcome, Error> {
    let real = realised(c, head.impulse)?;
    let mut outcome = outcome_of(&real, Method::ClosedForm, scales, &head);
    outcome.result.impulse = head.impulse;
    outcome.check = closed_form_checks(&real, &outcome.exact);
    outcome.stats = head.stats;
    let r = &outcome.exact.result;
    if r.sticks {
        outcome.stick_time = match r.stick_impulse.unwrap_or(0.0) {
            p if p > 0.0 => normal_run(scales, normal, Some(p), None)?.mark_time,
            _ => Some(0.0),
        };
    }
    if let Some((sink, sampling)) = trace {
        let n = match sampling {
            Sampling::Uniform(n) => n,
            Sampling::Steps => CLOSED_FORM_TRACE_SAMPLES,
        };
        let stop = match (outcome.stick_time, r.stick_impulse) {
            (Some(t), Some(p)) if p > 0.0 => Some((t, p)),
            _ => None,
        };
        let pulse = TracedPulse {
            duration: head.duration,
            samples: n,
            stop,
        };
        closed_form_trace(&real, &outcome.exact, scales, normal, &pulse, sink)?;
    }
    Ok(outcome)
}

/// The outcome of the realised collision `real` before its run is taken in: the closed form,
/// its eq 57 warning, the law's part from the normal law's run `head`.
fn outcome_of(real: &Collision, method: Method, scales: &LawScales, head: &HeadOn) -> Outcome {
    let exact = ClosedForm::new(real);
    Outcome {
        method,
        result: exact.result,
        stick_time: None,
        check: Default::default(),
        stats: Default::default(),
        warnings: eq57_warning(real, &exact).into_iter().collect(),
        exact,
        law: Some(law_outcome(scales, head)),
    }
}

/// The law's part of a normal law's run.
fn law_outcome(scales: &LawScales, head: &HeadOn) -> LawOutcome {
    LawOutcome {
        law: scales.law(),
        restitution: scales.restitution(head.impulse),
        impulse: head.impulse,
        duration: head.duration,
        max_compression: head.max_compression,
        peak_force: head.peak_force,
    }
}

/// Collision `c` with the realised impulse `impulse` (N s), kept within eq 56's
/// [m U(0), 2 m U(0)] (an integrator's round-off beyond it is the run's error, which the
/// checks then show).
fn realised(c: &Collision, impulse: f64) -> Result<Collision, Error> {
    let (m, u0) = (c.balls.pair_mass(), c.incoming.u_cm.x);
    let contact = Contact {
        friction: c.contact.friction,
        impulse: ImpulseRule::explicit(impulse.clamp(m * u0, 2.0 * m * u0))?,
    };
    Collision::new(c.balls, contact, c.effects, c.incoming)
}

/// What the closed form's trace under a law samples: the contact time (s), the number of
/// intervals, and the stop of sliding (time in s, impulse p_stick in N s) when sliding
/// stops after the start.
struct TracedPulse {
    duration: f64,
    samples: u64,
    stop: Option<(f64, f64)>,
}

/// The closed form's trace under a law: the normal law integrated again with a point every
/// `duration / samples`, at the stop of sliding and at the end, each row the closed form at
/// that point's impulse. The stop row, as the time-stepping methods write it, is at the
/// reported stick time and at p_stick itself (slip 0), with the force and the compression
/// of this integration where its impulse reaches p_stick. Points closer than 1e-9
/// `duration` to the next one are not written (the last sample and the end), except the
/// stop row.
fn closed_form_trace(
    real: &Collision,
    exact: &ClosedForm,
    scales: &LawScales,
    normal: &SolverSettings,
    pulse: &TracedPulse,
    sink: &mut dyn TraceSink,
) -> Result<(), Error> {
    let theta = real.theta();
    let duration = pulse.duration;
    let row = |[t, p, force, delta]: NormalPoint, stop: bool| {
        let (t, p) = match (stop, pulse.stop) {
            (true, Some(at)) => at,
            _ => (t, p),
        };
        exact_row(real, exact, theta, t, force, p, Some(delta))
    };
    let mut rows = CoincidentRows::new(duration);
    let mut write = |point: NormalPoint, stop: bool| rows.offer(sink, row(point, stop), stop);
    normal_run(
        scales,
        normal,
        pulse.stop.map(|(_, p)| p),
        Some((&mut write, duration / pulse.samples.max(1) as f64)),
    )?;
    rows.finish(sink)
}
