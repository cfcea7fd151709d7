//! `billiard-contact run` on a cluster scene (`[[balls]]`, docs/cluster.md): the run's report
//! or summary on stdout, and optionally its trace CSV (`--trace`, `--samples`), the trace
//! figure (`--plot-trace`) and the top view of the outgoing velocities (`--plot`). The
//! options of the two-ball stepping and of the table phase are refused, naming them.

use crate::apps::plot::cluster::{ClusterTopView, ClusterTraceData, ClusterTraceFigure};
use crate::apps::plot::FigureFormat;
use crate::base::error::Error;
use crate::base::settings::check_samples;
use crate::cli::run::RunArgs;
use crate::cluster::resolve::{
    ClusterOutcome, ClusterSampling, ClusterSettings, ClusterTrace, ClusterTraceRow,
};
use crate::outputs::atomic_file::AtomicFile;
use crate::outputs::cluster::{cluster_summary, ClusterReport};
use crate::outputs::cluster_trace::{ClusterColumns, ClusterTraceCsv};
use crate::scene::cluster::{ClusterScene, CLUSTER_RTOL_FIELD};
use crate::scene::file::is_cluster_scene;
use std::io::Write;
use std::path::Path;

/// The cluster scene in the file `path`, or `None` when it is not one (no `[[balls]]`).
pub(super) fn cluster_scene(path: &Path) -> Result<Option<ClusterScene>, Error> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Error::io_doing(path, "cannot read the scene file", e))?;
    if !is_cluster_scene(&text) {
        return Ok(None);
    }
    ClusterScene::parse(&text, Some(path)).map(Some)
}

/// Refuses the options of `run` that have no meaning for a cluster, naming the first given.
fn refuse_options(args: &RunArgs) -> Result<(), Error> {
    let shown = |p: &Option<std::path::PathBuf>| p.as_ref().map(|p| p.display().to_string());
    let own_stepping = "not for a cluster scene: its own Dormand-Prince 5(4) stepping, set by \
                        --rtol alone";
    let no_table = "not for a cluster scene: it ends when the last contact opens (no table \
                    phase)";
    let refused = [
        (
            "--method",
            args.method.map(|m| m.0.name().to_string()),
            own_stepping,
        ),
        ("--steps", args.steps.map(|n| n.to_string()), own_stepping),
        ("--atol", args.atol.map(|x| x.to_string()), own_stepping),
        (
            "--time-transform",
            args.time_transform.map(|b| b.to_string()),
            own_stepping,
        ),
        ("--path", shown(&args.ball_paths), no_table),
        (
            "--path-samples",
            args.ball_path_samples.map(|n| n.to_string()),
            no_table,
        ),
    ];
    for (option, value, why) in refused {
        if let Some(value) = value {
            return Err(Error::invalid(option, value, why));
        }
    }
    for (option, path) in [("--plot", &args.plot), ("--plot-trace", &args.plot_trace)] {
        if let Some(path) = path {
            FigureFormat::of(option, path)?;
        }
    }
    if let Some(n) = args.samples {
        check_samples("--samples", n)?;
        if args.trace.is_none() && args.plot_trace.is_none() {
            return Err(Error::invalid(
                "--samples",
                n,
                "only with --trace FILE.csv or --plot-trace FILE.svg|png (it sets the \
                 trace's rows)",
            ));
        }
    }
    Ok(())
}

/// The sample times of `--samples n` for the run `out`: t_0 + i (t_end - t_0) / n,
/// i = 0..n, from the first touch t_0 to the end of the run t_end (s; the last exactly t_end).
fn sample_times(out: &ClusterOutcome, n: u64) -> Vec<f64> {
    let (t0, t1) = (out.first_touch.min(out.time), out.time);
    (0..=n)
        .map(|i| {
            if i == n {
                t1
            } else {
                t0 + (t1 - t0) * (i as f64 / n as f64)
            }
        })
        .collect()
}

/// The traced run of `scene` (whose run without a trace gave `first`): the trace CSV
/// written to `--trace` (committed by the caller once the report is made) and the rows the
/// figure draws; the run's outcome, the same as `first`'s.
fn traced_run(
    args: &RunArgs,
    scene: &ClusterScene,
    settings: &ClusterSettings,
    first: &ClusterOutcome,
) -> Result<
    (
        ClusterOutcome,
        Option<ClusterTraceCsv<AtomicFile>>,
        ClusterTraceData,
    ),
    Error,
> {
    let mut columns = ClusterColumns::new(&scene.cluster, first);
    let mut csv = match &args.trace {
        Some(path) => Some(ClusterTraceCsv::new(
            AtomicFile::create(path)?,
            columns.header(),
        )?),
        None => None,
    };
    let mut data = ClusterTraceData::new(&columns);
    let keep = args.plot_trace.is_some();
    let times = args.samples.map(|n| sample_times(first, n));
    let mut sink = |row: &ClusterTraceRow<'_>| {
        let cells = columns.cells(row);
        if let Some(csv) = csv.as_mut() {
            csv.row(&cells);
        }
        if keep {
            data.push(&cells);
        }
    };
    let trace = ClusterTrace {
        sampling: match &times {
            Some(t) => ClusterSampling::Times(t),
            None => ClusterSampling::Steps,
        },
        sink: &mut sink,
    };
    let out = scene.run_traced(settings, rtol_field(args), trace)?;
    Ok((out, csv, data))
}

/// The field a bad tolerance is named by: `--rtol` when given, else the scene's.
fn rtol_field(args: &RunArgs) -> &'static str {
    if args.rtol.is_some() {
        "--rtol"
    } else {
        CLUSTER_RTOL_FIELD
    }
}

/// Runs the cluster scene (`--rtol` overriding its tolerance); prints the JSON report or the
/// summary. A run that does not end with every contact open fails (exit code 1).
pub(super) fn run(args: &RunArgs, scene: &ClusterScene) -> Result<(), Error> {
    refuse_options(args)?;
    let mut settings = scene.settings;
    if let Some(rtol) = args.rtol {
        settings.rtol = rtol;
    }
    let mut out = scene.run(&settings, rtol_field(args))?;
    // A trace's columns are the pairs that pressed and its samples span the run: both known
    // from the run above, the trace is taken by a second run, the same to the last bit.
    let mut traced = None;
    if args.trace.is_some() || args.plot_trace.is_some() {
        let (again, csv, data) = traced_run(args, scene, &settings, &out)?;
        debug_assert!(again == out, "a trace changed the run");
        out = again;
        traced = Some((csv, data));
    }
    let text = if args.json {
        ClusterReport::new(scene, &settings, &out).to_json()? + "\n"
    } else {
        cluster_summary(scene, &settings, &out)
    };
    // The files become visible only once the whole run, report included, succeeded.
    if let Some((csv, data)) = traced {
        if let Some(csv) = csv {
            csv.finish()?.commit()?;
        }
        if let Some(path) = &args.plot_trace {
            ClusterTraceFigure::new(scene, &settings, &out, &data, args.samples)
                .write("--plot-trace", path)?;
        }
    }
    if let Some(path) = &args.plot {
        ClusterTopView::new(scene, &out).write("--plot", path)?;
    }
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|_| stdout.flush())
        .map_err(|e| Error::io("stdout", e))
}
