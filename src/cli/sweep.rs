//! `billiard-contact sweep`: a throw chart, one scene run over a grid of shots, written as
//! a CSV and a figure, with a progress bar on stderr and the largest throw of each curve on
//! stdout.

use crate::apps::plot::sweep as figure;
use crate::apps::sweep::{self, parse_list, Grid, Spin};
use crate::base::error::Error;
use crate::cli::choice::MethodChoice;
use crate::cli::common::{load_two_ball_scene, progress_bar};
use crate::outputs::atomic_file::AtomicFile;
use crate::scene::overrides::SolverOverrides;
use clap::Args;
use std::path::PathBuf;

/// The options of `sweep`.
#[derive(Args)]
pub(super) struct SweepArgs {
    /// Scene file (TOML; the built-in default scene when omitted): its balls, contact,
    /// profile, solver and effects. Its incoming state is replaced by each shot's: the cue
    /// ball A moves along +y toward the object ball B at rest, B at the cut angle to the
    /// right of A's path.
    scene: Option<PathBuf>,
    /// Cut angles (degrees, in (-90, 90)): numbers or ranges start:stop:step,
    /// comma-separated.
    #[arg(
        long,
        value_name = "DEG",
        default_value = "0:60:1",
        allow_hyphen_values = true
    )]
    cut: String,
    /// Cue-ball speeds (m/s), comma-separated.
    #[arg(
        long,
        value_name = "V,...",
        default_value = "0.447,1.341,3.129",
        allow_hyphen_values = true
    )]
    speed: String,
    /// Cue-ball spins, comma-separated: stun (none), roll (natural roll, topspin v/r),
    /// draw (backspin v/r), or a number k (topspin k v/r).
    #[arg(long, value_name = "S,...", default_value = "stun,roll,draw")]
    spin: String,
    /// Side spins as fractions of v/r, comma-separated. Sign convention: positive is inside
    /// English (spin on the side of the cut, counter-clockwise seen from above for a
    /// positive cut), which adds to the cut's throw; negative is outside English.
    #[arg(
        long,
        value_name = "F,...",
        default_value = "0",
        allow_hyphen_values = true
    )]
    side: String,
    /// Method (default: the scene's).
    #[arg(long, value_name = "M")]
    method: Option<MethodChoice>,
    /// Directory for sweep.csv, sweep.svg and sweep.png (created if missing).
    #[arg(long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
}

/// Runs the sweep, writes its CSV and figure, and prints the largest throw of each curve.
pub(super) fn sweep(args: &SweepArgs) -> Result<(), Error> {
    let scene = load_two_ball_scene(args.scene.as_deref(), "sweep")?;
    let overrides = SolverOverrides {
        method: args.method.map(|m| m.0),
        ..SolverOverrides::default()
    };
    let settings = overrides.apply(&scene.solver)?;
    let spins = args
        .spin
        .split(',')
        .map(Spin::parse)
        .collect::<Result<Vec<_>, _>>()?;
    let grid = Grid::new(
        spins,
        parse_list("--speed", &args.speed)?,
        parse_list("--side", &args.side)?,
        parse_list("--cut", &args.cut)?,
    )?;
    std::fs::create_dir_all(&args.out).map_err(|e| Error::io(&args.out, e))?;
    let start = std::time::Instant::now();
    let bar = progress_bar(
        grid.len() as u64,
        "{elapsed:>4} [{bar:40}] {pos}/{len} shots",
    );
    let rows = sweep::run_sweep(&scene, &settings, &grid, |done| {
        bar.set_position(done as u64)
    })?;
    bar.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    let rolling = scene.effects.table;
    let csv_path = args.out.join("sweep.csv");
    let mut file = AtomicFile::create(&csv_path)?;
    sweep::write_csv(file.writer(), &rows, rolling)?;
    file.commit()?;
    let (svg, png) = (args.out.join("sweep.svg"), args.out.join("sweep.png"));
    figure::write(&rows, &figure::title(&scene), &svg, &png)?;
    print!("{}", sweep::summary(&rows));
    println!(
        "\n{} shots ({}) in {:.3} s; wrote {}, {} and {}",
        rows.len(),
        settings.method(),
        seconds,
        csv_path.display(),
        svg.display(),
        png.display()
    );
    Ok(())
}
