//! The `billiard-contact` command: parse, call the library, print.
//!
//! Exit codes: 0 success, 1 the run failed (integrator gave up, non-finite result, I/O
//! while writing), 2 bad input (scene, profile table, options).

use billiard_contact::integrate::{Method, Sampling, SolverSettings};
use billiard_contact::output::AtomicFile;
use billiard_contact::report::{summary, Report};
use billiard_contact::runner::run_scene;
use billiard_contact::scene::Scene;
use billiard_contact::trace::CsvTrace;
use billiard_contact::Error;
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
        None => base.method,
    };
    let rtol = args.rtol.unwrap_or(base.rtol);
    // A new rtol carries atol with it unless atol is given too.
    let atol = args
        .atol
        .unwrap_or(if args.rtol.is_some() { rtol } else { base.atol });
    let mut s = SolverSettings::new(method, rtol, atol, args.steps.unwrap_or(base.steps))?;
    s.breakpoints = base.breakpoints;
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
    let sampling = match args.samples {
        Some(n) => Sampling::Uniform(n),
        None => Sampling::Steps,
    };
    let render = |outcome| -> Result<String, Error> {
        Ok(if args.json {
            Report::new(&scene, &outcome).to_json()? + "\n"
        } else {
            summary(&scene, &outcome)
        })
    };
    // The trace becomes visible only once the whole run, report included, succeeded.
    let text = match &args.trace {
        Some(path) => {
            let file = AtomicFile::create(path)?;
            let mut csv = CsvTrace::new(file)?;
            let text = render(run_scene(&scene, &settings, Some((&mut csv, sampling)))?)?;
            csv.finish()?.commit()?;
            text
        }
        None => render(run_scene(&scene, &settings, None)?)?,
    };
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|_| stdout.flush())
        .map_err(|e| Error::io("stdout", e))
}
