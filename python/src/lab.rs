//! `BallBall`, `SpeedDependentFriction` and `BallBall.resolve_lab`: many lab-frame
//! collisions from numpy arrays, in Rust, without the GIL.

use crate::ball::Ball;
use crate::errors::to_py;
use crate::frame::{Frame, LabRow};
use crate::settings;
use billiard_contact::batch::{resolve, BatchInput, BatchSetup, Overrides};
use billiard_contact::nalgebra::Vector3;
use billiard_contact::{BallPair, Error, Friction, Incoming, Scene};
use numpy::npyffi::{npy_intp, NPY_ARRAY_CARRAY, NPY_TYPES, PY_ARRAY_API};
use numpy::{
    PyArray1, PyArray2, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::PyValueError;
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyString};
use rayon::prelude::*;
use std::os::raw::c_int;
use std::path::Path;

/// Rows from which `resolve_lab` releases the GIL and works on all cores (below, the
/// thread hand-over costs more than the rows).
const PARALLEL_ROWS: usize = 2048;
/// Rows per parallel work item.
const CHUNK_ROWS: usize = 1024;

/// Ball-ball friction mu(S) = a + b exp(-c S), S the sliding speed of the contact
/// points (m/s); a, b dimensionless, c in s/m.
///
/// `evaluate="contact"` (default): mu at the current sliding speed all along the contact
/// (the sliding speed falls as the friction acts).
/// `evaluate="initial-slip"`: mu frozen at the sliding speed before the collision,
/// mu(S(0)), and used as a constant coefficient (pooltool's convention).
#[pyclass(
    frozen,
    module = "billiard_contact._core",
    name = "SpeedDependentFriction"
)]
#[derive(Clone, Copy)]
pub struct SpeedDependentFriction {
    friction: Friction,
    #[pyo3(get)]
    a: f64,
    #[pyo3(get)]
    b: f64,
    #[pyo3(get)]
    c: f64,
    initial_slip: bool,
}

#[pymethods]
impl SpeedDependentFriction {
    #[new]
    #[pyo3(signature = (a, b, c, evaluate = "contact"))]
    fn new(a: f64, b: f64, c: f64, evaluate: &str) -> PyResult<Self> {
        let friction = Friction::speed_dependent(a, b, c).map_err(to_py)?;
        let initial_slip = match evaluate {
            "contact" => false,
            "initial-slip" => true,
            other => {
                return Err(to_py(Error::invalid(
                    "evaluate",
                    format!("\"{other}\""),
                    "\"contact\" (mu(S) along the contact) or \"initial-slip\" (mu(S(0)) \
                     frozen, pooltool's convention)",
                )))
            }
        };
        Ok(SpeedDependentFriction {
            friction,
            a,
            b,
            c,
            initial_slip,
        })
    }

    /// Where mu(S) is evaluated: "contact" or "initial-slip".
    #[getter]
    fn evaluate(&self) -> &'static str {
        if self.initial_slip {
            "initial-slip"
        } else {
            "contact"
        }
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
    /// [r_A, r_B] (m) and the mass weights [m_A, m_B] / (m_A + m_B), for the lab frame.
    radii: [f64; 2],
    weights: [f64; 2],
    mu: Mu,
    restitution: f64,
    profile: String,
    duration: f64,
    friction: bool,
    stick: bool,
}

/// One output row.
#[derive(Clone, Copy)]
struct RowOut {
    va: Vector3<f64>,
    wa: Vector3<f64>,
    vb: Vector3<f64>,
    wb: Vector3<f64>,
    impulse: f64,
    tangential_impulse: f64,
    sticks: bool,
    throw: f64,
}

/// The output columns of a range of rows.
struct OutSlices<'a> {
    va: &'a mut [f64],
    wa: &'a mut [f64],
    vb: &'a mut [f64],
    wb: &'a mut [f64],
    impulse: &'a mut [f64],
    tangential_impulse: &'a mut [f64],
    sticks: &'a mut [bool],
    throw: &'a mut [f64],
}

impl<'a> OutSlices<'a> {
    /// Rows [0, k) and [k, n).
    fn split_at(self, k: usize) -> (OutSlices<'a>, OutSlices<'a>) {
        let (va0, va1) = self.va.split_at_mut(3 * k);
        let (wa0, wa1) = self.wa.split_at_mut(3 * k);
        let (vb0, vb1) = self.vb.split_at_mut(3 * k);
        let (wb0, wb1) = self.wb.split_at_mut(3 * k);
        let (p0, p1) = self.impulse.split_at_mut(k);
        let (j0, j1) = self.tangential_impulse.split_at_mut(k);
        let (s0, s1) = self.sticks.split_at_mut(k);
        let (t0, t1) = self.throw.split_at_mut(k);
        (
            OutSlices {
                va: va0,
                wa: wa0,
                vb: vb0,
                wb: wb0,
                impulse: p0,
                tangential_impulse: j0,
                sticks: s0,
                throw: t0,
            },
            OutSlices {
                va: va1,
                wa: wa1,
                vb: vb1,
                wb: wb1,
                impulse: p1,
                tangential_impulse: j1,
                sticks: s1,
                throw: t1,
            },
        )
    }

    /// Row i (i < the number of rows: `fill_range` loops over `impulse.len()`, and every
    /// slice was split at the same rows).
    #[inline(always)]
    fn put(&mut self, i: usize, o: &RowOut) {
        debug_assert!(i < self.impulse.len() && 3 * i + 3 <= self.va.len());
        // SAFETY: as above; the vector slices hold 3 elements per row.
        unsafe {
            for k in 0..3 {
                *self.va.get_unchecked_mut(3 * i + k) = o.va[k];
                *self.wa.get_unchecked_mut(3 * i + k) = o.wa[k];
                *self.vb.get_unchecked_mut(3 * i + k) = o.vb[k];
                *self.wb.get_unchecked_mut(3 * i + k) = o.wb[k];
            }
            *self.impulse.get_unchecked_mut(i) = o.impulse;
            *self.tangential_impulse.get_unchecked_mut(i) = o.tangential_impulse;
            *self.sticks.get_unchecked_mut(i) = o.sticks;
            *self.throw.get_unchecked_mut(i) = o.throw;
        }
    }
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

    /// Row i, every component checked finite.
    #[inline(always)]
    fn row(&self, i: usize) -> Result<LabRow, Error> {
        let r = LabRow {
            pa: self.vec(0, i),
            va: self.vec(1, i),
            wa: self.vec(2, i),
            pb: self.vec(3, i),
            vb: self.vec(4, i),
            wb: self.vec(5, i),
            up: self.vec(6, i),
        };
        // x * 0 is 0 for finite x, NaN otherwise: one comparison for the 21 numbers.
        let z = |v: &Vector3<f64>| v.x * 0.0 + v.y * 0.0 + v.z * 0.0;
        let zero = z(&r.pa) + z(&r.va) + z(&r.wa) + z(&r.pb) + z(&r.vb) + z(&r.wb) + z(&r.up);
        if zero != 0.0 {
            return Err(non_finite(&[r.pa, r.va, r.wa, r.pb, r.vb, r.wb, r.up]));
        }
        Ok(r)
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

impl BallBall {
    /// One collision: lab row -> centre-of-mass state -> the library -> lab motions.
    #[inline(always)]
    fn resolve_row(
        &self,
        setup: &BatchSetup,
        frozen: Option<&Friction>,
        inputs: &Inputs,
        i: usize,
    ) -> Result<RowOut, Error> {
        let row = inputs.row(i)?;
        let frame = Frame::new(&row, self.radii, self.weights)?;
        let cm = frame.to_cm(&row);
        let input = match frozen {
            None => BatchInput::cm(cm),
            // mu(S(0)) from the incoming slip, then a constant coefficient for this row.
            Some(f) => BatchInput {
                incoming: Incoming::Cm(cm),
                overrides: Overrides {
                    mu: Some(f.mu(cm.sliding_speed_of(&self.scene.balls))),
                    ..Overrides::default()
                },
            },
        };
        let o = resolve(setup, &input)?;
        let (a, b) = frame.to_lab(&o.result.out);
        Ok(RowOut {
            va: a.velocity,
            wa: a.spin,
            vb: b.velocity,
            wb: b.spin,
            impulse: o.result.impulse,
            tangential_impulse: o.result.tangential_impulse,
            sticks: o.result.sticks,
            // No throw without a collision: B's velocity change is then the round-off of
            // the change of frame (as the library's batch).
            throw: if o.result.collided() {
                frame
                    .throw_angle_deg(&(b.velocity - row.vb))
                    .unwrap_or(f64::NAN)
            } else {
                f64::NAN
            },
        })
    }

    /// Rows [start, start + out.len) into `out`; the first failing row and its error.
    fn fill_range(
        &self,
        setup: &BatchSetup,
        frozen: Option<&Friction>,
        inputs: &Inputs,
        start: usize,
        mut out: OutSlices,
    ) -> Result<(), (usize, Error)> {
        for k in 0..out.impulse.len() {
            let i = start + k;
            match self.resolve_row(setup, frozen, inputs, i) {
                Ok(o) => out.put(k, &o),
                Err(e) => return Err((i, e)),
            }
        }
        Ok(())
    }

    /// All n rows, in parallel chunks when `parallel`.
    fn fill(
        &self,
        setup: &BatchSetup,
        frozen: Option<&Friction>,
        inputs: &Inputs,
        out: OutSlices,
        parallel: bool,
    ) -> Result<(), (usize, Error)> {
        let n = out.impulse.len();
        if !parallel {
            return self.fill_range(setup, frozen, inputs, 0, out);
        }
        let mut chunks = Vec::with_capacity(n.div_ceil(CHUNK_ROWS));
        let mut rest = out;
        let mut start = 0;
        while start < n {
            let k = CHUNK_ROWS.min(n - start);
            let (head, tail) = rest.split_at(k);
            chunks.push((start, head));
            rest = tail;
            start += k;
        }
        chunks
            .into_par_iter()
            .map(|(start, chunk)| self.fill_range(setup, frozen, inputs, start, chunk))
            .reduce(
                || Ok(()),
                |a, b| match (a, b) {
                    (Err(x), Err(y)) => Err(if x.0 <= y.0 { x } else { y }),
                    (Err(x), _) | (_, Err(x)) => Err(x),
                    _ => Ok(()),
                },
            )
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
    Ok((Inputs { views }, n.map_or(1, |(m, _)| m), n.is_none()))
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

/// The output arrays of `resolve_lab`. For N rows: arrays of shape (N, 3) and (N,). For
/// one collision, one numpy buffer holds everything and the outputs are views of it,
/// shapes (3,) and (): one allocation instead of eight (the single call is dominated by
/// numpy object creation).
enum Outputs<'py> {
    Rows {
        vectors: [Bound<'py, PyAny>; 4],
        scalars: [Bound<'py, PyAny>; 3],
        sticks: Bound<'py, PyAny>,
    },
    One {
        /// va, wa, vb, wb, impulse, tangential impulse, throw, sticks (a byte of the 16th).
        block: Bound<'py, PyArray1<f64>>,
    },
}

/// Elements of `block` for one collision.
const ONE_LEN: usize = 16;

impl<'py> Outputs<'py> {
    fn new(py: Python<'py>, n: usize, single: bool) -> Self {
        // SAFETY (uninitialised arrays): every element is written by `fill` before the
        // arrays reach Python; on error they are dropped unseen.
        unsafe {
            if single {
                let block = PyArray1::<f64>::new(py, [ONE_LEN], false);
                *block.data().add(ONE_LEN - 1) = 0.0;
                return Outputs::One { block };
            }
            let vector = || PyArray2::<f64>::new(py, [n, 3], false).into_any();
            let scalar = || PyArray1::<f64>::new(py, [n], false).into_any();
            Outputs::Rows {
                vectors: [vector(), vector(), vector(), vector()],
                scalars: [scalar(), scalar(), scalar()],
                sticks: PyArray1::<bool>::new(py, [n], false).into_any(),
            }
        }
    }

    /// The arrays' elements, to fill.
    ///
    /// # Safety
    /// The arrays are fresh, C-contiguous and not yet visible to Python: nothing else
    /// reads or writes them while the slices live.
    unsafe fn slices<'s>(&self) -> OutSlices<'s> {
        unsafe fn part<'s, T>(base: *mut T, len: usize) -> &'s mut [T] {
            unsafe { std::slice::from_raw_parts_mut(base, len) }
        }
        unsafe fn f64s<'s>(a: &Bound<'_, PyAny>) -> &'s mut [f64] {
            let a = unsafe { a.cast_unchecked::<PyArrayDyn<f64>>() };
            unsafe { part(a.data(), a.len()) }
        }
        unsafe {
            match self {
                Outputs::Rows {
                    vectors,
                    scalars,
                    sticks,
                } => {
                    let st = sticks.cast_unchecked::<PyArrayDyn<bool>>();
                    OutSlices {
                        va: f64s(&vectors[0]),
                        wa: f64s(&vectors[1]),
                        vb: f64s(&vectors[2]),
                        wb: f64s(&vectors[3]),
                        impulse: f64s(&scalars[0]),
                        tangential_impulse: f64s(&scalars[1]),
                        sticks: part(st.data(), st.len()),
                        throw: f64s(&scalars[2]),
                    }
                }
                Outputs::One { block } => {
                    let d = block.data();
                    OutSlices {
                        va: part(d, 3),
                        wa: part(d.add(3), 3),
                        vb: part(d.add(6), 3),
                        wb: part(d.add(9), 3),
                        impulse: part(d.add(12), 1),
                        tangential_impulse: part(d.add(13), 1),
                        throw: part(d.add(14), 1),
                        sticks: part(d.add(15).cast::<bool>(), 1),
                    }
                }
            }
        }
    }

    fn into_dict(self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = result_dict(py)?;
        let (vectors, scalars, sticks) = match self {
            Outputs::Rows {
                vectors,
                scalars,
                sticks,
            } => (vectors, scalars, sticks),
            Outputs::One { block } => {
                let v = |k: usize| vector_view(&block, 3 * k);
                let s = |k: usize| scalar(&block, k, NPY_TYPES::NPY_DOUBLE);
                (
                    [v(0)?, v(1)?, v(2)?, v(3)?],
                    [s(12)?, s(13)?, s(14)?],
                    scalar(&block, 15, NPY_TYPES::NPY_BOOL)?,
                )
            }
        };
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

/// A view of shape (3,) of `block` at element `at`.
fn vector_view<'py>(block: &Bound<'py, PyArray1<f64>>, at: usize) -> PyResult<Bound<'py, PyAny>> {
    let py = block.py();
    let mut dims: [npy_intp; 1] = [3];
    // SAFETY: elements at .. at + 3 lie inside the block (`ONE_LEN` elements); the view
    // keeps the block alive through its base object (PyArray_SetBaseObject steals the new
    // reference); the descriptor from PyArray_DescrFromType is a new reference, stolen by
    // PyArray_NewFromDescr.
    unsafe {
        let descr = PY_ARRAY_API.PyArray_DescrFromType(py, NPY_TYPES::NPY_DOUBLE as c_int);
        let ptr = PY_ARRAY_API.PyArray_NewFromDescr(
            py,
            numpy::npyffi::get_type_object(py, numpy::npyffi::NpyTypes::PyArray_Type),
            descr,
            1,
            dims.as_mut_ptr(),
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
    let py = block.py();
    // SAFETY: `at` lies inside the block; PyArray_Scalar copies the value and does not
    // take the descriptor's reference, which is released here.
    unsafe {
        let descr = PY_ARRAY_API.PyArray_DescrFromType(py, dtype as c_int);
        let ptr = PY_ARRAY_API.PyArray_Scalar(
            py,
            block.data().add(at).cast(),
            descr,
            std::ptr::null_mut(),
        );
        pyo3::ffi::Py_DECREF(descr.cast());
        Bound::from_owned_ptr_or_err(py, ptr)
    }
}

/// A fresh result dict: a copy of a template with the eight keys (copying a dict of the
/// right size is cheaper than growing a new one key by key).
fn result_dict(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    static TEMPLATE: PyOnceLock<Py<PyDict>> = PyOnceLock::new();
    let t = TEMPLATE.get_or_try_init(py, || -> PyResult<Py<PyDict>> {
        let d = PyDict::new(py);
        for k in [
            "va",
            "wa",
            "vb",
            "wb",
            "impulse",
            "tangential_impulse",
            "sticks",
            "throw_angle_deg",
        ] {
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
                "{{ model = \"speed-dependent\", a = {}, b = {}, c = {} }}",
                toml_f64(s.a),
                toml_f64(s.b),
                toml_f64(s.c)
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
        let closed_form =
            BatchSetup::from_scene(&scene, settings::for_batch(None, None).map_err(to_py)?);
        let balls = scene.balls;
        Ok(BallBall {
            scene,
            closed_form,
            by_ball: a.is_some() || b.is_some(),
            radii: balls.radii(),
            weights: balls.mass_weights(),
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
    /// rtol: relative tolerance of the adaptive methods (atol = rtol), default 1e-10.
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
    #[pyo3(signature = (pa, va, wa, pb, vb, wb, up = None, method = None, rtol = None))]
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
        let setup = if method.is_none() && rtol.is_none() {
            &self.closed_form
        } else {
            own_setup = BatchSetup::from_scene(
                &self.scene,
                settings::for_batch(method, rtol).map_err(to_py)?,
            );
            &own_setup
        };
        let frozen = match self.mu {
            Mu::Speed(s) if s.initial_slip => Some(s.friction),
            _ => None,
        };
        let out = Outputs::new(py, n, single);
        // SAFETY: fresh C-contiguous arrays, written only here (see `Outputs`).
        let slices = unsafe { out.slices() };
        let closed_form = matches!(method, None | Some("closed-form"));
        let result = if n >= PARALLEL_ROWS || !closed_form {
            // Without the GIL: hold read-only borrows, so no Rust code writes the inputs
            // meanwhile (numpy's borrow tracking).
            let borrows = arrays
                .iter()
                .flatten()
                .map(|a| a.try_readonly())
                .collect::<Result<Vec<_>, _>>()?;
            let parallel = n >= PARALLEL_ROWS;
            let r = py.detach(|| self.fill(setup, frozen.as_ref(), &inputs, slices, parallel));
            drop(borrows);
            r
        } else {
            // A few rows with the GIL held: read straight from the buffers.
            self.fill(setup, frozen.as_ref(), &inputs, slices, false)
        };
        drop(arrays);
        if let Err((i, e)) = result {
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
