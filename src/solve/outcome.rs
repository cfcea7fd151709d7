//! Resolving one collision with a chosen method: the outcome and its verification.

use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::settings::{Sampling, SolverSettings, Stats};
use crate::closed_form::kernel::ClosedForm;
use crate::integrator::driver::{integrate, Integrated};
use crate::model::collision::Collision;
use crate::model::contact_law::ContactLaw;
use crate::model::result::ContactResult;
use crate::model::trace::{CoincidentRows, TraceRow, TraceSink};
use crate::profile::force::ForceProfile;
use crate::solve::check::{checks, Checks};
use nalgebra::Vector2;

/// The outcome of a collision, with its checks.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// Method that produced it.
    pub method: Method,
    /// The result: impulses, sliding, heat and the outgoing state.
    pub result: ContactResult,
    /// Time (s) at which sliding stopped; `None` when it did not.
    pub stick_time: Option<f64>,
    /// Verification.
    pub check: Checks,
    /// Work done.
    pub stats: Stats,
    /// Warnings (e.g. eq 57 violated with `stick = false`).
    pub warnings: Vec<String>,
    /// The closed form of the same collision (the reference; under a contact law, at the
    /// realised impulse).
    pub exact: ClosedForm,
    /// What a contact law decided (`None` for a prescribed profile): docs/contact-law.md.
    pub law: Option<LawOutcome>,
}

/// What a contact law decided in one collision (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawOutcome {
    /// The law (its coefficient the given or calibrated one).
    pub law: ContactLaw,
    /// The realised restitution e = P / (m U(0)) - 1.
    pub restitution: f64,
    /// The realised impulse P (N s).
    pub impulse: f64,
    /// The realised contact time (s).
    pub duration: f64,
    /// Largest compression delta_max (m), from the normal law.
    pub max_compression: f64,
    /// Peak force (N), from the normal law.
    pub peak_force: f64,
}

/// Default number of trace rows of the closed-form method without `--samples`.
pub(crate) const CLOSED_FORM_TRACE_SAMPLES: u64 = 100;

/// Resolves a collision with `settings.method()`, optionally streaming a trace.
///
/// ```
/// # use billiard_contact::*;
/// # use billiard_contact::profile::HalfSine; use nalgebra::Vector3;
/// let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
/// let contact = Contact { friction: Friction::constant(0.06).unwrap(),
///                         impulse: ImpulseRule::restitution(1.0).unwrap() };
/// let s = CmState::new(Vector3::new(0.5, 0.25, 0.0), Vector3::zeros(), Vector3::zeros());
/// let c = Collision::new(ball, contact, Effects::default(), s).unwrap();
/// let settings = SolverSettings::default().with_rtol(1e-12).unwrap().with_atol(1e-12).unwrap();
/// let o = solve(&c, &HalfSine::new(2.5e-4).unwrap(), &settings, None).unwrap();
/// assert!(o.check.closed_form_error < 1e-10);
/// assert!((o.result.out.u_cm.x + 0.5).abs() < 1e-10); // eq 24 with P = 2 m U(0)
/// ```
pub fn solve<P: ForceProfile + ?Sized>(
    c: &Collision,
    profile: &P,
    settings: &SolverSettings,
    trace: Option<(&mut dyn TraceSink, Sampling)>,
) -> Result<Outcome, Error> {
    let exact = ClosedForm::new(c);
    let mut outcome = Outcome {
        method: settings.method(),
        result: exact.result,
        stick_time: None,
        check: Checks::default(),
        stats: Stats::default(),
        warnings: Vec::new(),
        exact,
        law: None,
    };
    if !c.collides() {
        outcome.result.stick_impulse = None;
        if let Some((sink, sampling)) = trace {
            // Nothing happens: the samples asked for (the closed form's default number of
            // them), or, without steps to show, the start and the end.
            let n = match (sampling, settings.method()) {
                (Sampling::Uniform(n), _) => n,
                (Sampling::Steps, Method::ClosedForm) => CLOSED_FORM_TRACE_SAMPLES,
                (Sampling::Steps, _) => 1,
            };
            closed_form_trace(c, &exact, profile, sink, n)?;
        }
        return Ok(outcome);
    }
    let exact_result = &exact.result;
    outcome.stick_time = exact_result
        .stick_fraction(profile)
        .map(|s| profile.duration() * s);
    outcome.warnings.extend(eq57_warning(c, &exact));
    match settings.method() {
        Method::ClosedForm => {
            outcome.check = closed_form_checks(c, &exact);
            if let Some((sink, sampling)) = trace {
                let n = match sampling {
                    Sampling::Uniform(n) => n,
                    Sampling::Steps => CLOSED_FORM_TRACE_SAMPLES,
                };
                closed_form_trace(c, &exact, profile, sink, n)?;
            }
        }
        _ => time_step(&mut outcome, c, profile, settings, trace)?,
    }
    Ok(outcome)
}

/// The time-stepping part of [`solve`]: integrates the collision and puts the run's result,
/// work and checks into `outcome` (which holds the closed form's).
fn time_step<P: ForceProfile + ?Sized>(
    outcome: &mut Outcome,
    c: &Collision,
    profile: &P,
    settings: &SolverSettings,
    trace: Option<(&mut dyn TraceSink, Sampling)>,
) -> Result<(), Error> {
    let run = integrate(c, profile, settings, trace)?;
    take_run(outcome, c, &run);
    Ok(())
}

/// The warning of a collision whose closed form violates eq 57 (`stick = false` only).
pub(crate) fn eq57_warning(c: &Collision, exact: &ClosedForm) -> Option<String> {
    let r = &exact.result;
    exact.violates_eq57().then(|| {
        let p_stick = r.stick_impulse.unwrap_or(f64::INFINITY);
        format!(
            "eq 57 fails: sliding would stop at p = {p_stick:e} N s < P = {:e} N s; with stick = \
             false friction kept acting and the slip reversed (S_out = {:e} m/s)",
            c.impulse, r.s_out
        )
    })
}

/// The checks of the closed form itself.
pub(crate) fn closed_form_checks(c: &Collision, exact: &ClosedForm) -> Checks {
    let r = &exact.result;
    checks(c, exact, &r.out, r.tangential_impulse, r.heat_sliding)
}

/// Puts a time-stepping run's result, work and checks into `outcome` (which holds the
/// closed form's).
pub(crate) fn take_run(outcome: &mut Outcome, c: &Collision, run: &Integrated) {
    let m = c.balls.pair_mass();
    let e = c.direction.unwrap_or_else(Vector2::zeros);
    let du = run.out.u_cm - c.incoming.u_cm;
    let j = -m * (du.y * e.x + du.z * e.y);
    let r = &mut outcome.result;
    r.s_out = run.s_out;
    r.sticks = run.sticks;
    if c.effects.stick {
        outcome.stick_time = run.stick_time;
        if run.sticks {
            r.stick_impulse = run.stick_impulse;
        }
    }
    r.tangential_impulse = j.max(0.0);
    r.heat_sliding = run.heat_sliding;
    r.heat = c.incoming.kinetic_energy(&c.balls) - run.out.kinetic_energy(&c.balls);
    r.out = run.out;
    outcome.stats = run.stats;
    outcome.check = checks(c, &outcome.exact, &run.out, j, run.heat_sliding);
    outcome.check.theta_drift = run.theta_drift;
    outcome.check.slip_consistency = run.slip_consistency;
}

/// The trace row of the closed form at time `t` (s), force `force` (N) and impulse `p`
/// (N s; the state at p capped at the collision's P), with the slip direction `theta` and a
/// law's compression.
pub(crate) fn exact_row(
    c: &Collision,
    exact: &ClosedForm,
    theta: Option<f64>,
    t: f64,
    force: f64,
    p: f64,
    compression: Option<f64>,
) -> TraceRow {
    let part = exact.at_impulse(p.min(c.impulse));
    TraceRow {
        t,
        force,
        impulse: p,
        state: part.state,
        slip_speed: part.sliding.slip,
        theta,
        heat_sliding: part.sliding.heat,
        compression,
    }
}

/// The exact trace: the closed form at p(t) for t = i tau / n, i = 0..=n, plus the stop of
/// sliding (docs/model.md#the-exact-state-during-the-contact).
fn closed_form_trace<P: ForceProfile + ?Sized>(
    c: &Collision,
    exact: &ClosedForm,
    profile: &P,
    sink: &mut dyn TraceSink,
    n: u64,
) -> Result<(), Error> {
    let tau = profile.duration();
    let stick_s = exact.result.stick_fraction(profile);
    let theta = c.theta();
    // The stop row carries p_stick itself (p(t) at the inverted time can fall an ulp short
    // of it, which would leave a round-off slip at the stop).
    let row = |s: f64, t: f64, p: Option<f64>| {
        let p = p.unwrap_or_else(|| c.impulse * profile.cumulative(s));
        exact_row(
            c,
            exact,
            theta,
            t,
            c.impulse / tau * profile.shape(s),
            p,
            None,
        )
    };
    let mut rows = CoincidentRows::new(tau);
    let mut last = -1.0;
    let n = n.max(1);
    for i in 0..=n {
        let s = i as f64 / n as f64;
        if let Some(ss) = stick_s {
            if ss > last && ss <= s {
                rows.offer(sink, row(ss, ss * tau, exact.result.stick_impulse), true)?;
            }
        }
        rows.offer(sink, row(s, i as f64 * tau / n as f64, None), false)?;
        last = s;
    }
    rows.finish(sink)
}
