//! The command's arguments, its subcommands and its exit codes.

use crate::base::names::closest;
use crate::base::number::readable_numbers;
use clap::{CommandFactory, Parser, Subcommand};
use std::ffi::OsString;
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
    run: crate::cli::run::RunArgs,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene (the built-in default scene when none is given).
    Run(crate::cli::run::RunArgs),
    /// Work-precision study: error against time per contact for every profile and method;
    /// writes DIR/work_precision.csv, .svg, .png and .md (the cost tables).
    WorkPrecision(crate::cli::work_precision::StudyArgs),
    /// Resolve one collision per row of a CSV file (docs/guide.md, "Batch").
    Batch(crate::cli::batch::BatchArgs),
    /// Throw chart: one scene over a grid of cut angles, speeds and spins; writes
    /// DIR/sweep.csv, sweep.svg and sweep.png.
    Sweep(crate::cli::sweep::SweepArgs),
    /// Cushion rebound chart: a cushion scene's ball over a grid of incidence angles,
    /// speeds, spins and side spins; writes DIR/rebound.csv, rebound.svg and rebound.png.
    Rebound(crate::cli::rebound::ReboundArgs),
}

/// Runs the command with the process's arguments; the exit code is 0 on success, 1 when the
/// run failed, 2 for bad input.
pub fn main() -> ExitCode {
    let args = arguments();
    if let Some(message) = misspelt_subcommand(&args) {
        eprintln!("{message}");
        return ExitCode::from(2);
    }
    let cli = match Cli::try_parse_from(&args) {
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
            // Bad options are bad input: one line, exit code 2.
            eprintln!("{}", crate::cli::common::one_line(&e));
            return ExitCode::from(2);
        }
    };
    let result = match cli.command {
        Some(Command::Run(args)) => run(&args),
        Some(Command::WorkPrecision(args)) => crate::cli::work_precision::work_precision(&args),
        Some(Command::Batch(args)) => crate::cli::batch::batch(&args),
        Some(Command::Sweep(args)) => crate::cli::sweep::sweep(&args),
        Some(Command::Rebound(args)) => crate::cli::rebound::rebound(&args),
        None => run(&cli.run),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", readable_numbers(&e.to_string()));
            if e.is_bad_input() {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}

/// `run`: a cushion scene ([cushion]) by `cli::cushion`, a cluster scene ([[balls]]) by
/// `cli::cluster`, any other by `cli::run`.
fn run(args: &crate::cli::run::RunArgs) -> Result<(), crate::base::error::Error> {
    if let Some(path) = &args.scene {
        if let Some(scene) = crate::cli::cushion::cushion_scene(path)? {
            return crate::cli::cushion::run(args, &scene);
        }
        if let Some(scene) = crate::cli::cluster::cluster_scene(path)? {
            return crate::cli::cluster::run(args, &scene);
        }
    }
    crate::cli::run::run(args)
}

/// The command line, with `help --help` read as `help` (clap's `help` subcommand takes no
/// options: `help --help` would fail).
fn arguments() -> Vec<OsString> {
    let mut args: Vec<OsString> = std::env::args_os().collect();
    if args.get(1).is_some_and(|a| a == "help") {
        args.retain(|a| a != "--help" && a != "-h");
    }
    args
}

/// The error for a first argument that is neither a subcommand nor an existing file but
/// close to a subcommand's name (`runn base.toml`): without it clap reads `runn` as the
/// scene of the default `run` and blames the next argument.
fn misspelt_subcommand(args: &[OsString]) -> Option<String> {
    let first = args.get(1)?.to_str()?;
    if first.starts_with('-') || std::path::Path::new(first).exists() {
        return None;
    }
    let command = Cli::command();
    let names: Vec<&str> = command
        .get_subcommands()
        .map(|c| c.get_name())
        .chain(["help"])
        .collect();
    if names.contains(&first) {
        return None;
    }
    let best = closest(first, &names)?;
    Some(format!(
        "error: `{first}` is neither a subcommand nor a scene file (did you mean `{best}`?); \
         subcommands: {} (see --help)",
        names.join(", ")
    ))
}
