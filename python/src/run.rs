//! `run` and `run_toml`: a scene, as `billiard-contact run SCENE --json`.

use crate::errors::{to_py, unwrap_scene_message};
use crate::settings;
use billiard_contact::{
    is_cushion_scene, run_scene, CushionReport, CushionScene, Error, Method, Report, Sampling,
    Scene, TraceRow, TraceSink,
};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// The trace CSV's columns without their units, in its order.
pub const TRACE_COLUMNS: [&str; 15] = [
    "t",
    "f",
    "p",
    "U",
    "V",
    "W",
    "omega_a_x",
    "omega_a_y",
    "omega_a_z",
    "omega_b_x",
    "omega_b_y",
    "omega_b_z",
    "S",
    "theta",
    "H_sfr",
];

/// The trace's column of the compression under a contact law, the CSV's `delta (m)`: after
/// [`TRACE_COLUMNS`], only when the scene has a law.
pub const COMPRESSION_COLUMN: &str = "delta";

/// Trace rows kept as columns (theta NaN where the CSV cell is empty), and the compression
/// of the rows that carry it (a contact law's).
#[derive(Default)]
struct Columns {
    data: [Vec<f64>; 15],
    compression: Vec<f64>,
}

impl TraceSink for Columns {
    fn row(&mut self, r: &TraceRow) -> Result<(), Error> {
        let s = &r.state;
        let values = [
            r.t,
            r.force,
            r.impulse,
            s.u_cm.x,
            s.u_cm.y,
            s.u_cm.z,
            s.omega_a.x,
            s.omega_a.y,
            s.omega_a.z,
            s.omega_b.x,
            s.omega_b.y,
            s.omega_b.z,
            r.slip_speed,
            r.theta.unwrap_or(f64::NAN),
            r.heat_sliding,
        ];
        for (k, (col, v)) in self.data.iter_mut().zip(values).enumerate() {
            if k != 13 && !v.is_finite() {
                return Err(Error::NonFinite {
                    field: format!("trace column {} at t = {}", TRACE_COLUMNS[k], r.t),
                    value: v,
                });
            }
            col.push(v);
        }
        if let Some(delta) = r.compression {
            if !delta.is_finite() {
                return Err(Error::NonFinite {
                    field: format!("trace column {COMPRESSION_COLUMN} at t = {}", r.t),
                    value: delta,
                });
            }
            self.compression.push(delta);
        }
        Ok(())
    }
}

enum Source {
    File(PathBuf),
    Text { text: String, base: PathBuf },
}

struct Options {
    method: Option<String>,
    rtol: Option<f64>,
    atol: Option<f64>,
    steps: Option<i64>,
    samples: Option<i64>,
    trace: bool,
    time_transform: Option<bool>,
}

/// What a run gives the bindings: the report's JSON, the trace columns (with samples or
/// trace=True), and the warnings: the scene's (values far outside any ball game, keys it
/// does not use) and those for options the run does not use.
struct RunOutput {
    json: String,
    columns: Option<Columns>,
    warnings: Vec<String>,
}

/// The report's JSON, the trace columns and the warnings (the command line's, on stderr
/// there).
fn run_json(source: Source, o: &Options) -> Result<RunOutput, Error> {
    let cushion = match &source {
        Source::File(p) => {
            let text = std::fs::read_to_string(p)
                .map_err(|e| Error::io_doing(p, "cannot read the scene file", e))?;
            is_cushion_scene(&text).then(|| CushionScene::parse(&text, Some(p)))
        }
        Source::Text { text, .. } => {
            is_cushion_scene(text).then(|| CushionScene::parse(text, None))
        }
    };
    if let Some(scene) = cushion {
        return run_cushion(&scene?, o);
    }
    let scene = match source {
        Source::File(p) => Scene::load(&p)?,
        Source::Text { text, base } => {
            Scene::parse(&text, &base, None).map_err(unwrap_scene_message)?
        }
    };
    let steps = match o.steps {
        None => None,
        Some(s) => {
            Some(u32::try_from(s).map_err(|_| Error::invalid("solver.steps", s, "in [1, 1e7]"))?)
        }
    };
    let overrides =
        settings::overrides(o.method.as_deref(), o.rtol, o.atol, steps, o.time_transform)?;
    let settings = overrides.apply(&scene.solver)?;
    let mut warnings = scene.warnings();
    warnings.extend(settings::unused(&overrides, &settings, scene.law.is_some()));
    let sampling = match o.samples {
        None => Sampling::Steps,
        Some(n) if n >= 1 => Sampling::Uniform(n as u64),
        Some(n) => return Err(Error::invalid("samples", n, "at least 1")),
    };
    let want_trace = o.samples.is_some() || o.trace;
    let mut columns = Columns::default();
    let outcome = run_scene(
        &scene,
        &settings,
        want_trace.then_some((&mut columns as &mut dyn TraceSink, sampling)),
    )?;
    let json = Report::new(&scene, &outcome).to_json()?;
    Ok(RunOutput {
        json,
        columns: want_trace.then_some(columns),
        warnings,
    })
}

/// A cushion scene ([cushion]), as `billiard-contact run SCENE --json` runs it: its report,
/// the options checked as the command checks them (`samples` and `trace` have no meaning
/// for an impact stepped in the impulse from Python; `steps` only with rk4).
fn run_cushion(scene: &CushionScene, o: &Options) -> Result<RunOutput, Error> {
    if let Some(n) = o.samples {
        return Err(Error::invalid(
            "samples",
            n,
            "not for a cushion scene: its trace has a row at the start, after every step, at \
             every slip event and at the end (it is stepped in the impulse, not in time)",
        ));
    }
    if o.trace {
        return Err(Error::invalid(
            "trace",
            "True",
            "False for a cushion scene (its trace CSV: `billiard-contact run SCENE --trace \
             FILE`; BallCushion resolves the impact from arrays)",
        ));
    }
    let steps = match o.steps {
        None => None,
        Some(s) => {
            Some(u32::try_from(s).map_err(|_| Error::invalid("solver.steps", s, "in [1, 1e7]"))?)
        }
    };
    let overrides = settings::overrides(o.method.as_deref(), o.rtol, o.atol, steps, None)?;
    let settings = overrides.apply(&scene.solver)?;
    if let Some(n) = steps {
        if settings.method() != Method::Rk4 {
            return Err(Error::invalid(
                "steps",
                n,
                format!(
                    "only with the method rk4 (this run's is {}, which chooses its own steps \
                     from rtol): add method=\"rk4\"",
                    settings.method()
                ),
            ));
        }
    }
    let mut warnings = Vec::new();
    if o.time_transform.is_some() {
        warnings.push(
            "time_transform= has no effect on a cushion impact (stepped in the impulse)".into(),
        );
    }
    if settings.method() == Method::Rk4 && (o.rtol.is_some() || o.atol.is_some()) {
        warnings.push("rtol= and atol= have no effect with rk4 (fixed steps)".into());
    }
    let out = scene.run(&settings, None)?;
    Ok(RunOutput {
        json: CushionReport::new(scene, &settings, &out).to_json()?,
        columns: None,
        warnings,
    })
}

fn run_py<'py>(py: Python<'py>, source: Source, o: Options) -> PyResult<Bound<'py, PyAny>> {
    let out = py.detach(|| run_json(source, &o)).map_err(to_py)?;
    settings::warn_all(py, &out.warnings)?;
    let report = py
        .import("json")?
        .call_method1("loads", (out.json,))?
        .cast_into::<PyDict>()?;
    if let Some(c) = out.columns {
        let trace = PyDict::new(py);
        let rows = c.data[0].len();
        for (name, col) in TRACE_COLUMNS.iter().zip(c.data) {
            trace.set_item(name, PyArray1::from_vec(py, col))?;
        }
        if !c.compression.is_empty() {
            debug_assert_eq!(c.compression.len(), rows);
            trace.set_item(COMPRESSION_COLUMN, PyArray1::from_vec(py, c.compression))?;
        }
        report.set_item("trace", trace)?;
    }
    Ok(report.into_any())
}

/// Runs a scene file (TOML) as `billiard-contact run SCENE --json` does and returns its
/// report: a dict with exactly the command's JSON keys and values.
///
/// method ("closed-form", "rk4", "dopri5", "dop853"), rtol, atol and steps override the
/// scene's [solver] as the command's options do (a new rtol sets atol too unless atol is
/// given); time_transform (True or False) overrides the scene's `[solver] time_transform`
/// as `--time-transform` does (None: the scene's, by default the library's True). samples=N adds report["trace"]: numpy arrays keyed by the trace CSV's column
/// names without units ("t", "f", "p", "U", "V", "W", "omega_a_x" .. "omega_b_z", "S",
/// "theta", "H_sfr"; SI units, the centre-of-mass frame), and "delta" (the compression, m)
/// when the scene has a contact law, at t = i duration / N plus the stop of sliding (under a
/// law the time-stepping methods sample its elastic time unit:
/// docs/contact-law.md#time-stepping); trace=True gives one row per accepted step instead.
/// theta is NaN where the CSV cell is empty (S(0) = 0). An option the run does not use
/// (rtol or atol with rk4 or a profile's closed form, time_transform with the closed form
/// or a contact law) is said in a UserWarning, as the command says it on stderr; so are the
/// scene's own warnings (a value far outside any ball game with the likely unit slip,
/// `[solver] time_transform` under a contact law).
///
/// Bad input raises ValueError with the command's one-line message; a failed run
/// RuntimeError.
#[pyfunction]
#[pyo3(signature = (path, method = None, rtol = None, samples = None, *, atol = None, steps = None, trace = false, time_transform = None))]
#[allow(clippy::too_many_arguments)]
pub fn run<'py>(
    py: Python<'py>,
    #[pyo3(from_py_with = crate::args::scene_path)] path: PathBuf,
    #[pyo3(from_py_with = crate::args::method)] method: Option<String>,
    #[pyo3(from_py_with = crate::args::rtol)] rtol: Option<f64>,
    #[pyo3(from_py_with = crate::args::samples)] samples: Option<i64>,
    #[pyo3(from_py_with = crate::args::atol)] atol: Option<f64>,
    #[pyo3(from_py_with = crate::args::steps)] steps: Option<i64>,
    #[pyo3(from_py_with = crate::args::trace)] trace: bool,
    #[pyo3(from_py_with = crate::args::time_transform)] time_transform: Option<bool>,
) -> PyResult<Bound<'py, PyAny>> {
    let o = Options {
        method,
        rtol,
        atol,
        steps,
        samples,
        trace,
        time_transform,
    };
    run_py(py, Source::File(path), o)
}

/// Runs a scene given as TOML text; relative profile files resolve against base_dir.
/// Otherwise as `run`.
#[pyfunction]
#[pyo3(signature = (text, base_dir = PathBuf::from("."), method = None, rtol = None, samples = None, *, atol = None, steps = None, trace = false, time_transform = None))]
#[allow(clippy::too_many_arguments)]
pub fn run_toml<'py>(
    py: Python<'py>,
    #[pyo3(from_py_with = crate::args::scene_text)] text: String,
    #[pyo3(from_py_with = crate::args::base_dir)] base_dir: PathBuf,
    #[pyo3(from_py_with = crate::args::method)] method: Option<String>,
    #[pyo3(from_py_with = crate::args::rtol)] rtol: Option<f64>,
    #[pyo3(from_py_with = crate::args::samples)] samples: Option<i64>,
    #[pyo3(from_py_with = crate::args::atol)] atol: Option<f64>,
    #[pyo3(from_py_with = crate::args::steps)] steps: Option<i64>,
    #[pyo3(from_py_with = crate::args::trace)] trace: bool,
    #[pyo3(from_py_with = crate::args::time_transform)] time_transform: Option<bool>,
) -> PyResult<Bound<'py, PyAny>> {
    let o = Options {
        method,
        rtol,
        atol,
        steps,
        samples,
        trace,
        time_transform,
    };
    run_py(
        py,
        Source::Text {
            text,
            base: base_dir,
        },
        o,
    )
}
