//! `billiard-contact run` on a cluster scene (`[[balls]]`, docs/cluster.md): the run's report
//! or summary on stdout. Traces of clusters are not yet written: the options of traces,
//! methods and the table phase are refused, naming them.

use crate::base::error::Error;
use crate::cli::run::RunArgs;
use crate::outputs::cluster::{cluster_summary, ClusterReport};
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
    let no_trace = "not for a cluster scene: traces of clusters are not yet written";
    let own_stepping = "not for a cluster scene: its own Dormand-Prince 5(4) stepping, set by \
                        --rtol alone";
    let no_table = "not for a cluster scene: it ends when the last contact opens (no table \
                    phase)";
    let refused = [
        ("--trace", shown(&args.trace), no_trace),
        ("--samples", args.samples.map(|n| n.to_string()), no_trace),
        ("--plot-trace", shown(&args.plot_trace), no_trace),
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
        ("--plot", shown(&args.plot), no_table),
    ];
    for (option, value, why) in refused {
        if let Some(value) = value {
            return Err(Error::invalid(option, value, why));
        }
    }
    Ok(())
}

/// Runs the cluster scene (`--rtol` overriding its tolerance); prints the JSON report or the
/// summary. A run that does not end with every contact open fails (exit code 1).
pub(super) fn run(args: &RunArgs, scene: &ClusterScene) -> Result<(), Error> {
    refuse_options(args)?;
    let mut settings = scene.settings;
    let mut rtol_field = CLUSTER_RTOL_FIELD;
    if let Some(rtol) = args.rtol {
        settings.rtol = rtol;
        rtol_field = "--rtol";
    }
    let out = scene.run(&settings, rtol_field)?;
    let text = if args.json {
        ClusterReport::new(scene, &settings, &out).to_json()? + "\n"
    } else {
        cluster_summary(scene, &settings, &out)
    };
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|_| stdout.flush())
        .map_err(|e| Error::io("stdout", e))
}
