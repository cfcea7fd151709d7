//! `BallBall`, `SpeedDependentFriction` and `BallBall.resolve_lab`: many lab-frame
//! collisions from numpy arrays, in Rust, without the GIL. The numpy arrays are read in
//! place and the results written straight into the output arrays by the library's
//! `batch::resolve_lab_into` (the change of frame, the method and the throw angle are the
//! library's, as for the command line's lab-frame batch rows).

use crate::ball::Ball;
use crate::errors::to_py;
use crate::settings;
use billiard_contact::batch::{
    resolve_lab_into, BatchSetup, LabOutColumns, LabRows, PARALLEL_LAB_ROWS,
};
use billiard_contact::nalgebra::Vector3;
use billiard_contact::{BallPair, Error, Evaluate, Friction, LabBall, LabScene, Method, Scene};
use numpy::npyffi::{npy_intp, NPY_ARRAY_CARRAY, NPY_TYPES, PY_ARRAY_API};
use numpy::{
    PyArray1, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::PyValueError;
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyString};
use std::os::raw::c_int;
use std::path::Path;

/// The names `evaluate=` takes: the library's (scene files' `contact.mu.evaluate`) first,
/// then the names of the first release, kept as aliases.
const EVALUATE_NAMES: [(&str, Evaluate); 4] = [
    ("along-contact", Evaluate::AlongContact),
    ("initial", Evaluate::Initial),
    ("contact", Evaluate::AlongContact),
    ("initial-slip", Evaluate::Initial),
];

/// Ball-ball friction mu(S) = a + b exp(-c S), S the sliding speed of the contact
/// points (m/s); a, b dimensionless, c in s/m.
///
/// `evaluate="along-contact"` (default): mu at the current sliding speed all along the
/// contact (the sliding speed falls as the friction acts).
/// `evaluate="initial"`: mu frozen at the sliding speed before the collision, mu(S(0)),
/// and used as a constant coefficient (pooltool's convention).
/// The names are the scene files' (`contact.mu.evaluate`); "contact" and "initial-slip"
/// are accepted for them too.
#[pyclass(
    frozen,
    module = "billiard_contact._core",
    name = "SpeedDependentFriction"
)]
#[derive(Clone, Copy)]
pub struct SpeedDependentFriction {
    /// The law, evaluated as `evaluate=` says.
    friction: Friction,
    #[pyo3(get)]
    a: f64,
    #[pyo3(get)]
    b: f64,
    #[pyo3(get)]
    c: f64,
    evaluate: Evaluate,
}

#[pymethods]
impl SpeedDependentFriction {
    #[new]
    #[pyo3(signature = (a, b, c, evaluate = "along-contact"))]
    fn new(a: f64, b: f64, c: f64, evaluate: &str) -> PyResult<Self> {
        let friction = Friction::speed_dependent(a, b, c).map_err(to_py)?;
        let Some(&(_, evaluate)) = EVALUATE_NAMES.iter().find(|(name, _)| *name == evaluate) else {
            let accepted: Vec<String> = EVALUATE_NAMES
                .iter()
                .map(|(name, _)| format!("\"{name}\""))
                .collect();
            return Err(to_py(Error::invalid(
                "evaluate",
                format!("\"{evaluate}\""),
                format!(
                    "{} (mu(S) along the contact) or {} (mu(S(0)) frozen, pooltool's \
                     convention); also {} and {}",
                    accepted[0], accepted[1], accepted[2], accepted[3]
                ),
            )));
        };
        Ok(SpeedDependentFriction {
            friction: friction.evaluated(evaluate),
            a,
            b,
            c,
            evaluate,
        })
    }

    /// Where mu(S) is evaluated: "along-contact" or "initial" (the library's names).
    #[getter]
    fn evaluate(&self) -> &'static str {
        self.evaluate.name()
    }

    /// mu at sliding speed `s` (m/s).
    fn mu(&self, s: f64) -> f64 {
        self.friction.mu(s)
    }

    fn __repr__(&self) -> String {
        format!(
            "SpeedDependentFriction(a={:?}, b={:?}, c={:?}, evaluate=\"{}\")",
            self.a,
            self.b,
            self.c,
            self.evaluate()
        )
    }
}

/// The friction argument of `BallBall`: a number or a `SpeedDependentFriction`.
#[derive(Clone, Copy)]
enum Mu {
    Constant(f64),
    Speed(SpeedDependentFriction),
}

impl<'a, 'py> FromPyObject<'a, 'py> for Mu {
    type Error = PyErr;
    fn extract(ob: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if let Ok(s) = ob.cast::<SpeedDependentFriction>() {
            return Ok(Mu::Speed(*s.get()));
        }
        match ob.extract::<f64>() {
            Ok(x) => Ok(Mu::Constant(x)),
            Err(_) => Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "mu: expected a number or SpeedDependentFriction, got {}",
                ob.get_type().name()?
            ))),
        }
    }
}

impl BallBall {
    /// The ball both A and B are, when they are identical.
    fn shared(&self) -> Option<billiard_contact::Ball> {
        let BallPair { a, b } = self.scene.balls;
        (a == b).then_some(a)
    }
}

/// The scene's balls as TOML: `[balls]` with the keys given (mass, radius, alpha: two
/// identical balls) and `[balls.a]`, `[balls.b]` for the balls given; the library refuses
/// a mix of the two forms, or one ball without the other, naming the keys.
fn balls_toml(shared: [Option<f64>; 3], own: [Option<Ball>; 2]) -> String {
    let mut text = String::from("[balls]\n");
    for (key, value) in ["mass", "radius", "alpha"].iter().zip(shared) {
        if let Some(x) = value {
            text += &format!("{key} = {}\n", toml_f64(x));
        }
    }
    for (name, ball) in ["a", "b"].iter().zip(own) {
        if let Some(Ball { ball }) = ball {
            text += &format!(
                "[balls.{name}]\nmass = {}\nradius = {}\nalpha = {}\n",
                toml_f64(ball.mass()),
                toml_f64(ball.radius()),
                toml_f64(ball.alpha())
            );
        }
    }
    text
}

/// A TOML number the library reads back to the same f64 (inf and nan included, so the
/// library's own validation names them).
fn toml_f64(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{x:?}")
    }
}

/// Two balls and their contact: two identical balls of mass (kg), radius (m) and alpha
/// (I = alpha m r^2, default 0.4), or balls of their own, a=Ball(...) and b=Ball(...)
/// (different mass, size or inertia); ball-ball friction mu (a number, or
/// SpeedDependentFriction), restitution e (P = (1 + e) m* v_n with the reduced mass
/// m* = m_A m_B / (m_A + m_B) and the relative approach speed v_n; (1 + e) m U(0) for
/// identical balls), the normal-force profile and its duration (s; used by the
/// time-stepping methods and for stick times; the closed form does not depend on them),
/// and the effects `friction` and `stick`.
///
/// Bad values raise ValueError with the command line's message, e.g.
/// "balls.mass = -1: > 0 kg".
#[pyclass(frozen, module = "billiard_contact._core", name = "BallBall")]
pub struct BallBall {
    scene: Scene,
    /// The closed form over this model (resolve_lab's default).
    closed_form: BatchSetup,
    /// Given as a=Ball(...), b=Ball(...) (else mass, radius, alpha).
    by_ball: bool,
    mu: Mu,
    restitution: f64,
    profile: String,
    duration: f64,
    friction: bool,
    stick: bool,
}

/// One input, read through its own byte strides (any memory order and alignment; a (3,)
/// input has row stride 0, so it is broadcast over the rows).
#[derive(Clone, Copy)]
struct Strided {
    ptr: *const u8,
    /// Strides in bytes.
    row: isize,
    col: isize,
}

// SAFETY: the pointer reads a numpy buffer that `resolve_lab` keeps alive (and, when it
// releases the GIL, holds a read-only borrow of) for the whole computation, or a static;
// nothing writes through it.
unsafe impl Send for Strided {}
unsafe impl Sync for Strided {}

/// The seven inputs, each of n rows.
struct Inputs {
    views: [Strided; 7],
    n: usize,
}

const NAMES: [&str; 7] = ["pa", "va", "wa", "pb", "vb", "wb", "up"];
static UP_DEFAULT: [f64; 3] = [0.0, 0.0, 1.0];

impl Inputs {
    #[inline(always)]
    fn vec(&self, k: usize, i: usize) -> Vector3<f64> {
        let v = self.views[k];
        let base = i as isize * v.row;
        // SAFETY: i < n, and each view addresses an (n, 3) (or broadcast (3,)) float64 array
        // that outlives the call (checked in `shaped`).
        unsafe {
            let at = |off: isize| v.ptr.offset(off).cast::<f64>().read_unaligned();
            Vector3::new(at(base), at(base + v.col), at(base + 2 * v.col))
        }
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

#[cold]
#[inline(never)]
fn non_finite(all: &[Vector3<f64>; 7]) -> Error {
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
fn with_argument_names(e: Error) -> Error {
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
/// numpy's conversion (lists, tuples, other dtypes).
fn float_array<'py>(ob: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    if let Ok(a) = ob.cast::<PyUntypedArray>() {
        let dtype = a.dtype();
        if dtype.num() == NPY_TYPES::NPY_DOUBLE as c_int
            && dtype.is_native_byteorder() != Some(false)
        {
            // SAFETY: a numpy array of native float64.
            return Ok(unsafe { a.cast_unchecked::<PyArrayDyn<f64>>() }.clone());
        }
    }
    let py = ob.py();
    // SAFETY: PyArray_FromAny with a new reference to the float64 descriptor (stolen), the
    // standard conversion of any array-like; the result is a new reference or NULL.
    let array = unsafe {
        let ptr = numpy::PY_ARRAY_API.PyArray_FromAny(
            py,
            ob.as_ptr(),
            numpy::dtype::<f64>(py).into_ptr().cast(),
            0,
            0,
            numpy::npyffi::NPY_ARRAY_FORCECAST,
            std::ptr::null_mut(),
        );
        Bound::from_owned_ptr_or_err(py, ptr)?
    };
    Ok(array.cast_into::<PyArrayDyn<f64>>()?)
}

/// The inputs and the number of rows n; `single` when every input has shape (3,).
fn shaped(arrays: &[Option<Bound<'_, PyArrayDyn<f64>>>; 7]) -> PyResult<(Inputs, usize, bool)> {
    let mut n: Option<(usize, &str)> = None;
    let mut views = [Strided {
        ptr: UP_DEFAULT.as_ptr().cast(),
        row: 0,
        col: 8,
    }; 7];
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
                    None => n = Some((rows, NAMES[k])),
                    Some((m, first)) if m != rows => {
                        return Err(PyValueError::new_err(format!(
                            "{} has {rows} rows but {first} has {m}: arrays of shape (N, 3) \
                             must have the same N",
                            NAMES[k]
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
                    NAMES[k],
                    shape_str(shape)
                )))
            }
        }
    }
    let rows = n.map_or(1, |(m, _)| m);
    Ok((Inputs { views, n: rows }, rows, n.is_none()))
}

fn shape_str(shape: &[usize]) -> String {
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

/// The output arrays of `resolve_lab`, all in one numpy buffer of float64 (the outputs are
/// C-contiguous views of it): "va", "wa", "vb", "wb" at elements 0, 3n, 6n, 9n (n rows of
/// 3), "impulse", "tangential_impulse", "throw_angle_deg" at 12n, 13n, 14n, then "sticks",
/// one byte a row. One allocation instead of eight: for one collision the call is
/// dominated by creating numpy objects; for many, a buffer of 4 MB or more is given huge
/// pages by numpy (one page fault per 2 MB where eight arrays took one per 4 kB, which
/// cost more than the collisions at 100,000 rows).
struct Outputs<'py> {
    block: Bound<'py, PyArray1<f64>>,
    n: usize,
    /// One collision: shapes (3,) and () instead of (N, 3) and (N,).
    single: bool,
}

/// Elements of the buffer for n rows: 15 float64 a row and the sticks' bytes.
fn block_len(n: usize) -> usize {
    15 * n + n.div_ceil(8)
}

impl<'py> Outputs<'py> {
    fn new(py: Python<'py>, n: usize, single: bool) -> Self {
        // SAFETY (uninitialised): every element is written by `resolve_lab_into` before the
        // arrays reach Python; on error they are dropped unseen. The padding bytes after
        // the sticks are never read.
        let block = unsafe { PyArray1::<f64>::new(py, [block_len(n)], false) };
        Outputs { block, n, single }
    }

    /// The buffer's parts, as the library's output columns.
    ///
    /// # Safety
    /// The buffer is fresh, C-contiguous and not yet visible to Python: nothing else reads
    /// or writes it while the columns live.
    unsafe fn columns<'s>(&self) -> LabOutColumns<'s> {
        let (d, n) = (self.block.data(), self.n);
        unsafe {
            let part = |at: usize| std::slice::from_raw_parts_mut(d.add(at), n);
            // [f64; 3] has f64's alignment: n rows of 3 elements are 3n elements.
            let rows = |at: usize| std::slice::from_raw_parts_mut(d.add(at).cast::<[f64; 3]>(), n);
            LabOutColumns {
                va: rows(0),
                wa: rows(3 * n),
                vb: rows(6 * n),
                wb: rows(9 * n),
                impulse: part(12 * n),
                tangential_impulse: part(13 * n),
                throw_angle_deg: part(14 * n),
                sticks: std::slice::from_raw_parts_mut(d.add(15 * n).cast::<bool>(), n),
            }
        }
    }

    fn into_dict(self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (b, n) = (&self.block, self.n);
        let real = NPY_TYPES::NPY_DOUBLE;
        let (vectors, scalars, sticks) = if self.single {
            let v = |at: usize| view(b, at, &[3], real);
            let s = |at: usize| scalar(b, at, real);
            (
                [v(0)?, v(3)?, v(6)?, v(9)?],
                [s(12)?, s(13)?, s(14)?],
                scalar(b, 15, NPY_TYPES::NPY_BOOL)?,
            )
        } else {
            let v = |at: usize| view(b, at, &[n, 3], real);
            let s = |at: usize| view(b, at, &[n], real);
            (
                [v(0)?, v(3 * n)?, v(6 * n)?, v(9 * n)?],
                [s(12 * n)?, s(13 * n)?, s(14 * n)?],
                view(b, 15 * n, &[n], NPY_TYPES::NPY_BOOL)?,
            )
        };
        let d = result_dict(py)?;
        let [va, wa, vb, wb] = vectors;
        let [p, j, throw] = scalars;
        d.set_item(intern!(py, "va"), va)?;
        d.set_item(intern!(py, "wa"), wa)?;
        d.set_item(intern!(py, "vb"), vb)?;
        d.set_item(intern!(py, "wb"), wb)?;
        d.set_item(intern!(py, "impulse"), p)?;
        d.set_item(intern!(py, "tangential_impulse"), j)?;
        d.set_item(intern!(py, "sticks"), sticks)?;
        d.set_item(intern!(py, "throw_angle_deg"), throw)?;
        Ok(d)
    }
}

/// One collision in the closed form, on (3,) inputs: computed into the stack, returned as
/// four fresh (3,) arrays and four numpy scalars. The general path's single buffer with
/// views of it costs more for one row than the eight small objects (measured with
/// callgrind: the buffer, the views' base objects and the dict's template were a third of
/// the call's instructions).
fn single_collision<'py>(
    py: Python<'py>,
    setup: &BatchSetup,
    inputs: &Inputs,
    arrays: [Option<Bound<'py, PyArrayDyn<f64>>>; 7],
) -> PyResult<Bound<'py, PyDict>> {
    let (mut va, mut wa, mut vb, mut wb) = ([[0.0; 3]], [[0.0; 3]], [[0.0; 3]], [[0.0; 3]]);
    let (mut p, mut j, mut throw, mut sticks) = ([0.0], [0.0], [0.0], [false]);
    let columns = LabOutColumns {
        va: &mut va,
        wa: &mut wa,
        vb: &mut vb,
        wb: &mut wb,
        impulse: &mut p,
        tangential_impulse: &mut j,
        sticks: &mut sticks,
        throw_angle_deg: &mut throw,
    };
    let result = resolve_lab_into(setup, inputs, columns);
    drop(arrays);
    if let Err((_, e)) = result {
        let e = with_argument_names(e);
        return Err(if e.is_bad_input() {
            PyValueError::new_err(e.to_string())
        } else {
            pyo3::exceptions::PyRuntimeError::new_err(e.to_string())
        });
    }
    let values = [
        vector(py, va[0])?,
        vector(py, wa[0])?,
        vector(py, vb[0])?,
        vector(py, wb[0])?,
        float64(py, p[0])?,
        float64(py, j[0])?,
        bool_(py, sticks[0])?,
        float64(py, throw[0])?,
    ];
    let keys = result_keys(py);
    // SAFETY: a fresh dict with the eight keys (values replaced); PyDict_SetItem
    // takes its own references to the key and the value.
    unsafe {
        let d = result_dict(py)?;
        for (k, v) in keys.iter().zip(&values) {
            if pyo3::ffi::PyDict_SetItem(d.as_ptr(), k.as_ptr(), v.as_ptr()) < 0 {
                return Err(PyErr::fetch(py));
            }
        }
        Ok(d)
    }
}

/// A fresh float64 array of shape (3,) holding `v`.
fn vector(py: Python<'_>, v: [f64; 3]) -> PyResult<Bound<'_, PyAny>> {
    let mut dims = [3 as npy_intp];
    // SAFETY: PyArray_NewFromDescr steals the new descriptor reference and allocates a
    // C-contiguous (3,) float64 buffer, written before the array is returned.
    unsafe {
        let descr = PY_ARRAY_API.PyArray_DescrFromType(py, NPY_TYPES::NPY_DOUBLE as c_int);
        let ptr = PY_ARRAY_API.PyArray_NewFromDescr(
            py,
            numpy::npyffi::get_type_object(py, numpy::npyffi::NpyTypes::PyArray_Type),
            descr,
            1,
            dims.as_mut_ptr(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            0,
            std::ptr::null_mut(),
        );
        let array = Bound::from_owned_ptr_or_err(py, ptr)?;
        let array = array.cast_into_unchecked::<PyArray1<f64>>();
        array.data().cast::<[f64; 3]>().write(v);
        Ok(array.into_any())
    }
}

/// The numpy scalar (np.float64 or np.bool_, shape ()) of the value at `data` (a bool is
/// its first byte).
///
/// # Safety
/// `data` points to a readable value of `dtype`.
unsafe fn numpy_scalar(
    py: Python<'_>,
    data: *const u8,
    dtype: NPY_TYPES,
) -> PyResult<Bound<'_, PyAny>> {
    // SAFETY: PyArray_Scalar copies the value and does not take the descriptor's
    // reference, which is released here.
    unsafe {
        let descr = PY_ARRAY_API.PyArray_DescrFromType(py, dtype as c_int);
        let ptr =
            PY_ARRAY_API.PyArray_Scalar(py, data.cast_mut().cast(), descr, std::ptr::null_mut());
        pyo3::ffi::Py_DECREF(descr.cast());
        Bound::from_owned_ptr_or_err(py, ptr)
    }
}

fn float64(py: Python<'_>, x: f64) -> PyResult<Bound<'_, PyAny>> {
    // SAFETY: a float64 on the stack.
    unsafe { numpy_scalar(py, (&x as *const f64).cast(), NPY_TYPES::NPY_DOUBLE) }
}

fn bool_(py: Python<'_>, x: bool) -> PyResult<Bound<'_, PyAny>> {
    // SAFETY: a bool (one byte, 0 or 1, numpy's) on the stack.
    unsafe { numpy_scalar(py, (&x as *const bool).cast(), NPY_TYPES::NPY_BOOL) }
}

/// The result dict's keys, in its order, interned once.
fn result_keys(py: Python<'_>) -> &[Py<PyString>; 8] {
    static KEYS: PyOnceLock<[Py<PyString>; 8]> = PyOnceLock::new();
    KEYS.get_or_init(py, || RESULT_KEYS.map(|k| PyString::intern(py, k).unbind()))
}

/// The keys of `resolve_lab`'s dict, in order.
const RESULT_KEYS: [&str; 8] = [
    "va",
    "wa",
    "vb",
    "wb",
    "impulse",
    "tangential_impulse",
    "sticks",
    "throw_angle_deg",
];

/// A C-contiguous view of shape `dims` and type `dtype` (float64 or bool) of `block`,
/// starting at float64 element `at`.
fn view<'py>(
    block: &Bound<'py, PyArray1<f64>>,
    at: usize,
    dims: &[usize],
    dtype: NPY_TYPES,
) -> PyResult<Bound<'py, PyAny>> {
    let py = block.py();
    let mut shape = [0 as npy_intp; 2];
    for (s, &d) in shape.iter_mut().zip(dims) {
        *s = d as npy_intp;
    }
    // SAFETY: the view lies inside the block (`block_len` elements: the caller's offsets
    // and shapes are the layout of `Outputs`); it keeps the block alive through its base
    // object (PyArray_SetBaseObject steals the new reference); the descriptor from
    // PyArray_DescrFromType is a new reference, stolen by PyArray_NewFromDescr.
    unsafe {
        let descr = PY_ARRAY_API.PyArray_DescrFromType(py, dtype as c_int);
        let ptr = PY_ARRAY_API.PyArray_NewFromDescr(
            py,
            numpy::npyffi::get_type_object(py, numpy::npyffi::NpyTypes::PyArray_Type),
            descr,
            dims.len() as c_int,
            shape.as_mut_ptr(),
            std::ptr::null_mut(),
            block.data().add(at).cast(),
            NPY_ARRAY_CARRAY,
            std::ptr::null_mut(),
        );
        let view = Bound::from_owned_ptr_or_err(py, ptr)?;
        if PY_ARRAY_API.PyArray_SetBaseObject(py, ptr.cast(), block.clone().into_ptr()) < 0 {
            return Err(PyErr::fetch(py));
        }
        Ok(view)
    }
}

/// The numpy scalar (np.float64 or np.bool_, shape ()) of element `at` of `block` (a bool
/// is the element's first byte).
fn scalar<'py>(
    block: &Bound<'py, PyArray1<f64>>,
    at: usize,
    dtype: NPY_TYPES,
) -> PyResult<Bound<'py, PyAny>> {
    // SAFETY: `at` lies inside the block.
    unsafe { numpy_scalar(block.py(), block.data().add(at).cast(), dtype) }
}

/// A fresh result dict: a copy of a template with the eight keys (copying a dict of the
/// right size is cheaper than growing a new one key by key).
fn result_dict(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    static TEMPLATE: PyOnceLock<Py<PyDict>> = PyOnceLock::new();
    let t = TEMPLATE.get_or_try_init(py, || -> PyResult<Py<PyDict>> {
        let d = PyDict::new(py);
        for k in RESULT_KEYS {
            d.set_item(PyString::intern(py, k), py.None())?;
        }
        Ok(d.unbind())
    })?;
    t.bind(py).copy()
}

#[pymethods]
impl BallBall {
    #[new]
    #[pyo3(signature = (*, mass = None, radius = None, alpha = None, a = None, b = None, mu,
                        restitution = 1.0, profile = "half-sine", duration = 2.5e-4,
                        friction = true, stick = true))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        mass: Option<f64>,
        radius: Option<f64>,
        alpha: Option<f64>,
        a: Option<&Bound<'_, Ball>>,
        b: Option<&Bound<'_, Ball>>,
        mu: Mu,
        restitution: f64,
        profile: &str,
        duration: f64,
        friction: bool,
        stick: bool,
    ) -> PyResult<Self> {
        // The model is a scene (with a placeholder incoming state): the library validates
        // every parameter and names it as in a scene file.
        let mu_toml = match mu {
            Mu::Constant(x) => toml_f64(x),
            Mu::Speed(s) => format!(
                "{{ model = \"speed-dependent\", a = {}, b = {}, c = {}, evaluate = \"{}\" }}",
                toml_f64(s.a),
                toml_f64(s.b),
                toml_f64(s.c),
                s.evaluate.name()
            ),
        };
        let profile_toml = serde_json::to_string(profile).expect("a string serialises");
        let (a, b) = (a.map(|x| *x.get()), b.map(|x| *x.get()));
        let balls_toml = balls_toml([mass, radius, alpha], [a, b]);
        let text = format!(
            "name = \"BallBall\"\n\
             {balls_toml}\
             [contact]\nmu = {mu_toml}\nrestitution = {}\n\
             [contact.profile]\nshape = {profile_toml}\nduration = {}\n\
             [incoming.cm]\nu = [1.0, 0.0, 0.0]\n\
             [effects]\nfriction = {friction}\nstick = {stick}\n",
            toml_f64(restitution),
            toml_f64(duration),
        );
        let scene = Scene::parse(&text, Path::new("."), None)
            .map_err(crate::errors::unwrap_scene_message)
            .map_err(to_py)?;
        let closed_form = BatchSetup::from_scene(
            &scene,
            settings::for_batch(None, None, None).map_err(to_py)?,
        );
        Ok(BallBall {
            scene,
            closed_form,
            by_ball: a.is_some() || b.is_some(),
            mu,
            restitution,
            profile: profile.to_string(),
            duration,
            friction,
            stick,
        })
    }

    /// Resolves collisions given in the lab frame.
    ///
    /// pa, va, wa, pb, vb, wb: positions (m), velocities (m/s) and spins (rad/s) of
    /// balls A and B, each of shape (3,) or (N, 3) (any memory order; lists work too; a
    /// (3,) array is used for every row). up: the direction away from the table (need
    /// not be unit), (3,) or (N, 3), default (0, 0, 1). The centres must touch:
    /// |pb - pa| = 2 radius (r_A + r_B) within a relative 1e-9.
    ///
    /// method: None (the closed form), "closed-form", "rk4", "dopri5" or "dop853";
    /// rtol: relative tolerance of the adaptive methods (atol = rtol), default 1e-10;
    /// time_transform: whether the time-stepping methods integrate in the smoothing
    /// change of time variable (the library's default, True; it acts on the "hertz" and
    /// "sine-power" profiles).
    ///
    /// Returns a dict of numpy arrays: "va", "wa", "vb", "wb" (outgoing velocities, m/s,
    /// and spins, rad/s; the input's shape), "impulse" (normal impulse P, N s),
    /// "tangential_impulse" (J, N s), "sticks" (bool: sliding stopped during contact),
    /// "throw_angle_deg" (degrees, counter-clockwise about up, from the line of centres
    /// to B's horizontal velocity change; NaN where the library has none: B's horizontal
    /// velocity change vanishes, or the line of centres is vertical), each of shape (N,),
    /// or for one collision a numpy scalar
    /// (np.float64, np.bool_: shape (), as numpy's own reductions return).
    ///
    /// Bad input raises ValueError naming the row and the field, with the command
    /// line's wording. N >= 2048 rows are resolved on all cores without the GIL.
    #[pyo3(signature = (pa, va, wa, pb, vb, wb, up = None, method = None, rtol = None,
                        time_transform = None))]
    #[allow(clippy::too_many_arguments)]
    fn resolve_lab<'py>(
        &self,
        py: Python<'py>,
        pa: &Bound<'py, PyAny>,
        va: &Bound<'py, PyAny>,
        wa: &Bound<'py, PyAny>,
        pb: &Bound<'py, PyAny>,
        vb: &Bound<'py, PyAny>,
        wb: &Bound<'py, PyAny>,
        up: Option<&Bound<'py, PyAny>>,
        method: Option<&str>,
        rtol: Option<f64>,
        time_transform: Option<bool>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let arrays = [
            Some(float_array(pa)?),
            Some(float_array(va)?),
            Some(float_array(wa)?),
            Some(float_array(pb)?),
            Some(float_array(vb)?),
            Some(float_array(wb)?),
            up.map(float_array).transpose()?,
        ];
        let (inputs, n, single) = shaped(&arrays)?;
        let own_setup;
        let setup = if method.is_none() && rtol.is_none() && time_transform.is_none() {
            &self.closed_form
        } else {
            own_setup = BatchSetup::from_scene(
                &self.scene,
                settings::for_batch(method, rtol, time_transform).map_err(to_py)?,
            );
            &own_setup
        };
        if single && setup.settings.method() == Method::ClosedForm {
            return single_collision(py, setup, &inputs, arrays);
        }
        let out = Outputs::new(py, n, single);
        // SAFETY: fresh C-contiguous arrays, written only here (see `Outputs`).
        let columns = unsafe { out.columns() };
        let result = if n >= PARALLEL_LAB_ROWS || setup.settings.method() != Method::ClosedForm {
            // Without the GIL (the library spreads the rows over its threads from
            // PARALLEL_LAB_ROWS on; time stepping takes long even for one row): hold
            // read-only borrows, so no Rust code writes the inputs meanwhile (numpy's
            // borrow tracking).
            let borrows = arrays
                .iter()
                .flatten()
                .map(|a| a.try_readonly())
                .collect::<Result<Vec<_>, _>>()?;
            let r = py.detach(|| resolve_lab_into(setup, &inputs, columns));
            drop(borrows);
            r
        } else {
            // A few rows with the GIL held: read straight from the buffers.
            resolve_lab_into(setup, &inputs, columns)
        };
        drop(arrays);
        if let Err((i, e)) = result {
            let e = with_argument_names(e);
            let msg = if single {
                e.to_string()
            } else {
                format!("row {i}: {e}")
            };
            return Err(if e.is_bad_input() {
                PyValueError::new_err(msg)
            } else {
                pyo3::exceptions::PyRuntimeError::new_err(msg)
            });
        }
        out.into_dict(py)
    }

    /// Mass m (kg) of both balls; None when A and B differ.
    #[getter]
    fn mass(&self) -> Option<f64> {
        self.shared().map(|b| b.mass())
    }

    /// Radius r (m) of both balls; None when A and B differ.
    #[getter]
    fn radius(&self) -> Option<f64> {
        self.shared().map(|b| b.radius())
    }

    /// I = alpha m r^2, alpha of both balls; None when A and B differ.
    #[getter]
    fn alpha(&self) -> Option<f64> {
        self.shared().map(|b| b.alpha())
    }

    /// Ball A.
    #[getter]
    fn a(&self) -> Ball {
        Ball {
            ball: self.scene.balls.a,
        }
    }

    /// Ball B.
    #[getter]
    fn b(&self) -> Ball {
        Ball {
            ball: self.scene.balls.b,
        }
    }

    /// Ball-ball friction: a number or SpeedDependentFriction.
    #[getter]
    fn mu(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        Ok(match self.mu {
            Mu::Constant(x) => x.into_pyobject(py)?.into_any().unbind(),
            Mu::Speed(s) => Bound::new(py, s)?.into_any().unbind(),
        })
    }

    /// Restitution e: P = (1 + e) m U(0).
    #[getter]
    fn restitution(&self) -> f64 {
        self.restitution
    }

    fn __repr__(&self) -> String {
        let mu = match self.mu {
            Mu::Constant(x) => format!("{x:?}"),
            Mu::Speed(s) => s.__repr__(),
        };
        let balls = match self.shared() {
            Some(ball) if !self.by_ball => format!(
                "mass={:?}, radius={:?}, alpha={:?}",
                ball.mass(),
                ball.radius(),
                ball.alpha()
            ),
            _ => format!("a={}, b={}", self.a().__repr__(), self.b().__repr__()),
        };
        format!(
            "BallBall({balls}, mu={mu}, restitution={:?}, \
             profile=\"{}\", duration={:?}, friction={}, stick={})",
            self.restitution,
            self.profile,
            self.duration,
            if self.friction { "True" } else { "False" },
            if self.stick { "True" } else { "False" },
        )
    }
}
