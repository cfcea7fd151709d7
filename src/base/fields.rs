//! The names inputs are known by in errors: the scene file's dotted fields.

/// The field a profile's duration is named by in errors (as in the scene file).
pub(crate) const DURATION_FIELD: &str = "contact.profile.duration";
/// The field the material's Young's modulus is named by (as in the scene file).
pub(crate) const YOUNGS_MODULUS_FIELD: &str = "balls.youngs_modulus";
/// The field the material's Poisson ratio is named by (as in the scene file).
pub(crate) const POISSON_RATIO_FIELD: &str = "balls.poisson_ratio";
