//! A contact law in the integrator (docs/contact-law.md#time-stepping): the compression as a
//! state beside eqs 14-19, the normal force from it, and the end of the contact as an event.
//!
//! Scaled variables: the time unit is the elastic Hertz contact time tau_0 of the law's
//! stiffness at the approach speed v = 2 U(0) (a damped contact lasts about as long), the
//! compression unit the elastic largest compression delta_0; velocities, spins and heat as
//! in [`super::rhs`]. With d = delta / delta_0 and U = U(0) + v_ref dU,
//!
//! ```text
//! dd/ds = 2 U tau_0 / delta_0          (delta' = 2 U)
//! n     = f(delta, 2 U) tau_0 / (M v_ref)   (M U' = -f; M = 2 m*, the mass m of identical balls)
//! ```
//!
//! and n drives eqs 14-19 as pi phi(s) does for a prescribed profile. The integration runs
//! in the scaled time itself: the smoothing change of time variable of
//! [`super::time_map`] needs the end of the contact in advance, and a law finds it as an
//! event. Events are located inside the step that crossed them by regula falsi (Illinois)
//! in the time, each trial re-integrated from the step's start with the run's method: the
//! end of the contact (the law's separation function reaches 0), the stop of sliding (as
//! for a profile, with friction along e0 in the trials), and, in a run of the normal law
//! alone, the largest compression (U = 0), the peak force (df/dt = 0) and the time a given
//! impulse is reached.

use super::driver::{initial_stage, result, Integrated};
use super::record::Recorder;
use super::rhs::{Direction, ScaledRhs, SlidingRhs, SlidingState, SLIDING_DIM};
use super::stages::{ContactStage, Problem, Run};
use super::stepping::{Stepper, WHOLE_SPAN};
use super::time_map::TimeMap;
use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::root::{illinois_update, Bound, Side};
use crate::base::settings::{Sampling, SolverSettings, Stats};
use crate::model::collision::Collision;
use crate::model::contact_law::{ContactLaw, Damping, STIFFNESS_FIELD};
use crate::model::material::elastic_impact;
use crate::model::trace::{TraceRow, TraceSink};
use crate::profile::force::ForceProfile;
use nalgebra::SVector;

/// Components of the state with a law: the sliding state and the scaled compression.
pub(crate) const LAW_DIM: usize = SLIDING_DIM + 1;
/// Index of the scaled compression d in the state with a law.
const COMPRESSION: usize = SLIDING_DIM;
/// Components of the normal law's state: x, dU, d.
const NORMAL_LAW_DIM: usize = 3;

/// The longest contact a law may have, in elastic contact times tau_0: a contact still on
/// after it is an error (a damping so strong that the balls hardly separate).
pub(crate) const LAW_SPAN: f64 = 1e4;

/// Largest Hunt-Crossley damping number c v (c the coefficient, v = 2 U(0) the approach
/// speed): the restitution is then about 2 / (c v) = 2e-6, and the contact's last part, where
/// the balls creep apart at the speed 1/c, lasts a few thousand elastic contact times (c v =
/// 1e6: 1.8e3 tau_0 for pool balls). Past about 2e7 it outlasts [`LAW_SPAN`], and far past it
/// the separation function is lost in rounding, so the bound is a number, not a run that fails.
pub(crate) const HUNT_CROSSLEY_MAX_DAMPING: f64 = 1e6;

/// Largest Kuwabara-Kono damping number gamma / tau_0 (tau_0 the elastic contact time): the
/// contact then lasts about 3.4 (gamma / tau_0)^(-2/3) tau_0 = 3e-8 tau_0 with a restitution
/// of 0 to every printed digit; far past it (gamma / tau_0 ~ 1e20) the steps underflow.
pub(crate) const KUWABARA_KONO_MAX_DAMPING: f64 = 1e12;

/// Bracket width in the scaled time at which an event is located: a few ulps of 1.
const X_TOL: f64 = 1e-14;
/// |g| at which an event is located, relative to its range over the crossing step.
const G_TOL: f64 = 1e-14;
/// Most trials of the event location.
const MAX_TRIALS: usize = 100;

/// A unit force: with it [`SlidingRhs`] takes its force n from the law at every evaluation.
#[derive(Debug, Clone, Copy)]
pub(super) struct UnitPulse;

impl ForceProfile for UnitPulse {
    fn duration(&self) -> f64 {
        1.0
    }
    fn shape(&self, _s: f64) -> f64 {
        1.0
    }
    fn cumulative(&self, s: f64) -> f64 {
        s
    }
}

static UNIT_PULSE: UnitPulse = UnitPulse;

/// The pair mass M = 2 m* (kg) of the law's normal dynamics, M U' = -f: the one place the
/// law reads the balls' masses (the mass m of identical balls).
pub(crate) fn pair_mass(balls: &crate::model::params::BallPair) -> f64 {
    balls.pair_mass()
}

/// A law with the scales of one collision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LawScales {
    law: ContactLaw,
    /// M = 2 m* (kg): M U' = -f.
    pair_mass: f64,
    /// U(0) (m/s).
    u0: f64,
    /// v_ref (m/s).
    v_ref: f64,
    /// Elastic contact time tau_0 (s): the unit of the scaled time.
    tau0: f64,
    /// Elastic largest compression delta_0 (m): the unit of d.
    delta0: f64,
}

impl LawScales {
    /// `law` for balls of pair mass `pair_mass` M (kg) approaching at U(0) = `u0` (m/s) with
    /// reference speed `v_ref` (m/s).
    fn new(law: &ContactLaw, pair_mass: f64, u0: f64, v_ref: f64) -> Result<Self, Error> {
        let (delta0, tau0) = elastic_impact(law.stiffness(), 0.5 * pair_mass, 2.0 * u0);
        if !(delta0.is_normal() && tau0.is_normal() && u0 > 0.0 && v_ref.is_normal()) {
            return Err(Error::invalid(
                STIFFNESS_FIELD,
                format!(
                    "{} N/m^1.5 at {} m/s (compression {delta0} m, time {tau0} s)",
                    law.stiffness(),
                    2.0 * u0
                ),
                "a stiffness, mass and approach speed whose elastic compression and contact \
                 time are normal positive numbers",
            ));
        }
        damping_within_bound(law, 2.0 * u0, tau0)?;
        Ok(LawScales {
            law: *law,
            pair_mass,
            u0,
            v_ref,
            tau0,
            delta0,
        })
    }

    /// The scales of `law` in collision `c`.
    pub(crate) fn for_collision(c: &Collision, law: &ContactLaw) -> Result<Self, Error> {
        LawScales::new(law, pair_mass(&c.balls), c.incoming.u_cm.x, c.scales.speed)
    }

    /// The law.
    pub(crate) fn law(&self) -> ContactLaw {
        self.law
    }

    /// The restitution e = P / (M U(0)) - 1 of impulse `impulse` (N s).
    pub(crate) fn restitution(&self, impulse: f64) -> f64 {
        impulse / (self.pair_mass * self.u0) - 1.0
    }

    /// Compression delta (m) of scaled compression `d`.
    fn delta(&self, d: f64) -> f64 {
        d * self.delta0
    }

    /// delta' = 2 U (m/s) at scaled change of U `du`.
    fn delta_dot(&self, du: f64) -> f64 {
        2.0 * (self.u0 + du * self.v_ref)
    }

    /// The force f (N).
    fn force(&self, du: f64, d: f64) -> f64 {
        self.law.force(self.delta(d), self.delta_dot(du))
    }

    /// The scaled force n and dd/ds.
    #[inline]
    fn rates(&self, du: f64, d: f64) -> (f64, f64) {
        let w = self.delta_dot(du);
        let f = self.law.force(self.delta(d), w);
        (
            f * self.tau0 / (self.pair_mass * self.v_ref),
            w * self.tau0 / self.delta0,
        )
    }

    /// The law's separation function over delta_0: the end of the contact is its zero.
    fn separation(&self, du: f64, d: f64) -> f64 {
        self.law.separation(self.delta(d), self.delta_dot(du)) / self.delta0
    }

    /// The impulse p (N s) delivered at scaled change of U `du`.
    fn impulse(&self, du: f64) -> f64 {
        -du * self.pair_mass * self.v_ref
    }

    /// The time t (s) of scaled time `x`.
    fn time(&self, x: f64) -> f64 {
        x * self.tau0
    }
}

/// The normal law alone: x, dU and d.
#[derive(Debug, Clone, Copy)]
struct NormalLawRhs {
    scales: LawScales,
}

impl ScaledRhs<NORMAL_LAW_DIM> for NormalLawRhs {
    #[inline]
    fn derivative(&self, y: &SVector<f64, NORMAL_LAW_DIM>, dy: &mut SVector<f64, NORMAL_LAW_DIM>) {
        let (n, dd) = self.scales.rates(y[1], y[2]);
        *dy = SVector::from([1.0, -n, dd]);
    }
}

/// Eqs 14-19 under the law's force, with the compression.
#[derive(Debug, Clone, Copy)]
struct SlidingLawRhs<'a> {
    scales: LawScales,
    /// Eqs 14-19 of a unit pulse, whose force is replaced by the law's n.
    sliding: SlidingRhs<'a, UnitPulse>,
}

/// The sliding part of a state with a law.
fn sliding_part(y: &SVector<f64, LAW_DIM>) -> SlidingState {
    SlidingState(y.fixed_rows::<SLIDING_DIM>(0).into_owned())
}

impl ScaledRhs<LAW_DIM> for SlidingLawRhs<'_> {
    #[inline]
    fn derivative(&self, y: &SVector<f64, LAW_DIM>, dy: &mut SVector<f64, LAW_DIM>) {
        let (n, dd) = self.scales.rates(y[1], y[COMPRESSION]);
        let rhs = SlidingRhs {
            impulse: n,
            ..self.sliding
        };
        let mut part = SVector::zeros();
        rhs.derivative(&sliding_part(y).0, &mut part);
        dy.fixed_rows_mut::<SLIDING_DIM>(0).copy_from(&part);
        dy[COMPRESSION] = dd;
    }
}

impl SlidingLawRhs<'_> {
    /// The stop-of-sliding event function slip . e0.
    fn stop_event(&self, y: &SVector<f64, LAW_DIM>) -> f64 {
        self.sliding.event(&sliding_part(y))
    }
}

/// Steps `rhs` from `y0` towards x = `b` until `on_step` reports a crossing after an
/// accepted step. Returns the state before that step, the state reached (the crossing, or
/// `b`), and whether a crossing stopped it.
fn step_until<const N: usize, R: ScaledRhs<N>>(
    stepper: &mut Stepper,
    rhs: &R,
    y0: SVector<f64, N>,
    b: f64,
    rec: &mut Recorder<'_>,
    mut on_step: impl FnMut(&mut Recorder<'_>, &SVector<f64, N>) -> bool,
) -> Result<(SVector<f64, N>, SVector<f64, N>, bool), Error> {
    let mut prev = y0;
    let mut hit = false;
    let end = stepper.advance_checked(rhs, y0, b, rec, |rec, v| {
        if on_step(rec, v) {
            hit = true;
            return true;
        }
        prev = *v;
        false
    })?;
    Ok((prev, end, hit))
}

/// Locates the zero of `event` inside the step from `prev` (event > 0) to `cross`
/// (event <= 0): regula falsi (Illinois) in the scaled time, each trial re-integrated from
/// `prev` with `rhs`. Returns the located state.
fn locate<const N: usize, R: ScaledRhs<N>>(
    stepper: &mut Stepper,
    rhs: &R,
    prev: &SVector<f64, N>,
    cross: &SVector<f64, N>,
    event: impl Fn(&SVector<f64, N>) -> f64,
) -> Result<SVector<f64, N>, Error> {
    let x0 = prev[0];
    let mut lo = Bound {
        q: x0,
        g: event(prev),
    };
    let mut hi = Bound {
        q: cross[0],
        g: event(cross),
    };
    if hi.g >= 0.0 || lo.g <= 0.0 {
        return Ok(if lo.g <= 0.0 { *prev } else { *cross });
    }
    let g_tol = G_TOL * (lo.g - hi.g);
    let (mut best, mut best_g) = (*cross, hi.g.abs());
    let mut side = Side::None;
    let mut never = |_: &SVector<f64, N>| false;
    for _ in 0..MAX_TRIALS {
        if best_g <= g_tol || hi.q - lo.q <= X_TOL * hi.q.abs().max(1.0) {
            break;
        }
        let x = (lo.q + (hi.q - lo.q) * (lo.g / (lo.g - hi.g))).clamp(lo.q, hi.q);
        let st = stepper
            .advance(rhs, x0, *prev, x, WHOLE_SPAN, &mut never)?
            .y;
        let g = event(&st);
        if g.abs() < best_g || (g <= 0.0 && g.abs() <= best_g) {
            (best, best_g) = (st, g.abs());
        }
        side = illinois_update(&mut lo, &mut hi, side, x, g);
    }
    Ok(best)
}

/// The largest coefficient of `damping` for an approach at `speed` (m/s) with the elastic
/// contact time `tau0` (s): [`HUNT_CROSSLEY_MAX_DAMPING`] / v, [`KUWABARA_KONO_MAX_DAMPING`]
/// tau_0, unbounded without damping.
pub(crate) fn largest_coefficient(damping: Damping, speed: f64, tau0: f64) -> f64 {
    match damping {
        Damping::None => f64::INFINITY,
        Damping::HuntCrossley => HUNT_CROSSLEY_MAX_DAMPING / speed,
        Damping::KuwabaraKono => KUWABARA_KONO_MAX_DAMPING * tau0,
    }
}

/// Refuses a damping past [`HUNT_CROSSLEY_MAX_DAMPING`] or [`KUWABARA_KONO_MAX_DAMPING`] for
/// an approach at `speed` (m/s) with the elastic contact time `tau0` (s), naming the
/// coefficient and its largest value for this collision.
pub(crate) fn damping_within_bound(law: &ContactLaw, speed: f64, tau0: f64) -> Result<(), Error> {
    use crate::base::number::{decimal, si};
    let largest = largest_coefficient(law.damping(), speed, tau0);
    if law.coefficient() <= largest {
        return Ok(());
    }
    let expected = match law.damping() {
        Damping::HuntCrossley => format!(
            "at most {} s/m for this collision (c v <= {HUNT_CROSSLEY_MAX_DAMPING:e} at the \
             approach speed v = {}): past it the restitution is below 2e-6 and the balls \
             creep apart for longer than the contact may last",
            decimal(largest, 4),
            si(speed, "m/s", 4),
        ),
        _ => format!(
            "at most {} s for this collision (gamma / tau_0 <= {KUWABARA_KONO_MAX_DAMPING:e}, \
             tau_0 = {} the elastic contact time): past it the contact ends within 3e-8 tau_0 \
             with a restitution of 0",
            decimal(largest, 4),
            si(tau0, "s", 4),
        ),
    };
    Err(Error::invalid(
        crate::model::contact_law::COEFFICIENT_FIELD,
        law.coefficient(),
        expected,
    ))
}

/// The error of a contact that is still on after [`LAW_SPAN`] elastic contact times.
fn contact_never_ends(law: &ContactLaw) -> Error {
    Error::invalid(
        crate::model::contact_law::COEFFICIENT_FIELD,
        law.coefficient(),
        format!(
            "a damping under which the balls separate within {LAW_SPAN:e} elastic contact \
             times"
        ),
    )
}

/// What a run of the normal law alone finds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadOn {
    /// Restitution e = -U_out / U(0).
    pub restitution: f64,
    /// Impulse P (N s).
    pub impulse: f64,
    /// Contact time (s).
    pub duration: f64,
    /// Largest compression delta_max (m), at U = 0.
    pub max_compression: f64,
    /// Peak force (N), at df/dt = 0.
    pub peak_force: f64,
    /// The time (s) at which the impulse reached the mark asked for (`None`: no mark, or
    /// not reached).
    pub mark_time: Option<f64>,
    /// Work done.
    pub stats: Stats,
}

/// A point of a run of the normal law alone: time (s), impulse (N s), force (N),
/// compression (m).
pub(crate) type NormalPoint = [f64; 4];

/// Receives the sample points of a run of the normal law alone, each with whether it is
/// the located mark (the time the impulse reaches the mark asked for), and the sampling
/// interval (s).
pub(crate) type NormalSamples<'s> = (
    &'s mut dyn FnMut(NormalPoint, bool) -> Result<(), Error>,
    f64,
);

/// The head-on impact of `law` between balls of reduced mass `reduced_mass` (kg) at the
/// relative approach speed `v` (m/s), integrated with dop853 at rtol = atol = `rtol`.
pub(crate) fn head_on(
    law: &ContactLaw,
    reduced_mass: f64,
    v: f64,
    rtol: f64,
) -> Result<HeadOn, Error> {
    let scales = LawScales::new(law, 2.0 * reduced_mass, 0.5 * v, 0.5 * v)?;
    let settings = SolverSettings::new(
        Method::Dop853,
        rtol,
        rtol,
        crate::base::settings::DEFAULT_STEPS,
    )?;
    normal_run(&scales, &settings, None, None)
}

/// The stepping settings of a run of the normal law alone: the closed form's runs step with
/// dop853 at its tolerances.
pub(crate) fn normal_settings(settings: &SolverSettings) -> SolverSettings {
    match settings.method() {
        Method::ClosedForm => settings.with_method(Method::Dop853),
        _ => *settings,
    }
}

/// The normal law alone (delta and U) from first touch to the end of the contact, with
/// `settings` (a stepping method), locating the largest compression, the peak force and,
/// when `mark` is given, the time the impulse reaches `mark` (N s); with `samples`, a point
/// every `samples.1` (s), at the located mark, and at the end.
pub(crate) fn normal_run(
    scales: &LawScales,
    settings: &SolverSettings,
    mark: Option<f64>,
    mut samples: Option<NormalSamples<'_>>,
) -> Result<HeadOn, Error> {
    let sc = *scales;
    let rhs = NormalLawRhs { scales: sc };
    let mut stepper = Stepper::new(settings)?;
    let mut rec = Recorder::new(None, None);
    let mark_du = mark.map(|p| -p / (sc.pair_mass * sc.v_ref));
    let end = |v: &SVector<f64, 3>| sc.separation(v[1], v[2]);
    // The watched events, each positive until it happens: U = 0, df/dt = 0, p = mark.
    let watched = |i: usize, v: &SVector<f64, 3>| match i {
        0 => sc.u0 / sc.v_ref + v[1],
        1 => sc
            .law
            .force_rate(sc.delta(v[2]), sc.delta_dot(v[1]), 0.5 * sc.pair_mass),
        _ => mark_du.map_or(1.0, |m| v[1] - m),
    };
    let point = |v: &SVector<f64, 3>| {
        [
            sc.time(v[0]),
            sc.impulse(v[1]),
            sc.force(v[1], v[2]),
            sc.delta(v[2]),
        ]
    };
    let mut found: [Option<SVector<f64, 3>>; 3] = [None; 3];
    let mut y = SVector::from([0.0, 0.0, 0.0]);
    let dx = samples.as_ref().map(|s| s.1 / sc.tau0);
    let mut next_sample = 1.0;
    if let Some((sink, _)) = samples.as_mut() {
        sink(point(&y), false)?;
    }
    loop {
        let b = dx.map_or(LAW_SPAN, |dx| (next_sample * dx).min(LAW_SPAN));
        let (prev, reached, hit) = step_until(&mut stepper, &rhs, y, b, &mut rec, |_, v| {
            end(v) <= 0.0 || (0..3).any(|i| found[i].is_none() && watched(i, v) <= 0.0)
        })?;
        if hit {
            for (i, slot) in found.iter_mut().enumerate() {
                if slot.is_none() && watched(i, &reached) <= 0.0 {
                    let at = locate(&mut stepper, &rhs, &prev, &reached, |v| watched(i, v))?;
                    *slot = Some(at);
                    if let (2, Some((sink, _))) = (i, samples.as_mut()) {
                        sink(point(&at), true)?;
                    }
                }
            }
            if end(&reached) <= 0.0 {
                y = locate(&mut stepper, &rhs, &prev, &reached, end)?;
                break;
            }
        } else if reached[0] >= LAW_SPAN {
            return Err(contact_never_ends(&sc.law));
        } else if let Some((sink, _)) = samples.as_mut() {
            sink(point(&reached), false)?;
            next_sample += 1.0;
        }
        y = reached;
    }
    if let Some((sink, _)) = samples.as_mut() {
        sink(point(&y), false)?;
    }
    let located = |i: usize| found[i].map(|v| point(&v));
    Ok(HeadOn {
        restitution: -(sc.u0 + y[1] * sc.v_ref) / sc.u0,
        impulse: sc.impulse(y[1]),
        duration: sc.time(y[0]),
        max_compression: located(0).map_or(0.0, |p| p[3]),
        peak_force: located(1).map_or(0.0, |p| p[2]),
        mark_time: located(2).map(|p| p[0]),
        stats: stepper.stats,
    })
}

/// Why the stepping of a stage with a law ended.
#[derive(Debug, Clone, Copy, PartialEq)]
enum LawEvent {
    /// The end of the segment (a sample time) was reached.
    ReachedEnd,
    /// Sliding stopped at `time` (s) with the impulse `impulse` (N s) delivered.
    SlidingStopped { time: f64, impulse: f64 },
    /// The contact ended.
    Ended,
}

/// The result of a time-stepping run under a law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LawIntegrated {
    /// The run's result, as for a profile.
    pub(crate) run: Integrated,
    /// The realised impulse P (N s).
    pub(crate) impulse: f64,
    /// The realised contact time (s).
    pub(crate) duration: f64,
}

/// A collision under a law: the profile problem of a unit pulse (its units, slip and
/// friction) with the law's scales.
struct LawProblem<'a> {
    problem: Problem<'a, UnitPulse>,
    scales: LawScales,
}

/// Integrates a collision that happens (U(0) > 0) under `law` with `settings` (not
/// `closed-form`), optionally writing a trace (with `--samples N`, a row every tau_0 / N,
/// tau_0 the elastic contact time, and at the end).
pub(crate) fn integrate_law(
    c: &Collision,
    law: &ContactLaw,
    settings: &SolverSettings,
    trace: Option<(&mut dyn TraceSink, Sampling)>,
) -> Result<LawIntegrated, Error> {
    if !c.collides() {
        return Err(Error::invalid(
            "collision.impulse",
            c.impulse,
            "> 0 N s: a contact law needs balls that approach (U(0) > 0)",
        ));
    }
    let lp = LawProblem {
        problem: Problem::new(c, &UNIT_PULSE, TimeMap::Identity),
        scales: LawScales::for_collision(c, law)?,
    };
    let dx = match trace.as_ref().map(|t| t.1) {
        Some(Sampling::Uniform(n)) => Some(1.0 / n.max(1) as f64),
        _ => None,
    };
    let mut run = Run {
        stepper: Stepper::new(settings)?,
        rec: Recorder::new(trace, c.theta()),
    };
    if dx.is_some() {
        run.rec.merge_coincident(lp.scales.time(1.0));
    }
    let mut y = SVector::<f64, LAW_DIM>::zeros();
    y.fixed_rows_mut::<SLIDING_DIM>(0)
        .copy_from(&SlidingState::initial(lp.problem.slip0).0);
    let (mut stage, mut stop) = initial_stage(c);
    lp.emit(&mut run.rec, &y, Some(0.0));
    let mut next_sample = 1.0;
    loop {
        let b = dx.map_or(LAW_SPAN, |dx| (next_sample * dx).min(LAW_SPAN));
        let (next, event) = lp.step(stage, y, b, &mut run)?;
        y = next;
        match event {
            LawEvent::Ended => {
                lp.emit(&mut run.rec, &y, None);
                break;
            }
            LawEvent::ReachedEnd if y[0] >= LAW_SPAN => return Err(contact_never_ends(law)),
            LawEvent::ReachedEnd => {
                lp.emit(&mut run.rec, &y, None);
                next_sample += 1.0;
            }
            LawEvent::SlidingStopped { time, impulse } => {
                (stop.time, stop.impulse) = (Some(time), Some(impulse));
                stage = if c.effects.stick {
                    stop.sticks = true;
                    y.fixed_rows_mut::<2>(6).fill(0.0);
                    ContactStage::Normal
                } else {
                    ContactStage::Frozen
                };
                lp.emit_stop(&mut run.rec, &y, time);
            }
        }
    }
    run.rec.finish();
    run.rec.take_error()?;
    Ok(LawIntegrated {
        run: result(&lp.problem, &sliding_part(&y), stop, &run),
        impulse: lp.scales.impulse(y[1]),
        duration: lp.scales.time(y[0]),
    })
}

impl LawProblem<'_> {
    /// Eqs 14-19 under the law, with the friction direction taken by `direction`.
    fn rhs(&self, direction: Direction) -> SlidingLawRhs<'_> {
        SlidingLawRhs {
            scales: self.scales,
            sliding: self.problem.sliding_rhs(direction),
        }
    }

    /// The separation function of state `y`.
    fn separation(&self, y: &SVector<f64, LAW_DIM>) -> f64 {
        self.scales.separation(y[1], y[COMPRESSION])
    }

    /// Writes the trace row of `y` (at `time`, s; default its own).
    fn emit(&self, rec: &mut Recorder<'_>, y: &SVector<f64, LAW_DIM>, time: Option<f64>) {
        rec.emit_with(y[0], |theta| self.row(y, time, theta));
    }

    /// Writes the trace row of the stop of sliding, state `y` at `time` (s).
    fn emit_stop(&self, rec: &mut Recorder<'_>, y: &SVector<f64, LAW_DIM>, time: f64) {
        rec.emit_stop_with(y[0], |theta| self.row(y, Some(time), theta));
    }

    /// The trace row of `y` (at `time`, s; default its own) with slip angle `theta`.
    fn row(&self, y: &SVector<f64, LAW_DIM>, time: Option<f64>, theta: Option<f64>) -> TraceRow {
        let sc = &self.scales;
        TraceRow {
            t: time.unwrap_or(sc.time(y[0])),
            force: sc.force(y[1], y[COMPRESSION]),
            impulse: sc.impulse(y[1]),
            compression: Some(sc.delta(y[COMPRESSION])),
            ..self.problem.units.row(&sliding_part(y), None, theta)
        }
    }

    /// Steps `stage` from `y` towards `b`, until it is reached, sliding stops or the contact
    /// ends.
    fn step(
        &self,
        stage: ContactStage,
        y: SVector<f64, LAW_DIM>,
        b: f64,
        run: &mut Run<'_>,
    ) -> Result<(SVector<f64, LAW_DIM>, LawEvent), Error> {
        match stage {
            ContactStage::Sliding => self.slide(y, b, run),
            ContactStage::Frozen => self.slide_frozen(y, b, run),
            ContactStage::Normal => self.press(y, b, run),
        }
    }

    /// Sliding, watching for the stop of sliding and the end of the contact.
    fn slide(
        &self,
        y: SVector<f64, LAW_DIM>,
        b: f64,
        run: &mut Run<'_>,
    ) -> Result<(SVector<f64, LAW_DIM>, LawEvent), Error> {
        let rhs = self.rhs(Direction::CurrentSlip);
        let p = &self.problem;
        let stopped = |v: &SVector<f64, LAW_DIM>| rhs.stop_event(v) <= p.stop_floor;
        let (prev, cross, hit) =
            step_until(&mut run.stepper, &rhs, y, b, &mut run.rec, |rec, v| {
                if self.separation(v) <= 0.0 || stopped(v) {
                    return true;
                }
                rec.measure_sliding(&sliding_part(v), p.e0, &p.slip0, rhs.sliding.slip_floor);
                if rec.takes_steps() {
                    self.emit(rec, v, None);
                }
                false
            })?;
        if !hit {
            return Ok((cross, LawEvent::ReachedEnd));
        }
        if stopped(&cross) {
            // Friction along e0 in the trials, as for a profile (stop_event.rs).
            let frozen = SlidingLawRhs {
                sliding: SlidingRhs {
                    slip_floor: f64::INFINITY,
                    ..rhs.sliding
                },
                ..rhs
            };
            let at = locate(&mut run.stepper, &frozen, &prev, &cross, |v| {
                rhs.stop_event(v)
            })?;
            if self.separation(&at) > 0.0 {
                let (time, impulse) = (self.scales.time(at[0]), self.scales.impulse(at[1]));
                return Ok((at, LawEvent::SlidingStopped { time, impulse }));
            }
        }
        self.end_or_segment(run, &rhs, prev, cross, true)
    }

    /// After stepping `rhs` from `prev` to `cross`: the segment's end when no event was
    /// `hit`, else the end of the contact located inside the step.
    fn end_or_segment<R: ScaledRhs<LAW_DIM>>(
        &self,
        run: &mut Run<'_>,
        rhs: &R,
        prev: SVector<f64, LAW_DIM>,
        cross: SVector<f64, LAW_DIM>,
        hit: bool,
    ) -> Result<(SVector<f64, LAW_DIM>, LawEvent), Error> {
        if !hit {
            return Ok((cross, LawEvent::ReachedEnd));
        }
        let at = locate(&mut run.stepper, rhs, &prev, &cross, |v| self.separation(v))?;
        Ok((at, LawEvent::Ended))
    }

    /// Sliding after the stop with friction frozen along e0 (`stick = false`).
    fn slide_frozen(
        &self,
        y: SVector<f64, LAW_DIM>,
        b: f64,
        run: &mut Run<'_>,
    ) -> Result<(SVector<f64, LAW_DIM>, LawEvent), Error> {
        let rhs = self.rhs(Direction::Frozen);
        let p = &self.problem;
        let (prev, cross, hit) =
            step_until(&mut run.stepper, &rhs, y, b, &mut run.rec, |rec, v| {
                if self.separation(v) <= 0.0 {
                    return true;
                }
                rec.measure_frozen(&sliding_part(v), p.e0, rhs.sliding.slip_floor);
                if rec.takes_steps() {
                    self.emit(rec, v, None);
                }
                false
            })?;
        self.end_or_segment(run, &rhs, prev, cross, hit)
    }

    /// The normal law alone (no friction, or stuck): only x, U and delta move.
    fn press(
        &self,
        y: SVector<f64, LAW_DIM>,
        b: f64,
        run: &mut Run<'_>,
    ) -> Result<(SVector<f64, LAW_DIM>, LawEvent), Error> {
        let rhs = NormalLawRhs {
            scales: self.scales,
        };
        let full = |v: &SVector<f64, NORMAL_LAW_DIM>| {
            let mut st = y;
            (st[0], st[1], st[COMPRESSION]) = (v[0], v[1], v[2]);
            st
        };
        let sc = self.scales;
        let end = |v: &SVector<f64, NORMAL_LAW_DIM>| sc.separation(v[1], v[2]);
        let y0 = SVector::from([y[0], y[1], y[COMPRESSION]]);
        let (prev, cross, hit) =
            step_until(&mut run.stepper, &rhs, y0, b, &mut run.rec, |rec, v| {
                if end(v) <= 0.0 {
                    return true;
                }
                if rec.takes_steps() {
                    self.emit(rec, &full(v), None);
                }
                false
            })?;
        if !hit {
            return Ok((full(&cross), LawEvent::ReachedEnd));
        }
        let at = locate(&mut run.stepper, &rhs, &prev, &cross, end)?;
        Ok((full(&at), LawEvent::Ended))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::contact_law::Damping;

    /// Elastic Hertz head on: e = 1, tau = (4/5) B(2/5, 1/2) delta_max / v with
    /// B(2/5, 1/2) = Gamma(2/5) Gamma(1/2) / Gamma(9/10) = 3.67905..., delta_max =
    /// (5 m* v^2 / (4 k))^(2/5), F_max = k delta_max^(3/2).
    #[test]
    fn elastic_head_on_is_hertz() {
        let (k, m, v) = (1e9, 0.085, 1.0);
        let h = head_on(&ContactLaw::elastic(k).unwrap(), m, v, 1e-12).unwrap();
        let d = (5.0 * m * v * v / (4.0 * k)).powf(0.4);
        let tau = 0.8 * 3.679_093_980_405_881 * d / v;
        assert!((h.restitution - 1.0).abs() < 1e-11, "{}", h.restitution);
        assert!(
            (h.duration - tau).abs() < 1e-10 * tau,
            "{} vs {tau}",
            h.duration
        );
        assert!((h.max_compression - d).abs() < 1e-11 * d);
        let f = k * d.powf(1.5);
        assert!((h.peak_force - f).abs() < 1e-9 * f);
        let _ = Damping::None;
    }
}
