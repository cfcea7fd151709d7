//! A scene with `contact.tangential = "mindlin"` (docs/tangential.md#scenes): the compliant
//! kernel run on the scene's balls, materials, law and friction, and its outcome in the
//! terms of every other run (the centre-of-mass state of the paper, or of a plane's
//! equivalent pair, docs/plane.md), so that the report, the lab motions and the table phase
//! read it unchanged; the kernel's own quantities are kept beside it.

use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::settings::{Sampling, SolverSettings, Stats};
use crate::closed_form::kernel::ClosedForm;
use crate::model::collision::Collision;
use crate::model::contact_law::ContactLaw;
use crate::model::params::{Contact, ImpulseRule};
use crate::model::state::CmState;
use crate::model::trace::{TraceRow, TraceSink};
use crate::scene::builder::TANGENTIAL_FIELD;
use crate::scene::types::{Incoming, Scene};
use crate::solve::check::checks;
use crate::solve::outcome::{LawOutcome, Outcome};
use crate::solve::plane::equivalent_state;
use crate::tangential::impact::resolve_sphere_plane_compliant_damped;
use crate::tangential::outcome::{CompliantOutcome, CompliantTraceRow};
use crate::tangential::pair::{resolve_sphere_sphere_compliant_damped, CompliantSphere};
use nalgebra::{Vector2, Vector3};

/// A stuck phase counts when it lasts longer than this fraction of the contact time. Where
/// the spring meets Coulomb's cap the kernel's steps may switch between stick and slide,
/// each switch landed to within 1e-9 of Hertz's contact time (its event resolution; near
/// first touch, steps of 1e-13 s at 1 m/s); 1e-6 is far above those and far below any phase
/// in which the spring actually holds.
const STUCK_PHASE: f64 = 1e-6;

/// The right-hand-side evaluations of one attempted step of the kernel's Dormand-Prince
/// 5(4) (seven stages, the first not reused: docs/tangential.md#stepping).
const STAGES: u64 = 7;

/// Turns a vector of the kernel's axes into the trace's frame.
type ToFrame = Box<dyn Fn(&Vector3<f64>) -> Vector3<f64>>;

/// One accepted step of a compliant run, in the frame of the run's trace (the paper's
/// centre-of-mass frame, or a plane's equivalent pair's: docs/plane.md).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompliantRow {
    /// The trace row: time, normal force, normal impulse, state, slip, the tangential work
    /// (in the sliding heat's column) and the compression.
    pub row: TraceRow,
    /// The tangential force on ball A (N): its components along the frame's y and z (the
    /// tangent plane; x is the line of centres).
    pub force: Vector2<f64>,
    /// The spring's elastic displacement xi = -F_t / k_t (m), along y and z.
    pub displacement: Vector2<f64>,
    /// Coulomb's cap mu F_n (N).
    pub cap: f64,
    /// Whether the spring slid over the step that ends here.
    pub sliding: bool,
}

/// What a compliant run adds to the outcome every run has.
#[derive(Debug, Clone, PartialEq)]
pub struct CompliantRun {
    /// The kernel's outcome as ball A sees it (lab axes of the kernel's call: the paper's
    /// frame for two balls, the scene's axes for a plane); its trace is in [`CompliantRun::rows`].
    pub outcome: CompliantOutcome,
    /// Coulomb's mu of the run (0 with the effect friction off).
    pub mu: f64,
    /// The spring's displacement xi at the last step before separation (m), along y and z
    /// of the trace's frame: what the contact leaves with (xi is kept while the contact
    /// shrinks sticking, and falls to 0 with the cap while it slides).
    pub final_displacement: Vector2<f64>,
    /// The outgoing slip along the incoming one, u'.e0 (m/s): negative when the contact
    /// point's slip reversed (0 without incoming slip).
    pub slip_out_along: f64,
    /// The tangential impulse on ball A (N s), along y and z of the trace's frame.
    pub tangential_impulse: Vector2<f64>,
    /// Every accepted step, in the trace's frame.
    pub rows: Vec<CompliantRow>,
}

impl CompliantRun {
    /// True when the contact point leaves slipping against its incoming slip.
    pub fn slip_reversed(&self) -> bool {
        self.slip_out_along < 0.0
    }
}

/// Runs the compliant kernel on `scene` (whose builder checked what Mindlin's spring
/// needs) for its collision `c`, with the rtol and atol of `settings`; sends the trace rows
/// to `trace`. `--samples` (uniform sampling) is refused: the kernel writes a row per step.
pub(crate) fn run_compliant(
    scene: &Scene,
    c: &Collision,
    settings: &SolverSettings,
    trace: Option<(&mut dyn TraceSink, Sampling)>,
) -> Result<(Outcome, CompliantRun), Error> {
    if let Some((_, Sampling::Uniform(n))) = &trace {
        return Err(Error::invalid(
            "samples",
            *n,
            format!(
                "not with {TANGENTIAL_FIELD} = \"mindlin\": its trace is a row per step of the \
                 compliant kernel (leave out the samples)"
            ),
        ));
    }
    let (law, material) = match (&scene.law, &scene.material) {
        (Some(law), Some(m)) => (*law, *m),
        _ => {
            return Err(Error::invalid(
                TANGENTIAL_FIELD,
                "\"mindlin\" without [contact.law] and the balls' material",
                "both (the scene builder checks this)",
            ))
        }
    };
    let mu = if scene.effects.friction {
        scene.contact.friction.mu(c.s0)
    } else {
        0.0
    };
    let damping = (law.damping(), law.coefficient());
    let balls = &c.balls;
    // The kernel's call, its axes and how its vectors turn into the trace's frame.
    let (kernel, out, to_frame): (CompliantOutcome, CmState, ToFrame) = match &scene.incoming {
        Incoming::Plane(p) => {
            // The scene's ball (the collision's is the equivalent pair's twin, of twice its
            // mass).
            let o = resolve_sphere_plane_compliant_damped(
                &scene.balls.a,
                material,
                p.material,
                damping,
                mu,
                p.velocity,
                p.spin,
                p.normal,
                settings,
            )?;
            let n = p.normal;
            let out = equivalent_state(&n, &o.velocity, &o.spin);
            // The equivalent pair's axes: its state holds v/2, so 2 u is the vector in
            // them.
            let turn =
                move |x: &Vector3<f64>| equivalent_state(&n, x, &Vector3::zeros()).u_cm * 2.0;
            (o, out, Box::new(turn))
        }
        _ => {
            let u = c.incoming.u_cm;
            let m = balls.pair_mass();
            let sphere = |ball, velocity, spin| CompliantSphere {
                ball,
                material,
                velocity,
                spin,
            };
            // The centre-of-mass velocities: u = (v_A - v_B) / 2, m_A v_A + m_B v_B = 0.
            let a = sphere(balls.a, u * (m / balls.a.mass()), c.incoming.omega_a);
            let b = sphere(balls.b, -u * (m / balls.b.mass()), c.incoming.omega_b);
            let o = resolve_sphere_sphere_compliant_damped(
                &a,
                &b,
                damping,
                Vector3::x(),
                mu,
                1.0,
                settings,
            )?;
            // u = g / 2 from the kernel's outgoing relative velocity (its last row's, so that
            // the trace ends on the reported state; (v_A' - v_B') / 2 differs by round-off).
            let g_out = o
                .ball_a
                .trace
                .last()
                .map_or(o.ball_a.velocity - o.velocity_b, |r| r.relative_velocity);
            let out = CmState::new(g_out / 2.0, o.ball_a.spin, o.spin_b);
            (o.ball_a, out, Box::new(|x: &Vector3<f64>| *x))
        }
    };
    let state_of = |r: &CompliantTraceRow| match &scene.incoming {
        Incoming::Plane(p) => equivalent_state(&p.normal, &r.relative_velocity, &r.spin),
        _ => CmState::new(r.relative_velocity / 2.0, r.spin, r.partner_spin),
    };
    let m = balls.pair_mass();
    let u0 = c.incoming.u_cm;
    let e0 = c.direction;
    let mut rows = Vec::with_capacity(kernel.trace.len());
    let mut drift = 0.0f64;
    for r in &kernel.trace {
        let state = state_of(r);
        let slip = state.slip_of(balls);
        if let Some(e) = e0 {
            drift = drift.max((slip.x * e.y - slip.y * e.x).abs());
        }
        let along = e0.map_or(slip.norm(), |e| slip.dot(&e));
        let (f, xi) = (to_frame(&r.tangential_force), to_frame(&r.displacement));
        rows.push(CompliantRow {
            row: TraceRow {
                t: r.time,
                force: r.normal_force,
                impulse: m * (u0.x - state.u_cm.x),
                state,
                slip_speed: along.signum() * slip.norm(),
                theta: state.theta_of(balls),
                heat_sliding: r.tangential_work,
                compression: Some(r.compression),
            },
            force: Vector2::new(f.y, f.z),
            displacement: Vector2::new(xi.y, xi.z),
            cap: mu * r.normal_force,
            sliding: r.sliding,
        });
    }
    if let Some((sink, _)) = trace {
        for r in &rows {
            sink.row(&r.row)?;
        }
    }
    let outcome = outcome_of(c, &law, &kernel, &out, &rows, drift)?;
    let slip_out = out.slip_of(balls);
    // At separation k_t = 0 and xi is written 0; while the contact shrinks sticking xi is
    // kept (the force falls with the stiffness), so the last step still in contact gives
    // the displacement the contact leaves with.
    let final_displacement = rows
        .iter()
        .rev()
        .find(|r| r.row.compression.is_some_and(|d| d > 0.0))
        .map_or(Vector2::zeros(), |r| r.displacement);
    Ok((
        outcome,
        CompliantRun {
            mu,
            final_displacement,
            slip_out_along: e0.map_or(0.0, |e| slip_out.dot(&e)),
            // M du is the impulse on A (for a plane's equivalent pair, M = 2 m and u = v/2).
            tangential_impulse: Vector2::new(m * (out.u_cm.y - u0.y), m * (out.u_cm.z - u0.z)),
            outcome: CompliantOutcome {
                trace: Vec::new(),
                ..kernel
            },
            rows,
        },
    ))
}

/// The outcome every run reports, from the kernel's `kernel` with the outgoing state `out`
/// and the trace `rows` (docs/formats.md#json-report: what the keys mean under Mindlin).
fn outcome_of(
    c: &Collision,
    law: &ContactLaw,
    kernel: &CompliantOutcome,
    out: &CmState,
    rows: &[CompliantRow],
    drift: f64,
) -> Result<Outcome, Error> {
    let m = c.balls.pair_mass();
    let u0 = c.incoming.u_cm;
    let du = out.u_cm - u0;
    let impulse = -m * du.x;
    // The realised collision: the closed form at the kernel's impulse is the rigid contact's
    // answer, the reference `closed_form_error` measures the compliance against.
    let real = Collision::new(
        c.balls,
        Contact {
            friction: c.contact.friction,
            impulse: ImpulseRule::explicit(impulse.clamp(m * u0.x, 2.0 * m * u0.x))?,
        },
        c.effects,
        c.incoming,
    )?;
    let exact = ClosedForm::new(&real);
    let e = c.direction.unwrap_or_else(Vector2::zeros);
    let j = -m * (du.y * e.x + du.z * e.y);
    let slip_out = out.slip_of(&c.balls);
    let (sticks, stick_time, stick_impulse) = stick_of(rows, kernel, c);
    let mut result = exact.result;
    result.impulse = impulse;
    result.s_out = c.direction.map_or(slip_out.norm(), |e| slip_out.dot(&e));
    result.sticks = sticks;
    result.stick_impulse = stick_impulse;
    result.tangential_impulse = j;
    result.heat = c.incoming.kinetic_energy(&c.balls) - out.kinetic_energy(&c.balls);
    result.heat_sliding = kernel.tangential_work;
    result.out = *out;
    let mut check = checks(&real, &exact, out, j, kernel.tangential_work);
    check.theta_drift = if drift == 0.0 {
        0.0
    } else {
        drift / c.scales.speed
    };
    Ok(Outcome {
        method: Method::Dopri5,
        result,
        stick_time,
        check,
        stats: Stats {
            rhs_evaluations: STAGES * (kernel.steps + kernel.rejected),
            accepted_steps: kernel.steps,
            rejected_steps: kernel.rejected,
        },
        warnings: Vec::new(),
        exact,
        law: Some(LawOutcome {
            law: *law,
            restitution: impulse / (m * u0.x) - 1.0,
            impulse,
            duration: kernel.contact_time,
            max_compression: kernel.max_compression,
            peak_force: kernel.max_normal_force,
        }),
    })
}

/// Whether the spring stuck, when (s) and at which normal impulse (N s): the start of its
/// first stuck phase (consecutive steps without sliding) longer than [`STUCK_PHASE`] of the
/// contact time; never without friction or incoming slip.
fn stick_of(
    rows: &[CompliantRow],
    kernel: &CompliantOutcome,
    c: &Collision,
) -> (bool, Option<f64>, Option<f64>) {
    if rows.iter().all(|r| r.cap == 0.0) || c.direction.is_none() {
        return (false, None, None);
    }
    let long = STUCK_PHASE * kernel.contact_time;
    let mut start: Option<usize> = None;
    for (i, r) in rows.iter().enumerate().skip(1) {
        match (r.sliding, start) {
            (false, None) => start = Some(i - 1),
            (true, Some(s)) => {
                if rows[i - 1].row.t - rows[s].row.t > long {
                    break;
                }
                start = None;
            }
            _ => {}
        }
    }
    let last = rows.last().map_or(0.0, |r| r.row.t);
    match start {
        Some(s) if last - rows[s].row.t > long => {
            (true, Some(rows[s].row.t), Some(rows[s].row.impulse))
        }
        _ => (false, None, None),
    }
}
