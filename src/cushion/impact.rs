//! The impact of a ball on the cushion, stepped in the cushion's normal impulse P_I: the
//! phases (compression until the normal velocity is zero, restitution until the rule's
//! end), the slip events of both contacts located in P_I, and the outcome
//! (docs/cushion.md).

use super::outcome::{
    CushionContact, CushionOutcome, CushionPhase, CushionTraceRow, SlipChange, SlipEvent,
};
use super::params::{Cushion, CushionRestitution};
use super::rhs::{
    normal_velocity, slip_cushion, slip_table, Eval, Friction, Modes, Rhs, State, DIRECTION_FLOOR,
    PC, WORK,
};
use super::tableau::{
    step, Scheme, StepControl, Tolerance, DIM, DOP853_CONTROL, DOPRI5_CONTROL, Z,
};
use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::settings::{SolverSettings, Stats};
use crate::base::validate::finite_output;
use crate::model::params::{check_stepped_alpha, energy_in, kinetic_energy, Ball};
use nalgebra::Vector3;

/// Events are located in P_I to this fraction of the impulse scale (1 + e) m v_n(0) /
/// cos^2 theta (the frictionless impact's total) at the tightest: well inside the 1e-10
/// asked of them at the default tolerance.
const EVENT_TOL: f64 = 1e-12;

/// An adaptive run locates its events to this fraction of its smaller tolerance (relative
/// to the impulse scale), not tighter than [`EVENT_TOL`]: the state moves by about the
/// impulse's error (its derivative in P_I is of order one when scaled), so a hundredth of
/// the tolerance keeps the location's error below the steps' own. At the default 1e-10 this
/// is EVENT_TOL; at 1e-2 it is 1e-4, where locating to 1e-12 cost two to four extra steps an
/// event for nothing.
const EVENT_TOL_PER_TOL: f64 = 1e-2;

/// While a slip runs out (stepped in -ln |slip|), the run goes back to stepping in P_I
/// when the slip's rate of decrease falls below this fraction of its rate when the run-out
/// began: the slip is turning away from zero, not stopping.
const RUN_OUT_EXIT: f64 = 0.25;

/// A sliding contact's slip whose predicted stop is closer than this many steps in P_I
/// runs out in -ln |slip|: stepped in P_I, the turning of its direction, ever faster as
/// the slip shrinks, would take ever smaller steps.
const RUN_OUT_TRIGGER: f64 = 20.0;

/// Largest tail of a run-out, over the impulse scale (Run::tail).
const TAIL_MAX: f64 = 1e-10;

/// ... and closer than this fraction of the impulse scale: farther, a slip may as well
/// turn away from zero as stop, and P_I steps it best.
const RUN_OUT_RANGE: f64 = 0.02;

/// A run-out within this of its tail (in -ln |slip|) ends: closer, the slip is a few
/// ulps of the velocities and its steps are lost in their rounding.
const TAIL_SLACK: f64 = 0.01;

/// A stalled run-out (Run::one_step) whose stop is predicted within this fraction of the
/// impulse scale is a stop.
const STALL_STOP: f64 = 1e-8;

/// A falling slip at most this many times the smaller tolerance (scaled by v_ref) is zero.
const SLIP_RESOLUTION: f64 = 10.0;

/// First step in -ln |slip| of a run-out (adaptive methods): a factor e of the slip.
const RUN_OUT_FIRST_STEP: f64 = 1.0;

/// rk4's steps in -ln |slip| during a run-out: this span over `solver.steps` (0.1 at the
/// default 1000 steps, 280 steps from a slip of 1 to 1e-12 of it).
const RK4_RUN_OUT_SPAN: f64 = 100.0;

/// |g| at which an event is located, relative to the range of g over the crossing step:
/// its round-off level.
const G_TOL: f64 = 1e-14;

/// Smallest step in -ln |slip| of a run-out: below it, the run goes back to P_I.
const MIN_RUN_OUT_STEP: f64 = 1e-9;

/// A slip at most this (scaled by v_ref) is zero at the start of the impact (a rolling
/// ball's cloth contact).
const SLIP_ZERO: f64 = 1e-13;

/// Static friction holds when the friction needed is at most mu N times (1 + this): the
/// round-off of the small linear solve.
const CONE_SLACK: f64 = 1e-12;

/// Most changes of state settled at one impulse (a contact sticking can make the other
/// restart, lift off...): more means the states cycle, and the first consistent set is
/// kept.
const MAX_SETTLE: usize = 8;

/// After a restart or a reversal the slip takes the quasi-static direction (along which it
/// grows under its own friction) until it is this large (scaled by v_ref): smaller, its
/// direction relaxes to that one at a rate mu / |slip| that explicit steps follow only in
/// tiny steps, and the lag the quasi-static direction neglects is about |slip| / mu of
/// impulse. Measured over the benchmark's shots, 1e-2 changes the rebound by at most
/// 4e-9 of the speed against 1e-7 at tolerance 1e-13, at a sixth of the cost
/// (docs/cushion.md#slip-growing-from-zero).
const SEED_FLOOR: f64 = 1e-2;

/// Bisections of the Hermite interpolant for a phase's end: to 1e-12 of the step.
const HERMITE_BISECTIONS: usize = 40;

/// Most trials of the event location (Illinois regula falsi on the step size).
const MAX_TRIALS: usize = 100;

/// A cushion impulse past this many times the frictionless impact's (the impulse scale) is
/// a jam (Run::jammed): over 1929 shots with mu up to 0.5 at both contacts (0.3-6 m/s, 0-88
/// degrees, topspin and side spin up to 1.5 v/r) the largest was 1.25 times it; wedging
/// balls (mu above 1) ran to 4.4 times it and stalled there, or on to 1.5e7 N s.
const JAM_IMPULSE: f64 = 4.0;

/// An adaptive run that still stalls at the tightest retry with the cushion's impulse past
/// this many times the frictionless one is a jam too: wedging balls with mu_cushion 3-4.1
/// (mu_table 1.21, no spin, 3.6 m/s at 44 degrees) chatter between cloth and air, slip
/// running out and restarting at both contacts, their velocities frozen while the impulse
/// creeps on (0.006 of the frictionless one per 2,000 evaluations), and spend the step
/// budget at 2.3-2.5 times it, before [`JAM_IMPULSE`]; physical shots end below 1.25.
const STALL_JAM_IMPULSE: f64 = 1.5;

/// Most steps (accepted and rejected) of one impact.
const MAX_STEPS: u32 = 100_000;

/// Most steps of one impact where friction can lock the ball between cushion and cloth
/// ([`self_locking`]): over 3000 such impacts (mu 0.66-5 at both contacts, h in (r, 2r),
/// 0.1-6 m/s at 0-86 degrees with spin, both rules, dop853 and dopri5) those that ended took
/// at most 243 steps; those that chatter in the lock spend any budget, so a tenth of
/// [`MAX_STEPS`] (41 times the most a resolved one took) refuses them ten times sooner.
const LOCKING_MAX_STEPS: u32 = 10_000;

/// rk4's budget: at most this many steps per requested step, plus [`RK4_EVENT_STEPS`].
/// A resolved impact's impulse stays below [`JAM_IMPULSE`] times the scale, so it takes at
/// most 4 steps per requested one, and every located event cuts one step short. An rk4 run
/// with too few steps that went astray spent the whole [`MAX_STEPS`] before it was refused
/// (0.85 s at 2 steps, mu_table 1521; a 60 s timeout under the fuzzer, niced).
const RK4_STEPS_PER_STEP: u32 = 8;
/// Steps beyond [`RK4_STEPS_PER_STEP`] times the requested ones that rk4 may take for the
/// steps events cut short.
const RK4_EVENT_STEPS: u32 = 1_000;

/// Smallest step, relative to the impulse scale: below it the run fails.
const MIN_STEP: f64 = 1e-15;

/// The stepping: the scheme, its control and tolerances.
#[derive(Debug, Clone, Copy)]
struct Stepping {
    scheme: Scheme,
    control: Option<StepControl>,
    tol: Tolerance,
    method: Method,
    /// rk4 steps over the impulse scale.
    steps: u32,
}

/// The smooth events, located by regula falsi: g > 0 before, <= 0 at the event.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Smooth {
    CompressionEnd,
    RestitutionEnd,
    CushionRestart,
    TableRestart,
    LiftOff,
    TouchDown,
}

const SMOOTH: [Smooth; 6] = [
    Smooth::CompressionEnd,
    Smooth::RestitutionEnd,
    Smooth::CushionRestart,
    Smooth::TableRestart,
    Smooth::LiftOff,
    Smooth::TouchDown,
];

/// Why the stepping loop moved on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum StepEnd {
    /// A step was accepted.
    Accepted,
    /// A step was rejected (error, or a slip crossing zero inside it).
    Rejected,
    /// A smooth event was located and applied.
    Event,
    /// A slip reached zero and its contact's state was settled.
    SlipZero,
    /// The independent variable changed (a slip starts or stops running out).
    Switch,
    /// The restitution ended: the impact is over.
    Done,
}

/// The running impact.
struct Run<'a> {
    rhs: Rhs,
    stepping: Stepping,
    y: State,
    /// The state before the impact.
    y_in: State,
    p: f64,
    modes: Modes,
    phase: CushionPhase,
    e: f64,
    rule: CushionRestitution,
    vn0: f64,
    w_c: f64,
    p_c: f64,
    p_scale: f64,
    events: Vec<SlipEvent>,
    lifts_off: bool,
    stats: Stats,
    /// Physical scales: impulse m v_ref, velocity v_ref, spin v_ref / r, work m v_ref^2.
    scale_p: f64,
    scale_v: f64,
    scale_w: f64,
    trace: Option<&'a mut dyn FnMut(&CushionTraceRow)>,
    /// While the initial state is classified, zero slips are no events.
    initial: bool,
    /// The changes of state at one impulse cycled without settling ([`MAX_SETTLE`]): the
    /// contacts have no consistent state.
    inconsistent: bool,
    /// The independent variable.
    var: Var,
    /// Rate of decrease of the running-out slip when its run-out began.
    rho_entry: f64,
    /// The impulse (scaled) at which a run-out was given up because its steps fell below
    /// [`MIN_RUN_OUT_STEP`]: a slip that passes close to zero without reaching it (its rate
    /// of decrease turns within any step of -ln |slip|). The run goes on in P_I from there
    /// instead of starting the same run-out again, which cycled without end.
    run_out_abandoned: Option<f64>,
    /// Most steps of this impact ([`MAX_STEPS`], or [`LOCKING_MAX_STEPS`]).
    max_steps: u32,
    /// Next step in P_I, and in -ln |slip|.
    h_p: f64,
    h_nu: f64,
    /// A run-out ends with an Euler step over the last this much of P_I (over the impulse
    /// scale): the smaller tolerance, at most 1e-10.
    tail: f64,
    /// A falling slip at most this (scaled) is zero: ten times the smaller tolerance.
    slip_resolution: f64,
    /// Events are located to this much of P_I (scaled): [`EVENT_TOL_PER_TOL`] times the
    /// smaller tolerance, at least [`EVENT_TOL`], times the impulse scale.
    event_tol: f64,
}

/// The independent variable of the stepping.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Var {
    /// The cushion's normal impulse P_I.
    Impulse,
    /// nu = -ln |slip| of contact k (0 cushion, 1 cloth) while that slip runs out to zero:
    /// its direction turns ever faster in P_I but smoothly in nu (docs/cushion.md).
    RunOut(usize),
    /// nu = ln |slip| of contact k while its slip grows from zero after a restart or a
    /// reversal: stiff in P_I (its direction relaxes at a rate mu / |slip|), smooth in nu.
    RunIn(usize),
}

fn norm2(a: [f64; 2]) -> f64 {
    // Not hypot: the scaled slips are of order 1, and libm's hypot was a quarter of the time.
    (a[0] * a[0] + a[1] * a[1]).sqrt()
}

fn vector_text(v: &Vector3<f64>) -> String {
    format!("[{}, {}, {}]", v.x, v.y, v.z)
}

/// Resolves the impact of a ball on a cushion (Mathavan, Jackson and Parkin 2010): the
/// ball's velocity `v` (m/s) and spin `w` (rad/s) in the cushion's frame (x along the
/// cushion, y towards it, z up) before the impact, and after it in the outcome, with the
/// impulses, works and slip events (docs/cushion.md).
///
/// The ball must be on the cloth (v_z = 0: a ball in the air is not modelled) and moving
/// towards the cushion (v_y > 0); the cushion's contact height must lie between r and 2r.
/// The impact is stepped in the cushion's normal impulse by `settings.method()` (`rk4`,
/// `dopri5` or `dop853`; there is no closed form: the slip directions turn), with
/// `settings.rtol()` and `settings.atol()` on the state scaled by m, r and
/// v_ref = |v| + r |w|, or `settings.steps()` rk4 steps over the impulse scale
/// (1 + e) m v_n / cos^2 theta. `trace` receives a row at the start, after each accepted
/// step, at each event and at the end.
///
/// ```
/// use billiard_contact::nalgebra::Vector3;
/// use billiard_contact::*;
///
/// let ball = Ball::new(0.17, 0.028575, 0.4)?;
/// // Frictionless cushion and cloth: the normal force along -(0, cos theta, sin theta) and
/// // the cloth's reaction keep v_z = 0, so only v_y changes, by dv_y = -cos theta dP / m;
/// // the normal velocity v_y cos theta goes from +v_n to -e v_n under either rule (the
/// // works of compression and restitution are m v_n^2 / (2 cos^2 theta) and e^2 that).
/// let cushion = Cushion::new(0.04, 0.0, 0.0, 0.9, CushionRestitution::Stronge)?;
/// let v = Vector3::new(0.7, 2.0, 0.0);
/// let w = Vector3::new(-10.0, 30.0, 5.0);
/// let out = resolve_cushion(&ball, &cushion, v, w, &SolverSettings::default(), None)?;
/// assert!((out.v - Vector3::new(0.7, -1.8, 0.0)).norm() < 1e-10);
/// assert!((out.w - w).norm() < 1e-9);
/// // The total impulse m (1 + e) v_y / cos theta, sin theta = (h - r) / r.
/// let sin: f64 = (0.04 - 0.028575) / 0.028575;
/// let p = 0.17 * 1.9 * 2.0 / (1.0 - sin * sin).sqrt();
/// assert!((out.impulse_cushion - p).abs() < 1e-10 * p);
/// # Ok::<(), billiard_contact::Error>(())
/// ```
///
/// An adaptive run whose steps stall (more than 100 000 of them, as happens on a few
/// impacts at some tolerances where a slip hovers about zero) is run again at a tolerance
/// a hundred times tighter, down to rtol = atol = 1e-13; the outcome's `stats` are the
/// run that succeeded. With a trace, the tolerance that succeeds is found first without it,
/// so the trace holds one run. An rk4 run that stalls where the contacts jam or have no
/// consistent state (friction far beyond a billiard table's) gives the refusal an adaptive
/// run gives.
pub fn resolve_cushion(
    ball: &Ball,
    cushion: &Cushion,
    v: Vector3<f64>,
    w: Vector3<f64>,
    settings: &SolverSettings,
    trace: Option<&mut dyn FnMut(&CushionTraceRow)>,
) -> Result<CushionOutcome, Error> {
    let mut s = *settings;
    let lock = self_locking(ball, cushion);
    loop {
        match (
            attempt(ball, cushion, v, w, &s, None),
            stall_retry(&s),
            lock,
        ) {
            // Where friction can lock the ball between cushion and cloth, a stall is the
            // lock's chatter: tighter tolerances only spend more steps on it.
            // A step size underflow there is the same chatter (dop853 at mu 2.9 and 8.21 with
            // the ball at 2.8e8 m/s went to NaN; found by fuzzing).
            (
                Err(
                    Error::TooManySteps { scaled_time, .. }
                    | Error::StepSizeTooSmall { scaled_time, .. },
                ),
                _,
                Some(lock),
            ) if s.method() != Method::Rk4 => {
                return Err(lock_refusal(cushion, lock, scaled_time));
            }
            (Err(Error::TooManySteps { .. }), Some(tighter), _) => s = tighter,
            (Err(Error::TooManySteps { scaled_time, .. }), None, _)
                if s.method() != Method::Rk4 && scaled_time > STALL_JAM_IMPULSE =>
            {
                return Err(jam_refusal(cushion, &format!("{scaled_time:.2}")));
            }
            // Too few rk4 steps can go astray (a non-finite state, an impulse run past the
            // jam bound, a negative work or impulse, or its step budget spent) where an
            // adaptive run resolves the impact: the step count is what is wrong. Where the
            // adaptive run finds that the contacts jam, lock or have no consistent state,
            // that refusal is the answer.
            (
                Err(
                    e @ (Error::NonFinite { .. }
                    | Error::InvalidParameter { .. }
                    | Error::StepSizeTooSmall { .. }
                    | Error::TooManySteps { .. }),
                ),
                _,
                _,
            ) if s.method() == Method::Rk4 => {
                return Err(rk4_astray(ball, cushion, v, w, &s, e.to_string()).unwrap_or(e));
            }
            (Ok(out), _, _) => {
                if s.method() == Method::Rk4 {
                    if let Some(cause) =
                        negative_part(&out).or_else(|| energy_made(ball, cushion, v, w, &out))
                    {
                        return Err(
                            rk4_astray(ball, cushion, v, w, &s, cause).unwrap_or_else(|f| f)
                        );
                    }
                }
                return match trace {
                    None => Ok(out),
                    Some(_) => attempt(ball, cushion, v, w, &s, trace),
                };
            }
            (Err(e), _, _) => return Err(e),
        }
    }
}

/// The first impulse or work of `out` that is negative (`name = value`), or `None`: each is
/// the integral of a force that is never negative on a motion that keeps its sign.
fn negative_part(out: &CushionOutcome) -> Option<String> {
    [
        ("impulse_cushion", out.impulse_cushion),
        ("impulse_compression", out.impulse_compression),
        ("impulse_table", out.impulse_table),
        ("work_compression", out.work_compression),
        ("work_restitution", out.work_restitution),
    ]
    .into_iter()
    .find(|(_, x)| x.is_nan() || *x < 0.0)
    .map(|(name, x)| format!("{name} = {x}"))
}

/// Under Stronge's rule the impact cannot make kinetic energy: `energy_lost = value J of
/// value J brought in` where it made more than [`RK4_ENERGY_SLACK`] of it, else `None`.
/// Too few rk4 steps can: a ball at 7.4 m/s spinning at 300 rad/s lost -31,849 J of 7.5 J
/// at one step and -0.65 J at 8 to 20 (1.0757 J at 100, 1.0754 J at 1000 and with dop853;
/// found by fuzzing the Python package).
fn energy_made(
    ball: &Ball,
    cushion: &Cushion,
    v: Vector3<f64>,
    w: Vector3<f64>,
    out: &CushionOutcome,
) -> Option<String> {
    let brought = kinetic_energy(ball, &v, &w);
    (cushion.rule() == CushionRestitution::Stronge && out.energy_lost < -RK4_ENERGY_SLACK * brought)
        .then(|| {
            format!(
                "energy_lost = {:e} J of {brought:e} J brought in",
                out.energy_lost
            )
        })
}

/// The kinetic energy (as a fraction of what the ball brings in) an rk4 run may make under
/// Stronge's rule before its step count is refused ([`energy_made`]).
const RK4_ENERGY_SLACK: f64 = 1e-6;

/// The error for an rk4 run that went astray (`cause`): the step count, refused, when
/// dop853 resolves the same impact, or dop853's refusal when it refuses; dop853's failure
/// as `Err` when it fails too.
fn rk4_astray(
    ball: &Ball,
    cushion: &Cushion,
    v: Vector3<f64>,
    w: Vector3<f64>,
    s: &SolverSettings,
    cause: String,
) -> Result<Error, Error> {
    let probe = SolverSettings::default().with_method(Method::Dop853);
    match resolve_cushion(ball, cushion, v, w, &probe, None) {
        Ok(_) => Ok(Error::invalid(
            "solver.steps",
            s.steps(),
            format!(
                "enough rk4 steps to follow this impact: with these it went astray \
                 (\"{cause}\"), where dop853 resolves it"
            ),
        )),
        Err(refusal) if refusal.is_bad_input() => Ok(refusal),
        Err(failure) => Err(failure),
    }
}

/// The tightest relative tolerance a stalled adaptive run is retried at.
pub(crate) const STALL_RETRY_TIGHTEST: f64 = 1e-13;

/// The settings a stalled run is retried with: an adaptive method's tolerances a hundred
/// times tighter (not past [`STALL_RETRY_TIGHTEST`]); `None` for rk4 or when the
/// tolerances are already that tight.
fn stall_retry(s: &SolverSettings) -> Option<SolverSettings> {
    if s.method() == Method::Rk4 || s.rtol() <= STALL_RETRY_TIGHTEST {
        return None;
    }
    let rtol = (s.rtol() * 1e-2).max(STALL_RETRY_TIGHTEST);
    let atol = (s.atol() * 1e-2).max(STALL_RETRY_TIGHTEST);
    s.with_rtol(rtol).and_then(|t| t.with_atol(atol)).ok()
}

/// The refusal of a wedged ball: the cushion's impulse passed `times` the frictionless one
/// without the ball leaving the cushion.
/// The friction above which the ball can lock between cushion and cloth, when both
/// coefficients reach it: `Some(cos theta / (1 + sin theta))`, else `None`. A rigid ball
/// held at two points carries, without torque about its centre, only forces along the chord
/// between them; the chord from the cloth's point (0, 0, -r) to the cushion's
/// r (0, cos theta, sin theta) makes the angle (90 degrees - theta) / 2 with either
/// contact's normal, so both friction cones hold it when mu >= tan(45 degrees - theta / 2)
/// = cos theta / (1 + sin theta) at both (0.65 at h = 7r/5).
fn self_locking(ball: &Ball, cushion: &Cushion) -> Option<f64> {
    let r = ball.radius();
    let sin = (cushion.height() - r) / r;
    let lock = (1.0 - sin * sin).sqrt() / (1.0 + sin);
    (cushion.mu_cushion() >= lock && cushion.mu_table() >= lock).then_some(lock)
}

/// The refusal of a run that stalled where friction can lock the ball.
fn lock_refusal(cushion: &Cushion, lock: f64, scaled_time: f64) -> Error {
    let stalled = if scaled_time.is_finite() {
        format!("its run stalled at {scaled_time:.2} times the frictionless impulse")
    } else {
        "its run's state went astray".to_string()
    };
    Error::invalid(
        "cushion.mu_cushion",
        format!(
            "{} (with cushion.mu_table = {})",
            cushion.mu_cushion(),
            cushion.mu_table()
        ),
        format!(
            "friction below cos theta / (1 + sin theta) = {lock:.3} at one contact at least: \
             with both at or above it the rigid ball can lock between cushion and cloth, and \
             this one chattered there ({stalled}); billiard cushions and cloths have mu of \
             about 0.1 to 0.3"
        ),
    )
}

fn jam_refusal(cushion: &Cushion, times: &str) -> Error {
    jam_refusal_of(cushion.mu_cushion(), cushion.mu_table(), times)
}

fn jam_refusal_of(mu_cushion: f64, mu_table: f64, times: &str) -> Error {
    Error::invalid(
        "cushion.mu_cushion",
        format!("{mu_cushion} (with cushion.mu_table = {mu_table})"),
        format!(
            "friction small enough for the ball to leave the cushion: with this much the \
             rigid ball wedges between cushion and cloth (the cushion's impulse passed \
             {times} times the frictionless one); billiard cushions and cloths have mu of \
             about 0.1 to 0.3"
        ),
    )
}

/// One run of [`resolve_cushion`] with `settings` as given.
fn attempt(
    ball: &Ball,
    cushion: &Cushion,
    v: Vector3<f64>,
    w: Vector3<f64>,
    settings: &SolverSettings,
    trace: Option<&mut dyn FnMut(&CushionTraceRow)>,
) -> Result<CushionOutcome, Error> {
    let (m, r) = (ball.mass(), ball.radius());
    if !v.iter().all(|x| x.is_finite()) {
        return Err(Error::invalid(
            "ball.v",
            vector_text(&v),
            "finite numbers (m/s)",
        ));
    }
    if !w.iter().all(|x| x.is_finite()) {
        return Err(Error::invalid(
            "ball.w",
            vector_text(&w),
            "finite numbers (rad/s)",
        ));
    }
    // Finite velocities and spins whose energy overflows end in NaN (a ball of radius
    // 1.2e21 m spinning at 7.7e307 rad/s: found by the Python target).
    energy_in(&[(ball, &v, &w, "ball.v", "ball.w")])?;
    let h = cushion.height();
    if !(h > r && h < 2.0 * r) {
        return Err(Error::invalid(
            "cushion.height",
            h,
            format!(
                "in (r, 2r) = ({r}, {}) m: the contact above the ball's centre and below its top",
                2.0 * r
            ),
        ));
    }
    check_stepped_alpha(
        "ball.alpha",
        ball,
        "against a cushion",
        "the contacts' slips change 1/alpha times faster than the ball's velocity",
    )?;
    if v.y <= 0.0 {
        return Err(Error::invalid(
            "ball.v",
            vector_text(&v),
            "v_y > 0 (m/s): the ball must move towards the cushion (y points into it)",
        ));
    }
    if v.z != 0.0 {
        return Err(Error::invalid(
            "ball.v",
            vector_text(&v),
            "v_z = 0: the ball on the cloth (a ball in the air, a jump shot, is not modelled)",
        ));
    }
    let stepping = stepping_of(settings)?;
    let s = (h - r) / r;
    let c = (1.0 - s * s).sqrt();
    let rhs = Rhs {
        c,
        s,
        inv_alpha: 1.0 / ball.alpha(),
        mu_i: cushion.mu_cushion(),
        mu_c: cushion.mu_table(),
    };
    let v_ref = v.norm() + r * w.norm();
    let mut y: State = [0.0; 8];
    for i in 0..3 {
        y[i] = v[i] / v_ref;
        y[i + 3] = w[i] * r / v_ref;
    }
    let e = cushion.restitution();
    let vn0 = normal_velocity(&rhs, &y);
    let p_scale = (1.0 + e) * vn0 / (c * c);
    let mut run = Run {
        rhs,
        stepping,
        y,
        y_in: y,
        p: 0.0,
        modes: Modes {
            cushion: Friction::Sliding {
                seed: [1.0, 0.0],
                origin: [0.0, 0.0],
                floor: 0.0,
            },
            table: Friction::Sliding {
                seed: [1.0, 0.0],
                origin: [0.0, 0.0],
                floor: 0.0,
            },
            airborne: false,
        },
        phase: CushionPhase::Compression,
        e,
        rule: cushion.rule(),
        vn0,
        w_c: 0.0,
        p_c: 0.0,
        p_scale,
        events: Vec::new(),
        lifts_off: false,
        stats: Stats::default(),
        scale_p: m * v_ref,
        scale_v: v_ref,
        scale_w: v_ref / r,
        trace,
        initial: true,
        inconsistent: false,
        max_steps: {
            let budget = if self_locking(ball, cushion).is_some() {
                LOCKING_MAX_STEPS
            } else {
                MAX_STEPS
            };
            match stepping.scheme {
                Scheme::Rk4 => budget.min(
                    stepping
                        .steps
                        .saturating_mul(RK4_STEPS_PER_STEP)
                        .saturating_add(RK4_EVENT_STEPS),
                ),
                _ => budget,
            }
        },
        var: Var::Impulse,
        rho_entry: 0.0,
        run_out_abandoned: None,
        h_p: 0.0,
        h_nu: 0.0,
        tail: settings.rtol().min(settings.atol()).min(TAIL_MAX),
        slip_resolution: SLIP_RESOLUTION * settings.rtol().min(settings.atol()),
        event_tol: p_scale
            * match stepping.control {
                Some(_) => {
                    (EVENT_TOL_PER_TOL * settings.rtol().min(settings.atol())).max(EVENT_TOL)
                }
                None => EVENT_TOL,
            },
    };
    let zero = [
        rhs.mu_i > 0.0 && norm2(slip_cushion(&rhs, &run.y)) <= SLIP_ZERO,
        rhs.mu_c > 0.0 && norm2(slip_table(&run.y)) <= SLIP_ZERO,
    ];
    run.settle(zero);
    run.initial = false;
    run.row();
    run.integrate()?;
    run.row();
    run.outcome(ball)
}

fn stepping_of(settings: &SolverSettings) -> Result<Stepping, Error> {
    let tol = Tolerance {
        rtol: settings.rtol(),
        atol: settings.atol(),
    };
    let (scheme, control) = match settings.method() {
        Method::ClosedForm => {
            return Err(Error::invalid(
                "solver.method",
                "closed-form",
                "rk4, dopri5 or dop853: the cushion impact has no closed form (the slip \
                 directions turn)",
            ))
        }
        Method::Rk4 => (Scheme::Rk4, None),
        Method::Dopri5 => (Scheme::Dopri5, Some(DOPRI5_CONTROL)),
        Method::Dop853 => (Scheme::Dop853, Some(DOP853_CONTROL)),
    };
    Ok(Stepping {
        scheme,
        control,
        tol,
        method: settings.method(),
        steps: settings.steps(),
    })
}

/// Kinetic energy of the scaled state (m = r = 1).
fn kinetic(y: &State, alpha: f64) -> f64 {
    let v2 = y[0] * y[0] + y[1] * y[1] + y[2] * y[2];
    let w2 = y[3] * y[3] + y[4] * y[4] + y[5] * y[5];
    0.5 * (v2 + alpha * w2)
}

fn slip_of(rhs: &Rhs, y: &[f64], k: usize) -> [f64; 2] {
    let mut s: State = [0.0; 8];
    s.copy_from_slice(&y[..8]);
    if k == 0 {
        slip_cushion(rhs, &s)
    } else {
        slip_table(&s)
    }
}

fn contact_of(k: usize) -> CushionContact {
    if k == 0 {
        CushionContact::Cushion
    } else {
        CushionContact::Table
    }
}

fn friction_of(modes: &Modes, k: usize) -> Friction {
    if k == 0 {
        modes.cushion
    } else {
        modes.table
    }
}

fn set_friction(modes: &mut Modes, k: usize, f: Friction) {
    if k == 0 {
        modes.cushion = f;
    } else {
        modes.table = f;
    }
}

/// Whether contact `k` slides (the cloth only while the ball is on it).
/// A contact without friction has no slip events.
fn sliding(rhs: &Rhs, modes: &Modes, k: usize) -> bool {
    let mu = if k == 0 { rhs.mu_i } else { rhs.mu_c };
    mu > 0.0
        && matches!(friction_of(modes, k), Friction::Sliding { .. })
        && !(k == 1 && modes.airborne)
}

/// The seed's floor of a sliding contact `k` (0 when stuck).
fn floor_of(modes: &Modes, k: usize) -> f64 {
    match friction_of(modes, k) {
        Friction::Sliding { floor, .. } => floor,
        Friction::Stuck | Friction::Fixed(_) => 0.0,
    }
}

/// The slip of contact `k` measured from its origin (sliding), or the slip (stuck).
fn relative_slip(rhs: &Rhs, modes: &Modes, y: &[f64], k: usize) -> [f64; 2] {
    let s = slip_of(rhs, y, k);
    match friction_of(modes, k) {
        Friction::Sliding { origin, .. } => [s[0] - origin[0], s[1] - origin[1]],
        Friction::Stuck | Friction::Fixed(_) => s,
    }
}

/// |slip| of contact `k` and its rate of decrease in P_I, from the state `z` and its
/// derivative `dz` in any variable.
fn slip_and_rate(rhs: &Rhs, modes: &Modes, z: &Z, dz: &Z, k: usize) -> (f64, f64) {
    let s = relative_slip(rhs, modes, z, k);
    let sig = norm2(s);
    let r = slip_of(rhs, dz, k);
    let rho = -(s[0] * r[0] + s[1] * r[1]) / (sig * dz[DIM - 1]);
    (sig, rho)
}

/// The derivative of the stepped state in the variable `var`, and the forces.
fn deriv(rhs: &Rhs, modes: &Modes, var: Var, z: &Z) -> (Z, Eval) {
    let mut y: State = [0.0; 8];
    y.copy_from_slice(&z[..8]);
    let e = rhs.eval(modes, &y);
    let q = match var {
        Var::Impulse => 1.0,
        Var::RunOut(k) | Var::RunIn(k) => {
            // dP/dnu = |s| / rho, nu = -ln |s| (run-out: rho = -d|s|/dP) or ln |s| (run-in:
            // rho = d|s|/dP).
            let s = relative_slip(rhs, modes, z, k);
            let sig = norm2(s);
            let r = slip_of(rhs, &e.dy, k);
            let sign = if matches!(var, Var::RunOut(_)) {
                -1.0
            } else {
                1.0
            };
            let rho = sign * (s[0] * r[0] + s[1] * r[1]) / sig;
            if rho > 0.0 {
                sig / rho
            } else {
                f64::NAN
            }
        }
    };
    let mut dz = [0.0; DIM];
    for (d, x) in dz.iter_mut().zip(&e.dy) {
        *d = x * q;
    }
    dz[DIM - 1] = q;
    (dz, e)
}

/// The forces the event functions of sliding contacts use, from a derivative in any
/// variable: the cloth's normal rate dP_C/dP_I (the friction is not needed).
fn forces_from(dz: &Z) -> Eval {
    let q = dz[DIM - 1];
    let mut dy = [0.0; 8];
    for (d, x) in dy.iter_mut().zip(dz) {
        *d = x / q;
    }
    Eval {
        dy,
        f_i: [0.0; 2],
        f_c: [0.0; 2],
        n_c: dy[PC],
    }
}

/// Forces for the event functions that do not use them (the phases' ends).
fn rhs_free_eval() -> Eval {
    Eval {
        dy: [0.0; 8],
        f_i: [0.0; 2],
        f_c: [0.0; 2],
        n_c: 0.0,
    }
}

impl Run<'_> {
    fn z(&self) -> Z {
        let mut z = [0.0; DIM];
        z[..8].copy_from_slice(&self.y);
        z[DIM - 1] = self.p;
        z
    }

    fn set_z(&mut self, z: &Z) {
        self.y.copy_from_slice(&z[..8]);
        self.p = z[DIM - 1];
    }

    fn eval(&mut self, modes: &Modes, y: &State) -> Eval {
        self.stats.rhs_evaluations += 1;
        self.rhs.eval(modes, y)
    }

    fn event(&mut self, k: usize, kind: SlipChange) {
        if self.initial && matches!(kind, SlipChange::Sticks | SlipChange::Reverses) {
            return;
        }
        if kind == SlipChange::LiftsOff {
            self.lifts_off = true;
        }
        self.events.push(SlipEvent {
            contact: contact_of(k),
            kind,
            impulse: self.p * self.scale_p,
        });
    }

    /// The event function of `ev` at `z` (with its forces `e`), or None when inactive.
    fn smooth_value(&self, ev: Smooth, z: &Z, e: &Eval) -> Option<f64> {
        let m = &self.modes;
        let vn = self.rhs.c * z[1] + self.rhs.s * z[2];
        match ev {
            Smooth::CompressionEnd => (self.phase == CushionPhase::Compression).then_some(vn),
            Smooth::RestitutionEnd => {
                (self.phase == CushionPhase::Restitution).then(|| match self.rule {
                    CushionRestitution::Stronge => z[WORK] - (1.0 - self.e * self.e) * self.w_c,
                    CushionRestitution::Newton => vn + self.e * self.vn0,
                })
            }
            Smooth::CushionRestart => {
                (m.cushion == Friction::Stuck).then(|| self.rhs.mu_i - norm2(e.f_i))
            }
            Smooth::TableRestart => (m.table == Friction::Stuck && !m.airborne)
                .then(|| self.rhs.mu_c * e.n_c - norm2(e.f_c)),
            Smooth::LiftOff => (!m.airborne).then_some(e.n_c),
            Smooth::TouchDown => m.airborne.then_some(z[2]),
        }
    }

    /// Steps to the end of the impact.
    fn integrate(&mut self) -> Result<(), Error> {
        let st = self.stepping;
        self.h_p = match st.control {
            Some(c) => self.p_scale * st.tol.rtol.powf(c.exponent).min(0.1),
            None => self.p_scale / f64::from(st.steps),
        };
        let (mut k0, mut e0) = deriv(&self.rhs, &self.modes, self.var, &self.z());
        self.stats.rhs_evaluations += 1;
        for _ in 0..self.max_steps {
            if self.inconsistent {
                return Err(self.no_consistent_state());
            }
            if self.p > JAM_IMPULSE * self.p_scale {
                return Err(self.jammed());
            }
            match self.one_step(&mut k0, &mut e0)? {
                StepEnd::Done => return Ok(()),
                StepEnd::Accepted | StepEnd::Rejected => {}
                StepEnd::Event | StepEnd::SlipZero | StepEnd::Switch => {
                    (k0, e0) = deriv(&self.rhs, &self.modes, self.var, &self.z());
                    self.stats.rhs_evaluations += 1;
                }
            }
        }
        Err(Error::TooManySteps {
            method: st.method,
            scaled_time: self.p / self.p_scale,
            segment_start: 0.0,
            steps: self.max_steps,
        })
    }

    /// Starts the run-out of contact `k`'s slip, decreasing at `rho`.
    fn start_run_out(&mut self, k: usize, rho: f64) {
        self.var = Var::RunOut(k);
        self.rho_entry = rho;
        self.h_nu = match self.stepping.control {
            Some(_) => RUN_OUT_FIRST_STEP,
            None => RK4_RUN_OUT_SPAN / f64::from(self.stepping.steps),
        };
    }

    /// One step from the current state, whose derivative is `k0`.
    fn one_step(&mut self, k0: &mut Z, e0: &mut Eval) -> Result<StepEnd, Error> {
        let st = self.stepping;
        let (modes, var, rhs) = (self.modes, self.var, self.rhs);
        let z0 = self.z();
        let tol_p = self.event_tol;
        // A phase's end reached by a step that located something else (a slip's run-out
        // ending within the event tolerance of it).
        let here = *e0;
        for ev in [Smooth::CompressionEnd, Smooth::RestitutionEnd] {
            if self.smooth_value(ev, &z0, &here).is_some_and(|g| g <= 0.0) {
                let done = self.apply(ev);
                self.row();
                return Ok(if done { StepEnd::Done } else { StepEnd::Event });
            }
        }
        // The sliding contacts: the distance in P_I to their predicted stop.
        let mut stop = [f64::INFINITY; 2];
        let mut rho = [0.0; 2];
        let mut sig = [0.0; 2];
        for k in 0..2 {
            if sliding(&rhs, &modes, k) {
                let (s, r) = slip_and_rate(&rhs, &modes, &z0, k0, k);
                sig[k] = s;
                rho[k] = r;
                if s > floor_of(&modes, k).max(DIRECTION_FLOOR) && r > 0.0 {
                    stop[k] = s / r;
                }
            }
        }
        let h_try = match var {
            Var::Impulse => {
                // A slip the tolerance cannot resolve, and falling, is zero: stepped on,
                // its direction would chatter (each step flipping the friction).
                let res = self.slip_resolution;
                let zero = [
                    stop[0] <= tol_p || (stop[0].is_finite() && sig[0] <= res),
                    stop[1] <= tol_p || (stop[1].is_finite() && sig[1] <= res),
                ];
                if zero[0] || zero[1] {
                    self.settle(zero);
                    self.row();
                    return Ok(StepEnd::SlipZero);
                }
                let k = if stop[0] <= stop[1] { 0 } else { 1 };
                if stop[k] < (RUN_OUT_TRIGGER * self.h_p).min(RUN_OUT_RANGE * self.p_scale)
                    && self.run_out_abandoned != Some(self.p)
                {
                    self.start_run_out(k, rho[k]);
                    return Ok(StepEnd::Switch);
                }
                // A slip growing from zero after a restart or a reversal, past its seed.
                for k in 0..2 {
                    let floor = floor_of(&modes, k);
                    if sliding(&rhs, &modes, k) && floor > 0.0 && sig[k] > floor {
                        if -rho[k] > 0.0 && sig[k] < -rho[k] * RUN_OUT_RANGE * self.p_scale {
                            self.var = Var::RunIn(k);
                            self.h_nu = match st.control {
                                Some(_) => RUN_OUT_FIRST_STEP,
                                None => RK4_RUN_OUT_SPAN / f64::from(st.steps),
                            };
                            return Ok(StepEnd::Switch);
                        }
                        self.clear_floor(k);
                    }
                }
                // Not past a falling slip's predicted stop (adaptive methods): a long step
                // at a loose tolerance could carry a slip through zero turned by less than
                // a right angle, unseen, and miss its stick (over 2000 random shots at
                // rtol 1e-3, a missed stick was an error of 8e-2 of the speed).
                match st.control {
                    Some(_) => self.h_p.min(stop[0]).min(stop[1]),
                    None => self.h_p,
                }
            }
            Var::RunOut(k) => {
                let j = 1 - k;
                if rho[k].is_nan() || rho[k] <= RUN_OUT_EXIT * self.rho_entry || stop[j] < stop[k] {
                    self.var = Var::Impulse;
                    return Ok(StepEnd::Switch);
                }
                let remaining = (stop[k] / (self.tail * self.p_scale)).ln();
                if remaining <= TAIL_SLACK {
                    // The tail: the last stop[k] of impulse in one Euler step along the
                    // slip's current direction, which has converged (docs/cushion.md).
                    let mut z = z0;
                    let q = k0[DIM - 1];
                    for i in 0..DIM {
                        z[i] += k0[i] / q * stop[k];
                    }
                    self.set_z(&z);
                    let mut zero = [false; 2];
                    zero[k] = true;
                    self.var = Var::Impulse;
                    self.settle(zero);
                    self.row();
                    return Ok(StepEnd::SlipZero);
                }
                if self.h_nu < MIN_RUN_OUT_STEP {
                    self.var = Var::Impulse;
                    self.run_out_abandoned = Some(self.p);
                    return Ok(StepEnd::Switch);
                }
                self.h_nu.min(remaining)
            }
            Var::RunIn(k) => {
                let j = 1 - k;
                let grow = -rho[k];
                if grow.is_nan()
                    || grow <= 0.0
                    || sig[k] >= grow * RUN_OUT_RANGE * self.p_scale
                    || stop[j] < self.p_scale * RUN_OUT_RANGE
                    || self.h_nu < MIN_RUN_OUT_STEP
                {
                    self.var = Var::Impulse;
                    self.clear_floor(k);
                    return Ok(StepEnd::Switch);
                }
                self.h_nu
            }
        };
        if var == Var::Impulse && h_try < MIN_STEP * self.p_scale {
            return Err(Error::StepSizeTooSmall {
                method: st.method,
                scaled_time: self.p / self.p_scale,
                segment_start: 0.0,
            });
        }
        let mut f = |z: &Z| deriv(&rhs, &modes, var, z).0;
        let stp = step(st.scheme, &mut f, &z0, k0, h_try, st.tol);
        self.stats.rhs_evaluations += stp.evals;
        let bad = !stp.err.is_finite() || stp.y.iter().any(|x| !x.is_finite());
        let too_big = st.control.is_some_and(|_| stp.err > 1.0);
        // A slip that passed zero inside the step (not predicted at its start).
        let crossed = (0..2).any(|k| {
            sliding(&rhs, &modes, k)
                && var != Var::RunOut(k)
                && var != Var::RunIn(k)
                && sig[k] > floor_of(&modes, k).max(DIRECTION_FLOOR)
                && {
                    let s0 = relative_slip(&rhs, &modes, &z0, k);
                    let s1 = relative_slip(&rhs, &modes, &stp.y, k);
                    s0[0] * s1[0] + s0[1] * s1[1] <= 0.0
                }
        });
        if bad || too_big || crossed {
            self.stats.rejected_steps += 1;
            let h_new = match st.control {
                Some(c) if too_big && !bad && !crossed => c.next(h_try, stp.err),
                _ => 0.5 * h_try,
            };
            self.set_h(var, h_new);
            return Ok(StepEnd::Rejected);
        }
        // DOPRI5's last stage is the derivative at the new state; its forces are needed
        // apart only by the restart events of a stuck contact.
        let stuck =
            modes.cushion == Friction::Stuck || (modes.table == Friction::Stuck && !modes.airborne);
        let (k1, e1) = match stp.last {
            Some(k) if !stuck => (k, forces_from(&k)),
            _ => {
                self.stats.rhs_evaluations += 1;
                deriv(&rhs, &modes, var, &stp.y)
            }
        };
        let e0_here = here;
        let mut first: Option<(Z, Smooth)> = None;
        for ev in SMOOTH {
            let (Some(g0), Some(g1)) = (
                self.smooth_value(ev, &z0, &e0_here),
                self.smooth_value(ev, &stp.y, &e1),
            ) else {
                continue;
            };
            if g0 > 0.0 && g1 <= 0.0 {
                let at = self.locate(ev, &z0, k0, (h_try, stp.y, &k1), g0, g1);
                if first.is_none_or(|(z, _)| at[DIM - 1] < z[DIM - 1]) {
                    first = Some((at, ev));
                }
            }
        }
        self.stats.accepted_steps += 1;
        // A step cut short (to the end of a run-out) does not shrink the next one.
        let h_next = match st.control {
            Some(c) => c.next(h_try, stp.err).max(if h_try < self.h_of(var) {
                self.h_of(var)
            } else {
                0.0
            }),
            None => h_try.max(self.h_of(var)),
        };
        self.set_h(var, h_next);
        if let Some((z, ev)) = first {
            self.set_z(&z);
            self.var = Var::Impulse;
            let done = self.apply(ev);
            self.row();
            return Ok(if done { StepEnd::Done } else { StepEnd::Event });
        }
        self.set_z(&stp.y);
        *k0 = k1;
        *e0 = e1;
        self.row();
        if let Var::RunOut(k) = var {
            // A run-out that stalls (the slip falls by less than half the factor e^-h the
            // step stands for: its direction chatters at a level the step cannot resolve)
            // ends: at a stop when that is within STALL_STOP of the impulse scale.
            let sig1 = norm2(relative_slip(&rhs, &modes, &stp.y, k));
            if sig1 > sig[k] * (-0.5 * h_try).exp() {
                let (s1, r1) = slip_and_rate(&rhs, &modes, &stp.y, &k1, k);
                self.var = Var::Impulse;
                if r1 > 0.0 && s1 / r1 <= STALL_STOP * self.p_scale {
                    // The tail, as at the end of a run-out.
                    let mut z = stp.y;
                    let q = k1[DIM - 1];
                    for i in 0..DIM {
                        z[i] += k1[i] / q * (s1 / r1);
                    }
                    self.set_z(&z);
                    let mut zero = [false; 2];
                    zero[k] = true;
                    self.settle(zero);
                    self.row();
                    return Ok(StepEnd::SlipZero);
                }
                return Ok(StepEnd::Switch);
            }
        }
        Ok(StepEnd::Accepted)
    }

    /// Contact `k` has left its seed for good: its slip is large enough to be followed.
    fn clear_floor(&mut self, k: usize) {
        if let Friction::Sliding { seed, origin, .. } = friction_of(&self.modes, k) {
            set_friction(
                &mut self.modes,
                k,
                Friction::Sliding {
                    seed,
                    origin,
                    floor: 0.0,
                },
            );
        }
    }

    fn h_of(&self, var: Var) -> f64 {
        match var {
            Var::Impulse => self.h_p,
            Var::RunOut(_) | Var::RunIn(_) => self.h_nu,
        }
    }

    fn set_h(&mut self, var: Var, h: f64) {
        match (var, self.stepping.control) {
            (Var::Impulse, Some(_)) => self.h_p = h,
            (Var::RunOut(_) | Var::RunIn(_), Some(_)) => self.h_nu = h,
            // rk4 keeps its step but for the retries of a rejected one.
            (Var::Impulse, None) => {
                self.h_p = if h < self.h_p {
                    h
                } else {
                    self.p_scale / f64::from(self.stepping.steps)
                }
            }
            (Var::RunOut(_) | Var::RunIn(_), None) => {
                self.h_nu = if h < self.h_nu {
                    h
                } else {
                    RK4_RUN_OUT_SPAN / f64::from(self.stepping.steps)
                }
            }
        }
    }

    /// The state where the event function of `ev` reaches zero inside the step from `z0`
    /// (derivative `k0`) of size `h` to `z1`: regula falsi with the Illinois modification
    /// on the step size, each trial one step from `z0`, until the bracket is narrower than
    /// the event tolerance in P_I.
    fn locate(
        &mut self,
        ev: Smooth,
        z0: &Z,
        k0: &Z,
        (h, z1, k1): (f64, Z, &Z),
        g0: f64,
        g1: f64,
    ) -> Z {
        let st = self.stepping;
        // The phases' ends depend on the state alone: their first trial is the zero of g on
        // the cubic Hermite interpolant of the step (no evaluations), close enough that the
        // secant steps that follow converge in one or two trials.
        let mut guess = None;
        if matches!(ev, Smooth::CompressionEnd | Smooth::RestitutionEnd) {
            let e = rhs_free_eval();
            let at = |theta: f64| {
                let (t2, t3) = (theta * theta, theta * theta * theta);
                let (h00, h10) = (2.0 * t3 - 3.0 * t2 + 1.0, t3 - 2.0 * t2 + theta);
                let (h01, h11) = (-2.0 * t3 + 3.0 * t2, t3 - t2);
                let mut z = [0.0; DIM];
                for i in 0..DIM {
                    z[i] = h00 * z0[i] + h10 * h * k0[i] + h01 * z1[i] + h11 * h * k1[i];
                }
                z
            };
            let (mut a, mut b) = (0.0, 1.0);
            for _ in 0..HERMITE_BISECTIONS {
                let m = 0.5 * (a + b);
                if self.smooth_value(ev, &at(m), &e).unwrap_or(0.0) > 0.0 {
                    a = m;
                } else {
                    b = m;
                }
            }
            guess = Some(0.5 * (a + b) * h);
        }
        let (modes, var, rhs) = (self.modes, self.var, self.rhs);
        let mut f = |z: &Z| deriv(&rhs, &modes, var, z).0;
        let (mut lo, mut lo_g, mut lo_p) = (0.0, g0, z0[DIM - 1]);
        let (mut hi, mut hi_g, mut hi_z) = (h, g1, z1);
        let tol_p = self.event_tol;
        // |g| at which the event is located: g's range over the step times the event
        // tolerance over the step's span in P_I (the zero is then within about tol_p), not
        // below its round-off level.
        let span = (z1[DIM - 1] - z0[DIM - 1]).max(f64::MIN_POSITIVE);
        let g_tol = (g0 - g1) * G_TOL.max(tol_p / span);
        let phase_end = matches!(ev, Smooth::CompressionEnd | Smooth::RestitutionEnd);
        let mut side = 0i8;
        for _ in 0..MAX_TRIALS {
            if hi_z[DIM - 1] - lo_p <= tol_p || -hi_g <= g_tol {
                break;
            }
            let mut t = match guess.take() {
                Some(t) => t,
                None => lo + (hi - lo) * (lo_g / (lo_g - hi_g)),
            };
            if !(t > lo && t < hi) {
                t = 0.5 * (lo + hi);
            }
            let s = step(st.scheme, &mut f, z0, k0, t, st.tol);
            self.stats.rhs_evaluations += s.evals;
            let g = if phase_end {
                // The phases' ends depend on the state alone; the derivative there (the
                // step's last stage for dopri5) gives the next trial by Newton's method.
                let g = self.smooth_value(ev, &s.y, &rhs_free_eval()).unwrap_or(0.0);
                let d = match s.last {
                    Some(d) => d,
                    None => {
                        self.stats.rhs_evaluations += 1;
                        f(&s.y)
                    }
                };
                let slope = self.phase_slope(ev, &d);
                if slope < 0.0 {
                    guess = Some(t - g / slope);
                }
                g
            } else {
                let mut y = [0.0; 8];
                y.copy_from_slice(&s.y[..8]);
                self.stats.rhs_evaluations += 1;
                let e = rhs.eval(&modes, &y);
                self.smooth_value(ev, &s.y, &e).unwrap_or(0.0)
            };
            if g > 0.0 {
                if g <= g_tol {
                    return s.y;
                }
                lo = t;
                lo_g = g;
                lo_p = s.y[DIM - 1];
                if side == 1 {
                    hi_g *= 0.5;
                }
                side = 1;
            } else {
                hi = t;
                hi_g = g;
                hi_z = s.y;
                if side == -1 {
                    lo_g *= 0.5;
                }
                side = -1;
            }
        }
        hi_z
    }

    /// The derivative of a phase's end function (CompressionEnd, RestitutionEnd) along
    /// the derivative `d` of the stepped state.
    fn phase_slope(&self, ev: Smooth, d: &Z) -> f64 {
        let dvn = self.rhs.c * d[1] + self.rhs.s * d[2];
        match (ev, self.rule) {
            (Smooth::RestitutionEnd, CushionRestitution::Stronge) => d[WORK],
            _ => dvn,
        }
    }

    /// Applies the located event `ev`; true when the impact is over.
    fn apply(&mut self, ev: Smooth) -> bool {
        match ev {
            Smooth::CompressionEnd => {
                self.phase = CushionPhase::Restitution;
                self.p_c = self.p;
                self.w_c = self.y[WORK];
                if self.e == 0.0 {
                    return true;
                }
            }
            Smooth::RestitutionEnd => return true,
            Smooth::CushionRestart => self.restart(0, SlipChange::Restarts),
            Smooth::TableRestart => self.restart(1, SlipChange::Restarts),
            Smooth::LiftOff => {
                self.modes.airborne = true;
                self.event(1, SlipChange::LiftsOff);
            }
            Smooth::TouchDown => {
                self.touch_down();
                let zero = self.rhs.mu_c > 0.0 && norm2(slip_table(&self.y)) <= SLIP_ZERO;
                self.settle([false, zero]);
                return false;
            }
        }
        self.settle([false, false]);
        false
    }

    fn touch_down(&mut self) {
        self.modes.airborne = false;
        self.y[2] = 0.0;
        self.modes.table = Friction::Sliding {
            seed: [1.0, 0.0],
            origin: [0.0, 0.0],
            floor: 0.0,
        };
        self.event(1, SlipChange::TouchesDown);
    }

    /// Contact `k` slides again, from stuck (`Restarts`) or through zero slip
    /// (`Reverses`): in the direction its slip takes under limiting friction, measured
    /// from the slip it has now.
    fn restart(&mut self, k: usize, kind: SlipChange) {
        let mut trial = self.modes;
        set_friction(&mut trial, k, Friction::Stuck);
        let y = self.y;
        let e = self.eval(&trial, &y);
        let f = if k == 0 { e.f_i } else { e.f_c };
        let n = norm2(f);
        // The slip starts in the direction d along which it grows under friction -mu N d,
        // near the opposite of the friction that would have kept it stuck.
        let d = if n > 0.0 {
            [-f[0] / n, -f[1] / n]
        } else {
            [1.0, 0.0]
        };
        let origin = slip_of(&self.rhs, &y, k);
        self.stats.rhs_evaluations += 3;
        let d = self.rhs.quasi_static_direction(&self.modes, &y, k, d);
        set_friction(
            &mut self.modes,
            k,
            Friction::Sliding {
                seed: d,
                origin,
                floor: SEED_FLOOR,
            },
        );
        self.event(k, kind);
    }

    /// Whether contact `k`'s friction in `e` lies within its cone.
    fn in_cone(&self, k: usize, e: &Eval) -> bool {
        if k == 0 {
            norm2(e.f_i) <= self.rhs.mu_i * (1.0 + CONE_SLACK)
        } else {
            e.n_c >= 0.0 && norm2(e.f_c) <= self.rhs.mu_c * e.n_c * (1.0 + CONE_SLACK)
        }
    }

    /// The contacts whose slip is zero (`zero`) stick or slide on; then the states are made
    /// consistent: the ball leaves the cloth or lands, stuck contacts past their cone slide.
    fn settle(&mut self, zero: [bool; 2]) {
        let mut pending = zero;
        for round in 0..=MAX_SETTLE {
            if round == MAX_SETTLE {
                self.inconsistent = true;
                break;
            }
            let mut changed = false;
            if pending[0] || pending[1] {
                self.stick_or_slide(pending);
                pending = [false, false];
                changed = true;
            }
            let (modes, y) = (self.modes, self.y);
            let e = self.eval(&modes, &y);
            if !modes.airborne && e.n_c < 0.0 {
                self.modes.airborne = true;
                self.event(1, SlipChange::LiftsOff);
                changed = true;
            } else if modes.airborne && y[2] <= 0.0 && e.n_c >= 0.0 {
                self.touch_down();
                pending[1] = self.rhs.mu_c > 0.0 && norm2(slip_table(&self.y)) <= SLIP_ZERO;
                changed = true;
            }
            if !changed {
                if modes.cushion == Friction::Stuck && !self.in_cone(0, &e) {
                    self.restart(0, SlipChange::Restarts);
                    changed = true;
                } else if modes.table == Friction::Stuck && !modes.airborne && !self.in_cone(1, &e)
                {
                    self.restart(1, SlipChange::Restarts);
                    changed = true;
                }
            }
            if !changed && !pending[1] {
                break;
            }
        }
    }

    /// The contacts in `pending` (zero slip) stick if static friction can hold them (both
    /// at once first when both are zero), else slide on in the limiting direction.
    fn stick_or_slide(&mut self, pending: [bool; 2]) {
        let y = self.y;
        let table = pending[1] && !self.modes.airborne;
        if pending[0] && table {
            let mut trial = self.modes;
            trial.cushion = Friction::Stuck;
            trial.table = Friction::Stuck;
            let e = self.eval(&trial, &y);
            if self.in_cone(0, &e) && self.in_cone(1, &e) {
                self.modes = trial;
                self.event(0, SlipChange::Sticks);
                self.event(1, SlipChange::Sticks);
                return;
            }
        }
        for (k, &zero) in pending.iter().enumerate() {
            if !zero || (k == 1 && !table) {
                continue;
            }
            let mut trial = self.modes;
            set_friction(&mut trial, k, Friction::Stuck);
            let e = self.eval(&trial, &y);
            if self.in_cone(k, &e) {
                self.modes = trial;
                self.event(k, SlipChange::Sticks);
            } else {
                self.restart(k, SlipChange::Reverses);
            }
        }
    }

    /// A trace row of the current state.
    fn row(&mut self) {
        let Some(trace) = self.trace.as_mut() else {
            return;
        };
        let y = &self.y;
        let (sv, sp) = (self.scale_v, self.scale_p);
        let si = slip_cushion(&self.rhs, y);
        let sc = slip_table(y);
        let row = CushionTraceRow {
            p_i: self.p * sp,
            p_c: y[PC] * sp,
            v: Vector3::new(y[0], y[1], y[2]) * sv,
            w: Vector3::new(y[3], y[4], y[5]) * self.scale_w,
            slip_cushion: [si[0] * sv, si[1] * sv],
            slip_table: [sc[0] * sv, sc[1] * sv],
            normal_velocity: normal_velocity(&self.rhs, y) * sv,
            work: y[WORK] * sp * sv,
            phase: self.phase,
        };
        trace(&row);
    }

    /// The outcome, in physical units.
    /// The refusal of an impact whose contacts have no consistent state: a cloth that would
    /// have to pull, or states that cycle at one impulse. Rigid contacts with friction this
    /// large have no solution (Painlevé's paradox): the cushion's friction, pushing the ball
    /// down onto the cloth while it lifts off, would have the cloth pull it back.
    fn no_consistent_state(&self) -> Error {
        Error::invalid(
            "cushion.mu_cushion",
            format!(
                "{} (with cushion.mu_table = {})",
                self.rhs.mu_i, self.rhs.mu_c
            ),
            "friction small enough for the rigid ball, cushion and cloth to have a \
             consistent state: with this much, the ball lifting off the cloth would be \
             pushed back onto it and the cloth would have to pull (Painleve's paradox of \
             rigid contacts with friction); billiard cushions and cloths have mu of about 0.1 \
             to 0.3",
        )
    }

    /// The refusal of an impact whose cushion impulse passes [`JAM_IMPULSE`] times the
    /// frictionless one: both contacts stuck with the ball no longer leaving the cushion, a
    /// rigid ball wedged between cushion and cloth by friction this large.
    fn jammed(&self) -> Error {
        jam_refusal_of(self.rhs.mu_i, self.rhs.mu_c, &JAM_IMPULSE.to_string())
    }

    fn outcome(&self, ball: &Ball) -> Result<CushionOutcome, Error> {
        if self.inconsistent || self.y[PC] < -1e-12 * self.p {
            return Err(self.no_consistent_state());
        }
        let y = &self.y;
        let (sv, sp) = (self.scale_v, self.scale_p);
        let names = ["v.x", "v.y", "v.z", "w.x", "w.y", "w.z"];
        for (i, name) in names.iter().enumerate() {
            finite_output(y[i], || format!("cushion outcome {name}"))?;
        }
        let work = sp * sv;
        Ok(CushionOutcome {
            v: Vector3::new(y[0], y[1], y[2]) * sv,
            w: Vector3::new(y[3], y[4], y[5]) * self.scale_w,
            impulse_cushion: self.p * sp,
            impulse_compression: self.p_c * sp,
            impulse_table: y[PC] * sp,
            work_compression: self.w_c * work,
            work_restitution: (self.w_c - y[WORK]) * work,
            energy_lost: (kinetic(&self.y_in, ball.alpha()) - kinetic(y, ball.alpha())) * work,
            events: self.events.clone(),
            lifts_off: self.lifts_off,
            stats: self.stats,
        })
    }
}
