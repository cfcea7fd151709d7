//! Many balls touching at once, resolved together (docs/cluster.md): the inputs
//! (`params.rs`) and the run (`resolve.rs`).

pub(crate) mod params;
pub(crate) mod resolve;
