//! One call of an `ode_solvers` method over a span: the step-control constants, the adapter
//! of a [`ScaledRhs`] to `ode_solvers::System`, the classical RK4 run in chunks, and the
//! spans too short to step (docs/model.md#breakpoints).

use super::record::Recorder;
use super::rhs::ScaledRhs;
use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::settings::{SolverSettings, Stats};
use nalgebra::SVector;
use ode_solvers::dop_shared::IntegrationError;
use ode_solvers::{Dop853, Dopri5, OutputType, Rk4, System};
use std::cell::Cell;

/// Step-size control of an embedded Dormand-Prince pair: the arguments of
/// `ode_solvers`' `from_param` besides the problem, the tolerances and the span.
#[derive(Debug, Clone, Copy, PartialEq)]
struct StepControl {
    /// Factor on the optimal step-size proposal, so that the next step is accepted with
    /// high probability.
    safety_factor: f64,
    /// beta of the PI step-size controller (0: the classical controller).
    beta: f64,
    /// Smallest ratio of a new step to the old one.
    fac_min: f64,
    /// Largest ratio of a new step to the old one.
    fac_max: f64,
    /// Steps one call may take before it gives up ([`Error::TooManySteps`]).
    max_steps: u32,
    /// Stiffness is tested every this many accepted steps ([`Error::Stiff`]).
    stiffness_test_interval: u32,
    /// Largest step, in scaled time (the contact lasts about 1): a span is otherwise
    /// stepped in as few steps as the error estimate allows.
    max_step: f64,
}

/// The step control of DOPRI5 as published by Hairer, Nørsett and Wanner (Solving ODEs I,
/// 2nd ed., II.4 and the code DOPRI5: safety 0.9, beta 0.04, step ratios in [0.2, 10],
/// 100 000 steps, stiffness test every 1000), which `ode_solvers::Dopri5::new` also uses.
const DOPRI5_CONTROL: StepControl = StepControl {
    safety_factor: 0.9,
    beta: 0.04,
    fac_min: 0.2,
    fac_max: 10.0,
    max_steps: 100_000,
    stiffness_test_interval: 1000,
    max_step: f64::INFINITY,
};

/// The step control of DOP853 as published by Hairer, Nørsett and Wanner (the code DOP853:
/// safety 0.9, beta 0, step ratios in [0.333, 6], 100 000 steps, stiffness test every
/// 1000), which `ode_solvers::Dop853::new` also uses, with steps of at most a quarter of
/// the contact: DOP853's error estimate (its fifth-order error damped by the third-order
/// one) let a contact with a steep speed-dependent mu (alpha 0.01) through in 5 steps at
/// rtol 1e-10, 1.4e-8 off the closed form (4.4e-10 at rtol 1e-9 in 6 steps; 2.2e-11 with
/// the cap, in 8; found by the property tests).
const DOP853_CONTROL: StepControl = StepControl {
    safety_factor: 0.9,
    beta: 0.0,
    fac_min: 0.333,
    fac_max: 6.0,
    max_steps: 100_000,
    stiffness_test_interval: 1000,
    max_step: 0.25,
};

/// Output interval of the dense output: unused, the output is sparse (accepted steps only).
const NO_DENSE_OUTPUT: f64 = 0.0;

/// A span [a, b] with b - a at most this many times eps |a| is nothing to integrate: it is
/// below the step-size floor of Dopri5 and Dop853 (they give up with a step-size underflow
/// when 0.1 h <= eps |x|, i.e. h <= 10 eps |x|), and the state moves by at most a rounding
/// error.
const NEGLIGIBLE_SPAN_ULPS: f64 = 16.0;

/// Relative size (against the scaled time) of a span the adaptive methods cannot step: it
/// is taken in one classical RK4 step, exact to O(span^5) on a smooth segment (a stick event
/// or a sample a few ulps from a breakpoint). It is about 450 times the adaptive methods'
/// floor of 10 eps |x|, so that every step they are given is well above that floor.
const ROUND_OFF_SPAN: f64 = 1e-12;

/// Slack subtracted before rounding a segment's share of the rk4 steps up: a share that is
/// an integer up to round-off (span x steps = 250.0000000001) is not given an extra step.
const RK4_COUNT_SLACK: f64 = 1e-9;

/// Largest number of rk4 steps given to one `ode_solvers::Rk4`: it keeps every step in its
/// output vector (80 bytes a step here), so a segment of a million steps took 80 MB and
/// steps = 1e9 would exhaust memory. 4096 steps are 320 kB.
const RK4_CHUNK: u64 = 4096;

/// First step of an advance that should cross its span in one step when the error allows
/// (the trials of an event search, which re-integrate one step from its start): `Span::new`
/// clamps the first step to the span's length.
pub(super) const WHOLE_SPAN: f64 = f64::INFINITY;

/// Runs an embedded Dormand-Prince pair (`Dopri5` or `Dop853`) with its [`StepControl`]
/// over a [`Span`] from `(a, y0)` to `b`, with the tolerances of a [`Stepper`]: the 16
/// positional arguments of `ode_solvers`' `from_param`, each named.
macro_rules! dormand_prince {
    ($solver:ident, $control:expr, $system:expr, $a:expr, $y0:expr, $b:expr, $stepper:expr, $span:expr) => {{
        let control: StepControl = $control;
        $solver::from_param(
            $system,
            $a,
            $b,
            NO_DENSE_OUTPUT,
            $y0,
            $stepper.rtol,
            $stepper.atol,
            control.safety_factor,
            control.beta,
            control.fac_min,
            control.fac_max,
            $span.length.min(control.max_step),
            $span.h0,
            control.max_steps,
            control.stiffness_test_interval,
            OutputType::Sparse,
        )
        .integrate()
    }};
}

/// A stepping method (the methods of [`Method`] but the closed form, which does not step).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum StepMethod {
    Rk4,
    Dopri5,
    Dop853,
}

impl StepMethod {
    fn method(self) -> Method {
        match self {
            StepMethod::Rk4 => Method::Rk4,
            StepMethod::Dopri5 => Method::Dopri5,
            StepMethod::Dop853 => Method::Dop853,
        }
    }
}

/// The integrator of a run: the method and its tolerances, the step size carried from one
/// span to the next, and the work done.
#[derive(Debug, Clone)]
pub(super) struct Stepper {
    method: StepMethod,
    rtol: f64,
    atol: f64,
    /// rk4 steps per unit of scaled time.
    steps_per_unit: f64,
    /// Last accepted step size (scaled), the first step tried in the next span (0: the
    /// solver chooses).
    h: f64,
    /// Work done so far.
    pub(super) stats: Stats,
}

/// End of one call to the integrator.
pub(super) struct Advanced<const N: usize> {
    /// The state reached: at the span's end, or where the observer stopped the solver.
    pub(super) y: SVector<f64, N>,
    /// The last accepted step size.
    h_last: f64,
}

impl Stepper {
    /// The stepper of `settings`; the closed form does not step and is refused.
    pub(super) fn new(settings: &SolverSettings) -> Result<Self, Error> {
        let method = match settings.method() {
            Method::Rk4 => StepMethod::Rk4,
            Method::Dopri5 => StepMethod::Dopri5,
            Method::Dop853 => StepMethod::Dop853,
            Method::ClosedForm => {
                return Err(Error::invalid(
                    "solver.method",
                    Method::ClosedForm,
                    "rk4, dopri5 or dop853: the closed form does not step (use solve)",
                ))
            }
        };
        Ok(Stepper {
            method,
            rtol: settings.rtol(),
            atol: settings.atol(),
            steps_per_unit: f64::from(settings.steps()),
            h: 0.0,
            stats: Stats::default(),
        })
    }

    /// Integrates from `y0` (its component 0 is the scaled time) to `b`, starting with the
    /// step size carried from the last span. The recorder watches every accepted step: a
    /// non-finite state, or an error the `observer` records (it returns true to stop the
    /// solver for its own reasons), stops the solver and is returned.
    pub(super) fn advance_checked<const N: usize, R: ScaledRhs<N>>(
        &mut self,
        rhs: &R,
        y0: SVector<f64, N>,
        b: f64,
        rec: &mut Recorder<'_>,
        mut observer: impl FnMut(&mut Recorder<'_>, &SVector<f64, N>) -> bool,
    ) -> Result<SVector<f64, N>, Error> {
        let mut watch = |v: &SVector<f64, N>| {
            if rec.flag_non_finite(v) {
                return true;
            }
            observer(rec, v) || rec.has_error()
        };
        let adv = self.advance(rhs, y0[0], y0, b, self.h, &mut watch)?;
        rec.take_error()?;
        self.h = adv.h_last;
        Ok(adv.y)
    }

    /// Integrates from `(a, y0)` to `b` with first step `h_init` (0: the solver chooses),
    /// calling `observer` after each accepted step (it returns true to stop). The time
    /// component of the result is snapped to `b`.
    pub(super) fn advance<const N: usize, R, O>(
        &mut self,
        rhs: &R,
        a: f64,
        y0: SVector<f64, N>,
        b: f64,
        h_init: f64,
        observer: &mut O,
    ) -> Result<Advanced<N>, Error>
    where
        R: ScaledRhs<N>,
        O: FnMut(&SVector<f64, N>) -> bool,
    {
        if b - a <= NEGLIGIBLE_SPAN_ULPS * f64::EPSILON * a.abs() {
            let mut y = y0;
            y[0] = y[0].max(b);
            return Ok(Advanced { y, h_last: h_init });
        }
        let span = Span::new(self, a, b, h_init);
        let mut adapter = Adapter::new(rhs, observer, y0, span.step_limit());
        let method = self.method.method();
        let fail = |source| failure(method, a, source);
        let solver_stats = match span.method {
            StepMethod::Rk4 => {
                let accepted = rk4_in_chunks(&mut adapter, a, y0, b, span.rk4_steps);
                self.stats.accepted_steps += accepted.map_err(fail)?;
                Stats::default()
            }
            StepMethod::Dopri5 => {
                dormand_prince!(Dopri5, DOPRI5_CONTROL, &mut adapter, a, y0, b, self, span)
                    .map(solver_stats)
                    .map_err(fail)?
            }
            StepMethod::Dop853 => {
                dormand_prince!(Dop853, DOP853_CONTROL, &mut adapter, a, y0, b, self, span)
                    .map(solver_stats)
                    .map_err(fail)?
            }
        };
        self.stats.rhs_evaluations += adapter.evals.get();
        self.stats.accepted_steps += solver_stats.accepted_steps;
        self.stats.rejected_steps += solver_stats.rejected_steps;
        Ok(adapter.end(b))
    }
}

/// The error of a solver (`method`) that gave up in the span starting at scaled time `a`.
fn failure(method: Method, a: f64, source: IntegrationError) -> Error {
    match source {
        IntegrationError::StepSizeUnderflow { x } => Error::StepSizeTooSmall {
            method,
            scaled_time: x,
            segment_start: a,
        },
        IntegrationError::MaxNumStepReached { x, n_step } => Error::TooManySteps {
            method,
            scaled_time: x,
            segment_start: a,
            steps: n_step,
        },
        IntegrationError::StiffnessDetected { x } => Error::Stiff {
            method,
            scaled_time: x,
            segment_start: a,
        },
    }
}

/// Work reported by one `ode_solvers` call.
fn solver_stats(st: ode_solvers::dop_shared::Stats) -> Stats {
    Stats {
        rhs_evaluations: 0,
        accepted_steps: u64::from(st.accepted_steps),
        rejected_steps: u64::from(st.rejected_steps),
    }
}

/// How one span [a, b] is stepped.
struct Span {
    /// The method: the run's, or RK4 for a span the adaptive methods cannot step.
    method: StepMethod,
    /// b - a.
    length: f64,
    /// Number of rk4 steps (1 for a round-off span).
    rk4_steps: f64,
    /// First step of an adaptive method (0: the solver chooses). A step size carried over
    /// from a round-off span is not used.
    h0: f64,
}

impl Span {
    fn new(stepper: &Stepper, a: f64, b: f64, h_init: f64) -> Self {
        let length = b - a;
        let round_off = ROUND_OFF_SPAN * a.abs().max(b.abs());
        let tiny = length <= round_off;
        Span {
            method: if tiny {
                StepMethod::Rk4
            } else {
                stepper.method
            },
            length,
            rk4_steps: if tiny {
                1.0
            } else {
                ((length * stepper.steps_per_unit - RK4_COUNT_SLACK).ceil()).max(1.0)
            },
            h0: if h_init > round_off {
                h_init.min(length)
            } else {
                0.0
            },
        }
    }

    /// Accepted steps after which the adapter stops the solver: the rk4 step count, no
    /// limit for the adaptive methods.
    fn step_limit(&self) -> u64 {
        if self.method == StepMethod::Rk4 {
            self.rk4_steps as u64
        } else {
            u64::MAX
        }
    }
}

/// Classical RK4 from `(a, y0)` to `b` in `steps` equal steps, in chunks of at most
/// [`RK4_CHUNK`] steps, each with its own solver. Returns the accepted steps.
fn rk4_in_chunks<const N: usize, R, O>(
    adapter: &mut Adapter<'_, N, R, O>,
    a: f64,
    y0: SVector<f64, N>,
    b: f64,
    steps: f64,
) -> Result<u64, IntegrationError>
where
    R: ScaledRhs<N>,
    O: FnMut(&SVector<f64, N>) -> bool,
{
    let total = steps as u64;
    let h = (b - a) / steps;
    let (mut done, mut x, mut y, mut accepted) = (0u64, a, y0, 0u64);
    while done < total && !adapter.stopped {
        let n = (total - done).min(RK4_CHUNK);
        let x_end = if done + n == total {
            b
        } else {
            a + (done + n) as f64 * h
        };
        adapter.step_limit = adapter.steps + n;
        let st = Rk4::new(&mut *adapter, x, y, x_end, (x_end - x) / n as f64).integrate()?;
        accepted += u64::from(st.accepted_steps);
        done += n;
        x = x_end;
        y = adapter.last;
    }
    Ok(accepted)
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

impl<'a, const N: usize, R, O> Adapter<'a, N, R, O> {
    fn new(rhs: &'a R, observer: &'a mut O, y0: SVector<f64, N>, step_limit: u64) -> Self {
        Adapter {
            rhs,
            observer,
            evals: Cell::new(0),
            last: y0,
            before_last: y0,
            step_limit,
            steps: 0,
            stopped: false,
        }
    }

    /// The state reached and the last step size; the time snapped to `b` unless the
    /// observer stopped the solver.
    fn end(&self, b: f64) -> Advanced<N> {
        let mut y = self.last;
        let h_last = self.last[0] - self.before_last[0];
        if !self.stopped {
            y[0] = b;
        }
        Advanced { y, h_last }
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// y' = y^2, y(0) = 1 (component 1; component 0 is the time): y = 1 / (1 - s) blows up
    /// at s = 1.
    struct BlowUp;
    impl ScaledRhs<2> for BlowUp {
        fn derivative(&self, y: &SVector<f64, 2>, dy: &mut SVector<f64, 2>) {
            *dy = SVector::from([1.0, y[1] * y[1]]);
        }
    }

    /// The adaptive methods shrink their steps towards the singularity until they are below
    /// the floor of 10 eps s: StepSizeTooSmall, near s = 1, naming the method and the
    /// segment.
    #[test]
    fn a_blow_up_is_a_step_size_too_small() {
        for method in [Method::Dopri5, Method::Dop853] {
            let settings = SolverSettings::new(method, 1e-10, 1e-10, 1000).unwrap();
            let mut stepper = Stepper::new(&settings).unwrap();
            let y0 = SVector::from([0.25, 4.0 / 3.0]);
            let mut never = |_: &SVector<f64, 2>| false;
            let e = stepper
                .advance(&BlowUp, 0.25, y0, 2.0, 0.0, &mut never)
                .err();
            let near_one = |t: f64| (t - 1.0).abs() < 1e-6;
            assert!(
                matches!(e, Some(Error::StepSizeTooSmall { method: m, scaled_time, segment_start: 0.25 })
                    if m == method && near_one(scaled_time)),
                "{method}: {e:?}"
            );
        }
    }

    /// Each failure of ode_solvers has its own variant.
    #[test]
    fn failures_map_to_variants() {
        let m = Method::Dop853;
        let e = failure(
            m,
            0.1,
            IntegrationError::MaxNumStepReached { x: 0.2, n_step: 7 },
        );
        assert!(matches!(
            e,
            Error::TooManySteps {
                method: Method::Dop853,
                scaled_time: 0.2,
                segment_start: 0.1,
                steps: 7
            }
        ));
        let e = failure(m, 0.1, IntegrationError::StiffnessDetected { x: 0.3 });
        assert!(matches!(
            e,
            Error::Stiff {
                method: Method::Dop853,
                scaled_time: 0.3,
                segment_start: 0.1
            }
        ));
        let e = failure(m, 0.1, IntegrationError::StepSizeUnderflow { x: 0.4 });
        assert!(matches!(
            e,
            Error::StepSizeTooSmall {
                scaled_time: 0.4,
                ..
            }
        ));
    }

    /// rk4 takes its share of the steps, rounded up, and snaps to the span's end: on
    /// y' = y^2 from s = 0 (y = 1) to 1/2 the exact value is 2; the last step size, which the
    /// next span tries first, is the share's.
    #[test]
    fn rk4_share_of_steps() {
        let settings = SolverSettings::new(Method::Rk4, 1e-10, 1e-10, 1000).unwrap();
        let mut stepper = Stepper::new(&settings).unwrap();
        let y0 = SVector::from([0.0, 1.0]);
        let a = stepper
            .advance(&BlowUp, 0.0, y0, 0.5, 0.0, &mut |_: &SVector<f64, 2>| false)
            .unwrap();
        assert_eq!(stepper.stats.accepted_steps, 500);
        // The last step, the first of the next span: 0.5 / 500.
        assert!((a.h_last - 1e-3).abs() < 1e-15, "{}", a.h_last);
        assert_eq!(a.y[0], 0.5);
        assert!((a.y[1] - 2.0).abs() < 1e-10, "{}", a.y[1]);
    }

    /// A span far below the adaptive methods' floor is one RK4 step; a negligible one is
    /// no step at all.
    #[test]
    fn round_off_spans() {
        let settings = SolverSettings::new(Method::Dop853, 1e-10, 1e-10, 1000).unwrap();
        let mut stepper = Stepper::new(&settings).unwrap();
        let y0 = SVector::from([0.5, 2.0]);
        let b = 0.5 + 1e-14;
        let a = stepper
            .advance(&BlowUp, 0.5, y0, b, 0.0, &mut |_: &SVector<f64, 2>| false)
            .unwrap();
        assert_eq!(stepper.stats.accepted_steps, 1);
        assert_eq!(a.y[0], b);
        let y0 = SVector::from([0.5, 2.0]);
        let a = stepper
            .advance(
                &BlowUp,
                0.5,
                y0,
                0.5 + f64::EPSILON,
                0.0,
                &mut |_: &SVector<f64, 2>| false,
            )
            .unwrap();
        assert_eq!(stepper.stats.accepted_steps, 1);
        assert_eq!(a.y[1], 2.0);
    }

    /// y' = 0 where the fractional part of s is below 1/2, 1 above (component 0 is the
    /// time): a jump in the derivative at every half-integer, which no step crossing it
    /// meets to a tolerance of 1e-10.
    struct Jumps;
    impl ScaledRhs<2> for Jumps {
        fn derivative(&self, y: &SVector<f64, 2>, dy: &mut SVector<f64, 2>) {
            let up = y[0] - y[0].floor() >= 0.5;
            *dy = SVector::from([1.0, if up { 1.0 } else { 0.0 }]);
        }
    }

    /// The rejected steps are counted, summed over the calls. Each call starts with a step
    /// of 1e-6 on y' = 0, which has no error and is accepted (ode_solvers counts no
    /// rejection before the first acceptance); the steps then grow tenfold until one
    /// crosses the jump at s = 1/2 or 3/2 and is rejected. The work of the two
    /// Dormand-Prince codes (Hairer, Norsett and Wanner, the codes DOPRI5 and DOP853, whose
    /// counts ode_solvers follows) then pins the rejections: a call evaluates the
    /// right-hand side once at its start; DOPRI5 (first same as last) six times per step
    /// tried; DOP853 eleven times per step tried and once more at each accepted point.
    #[test]
    fn rejected_steps_are_counted_over_calls() {
        for method in [Method::Dopri5, Method::Dop853] {
            let settings = SolverSettings::new(method, 1e-10, 1e-10, 1000).unwrap();
            let mut stepper = Stepper::new(&settings).unwrap();
            let mut never = |_: &SVector<f64, 2>| false;
            let first = stepper
                .advance(&Jumps, 0.0, SVector::zeros(), 1.0, 1e-6, &mut never)
                .unwrap();
            assert!((first.y[1] - 0.5).abs() < 1e-6, "{method}: {}", first.y[1]);
            let once = stepper.stats;
            stepper
                .advance(&Jumps, 1.0, first.y, 2.0, 1e-6, &mut never)
                .unwrap();
            for (st, calls) in [(once, 1), (stepper.stats, 2)] {
                let (acc, evals) = (st.accepted_steps, st.rhs_evaluations);
                // Evaluations in the steps tried, and per step tried.
                let (in_steps, per_step) = match method {
                    Method::Dopri5 => (evals - calls, 6),
                    _ => (evals - calls - acc, 11),
                };
                assert_eq!(in_steps % per_step, 0, "{method}: {st:?}");
                let rejected = in_steps / per_step - acc;
                assert!(rejected > 0, "{method}: {st:?}");
                assert_eq!(st.rejected_steps, rejected, "{method}: {st:?}");
            }
            assert!(stepper.stats.rejected_steps > once.rejected_steps);
        }
    }
}
