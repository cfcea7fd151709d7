//! File formats: the scene (TOML), the JSON report and text summary, the trace CSV, the ball
//! path CSV, the numbers they write, and files written whole or not at all; the names they
//! accept (did you mean) and the values that look like a unit slip.

pub mod atomic_file;
pub mod ball_paths;
pub mod names;
pub mod number;
pub mod plausible;
pub mod report;
pub mod scene;
pub mod trace;

pub use atomic_file::AtomicFile;
