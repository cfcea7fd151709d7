//! Scalar arguments converted with errors that name them: `Ball(mass="x")` raises
//! "TypeError: mass: expected a real number (float or int), got str" where PyO3's own
//! conversion says "must be real number, not str" (naming the argument only in a note).
//! Each argument has its extractor, used as `#[pyo3(from_py_with = args::mass)]`.

use crate::ball::Ball;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use std::path::PathBuf;

#[cold]
#[inline(never)]
fn wrong_type(name: &str, expected: &str, ob: &Bound<'_, PyAny>) -> PyErr {
    let got = ob
        .get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_else(|_| "?".into());
    PyTypeError::new_err(format!("{name}: expected {expected}, got {got}"))
}

/// A real number: a float, an int or any object with `__float__` or `__index__` (numpy's
/// scalars), as Python's `float()` takes it.
pub(crate) fn real(name: &str, ob: &Bound<'_, PyAny>) -> PyResult<f64> {
    ob.extract::<f64>()
        .map_err(|_| wrong_type(name, "a real number (float or int)", ob))
}

pub(crate) fn real_or_none(name: &str, ob: &Bound<'_, PyAny>) -> PyResult<Option<f64>> {
    if ob.is_none() {
        return Ok(None);
    }
    ob.extract::<f64>()
        .map(Some)
        .map_err(|_| wrong_type(name, "a real number (float or int) or None", ob))
}

/// True or False (Python's bool or numpy's bool_).
pub(crate) fn flag(name: &str, ob: &Bound<'_, PyAny>) -> PyResult<bool> {
    ob.extract::<bool>()
        .map_err(|_| wrong_type(name, "True or False (a bool)", ob))
}

pub(crate) fn flag_or_none(name: &str, ob: &Bound<'_, PyAny>) -> PyResult<Option<bool>> {
    if ob.is_none() {
        return Ok(None);
    }
    ob.extract::<bool>()
        .map(Some)
        .map_err(|_| wrong_type(name, "True, False or None", ob))
}

pub(crate) fn text(name: &str, ob: &Bound<'_, PyAny>) -> PyResult<String> {
    ob.extract::<String>()
        .map_err(|_| wrong_type(name, "a string", ob))
}

pub(crate) fn text_or_none(name: &str, ob: &Bound<'_, PyAny>) -> PyResult<Option<String>> {
    if ob.is_none() {
        return Ok(None);
    }
    ob.extract::<String>()
        .map(Some)
        .map_err(|_| wrong_type(name, "a string or None", ob))
}

/// An integer (an int, or an object with `__index__`; not a float).
pub(crate) fn integer_or_none(name: &str, ob: &Bound<'_, PyAny>) -> PyResult<Option<i64>> {
    if ob.is_none() {
        return Ok(None);
    }
    ob.extract::<i64>()
        .map(Some)
        .map_err(|_| wrong_type(name, "an integer or None", ob))
}

/// A path: a str or an os.PathLike.
pub(crate) fn path(name: &str, ob: &Bound<'_, PyAny>) -> PyResult<PathBuf> {
    ob.extract::<PathBuf>()
        .map_err(|_| wrong_type(name, "a path (str or os.PathLike)", ob))
}

pub(crate) fn ball_or_none(name: &str, ob: &Bound<'_, PyAny>) -> PyResult<Option<Ball>> {
    if ob.is_none() {
        return Ok(None);
    }
    match ob.cast::<Ball>() {
        Ok(b) => Ok(Some(*b.get())),
        Err(_) => Err(wrong_type(name, "a Ball or None", ob)),
    }
}

/// One extractor a named argument: `fn mass(ob) -> PyResult<f64> { real("mass", ob) }`.
macro_rules! named {
    ($($f:ident: $kind:ident -> $t:ty;)*) => {
        $(
            pub(crate) fn $f(ob: &Bound<'_, PyAny>) -> PyResult<$t> {
                $kind(stringify!($f), ob)
            }
        )*
    };
}

/// The same with the name given (for the names that are Rust keywords or clash).
macro_rules! named_as {
    ($($f:ident($name:literal): $kind:ident -> $t:ty;)*) => {
        $(
            pub(crate) fn $f(ob: &Bound<'_, PyAny>) -> PyResult<$t> {
                $kind($name, ob)
            }
        )*
    };
}

named! {
    mass: real -> f64;
    radius: real -> f64;
    alpha: real -> f64;
    mu: real -> f64;
    restitution: real -> f64;
    duration: real -> f64;
    height: real -> f64;
    mu_cushion: real -> f64;
    mu_table: real -> f64;
    rule: text -> String;
    s: real -> f64;
    friction: flag -> bool;
    stick: flag -> bool;
    trace: flag -> bool;
    on: flag -> bool;
    profile: text -> String;
    evaluate: text -> String;
    method: text_or_none -> Option<String>;
    rtol: real_or_none -> Option<f64>;
    atol: real_or_none -> Option<f64>;
    time_transform: flag_or_none -> Option<bool>;
    samples: integer_or_none -> Option<i64>;
    steps: integer_or_none -> Option<i64>;
    base_dir: path -> PathBuf;
    youngs_modulus: real_or_none -> Option<f64>;
    poisson_ratio: real_or_none -> Option<f64>;
    stiffness: real_or_none -> Option<f64>;
    damping: text_or_none -> Option<String>;
    coefficient: real_or_none -> Option<f64>;
    at_speed: real_or_none -> Option<f64>;
    tangential: text -> String;
    plane_youngs_modulus: real_or_none -> Option<f64>;
    plane_poisson_ratio: real_or_none -> Option<f64>;
    shear_stiffness_factor: real_or_none -> Option<f64>;
}

named_as! {
    mass_or_none("mass"): real_or_none -> Option<f64>;
    radius_or_none("radius"): real_or_none -> Option<f64>;
    alpha_or_none("alpha"): real_or_none -> Option<f64>;
    a_real("a"): real -> f64;
    b_real("b"): real -> f64;
    c_real("c"): real -> f64;
    a_ball("a"): ball_or_none -> Option<Ball>;
    b_ball("b"): ball_or_none -> Option<Ball>;
    scene_path("path"): path -> PathBuf;
    scene_text("text"): text -> String;
    restitution_or_none("restitution"): real_or_none -> Option<f64>;
}
