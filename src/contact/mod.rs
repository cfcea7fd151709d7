//! The contact: the closed form (eqs 24-35, 52, 56 with the stick rule), the sliding law
//! (constant or speed-dependent friction), the result every method reports, the checks of a
//! run, and its outcome.

pub(crate) mod check;
pub(crate) mod closed_form;
pub(crate) mod friction;
pub(crate) mod law_outcome;
pub(crate) mod outcome;
pub(crate) mod result;
