//! What a run writes: the JSON report and the text summary, the trace CSV, the ball path
//! CSV, and files written whole or not at all.

pub(crate) mod atomic_file;
pub(crate) mod ball_paths;
pub(crate) mod cluster;
pub(crate) mod cluster_trace;
pub(crate) mod cushion;
pub(crate) mod report;
pub(crate) mod summary;
pub(crate) mod trace_csv;
