//! One collision solved: the outcome of a run under a force profile or a contact law, with
//! the checks against the closed form; a sphere against a plane through its equivalent pair.

pub(crate) mod check;
pub(crate) mod law_outcome;
pub(crate) mod outcome;
pub(crate) mod plane;
