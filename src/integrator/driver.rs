//! Time stepping of the contact: method choice, tolerances, segments between breakpoints
//! and samples, location of the stick event, statistics.
//!
//! The integration runs in the scaled variables of [`crate::integrator::rhs`]. It proceeds in
//! segments ending at the profile's breakpoints (kinks or jumps of f: the integrators step
//! exactly to them) and, with `--samples N`, at the sample times i/N. While the balls slide,
//! every accepted step evaluates the event function g = slip . e0; the step that makes it
//! non-positive has crossed the stop. The stop is then located inside that step by
//! re-integrating from the step's start, with the same method, to trial times chosen by
//! regula falsi (Illinois) in the impulse fraction q = Phi(s): g is affine in q while mu is
//! constant, so the iteration converges in one or two trials, and the located state is the
//! integrator's own. After the stop the rest of the pulse is integrated with the normal
//! equation alone (sticking), or with friction frozen along e0 (effect `stick = false`).

use super::settings::{Method, Sampling, SolverSettings, Stats};
use crate::error::Error;
use crate::formats::trace::{TraceRow, TraceSink};
use crate::integrator::rhs::{
    Direction, NormalRhs, NormalState, ScaledRhs, SlidingRhs, SlidingState, NORMAL_DIM,
    SLIDING_DIM, SLIP_ROUND_OFF,
};
use crate::model::collision::Collision;
use crate::model::state::CmState;
use crate::profile::ForceProfile;
use nalgebra::{SVector, Vector2, Vector3};
use ode_solvers::{Dop853, Dopri5, OutputType, Rk4, System};
use std::cell::Cell;

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

/// The integrator as configured for one segment.
#[derive(Debug, Clone, Copy)]
struct Stepper {
    method: Method,
    rtol: f64,
    atol: f64,
    steps_per_unit: f64,
}

/// Adapts a [`ScaledRhs`] and an observer of accepted steps to `ode_solvers::System`.
struct Adapter<'a, const N: usize, R, O> {
    rhs: &'a R,
    observer: &'a mut O,
    evals: Cell<u64>,
    last: SVector<f64, N>,
    before_last: SVector<f64, N>,
    step_limit: u64,
    steps: u64,
    stopped: bool,
}

impl<const N: usize, R: ScaledRhs<N>, O: FnMut(&SVector<f64, N>) -> bool>
    System<f64, SVector<f64, N>> for Adapter<'_, N, R, O>
{
    #[inline]
    fn system(&self, _x: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>) {
        self.evals.set(self.evals.get() + 1);
        self.rhs.derivative(y, dy);
    }

    fn solout(&mut self, _x: f64, y: &SVector<f64, N>, _dy: &SVector<f64, N>) -> bool {
        self.before_last = self.last;
        self.last = *y;
        self.steps += 1;
        if (self.observer)(y) {
            self.stopped = true;
            return true;
        }
        self.steps >= self.step_limit
    }
}

/// Relative size (against the scaled time) of a span the adaptive methods cannot step.
const ROUND_OFF_SPAN: f64 = 1e-12;

/// Largest number of rk4 steps given to one `ode_solvers::Rk4` (its output vector holds
/// them all).
const RK4_CHUNK: u64 = 4096;

/// End of one call to the integrator.
struct Advanced<const N: usize> {
    y: SVector<f64, N>,
    h_last: f64,
}

/// Integrates from `(a, y0)` to `b`, calling `observer` after each accepted step (it
/// returns true to stop). The time component of the result is snapped to `b`.
#[allow(clippy::too_many_arguments)]
fn advance<const N: usize, R: ScaledRhs<N>, O: FnMut(&SVector<f64, N>) -> bool>(
    rhs: &R,
    stepper: &Stepper,
    a: f64,
    y0: SVector<f64, N>,
    b: f64,
    h_init: f64,
    observer: &mut O,
    stats: &mut Stats,
) -> Result<Advanced<N>, Error> {
    if b - a <= 16.0 * f64::EPSILON * a.abs() {
        // Nothing to integrate (or less than the solvers' step-size floor at this time:
        // Dopri5 and Dop853 give up with StepSizeUnderflow when 0.1 h <= EPSILON |x|, i.e.
        // h <= 10 EPSILON |x|): the state moves by at most a rounding error.
        let mut y = y0;
        y[0] = y[0].max(b);
        return Ok(Advanced { y, h_last: h_init });
    }
    let span = b - a;
    // The adaptive methods of ode_solvers stop with StepSizeUnderflow when a step is below
    // 10 eps |x|. A span that short (a stick event or a sample a few ulps from a breakpoint)
    // is taken in one classical RK4 step, exact to O(span^5) on a smooth segment; a step
    // size carried over from such a span is not used as the first step of the next one.
    let round_off = ROUND_OFF_SPAN * a.abs().max(b.abs());
    let tiny = span <= round_off;
    let method = if tiny { Method::Rk4 } else { stepper.method };
    let rk4_steps = if tiny {
        1.0
    } else {
        ((span * stepper.steps_per_unit - 1e-9).ceil()).max(1.0)
    };
    let mut adapter = Adapter {
        rhs,
        observer,
        evals: Cell::new(0),
        last: y0,
        before_last: y0,
        step_limit: if method == Method::Rk4 {
            rk4_steps as u64
        } else {
            u64::MAX
        },
        steps: 0,
        stopped: false,
    };
    let h0 = if h_init > round_off {
        h_init.min(span)
    } else {
        0.0
    };
    let fail = |source| Error::Integration {
        method: stepper.method.name(),
        scaled_time: a,
        source,
    };
    let st = match method {
        Method::Rk4 => {
            // ode_solvers' Rk4 keeps every step in its output vector (80 bytes a step here):
            // a segment of a million steps took 80 MB, steps = 1e9 would exhaust memory.
            // Integrate in chunks of at most RK4_CHUNK steps, each with its own solver.
            let total = rk4_steps as u64;
            let h = span / rk4_steps;
            let (mut done, mut x, mut y) = (0u64, a, y0);
            while done < total && !adapter.stopped {
                let n = (total - done).min(RK4_CHUNK);
                let x_end = if done + n == total {
                    b
                } else {
                    a + (done + n) as f64 * h
                };
                adapter.step_limit = adapter.steps + n;
                let st = Rk4::new(&mut adapter, x, y, x_end, (x_end - x) / n as f64)
                    .integrate()
                    .map_err(fail)?;
                stats.accepted_steps += u64::from(st.accepted_steps);
                done += n;
                x = x_end;
                y = adapter.last;
            }
            ode_solvers::dop_shared::Stats {
                num_eval: 0,
                accepted_steps: 0,
                rejected_steps: 0,
            }
        }
        Method::Dopri5 => {
            let mut s = Dopri5::from_param(
                &mut adapter,
                a,
                b,
                0.0,
                y0,
                stepper.rtol,
                stepper.atol,
                0.9,
                0.04,
                0.2,
                10.0,
                span,
                h0,
                100_000,
                1000,
                OutputType::Sparse,
            );
            s.integrate().map_err(fail)?
        }
        Method::Dop853 => {
            let mut s = Dop853::from_param(
                &mut adapter,
                a,
                b,
                0.0,
                y0,
                stepper.rtol,
                stepper.atol,
                0.9,
                0.0,
                0.333,
                6.0,
                span,
                h0,
                100_000,
                1000,
                OutputType::Sparse,
            );
            s.integrate().map_err(fail)?
        }
        Method::ClosedForm => unreachable!("the closed form does not step"),
    };
    stats.rhs_evaluations += adapter.evals.get();
    stats.accepted_steps += u64::from(st.accepted_steps);
    stats.rejected_steps += u64::from(st.rejected_steps);
    let mut y = adapter.last;
    let h_last = adapter.last[0] - adapter.before_last[0];
    if !adapter.stopped {
        y[0] = b;
    }
    Ok(Advanced { y, h_last })
}

/// `System` for `&mut Adapter`, so the adapter (and the observer's findings) outlive the
/// solver, which takes its system by value.
impl<const N: usize, R: ScaledRhs<N>, O: FnMut(&SVector<f64, N>) -> bool>
    System<f64, SVector<f64, N>> for &mut Adapter<'_, N, R, O>
{
    #[inline]
    fn system(&self, x: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>) {
        (**self).system(x, y, dy)
    }
    fn solout(&mut self, x: f64, y: &SVector<f64, N>, dy: &SVector<f64, N>) -> bool {
        (**self).solout(x, y, dy)
    }
}

/// Converts scaled states to physical ones.
struct Units<'a, P: ForceProfile + ?Sized> {
    c: &'a Collision,
    profile: &'a P,
    v: f64,
    w: f64,
    e: f64,
}

impl<P: ForceProfile + ?Sized> Units<'_, P> {
    fn state(&self, y: &SlidingState) -> CmState {
        let mut s = self.c.incoming;
        let [du, dv, dw] = y.delta_u();
        let [doy, doz] = y.delta_omega_yz();
        s.u_cm += Vector3::new(du, dv, dw) * self.v;
        // Eq 11: both balls' spins change by half the change of Omega; for unequal balls
        // A takes the share i_A / (i_A + i_B) of the change of r_A Omega^A + r_B Omega^B,
        // B the rest over r_B (both 1/2 for identical balls).
        let [ia, ib] = self.c.balls.scaled_inverse_alphas();
        let change = Vector3::new(0.0, doy, doz);
        s.omega_a += change * (ia / (ia + ib) * self.w);
        s.omega_b += change * (ib / (ia + ib) * (self.w / self.c.balls.radius_ratio()));
        s
    }

    fn row(
        &self,
        y: &SlidingState,
        time: Option<f64>,
        theta: Option<f64>,
        e0: Vector2<f64>,
    ) -> TraceRow {
        let s = y.time();
        let tau = self.profile.duration();
        let p = self.c.impulse;
        let slip = y.slip();
        let sign = if slip.dot(&e0) < 0.0 { -1.0 } else { 1.0 };
        TraceRow {
            t: time.unwrap_or(s * tau),
            force: p / tau * self.profile.shape(s),
            impulse: p * self.profile.cumulative(s),
            state: self.state(y),
            slip_speed: sign * slip.x.hypot(slip.y) * self.v,
            theta,
            heat_sliding: y.heat() * self.e,
        }
    }
}

/// The phase of the contact.
#[derive(Debug, Clone, Copy)]
enum Phase {
    /// Sliding with the direction from the current slip, watching for the stop.
    Sliding,
    /// Sliding with friction frozen along e0 (after the stop, `stick = false`).
    Frozen,
    /// Normal force only; the tangential part of the state is frozen at `base`.
    Normal,
}

/// Mutable bookkeeping of a run.
struct Run<'a> {
    sink: Option<&'a mut dyn TraceSink>,
    steps_mode: bool,
    last_row_time: f64,
    error: Option<Error>,
    theta_drift: f64,
    slip_consistency: f64,
    theta_last: Option<f64>,
}

impl Run<'_> {
    /// Records a non-finite accepted state as the run's error; true when it was one (the
    /// observer then stops the solver).
    fn flag_non_finite<const N: usize>(&mut self, v: &SVector<f64, N>) -> bool {
        if v.iter().all(|x| x.is_finite()) {
            return false;
        }
        self.error = Some(non_finite("state", v));
        true
    }

    fn emit<P: ForceProfile + ?Sized>(
        &mut self,
        units: &Units<'_, P>,
        y: &SlidingState,
        time: Option<f64>,
        e0: Vector2<f64>,
    ) {
        if self.error.is_some() || y.time() <= self.last_row_time {
            return;
        }
        if let Some(sink) = self.sink.as_deref_mut() {
            let row = units.row(y, time, self.theta_last, e0);
            if let Err(e) = sink.row(&row) {
                self.error = Some(e);
            }
        }
        self.last_row_time = y.time();
    }
}

/// Integrates a collision that happens (U(0) > 0) with the given settings (not
/// `closed-form`), optionally writing a trace.
pub fn integrate<P: ForceProfile + ?Sized>(
    c: &Collision,
    profile: &P,
    settings: &SolverSettings,
    trace: Option<(&mut dyn TraceSink, Sampling)>,
) -> Result<Integrated, Error> {
    assert!(c.collides(), "integrate needs a collision");
    assert!(settings.method != Method::ClosedForm);
    let stepper = Stepper {
        method: settings.method,
        rtol: settings.rtol,
        atol: settings.atol,
        steps_per_unit: f64::from(settings.steps),
    };
    let sc = c.scales;
    let units = Units {
        c,
        profile,
        v: sc.speed,
        w: sc.spin,
        e: sc.energy,
    };
    let pi = c.impulse / sc.impulse;
    let e0 = c.direction.unwrap_or_else(Vector2::zeros);
    let slip0 = c.incoming.slip_of(&c.balls) / sc.speed;
    // The event function at or below which the slip counts as stopped: its round-off level,
    // a relative 1e-14 of S(0) (an impulse error of at most 1e-14 p_stick).
    let stop_floor = 1e-14 * slip0.norm();
    let sliding_rhs = |direction| SlidingRhs {
        profile,
        impulse: pi,
        friction: c.contact.friction,
        speed_scale: sc.speed,
        inv_alpha: c.balls.scaled_inverse_alphas(),
        e0,
        direction,
        slip_floor: SLIP_ROUND_OFF * slip0.norm(),
    };
    let normal_rhs = NormalRhs {
        profile,
        impulse: pi,
    };
    let (sink, sampling) = match trace {
        Some((s, m)) => (Some(s), m),
        None => (None, Sampling::Steps),
    };
    let mut run = Run {
        sink,
        steps_mode: sampling == Sampling::Steps,
        last_row_time: -1.0,
        error: None,
        theta_drift: 0.0,
        slip_consistency: 0.0,
        theta_last: c.theta(),
    };
    let mut stats = Stats::default();
    let mut h = 0.0;

    let mut y = SlidingState::initial(slip0);
    let mut sticks = false;
    let mut stick_time = None;
    let mut stick_impulse = None;
    let mut phase = match c.active_friction() {
        Some(_) if c.s0 > 0.0 => Phase::Sliding,
        Some(_) => {
            // S(0) = 0: the surfaces do not slide at all (ERRATA.md, gap 1).
            sticks = true;
            stick_time = Some(0.0);
            stick_impulse = Some(0.0);
            Phase::Normal
        }
        None => Phase::Normal,
    };
    run.emit(&units, &y, Some(0.0), e0);

    let breakpoints: &[f64] = if settings.breakpoints {
        profile.breakpoints()
    } else {
        &[]
    };
    let samples = match sampling {
        Sampling::Uniform(n) => n.max(1),
        Sampling::Steps => 0,
    };
    let (mut next_bp, mut next_sample) = (0usize, 1u64);
    let mut s = 0.0;
    while s < 1.0 {
        while next_bp < breakpoints.len() && breakpoints[next_bp] <= s {
            next_bp += 1;
        }
        let mut stop = 1.0_f64;
        if next_bp < breakpoints.len() {
            stop = stop.min(breakpoints[next_bp]);
        }
        let sample_time = (samples > 0).then(|| next_sample as f64 / samples as f64);
        if let Some(ts) = sample_time {
            stop = stop.min(ts);
        }
        // Integrate [s, stop], switching phase at the stick event.
        while y.time() < stop {
            match phase {
                Phase::Sliding => {
                    let rhs = sliding_rhs(Direction::CurrentSlip);
                    let mut prev = y;
                    let mut crossed = None;
                    let mut observer = |v: &SVector<f64, SLIDING_DIM>| -> bool {
                        let st = SlidingState(*v);
                        if run.flag_non_finite(v) {
                            return true;
                        }
                        // A slip within round-off of zero has stopped: a step that lands
                        // there (a sample time, a breakpoint) is the stop itself.
                        if rhs.event(&st) <= stop_floor {
                            crossed = Some(st);
                            return true;
                        }
                        let slip = st.slip();
                        run.theta_drift =
                            run.theta_drift.max((slip.x * e0.y - slip.y * e0.x).abs());
                        run.slip_consistency = run.slip_consistency.max(consistency(&st, &slip0));
                        // Near the stop the slip's direction is round-off (SLIP_ROUND_OFF):
                        // the trace keeps the last angle measured above that floor. Only a
                        // trace reads it.
                        if run.sink.is_some() && slip.norm() > rhs.slip_floor {
                            run.theta_last = Some(crate::model::state::slip_angle(slip));
                        }
                        if run.steps_mode {
                            run.emit(&units, &st, None, e0);
                        }
                        prev = st;
                        run.error.is_some()
                    };
                    let adv = advance(
                        &rhs,
                        &stepper,
                        y.time(),
                        y.0,
                        stop,
                        h,
                        &mut observer,
                        &mut stats,
                    )?;
                    if let Some(e) = run.error.take() {
                        return Err(e);
                    }
                    h = adv.h_last;
                    match crossed {
                        None => y = SlidingState(adv.y),
                        Some(cross) => {
                            let mut at =
                                locate_stop(&rhs, &stepper, profile, &prev, &cross, &mut stats)?;
                            // The event is pinned down by the impulse (CONTRACTS.md): the
                            // fraction q of P the integrator itself delivered up to the stop
                            // (-Delta U / pi), and the time at which the exact p(t) reaches
                            // it. Where the method's own quadrature of f is coarse (rk4 on
                            // a t^0.5 end) its internal time is off, not the impulse. The
                            // trace's stop row carries that time.
                            let q = (-at.delta_u()[0] / pi).clamp(0.0, 1.0);
                            let t_stop = profile.time_at_cumulative(q) * profile.duration();
                            stick_time = Some(t_stop);
                            stick_impulse = Some(q * c.impulse);
                            if c.effects.stick {
                                sticks = true;
                                at.set_slip(Vector2::zeros());
                                phase = Phase::Normal;
                            } else {
                                phase = Phase::Frozen;
                            }
                            run.emit(&units, &at, stick_time, e0);
                            y = at;
                        }
                    }
                }
                Phase::Frozen => {
                    let rhs = sliding_rhs(Direction::Frozen);
                    let mut observer = |v: &SVector<f64, SLIDING_DIM>| -> bool {
                        if run.flag_non_finite(v) {
                            return true;
                        }
                        // Past the stop the signed slip S < 0 runs along -e0: theta is
                        // the angle of slip / S, measured once the slip is clear of
                        // round-off again (an angle kept from near the stop is noise).
                        let slip = SlidingState(*v).slip();
                        if run.sink.is_some() && slip.norm() > rhs.slip_floor {
                            let along = if slip.dot(&e0) < 0.0 { -slip } else { slip };
                            run.theta_last = Some(crate::model::state::slip_angle(along));
                        }
                        if run.steps_mode {
                            run.emit(&units, &SlidingState(*v), None, e0);
                        }
                        run.error.is_some()
                    };
                    let adv = advance(
                        &rhs,
                        &stepper,
                        y.time(),
                        y.0,
                        stop,
                        h,
                        &mut observer,
                        &mut stats,
                    )?;
                    if let Some(e) = run.error.take() {
                        return Err(e);
                    }
                    h = adv.h_last;
                    y = SlidingState(adv.y);
                }
                Phase::Normal => {
                    let base = y;
                    let full = |v: &SVector<f64, NORMAL_DIM>| {
                        let n = NormalState(*v);
                        let mut st = base;
                        st.set_time(n.time());
                        st.set_delta_u_normal(n.delta_u());
                        st
                    };
                    let mut observer = |v: &SVector<f64, NORMAL_DIM>| -> bool {
                        if run.flag_non_finite(v) {
                            return true;
                        }
                        if run.steps_mode {
                            run.emit(&units, &full(v), None, e0);
                        }
                        run.error.is_some()
                    };
                    let y0 = NormalState::new(y.time(), base.delta_u()[0]);
                    let adv = advance(
                        &normal_rhs,
                        &stepper,
                        y.time(),
                        y0.0,
                        stop,
                        h,
                        &mut observer,
                        &mut stats,
                    )?;
                    if let Some(e) = run.error.take() {
                        return Err(e);
                    }
                    h = adv.h_last;
                    y = full(&adv.y);
                }
            }
        }
        s = stop;
        if sample_time == Some(stop) {
            let t = next_sample as f64 * profile.duration() / samples as f64;
            run.emit(&units, &y, Some(t), e0);
            next_sample += 1;
        }
    }
    if let Some(e) = run.error.take() {
        return Err(e);
    }
    let slip = y.slip();
    let s_out = if sticks {
        0.0
    } else {
        slip.dot(&e0) * sc.speed
    };
    let s_out = if c.active_friction().is_none() {
        c.s0
    } else {
        s_out
    };
    Ok(Integrated {
        out: units.state(&y),
        heat_sliding: y.heat() * sc.energy,
        s_out,
        sticks,
        stick_time,
        stick_impulse,
        theta_drift: run.theta_drift,
        slip_consistency: run.slip_consistency,
        stats,
    })
}

/// |carried slip - (2 dV + dOmega_z, 2 dW - dOmega_y) - slip0|, scaled.
fn consistency(st: &SlidingState, slip0: &Vector2<f64>) -> f64 {
    let [_, dv, dw] = st.delta_u();
    let [doy, doz] = st.delta_omega_yz();
    let recomputed = slip0 + Vector2::new(2.0 * dv + doz, 2.0 * dw - doy);
    (st.slip() - recomputed).amax()
}

fn non_finite<const N: usize>(what: &str, v: &SVector<f64, N>) -> Error {
    let bad = v
        .iter()
        .copied()
        .find(|x| !x.is_finite())
        .unwrap_or(f64::NAN);
    Error::NonFinite {
        field: what.to_string(),
        value: bad,
    }
}

/// Locates the stop of sliding inside the step from `prev` (g > 0) to `cross` (g <= 0):
/// regula falsi (Illinois) in q = Phi(s), each trial re-integrated from `prev`.
///
/// The trials integrate with friction along e0 (the round-off branch of the right-hand side). Every trial is
/// aimed at the stop, so its last stages evaluate the right-hand side where the slip is a
/// rounding error of S(0) and its direction slip/|slip| is noise: friction at full
/// strength in a random direction, an error of order (step) x mu f in the located state
/// (3e-8 scaled for RK4 on a rectangle pulse) and a root finder that stalls. For the
/// exact flow the slip stays on its ray (theta constant, eq 23), so inside this one step
/// e0 is the direction the slip has; the accepted steps before it keep taking the
/// direction from the current slip, and theta_drift measures them.
fn locate_stop<P: ForceProfile + ?Sized>(
    rhs: &SlidingRhs<'_, P>,
    stepper: &Stepper,
    profile: &P,
    prev: &SlidingState,
    cross: &SlidingState,
    stats: &mut Stats,
) -> Result<SlidingState, Error> {
    /// Bracket width in q (fraction of P) at which the location is done.
    const Q_TOL: f64 = 1e-14;
    let (s_lo0, s_hi0) = (prev.time(), cross.time());
    let (mut q_lo, mut g_lo) = (profile.cumulative(s_lo0), rhs.event(prev));
    let (mut q_hi, mut g_hi) = (profile.cumulative(s_hi0), rhs.event(cross));
    if g_hi >= 0.0 {
        // The step ended within round-off of the stop: that is the stop.
        return Ok(*cross);
    }
    let g_tol = 1e-14 * (g_lo - g_hi);
    let mut best = *cross;
    let mut best_g = g_hi.abs();
    let mut side = 0i8;
    let mut no_stop = |_: &SVector<f64, SLIDING_DIM>| false;
    // Friction along e0 in every trial, with a speed-dependent mu continued in the signed
    // slip: an infinite round-off floor selects exactly that branch of the right-hand side.
    let frozen = SlidingRhs {
        slip_floor: f64::INFINITY,
        ..*rhs
    };
    for _ in 0..100 {
        if best_g <= g_tol || q_hi - q_lo <= Q_TOL {
            break;
        }
        let q = q_lo + (q_hi - q_lo) * (g_lo / (g_lo - g_hi));
        let s = profile.time_at_cumulative(q).clamp(s_lo0, s_hi0);
        let adv = advance(
            &frozen,
            stepper,
            s_lo0,
            prev.0,
            s,
            s - s_lo0,
            &mut no_stop,
            stats,
        )?;
        let st = SlidingState(adv.y);
        let g = rhs.event(&st);
        if g.abs() < best_g || (g <= 0.0 && g.abs() <= best_g) {
            best = st;
            best_g = g.abs();
        }
        if g > 0.0 {
            q_lo = q;
            g_lo = g;
            if side == 1 {
                g_hi *= 0.5;
            }
            side = 1;
        } else {
            q_hi = q;
            g_hi = g;
            if side == -1 {
                g_lo *= 0.5;
            }
            side = -1;
        }
    }
    Ok(best)
}
