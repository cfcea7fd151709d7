//! A ball against a cushion (Mathavan, Jackson and Parkin 2010): the cushion's inputs, the
//! impact kernel stepped in the cushion's normal impulse with its slip events, and the
//! outcome (docs/cushion.md).

pub(crate) mod impact;
pub(crate) mod outcome;
pub(crate) mod params;
pub(crate) mod rhs;
pub(crate) mod tableau;
