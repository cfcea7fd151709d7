//! The lowest layer: the crate's error, the solver settings, the names of fields and their
//! checks, numbers written for people, and small numerics (the Beta function, the scalar
//! root finder's step). It imports nothing of the crate above it.

pub(crate) mod beta;
pub(crate) mod error;
pub(crate) mod fields;
pub(crate) mod method;
pub(crate) mod names;
pub(crate) mod number;
pub(crate) mod plausible;
pub(crate) mod root;
pub(crate) mod settings;
pub(crate) mod validate;
