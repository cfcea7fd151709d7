//! `billiard-contact run`: one scene, its report or summary on stdout, and optionally its
//! trace, the balls' paths on the table and their top view.

use crate::apps::plot::paths::TopView;
use crate::apps::plot::trace::TraceFigure;
use crate::apps::plot::FigureFormat;
use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::settings::SolverSettings;
use crate::base::settings::{check_samples, check_steps_as, Sampling};
use crate::cli::choice::{number, whole, MethodChoice};
use crate::cli::common::{load_scene, solver_options_unused, warn};
use crate::model::trace::{Tee, TraceRow};
use crate::outputs::atomic_file::AtomicFile;
use crate::outputs::ball_paths::{write_ball_paths, DEFAULT_BALL_PATH_SAMPLES};
use crate::outputs::report::Report;
use crate::outputs::trace_csv::CsvTrace;
use crate::scene::overrides::SolverOverrides;
use crate::scene::run::run_scene;
use crate::scene::run::SceneOutcome;
use crate::scene::types::{Scene, TangentialLaw};
use crate::table_phase::outcome::TableOutcome;
use crate::table_phase::path::ball_path_rows;
use clap::Args;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The options of `run`.
#[derive(Args, Clone, Default)]
pub(super) struct RunArgs {
    /// Scene file (TOML); the built-in default scene when omitted.
    pub(super) scene: Option<PathBuf>,
    /// Print one JSON object on stdout instead of the summary.
    #[arg(long)]
    pub(super) json: bool,
    /// Write a CSV trace (centre-of-mass frame) to this file.
    #[arg(long, value_name = "FILE.csv")]
    pub(super) trace: Option<PathBuf>,
    /// Trace rows at t = i duration / N, i = 0..N (plus the stop of sliding), instead of a
    /// row per step of the integrator (needs --trace).
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = whole::<u64>)]
    pub(super) samples: Option<u64>,
    /// Method (overrides the scene).
    #[arg(long, value_name = "M")]
    pub(super) method: Option<MethodChoice>,
    /// Relative tolerance of dopri5 and dop853 (overrides the scene).
    #[arg(long, value_name = "X", allow_hyphen_values = true, value_parser = number)]
    pub(super) rtol: Option<f64>,
    /// Absolute tolerance of dopri5 and dop853 on the scaled variables (default: rtol).
    #[arg(long, value_name = "X", allow_hyphen_values = true, value_parser = number)]
    pub(super) atol: Option<f64>,
    /// RK4 steps over the contact (overrides the scene; only with the method rk4).
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = whole::<u32>)]
    pub(super) steps: Option<u32>,
    /// Integrate hertz and fractional sine-power pulses in a smoothed time variable
    /// (default true; false: steps graded toward the ends instead). Overrides the scene.
    #[arg(long, value_name = "BOOL")]
    pub(super) time_transform: Option<bool>,
    /// Write both balls' paths on the table (lab frame, until both roll) to this CSV
    /// (needs `[effects] table = true`).
    #[arg(long = "path", value_name = "FILE.csv")]
    pub(super) ball_paths: Option<PathBuf>,
    /// Uniform intervals of the path CSV (plus every change of phase; default 200; needs
    /// --path).
    #[arg(
        long = "path-samples",
        value_name = "N",
        allow_hyphen_values = true,
        value_parser = whole::<u64>
    )]
    pub(super) ball_path_samples: Option<u64>,
    /// Draw a top view of both balls' paths with the line of centres (`.svg` or `.png`;
    /// needs `[effects] table = true`).
    #[arg(long, value_name = "FILE.svg|png")]
    pub(super) plot: Option<PathBuf>,
    /// Draw the run's trace against time (`.svg` or `.png`): force and impulse, slip speed,
    /// slip direction, velocity, spins, sliding heat; the rows of --trace (with --samples).
    #[arg(long, value_name = "FILE.svg|png")]
    pub(super) plot_trace: Option<PathBuf>,
}

impl RunArgs {
    /// The options that override the scene's `[solver]`.
    pub(super) fn solver_overrides(&self) -> SolverOverrides {
        SolverOverrides {
            method: self.method.map(|m| m.0),
            rtol: self.rtol,
            atol: self.atol,
            steps: self.steps,
            time_transform: self.time_transform,
        }
    }

    /// The checks of the options that need the scene and the settings: refused when they
    /// could not act (exit code 2), a warning when an option has no effect on this run.
    fn validate(&self, scene: &Scene, settings: &SolverSettings) -> Result<(), Error> {
        for (option, path) in [("--plot", &self.plot), ("--plot-trace", &self.plot_trace)] {
            if let Some(path) = path {
                FigureFormat::of(option, path)?;
            }
        }
        if let Some(n) = self.samples {
            check_samples("--samples", n)?;
            if scene.tangential == TangentialLaw::Mindlin {
                return Err(Error::invalid(
                    "--samples",
                    n,
                    "not with contact.tangential = \"mindlin\": its trace is a row per step of \
                     the compliant kernel",
                ));
            }
            if self.trace.is_none() && self.plot_trace.is_none() {
                return Err(Error::invalid(
                    "--samples",
                    n,
                    "only with --trace FILE.csv or --plot-trace FILE.svg|png (it sets the \
                     trace's rows)",
                ));
            }
        }
        if let Some(n) = self.ball_path_samples {
            check_samples("--path-samples", n)?;
            if self.ball_paths.is_none() {
                return Err(Error::invalid(
                    "--path-samples",
                    n,
                    "only with --path FILE.csv (it sets the path's rows)",
                ));
            }
        }
        if let Some(n) = self.steps {
            if settings.method() != Method::Rk4 {
                return Err(Error::invalid(
                    "--steps",
                    n,
                    format!(
                        "only with the method rk4 (this run's is {}, which {}): add --method rk4",
                        settings.method(),
                        if settings.method() == Method::ClosedForm {
                            "does not step"
                        } else {
                            "chooses its own steps from --rtol"
                        }
                    ),
                ));
            }
        }
        for w in solver_options_unused(&self.solver_overrides(), settings, scene.law.is_some()) {
            warn(w);
        }
        let table_options = [("--path", &self.ball_paths), ("--plot", &self.plot)];
        if let Some((option, Some(path))) = table_options.iter().find(|(_, p)| p.is_some()) {
            if !scene.effects.table {
                return Err(Error::invalid(
                    *option,
                    path.display(),
                    "only with the table effect: set `table = true` under [effects] in the \
                     scene (lab frame, horizontal line of centres)",
                ));
            }
        }
        Ok(())
    }
}

/// Runs the scene; prints the JSON report or the summary once every file is written.
pub(super) fn run(args: &RunArgs) -> Result<(), Error> {
    let scene = load_scene(args.scene.as_deref())?;
    if let Some(n) = args.steps {
        check_steps_as("--steps", n)?;
    }
    let settings = args.solver_overrides().apply(&scene.solver)?;
    args.validate(&scene, &settings)?;
    let sampling = match args.samples {
        Some(n) => Sampling::Uniform(n),
        None => Sampling::Steps,
    };
    let render = |outcome: &SceneOutcome| -> Result<String, Error> {
        Ok(if args.json {
            Report::new(&scene, outcome).to_json()? + "\n"
        } else {
            Report::new(&scene, outcome).summary()
        })
    };
    // The trace becomes visible only once the whole run, report included, succeeded; the
    // trace figure draws the same rows.
    let mut rows: Vec<TraceRow> = Vec::new();
    let mindlin = scene.tangential == TangentialLaw::Mindlin;
    let (text, outcome) = match (&args.trace, args.plot_trace.is_some()) {
        // A compliant run's rows are in its outcome, with the tangential columns.
        (Some(path), plot) if mindlin => {
            let file = AtomicFile::create(path)?;
            let mut csv = CsvTrace::for_compliant(file, scene.plane()?)?;
            let outcome = if plot {
                run_scene(&scene, &settings, Some((&mut rows, sampling)))?
            } else {
                run_scene(&scene, &settings, None)?
            };
            let text = render(&outcome)?;
            for r in outcome.compliant.iter().flat_map(|c| &c.rows) {
                csv.compliant_row(r)?;
            }
            csv.finish()?.commit()?;
            (text, outcome)
        }
        (Some(path), plot) => {
            let file = AtomicFile::create(path)?;
            let mut csv = match scene.plane()? {
                Some(plane) => CsvTrace::for_plane(file, scene.law.is_some(), plane)?,
                None => CsvTrace::with_columns(file, scene.law.is_some())?,
            };
            let outcome = if plot {
                let mut both = Tee(&mut csv, &mut rows);
                run_scene(&scene, &settings, Some((&mut both, sampling)))?
            } else {
                run_scene(&scene, &settings, Some((&mut csv, sampling)))?
            };
            let text = render(&outcome)?;
            csv.finish()?.commit()?;
            (text, outcome)
        }
        (None, true) => {
            let outcome = run_scene(&scene, &settings, Some((&mut rows, sampling)))?;
            (render(&outcome)?, outcome)
        }
        (None, false) => {
            let outcome = run_scene(&scene, &settings, None)?;
            (render(&outcome)?, outcome)
        }
    };
    if let Some(path) = &args.plot_trace {
        TraceFigure::new(&scene, &outcome, &rows).write("--plot-trace", path)?;
    }
    if let Some(table_phase) = &outcome.table {
        if let Some(path) = &args.ball_paths {
            let samples = args.ball_path_samples.unwrap_or(DEFAULT_BALL_PATH_SAMPLES);
            let rows = ball_path_rows(table_phase, samples);
            write_ball_paths(AtomicFile::create(path)?, &rows)?.commit()?;
        }
        if let Some(path) = &args.plot {
            write_plot(path, table_phase, &scene, &outcome)?;
        }
    }
    for w in &outcome.outcome.warnings {
        warn(w);
    }
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|_| stdout.flush())
        .map_err(|e| Error::io("stdout", e))
}

/// The top view of the table phase, SVG or PNG by the file name's extension.
fn write_plot(
    path: &Path,
    table_phase: &TableOutcome,
    scene: &Scene,
    outcome: &SceneOutcome,
) -> Result<(), Error> {
    TopView::new(scene, outcome, table_phase).write("--plot", path)
}
