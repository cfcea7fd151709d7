//! The Python extension `billiard_contact._core` (PyO3): scenes as the command line runs
//! them, and batches of lab-frame collisions from numpy arrays.

mod args;
mod ball;
mod cluster;
mod compliant_pair;
mod cushion;
mod errors;
mod friction;
mod inputs;
mod model;
mod outputs;
mod plane;
mod run;
mod settings;

use pyo3::prelude::*;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<ball::Ball>()?;
    m.add_class::<model::BallBall>()?;
    m.add_class::<friction::SpeedDependentFriction>()?;
    m.add_class::<plane::BallPlane>()?;
    m.add_class::<cushion::BallCushion>()?;
    m.add_class::<cluster::Cluster>()?;
    m.add_function(wrap_pyfunction!(outputs::_check_outputs_per_chunk, m)?)?;
    m.add_function(wrap_pyfunction!(run::run, m)?)?;
    m.add_function(wrap_pyfunction!(run::run_toml, m)?)?;
    m.add("TRACE_COLUMNS", run::TRACE_COLUMNS.to_vec())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
