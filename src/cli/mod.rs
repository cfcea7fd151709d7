//! The `billiard-contact` command (feature `cli`): parse, call the library, print. One file
//! per subcommand; the binary's `main` calls [`main`].
//!
//! Exit codes: 0 success, 1 the run failed (integrator gave up, non-finite result, I/O
//! while writing), 2 bad input (scene, profile table, options).

mod app;
mod batch;
mod choice;
mod cluster;
mod common;
mod cushion;
mod rebound;
mod run;
mod sweep;
mod work_precision;

pub use app::main;
