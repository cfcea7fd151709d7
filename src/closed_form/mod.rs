//! The closed form of the contact (eqs 24-35, 52, 56 with the stick rule) and the sliding
//! law it rests on (constant or speed-dependent friction, eqs 47-49); a sphere against a
//! plane.

pub(crate) mod kernel;
pub(crate) mod plane;
pub(crate) mod sliding;
