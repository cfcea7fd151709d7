//! Applications built on the contact: running a scene, batches of collisions, the
//! work-precision study, throw sweeps and the figures.

pub mod batch;
#[cfg(feature = "plots")]
pub mod plot;
pub(crate) mod rebound;
pub mod sweep;
pub mod work_precision;
