//! `BallCushion`: a ball on the cloth against a cushion (Mathavan, Jackson and Parkin
//! 2010; the library's `resolve_cushion`), one impact or N from numpy arrays, in the
//! cushion's frame (x along the cushion, y towards it, z up).

use crate::errors::to_py;
use crate::inputs::{float_array, strided, Strided};
use crate::outputs::{bool_, float64, vector};
use crate::settings;
use billiard_contact::nalgebra::Vector3;
use billiard_contact::{
    resolve_cushion, Ball, Cushion, CushionContact, CushionOutcome, CushionRestitution, Error,
    Method, SlipChange, SolverOverrides, SolverSettings,
};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use rayon::prelude::*;

/// The argument names of `resolve`, in the order of the views.
const NAMES: [&str; 2] = ["v", "w"];

/// Rows from which the impacts spread over rayon's pool (an impact takes microseconds).
const PARALLEL_ROWS: usize = 64;

/// The names `rule=` takes.
const RULES: [(&str, CushionRestitution); 2] = [
    ("stronge", CushionRestitution::Stronge),
    ("newton", CushionRestitution::Newton),
];

/// A ball against a cushion: the ball's mass (kg), radius (m) and alpha (I = alpha m r^2),
/// the height of the cushion's contact above the cloth (m, between r and 2r), the friction
/// of the ball on the cushion and on the cloth, the restitution e in [0, 1] and its rule
/// ("stronge": the work of restitution is e^2 that of compression; "newton": the normal
/// velocity at the cushion ends at -e times its start).
///
/// Bad values raise ValueError naming the keyword, e.g. "height = 0.02: in (r, 2r) ...".
#[pyclass(frozen, module = "billiard_contact._core", name = "BallCushion")]
pub struct BallCushion {
    ball: Ball,
    cushion: Cushion,
}

/// `e` with the field `from` named `to`.
fn renamed(e: Error, from: &str, to: &str) -> Error {
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

/// The library's error for a row, with the arguments' names (`ball.v` is `v`, ...).
fn named(e: Error) -> Error {
    renamed(
        renamed(renamed(e, "ball.", ""), "cushion.", ""),
        "solver.",
        "",
    )
}

fn contact_name(c: CushionContact) -> &'static str {
    match c {
        CushionContact::Cushion => "cushion",
        CushionContact::Table => "table",
    }
}

fn change_name(k: SlipChange) -> &'static str {
    match k {
        SlipChange::Sticks => "sticks",
        SlipChange::Reverses => "reverses",
        SlipChange::Restarts => "restarts",
        SlipChange::LiftsOff => "lifts-off",
        SlipChange::TouchesDown => "touches-down",
    }
}

/// Whether every number an impact gives is finite.
fn finite(o: &CushionOutcome) -> bool {
    o.v.iter().chain(o.w.iter()).all(|x| x.is_finite())
        && [
            o.impulse_cushion,
            o.impulse_compression,
            o.impulse_table,
            o.work_compression,
            o.work_restitution,
            o.energy_lost,
        ]
        .iter()
        .all(|x| x.is_finite())
}

#[cold]
#[inline(never)]
fn non_finite_message(o: &CushionOutcome) -> String {
    let named = ["v", "w"]
        .into_iter()
        .zip([o.v, o.w])
        .flat_map(|(name, v)| (0..3).map(move |k| (format!("{name}[{k}]"), v[k])))
        .chain(
            [
                ("impulse", o.impulse_cushion),
                ("impulse_compression", o.impulse_compression),
                ("impulse_table", o.impulse_table),
                ("work_compression", o.work_compression),
                ("work_restitution", o.work_restitution),
                ("energy_lost", o.energy_lost),
            ]
            .map(|(n, x)| (n.to_string(), x)),
        );
    let (name, x) = named
        .into_iter()
        .find(|(_, x)| !x.is_finite())
        .unwrap_or_else(|| ("output".into(), f64::NAN));
    format!(
        "{name} = {x}: the result is not finite (the impact overflows double precision: \
         mass, speed or spin too large)"
    )
}

enum Failure {
    Input(Error),
    Output(String),
}

fn failure_error(i: usize, f: Failure, single: bool) -> PyErr {
    let row = |m: String| if single { m } else { format!("row {i}: {m}") };
    match f {
        Failure::Input(e) if e.is_bad_input() => PyValueError::new_err(row(e.to_string())),
        Failure::Input(e) => PyRuntimeError::new_err(row(e.to_string())),
        Failure::Output(m) => PyValueError::new_err(row(m)),
    }
}

impl BallCushion {
    fn row(
        &self,
        views: &[Strided; 2],
        i: usize,
        settings: &SolverSettings,
    ) -> Result<CushionOutcome, Failure> {
        // SAFETY: i < n of the views, whose arrays outlive the call.
        let (v, w): (Vector3<f64>, Vector3<f64>) = unsafe { (views[0].row(i), views[1].row(i)) };
        let o = resolve_cushion(&self.ball, &self.cushion, v, w, settings, None)
            .map_err(|e| Failure::Input(named(e)))?;
        if !finite(&o) {
            return Err(Failure::Output(non_finite_message(&o)));
        }
        Ok(o)
    }
}

/// The settings of `resolve`: dop853 unless a method is named (the impact has no closed
/// form), rtol (atol with it) and rk4's steps as given, else the library's.
fn cushion_settings(
    method: Option<&str>,
    rtol: Option<f64>,
    steps: Option<i64>,
) -> Result<SolverSettings, Error> {
    let steps = steps
        .map(|s| u32::try_from(s).map_err(|_| Error::invalid("steps", s, "in [1, 1e7]")))
        .transpose()?;
    let method = method
        .map(settings::method)
        .transpose()?
        .unwrap_or(Method::Dop853);
    if method == Method::ClosedForm {
        return Err(Error::invalid(
            "method",
            "\"closed-form\"",
            "\"dop853\", \"dopri5\" or \"rk4\": the cushion impact has no closed form (the \
             slip directions turn)",
        ));
    }
    SolverOverrides {
        method: Some(method),
        rtol,
        atol: None,
        steps,
        time_transform: None,
    }
    .apply(&SolverSettings::default())
    .map_err(|e| renamed(e, "solver.", ""))
}

fn events_list<'py>(py: Python<'py>, o: &CushionOutcome) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for e in &o.events {
        list.append((contact_name(e.contact), change_name(e.kind), e.impulse))?;
    }
    Ok(list)
}

#[pymethods]
impl BallCushion {
    #[new]
    #[pyo3(signature = (*, mass, radius, alpha = 0.4, height, mu_cushion, mu_table,
                        restitution, rule = "stronge".to_string()),
           text_signature = "(*, mass, radius, alpha=0.4, height, mu_cushion, mu_table, \
                             restitution, rule='stronge')")]
    #[allow(clippy::too_many_arguments)]
    fn new(
        #[pyo3(from_py_with = crate::args::mass)] mass: f64,
        #[pyo3(from_py_with = crate::args::radius)] radius: f64,
        #[pyo3(from_py_with = crate::args::alpha)] alpha: f64,
        #[pyo3(from_py_with = crate::args::height)] height: f64,
        #[pyo3(from_py_with = crate::args::mu_cushion)] mu_cushion: f64,
        #[pyo3(from_py_with = crate::args::mu_table)] mu_table: f64,
        #[pyo3(from_py_with = crate::args::restitution)] restitution: f64,
        #[pyo3(from_py_with = crate::args::rule)] rule: String,
    ) -> PyResult<Self> {
        let ball = Ball::in_section("ball", mass, radius, alpha)
            .map_err(|e| to_py(renamed(e, "ball.", "")))?;
        let Some(&(_, rule)) = RULES.iter().find(|(name, _)| *name == rule) else {
            return Err(to_py(Error::invalid(
                "rule",
                format!("\"{rule}\""),
                "\"stronge\" (the work of restitution e^2 that of compression) or \"newton\" \
                 (the normal velocity at the cushion ends at -e times its start)",
            )));
        };
        let cushion = Cushion::new(height, mu_cushion, mu_table, restitution, rule)
            .map_err(|e| to_py(renamed(e, "cushion.", "")))?;
        let r = ball.radius();
        if !(height > r && height < 2.0 * r) {
            return Err(to_py(Error::invalid(
                "height",
                height,
                format!(
                    "in (radius, 2 radius) = ({r}, {}) m: the cushion's contact above the \
                     ball's centre and below its top",
                    2.0 * r
                ),
            )));
        }
        Ok(BallCushion { ball, cushion })
    }

    /// Resolves impacts on the cushion, in its frame: x along the cushion, y towards it
    /// (into the cushion), z up.
    ///
    /// v, w: the ball's velocity (m/s) and spin (rad/s) before, each (3,) or (N, 3) (a
    /// (3,) input is used for every row). The ball must be on the cloth, v_z = 0, and
    /// approach the cushion, v_y > 0 (else ValueError naming the row and v).
    ///
    /// method: "dop853" (default), "dopri5" or "rk4" (the impact has no closed form); rtol
    /// (default 1e-10, atol with it) of the adaptive methods; steps of rk4.
    ///
    /// Returns a dict: "v", "w" (after; the input's shape), "impulse" (the cushion's
    /// normal impulse P_I, N s), "impulse_compression" (P_I at the end of compression),
    /// "impulse_table" (the cloth's normal impulse), "work_compression",
    /// "work_restitution" (J, >= 0), "energy_lost" (J), "lifts_off" (the ball left the
    /// cloth during the impact), "events" (the slip events in order, tuples (contact,
    /// change, P_I): contact "cushion" or "table", change "sticks", "reverses",
    /// "restarts", "lifts-off", "touches-down"; a list of such lists for N rows),
    /// "steps" (accepted steps), "evaluations" (of the right-hand side, event location
    /// included); (N,) arrays, or numpy scalars for one impact.
    #[pyo3(signature = (v, w, method = None, rtol = None, steps = None))]
    fn resolve<'py>(
        &self,
        py: Python<'py>,
        v: &Bound<'py, PyAny>,
        w: &Bound<'py, PyAny>,
        #[pyo3(from_py_with = crate::args::method)] method: Option<String>,
        #[pyo3(from_py_with = crate::args::rtol)] rtol: Option<f64>,
        #[pyo3(from_py_with = crate::args::steps)] steps: Option<i64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let settings = cushion_settings(method.as_deref(), rtol, steps).map_err(to_py)?;
        let arrays = [Some(float_array("v", v)?), Some(float_array("w", w)?)];
        let (views, n, single) = strided(&NAMES, &arrays)?;
        if single {
            let o = self.row(&views, 0, &settings);
            drop(arrays);
            let o = o.map_err(|f| failure_error(0, f, true))?;
            let d = PyDict::new(py);
            d.set_item(intern!(py, "v"), vector(py, o.v.into())?)?;
            d.set_item(intern!(py, "w"), vector(py, o.w.into())?)?;
            for (k, x) in [
                ("impulse", o.impulse_cushion),
                ("impulse_compression", o.impulse_compression),
                ("impulse_table", o.impulse_table),
                ("work_compression", o.work_compression),
                ("work_restitution", o.work_restitution),
                ("energy_lost", o.energy_lost),
            ] {
                d.set_item(k, float64(py, x)?)?;
            }
            d.set_item(intern!(py, "lifts_off"), bool_(py, o.lifts_off)?)?;
            d.set_item(intern!(py, "events"), events_list(py, &o)?)?;
            d.set_item(intern!(py, "steps"), o.stats.accepted_steps)?;
            d.set_item(intern!(py, "evaluations"), o.stats.rhs_evaluations)?;
            return Ok(d);
        }
        let borrows = arrays
            .iter()
            .flatten()
            .map(|a| a.try_readonly())
            .collect::<Result<Vec<_>, _>>()?;
        let outcomes: Result<Vec<CushionOutcome>, (usize, Failure)> = py.detach(|| {
            let one = |i: usize| self.row(&views, i, &settings).map_err(|f| (i, f));
            if n >= PARALLEL_ROWS {
                // collect stops at an error; the first row's error is wanted: keep going
                // and take the least row that failed.
                let all: Vec<Result<CushionOutcome, (usize, Failure)>> =
                    (0..n).into_par_iter().map(one).collect();
                all.into_iter().collect()
            } else {
                (0..n).map(one).collect()
            }
        });
        drop(borrows);
        drop(arrays);
        let outcomes = outcomes.map_err(|(i, f)| failure_error(i, f, false))?;
        let rows = |f: fn(&CushionOutcome) -> Vector3<f64>| {
            let flat: Vec<f64> = outcomes
                .iter()
                .flat_map(|o| <[f64; 3]>::from(f(o)))
                .collect();
            PyArray1::from_vec(py, flat).reshape([n, 3])
        };
        let column = |f: fn(&CushionOutcome) -> f64| {
            PyArray1::from_iter(py, outcomes.iter().map(f)).into_any()
        };
        let d = PyDict::new(py);
        d.set_item(intern!(py, "v"), rows(|o| o.v)?)?;
        d.set_item(intern!(py, "w"), rows(|o| o.w)?)?;
        d.set_item("impulse", column(|o| o.impulse_cushion))?;
        d.set_item("impulse_compression", column(|o| o.impulse_compression))?;
        d.set_item("impulse_table", column(|o| o.impulse_table))?;
        d.set_item("work_compression", column(|o| o.work_compression))?;
        d.set_item("work_restitution", column(|o| o.work_restitution))?;
        d.set_item("energy_lost", column(|o| o.energy_lost))?;
        d.set_item(
            "lifts_off",
            PyArray1::from_iter(py, outcomes.iter().map(|o| o.lifts_off)),
        )?;
        let events = PyList::empty(py);
        for o in &outcomes {
            events.append(events_list(py, o)?)?;
        }
        d.set_item("events", events)?;
        d.set_item(
            "steps",
            PyArray1::from_iter(py, outcomes.iter().map(|o| o.stats.accepted_steps)),
        )?;
        d.set_item(
            "evaluations",
            PyArray1::from_iter(py, outcomes.iter().map(|o| o.stats.rhs_evaluations)),
        )?;
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

    /// Height of the cushion's contact above the cloth (m).
    #[getter]
    fn height(&self) -> f64 {
        self.cushion.height()
    }

    /// Friction of the ball on the cushion.
    #[getter]
    fn mu_cushion(&self) -> f64 {
        self.cushion.mu_cushion()
    }

    /// Friction of the ball on the cloth.
    #[getter]
    fn mu_table(&self) -> f64 {
        self.cushion.mu_table()
    }

    /// Restitution e.
    #[getter]
    fn restitution(&self) -> f64 {
        self.cushion.restitution()
    }

    /// The restitution rule: "stronge" or "newton".
    #[getter]
    fn rule(&self) -> &'static str {
        self.cushion.rule().name()
    }

    /// Pickling and copying: the keywords that built the model.
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        let kwargs = PyDict::new(py);
        kwargs.set_item("mass", self.ball.mass())?;
        kwargs.set_item("radius", self.ball.radius())?;
        kwargs.set_item("alpha", self.ball.alpha())?;
        kwargs.set_item("height", self.cushion.height())?;
        kwargs.set_item("mu_cushion", self.cushion.mu_cushion())?;
        kwargs.set_item("mu_table", self.cushion.mu_table())?;
        kwargs.set_item("restitution", self.cushion.restitution())?;
        kwargs.set_item("rule", self.rule())?;
        Ok((PyTuple::empty(py), kwargs))
    }

    fn __eq__(&self, other: &Self) -> bool {
        (self.ball, self.cushion) == (other.ball, other.cushion)
    }

    fn __repr__(&self) -> String {
        format!(
            "BallCushion(mass={:?}, radius={:?}, alpha={:?}, height={:?}, mu_cushion={:?}, \
             mu_table={:?}, restitution={:?}, rule=\"{}\")",
            self.ball.mass(),
            self.ball.radius(),
            self.ball.alpha(),
            self.cushion.height(),
            self.cushion.mu_cushion(),
            self.cushion.mu_table(),
            self.cushion.restitution(),
            self.rule()
        )
    }
}
