//! Many balls touching at once, resolved together (docs/cluster.md): the inputs
//! (`params.rs`), the run (`resolve.rs`) and its linearly implicit step
//! (`rosenbrock.rs`).

pub(crate) mod params;
pub(crate) mod resolve;
mod rosenbrock;
