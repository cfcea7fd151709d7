//! `BallPlane`: a sphere against a plane (docs/plane.md), one impact or N from numpy
//! arrays. The closed form is the library's direct sphere-plane closed form
//! (`details::plane_impact`, a few dozen operations a row); `method=` runs the library's
//! `PlaneCollision` with `solve_plane` instead (its equivalent pair, by any method).

use crate::errors::to_py;
use crate::inputs::{float_array, strided, Strided};
use crate::outputs::{bool_, float64, vector};
use crate::settings;
use billiard_contact::details::{plane_impact, PlaneImpact};
use billiard_contact::nalgebra::Vector3;
use billiard_contact::profile::HalfSine;
use billiard_contact::{
    resolve_sphere_plane_compliant_damped, solve_plane, Ball, Contact, ContactLaw, Damping, Error,
    Friction, HertzContact, ImpulseRule, Material, Method, PlaneCollision, SolverSettings,
};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use rayon::prelude::*;

/// The argument names of `resolve`, in the order of the views.
const NAMES: [&str; 3] = ["v", "w", "normal"];

/// Rows from which the closed form spreads over rayon's pool.
const PARALLEL_ROWS: usize = 2048;

/// Rows a chunk: the unit of the parallel split and of the check that every output is
/// finite (one branch a chunk; the row is found only when a chunk fails).
const CHUNK: usize = 1024;

/// Contact duration (s) of the half-sine pulse the time-stepping methods integrate (the
/// outcome does not depend on it: friction and restitution act on the impulse).
const DURATION: f64 = 2.5e-4;

/// A ball against a plane: the ball's mass (kg), radius (m) and alpha (I = alpha m r^2,
/// default 0.4), Coulomb friction mu between ball and plane (a number >= 0), restitution e
/// in [0, 1] (P = (1 + e) m |v.n|: Newton's, Poisson's and Stronge's rules agree for a
/// sphere on a plane).
///
/// Bad values raise ValueError naming the keyword, e.g. "mass = -1: > 0 kg".
#[pyclass(frozen, module = "billiard_contact._core", name = "BallPlane")]
pub struct BallPlane {
    ball: Ball,
    contact: Contact,
    mu: f64,
    restitution: f64,
    /// The tangential law: `None` the rigid stick rule, else Mindlin's spring.
    mindlin: Option<Mindlin>,
}

/// The compliant contact: Mindlin's spring between the ball's material and the plane's
/// (`None`: a rigid plane), on Hertz's force with its damping.
#[derive(Clone, Copy, PartialEq)]
struct Mindlin {
    ball: Material,
    plane: Option<Material>,
    /// The damping law and its coefficient (beta in s/m or gamma in s), as run.
    law: (Damping, f64),
    /// The keywords it came from: a coefficient given, or the speed of the calibration.
    coefficient: Option<f64>,
    at_speed: Option<f64>,
}

/// The rows of a compliant run, as output columns.
struct CompliantRows {
    v: Vec<f64>,
    w: Vec<f64>,
    impulse: Vec<f64>,
    tangential_impulse: Vec<f64>,
    contact_time: Vec<f64>,
    rebound_angle: Vec<f64>,
}

/// `e` with the field `from` named `to` (the library names a scene file's fields).
pub(crate) fn renamed(e: Error, from: &str, to: &str) -> Error {
    match e {
        Error::InvalidParameter {
            field,
            value,
            expected,
        } => Error::InvalidParameter {
            field: field
                .strip_prefix(from)
                .map_or(field.clone(), |rest| format!("{to}{rest}")),
            value,
            expected,
        },
        other => other,
    }
}

/// One row's outputs.
#[derive(Clone, Copy)]
struct Row {
    v: [f64; 3],
    w: [f64; 3],
    impulse: f64,
    tangential_impulse: f64,
    sticks: bool,
    /// NaN where there is none.
    stick_impulse: f64,
}

impl Row {
    fn of(i: &PlaneImpact) -> Row {
        Row {
            v: i.velocity.into(),
            w: i.spin.into(),
            impulse: i.normal_impulse,
            tangential_impulse: i.tangential_impulse,
            sticks: i.sticks,
            stick_impulse: i.stick_impulse.unwrap_or(f64::NAN),
        }
    }

    /// Whether every output but the stick impulse (NaN where there is none) is finite.
    #[inline(always)]
    fn finite(&self) -> bool {
        let z = self.v[0] * 0.0
            + self.v[1] * 0.0
            + self.v[2] * 0.0
            + self.w[0] * 0.0
            + self.w[1] * 0.0
            + self.w[2] * 0.0
            + self.impulse * 0.0
            + self.tangential_impulse * 0.0;
        z == 0.0
    }
}

/// The first output of a row that is not finite, as the error message.
#[cold]
#[inline(never)]
fn non_finite_output(r: &Row) -> String {
    let named = ["v", "w"]
        .into_iter()
        .zip([r.v, r.w])
        .flat_map(|(name, v)| (0..3).map(move |k| (format!("{name}[{k}]"), v[k])))
        .chain([
            ("impulse".to_string(), r.impulse),
            ("tangential_impulse".to_string(), r.tangential_impulse),
        ]);
    let (name, x) = named
        .into_iter()
        .find(|(_, x)| !x.is_finite())
        .unwrap_or_else(|| ("output".into(), f64::NAN));
    format!(
        "{name} = {x}: the result is not finite (the impact overflows double precision: \
         mass, speed or spin too large)"
    )
}

/// The error for a non-finite input of a row.
#[cold]
#[inline(never)]
fn non_finite_input(all: [Vector3<f64>; 3]) -> Error {
    for (name, v) in NAMES.iter().zip(all) {
        for k in 0..3 {
            if !v[k].is_finite() {
                return Error::invalid(format!("{name}[{k}]"), v[k], "a finite number");
            }
        }
    }
    Error::invalid("input", "a non-finite number", "finite numbers")
}

#[cold]
#[inline(never)]
fn bad_normal(n: Vector3<f64>) -> Error {
    Error::invalid(
        "normal",
        format!("[{}, {}, {}]", n.x, n.y, n.z),
        "a non-zero, finite direction (out of the plane, towards the ball)",
    )
}

/// Why a row failed: its input (ValueError), or the method (RuntimeError).
enum Failure {
    Input(Error),
    Output(String),
}

/// The raw output columns, written row by row from several threads (each row by one).
#[derive(Clone, Copy)]
struct Columns {
    v: *mut [f64; 3],
    w: *mut [f64; 3],
    impulse: *mut f64,
    tangential_impulse: *mut f64,
    sticks: *mut bool,
    stick_impulse: *mut f64,
}

// SAFETY: the columns are fresh numpy buffers of n rows, not visible to Python until every
// row is written; each row is written by exactly one thread.
unsafe impl Send for Columns {}
unsafe impl Sync for Columns {}

impl Columns {
    /// # Safety
    /// i < n, and no other thread writes row i.
    #[inline(always)]
    unsafe fn write(&self, i: usize, r: &Row) {
        unsafe {
            *self.v.add(i) = r.v;
            *self.w.add(i) = r.w;
            *self.impulse.add(i) = r.impulse;
            *self.tangential_impulse.add(i) = r.tangential_impulse;
            *self.sticks.add(i) = r.sticks;
            *self.stick_impulse.add(i) = r.stick_impulse;
        }
    }
}

impl BallPlane {
    /// Row i's inputs: v, w and the unit normal, checked (finite; the normal non-zero).
    #[inline(always)]
    fn inputs(views: &[Strided; 3], i: usize) -> Result<[Vector3<f64>; 3], Error> {
        // SAFETY: i < n of the views (the callers' loops), whose arrays outlive the call.
        let (v, w, normal) = unsafe { (views[0].row(i), views[1].row(i), views[2].row(i)) };
        let z = |x: &Vector3<f64>| x.x * 0.0 + x.y * 0.0 + x.z * 0.0;
        if z(&v) + z(&w) + z(&normal) != 0.0 {
            return Err(non_finite_input([v, w, normal]));
        }
        let length = normal.norm();
        if !(length > 0.0 && length.is_finite()) {
            return Err(bad_normal(normal));
        }
        // A unit normal divides by 1: exactly itself.
        Ok([v, w, normal / length])
    }

    /// The closed form of one row.
    #[inline(always)]
    fn closed_form(&self, views: &[Strided; 3], i: usize) -> Result<Row, Error> {
        let [v, w, n] = Self::inputs(views, i)?;
        let p = self.contact.impulse.impulse(self.ball.mass(), -v.dot(&n))?;
        Ok(Row::of(&plane_impact(&self.ball, self.mu, p, &n, &v, &w)))
    }

    /// One row by `settings`' method: the library's `PlaneCollision` and `solve_plane`.
    fn by_method(
        &self,
        views: &[Strided; 3],
        i: usize,
        settings: &SolverSettings,
    ) -> Result<Row, Error> {
        let [v, w, n] = Self::inputs(views, i)?;
        // The library names the vectors as a scene file does; here they are v and w.
        let hit = PlaneCollision::new(self.ball, self.contact, n, v, w).map_err(|e| {
            renamed(
                renamed(e, "incoming.plane.velocity", "v"),
                "incoming.plane.spin",
                "w",
            )
        })?;
        let out = solve_plane(&hit, &HalfSine::new(DURATION)?, settings, None)?;
        let r = &out.outcome.result;
        Ok(Row {
            v: out.velocity.into(),
            w: out.spin.into(),
            impulse: r.impulse,
            tangential_impulse: r.tangential_impulse,
            sticks: r.sticks,
            stick_impulse: r.stick_impulse.unwrap_or(f64::NAN),
        })
    }

    /// Rows [start, end) into `out`: the first failure (its row) if any. The outputs are
    /// checked finite once for the chunk; the failing row is looked for only when it fails.
    fn rows(
        &self,
        views: &[Strided; 3],
        settings: Option<&SolverSettings>,
        out: Columns,
        start: usize,
        end: usize,
    ) -> Option<(usize, Failure)> {
        let mut finite = true;
        for i in start..end {
            let r = match settings {
                None => self.closed_form(views, i),
                Some(s) => self.by_method(views, i, s),
            };
            match r {
                Ok(r) => {
                    finite &= r.finite();
                    // SAFETY: i < n; this chunk is this thread's alone.
                    unsafe { out.write(i, &r) }
                }
                Err(e) => return Some((i, Failure::Input(e))),
            }
        }
        if finite {
            return None;
        }
        (start..end).find_map(|i| {
            // SAFETY: rows [start, end) were written above, by this thread.
            let r = unsafe {
                Row {
                    v: *out.v.add(i),
                    w: *out.w.add(i),
                    impulse: *out.impulse.add(i),
                    tangential_impulse: *out.tangential_impulse.add(i),
                    sticks: *out.sticks.add(i),
                    stick_impulse: *out.stick_impulse.add(i),
                }
            };
            (!r.finite()).then(|| (i, Failure::Output(non_finite_output(&r))))
        })
    }
}

/// The tangential law from the keywords: `None` for "rigid" (no material or damping may be
/// given: the stick rule uses none), for "mindlin" the ball's and the plane's (or a rigid
/// plane's `None`) materials and the normal force's damping: elastic (restitution 1), a
/// coefficient, or calibrated to the restitution at `at_speed`.
#[allow(clippy::too_many_arguments)]
fn mindlin_of(
    ball_model: &Ball,
    tangential: &str,
    restitution: f64,
    ball: [Option<f64>; 2],
    plane: [Option<f64>; 2],
    damping: Option<&str>,
    coefficient: Option<f64>,
    at_speed: Option<f64>,
) -> Result<Option<Mindlin>, Error> {
    let material = |[e, nu]: [Option<f64>; 2], names: [&str; 2]| match (e, nu) {
        (Some(e), Some(nu)) => Material::new(e, nu).map(Some).map_err(|err| {
            renamed(
                renamed(err, "balls.youngs_modulus", names[0]),
                "balls.poisson_ratio",
                names[1],
            )
        }),
        (None, None) => Ok(None),
        _ => Err(Error::invalid(
            format!("{}, {}", names[0], names[1]),
            "one given without the other",
            "both or neither",
        )),
    };
    let ball = material(ball, ["youngs_modulus", "poisson_ratio"])?;
    let plane = material(plane, ["plane_youngs_modulus", "plane_poisson_ratio"])?;
    let law = crate::cluster::damping_of(damping)?;
    match tangential {
        "rigid" => match (ball, plane, damping, coefficient, at_speed) {
            (None, None, None, None, None) => Ok(None),
            _ => Err(Error::invalid(
                "tangential",
                "\"rigid\" with a material or a damping",
                "tangential=\"mindlin\" with the materials and damping (the rigid stick \
                 rule uses none)",
            )),
        },
        "mindlin" => {
            let Some(ball) = ball else {
                return Err(Error::invalid(
                    "youngs_modulus, poisson_ratio",
                    "not given with tangential=\"mindlin\"",
                    "the ball's material (Mindlin's spring and Hertz's force need it)",
                ));
            };
            let run_law = damping_law(
                law,
                restitution,
                coefficient,
                at_speed,
                ball_model.mass(),
                |v| {
                    HertzContact::sphere_plane(ball_model, &ball, plane.as_ref(), v)
                        .map(|h| h.stiffness)
                },
            )?;
            Ok(Some(Mindlin {
                ball,
                plane,
                law: run_law,
                coefficient,
                at_speed,
            }))
        }
        other => Err(Error::invalid(
            "tangential",
            format!("{other:?}"),
            "\"rigid\" (the stick rule) or \"mindlin\" (Mindlin's tangential spring)",
        )),
    }
}

/// The damping keywords of a compliant model's repr: `, damping=..., coefficient=...,
/// at_speed=...`, each only when given; empty without damping.
pub(crate) fn damping_repr(
    damping: Damping,
    coefficient: Option<f64>,
    at_speed: Option<f64>,
) -> String {
    let mut s = String::new();
    if damping != Damping::None {
        s += &format!(", damping={:?}", damping.name());
        if let Some(c) = coefficient {
            s += &format!(", coefficient={c:?}");
        }
        if let Some(v) = at_speed {
            s += &format!(", at_speed={v:?}");
        }
    }
    s
}

/// The damping law and its coefficient (beta in s/m or gamma in s) that a compliant contact
/// runs, from the keywords `damping=` (already parsed to `law`), `coefficient=`,
/// `restitution=` and `at_speed=` (m/s): elastic Hertz (restitution 1, neither coefficient
/// nor speed), a coefficient as given (restitution left at 1), or the coefficient
/// calibrated (`ContactLaw::calibrated`) so that a head-on impact at `at_speed` on the
/// contact's Hertz stiffness `stiffness(at_speed)` (N/m^1.5) with the reduced mass `mass`
/// (kg) rebounds with `restitution`. Shared by `BallPlane` and `BallBall`; errors name the
/// keywords.
pub(crate) fn damping_law(
    law: Damping,
    restitution: f64,
    coefficient: Option<f64>,
    at_speed: Option<f64>,
    mass: f64,
    stiffness: impl FnOnce(f64) -> Result<f64, Error>,
) -> Result<(Damping, f64), Error> {
    let named = |e: Error| {
        renamed(
            renamed(
                renamed(e, "contact.law.coefficient", "coefficient"),
                "contact.law.restitution",
                "restitution",
            ),
            "contact.law.at_speed",
            "at_speed",
        )
    };
    Ok(match (law, coefficient, at_speed) {
        (Damping::None, None, None) if restitution == 1.0 => (Damping::None, 0.0),
        (Damping::None, c, v) if c.is_some() || v.is_some() => {
            return Err(Error::invalid(
                "damping",
                "None with coefficient= or at_speed=",
                "\"hunt-crossley\" or \"kuwabara-kono\" (elastic Hertz takes neither)",
            ))
        }
        (Damping::None, _, _) => {
            return Err(Error::invalid(
                "restitution",
                format!("{restitution} with damping None"),
                "1 (elastic Hertz), or a damping law (\"hunt-crossley\", \
                 \"kuwabara-kono\") with coefficient= or at_speed=",
            ))
        }
        (d, Some(c), None) if restitution == 1.0 => {
            ContactLaw::new(1.0, d, c).map_err(named)?;
            (d, c)
        }
        (d, None, Some(v)) => {
            // Checked before the stiffness, which may depend on it (a Hertz contact time at
            // 0 m/s was refused naming `incoming`; found by fuzzing).
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid(
                    "at_speed",
                    v,
                    "finite and > 0 (m/s): the approach speed the restitution is calibrated at",
                ));
            }
            let k = stiffness(v).map_err(named)?;
            let l = ContactLaw::calibrated(k, d, restitution, v, mass).map_err(named)?;
            (l.damping(), l.coefficient())
        }
        _ => {
            return Err(Error::invalid(
                "coefficient, at_speed",
                "both or neither given (or a coefficient with restitution)",
                "coefficient= (restitution left at 1), or restitution= with \
                 at_speed= to calibrate it",
            ))
        }
    })
}

impl BallPlane {
    /// Every row by the compliant kernel (a row that does not approach passes unchanged);
    /// the first failure and its row.
    fn compliant_rows(
        &self,
        views: &[Strided; 3],
        n: usize,
        mindlin: Mindlin,
        settings: &SolverSettings,
    ) -> Result<CompliantRows, (usize, Error)> {
        let one = |i: usize| -> Result<[f64; 10], (usize, Error)> {
            let [v, w, normal] = Self::inputs(views, i).map_err(|e| (i, e))?;
            if v.dot(&normal) >= 0.0 {
                return Ok([v.x, v.y, v.z, w.x, w.y, w.z, 0.0, 0.0, 0.0, f64::NAN]);
            }
            let o = resolve_sphere_plane_compliant_damped(
                &self.ball,
                mindlin.ball,
                mindlin.plane,
                mindlin.law,
                self.mu,
                v,
                w,
                normal,
                settings,
            )
            .map_err(|e| {
                (
                    i,
                    [
                        ("incoming.velocity", "v"),
                        ("incoming.spin", "w"),
                        ("friction.mu", "mu"),
                        ("plane.normal", "normal"),
                        ("balls.alpha", "alpha"),
                        // Hertz's contact time out of the doubles' range: the materials.
                        ("contact.profile.duration", "youngs_modulus, poisson_ratio"),
                    ]
                    .iter()
                    .fold(e, |e, (from, to)| renamed(e, from, to)),
                )
            })?;
            let (v, w) = (o.velocity, o.spin);
            Ok([
                v.x,
                v.y,
                v.z,
                w.x,
                w.y,
                w.z,
                o.normal_impulse,
                o.tangential_impulse.norm(),
                o.contact_time,
                o.rebound_angle,
            ])
        };
        let all: Vec<[f64; 10]> = if n >= 64 {
            (0..n).into_par_iter().map(one).collect::<Vec<_>>()
        } else {
            (0..n).map(one).collect::<Vec<_>>()
        }
        .into_iter()
        .collect::<Result<_, _>>()?;
        Ok(CompliantRows {
            v: all.iter().flat_map(|r| r[0..3].to_vec()).collect(),
            w: all.iter().flat_map(|r| r[3..6].to_vec()).collect(),
            impulse: all.iter().map(|r| r[6]).collect(),
            tangential_impulse: all.iter().map(|r| r[7]).collect(),
            contact_time: all.iter().map(|r| r[8]).collect(),
            rebound_angle: all.iter().map(|r| r[9]).collect(),
        })
    }
}

/// The compliant rows as the result dict: (N, 3) and (N,) arrays, or (3,) arrays and
/// numpy scalars for one impact.
fn compliant_dict(
    py: Python<'_>,
    r: CompliantRows,
    n: usize,
    single: bool,
) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    if single {
        d.set_item(intern!(py, "v"), vector(py, [r.v[0], r.v[1], r.v[2]])?)?;
        d.set_item(intern!(py, "w"), vector(py, [r.w[0], r.w[1], r.w[2]])?)?;
        for (k, x) in [
            ("impulse", &r.impulse),
            ("tangential_impulse", &r.tangential_impulse),
            ("contact_time", &r.contact_time),
            ("rebound_angle", &r.rebound_angle),
        ] {
            d.set_item(k, float64(py, x[0])?)?;
        }
        return Ok(d);
    }
    d.set_item(
        intern!(py, "v"),
        PyArray1::from_vec(py, r.v).reshape([n, 3])?,
    )?;
    d.set_item(
        intern!(py, "w"),
        PyArray1::from_vec(py, r.w).reshape([n, 3])?,
    )?;
    for (k, x) in [
        ("impulse", r.impulse),
        ("tangential_impulse", r.tangential_impulse),
        ("contact_time", r.contact_time),
        ("rebound_angle", r.rebound_angle),
    ] {
        d.set_item(k, PyArray1::from_vec(py, x))?;
    }
    Ok(d)
}

/// The Python exception for a failed row (`row i: ` for arrays).
fn failure_error(i: usize, f: Failure, single: bool) -> PyErr {
    let row = |m: String| if single { m } else { format!("row {i}: {m}") };
    match f {
        Failure::Input(e) if e.is_bad_input() => PyValueError::new_err(row(e.to_string())),
        Failure::Input(e) => PyRuntimeError::new_err(row(e.to_string())),
        Failure::Output(m) => PyValueError::new_err(row(m)),
    }
}

#[pymethods]
impl BallPlane {
    #[new]
    #[pyo3(signature = (*, mass, radius, alpha = 0.4, mu, restitution = 1.0,
                        tangential = "rigid".to_string(), youngs_modulus = None,
                        poisson_ratio = None, plane_youngs_modulus = None,
                        plane_poisson_ratio = None, damping = None, coefficient = None,
                        at_speed = None),
           text_signature = "(*, mass, radius, alpha=0.4, mu, restitution=1.0, \
                             tangential='rigid', youngs_modulus=None, poisson_ratio=None, \
                             plane_youngs_modulus=None, plane_poisson_ratio=None, \
                             damping=None, coefficient=None, at_speed=None)")]
    #[allow(clippy::too_many_arguments)]
    fn new(
        #[pyo3(from_py_with = crate::args::mass)] mass: f64,
        #[pyo3(from_py_with = crate::args::radius)] radius: f64,
        #[pyo3(from_py_with = crate::args::alpha)] alpha: f64,
        #[pyo3(from_py_with = crate::args::mu)] mu: f64,
        #[pyo3(from_py_with = crate::args::restitution)] restitution: f64,
        #[pyo3(from_py_with = crate::args::tangential)] tangential: String,
        #[pyo3(from_py_with = crate::args::youngs_modulus)] youngs_modulus: Option<f64>,
        #[pyo3(from_py_with = crate::args::poisson_ratio)] poisson_ratio: Option<f64>,
        #[pyo3(from_py_with = crate::args::plane_youngs_modulus)] plane_youngs_modulus: Option<f64>,
        #[pyo3(from_py_with = crate::args::plane_poisson_ratio)] plane_poisson_ratio: Option<f64>,
        #[pyo3(from_py_with = crate::args::damping)] damping: Option<String>,
        #[pyo3(from_py_with = crate::args::coefficient)] coefficient: Option<f64>,
        #[pyo3(from_py_with = crate::args::at_speed)] at_speed: Option<f64>,
    ) -> PyResult<Self> {
        let ball = Ball::in_section("ball", mass, radius, alpha)
            .map_err(|e| to_py(renamed(e, "ball.", "")))?;
        let friction = Friction::constant(mu).map_err(|e| to_py(renamed(e, "contact.", "")))?;
        let mindlin = mindlin_of(
            &ball,
            &tangential,
            restitution,
            [youngs_modulus, poisson_ratio],
            [plane_youngs_modulus, plane_poisson_ratio],
            damping.as_deref(),
            coefficient,
            at_speed,
        )
        .map_err(to_py)?;
        let impulse =
            ImpulseRule::restitution(restitution).map_err(|e| to_py(renamed(e, "contact.", "")))?;
        Ok(BallPlane {
            ball,
            contact: Contact { friction, impulse },
            mu,
            restitution,
            mindlin,
        })
    }

    /// Resolves impacts of the ball on the plane.
    ///
    /// v, w: the ball's velocity (m/s) and spin (rad/s) before; normal: the plane's normal,
    /// out of the plane towards the ball (any non-zero length); each (3,) or (N, 3) (a (3,)
    /// input, say one normal, is used for every row). A ball that does not approach the
    /// plane (v.n >= 0) passes unchanged: impulse 0, sticks False.
    ///
    /// method None: the direct closed form; "closed-form", "rk4", "dopri5", "dop853": the
    /// library's PlaneCollision by that method (a half-sine pulse; rtol as resolve_lab's).
    ///
    /// Returns a dict: "v", "w" (after; the input's shape), "impulse" (P = (1 + e) m |v.n|,
    /// N s), "tangential_impulse" (J <= mu P, N s), "sticks" (the slip stopped),
    /// "stick_impulse" (the normal impulse at which the slip stops or would stop, N s; NaN
    /// without friction or impulse), each (N,) or a numpy scalar for one impact.
    #[pyo3(signature = (v, w, normal, method = None, rtol = None))]
    fn resolve<'py>(
        &self,
        py: Python<'py>,
        v: &Bound<'py, PyAny>,
        w: &Bound<'py, PyAny>,
        normal: &Bound<'py, PyAny>,
        #[pyo3(from_py_with = crate::args::method)] method: Option<String>,
        #[pyo3(from_py_with = crate::args::rtol)] rtol: Option<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let method = method.as_deref();
        let arrays = [
            Some(float_array("v", v)?),
            Some(float_array("w", w)?),
            Some(float_array("normal", normal)?),
        ];
        let (views, n, single) = strided(&NAMES, &arrays)?;
        if let Some(mindlin) = self.mindlin {
            if let Some(m) = method {
                return Err(to_py(Error::invalid(
                    "method",
                    format!("{m:?}"),
                    "None with tangential=\"mindlin\" (the compliant contact steps with its \
                     own Dormand-Prince 5(4); rtol= sets its tolerance)",
                )));
            }
            let settings = settings::for_batch(Some("dopri5"), rtol, None).map_err(to_py)?;
            let borrows = arrays
                .iter()
                .flatten()
                .map(|a| a.try_readonly())
                .collect::<Result<Vec<_>, _>>()?;
            let rows = py.detach(|| self.compliant_rows(&views, n, mindlin, &settings));
            drop(borrows);
            drop(arrays);
            let rows = rows.map_err(|(i, e)| failure_error(i, Failure::Input(e), single))?;
            return compliant_dict(py, rows, n, single);
        }
        let settings = match (method, rtol) {
            (None, None) => None,
            _ => Some(settings::for_batch(method, rtol, None).map_err(to_py)?),
        };
        if single {
            let r = match &settings {
                None => self.closed_form(&views, 0),
                Some(s) => self.by_method(&views, 0, s),
            };
            drop(arrays);
            let r = r.map_err(|e| failure_error(0, Failure::Input(e), true))?;
            if !r.finite() {
                return Err(failure_error(
                    0,
                    Failure::Output(non_finite_output(&r)),
                    true,
                ));
            }
            let d = PyDict::new(py);
            d.set_item(intern!(py, "v"), vector(py, r.v)?)?;
            d.set_item(intern!(py, "w"), vector(py, r.w)?)?;
            d.set_item(intern!(py, "impulse"), float64(py, r.impulse)?)?;
            d.set_item(
                intern!(py, "tangential_impulse"),
                float64(py, r.tangential_impulse)?,
            )?;
            d.set_item(intern!(py, "sticks"), bool_(py, r.sticks)?)?;
            d.set_item(intern!(py, "stick_impulse"), float64(py, r.stick_impulse)?)?;
            return Ok(d);
        }
        // SAFETY (uninitialised): every row is written before the arrays reach Python; on
        // error they are dropped unseen.
        let (ov, ow, op, oj, os, osp) = unsafe {
            (
                PyArray2::<f64>::new(py, [n, 3], false),
                PyArray2::<f64>::new(py, [n, 3], false),
                PyArray1::<f64>::new(py, [n], false),
                PyArray1::<f64>::new(py, [n], false),
                PyArray1::<bool>::new(py, [n], false),
                PyArray1::<f64>::new(py, [n], false),
            )
        };
        let columns = Columns {
            v: ov.data().cast(),
            w: ow.data().cast(),
            impulse: op.data(),
            tangential_impulse: oj.data(),
            sticks: os.data(),
            stick_impulse: osp.data(),
        };
        let serial = || {
            (0..n.div_ceil(CHUNK)).find_map(|c| {
                self.rows(
                    &views,
                    settings.as_ref(),
                    columns,
                    c * CHUNK,
                    ((c + 1) * CHUNK).min(n),
                )
            })
        };
        let failure = if n >= PARALLEL_ROWS || settings.is_some() {
            // Without the GIL, holding read-only borrows of the inputs.
            let borrows = arrays
                .iter()
                .flatten()
                .map(|a| a.try_readonly())
                .collect::<Result<Vec<_>, _>>()?;
            let parallel = settings
                .as_ref()
                .is_none_or(|s| s.method() == Method::ClosedForm);
            let r = py.detach(|| {
                if parallel {
                    (0..n.div_ceil(CHUNK))
                        .into_par_iter()
                        .filter_map(|c| {
                            self.rows(
                                &views,
                                settings.as_ref(),
                                columns,
                                c * CHUNK,
                                ((c + 1) * CHUNK).min(n),
                            )
                        })
                        .min_by_key(|(i, _)| *i)
                } else {
                    serial()
                }
            });
            drop(borrows);
            r
        } else {
            serial()
        };
        drop(arrays);
        if let Some((i, f)) = failure {
            return Err(failure_error(i, f, false));
        }
        let d = PyDict::new(py);
        d.set_item(intern!(py, "v"), ov)?;
        d.set_item(intern!(py, "w"), ow)?;
        d.set_item(intern!(py, "impulse"), op)?;
        d.set_item(intern!(py, "tangential_impulse"), oj)?;
        d.set_item(intern!(py, "sticks"), os)?;
        d.set_item(intern!(py, "stick_impulse"), osp)?;
        Ok(d)
    }

    /// Mass m (kg).
    #[getter]
    fn mass(&self) -> f64 {
        self.ball.mass()
    }

    /// Radius r (m).
    #[getter]
    fn radius(&self) -> f64 {
        self.ball.radius()
    }

    /// I = alpha m r^2.
    #[getter]
    fn alpha(&self) -> f64 {
        self.ball.alpha()
    }

    /// Friction between ball and plane.
    #[getter]
    fn mu(&self) -> f64 {
        self.mu
    }

    /// Restitution e: P = (1 + e) m |v.n|.
    #[getter]
    fn restitution(&self) -> f64 {
        self.restitution
    }

    /// Pickling and copying: the keywords that built the model (the same numbers, so
    /// bit-identical results).
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        let kwargs = PyDict::new(py);
        kwargs.set_item("mass", self.ball.mass())?;
        kwargs.set_item("radius", self.ball.radius())?;
        kwargs.set_item("alpha", self.ball.alpha())?;
        kwargs.set_item("mu", self.mu)?;
        kwargs.set_item("restitution", self.restitution)?;
        if let Some(m) = self.mindlin {
            kwargs.set_item("tangential", "mindlin")?;
            kwargs.set_item("youngs_modulus", m.ball.youngs_modulus())?;
            kwargs.set_item("poisson_ratio", m.ball.poisson_ratio())?;
            if let Some(p) = m.plane {
                kwargs.set_item("plane_youngs_modulus", p.youngs_modulus())?;
                kwargs.set_item("plane_poisson_ratio", p.poisson_ratio())?;
            }
            if m.law.0 != Damping::None {
                kwargs.set_item("damping", m.law.0.name())?;
                kwargs.set_item("coefficient", m.coefficient)?;
                kwargs.set_item("at_speed", m.at_speed)?;
            }
        }
        Ok((PyTuple::empty(py), kwargs))
    }

    fn __eq__(&self, other: &Self) -> bool {
        (self.ball, self.mu, self.restitution, self.mindlin)
            == (other.ball, other.mu, other.restitution, other.mindlin)
    }

    fn __repr__(&self) -> String {
        let mut s = format!(
            "BallPlane(mass={:?}, radius={:?}, alpha={:?}, mu={:?}, restitution={:?}",
            self.ball.mass(),
            self.ball.radius(),
            self.ball.alpha(),
            self.mu,
            self.restitution
        );
        if let Some(m) = self.mindlin {
            s += &format!(
                ", tangential=\"mindlin\", youngs_modulus={:?}, poisson_ratio={:?}",
                m.ball.youngs_modulus(),
                m.ball.poisson_ratio()
            );
            if let Some(p) = m.plane {
                s += &format!(
                    ", plane_youngs_modulus={:?}, plane_poisson_ratio={:?}",
                    p.youngs_modulus(),
                    p.poisson_ratio()
                );
            }
            s += &damping_repr(m.law.0, m.coefficient, m.at_speed);
        }
        s + ")"
    }

    /// The tangential law: "rigid" (the stick rule) or "mindlin" (Mindlin's spring).
    #[getter]
    fn tangential(&self) -> &'static str {
        if self.mindlin.is_some() {
            "mindlin"
        } else {
            "rigid"
        }
    }
}
