//! The arrays `resolve_lab` reads: any memory order, alignment and broadcast of (3,) or
//! (N, 3), read in place; their errors name the argument.

use billiard_contact::batch::LabRows;
use billiard_contact::nalgebra::Vector3;
use billiard_contact::{Error, LabBall, LabScene};
use numpy::npyffi::NPY_TYPES;
use numpy::{
    PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use std::os::raw::c_int;

/// One input, read through its own byte strides (any memory order and alignment; a (3,)
/// input has row stride 0, so it is broadcast over the rows).
#[derive(Clone, Copy)]
pub(crate) struct Strided {
    ptr: *const u8,
    /// Strides in bytes.
    row: isize,
    col: isize,
}

impl Strided {
    /// Row i of the (n, 3) (or broadcast (3,)) float64 array this view addresses.
    ///
    /// # Safety
    /// i < n, and the array outlives the view (see `strided`).
    #[inline(always)]
    pub(crate) unsafe fn row(&self, i: usize) -> Vector3<f64> {
        let base = i as isize * self.row;
        unsafe {
            let at = |off: isize| self.ptr.offset(off).cast::<f64>().read_unaligned();
            Vector3::new(at(base), at(base + self.col), at(base + 2 * self.col))
        }
    }
}

// SAFETY: the pointer reads a numpy buffer that `resolve_lab` keeps alive (and, when it
// releases the GIL, holds a read-only borrow of) for the whole computation, or a static;
// nothing writes through it.
unsafe impl Send for Strided {}
unsafe impl Sync for Strided {}

/// The seven inputs, each of n rows.
pub(crate) struct Inputs {
    views: [Strided; 7],
    n: usize,
}

pub(crate) const NAMES: [&str; 7] = ["pa", "va", "wa", "pb", "vb", "wb", "up"];
pub(crate) static UP_DEFAULT: [f64; 3] = [0.0, 0.0, 1.0];

impl Inputs {
    #[inline(always)]
    pub(crate) fn vec(&self, k: usize, i: usize) -> Vector3<f64> {
        // SAFETY: i < n, and each view addresses an (n, 3) (or broadcast (3,)) float64 array
        // that outlives the call (checked in `shaped`).
        unsafe { self.views[k].row(i) }
    }
}

impl LabRows for Inputs {
    fn len(&self) -> usize {
        self.n
    }

    /// Row i, every component checked finite (the library's lab rows from a file are
    /// checked as they are parsed; these come as numbers).
    #[inline(always)]
    fn row(&self, i: usize) -> Result<LabScene, Error> {
        let (pa, va, wa) = (self.vec(0, i), self.vec(1, i), self.vec(2, i));
        let (pb, vb, wb, up) = (
            self.vec(3, i),
            self.vec(4, i),
            self.vec(5, i),
            self.vec(6, i),
        );
        // x * 0 is 0 for finite x, NaN otherwise: one comparison for the 21 numbers.
        let z = |v: &Vector3<f64>| v.x * 0.0 + v.y * 0.0 + v.z * 0.0;
        if z(&pa) + z(&va) + z(&wa) + z(&pb) + z(&vb) + z(&wb) + z(&up) != 0.0 {
            return Err(non_finite(&[pa, va, wa, pb, vb, wb, up]));
        }
        Ok(LabScene {
            a: LabBall {
                position: pa,
                velocity: va,
                spin: wa,
            },
            b: LabBall {
                position: pb,
                velocity: vb,
                spin: wb,
            },
            up,
        })
    }
}

/// numpy's own refusal of an array-like (a ragged list: "setting an array element with a
/// sequence...", an object that is no number) with the argument's name in front.
#[cold]
fn naming(py: Python<'_>, name: &str, e: PyErr) -> PyErr {
    let message = e
        .value(py)
        .str()
        .map_or_else(|_| String::new(), |m| m.to_string());
    let text = format!("{name}: {}", message.replace('\n', " "));
    if e.is_instance_of::<PyTypeError>(py) {
        PyTypeError::new_err(text)
    } else if e.is_instance_of::<PyValueError>(py) {
        PyValueError::new_err(text)
    } else {
        e
    }
}

#[cold]
#[inline(never)]
pub(crate) fn non_finite(all: &[Vector3<f64>; 7]) -> Error {
    for (name, v) in NAMES.iter().zip(all) {
        for k in 0..3 {
            if !v[k].is_finite() {
                return Error::invalid(format!("{name}[{k}]"), v[k], "a finite number");
            }
        }
    }
    Error::invalid("input", "a non-finite number", "finite numbers")
}

/// The library's error for a lab scene, with the arguments' names: `pb` and `pa` for the
/// balls' positions, `up`.
#[cold]
#[inline(never)]
pub(crate) fn with_argument_names(e: Error) -> Error {
    match e {
        Error::NotTouching {
            position_b: [x, y, z],
            distance,
            contact_distance,
            contact_term,
            tolerance,
            ..
        } => Error::invalid(
            "pb",
            format!("[{x}, {y}, {z}] (|pb - pa| = {distance} m)"),
            format!(
                "the balls must touch: |pb - pa| = {contact_term} = {contact_distance} m within a \
                 relative {tolerance:e}"
            ),
        ),
        Error::InvalidParameter {
            field,
            value,
            expected,
        } if field == "incoming.lab.up" => Error::InvalidParameter {
            field: "up".into(),
            value,
            expected,
        },
        other => other,
    }
}

/// An input as a float64 numpy array: itself when it is one (no copy, any strides), else
/// numpy's conversion (lists, tuples, other dtypes). Real numbers only: float, integer and
/// bool arrays are converted; complex, object, string and other non-real dtypes raise
/// TypeError naming the argument (`name`), as numpy's cast would drop an imaginary part or
/// fail with a message that names no argument.
pub(crate) fn float_array<'py>(
    name: &str,
    ob: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let py = ob.py();
    let array = match ob.cast::<PyUntypedArray>() {
        Ok(a) => a.clone(),
        // SAFETY: PyArray_FromAny without a descriptor (numpy picks the dtype), the
        // standard conversion of any array-like; the result is a new reference or NULL.
        Err(_) => unsafe {
            let ptr = numpy::PY_ARRAY_API.PyArray_FromAny(
                py,
                ob.as_ptr(),
                std::ptr::null_mut(),
                0,
                0,
                0,
                std::ptr::null_mut(),
            );
            Bound::from_owned_ptr_or_err(py, ptr)
                .map_err(|e| naming(py, name, e))?
                .cast_into::<PyUntypedArray>()?
        },
    };
    let dtype = array.dtype();
    if dtype.num() == NPY_TYPES::NPY_DOUBLE as c_int && dtype.is_native_byteorder() != Some(false) {
        // SAFETY: a numpy array of native float64.
        return Ok(unsafe { array.cast_into_unchecked::<PyArrayDyn<f64>>() });
    }
    if !matches!(dtype.kind(), b'f' | b'i' | b'u' | b'b') {
        return Err(not_real(name, &dtype));
    }
    // SAFETY: PyArray_FromAny with a new reference to the float64 descriptor (stolen), a
    // cast of a real array; the result is a new reference or NULL.
    let converted = unsafe {
        let ptr = numpy::PY_ARRAY_API.PyArray_FromAny(
            py,
            array.as_ptr(),
            numpy::dtype::<f64>(py).into_ptr().cast(),
            0,
            0,
            numpy::npyffi::NPY_ARRAY_FORCECAST,
            std::ptr::null_mut(),
        );
        Bound::from_owned_ptr_or_err(py, ptr)?
    };
    Ok(converted.cast_into::<PyArrayDyn<f64>>()?)
}

#[cold]
#[inline(never)]
fn not_real(name: &str, dtype: &Bound<'_, numpy::PyArrayDescr>) -> PyErr {
    let shown = dtype
        .str()
        .map(|s| s.to_string())
        .unwrap_or_else(|_| "?".into());
    PyTypeError::new_err(format!(
        "{name} has dtype {shown}: expected real numbers (a float, integer or bool array)"
    ))
}

/// The inputs and the number of rows n; `single` when every input has shape (3,).
pub(crate) fn shaped(
    arrays: &[Option<Bound<'_, PyArrayDyn<f64>>>; 7],
) -> PyResult<(Inputs, usize, bool)> {
    let (views, rows, single) = strided(&NAMES, arrays)?;
    Ok((Inputs { views, n: rows }, rows, single))
}

/// The views of `arrays` (named `names`; a missing one reads `UP_DEFAULT`, broadcast), the
/// number of rows n (1 when every input has shape (3,)) and whether every input has shape
/// (3,). Shapes other than (3,) and (N, 3), and different N, raise ValueError naming the
/// argument.
pub(crate) fn strided<const K: usize>(
    names: &[&str; K],
    arrays: &[Option<Bound<'_, PyArrayDyn<f64>>>; K],
) -> PyResult<([Strided; K], usize, bool)> {
    let mut n: Option<(usize, &str)> = None;
    let mut views = [Strided {
        ptr: UP_DEFAULT.as_ptr().cast(),
        row: 0,
        col: 8,
    }; K];
    for (k, a) in arrays.iter().enumerate() {
        let Some(a) = a else { continue };
        let shape = a.shape();
        let strides = a.strides();
        match *shape {
            [3] => {
                views[k] = Strided {
                    ptr: a.data() as *const u8,
                    row: 0,
                    col: strides[0],
                }
            }
            [rows, 3] => {
                match n {
                    None => n = Some((rows, names[k])),
                    Some((m, first)) if m != rows => {
                        return Err(PyValueError::new_err(format!(
                            "{} has {rows} rows but {first} has {m}: arrays of shape (N, 3) \
                             must have the same N",
                            names[k]
                        )))
                    }
                    _ => {}
                }
                views[k] = Strided {
                    ptr: a.data() as *const u8,
                    row: strides[0],
                    col: strides[1],
                }
            }
            _ => {
                return Err(PyValueError::new_err(format!(
                    "{} has shape {}: expected (3,) or (N, 3)",
                    names[k],
                    shape_str(shape)
                )))
            }
        }
    }
    let rows = n.map_or(1, |(m, _)| m);
    Ok((views, rows, n.is_none()))
}

pub(crate) fn shape_str(shape: &[usize]) -> String {
    match shape {
        [one] => format!("({one},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}
