//! A sphere against a plane or another sphere with elastic compliance in both directions: Hertz's normal force
//! and Mindlin's no-slip tangential spring of the current contact radius under Coulomb's cap,
//! time-stepped with the kernel's own Dormand-Prince 5(4) (docs/tangential.md).

pub(crate) mod impact;
pub(crate) mod outcome;
pub(crate) mod pair;
pub(crate) mod stepper;
