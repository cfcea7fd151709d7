//! `billiard-contact rebound`: a cushion scene's ball sent into its cushion over a grid of
//! incidence angles, speeds, spins and side spins; the rebound angles and speeds written as
//! a CSV and a figure, with a progress bar on stderr and a summary on stdout.

use crate::apps::plot::rebound as figure;
use crate::apps::rebound::{self, grid, parse_incidences, parse_spin};
use crate::apps::sweep::parse_list;
use crate::base::error::Error;
use crate::cli::choice::MethodChoice;
use crate::cli::common::progress_bar;
use crate::cli::cushion::cushion_scene;
use crate::outputs::atomic_file::AtomicFile;
use crate::outputs::cushion::contact_angle_deg;
use crate::scene::cushion::CushionScene;
use crate::scene::overrides::SolverOverrides;
use clap::Args;
use std::path::PathBuf;

/// The built-in cushion scene of `rebound` (`data/scenes/cushion_stun_45.toml`).
const DEFAULT_CUSHION_SCENE: &str = include_str!("../../data/scenes/cushion_stun_45.toml");

/// The options of `rebound`.
#[derive(Args)]
pub(super) struct ReboundArgs {
    /// Cushion scene (TOML with `[cushion]`; default: the built-in
    /// data/scenes/cushion_stun_45.toml): its ball, cushion and solver. Its incoming state
    /// is replaced by each shot's.
    scene: Option<PathBuf>,
    /// Incidence angles from the cushion's normal (degrees, in [0, 90)): numbers or ranges
    /// start:stop:step, comma-separated.
    #[arg(
        long,
        value_name = "DEG",
        default_value = "0:85:2.5",
        allow_hyphen_values = true
    )]
    incidence: String,
    /// Speeds (m/s), comma-separated (the rigid impact scales with the speed: the angles and
    /// speed ratios do not depend on it).
    #[arg(
        long,
        value_name = "V,...",
        default_value = "2",
        allow_hyphen_values = true
    )]
    speed: String,
    /// Spins, comma-separated: stun (none), follow (natural roll, topspin v/r), draw
    /// (backspin v/r), or a number k (topspin k v/r).
    #[arg(long, value_name = "S,...", default_value = "stun,follow,draw")]
    spin: String,
    /// Side spins as fractions of v/r about the vertical, comma-separated (positive:
    /// counter-clockwise seen from above, which turns the rebound toward +x).
    #[arg(
        long,
        value_name = "F,...",
        default_value = "-0.5,0,0.5",
        allow_hyphen_values = true
    )]
    side: String,
    /// Method (default: the scene's; dop853, dopri5 or rk4).
    #[arg(long, value_name = "M")]
    method: Option<MethodChoice>,
    /// Directory for rebound.csv, rebound.svg and rebound.png (created if missing).
    #[arg(long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
}

/// Runs the sweep, writes its CSV and figure, and prints a summary.
pub(super) fn rebound(args: &ReboundArgs) -> Result<(), Error> {
    let scene = match &args.scene {
        Some(path) => cushion_scene(path)?.ok_or_else(|| {
            Error::invalid(
                "scene",
                path.display(),
                "a cushion scene (with [cushion], docs/cushion.md): rebound sends its ball \
                 into its cushion",
            )
        })?,
        None => CushionScene::parse(DEFAULT_CUSHION_SCENE, None)?,
    };
    let overrides = SolverOverrides {
        method: args.method.map(|m| m.0),
        ..SolverOverrides::default()
    };
    let settings = overrides.apply(&scene.solver)?;
    let spins = args
        .spin
        .split(',')
        .map(parse_spin)
        .collect::<Result<Vec<_>, _>>()?;
    let shots = grid(
        &spins,
        &parse_list("--speed", &args.speed)?,
        &parse_list("--side", &args.side)?,
        &parse_incidences(&args.incidence)?,
    )?;
    std::fs::create_dir_all(&args.out).map_err(|e| Error::io(&args.out, e))?;
    let start = std::time::Instant::now();
    let bar = progress_bar(
        shots.len() as u64,
        "{elapsed:>4} [{bar:40}] {pos}/{len} impacts",
    );
    let rows = rebound::run_rebound(&scene, &settings, &shots, |done| {
        bar.set_position(done as u64)
    })?;
    bar.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    let csv_path = args.out.join("rebound.csv");
    let mut file = AtomicFile::create(&csv_path)?;
    rebound::write_csv(file.writer(), &rows)?;
    file.commit()?;
    let (svg, png) = (args.out.join("rebound.svg"), args.out.join("rebound.png"));
    let (b, c) = (&scene.ball, &scene.cushion);
    let title = format!(
        "Cushion rebound: contact {:.1} deg above the equator, mu_cushion {}, mu_table {}, e {} \
         ({})",
        contact_angle_deg(c.height(), b.radius()),
        c.mu_cushion(),
        c.mu_table(),
        c.restitution(),
        c.rule().name()
    );
    figure::write(&rows, &title, &svg, &png)?;
    print!("{}", rebound::summary(&rows));
    println!(
        "\n{} impacts ({}) in {:.3} s; wrote {}, {} and {}",
        rows.len(),
        settings.method(),
        seconds,
        csv_path.display(),
        svg.display(),
        png.display()
    );
    Ok(())
}
