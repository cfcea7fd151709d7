//! `billiard-contact batch`: one collision per row of a CSV file, streamed in chunks over a
//! thread pool, with a progress bar and a one-line account on stderr.

use crate::apps::batch::cushion::run_cushion_csv;
use crate::apps::batch::{run_csv, BatchSetup, BatchSummary, DEFAULT_CHUNK_ROWS, MAX_CHUNK_ROWS};
use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::number::count;
use crate::cli::choice::{number, whole, MethodChoice};
use crate::cli::common::{load_two_ball_scene, progress_bar, solver_options_unused, warn};
use crate::cli::cushion::cushion_scene;
use crate::outputs::atomic_file::AtomicFile;
use crate::scene::cushion::CushionScene;
use crate::scene::overrides::SolverOverrides;
use clap::Args;
use std::fs::File;
use std::io::BufReader;
use std::path::PathBuf;

/// The options of `batch`.
#[derive(Args)]
pub(super) struct BatchArgs {
    /// Input CSV, one collision per row.
    input: PathBuf,
    /// Output CSV (written beside it and renamed into place when complete).
    #[arg(long, value_name = "OUTPUT.csv")]
    out: PathBuf,
    /// Method (default closed-form; for a cushion scene, which has no closed form, the
    /// scene's, dop853 unless it says otherwise).
    #[arg(long, value_name = "M")]
    method: Option<MethodChoice>,
    /// Relative tolerance of dopri5 / dop853 (atol = rtol); default: the scene's.
    #[arg(long, value_name = "X", allow_hyphen_values = true, value_parser = number)]
    rtol: Option<f64>,
    /// Worker threads (default: all cores).
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = whole::<usize>)]
    threads: Option<usize>,
    /// Scene giving balls, friction, impulse rule, profile and effects (default: the
    /// built-in default scene); rows may override some of them.
    #[arg(long, value_name = "SCENE")]
    scene: Option<PathBuf>,
    /// Smoothed time variable for hertz and fractional sine-power pulses (default: the
    /// scene's, true).
    #[arg(long, value_name = "BOOL")]
    time_transform: Option<bool>,
    /// Rows per chunk (memory holds one chunk).
    #[arg(
        long,
        value_name = "N",
        default_value_t = DEFAULT_CHUNK_ROWS,
        allow_hyphen_values = true,
        value_parser = whole::<usize>
    )]
    chunk: usize,
}

/// Resolves every row of the input into the output CSV (written whole or not at all).
pub(super) fn batch(args: &BatchArgs) -> Result<(), Error> {
    check_pool_and_chunk(args)?;
    if let Some(path) = &args.scene {
        if let Some(scene) = cushion_scene(path)? {
            return cushion_batch(args, &scene);
        }
    }
    let scene = load_two_ball_scene(args.scene.as_deref(), "batch")?;
    let method: Method = args.method.map_or(Method::ClosedForm, |m| m.0);
    let overrides = SolverOverrides {
        method: Some(method),
        rtol: args.rtol,
        time_transform: args.time_transform,
        ..SolverOverrides::default()
    };
    let settings = overrides.apply(&scene.solver)?;
    for w in solver_options_unused(&overrides, &settings, scene.law.is_some()) {
        warn(w);
    }
    if scene.effects.table {
        warn(format!(
            "--scene {}: the effect table is not simulated by batch (each row ends at \
             separation); `run --path` follows a lab scene on the table",
            scene_name(args)
        ));
    }
    let setup = BatchSetup::from_scene(&scene, settings);
    let (summary, secs, threads) = streamed(args, "row", "rows", |input, out, progress| {
        run_csv(&setup, input, &args.input, out, args.chunk, progress)
    })?;
    eprintln!(
        "{} ({}, {} stick) in {:.2} s ({:.0} rows/s, {}, {}) -> {}",
        count(summary.rows, "row", "rows"),
        count(summary.collisions, "collision", "collisions"),
        summary.sticks,
        secs,
        summary.rows as f64 / secs.max(1e-9),
        count(threads as u64, "thread", "threads"),
        method,
        args.out.display()
    );
    Ok(())
}

/// The scene as the user named it: its file, or the built-in scene.
fn scene_name(args: &BatchArgs) -> String {
    args.scene
        .as_ref()
        .map_or_else(|| "(built-in)".into(), |p| p.display().to_string())
}

/// Refuses --threads 0 and a --chunk of 0 or past [`MAX_CHUNK_ROWS`].
fn check_pool_and_chunk(args: &BatchArgs) -> Result<(), Error> {
    if args.threads == Some(0) {
        return Err(Error::invalid("--threads", 0, "at least 1"));
    }
    if args.chunk == 0 {
        return Err(Error::invalid("--chunk", 0, "at least 1"));
    }
    if args.chunk > MAX_CHUNK_ROWS {
        return Err(Error::invalid(
            "--chunk",
            args.chunk,
            format!(
                "at most {MAX_CHUNK_ROWS} rows (memory holds one chunk, up to about 1 kB a row)"
            ),
        ));
    }
    Ok(())
}

/// A batch of impacts on the cushion of a cushion scene (docs/formats.md#cushion-batch-csv).
fn cushion_batch(args: &BatchArgs, scene: &CushionScene) -> Result<(), Error> {
    let overrides = SolverOverrides {
        method: args.method.map(|m| m.0),
        rtol: args.rtol,
        ..SolverOverrides::default()
    };
    let settings = overrides.apply(&scene.solver)?;
    if settings.method() == Method::ClosedForm {
        return Err(Error::invalid(
            "--method",
            "closed-form",
            "dop853, dopri5 or rk4 for a cushion scene: the cushion's two coupled slips have no \
             closed form",
        ));
    }
    if args.time_transform.is_some() {
        warn("--time-transform has no effect on a cushion impact (stepped in the impulse)");
    }
    let (summary, secs, threads) = streamed(
        args,
        "cushion impact",
        "cushion impacts",
        |input, out, progress| {
            run_cushion_csv(
                scene,
                &settings,
                input,
                &args.input,
                out,
                args.chunk,
                progress,
            )
        },
    )?;
    eprintln!(
        "{} ({} leave the cloth) in {:.2} s ({:.0} impacts/s, {}, {}) -> {}",
        count(summary.rows, "cushion impact", "cushion impacts"),
        summary.sticks,
        secs,
        summary.rows as f64 / secs.max(1e-9),
        count(threads as u64, "thread", "threads"),
        settings.method(),
        args.out.display()
    );
    Ok(())
}

/// The streaming shared by both kinds of batch: opens the input, runs `stream` (input,
/// output, progress) on a pool of `--threads` with a progress bar counting `one`/`many`,
/// and commits the output. Returns the summary, the seconds taken and the threads used.
fn streamed(
    args: &BatchArgs,
    one: &str,
    many: &str,
    stream: impl FnOnce(
            BufReader<File>,
            AtomicFile,
            &mut dyn FnMut(u64, u64),
        ) -> Result<(AtomicFile, BatchSummary), Error>
        + Send,
) -> Result<(BatchSummary, f64, usize), Error> {
    let input = File::open(&args.input)
        .map_err(|e| Error::io_doing(&args.input, "cannot read the batch input", e))?;
    let size = input.metadata().map(|m| m.len()).unwrap_or(0);
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = args.threads {
        pool = pool.num_threads(n);
    }
    let pool = pool.build()?;
    let bar = progress_bar(size, "{elapsed:>4} [{bar:40}] {bytes}/{total_bytes} {msg}");
    let start = std::time::Instant::now();
    let out = AtomicFile::create(&args.out)?;
    let mut progress = |rows: u64, bytes: u64| {
        bar.set_position(bytes);
        bar.set_message(count(rows, one, many));
    };
    let (out, summary) =
        pool.install(|| stream(BufReader::with_capacity(1 << 16, input), out, &mut progress))?;
    out.commit()?;
    bar.finish_and_clear();
    Ok((
        summary,
        start.elapsed().as_secs_f64(),
        pool.current_num_threads(),
    ))
}
