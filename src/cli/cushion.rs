//! `billiard-contact run` on a cushion scene (a `[cushion]` instead of ball B): the impact's
//! report or summary on stdout, and optionally its trace CSV and trace figure.

use crate::apps::plot::cushion::cushion_figure;
use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::settings::check_steps_as;
use crate::cli::common::warn;
use crate::cli::run::RunArgs;
use crate::cushion::outcome::CushionTraceRow;
use crate::outputs::atomic_file::AtomicFile;
use crate::outputs::cushion::{cushion_summary, CushionCsv, CushionReport};
use crate::scene::cushion::CushionScene;
use crate::scene::file::is_cushion_scene;
use std::io::Write;
use std::path::Path;

/// The cushion scene in the file `path`, or `None` when it is not one (no `[cushion]`).
pub(super) fn cushion_scene(path: &Path) -> Result<Option<CushionScene>, Error> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Error::io_doing(path, "cannot read the scene file", e))?;
    if !is_cushion_scene(&text) {
        return Ok(None);
    }
    CushionScene::parse(&text, Some(path)).map(Some)
}

/// Refuses the options of `run` that have no meaning for a cushion impact, naming them.
fn refuse_two_ball_options(args: &RunArgs) -> Result<(), Error> {
    let table = "only with the table effect of a two-ball scene (a cushion scene ends with the \
                 impact)";
    let refused = [
        (
            "--path",
            args.ball_paths.as_ref().map(|p| p.display().to_string()),
            table,
        ),
        (
            "--plot",
            args.plot.as_ref().map(|p| p.display().to_string()),
            table,
        ),
        (
            "--path-samples",
            args.ball_path_samples.map(|n| n.to_string()),
            table,
        ),
        (
            "--samples",
            args.samples.map(|n| n.to_string()),
            "not for a cushion scene: its trace has a row at the start, after every step, at \
             every slip event and at the end (it is stepped in the impulse, not in time)",
        ),
    ];
    for (option, value, why) in refused {
        if let Some(value) = value {
            return Err(Error::invalid(option, value, why));
        }
    }
    Ok(())
}

/// Runs the cushion scene; prints the JSON report or the summary once every file is written.
pub(super) fn run(args: &RunArgs, scene: &CushionScene) -> Result<(), Error> {
    refuse_two_ball_options(args)?;
    for (option, path) in [("--plot-trace", &args.plot_trace)] {
        if let Some(path) = path {
            crate::apps::plot::FigureFormat::of(option, path)?;
        }
    }
    if let Some(n) = args.steps {
        check_steps_as("--steps", n)?;
    }
    let settings = args.solver_overrides().apply(&scene.solver)?;
    if let Some(n) = args.steps {
        if settings.method() != Method::Rk4 {
            return Err(Error::invalid(
                "--steps",
                n,
                format!(
                    "only with the method rk4 (this run's is {}, which chooses its own steps \
                     from --rtol): add --method rk4",
                    settings.method()
                ),
            ));
        }
    }
    if args.time_transform.is_some() {
        warn("--time-transform has no effect on a cushion impact (stepped in the impulse)");
    }
    if settings.method() == Method::Rk4 && (args.rtol.is_some() || args.atol.is_some()) {
        warn("--rtol and --atol have no effect with rk4 (fixed steps)");
    }
    let mut csv = match &args.trace {
        Some(path) => Some(CushionCsv::new(AtomicFile::create(path)?)?),
        None => None,
    };
    let mut rows: Vec<CushionTraceRow> = Vec::new();
    let keep_rows = args.plot_trace.is_some();
    let mut sink = |r: &CushionTraceRow| {
        if let Some(csv) = csv.as_mut() {
            csv.row(r);
        }
        if keep_rows {
            rows.push(*r);
        }
    };
    let traced = args.trace.is_some() || keep_rows;
    let out = scene.run(
        &settings,
        if traced {
            Some(&mut sink as &mut dyn FnMut(&CushionTraceRow))
        } else {
            None
        },
    )?;
    let text = if args.json {
        CushionReport::new(scene, &settings, &out).to_json()? + "\n"
    } else {
        cushion_summary(scene, &settings, &out)
    };
    if let Some(csv) = csv {
        csv.finish()?.commit()?;
    }
    if let Some(path) = &args.plot_trace {
        cushion_figure(scene, &settings, &out, &rows).write("--plot-trace", path)?;
    }
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|_| stdout.flush())
        .map_err(|e| Error::io("stdout", e))
}
