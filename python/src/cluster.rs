//! `Cluster`: N balls that touch or come to touch, resolved together as one system
//! (docs/cluster.md): every pair's normal law from the balls' materials (or one given
//! stiffness), Coulomb friction with the stick rule at every contact, or Mindlin's
//! tangential spring (`tangential="mindlin"`).

use crate::ball::Ball;
use crate::errors::to_py;
use crate::inputs::float_array;
use billiard_contact::nalgebra::Vector3;
use billiard_contact::{
    resolve_cluster, Cluster as Kernel, ClusterBall, ClusterCloth, ClusterLaw, ClusterSettings,
    ClusterTangential, ContactLaw, Damping, Error, HertzContact, Material, PairDamping, StopReason,
    CLOTH_DEFAULT_GRAVITY, CLOTH_DEFAULT_MU,
};
use numpy::{PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

/// The argument names of `resolve`, in order.
const NAMES: [&str; 3] = ["positions", "velocities", "spins"];

/// Default relative tolerance of the step control (the library's default for clusters).
const DEFAULT_RTOL: f64 = billiard_contact::CLUSTER_DEFAULT_RTOL;

/// N balls resolved together: balls, a list of Ball (2 to 22; each its own mass, radius
/// and alpha); mu, Coulomb's friction at every contact (>= 0); the normal law of every
/// pair, Hertz's k = (4/3) E* sqrt(R*) from the balls' material, youngs_modulus (Pa) and
/// poisson_ratio (the same for every ball; phenolic resin: about 5.4e9 and 0.34), or one
/// stiffness (N/m^1.5) for every pair instead; damping None (elastic), "hunt-crossley"
/// or "kuwabara-kono", its coefficient (s/m or s) or, instead, the restitution a head-on
/// impact at at_speed (m/s, relative approach speed) has; stick: whether a contact whose
/// slip stops sticks (the stick rule, default True); tangential: "rigid" (default, Coulomb
/// with the stick rule) or "mindlin" (Mindlin's no-slip tangential spring under Coulomb's
/// cap at every contact, docs/cluster.md; it needs youngs_modulus and poisson_ratio);
/// cloth: None (free balls, default) or a dict with the scene's [cloth] keys,
/// "youngs_modulus" and "poisson_ratio" (the bed's material; required), "mu" (ball-cloth
/// friction, default 0.2), "height" (m, the cloth's z; default the first ball's z minus its
/// radius at each resolve) and "gravity" (m/s^2 along -z, default 9.81): every ball then
/// rests on the cloth (docs/cluster.md, "The cloth").
///
/// The keyword names are the scene file's: [balls] youngs_modulus and poisson_ratio,
/// [contact.law] stiffness, damping, coefficient, restitution and at_speed. A calibrated
/// damping is solved here, once per kind of pair (a head-on run each); balls that are not
/// all identical are calibrated again on every resolve.
///
/// Bad values raise ValueError naming the keyword, e.g. "mu = -1: finite, in [0, 1e6]".
#[pyclass(frozen, module = "billiard_contact._core", name = "Cluster")]
pub struct Cluster {
    balls: Vec<Ball>,
    mu: f64,
    youngs_modulus: Option<f64>,
    poisson_ratio: Option<f64>,
    stiffness: Option<f64>,
    damping: Option<String>,
    coefficient: Option<f64>,
    restitution: Option<f64>,
    at_speed: Option<f64>,
    stick: bool,
    /// "rigid" or "mindlin".
    tangential: String,
    /// The cloth the balls rest on, if any.
    cloth: Option<ClothSpec>,
    /// The law of every pair (calibrations done once, here).
    law: ClusterLaw,
}

/// The `cloth=` keyword's dict, checked.
#[derive(Debug, Clone, PartialEq)]
struct ClothSpec {
    material: Material,
    mu: f64,
    height: Option<f64>,
    gravity: f64,
    /// The damping keys as given ("damping" by its name).
    damping: Option<String>,
    coefficient: Option<f64>,
    restitution: Option<f64>,
    at_speed: Option<f64>,
    /// The damping they give (elastic by default).
    pair: PairDamping,
}

/// The keys of the `cloth=` dict (the scene's [cloth] keys).
const CLOTH_KEYS: [&str; 9] = [
    "youngs_modulus",
    "poisson_ratio",
    "mu",
    "height",
    "gravity",
    "damping",
    "coefficient",
    "restitution",
    "at_speed",
];

impl ClothSpec {
    /// From the `cloth=` dict: unknown keys, missing material, bad numbers raise ValueError
    /// naming "cloth.<key>"; the rest is checked where the kernel builds the cloth.
    fn from_dict(d: &Bound<'_, PyAny>) -> PyResult<Self> {
        let d = d
            .cast::<PyDict>()
            .map_err(|_| PyTypeError::new_err("cloth: expected a dict (or None)"))?;
        for k in d.keys() {
            let k: String = k
                .extract()
                .map_err(|_| PyTypeError::new_err("cloth: keys are strings"))?;
            if !CLOTH_KEYS.contains(&k.as_str()) {
                return Err(bad(
                    &format!("cloth.{k}"),
                    "an unknown key",
                    &format!("one of {}", CLOTH_KEYS.join(", ")),
                ));
            }
        }
        let get = |k: &str| -> PyResult<Option<f64>> {
            match d.get_item(k)? {
                None => Ok(None),
                Some(v) if v.is_none() => Ok(None),
                Some(v) => v
                    .extract::<f64>()
                    .map(Some)
                    .map_err(|_| PyTypeError::new_err(format!("cloth.{k}: expected a number"))),
            }
        };
        let need = |k: &str| -> PyResult<f64> {
            get(k)?.ok_or_else(|| {
                bad(
                    &format!("cloth.{k}"),
                    "missing",
                    "youngs_modulus (Pa) and poisson_ratio of the bed (slate: about 5e10 and \
                     0.25)",
                )
            })
        };
        let material =
            Material::in_section("cloth", need("youngs_modulus")?, need("poisson_ratio")?)
                .map_err(to_py)?;
        let damping: Option<String> = match d.get_item("damping")? {
            None => None,
            Some(v) if v.is_none() => None,
            Some(v) => Some(v.extract().map_err(|_| {
                PyTypeError::new_err(
                    "cloth.damping: expected None, \"hunt-crossley\" or \"kuwabara-kono\"",
                )
            })?),
        };
        let law = damping_of(damping.as_deref()).map_err(|e| {
            bad(
                "cloth.damping",
                format!("{:?}", damping.as_deref().unwrap_or("")),
                &match e {
                    Error::InvalidParameter { expected, .. } => expected,
                    e => e.to_string(),
                },
            )
        })?;
        let (coefficient, restitution, at_speed) =
            (get("coefficient")?, get("restitution")?, get("at_speed")?);
        let pair = pair_damping_of("cloth.", law, coefficient, restitution, at_speed)?;
        Ok(ClothSpec {
            material,
            mu: get("mu")?.unwrap_or(CLOTH_DEFAULT_MU),
            height: get("height")?,
            gravity: get("gravity")?.unwrap_or(CLOTH_DEFAULT_GRAVITY),
            damping,
            coefficient,
            restitution,
            at_speed,
            pair,
        })
    }

    /// The dict again (every key, the defaults written out; height only when given).
    fn as_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("youngs_modulus", self.material.youngs_modulus())?;
        d.set_item("poisson_ratio", self.material.poisson_ratio())?;
        d.set_item("mu", self.mu)?;
        if let Some(h) = self.height {
            d.set_item("height", h)?;
        }
        d.set_item("gravity", self.gravity)?;
        if let Some(name) = &self.damping {
            d.set_item("damping", name)?;
        }
        for (k, x) in [
            ("coefficient", self.coefficient),
            ("restitution", self.restitution),
            ("at_speed", self.at_speed),
        ] {
            if let Some(x) = x {
                d.set_item(k, x)?;
            }
        }
        Ok(d)
    }

    /// The kernel's cloth for balls whose first is `first`.
    fn cloth(&self, first: &ClusterBall) -> ClusterCloth {
        ClusterCloth {
            height: self
                .height
                .unwrap_or(first.position.z - first.ball.radius()),
            material: self.material,
            mu: self.mu,
            gravity: self.gravity,
        }
    }
}

/// `e` with the library's `cluster.` and `contact.law.` prefixes taken off its field:
/// the keywords are the bare names.
fn keyword(e: Error) -> Error {
    match e {
        Error::InvalidParameter {
            field,
            value,
            expected,
        } => {
            // Hertz's contact time out of the doubles' range comes from the material.
            let field = if field == "contact.profile.duration" {
                "youngs_modulus, poisson_ratio".to_string()
            } else {
                field
            };
            let bare = ["cluster.", "contact.law.", "balls."]
                .iter()
                .find_map(|p| field.strip_prefix(p))
                .map(|s| s.replace(", cluster.", ", "))
                .unwrap_or(field);
            Error::InvalidParameter {
                field: bare,
                value,
                expected,
            }
        }
        other => other,
    }
}

fn bad(field: &str, value: impl std::fmt::Display, expected: &str) -> PyErr {
    to_py(Error::invalid(field, value, expected))
}

/// The damping law named `name` (None: elastic), as the `damping=` keyword takes it.
pub(crate) fn damping_of(name: Option<&str>) -> Result<Damping, Error> {
    match name {
        None | Some("none") => Ok(Damping::None),
        Some("hunt-crossley") => Ok(Damping::HuntCrossley),
        Some("kuwabara-kono") => Ok(Damping::KuwabaraKono),
        Some(other) => Err(Error::invalid(
            "damping",
            format!("{other:?}"),
            "None, \"hunt-crossley\" or \"kuwabara-kono\"",
        )),
    }
}

/// The damping of a law from the keywords `damping`, `coefficient`, `restitution` and
/// `at_speed` (refused as the scene file's are: the coefficient or the restitution with
/// its speed), their names prefixed by `p` in errors ("" for the pairs, "cloth." for the
/// cloth's dict).
fn pair_damping_of(
    p: &str,
    damping: Damping,
    coefficient: Option<f64>,
    restitution: Option<f64>,
    at_speed: Option<f64>,
) -> PyResult<PairDamping> {
    let calibration = match (coefficient, restitution, at_speed) {
        (Some(_), Some(_), _) => {
            return Err(bad(
                &format!("{p}coefficient, {p}restitution"),
                "both given",
                "the coefficient or the restitution (with at_speed), not both",
            ))
        }
        (_, Some(_), None) | (_, None, Some(_)) => {
            return Err(bad(
                &format!("{p}restitution, {p}at_speed"),
                "one given without the other",
                "restitution and at_speed together",
            ))
        }
        (_, Some(e), Some(v)) => Some((e, v)),
        (_, None, None) => None,
    };
    if damping == Damping::None && coefficient.is_some() {
        return Err(bad(
            &format!("{p}coefficient"),
            "given with damping None",
            "no coefficient for elastic Hertz; name a damping law",
        ));
    }
    Ok(match (coefficient, calibration) {
        (Some(c), _) => PairDamping::Coefficient(damping, c),
        (None, Some((e, v))) => PairDamping::Restitution {
            damping,
            restitution: e,
            at_speed: v,
        },
        (None, None) if damping == Damping::None => PairDamping::None,
        (None, None) => {
            return Err(bad(
                &format!("{p}damping"),
                format!(
                    "{:?} without a coefficient or a restitution",
                    damping.name()
                ),
                "coefficient=, or restitution= with at_speed=",
            ))
        }
    })
}

/// The law of every pair from the keywords, refused as the scene file's `[contact.law]`
/// is: exactly one of the stiffness or the material, the coefficient or the restitution
/// with its speed.
#[allow(clippy::too_many_arguments)]
fn law_of(
    balls: &[Ball],
    youngs_modulus: Option<f64>,
    poisson_ratio: Option<f64>,
    stiffness: Option<f64>,
    damping: Damping,
    coefficient: Option<f64>,
    restitution: Option<f64>,
    at_speed: Option<f64>,
    mindlin: bool,
) -> PyResult<ClusterLaw> {
    let material = match (youngs_modulus, poisson_ratio) {
        (Some(e), Some(nu)) => Some(Material::new(e, nu).map_err(|e| to_py(keyword(e)))?),
        (None, None) => None,
        (Some(_), None) => {
            return Err(bad(
                "youngs_modulus",
                "given without poisson_ratio",
                "both youngs_modulus and poisson_ratio, or neither",
            ))
        }
        (None, Some(_)) => {
            return Err(bad(
                "poisson_ratio",
                "given without youngs_modulus",
                "both youngs_modulus and poisson_ratio, or neither",
            ))
        }
    };
    let pair_damping = pair_damping_of("", damping, coefficient, restitution, at_speed)?;
    match (stiffness, material) {
        (Some(_), Some(_)) => Err(bad(
            "stiffness",
            "given with youngs_modulus and poisson_ratio",
            "the stiffness or the material, not both",
        )),
        (None, None) => Err(bad(
            "youngs_modulus",
            "not given (nor stiffness)",
            "youngs_modulus and poisson_ratio, or stiffness",
        )),
        (None, Some(m)) => {
            // Each distinct pair's law, built (and its calibration checked) here, once: for
            // identical balls that one law is every pair's (the kernel would build the same
            // law from the materials, on every resolve).
            let mut laws: Vec<(billiard_contact::Ball, billiard_contact::Ball, ContactLaw)> =
                Vec::new();
            for (i, a) in balls.iter().enumerate() {
                for b in &balls[i + 1..] {
                    let (a, b) = (a.ball, b.ball);
                    if laws.iter().any(|l| (l.0, l.1) == (a, b)) {
                        continue;
                    }
                    let k = HertzContact::between((&a, &m), (&b, &m), 1.0)
                        .map_err(|e| to_py(keyword(e)))?
                        .stiffness;
                    let reduced = a.mass() * b.mass() / (a.mass() + b.mass());
                    let law = pair_damping
                        .law(k, reduced)
                        .map_err(|e| to_py(keyword(e)))?;
                    laws.push((a, b, law));
                }
            }
            // Mindlin's spring and the cloth need the materials themselves (the shear
            // modulus; the ball's share of the cloth contact's E*).
            Ok(match laws.as_slice() {
                [(_, _, law)] if !mindlin => ClusterLaw::Same(*law),
                _ => ClusterLaw::Materials(vec![m; balls.len()], pair_damping),
            })
        }
        (Some(k), None) => {
            let kinds: Vec<billiard_contact::Ball> = balls.iter().map(|b| b.ball).collect();
            ClusterLaw::same_stiffness(k, pair_damping, &kinds).map_err(|e| to_py(keyword(e)))
        }
    }
}

/// An (N, 3) float array's rows.
fn rows(name: &str, ob: &Bound<'_, PyAny>) -> PyResult<Vec<Vector3<f64>>> {
    let a = float_array(name, ob)?;
    let shape = a.shape().to_vec();
    if shape.len() != 2 || shape[1] != 3 {
        return Err(PyValueError::new_err(format!(
            "{name}: shape {shape:?}: an (N, 3) array, a row per ball"
        )));
    }
    let ro = a.try_readonly()?;
    let view = ro.as_array();
    Ok((0..shape[0])
        .map(|i| Vector3::new(view[[i, 0]], view[[i, 1]], view[[i, 2]]))
        .collect())
}

fn stop_name(s: StopReason) -> &'static str {
    match s {
        StopReason::Separated => "separated",
        StopReason::WorkBound => "work-bound",
        StopReason::StepTooSmall => "step-too-small",
    }
}

#[pymethods]
impl Cluster {
    #[new]
    #[pyo3(signature = (*, balls, mu, youngs_modulus = None, poisson_ratio = None,
                        stiffness = None, damping = None, coefficient = None,
                        restitution = None, at_speed = None, stick = true,
                        tangential = "rigid".to_string(), cloth = None),
           text_signature = "(*, balls, mu, youngs_modulus=None, poisson_ratio=None, \
                             stiffness=None, damping=None, coefficient=None, \
                             restitution=None, at_speed=None, stick=True, tangential='rigid', \
                             cloth=None)")]
    #[allow(clippy::too_many_arguments)]
    fn new(
        balls: &Bound<'_, PyAny>,
        #[pyo3(from_py_with = crate::args::mu)] mu: f64,
        #[pyo3(from_py_with = crate::args::youngs_modulus)] youngs_modulus: Option<f64>,
        #[pyo3(from_py_with = crate::args::poisson_ratio)] poisson_ratio: Option<f64>,
        #[pyo3(from_py_with = crate::args::stiffness)] stiffness: Option<f64>,
        #[pyo3(from_py_with = crate::args::damping)] damping: Option<String>,
        #[pyo3(from_py_with = crate::args::coefficient)] coefficient: Option<f64>,
        #[pyo3(from_py_with = crate::args::restitution_or_none)] restitution: Option<f64>,
        #[pyo3(from_py_with = crate::args::at_speed)] at_speed: Option<f64>,
        #[pyo3(from_py_with = crate::args::stick)] stick: bool,
        #[pyo3(from_py_with = crate::args::tangential)] tangential: String,
        cloth: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let cloth = match cloth {
            Some(c) if !c.is_none() => Some(ClothSpec::from_dict(c)?),
            _ => None,
        };
        let mindlin = match tangential.as_str() {
            "rigid" => false,
            "mindlin" => true,
            other => {
                return Err(bad(
                    "tangential",
                    format!("{other:?}"),
                    "\"rigid\" (the stick rule) or \"mindlin\" (Mindlin's tangential spring)",
                ))
            }
        };
        if mindlin && (youngs_modulus.is_none() || poisson_ratio.is_none()) {
            return Err(bad(
                "youngs_modulus, poisson_ratio",
                "not given with tangential=\"mindlin\"",
                "the balls' material (Mindlin's spring and Hertz's force need it)",
            ));
        }
        let balls: Vec<Ball> = balls
            .try_iter()
            .map_err(|_| PyTypeError::new_err("balls: expected a list of Ball"))?
            .map(|b| {
                b.and_then(|b| {
                    b.cast::<Ball>()
                        .map(|b| *b.get())
                        .map_err(|_| PyTypeError::new_err("balls: expected a list of Ball"))
                })
            })
            .collect::<PyResult<_>>()?;
        let n = balls.len();
        if !(2..=billiard_contact::MAX_CLUSTER_BALLS).contains(&n) {
            return Err(bad(
                "balls",
                format!("{n} balls"),
                &format!("2 to {} balls", billiard_contact::MAX_CLUSTER_BALLS),
            ));
        }
        if !(mu.is_finite() && (0.0..=1e6).contains(&mu)) {
            return Err(bad(
                "mu",
                mu,
                "finite, in [0, 1e6] (Coulomb's friction coefficient)",
            ));
        }
        let law = law_of(
            &balls,
            youngs_modulus,
            poisson_ratio,
            stiffness,
            damping_of(damping.as_deref()).map_err(to_py)?,
            coefficient,
            restitution,
            at_speed,
            mindlin || cloth.is_some(),
        )?;
        if cloth.is_some() && mindlin {
            return Err(bad(
                "cloth",
                "given with tangential=\"mindlin\"",
                "tangential=\"rigid\" with a cloth (its contacts carry Coulomb's friction \
                 with the stick rule)",
            ));
        }
        Ok(Cluster {
            balls,
            mu,
            youngs_modulus,
            poisson_ratio,
            stiffness,
            damping,
            coefficient,
            restitution,
            at_speed,
            stick,
            tangential,
            cloth,
            law,
        })
    }

    /// Resolves the balls from the given state to the end of every contact.
    ///
    /// positions (m), velocities (m/s), spins (rad/s): (N, 3) arrays (lists work too), a
    /// row per ball in the order of `balls`. Balls may touch (within 1e-9 of r_i + r_j)
    /// or stand apart and come to touch; at least one pair must approach. rtol: relative
    /// tolerance of the step control (default 1e-8).
    ///
    /// Returns a dict: "velocities" and "spins" ((N, 3) after the last contact opened),
    /// "positions" ((N, 3) when the run ended), "contacts" (a list with one dict per
    /// contact that carried force, in the order they opened again: "pair" (i, j), i < j,
    /// "impulse" (normal impulse on ball j, N s), "friction_impulse" (on ball i, (3,),
    /// N s), "normal" (from i to j), "start" and "duration" (s), "heat" (J) and
    /// "stick_time" (s from its closing, or None)), "time" (s covered), "steps" and
    /// "evaluations"; with a cloth also "cloth_contacts" (one dict per ball's contact with
    /// it) and "cloth_held" (J: what the cloth's spring and gravity hold at the end, so that
    /// the kinetic energy in is the kinetic energy out plus every heat plus it). A run that
    /// cannot finish (the step control stalls or the work bound
    /// is reached) raises RuntimeError; nothing partial is returned.
    #[pyo3(signature = (positions, velocities, spins, rtol = None))]
    fn resolve<'py>(
        &self,
        py: Python<'py>,
        positions: &Bound<'py, PyAny>,
        velocities: &Bound<'py, PyAny>,
        spins: &Bound<'py, PyAny>,
        #[pyo3(from_py_with = crate::args::rtol)] rtol: Option<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let [p, v, w] = [
            rows(NAMES[0], positions)?,
            rows(NAMES[1], velocities)?,
            rows(NAMES[2], spins)?,
        ];
        let n = self.balls.len();
        for (name, r) in NAMES.iter().zip([&p, &v, &w]) {
            if r.len() != n {
                return Err(PyValueError::new_err(format!(
                    "{name}: {} rows: a row per ball ({n})",
                    r.len()
                )));
            }
        }
        let balls: Vec<ClusterBall> = (0..n)
            .map(|i| ClusterBall {
                ball: self.balls[i].ball,
                position: p[i],
                velocity: v[i],
                spin: w[i],
            })
            .collect();
        let settings = ClusterSettings {
            rtol: rtol.unwrap_or(DEFAULT_RTOL),
            stick: self.stick,
        };
        let law = self.law.clone();
        let mu = self.mu;
        let tangential = if self.tangential == "mindlin" {
            ClusterTangential::Mindlin
        } else {
            ClusterTangential::Rigid
        };
        let cloth = self.cloth.as_ref().map(|c| (c.cloth(&balls[0]), c.pair));
        let (out, held) = py
            .detach(move || {
                let mut cluster = Kernel::new(balls, law, mu)?.with_tangential(tangential)?;
                if let Some((c, damping)) = cloth {
                    cluster = cluster.with_cloth(c)?;
                    if damping != PairDamping::None {
                        cluster = cluster.with_cloth_damping(damping)?;
                    }
                }
                let out = resolve_cluster(&cluster, &settings)?;
                let held = out.cloth_held(&cluster);
                Ok::<_, Error>((out, held))
            })
            .map_err(|e| to_py(keyword(e)))?;
        if out.stop != StopReason::Separated {
            return Err(PyRuntimeError::new_err(format!(
                "the cluster's run stopped ({}) at t = {:e} s after {} steps with contacts \
                 still compressed or closing; a looser rtol, or fewer balls at once",
                stop_name(out.stop),
                out.time,
                out.stats.steps
            )));
        }
        let matrix = |f: &dyn Fn(usize) -> Vector3<f64>| -> PyResult<Bound<'py, PyArray2<f64>>> {
            let flat: Vec<f64> = (0..n).flat_map(|i| <[f64; 3]>::from(f(i))).collect();
            numpy::PyArray1::from_vec(py, flat).reshape([n, 3])
        };
        let d = PyDict::new(py);
        d.set_item("velocities", matrix(&|i| out.balls[i].velocity)?)?;
        d.set_item("spins", matrix(&|i| out.balls[i].spin)?)?;
        d.set_item("positions", matrix(&|i| out.balls[i].position)?)?;
        let contacts = PyList::empty(py);
        for c in &out.contacts {
            let e = PyDict::new(py);
            e.set_item("pair", PyTuple::new(py, [c.pair.0, c.pair.1])?)?;
            e.set_item("impulse", c.normal_impulse)?;
            e.set_item(
                "friction_impulse",
                numpy::PyArray1::from_slice(py, c.friction_impulse.as_slice()),
            )?;
            e.set_item(
                "normal",
                numpy::PyArray1::from_slice(py, c.normal.as_slice()),
            )?;
            e.set_item("start", c.start)?;
            e.set_item("duration", c.duration)?;
            e.set_item("heat", c.heat)?;
            e.set_item("stick_time", c.stick_time)?;
            contacts.append(e)?;
        }
        d.set_item("contacts", contacts)?;
        if self.cloth.is_some() {
            let cloth = PyList::empty(py);
            for c in &out.cloth {
                let e = PyDict::new(py);
                e.set_item("ball", c.pair.0)?;
                e.set_item("impulse", c.normal_impulse)?;
                e.set_item(
                    "friction_impulse",
                    numpy::PyArray1::from_slice(py, c.friction_impulse.as_slice()),
                )?;
                e.set_item("start", c.start)?;
                e.set_item("duration", c.duration)?;
                e.set_item("heat", c.heat)?;
                e.set_item("stick_time", c.stick_time)?;
                cloth.append(e)?;
            }
            d.set_item("cloth_contacts", cloth)?;
            d.set_item("cloth_held", held)?;
        }
        d.set_item("time", out.time)?;
        d.set_item("steps", out.stats.steps)?;
        d.set_item("evaluations", out.stats.evaluations)?;
        Ok(d)
    }

    /// The balls.
    #[getter]
    fn balls(&self) -> Vec<Ball> {
        self.balls.clone()
    }

    /// Coulomb's mu at every contact.
    #[getter]
    fn mu(&self) -> f64 {
        self.mu
    }

    /// Pickling and copying: the keywords again (the same numbers, so the same model).
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        let kwargs = PyDict::new(py);
        kwargs.set_item("balls", self.balls.clone())?;
        kwargs.set_item("mu", self.mu)?;
        kwargs.set_item("youngs_modulus", self.youngs_modulus)?;
        kwargs.set_item("poisson_ratio", self.poisson_ratio)?;
        kwargs.set_item("stiffness", self.stiffness)?;
        kwargs.set_item("damping", self.damping.clone())?;
        kwargs.set_item("coefficient", self.coefficient)?;
        kwargs.set_item("restitution", self.restitution)?;
        kwargs.set_item("at_speed", self.at_speed)?;
        kwargs.set_item("stick", self.stick)?;
        kwargs.set_item("tangential", &self.tangential)?;
        match &self.cloth {
            Some(c) => kwargs.set_item("cloth", c.as_dict(py)?)?,
            None => kwargs.set_item("cloth", py.None())?,
        }
        Ok((PyTuple::empty(py), kwargs))
    }

    fn __eq__(&self, other: &Self) -> bool {
        self.balls
            .iter()
            .map(|b| b.ball)
            .eq(other.balls.iter().map(|b| b.ball))
            && (self.mu, self.stick) == (other.mu, other.stick)
            && self.tangential == other.tangential
            && self.cloth == other.cloth
            && self.law == other.law
    }

    fn __repr__(&self) -> String {
        let balls: Vec<String> = self.balls.iter().map(Ball::__repr__).collect();
        let mut s = format!("Cluster(balls=[{}], mu={:?}", balls.join(", "), self.mu);
        for (k, x) in [
            ("youngs_modulus", self.youngs_modulus),
            ("poisson_ratio", self.poisson_ratio),
            ("stiffness", self.stiffness),
        ] {
            if let Some(x) = x {
                s += &format!(", {k}={x:?}");
            }
        }
        if let Some(d) = &self.damping {
            s += &format!(", damping={d:?}");
        }
        for (k, x) in [
            ("coefficient", self.coefficient),
            ("restitution", self.restitution),
            ("at_speed", self.at_speed),
        ] {
            if let Some(x) = x {
                s += &format!(", {k}={x:?}");
            }
        }
        if !self.stick {
            s += ", stick=False";
        }
        if self.tangential != "rigid" {
            s += &format!(", tangential={:?}", self.tangential);
        }
        if let Some(c) = &self.cloth {
            s += &format!(
                ", cloth={{'youngs_modulus': {:?}, 'poisson_ratio': {:?}, 'mu': {:?}",
                c.material.youngs_modulus(),
                c.material.poisson_ratio(),
                c.mu
            );
            if let Some(h) = c.height {
                s += &format!(", 'height': {h:?}");
            }
            s += &format!(", 'gravity': {:?}", c.gravity);
            if let Some(name) = &c.damping {
                s += &format!(", 'damping': '{name}'");
            }
            for (k, x) in [
                ("coefficient", c.coefficient),
                ("restitution", c.restitution),
                ("at_speed", c.at_speed),
            ] {
                if let Some(x) = x {
                    s += &format!(", '{k}': {x:?}");
                }
            }
            s += "}";
        }
        s + ")"
    }
}
