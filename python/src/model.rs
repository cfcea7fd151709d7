//! `BallBall`: two balls and their contact, built with the library's scene builder, and
//! `BallBall.resolve_lab`: many lab-frame collisions from numpy arrays, in Rust, without the
//! GIL. The numpy arrays are read in place and the results written straight into the
//! output arrays by the library's `batch::resolve_lab_into` (the change of frame, the
//! method and the throw angle are the library's, as for the command line's lab-frame
//! batch rows).

use crate::ball::Ball;
use crate::compliant_pair::{DampingKeywords, PairMindlin};
use crate::errors::to_py;
use crate::friction::Mu;
use crate::inputs::{float_array, shaped, with_argument_names};
use crate::outputs::{resolve_checked, single_collision, Outputs, RowFailure, PER_CHUNK};
use crate::plane::damping_repr;
use crate::settings;
use billiard_contact::batch::{resolve_lab_into, BatchSetup, PARALLEL_LAB_ROWS};
use billiard_contact::nalgebra::Vector3;
use billiard_contact::{BallPair, Damping, Error, Friction, Method, Scene};
use numpy::PyArrayMethods;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use std::sync::atomic::Ordering;

use billiard_contact::profile::{ProfileKind, ProfileSpec};
use billiard_contact::{CmState, Effects, ForceSpec, Incoming, SceneBuilder};

/// Two balls and their contact: two identical balls of mass (kg), radius (m) and alpha
/// (I = alpha m r^2, default 0.4), or balls of their own, a=Ball(...) and b=Ball(...)
/// (different mass, size or inertia); ball-ball friction mu (a number, or
/// SpeedDependentFriction), restitution e (P = (1 + e) m* v_n with the reduced mass
/// m* = m_A m_B / (m_A + m_B) and the relative approach speed v_n; (1 + e) m U(0) for
/// identical balls), the normal-force profile and its duration (s; used by the
/// time-stepping methods and for stick times; the closed form does not depend on them),
/// and the effects `friction` and `stick`.
///
/// `tangential="mindlin"` with the balls' material (`youngs_modulus` in Pa,
/// `poisson_ratio`) resolves each collision compliantly instead: Hertz's normal
/// force and Mindlin's tangential spring (its stiffness times `shear_stiffness_factor`,
/// default 1) under Coulomb's cap, stepped through the contact (docs/tangential.md#two-spheres);
/// mu a number. Hertz's force is elastic (restitution 1) unless `damping` is
/// "hunt-crossley" or "kuwabara-kono" (docs/contact-law.md), with its `coefficient` (beta
/// in s/m or gamma in s; restitution left at 1) or calibrated so that a head-on impact at
/// the relative approach speed `at_speed` (m/s) rebounds with `restitution`, on the pair's
/// Hertz stiffness and reduced mass m* = m_A m_B / (m_A + m_B), as `BallPlane` does.
///
/// Bad values raise ValueError with the command line's message, e.g.
/// "balls.mass = -1: > 0 kg".
#[pyclass(frozen, module = "billiard_contact._core", name = "BallBall")]
pub struct BallBall {
    scene: Scene,
    /// The closed form over this model (resolve_lab's default).
    closed_form: BatchSetup,
    /// Given as a=Ball(...), b=Ball(...) (else mass, radius, alpha).
    by_ball: bool,
    mu: Mu,
    restitution: f64,
    profile: String,
    duration: f64,
    friction: bool,
    stick: bool,
    /// The tangential law: `None` the rigid stick rule (eqs 24-35), else Mindlin's spring.
    mindlin: Option<PairMindlin>,
}

impl BallBall {
    /// The ball both A and B are, when they are identical.
    fn shared(&self) -> Option<billiard_contact::Ball> {
        let BallPair { a, b } = self.scene.balls;
        (a == b).then_some(a)
    }
}

#[pymethods]
impl BallBall {
    #[new]
    #[pyo3(signature = (*, mass = None, radius = None, alpha = None, a = None, b = None, mu,
                        restitution = 1.0, profile = "half-sine".to_string(), duration = 2.5e-4,
                        friction = true, stick = true, tangential = "rigid".to_string(),
                        youngs_modulus = None, poisson_ratio = None,
                        shear_stiffness_factor = None, damping = None, coefficient = None,
                        at_speed = None),
           text_signature = "(*, mass=None, radius=None, alpha=None, a=None, b=None, mu, \
                             restitution=1.0, profile='half-sine', duration=0.00025, \
                             friction=True, stick=True, tangential='rigid', \
                             youngs_modulus=None, poisson_ratio=None, \
                             shear_stiffness_factor=None, damping=None, coefficient=None, \
                             at_speed=None)")]
    #[allow(clippy::too_many_arguments)]
    fn new(
        #[pyo3(from_py_with = crate::args::mass_or_none)] mass: Option<f64>,
        #[pyo3(from_py_with = crate::args::radius_or_none)] radius: Option<f64>,
        #[pyo3(from_py_with = crate::args::alpha_or_none)] alpha: Option<f64>,
        #[pyo3(from_py_with = crate::args::a_ball)] a: Option<Ball>,
        #[pyo3(from_py_with = crate::args::b_ball)] b: Option<Ball>,
        mu: Mu,
        #[pyo3(from_py_with = crate::args::restitution)] restitution: f64,
        #[pyo3(from_py_with = crate::args::profile)] profile: String,
        #[pyo3(from_py_with = crate::args::duration)] duration: f64,
        #[pyo3(from_py_with = crate::args::friction)] friction: bool,
        #[pyo3(from_py_with = crate::args::stick)] stick: bool,
        #[pyo3(from_py_with = crate::args::tangential)] tangential: String,
        #[pyo3(from_py_with = crate::args::youngs_modulus)] youngs_modulus: Option<f64>,
        #[pyo3(from_py_with = crate::args::poisson_ratio)] poisson_ratio: Option<f64>,
        #[pyo3(from_py_with = crate::args::shear_stiffness_factor)] shear_stiffness_factor: Option<
            f64,
        >,
        #[pyo3(from_py_with = crate::args::damping)] damping: Option<String>,
        #[pyo3(from_py_with = crate::args::coefficient)] coefficient: Option<f64>,
        #[pyo3(from_py_with = crate::args::at_speed)] at_speed: Option<f64>,
    ) -> PyResult<Self> {
        let profile = profile.as_str();
        // The model is a scene (with a placeholder incoming state): the library's scene
        // builder validates every parameter and names it as a scene file does.
        let balls = SceneBuilder::balls(
            [mass, radius, alpha],
            a.map(|x| Ok(x.ball)),
            b.map(|x| Ok(x.ball)),
        )
        .map_err(to_py)?;
        let friction_law = match mu {
            Mu::Constant(x) => Friction::constant(x).map_err(to_py)?,
            Mu::Speed(s) => s.friction,
        };
        let force = profile_spec(profile, duration).map_err(to_py)?;
        let placeholder = CmState::new(Vector3::x(), Vector3::zeros(), Vector3::zeros());
        let scene = SceneBuilder::new(balls, friction_law, Incoming::Cm(placeholder))
            .name("BallBall")
            .restitution(restitution)
            .force(ForceSpec::Profile(force))
            .effects(Effects {
                friction,
                stick,
                ..Effects::default()
            })
            .build()
            .map_err(to_py)?;
        let closed_form = BatchSetup::from_scene(
            &scene,
            settings::for_batch(None, None, None).map_err(to_py)?,
        );
        let mindlin = mindlin_of(
            &scene.balls,
            &tangential,
            mu,
            [friction, stick],
            [youngs_modulus, poisson_ratio, shear_stiffness_factor],
            DampingKeywords {
                damping: damping.as_deref(),
                coefficient,
                restitution,
                at_speed,
            },
        )
        .map_err(to_py)?;
        Ok(BallBall {
            scene,
            closed_form,
            by_ball: a.is_some() || b.is_some(),
            mu,
            restitution,
            profile: profile.to_string(),
            duration,
            friction,
            stick,
            mindlin,
        })
    }

    /// Resolves collisions given in the lab frame.
    ///
    /// pa, va, wa, pb, vb, wb: positions (m), velocities (m/s) and spins (rad/s) of
    /// balls A and B, each of shape (3,) or (N, 3) (any memory order; lists work too; a
    /// (3,) array is used for every row; float, integer and bool dtypes are converted to
    /// float64, complex, object, string and other dtypes raise TypeError naming the
    /// argument). up: the direction away from the table (need
    /// not be unit), (3,) or (N, 3), default (0, 0, 1). The centres must touch:
    /// |pb - pa| = 2 radius (r_A + r_B) within a relative 1e-9.
    ///
    /// method: None (the closed form), "closed-form", "rk4", "dopri5" or "dop853";
    /// rtol: relative tolerance of the adaptive methods (atol = rtol), default 1e-10;
    /// time_transform: whether the time-stepping methods integrate in the smoothing
    /// change of time variable (the library's default, True; it acts on the "hertz" and
    /// "sine-power" profiles).
    ///
    /// Returns a dict of numpy arrays: "va", "wa", "vb", "wb" (outgoing velocities, m/s,
    /// and spins, rad/s; the input's shape), "impulse" (normal impulse P, N s),
    /// "tangential_impulse" (J, N s), "sticks" (bool: sliding stopped during contact),
    /// "throw_angle_deg" (degrees, counter-clockwise about up, from the line of centres
    /// to B's horizontal velocity change; NaN where the library has none: B's horizontal
    /// velocity change vanishes, or the line of centres is vertical), each of shape (N,),
    /// or for one collision a numpy scalar
    /// (np.float64, np.bool_: shape (), as numpy's own reductions return).
    ///
    /// Bad input raises ValueError naming the row and the field, with the command
    /// line's wording; so does a collision whose result overflows double precision
    /// ("row 3: va[0] = -inf: the result is not finite ...": no output is ever inf or
    /// NaN, but for the throw angle where it is undefined). N >= 2048 rows are resolved on all cores without the GIL.
    #[pyo3(signature = (pa, va, wa, pb, vb, wb, up = None, method = None, rtol = None,
                        time_transform = None))]
    #[allow(clippy::too_many_arguments)]
    fn resolve_lab<'py>(
        &self,
        py: Python<'py>,
        pa: &Bound<'py, PyAny>,
        va: &Bound<'py, PyAny>,
        wa: &Bound<'py, PyAny>,
        pb: &Bound<'py, PyAny>,
        vb: &Bound<'py, PyAny>,
        wb: &Bound<'py, PyAny>,
        up: Option<&Bound<'py, PyAny>>,
        #[pyo3(from_py_with = crate::args::method)] method: Option<String>,
        #[pyo3(from_py_with = crate::args::rtol)] rtol: Option<f64>,
        #[pyo3(from_py_with = crate::args::time_transform)] time_transform: Option<bool>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let method = method.as_deref();
        let arrays = [
            Some(float_array("pa", pa)?),
            Some(float_array("va", va)?),
            Some(float_array("wa", wa)?),
            Some(float_array("pb", pb)?),
            Some(float_array("vb", vb)?),
            Some(float_array("wb", wb)?),
            up.map(|u| float_array("up", u)).transpose()?,
        ];
        let (inputs, n, single) = shaped(&arrays)?;
        if let Some(mindlin) = self.mindlin {
            let refused = match (method, up.is_some(), time_transform) {
                (Some(m), _, _) => Some(("method", format!("{m:?}"))),
                (_, true, _) => Some(("up", "given".to_string())),
                (_, _, Some(t)) => Some(("time_transform", format!("{t}"))),
                _ => None,
            };
            if let Some((name, value)) = refused {
                return Err(to_py(Error::invalid(
                    name,
                    value,
                    "None with tangential=\"mindlin\" (the compliant contact steps with its \
                     own Dormand-Prince 5(4), rtol= its tolerance, and reports no throw angle)",
                )));
            }
            let settings = settings::for_batch(Some("dopri5"), rtol, None).map_err(to_py)?;
            let borrows = arrays
                .iter()
                .flatten()
                .map(|a| a.try_readonly())
                .collect::<Result<Vec<_>, _>>()?;
            let balls = self.scene.balls;
            let rows = py.detach(|| mindlin.rows(&balls, &inputs, n, &settings));
            drop(borrows);
            drop(arrays);
            return match rows {
                Ok(rows) => rows.into_dict(py, single),
                Err((i, e)) => {
                    let msg = if single {
                        e.to_string()
                    } else {
                        format!("row {i}: {e}")
                    };
                    Err(if e.is_bad_input() {
                        PyValueError::new_err(msg)
                    } else {
                        pyo3::exceptions::PyRuntimeError::new_err(msg)
                    })
                }
            };
        }
        let own_setup;
        let setup = if method.is_none() && rtol.is_none() && time_transform.is_none() {
            &self.closed_form
        } else {
            own_setup = BatchSetup::from_scene(
                &self.scene,
                settings::for_batch(method, rtol, time_transform).map_err(to_py)?,
            );
            &own_setup
        };
        if single && setup.settings.method() == Method::ClosedForm {
            return single_collision(py, setup, &inputs, arrays);
        }
        let out = Outputs::new(py, n, single);
        // SAFETY: fresh C-contiguous arrays, written only here (see `Outputs`).
        let columns = unsafe { out.columns() };
        let per_chunk = PER_CHUNK.load(Ordering::Relaxed);
        let parallel = n >= PARALLEL_LAB_ROWS;
        let run = |columns| {
            if per_chunk {
                resolve_checked(setup, &inputs, columns, parallel)
            } else {
                resolve_lab_into(setup, &inputs, columns)
                    .map_err(|(i, e)| (i, RowFailure::Library(e)))
            }
        };
        let result = if parallel || setup.settings.method() != Method::ClosedForm {
            // Without the GIL (from PARALLEL_LAB_ROWS rows on all cores; time stepping
            // takes long even for one row): hold read-only borrows, so no Rust code writes
            // the inputs meanwhile (numpy's borrow tracking).
            let borrows = arrays
                .iter()
                .flatten()
                .map(|a| a.try_readonly())
                .collect::<Result<Vec<_>, _>>()?;
            let r = py.detach(|| run(columns));
            drop(borrows);
            r
        } else {
            // A few rows with the GIL held: read straight from the buffers.
            run(columns)
        };
        drop(arrays);
        let result = match result {
            Ok(()) if !per_chunk => match out.first_non_finite() {
                Some((i, what)) => Err((i, RowFailure::NonFinite(what))),
                None => Ok(()),
            },
            other => other,
        };
        match result {
            Ok(()) => {}
            Err((i, RowFailure::Library(e))) => {
                let e = with_argument_names(e);
                let msg = if single {
                    e.to_string()
                } else {
                    format!("row {i}: {e}")
                };
                return Err(if e.is_bad_input() {
                    PyValueError::new_err(msg)
                } else {
                    pyo3::exceptions::PyRuntimeError::new_err(msg)
                });
            }
            Err((i, RowFailure::NonFinite(what))) => {
                return Err(PyValueError::new_err(if single {
                    what
                } else {
                    format!("row {i}: {what}")
                }));
            }
        }
        out.into_dict(py)
    }

    /// Mass m (kg) of both balls; None when A and B differ.
    #[getter]
    fn mass(&self) -> Option<f64> {
        self.shared().map(|b| b.mass())
    }

    /// Radius r (m) of both balls; None when A and B differ.
    #[getter]
    fn radius(&self) -> Option<f64> {
        self.shared().map(|b| b.radius())
    }

    /// I = alpha m r^2, alpha of both balls; None when A and B differ.
    #[getter]
    fn alpha(&self) -> Option<f64> {
        self.shared().map(|b| b.alpha())
    }

    /// Ball A.
    #[getter]
    fn a(&self) -> Ball {
        Ball {
            ball: self.scene.balls.a,
        }
    }

    /// Ball B.
    #[getter]
    fn b(&self) -> Ball {
        Ball {
            ball: self.scene.balls.b,
        }
    }

    /// Ball-ball friction: a number or SpeedDependentFriction.
    #[getter]
    fn mu(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        Ok(match self.mu {
            Mu::Constant(x) => x.into_pyobject(py)?.into_any().unbind(),
            Mu::Speed(s) => Bound::new(py, s)?.into_any().unbind(),
        })
    }

    /// Restitution e: P = (1 + e) m U(0).
    #[getter]
    fn restitution(&self) -> f64 {
        self.restitution
    }

    /// Pickling and copying: the keywords that built the model, so `BallBall(**kwargs)`
    /// builds it again (the same numbers, so bit-identical results).
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        let kwargs = PyDict::new(py);
        match self.shared() {
            Some(ball) if !self.by_ball => {
                kwargs.set_item("mass", ball.mass())?;
                kwargs.set_item("radius", ball.radius())?;
                kwargs.set_item("alpha", ball.alpha())?;
            }
            _ => {
                kwargs.set_item("a", self.a())?;
                kwargs.set_item("b", self.b())?;
            }
        }
        kwargs.set_item("mu", self.mu(py)?)?;
        kwargs.set_item("restitution", self.restitution)?;
        kwargs.set_item("profile", &self.profile)?;
        kwargs.set_item("duration", self.duration)?;
        kwargs.set_item("friction", self.friction)?;
        kwargs.set_item("stick", self.stick)?;
        if let Some(m) = self.mindlin {
            kwargs.set_item("tangential", "mindlin")?;
            kwargs.set_item("youngs_modulus", m.material.youngs_modulus())?;
            kwargs.set_item("poisson_ratio", m.material.poisson_ratio())?;
            kwargs.set_item("shear_stiffness_factor", m.shear_stiffness_factor)?;
            if m.law.0 != Damping::None {
                kwargs.set_item("damping", m.law.0.name())?;
                kwargs.set_item("coefficient", m.coefficient)?;
                kwargs.set_item("at_speed", m.at_speed)?;
            }
        }
        Ok((PyTuple::empty(py), kwargs))
    }

    fn __repr__(&self) -> String {
        let mu = match self.mu {
            Mu::Constant(x) => format!("{x:?}"),
            Mu::Speed(s) => s.__repr__(),
        };
        let balls = match self.shared() {
            Some(ball) if !self.by_ball => format!(
                "mass={:?}, radius={:?}, alpha={:?}",
                ball.mass(),
                ball.radius(),
                ball.alpha()
            ),
            _ => format!("a={}, b={}", self.a().__repr__(), self.b().__repr__()),
        };
        let tangential = match self.mindlin {
            None => String::new(),
            Some(m) => {
                let mut s = format!(
                    ", tangential=\"mindlin\", youngs_modulus={:?}, poisson_ratio={:?}, \
                     shear_stiffness_factor={:?}",
                    m.material.youngs_modulus(),
                    m.material.poisson_ratio(),
                    m.shear_stiffness_factor
                );
                s += &damping_repr(m.law.0, m.coefficient, m.at_speed);
                s
            }
        };
        format!(
            "BallBall({balls}, mu={mu}, restitution={:?}, \
             profile=\"{}\", duration={:?}, friction={}, stick={}{tangential})",
            self.restitution,
            self.profile,
            self.duration,
            if self.friction { "True" } else { "False" },
            if self.stick { "True" } else { "False" },
        )
    }

    /// The tangential law: "rigid" (the stick rule, eqs 24-35) or "mindlin" (Mindlin's
    /// spring, the compliant pair).
    #[getter]
    fn tangential(&self) -> &'static str {
        if self.mindlin.is_some() {
            "mindlin"
        } else {
            "rigid"
        }
    }
}

/// The tangential law from the keywords: `None` for "rigid" (no material, factor or
/// damping may be given: the stick rule uses none); for "mindlin" the balls' material, the
/// factor on Mindlin's stiffness and the normal force's damping (elastic at restitution 1,
/// a coefficient, or calibrated to the restitution at `at_speed`), with a constant mu and
/// friction and stick on (the compliant contact has no stick rule to switch).
fn mindlin_of(
    balls: &BallPair,
    tangential: &str,
    mu: Mu,
    [friction, stick]: [bool; 2],
    [youngs_modulus, poisson_ratio, factor]: [Option<f64>; 3],
    keywords: DampingKeywords<'_>,
) -> Result<Option<PairMindlin>, Error> {
    match tangential {
        "rigid" => match (
            youngs_modulus,
            poisson_ratio,
            factor,
            keywords.damping,
            keywords.coefficient,
            keywords.at_speed,
        ) {
            (None, None, None, None, None, None) => Ok(None),
            _ => Err(Error::invalid(
                "tangential",
                "\"rigid\" with a material, shear_stiffness_factor or a damping",
                "tangential=\"mindlin\" with them (the rigid stick rule uses none)",
            )),
        },
        "mindlin" => {
            let Mu::Constant(mu) = mu else {
                return Err(Error::invalid(
                    "mu",
                    "SpeedDependentFriction with tangential=\"mindlin\"",
                    "a number (the compliant pair takes a constant Coulomb coefficient)",
                ));
            };
            if !(friction && stick) {
                return Err(Error::invalid(
                    "friction, stick",
                    format!("{friction}, {stick} with tangential=\"mindlin\""),
                    "True, True (mu=0 for no friction; the compliant contact has no stick rule)",
                ));
            }
            PairMindlin::of(balls, youngs_modulus, poisson_ratio, mu, factor, keywords).map(Some)
        }
        other => Err(Error::invalid(
            "tangential",
            format!("{other:?}"),
            "\"rigid\" (the stick rule) or \"mindlin\" (Mindlin's tangential spring)",
        )),
    }
}

/// The profile `profile=` names, with the contact duration `duration` (s): the scene
/// file's shapes but `tabulated`, whose points come from a file (`run_toml` reads it).
fn profile_spec(profile: &str, duration: f64) -> Result<ProfileSpec, Error> {
    Ok(match profile.parse::<ProfileKind>()? {
        ProfileKind::HalfSine => ProfileSpec::HalfSine { duration },
        ProfileKind::Hertz => ProfileSpec::Hertz {
            duration: Some(duration),
        },
        ProfileKind::SinePower => ProfileSpec::SinePower {
            duration: Some(duration),
            exponent: None,
        },
        ProfileKind::Rectangle => ProfileSpec::Rectangle { duration },
        ProfileKind::Tabulated => {
            return Err(Error::invalid(
                "profile",
                "\"tabulated\"",
                "half-sine, hertz, sine-power or rectangle (a tabulated profile takes its \
                 points from a file: give it in a scene to run or run_toml)",
            ))
        }
    })
}
