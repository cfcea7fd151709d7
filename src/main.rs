//! The `billiard-contact` command: parse, call the library, print. Each subcommand lives in
//! `src/cli/`.
//!
//! Exit codes: 0 success, 1 the run failed (integrator gave up, non-finite result, I/O
//! while writing), 2 bad input (scene, profile table, options).

mod cli;

use clap::{Parser, Subcommand};
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
    run: cli::run::RunArgs,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene (the built-in default scene when none is given).
    Run(cli::run::RunArgs),
    /// Work-precision study: error against time per contact for every profile and method;
    /// writes DIR/work_precision.csv, .svg, .png and .md (the cost tables).
    WorkPrecision(cli::work_precision::StudyArgs),
    /// Resolve one collision per row of a CSV file (docs/guide.md, "Batch").
    Batch(cli::batch::BatchArgs),
    /// Throw chart: one scene over a grid of cut angles, speeds and spins; writes
    /// DIR/sweep.csv, sweep.svg and sweep.png.
    Sweep(cli::sweep::SweepArgs),
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
            // Bad options are bad input: one line, exit code 2.
            eprintln!("{}", cli::one_line(&e));
            return ExitCode::from(2);
        }
    };
    let result = match cli.command {
        Some(Command::Run(args)) => cli::run::run(&args),
        Some(Command::WorkPrecision(args)) => cli::work_precision::work_precision(&args),
        Some(Command::Batch(args)) => cli::batch::batch(&args),
        Some(Command::Sweep(args)) => cli::sweep::sweep(&args),
        None => cli::run::run(&cli.run),
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
