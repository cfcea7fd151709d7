//! The `billiard-contact` command: parse, call the library, print.
//!
//! Exit codes: 0 success, 1 the run failed (integrator gave up, non-finite result, I/O
//! while writing), 2 bad input (scene, profile table, options).

use billiard_contact::formats::atomic_file::AtomicFile;
use billiard_contact::formats::report::{summary, Report};
use billiard_contact::formats::trace::CsvTrace;
use billiard_contact::table_phase::TableOutcome;
use billiard_contact::Error;
use billiard_contact::Scene;
use billiard_contact::{run_scene, SceneOutcome};
use billiard_contact::{Method, Sampling, SolverSettings};
use clap::{Args, Parser, Subcommand};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

/// Contact phase of billiard-ball collisions (Peskin 2020): closed form and time stepping.
#[derive(Parser)]
#[command(
    name = "billiard-contact",
    version,
    args_conflicts_with_subcommands = true
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Options of `run` when no subcommand is given (runs the built-in default scene).
    #[command(flatten)]
    run: RunArgs,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene (the built-in default scene when none is given).
    Run(RunArgs),
    /// Work-precision study: error against time per contact for every profile and method;
    /// writes DIR/work_precision.csv, .svg and .png.
    WorkPrecision(StudyArgs),
    /// Resolve one collision per row of a CSV file (see README, "Batch").
    Batch(BatchArgs),
}

#[derive(Args)]
struct StudyArgs {
    /// Scene file (TOML); the built-in default scene when omitted. Its balls, friction,
    /// impulse and duration are used with every profile.
    scene: Option<PathBuf>,
    /// Directory for work_precision.csv, .svg and .png (created if missing).
    #[arg(long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
    /// Profiles (comma-separated): half-sine, hertz, sine-power, rectangle, tabulated.
    #[arg(long, value_delimiter = ',', value_name = "P,...")]
    profiles: Option<Vec<String>>,
    /// Timed samples per setting (the median is reported).
    #[arg(long, value_name = "N", default_value_t = 9)]
    repeats: usize,
    /// Leave out the companion scene in which sliding stops during contact.
    #[arg(long)]
    no_sticking: bool,
    /// Only redraw the figure from DIR/work_precision.csv (e.g. after the peers' script
    /// appended its rows).
    #[arg(long)]
    replot: bool,
}

#[derive(Args)]
struct BatchArgs {
    /// Input CSV, one collision per row.
    input: PathBuf,
    /// Output CSV (written beside it and renamed into place when complete).
    #[arg(long, value_name = "OUTPUT.csv")]
    out: PathBuf,
    /// Method: closed-form (default), rk4, dopri5, dop853.
    #[arg(long, value_name = "M", default_value = "closed-form")]
    method: String,
    /// Relative tolerance of dopri5 / dop853 (atol = rtol); default: the scene's.
    #[arg(long, value_name = "X")]
    rtol: Option<f64>,
    /// Worker threads (default: all cores).
    #[arg(long, value_name = "N")]
    threads: Option<usize>,
    /// Scene giving balls, friction, impulse rule, profile and effects (default: the
    /// built-in default scene); rows may override some of them.
    #[arg(long, value_name = "SCENE")]
    scene: Option<PathBuf>,
    /// Rows per chunk (memory holds one chunk).
    #[arg(long, value_name = "N", default_value_t = billiard_contact::batch::DEFAULT_CHUNK_ROWS)]
    chunk: usize,
}

#[derive(Args, Clone, Default)]
struct RunArgs {
    /// Scene file (TOML); the built-in default scene when omitted.
    scene: Option<PathBuf>,
    /// Print one JSON object on stdout instead of the summary.
    #[arg(long)]
    json: bool,
    /// Write a CSV trace (centre-of-mass frame) to this file.
    #[arg(long, value_name = "FILE.csv")]
    trace: Option<PathBuf>,
    /// Trace rows at t = i duration / N, i = 0..N (plus the stick event), instead of one row
    /// per accepted step.
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    samples: Option<u64>,
    /// Method: closed-form, rk4, dopri5, dop853 (overrides the scene).
    #[arg(long, value_name = "M")]
    method: Option<String>,
    /// Relative tolerance (overrides the scene).
    #[arg(long, value_name = "X", allow_negative_numbers = true)]
    rtol: Option<f64>,
    /// Absolute tolerance on the scaled variables (default: rtol).
    #[arg(long, value_name = "X", allow_negative_numbers = true)]
    atol: Option<f64>,
    /// RK4 steps over the contact (overrides the scene).
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    steps: Option<u32>,
    /// Write both balls' paths on the table (lab frame, until both roll) to this CSV
    /// (needs `[effects] table = true`).
    #[arg(long, value_name = "FILE.csv")]
    path: Option<PathBuf>,
    /// Uniform intervals of the path CSV (plus every change of phase; default 200).
    #[arg(long, value_name = "N")]
    path_samples: Option<u64>,
    /// Draw a top view of both balls' paths with the line of centres (SVG, or PNG for a
    /// `.png` name; needs `[effects] table = true`).
    #[arg(long, value_name = "FILE.svg")]
    plot: Option<PathBuf>,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(
                e.kind(),
                ErrorKind::DisplayHelp
                    | ErrorKind::DisplayVersion
                    | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
            ) {
                e.exit();
            }
            // Bad options are bad input: one line (clap's first), exit code 2.
            let text = e.to_string();
            let first = text.lines().next().unwrap_or("error: invalid arguments");
            eprintln!("{} (see --help)", first.trim_end());
            return ExitCode::from(2);
        }
    };
    let result = match cli.command {
        Some(Command::Run(args)) => run(&args),
        Some(Command::WorkPrecision(args)) => work_precision(&args),
        Some(Command::Batch(args)) => batch(&args),
        None => run(&cli.run),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            if e.is_bad_input() {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}

/// The scene's solver settings with the command-line overrides applied.
fn settings(scene: &Scene, args: &RunArgs) -> Result<SolverSettings, Error> {
    let base = scene.solver;
    let method = match &args.method {
        Some(m) => m.parse::<Method>()?,
        None => base.method(),
    };
    let rtol = args.rtol.unwrap_or(base.rtol());
    // A new rtol carries atol with it unless atol is given too.
    let atol = args.atol.unwrap_or(if args.rtol.is_some() {
        rtol
    } else {
        base.atol()
    });
    let mut s = SolverSettings::new(method, rtol, atol, args.steps.unwrap_or(base.steps()))?;
    s = s.with_breakpoints(base.breakpoints());
    Ok(s)
}

fn run(args: &RunArgs) -> Result<(), Error> {
    let scene = match &args.scene {
        Some(p) => Scene::load(p)?,
        None => Scene::default_scene(),
    };
    let settings = settings(&scene, args)?;
    if args.samples == Some(0) {
        return Err(Error::invalid("--samples", 0, "at least 1"));
    }
    if (args.path.is_some() || args.plot.is_some()) && !scene.effects.table {
        return Err(Error::invalid(
            if args.path.is_some() {
                "--path"
            } else {
                "--plot"
            },
            "given",
            "the table effect: set `table = true` under [effects] in the scene (lab frame, \
             horizontal line of centres)",
        ));
    }
    if args.path_samples == Some(0) {
        return Err(Error::invalid("--path-samples", 0, "at least 1"));
    }
    let sampling = match args.samples {
        Some(n) => Sampling::Uniform(n),
        None => Sampling::Steps,
    };
    let render = |outcome: &SceneOutcome| -> Result<String, Error> {
        Ok(if args.json {
            Report::new(&scene, outcome).to_json()? + "\n"
        } else {
            summary(&scene, outcome)
        })
    };
    // The trace becomes visible only once the whole run, report included, succeeded.
    let (text, outcome) = match &args.trace {
        Some(path) => {
            let file = AtomicFile::create(path)?;
            let mut csv = CsvTrace::new(file)?;
            let outcome = run_scene(&scene, &settings, Some((&mut csv, sampling)))?;
            let text = render(&outcome)?;
            csv.finish()?.commit()?;
            (text, outcome)
        }
        None => {
            let outcome = run_scene(&scene, &settings, None)?;
            (render(&outcome)?, outcome)
        }
    };
    if let Some(table) = &outcome.table {
        if let Some(path) = &args.path {
            let rows = billiard_contact::formats::ball_paths::path_rows(
                table,
                args.path_samples
                    .unwrap_or(billiard_contact::formats::ball_paths::DEFAULT_PATH_SAMPLES),
            );
            billiard_contact::formats::ball_paths::write_path(AtomicFile::create(path)?, &rows)?
                .commit()?;
        }
        if let Some(path) = &args.plot {
            write_plot(path, table, &scene)?;
        }
    }
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|_| stdout.flush())
        .map_err(|e| Error::io("stdout", e))
}

/// The top view of the table phase: SVG through an atomic file, PNG for a `.png` name
/// (rendered beside the target and renamed into place).
fn write_plot(path: &std::path::Path, table: &TableOutcome, scene: &Scene) -> Result<(), Error> {
    use billiard_contact::plot::paths;
    let title = format!("{}: top view", scene.name);
    let png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if png {
        let file = AtomicFile::create(path)?;
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        let temp = path.with_file_name(format!(".{name}.{}.render.png", std::process::id()));
        let drawn = paths::png(table, scene.ball.radius, &title, &temp);
        let moved =
            drawn.and_then(|_| std::fs::rename(&temp, path).map_err(|e| Error::io(path, e)));
        if moved.is_err() {
            let _ = std::fs::remove_file(&temp);
        }
        drop(file);
        moved
    } else {
        let svg = paths::svg(table, scene.ball.radius, &title)?;
        let mut file = AtomicFile::create(path)?;
        file.write_all(svg.as_bytes())
            .map_err(|e| Error::io(path, e))?;
        file.commit()
    }
}

fn progress_bar(len: u64, template: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(len),
        indicatif::ProgressDrawTarget::stderr(),
    );
    bar.set_style(
        indicatif::ProgressStyle::with_template(template)
            .expect("a valid progress template")
            .progress_chars("=> "),
    );
    bar
}

fn work_precision(args: &StudyArgs) -> Result<(), Error> {
    use billiard_contact::plot::work_precision as figure;
    use billiard_contact::work_precision::{self, ProfileKind, StudyOptions};
    let csv_path = args.out.join("work_precision.csv");
    let svg = args.out.join("work_precision.svg");
    let png = args.out.join("work_precision.png");
    if args.replot {
        let file = std::fs::File::open(&csv_path).map_err(|e| Error::io(&csv_path, e))?;
        let rows = work_precision::read_csv(std::io::BufReader::new(file), &csv_path)?;
        figure::write(&rows, &svg, &png)?;
        print!("{}", work_precision::summary(&rows));
        println!("\nwrote {} and {}", svg.display(), png.display());
        return Ok(());
    }
    let scene = match &args.scene {
        Some(p) => Scene::load(p)?,
        None => Scene::default_scene(),
    };
    let mut options = StudyOptions::default();
    if let Some(list) = &args.profiles {
        options.profiles = list
            .iter()
            .map(|p| p.trim().parse::<ProfileKind>())
            .collect::<Result<_, _>>()?;
    }
    if args.repeats == 0 {
        return Err(Error::invalid("--repeats", 0, "at least 1"));
    }
    options.repeats = args.repeats;
    options.sticking_scene = !args.no_sticking;
    std::fs::create_dir_all(&args.out).map_err(|e| Error::io(&args.out, e))?;
    let start = std::time::Instant::now();
    let mut bar: Option<indicatif::ProgressBar> = None;
    let rows = work_precision::run_study(scene, &options, |done, total, row| {
        let b = bar.get_or_insert_with(|| {
            progress_bar(total as u64, "{elapsed:>4} [{bar:40}] {pos}/{len} {msg}")
        });
        b.set_position(done as u64);
        b.set_message(format!("{} {}", row.profile, row.method));
    })?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let mut file = AtomicFile::create(&csv_path)?;
    work_precision::write_csv(&mut file, &rows)?;
    file.commit()?;
    figure::write(&rows, &svg, &png)?;
    print!("{}", work_precision::summary(&rows));
    for r in rows.iter().filter(|r| !r.note.is_empty()) {
        eprintln!(
            "warning: {} {} {:?} failed: {}",
            r.profile, r.method, r.rtol, r.note
        );
    }
    println!(
        "\nwrote {}, {} and {} in {:.1} s",
        csv_path.display(),
        svg.display(),
        png.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

fn batch(args: &BatchArgs) -> Result<(), Error> {
    use billiard_contact::batch::{run_csv, BatchSetup};
    let scene = match &args.scene {
        Some(p) => Scene::load(p)?,
        None => Scene::default_scene(),
    };
    let method = args.method.parse::<Method>()?;
    let base = scene.solver;
    let rtol = args.rtol.unwrap_or(base.rtol());
    let atol = if args.rtol.is_some() {
        rtol
    } else {
        base.atol()
    };
    let mut settings = SolverSettings::new(method, rtol, atol, base.steps())?;
    settings = settings.with_breakpoints(base.breakpoints());
    if args.threads == Some(0) {
        return Err(Error::invalid("--threads", 0, "at least 1"));
    }
    if args.chunk == 0 {
        return Err(Error::invalid("--chunk", 0, "at least 1"));
    }
    let setup = BatchSetup::from_scene(&scene, settings);
    let input = std::fs::File::open(&args.input).map_err(|e| Error::io(&args.input, e))?;
    let size = input.metadata().map(|m| m.len()).unwrap_or(0);
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = args.threads {
        pool = pool.num_threads(n);
    }
    let pool = pool.build()?;
    let bar = progress_bar(size, "{elapsed:>4} [{bar:40}] {bytes}/{total_bytes} {msg}");
    let start = std::time::Instant::now();
    let out = AtomicFile::create(&args.out)?;
    let (out, summary) = pool.install(|| {
        run_csv(
            &setup,
            std::io::BufReader::with_capacity(1 << 16, input),
            &args.input,
            out,
            args.chunk,
            |rows, bytes| {
                bar.set_position(bytes);
                bar.set_message(format!("{rows} rows"));
            },
        )
    })?;
    out.commit()?;
    bar.finish_and_clear();
    let secs = start.elapsed().as_secs_f64();
    eprintln!(
        "{} rows ({} collisions, {} stick) in {:.2} s ({:.0} rows/s, {} threads, {}) -> {}",
        summary.rows,
        summary.collisions,
        summary.sticks,
        secs,
        summary.rows as f64 / secs.max(1e-9),
        pool.current_num_threads(),
        method,
        args.out.display()
    );
    Ok(())
}
