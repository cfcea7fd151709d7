//! Many collisions at once: one per row of a CSV file (streamed in chunks, so memory does
//! not grow with the number of rows) or of an in-memory slice, resolved in parallel over
//! rows with rayon.
//!
//! The balls, friction, impulse rule, profile and effects come from a scene (the built-in
//! default scene when none is given); a row may override some of them. Rows carry the
//! incoming state either in the paper's centre-of-mass frame or in the lab frame.
//!
//! # Input columns
//!
//! Header names as below; a trailing unit in parentheses (`u_x (m/s)`) is ignored; column
//! order is free; empty cells are "not given". Exactly one of the two frames:
//!
//! | columns | meaning |
//! |---|---|
//! | `u_x, u_y, u_z` | centre-of-mass frame: velocity of ball A (m/s), line of centres +x, B has -u |
//! | `omega_a_x .. omega_a_z`, `omega_b_x .. omega_b_z` | spins (rad/s), optional, default 0 |
//! | `a_px, a_py, a_pz`, `b_px, b_py, b_pz` | lab frame: centres (m), touching |
//! | `a_vx, a_vy, a_vz`, `b_vx, b_vy, b_vz` | lab velocities (m/s) |
//! | `a_wx, a_wy, a_wz`, `b_wx, b_wy, b_wz` | lab spins (rad/s), optional, default 0 |
//! | `up_x, up_y, up_z` | lab `up`, optional, default (0, 0, 1) |
//!
//! Optional in both: `id` (copied to the output), and per-row overrides of the scene:
//! `mass` (kg), `radius` (m), `alpha`, `mu` (constant), `restitution` or `impulse` (N s),
//! `duration` (s; the outgoing state does not depend on it, the stick time scales with it).
//! With a scene that gives the balls' material, each row's duration is its own Hertz contact
//! time (from its mass, radius and approach speed), and a `duration` column is refused.
//! With a scene whose force comes from a contact law (`[contact.law]`), each row realises its
//! own impulse, restitution and duration; `restitution`, `impulse` and `duration` columns are
//! refused, and the stick time is the row's own (docs/contact-law.md#batch-and-sweep).
//!
//! # Output columns
//!
//! `line` (the input line), `id` (when the input has it), `collision`, `impulse` (N s),
//! `s0` (m/s), `theta` (rad, empty when S(0) = 0), `sticks`, `stick_time` (s, empty when
//! sliding does not stop), `stick_impulse` (N s, empty when undefined), `tangential_impulse`
//! (N s), `s_out` (m/s), `heat`, `heat_sliding` (J), the outgoing centre-of-mass state
//! `u_x, u_y, u_z, omega_a_x .. omega_b_z`; with lab input also `a_vx .. a_wz, b_vx .. b_wz`
//! (outgoing lab velocities and spins) and `throw_angle_deg` (empty when undefined); with
//! a time-stepping method also `closed_form_error` and `rhs_evaluations`.

use crate::contact::closed_form::ClosedFormBatch;
use crate::contact::law_outcome::solve_law;
use crate::contact::outcome::solve;
use crate::contact::result::ContactResult;
use crate::error::Error;
use crate::formats::names::did_you_mean;
use crate::formats::number::{finite_output, Shortest};
use crate::formats::scene::{Incoming, LabFrame, Scene};
use crate::integrator::{Method, SolverSettings};
use crate::model::collision::Collision;
use crate::model::contact_law::ContactLaw;
use crate::model::effects::Effects;
use crate::model::frame::LabScene;
use crate::model::material::{hertz_stiffness, HertzContact, Material, YOUNGS_MODULUS_FIELD};
use crate::model::params::{Ball, BallPair, Contact, Friction, ImpulseRule};
use crate::model::state::{CmState, LabBall, LabMotion};
use crate::profile::{ForceProfile, Profile};
use nalgebra::Vector3;
use rayon::prelude::*;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

pub use crate::apps::lab_rows::{resolve_lab_into, LabOutColumns, LabRows, PARALLEL_LAB_ROWS};

/// Rows read, resolved and written per chunk by default: the memory held at any time.
pub const DEFAULT_CHUNK_ROWS: usize = 16_384;

/// What every row shares: the scene's parameters and the method.
#[derive(Debug, Clone, PartialEq)]
pub struct BatchSetup {
    /// The balls (every row's, see [`Overrides`]).
    pub balls: BallPair,
    /// Friction and impulse rule.
    pub contact: Contact,
    /// Effects.
    pub effects: Effects,
    /// Normal-force profile (its duration is the default duration).
    pub profile: Profile,
    /// The balls' material, when the scene gives it: each row's duration is then its own
    /// Hertz contact time.
    pub material: Option<Material>,
    /// Method and tolerances.
    pub settings: SolverSettings,
    /// The scene's contact law (docs/contact-law.md), when the force comes from the
    /// compression: each row realises its own impulse and duration.
    pub law: Option<ContactLaw>,
}

impl BatchSetup {
    /// The parameters of `scene`, solved with `settings`.
    pub fn from_scene(scene: &Scene, settings: SolverSettings) -> Self {
        BatchSetup {
            balls: scene.balls,
            contact: scene.contact,
            effects: scene.effects,
            profile: scene.profile.clone(),
            material: scene.material,
            settings,
            law: scene.law,
        }
    }
}

/// Per-row overrides of the setup (`None`: the setup's value). `mass`, `radius` and `alpha`
/// change both balls of a setup of identical balls; a setup of unequal balls refuses them
/// (which ball they would change is ambiguous).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Overrides {
    /// Mass (kg).
    pub mass: Option<f64>,
    /// Radius (m).
    pub radius: Option<f64>,
    /// I = alpha m r^2.
    pub alpha: Option<f64>,
    /// Constant friction coefficient.
    pub mu: Option<f64>,
    /// Restitution e (P = (1 + e) m U(0)).
    pub restitution: Option<f64>,
    /// Explicit impulse P (N s).
    pub impulse: Option<f64>,
    /// Contact duration (s).
    pub duration: Option<f64>,
}

impl Overrides {
    fn is_empty(&self) -> bool {
        *self == Overrides::default()
    }
}

/// One collision of a batch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BatchInput {
    /// Incoming state, centre-of-mass or lab frame.
    pub incoming: Incoming,
    /// Overrides of the setup.
    pub overrides: Overrides,
}

impl BatchInput {
    /// A centre-of-mass state with the setup's parameters.
    pub fn cm(state: CmState) -> Self {
        BatchInput {
            incoming: Incoming::Cm(state),
            overrides: Overrides::default(),
        }
    }
}

/// The result of one collision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BatchOutput {
    /// Impulses, sliding, heat and the outgoing centre-of-mass state.
    pub result: ContactResult,
    /// When sliding stopped (s); `None` when it did not.
    pub stick_time: Option<f64>,
    /// Outgoing lab motions of A and B, and the throw angle (degrees), for lab input.
    pub lab: Option<(LabMotion, LabMotion, Option<f64>)>,
    /// Distance to the closed form (time stepping; 0 for the closed form).
    pub closed_form_error: f64,
    /// Right-hand-side evaluations (time stepping).
    pub rhs_evaluations: u64,
}

/// The ball and contact of a row: the setup's, or with the row's overrides.
fn params_of(setup: &BatchSetup, o: &Overrides) -> Result<(BallPair, Contact), Error> {
    if o.is_empty() {
        return Ok((setup.balls, setup.contact));
    }
    let b = setup.balls.a;
    let ball_keys = [("mass", o.mass), ("radius", o.radius), ("alpha", o.alpha)];
    let balls = match ball_keys.iter().find_map(|(k, v)| v.map(|v| (k, v))) {
        None => setup.balls,
        Some((key, value)) if !setup.balls.is_identical() => {
            return Err(Error::invalid(
                *key,
                value,
                "no mass, radius or alpha column with a scene of unequal balls ([balls.a] and \
                 [balls.b] apply to every row)",
            ))
        }
        Some(_) => BallPair::identical(Ball::new(
            o.mass.unwrap_or(b.mass()),
            o.radius.unwrap_or(b.radius()),
            o.alpha.unwrap_or(b.alpha()),
        )?),
    };
    let friction = match o.mu {
        Some(mu) => Friction::constant(mu)?,
        None => setup.contact.friction,
    };
    let impulse =
        ImpulseRule::from_either("", o.restitution, o.impulse)?.unwrap_or(setup.contact.impulse);
    if let Some(d) = o.duration {
        crate::model::params::positive("duration", d, "s")?;
    }
    Ok((balls, Contact { friction, impulse }))
}

/// The contact duration of a row (s): its `duration` column, else the Hertz contact time of
/// the setup's material for the row's balls and approach speed (balls that approach), else
/// the profile's.
fn row_duration(
    setup: &BatchSetup,
    o: &Overrides,
    balls: &BallPair,
    cm: &CmState,
) -> Result<f64, Error> {
    match (o.duration, &setup.material) {
        (Some(d), Some(m)) => Err(Error::invalid(
            "duration",
            format!(
                "{d} s together with the scene's {YOUNGS_MODULUS_FIELD} = {}",
                m.youngs_modulus()
            ),
            "one of them: with the material each row's contact time follows from its balls and \
             approach speed; leave out the column, or the material",
        )),
        (Some(d), None) => Ok(d),
        (None, Some(m)) if cm.u_cm.x > 0.0 => {
            Ok(HertzContact::of_pair(balls, m, cm.u_cm.x)?.duration)
        }
        (None, _) => Ok(setup.profile.duration()),
    }
}

/// Resolves one collision with the setup's method. The closed form
/// ([`ClosedFormBatch`]: the same numbers as [`crate::ClosedForm`]) skips the checks (they hold to
/// round-off by construction) and computes the stick time only when sliding stops.
pub fn resolve(setup: &BatchSetup, input: &BatchInput) -> Result<BatchOutput, Error> {
    resolve_with(setup, None, input)
}

/// The closed-form kernel of the setup's own parameters, when the method is the closed form.
fn shared_kernel(setup: &BatchSetup) -> Option<ClosedFormBatch> {
    (setup.settings.method() == Method::ClosedForm)
        .then(|| ClosedFormBatch::new(setup.balls, setup.contact, setup.effects))
}

/// [`resolve`] with the closed-form kernel of the setup's own parameters when the caller
/// made it once for many rows (`shared`; used for rows without overrides).
pub(crate) fn resolve_with(
    setup: &BatchSetup,
    shared: Option<&ClosedFormBatch>,
    input: &BatchInput,
) -> Result<BatchOutput, Error> {
    let (balls, contact) = params_of(setup, &input.overrides)?;
    let (cm, lab) = input.incoming.to_cm(&balls)?;
    if let Some(law) = &setup.law {
        let mut out = resolve_law(setup, law, &input.overrides, balls, contact, &cm)?;
        if let Some(LabFrame { frame, lab }) = lab {
            out.lab = Some(frame.outgoing(lab, &out.result.out, out.result.collided()));
        }
        return Ok(out);
    }
    let profile = &setup.profile;
    let time_scale = row_duration(setup, &input.overrides, &balls, &cm)?;
    let mut out = if setup.settings.method() == Method::ClosedForm {
        let own;
        let kernel = match shared {
            Some(k) if input.overrides.is_empty() => k,
            _ => {
                own = ClosedFormBatch::new(balls, contact, setup.effects);
                &own
            }
        };
        let mut result = kernel.resolve(&cm)?;
        let stick_time = result.stick_fraction(profile).map(|s| time_scale * s);
        if !result.collided() {
            result.stick_impulse = None;
        }
        BatchOutput {
            result,
            stick_time,
            lab: None,
            closed_form_error: 0.0,
            rhs_evaluations: 0,
        }
    } else {
        let c = Collision::new(balls, contact, setup.effects, cm)?;
        let o = solve(&c, profile, &setup.settings, None)?;
        BatchOutput {
            result: o.result,
            stick_time: o.stick_time.map(|t| t / profile.duration() * time_scale),
            lab: None,
            closed_form_error: o.check.closed_form_error,
            rhs_evaluations: o.stats.rhs_evaluations,
        }
    };
    if let Some(LabFrame { frame, lab }) = lab {
        out.lab = Some(frame.outgoing(lab, &out.result.out, out.result.collided()));
    }
    Ok(out)
}

/// One row under the setup's contact law: the row's restitution, impulse and duration
/// columns are refused (the law decides them); with the balls' material the stiffness
/// follows from the row's ball.
fn resolve_law(
    setup: &BatchSetup,
    law: &ContactLaw,
    o: &Overrides,
    balls: BallPair,
    contact: Contact,
    cm: &CmState,
) -> Result<BatchOutput, Error> {
    let given = [
        ("restitution", o.restitution),
        ("impulse", o.impulse),
        ("duration", o.duration),
    ];
    if let Some((column, Some(v))) = given.iter().find(|(_, v)| v.is_some()) {
        return Err(Error::invalid(
            *column,
            format!("{v} with the scene's [contact.law]"),
            "no restitution, impulse or duration column: the law decides them for every row",
        ));
    }
    let law = match &setup.material {
        Some(m) if balls != setup.balls => ContactLaw::new(
            hertz_stiffness((&balls.a, m), (&balls.b, m)).2,
            law.damping(),
            law.coefficient(),
        )?,
        _ => *law,
    };
    let contact = Contact {
        impulse: ImpulseRule::ELASTIC,
        ..contact
    };
    let c = Collision::new(balls, contact, setup.effects, *cm)?;
    let o = solve_law(&c, &law, &setup.settings, None)?;
    Ok(BatchOutput {
        result: o.result,
        stick_time: o.stick_time,
        lab: None,
        closed_form_error: o.check.closed_form_error,
        rhs_evaluations: o.stats.rhs_evaluations,
    })
}

/// Resolves a slice of collisions in parallel (rayon's current pool), in order: element i
/// of the result belongs to `inputs[i]`.
///
/// ```
/// use billiard_contact::batch::{resolve_slice, BatchInput, BatchSetup};
/// use billiard_contact::{Scene, CmState, Method, SolverSettings};
/// use nalgebra::Vector3;
/// let setup = BatchSetup::from_scene(
///     &Scene::default_scene(),
///     SolverSettings::default().with_method(Method::ClosedForm),
/// );
/// let head_on = CmState::new(Vector3::new(1.0, 0.0, 0.0), Vector3::zeros(), Vector3::zeros());
/// let out = resolve_slice(&setup, &[BatchInput::cm(head_on)]);
/// let o = out[0].as_ref().unwrap();
/// assert_eq!(o.result.out.u_cm.x, -1.0); // eq 24, P = 2 m U(0)
/// // S(0) = 0: the surfaces never slide (docs/model.md#no-initial-sliding: sticks at
/// // t = 0, theta undefined).
/// assert!(o.result.sticks && o.result.theta.is_none() && o.stick_time == Some(0.0));
/// ```
pub fn resolve_slice(setup: &BatchSetup, inputs: &[BatchInput]) -> Vec<Result<BatchOutput, Error>> {
    let kernel = shared_kernel(setup);
    inputs
        .par_iter()
        .map(|i| resolve_with(setup, kernel.as_ref(), i))
        .collect()
}

/// Closed form of centre-of-mass states sharing the setup's balls and contact, one core, into
/// `out` (same length as `states`): the fast path the 50 ns target is measured on (the
/// outgoing state, impulse, S(0), theta, stick flag and p_stick; `benches/closed_form.rs`).
pub fn closed_form_into(
    setup: &BatchSetup,
    states: &[CmState],
    out: &mut [ContactResult],
) -> Result<(), Error> {
    if states.len() != out.len() {
        return Err(Error::invalid(
            "out",
            format!("{} results for {} states", out.len(), states.len()),
            "one result per state",
        ));
    }
    let kernel = ClosedFormBatch::new(setup.balls, setup.contact, setup.effects);
    for (s, o) in states.iter().zip(out.iter_mut()) {
        *o = kernel.resolve(s)?;
    }
    Ok(())
}

/// Positions of the input columns.
#[derive(Debug, Clone)]
struct Columns {
    id: Option<usize>,
    state: StateColumns,
    overrides: [Option<usize>; 7],
}

/// The incoming state's columns: one frame or the other.
#[derive(Debug, Clone)]
enum StateColumns {
    Cm(CmColumns),
    Lab(Box<LabColumns>),
}

#[derive(Debug, Clone)]
struct CmColumns {
    u: [usize; 3],
    omega_a: [Option<usize>; 3],
    omega_b: [Option<usize>; 3],
}

#[derive(Debug, Clone)]
struct LabColumns {
    a: [[Option<usize>; 3]; 3],
    b: [[Option<usize>; 3]; 3],
    up: [Option<usize>; 3],
}

const OVERRIDES: [&str; 7] = [
    "mass",
    "radius",
    "alpha",
    "mu",
    "restitution",
    "impulse",
    "duration",
];

/// The header cell without a trailing `(unit)`.
fn bare(cell: &str) -> &str {
    let c = cell.trim().trim_start_matches('\u{feff}');
    match c.find('(') {
        Some(i) if c.ends_with(')') => c[..i].trim_end(),
        _ => c,
    }
}

/// Prefixes of the x, y, z columns of the centre-of-mass frame's state.
const CM_PREFIXES: [&str; 3] = ["u_", "omega_a_", "omega_b_"];

/// Prefixes of the x, y, z columns of the lab frame's state.
const LAB_PREFIXES: [&str; 7] = ["a_p", "a_v", "a_w", "b_p", "b_v", "b_w", "up_"];

/// The input columns accepted with the state columns of `prefixes`: `id`, the state's x, y
/// and z columns, the overrides.
fn accepted_columns(prefixes: &[&str]) -> Vec<String> {
    let mut names = vec!["id".to_string()];
    for p in prefixes {
        names.extend(["x", "y", "z"].map(|axis| format!("{p}{axis}")));
    }
    names.extend(OVERRIDES.map(String::from));
    names
}

/// Every header cell names an input column (`id`, a state column of either frame, an
/// override), once: an unknown column is refused with the accepted names and the closest
/// one, as a scene file's unknown key is.
fn check_names(names: &[&str]) -> Result<(), String> {
    let all = accepted_columns(&[&CM_PREFIXES[..], &LAB_PREFIXES[..]].concat());
    let all: Vec<&str> = all.iter().map(String::as_str).collect();
    let mut seen = std::collections::HashSet::new();
    for (k, n) in names.iter().enumerate() {
        if n.is_empty() {
            return Err(format!(
                "column {} has no name: every column needs one (see docs/formats.md#input-columns)",
                k + 1
            ));
        }
        if !all.contains(n) {
            return Err(format!(
                "column `{n}`: unknown column, expected one of {}{}",
                all.iter()
                    .map(|a| format!("`{a}`"))
                    .collect::<Vec<_>>()
                    .join(", "),
                did_you_mean(n, &all)
            ));
        }
        if !seen.insert(*n) {
            return Err(format!("column `{n}` appears twice"));
        }
    }
    Ok(())
}

/// Every state column belongs to the input's frame (`prefixes`, named `frame`): a column of
/// the other frame would be ignored.
fn check_frame(names: &[&str], prefixes: &[&str], frame: &str) -> Result<(), String> {
    let own = accepted_columns(prefixes);
    match names.iter().find(|n| !own.iter().any(|o| o == *n)) {
        Some(n) => Err(format!(
            "column `{n}` belongs to the other frame; this input is in the {frame} frame: give \
             the columns of one frame"
        )),
        None => Ok(()),
    }
}

impl Columns {
    fn from_header(header: &csv::StringRecord) -> Result<Self, String> {
        let names: Vec<&str> = header.iter().map(bare).collect();
        check_names(&names)?;
        let find = |n: &str| names.iter().position(|h| *h == n);
        let xyz = |prefix: &str| {
            [
                find(&format!("{prefix}x")),
                find(&format!("{prefix}y")),
                find(&format!("{prefix}z")),
            ]
        };
        let u = xyz("u_");
        let any_cm = u.iter().any(Option::is_some);
        let lab_names = ["a_p", "a_v", "b_p", "b_v"];
        let any_lab = lab_names.iter().any(|p| xyz(p).iter().any(Option::is_some));
        let state = match (any_cm, any_lab) {
            (true, true) => {
                return Err("both centre-of-mass (u_x, ...) and lab (a_px, ...) columns: give one frame".into())
            }
            (false, false) => {
                return Err("no state columns: give u_x, u_y, u_z (centre-of-mass frame) or a_px .. b_vz (lab frame)".into())
            }
            (true, false) => {
                check_frame(&names, &CM_PREFIXES, "centre-of-mass")?;
                let mut req = [0; 3];
                for (k, c) in u.iter().enumerate() {
                    req[k] = c.ok_or_else(|| format!("missing column `u_{}`", ["x", "y", "z"][k]))?;
                }
                StateColumns::Cm(CmColumns {
                    u: req,
                    omega_a: xyz("omega_a_"),
                    omega_b: xyz("omega_b_"),
                })
            }
            (false, true) => {
                check_frame(&names, &LAB_PREFIXES, "lab")?;
                for p in lab_names {
                    for (k, c) in xyz(p).iter().enumerate() {
                        if c.is_none() {
                            return Err(format!("missing column `{p}{}`", ["x", "y", "z"][k]));
                        }
                    }
                }
                StateColumns::Lab(Box::new(LabColumns {
                    a: [xyz("a_p"), xyz("a_v"), xyz("a_w")],
                    b: [xyz("b_p"), xyz("b_v"), xyz("b_w")],
                    up: xyz("up_"),
                }))
            }
        };
        let mut overrides = [None; 7];
        for (slot, n) in overrides.iter_mut().zip(OVERRIDES) {
            *slot = find(n);
        }
        Ok(Columns {
            id: find("id"),
            state,
            overrides,
        })
    }

    fn parse(&self, rec: &csv::StringRecord) -> Result<BatchInput, String> {
        let num = |i: Option<usize>, name: &dyn Fn() -> String| -> Result<Option<f64>, String> {
            let Some(i) = i else { return Ok(None) };
            let cell = rec.get(i).unwrap_or("").trim();
            if cell.is_empty() {
                return Ok(None);
            }
            let v: f64 = cell
                .parse()
                .map_err(|_| format!("{} = `{cell}` is not a number", name()))?;
            if !v.is_finite() {
                return Err(format!("{} = {cell}: expected a finite number", name()));
            }
            Ok(Some(v))
        };
        let vec3 = |cols: [Option<usize>; 3],
                    prefix: &str,
                    default: Option<[f64; 3]>|
         -> Result<Vector3<f64>, String> {
            let mut v = [0.0; 3];
            for k in 0..3 {
                let axis = ["x", "y", "z"][k];
                v[k] = match (num(cols[k], &|| format!("{prefix}{axis}"))?, default) {
                    (Some(x), _) => x,
                    (None, Some(d)) => d[k],
                    (None, None) => return Err(format!("{prefix}{axis} is empty")),
                };
            }
            Ok(Vector3::from(v))
        };
        let incoming = match &self.state {
            StateColumns::Cm(cm) => Incoming::Cm(CmState::new(
                vec3(cm.u.map(Some), "u_", None)?,
                vec3(cm.omega_a, "omega_a_", Some([0.0; 3]))?,
                vec3(cm.omega_b, "omega_b_", Some([0.0; 3]))?,
            )),
            StateColumns::Lab(lab) => {
                let ball = |c: &[[Option<usize>; 3]; 3], n: &str| -> Result<LabBall, String> {
                    Ok(LabBall {
                        position: vec3(c[0], &format!("{n}_p"), None)?,
                        velocity: vec3(c[1], &format!("{n}_v"), None)?,
                        spin: vec3(c[2], &format!("{n}_w"), Some([0.0; 3]))?,
                    })
                };
                Incoming::Lab(LabScene {
                    a: ball(&lab.a, "a")?,
                    b: ball(&lab.b, "b")?,
                    up: vec3(lab.up, "up_", Some([0.0, 0.0, 1.0]))?,
                })
            }
        };
        let mut o = [None; 7];
        for (k, slot) in o.iter_mut().enumerate() {
            *slot = num(self.overrides[k], &|| OVERRIDES[k].to_string())?;
        }
        Ok(BatchInput {
            incoming,
            overrides: Overrides {
                mass: o[0],
                radius: o[1],
                alpha: o[2],
                mu: o[3],
                restitution: o[4],
                impulse: o[5],
                duration: o[6],
            },
        })
    }

    /// The output header for this input and method.
    fn output_header(&self, method: Method) -> Vec<&'static str> {
        let mut h = vec!["line"];
        if self.id.is_some() {
            h.push("id");
        }
        h.extend(OUTPUT_COLUMNS);
        if matches!(self.state, StateColumns::Lab(_)) {
            h.extend(LAB_OUTPUT_COLUMNS);
        }
        if method != Method::ClosedForm {
            h.extend(["closed_form_error", "rhs_evaluations"]);
        }
        h
    }
}

/// Output columns after `line` and `id`, for every input.
pub const OUTPUT_COLUMNS: [&str; 20] = [
    "collision",
    "impulse",
    "s0",
    "theta",
    "sticks",
    "stick_time",
    "stick_impulse",
    "tangential_impulse",
    "s_out",
    "heat",
    "heat_sliding",
    "u_x",
    "u_y",
    "u_z",
    "omega_a_x",
    "omega_a_y",
    "omega_a_z",
    "omega_b_x",
    "omega_b_y",
    "omega_b_z",
];

/// Output columns for lab-frame input.
pub const LAB_OUTPUT_COLUMNS: [&str; 13] = [
    "a_vx",
    "a_vy",
    "a_vz",
    "a_wx",
    "a_wy",
    "a_wz",
    "b_vx",
    "b_vy",
    "b_vz",
    "b_wx",
    "b_wy",
    "b_wz",
    "throw_angle_deg",
];

/// What a streamed batch did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BatchSummary {
    /// Rows resolved.
    pub rows: u64,
    /// Rows where the balls collided.
    pub collisions: u64,
    /// Rows where sliding stopped during contact.
    pub sticks: u64,
    /// The most rows held in memory at once (at most the chunk size).
    pub max_rows_in_memory: usize,
}

/// Formats one output row (with its newline) into `line_out`; every float must be finite.
/// Rows are formatted by the workers, so the single writer only copies bytes.
fn format_row(
    line: u64,
    id: Option<&str>,
    o: &BatchOutput,
    method: Method,
    line_out: &mut String,
) -> Result<(), String> {
    use std::fmt::Write as _;
    fn num(s: &mut String, name: &str, v: f64) -> Result<(), String> {
        let v = finite_output(v, || name.to_string()).map_err(|e| e.to_string())?;
        let _ = write!(s, ",{}", Shortest(v));
        Ok(())
    }
    fn opt(s: &mut String, name: &str, v: Option<f64>) -> Result<(), String> {
        match v {
            Some(x) => num(s, name, x),
            None => {
                s.push(',');
                Ok(())
            }
        }
    }
    let s = line_out;
    s.clear();
    let _ = write!(s, "{line}");
    if let Some(id) = id {
        s.push(',');
        if id.contains([',', '"', '\n', '\r']) {
            s.push('"');
            s.push_str(&id.replace('"', "\"\""));
            s.push('"');
        } else {
            s.push_str(id);
        }
    }
    let r = &o.result;
    let _ = write!(s, ",{}", r.collided());
    num(s, "impulse", r.impulse)?;
    num(s, "s0", r.s0)?;
    opt(s, "theta", r.theta)?;
    let _ = write!(s, ",{}", r.sticks);
    opt(s, "stick_time", o.stick_time)?;
    opt(s, "stick_impulse", r.stick_impulse)?;
    let st = &r.out;
    let scalars = [
        r.tangential_impulse,
        r.s_out,
        r.heat,
        r.heat_sliding,
        st.u_cm.x,
        st.u_cm.y,
        st.u_cm.z,
        st.omega_a.x,
        st.omega_a.y,
        st.omega_a.z,
        st.omega_b.x,
        st.omega_b.y,
        st.omega_b.z,
    ];
    for (name, v) in OUTPUT_COLUMNS[7..].iter().zip(scalars) {
        num(s, name, v)?;
    }
    if let Some((a, b, throw)) = &o.lab {
        let v = [a.velocity, a.spin, b.velocity, b.spin];
        for (name, x) in LAB_OUTPUT_COLUMNS
            .iter()
            .zip(v.iter().flat_map(|v| v.iter()))
        {
            num(s, name, *x)?;
        }
        opt(s, "throw_angle_deg", *throw)?;
    }
    if method != Method::ClosedForm {
        num(s, "closed_form_error", o.closed_form_error)?;
        let _ = write!(s, ",{}", o.rhs_evaluations);
    }
    s.push('\n');
    Ok(())
}

/// Reads up to `chunk_rows` records into the reused buffers `records`, with their input
/// lines in `lines`; returns how many it read (fewer at the end of the input). `bad` makes
/// the error of a line.
fn read_chunk<R: Read>(
    rd: &mut csv::Reader<R>,
    records: &mut Vec<csv::StringRecord>,
    lines: &mut Vec<u64>,
    chunk_rows: usize,
    bad: &impl Fn(u64, String) -> Error,
) -> Result<usize, Error> {
    let mut n = 0;
    while n < chunk_rows {
        if records.len() <= n {
            records.push(csv::StringRecord::new());
            lines.push(0);
        }
        let more = rd
            .read_record(&mut records[n])
            .map_err(|e| bad(line_read(rd, None), csv_cause(&e)))?;
        if !more {
            break;
        }
        lines[n] = line_read(rd, Some(&records[n]));
        n += 1;
    }
    Ok(n)
}

/// The input line where the record just read (`record`; `None` for one that failed to
/// read, counted as one line) starts. The CSV reader's own record positions are counted
/// before the blank lines it skips; its position after a record is exact: the line after
/// the record's terminating LF (every record has one: [`CrlfAsLf`]).
fn line_read<R: Read>(rd: &csv::Reader<R>, record: Option<&csv::StringRecord>) -> u64 {
    let inside = record.map_or(0, |r| r.iter().map(|f| f.matches('\n').count()).sum());
    rd.position()
        .line()
        .saturating_sub(1 + inside as u64)
        .max(1)
}

/// A CSV reading error's cause in words, without the reader's own record position (whose
/// line can be off; the caller names the line).
fn csv_cause(e: &csv::Error) -> String {
    match e.kind() {
        csv::ErrorKind::UnequalLengths {
            expected_len, len, ..
        } => format!("{len} cells where the header has {expected_len}"),
        csv::ErrorKind::Utf8 { err, .. } => {
            format!("cell {} is not valid UTF-8", err.field() + 1)
        }
        _ => e.to_string(),
    }
}

/// A reader that passes its input on with every CRLF line end as LF (a lone CR stays), and
/// ends it with an LF if it does not end with one.
struct CrlfAsLf<R> {
    inner: R,
    buf: Box<[u8]>,
    /// The unread part of `buf` is `start..end`.
    start: usize,
    end: usize,
    eof: bool,
    /// The last byte passed on.
    last: Option<u8>,
}

impl<R: Read> CrlfAsLf<R> {
    fn new(inner: R) -> Self {
        CrlfAsLf {
            inner,
            buf: vec![0; 1 << 16].into_boxed_slice(),
            start: 0,
            end: 0,
            eof: false,
            last: None,
        }
    }

    /// Whether more input is needed before a byte can be passed on: none is left, or only a
    /// CR whose next byte is still to come.
    fn needs_input(&self) -> bool {
        match self.end - self.start {
            0 => !self.eof,
            1 => !self.eof && self.buf[self.start] == b'\r',
            _ => false,
        }
    }
}

impl<R: Read> Read for CrlfAsLf<R> {
    fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        while self.needs_input() {
            self.buf.copy_within(self.start..self.end, 0);
            self.end -= self.start;
            self.start = 0;
            let n = self.inner.read(&mut self.buf[self.end..])?;
            self.eof = n == 0;
            self.end += n;
        }
        let mut written = 0;
        while written < out.len() && self.start < self.end {
            let b = self.buf[self.start];
            if b == b'\r' {
                match self.buf[self.start + 1..self.end].first() {
                    Some(b'\n') => {
                        self.start += 1;
                        continue;
                    }
                    None if !self.eof => break,
                    _ => {}
                }
            }
            out[written] = b;
            written += 1;
            self.start += 1;
        }
        if written == 0 && self.eof && !out.is_empty() && self.last.is_some_and(|b| b != b'\n') {
            out[0] = b'\n';
            written = 1;
        }
        if written > 0 {
            self.last = Some(out[written - 1]);
        }
        Ok(written)
    }
}

/// Streams a batch: reads CSV rows from `input` (`input_name` in errors), resolves them
/// `chunk_rows` at a time in parallel (rayon's current pool), writes the results to `output`
/// in input order, and calls `progress(rows_done, bytes_read)` after each chunk. Memory holds
/// at most one chunk of rows. Errors name the input line; the output is then incomplete
/// and the caller discards it (the command writes through an atomic file).
pub fn run_csv<R: Read, W: Write>(
    setup: &BatchSetup,
    input: R,
    input_name: &Path,
    output: W,
    chunk_rows: usize,
    mut progress: impl FnMut(u64, u64),
) -> Result<(W, BatchSummary), Error> {
    let chunk_rows = chunk_rows.max(1);
    let path = PathBuf::from(input_name);
    let bad = |line: u64, message: String| Error::BatchInput {
        path: path.clone(),
        line,
        message,
    };
    // CRLF read as LF: the CSV reader counts the line of a record that follows a CRLF one
    // too low.
    let mut rd = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(CrlfAsLf::new(input));
    let header = rd.headers().map_err(|e| bad(1, e.to_string()))?.clone();
    let cols = Columns::from_header(&header).map_err(|m| bad(1, m))?;
    let method = setup.settings.method();
    let kernel = shared_kernel(setup);
    let mut w = output;
    let io = |e: std::io::Error| Error::io("batch output", e);
    w.write_all(cols.output_header(method).join(",").as_bytes())
        .and_then(|_| w.write_all(b"\n"))
        .map_err(io)?;
    let mut summary = BatchSummary::default();
    // Reused buffers: their size is bounded by the chunk, not by the file.
    let mut records: Vec<csv::StringRecord> = Vec::with_capacity(chunk_rows);
    let mut lines: Vec<u64> = Vec::with_capacity(chunk_rows);
    let mut results: Vec<Result<(String, bool, bool), String>> = Vec::with_capacity(chunk_rows);
    loop {
        let n = read_chunk(&mut rd, &mut records, &mut lines, chunk_rows, &bad)?;
        if n == 0 {
            break;
        }
        summary.max_rows_in_memory = summary.max_rows_in_memory.max(records.len());
        results.clear();
        records[..n]
            .par_iter()
            .zip(lines[..n].par_iter())
            .map(|(rec, &line)| {
                let input = cols.parse(rec)?;
                let out =
                    resolve_with(setup, kernel.as_ref(), &input).map_err(|e| e.to_string())?;
                let id = cols.id.and_then(|i| rec.get(i));
                let mut text = String::with_capacity(400);
                format_row(line, id, &out, method, &mut text)?;
                Ok((text, out.result.collided(), out.result.sticks))
            })
            .collect_into_vec(&mut results);
        for (k, r) in results.iter().enumerate() {
            let (text, collision, sticks) = r.as_ref().map_err(|m| bad(lines[k], m.clone()))?;
            w.write_all(text.as_bytes()).map_err(io)?;
            summary.rows += 1;
            summary.collisions += u64::from(*collision);
            summary.sticks += u64::from(*sticks);
        }
        progress(summary.rows, rd.position().byte());
        if n < chunk_rows {
            break;
        }
    }
    w.flush().map_err(io)?;
    Ok((w, summary))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reader that hands out at most `.1` bytes per call: with 1 every CR meets the end
    /// of a read; with more, a CR also ends a read after other bytes ("a,b\r\n" in reads
    /// of 3: "a,b", "\r\n..."; in reads of 2: "a,", "b\r", "\n...").
    struct Chunks<'a>(&'a [u8], usize);

    impl Read for Chunks<'_> {
        fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
            let n = self.0.len().min(out.len()).min(self.1);
            out[..n].copy_from_slice(&self.0[..n]);
            self.0 = &self.0[n..];
            Ok(n)
        }
    }

    fn through(input: &[u8], in_len: usize, out_len: usize) -> Vec<u8> {
        let mut r = CrlfAsLf::new(Chunks(input, in_len));
        let mut all = Vec::new();
        let mut buf = vec![0; out_len];
        loop {
            let n = r.read(&mut buf).unwrap();
            if n == 0 {
                return all;
            }
            all.extend_from_slice(&buf[..n]);
        }
    }

    /// CRLF becomes LF wherever the reads (of the input, and of the output) split it, a lone
    /// CR stays, and the text ends with one LF (added only when missing).
    #[test]
    fn crlf_reads_as_lf() {
        for in_len in [1, 2, 3, 5, 64] {
            for out_len in [1, 2, 7] {
                let through = |input: &[u8]| through(input, in_len, out_len);
                assert_eq!(through(b"a,b\r\n1,2\r\n"), b"a,b\n1,2\n");
                assert_eq!(through(b"a\rb\r\n\r\nc"), b"a\rb\n\nc\n");
                assert_eq!(through(b"x\r"), b"x\r\n");
                assert_eq!(through(b""), b"");
            }
        }
    }
}
