//! The validated model inputs: ball and contact parameters, the balls' material (and the
//! Hertz contact it gives), centre-of-mass and lab states, the lab <-> centre-of-mass frame,
//! the effects a run simulates, and one collision.

pub(crate) mod collision;
pub(crate) mod contact_law;
pub(crate) mod effects;
pub(crate) mod frame;
pub(crate) mod material;
pub(crate) mod params;
pub(crate) mod result;
pub(crate) mod state;
pub(crate) mod trace;
