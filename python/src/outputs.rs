//! The arrays and scalars `resolve_lab` returns, written in place by the library.

use crate::inputs::{with_argument_names, Inputs};
use billiard_contact::batch::{resolve_lab_into, BatchSetup, LabOutColumns, LabRows};
use billiard_contact::{Error, LabScene};
use numpy::npyffi::{npy_intp, NPY_ARRAY_CARRAY, NPY_TYPES, PY_ARRAY_API};
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyString};
use rayon::prelude::*;
use std::os::raw::c_int;
use std::sync::atomic::{AtomicBool, Ordering};

/// The output arrays of `resolve_lab`, all in one numpy buffer of float64 (the outputs are
/// C-contiguous views of it): "va", "wa", "vb", "wb" at elements 0, 3n, 6n, 9n (n rows of
/// 3), "impulse", "tangential_impulse", "throw_angle_deg" at 12n, 13n, 14n, then "sticks",
/// one byte a row. One allocation instead of eight: for one collision the call is
/// dominated by creating numpy objects; for many, a buffer of 4 MB or more is given huge
/// pages by numpy (one page fault per 2 MB where eight arrays took one per 4 kB, which
/// cost more than the collisions at 100,000 rows).
pub(crate) struct Outputs<'py> {
    block: Bound<'py, PyArray1<f64>>,
    n: usize,
    /// One collision: shapes (3,) and () instead of (N, 3) and (N,).
    single: bool,
}

/// Elements of the buffer for n rows: 15 float64 a row and the sticks' bytes.
pub(crate) fn block_len(n: usize) -> usize {
    15 * n + n.div_ceil(8)
}

impl<'py> Outputs<'py> {
    pub(crate) fn new(py: Python<'py>, n: usize, single: bool) -> Self {
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
    pub(crate) unsafe fn columns<'s>(&self) -> LabOutColumns<'s> {
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

    /// The first row (and its message) with an output that is not finite: "va", "wa", "vb",
    /// "wb", "impulse" or "tangential_impulse" (the throw angle is NaN by definition where
    /// there is none). The inputs were finite, so the collision overflowed. One pass over
    /// the whole buffer after every row is written: the check before [`resolve_checked`],
    /// kept for the benchmark (`_core._check_outputs_per_chunk(False)`).
    pub(crate) fn first_non_finite(&self) -> Option<(usize, String)> {
        let n = self.n;
        // SAFETY: the buffer's first 14n elements were all written by `resolve_lab_into`,
        // and nothing writes them now.
        let values = unsafe { std::slice::from_raw_parts(self.block.data(), 14 * n) };
        // Fast path: chunks of 64 checked without branches.
        if values
            .chunks(64)
            .all(|c| c.iter().fold(true, |ok, x| ok & x.is_finite()))
        {
            return None;
        }
        (0..n).find_map(|i| {
            let row = |at: usize| {
                [
                    values[at + 3 * i],
                    values[at + 3 * i + 1],
                    values[at + 3 * i + 2],
                ]
            };
            non_finite_output(
                [row(0), row(3 * n), row(6 * n), row(9 * n)],
                [values[12 * n + i], values[13 * n + i]],
            )
            .map(|m| (i, m))
        })
    }

    pub(crate) fn into_dict(self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
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
pub(crate) fn single_collision<'py>(
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
    if let Some(what) = non_finite_output([va[0], wa[0], vb[0], wb[0]], [p[0], j[0]]) {
        return Err(PyValueError::new_err(what));
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

/// The message for the first output of one collision that is not finite (va, wa, vb, wb,
/// impulse, tangential_impulse), if any.
#[inline]
pub(crate) fn non_finite_output(vectors: [[f64; 3]; 4], scalars: [f64; 2]) -> Option<String> {
    let finite = vectors
        .iter()
        .flatten()
        .chain(&scalars)
        .fold(true, |ok, x| ok & x.is_finite());
    if finite {
        None
    } else {
        Some(non_finite_message(vectors, scalars))
    }
}

#[cold]
#[inline(never)]
fn non_finite_message(vectors: [[f64; 3]; 4], scalars: [f64; 2]) -> String {
    let named_vectors = ["va", "wa", "vb", "wb"]
        .into_iter()
        .zip(vectors)
        .flat_map(|(name, v)| (0..3).map(move |k| (format!("{name}[{k}]"), v[k])));
    let named_scalars = ["impulse", "tangential_impulse"]
        .into_iter()
        .zip(scalars)
        .map(|(name, x)| (name.to_string(), x));
    let (name, x) = named_vectors
        .chain(named_scalars)
        .find(|(_, x)| !x.is_finite())
        .unwrap_or_else(|| ("output".into(), f64::NAN));
    format!(
        "{name} = {x}: the result is not finite (the collision overflows double precision: \
         masses, speeds or spins too large)"
    )
}

/// A fresh float64 array of shape (3,) holding `v`.
pub(crate) fn vector(py: Python<'_>, v: [f64; 3]) -> PyResult<Bound<'_, PyAny>> {
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

pub(crate) fn float64(py: Python<'_>, x: f64) -> PyResult<Bound<'_, PyAny>> {
    // SAFETY: a float64 on the stack.
    unsafe { numpy_scalar(py, (&x as *const f64).cast(), NPY_TYPES::NPY_DOUBLE) }
}

pub(crate) fn bool_(py: Python<'_>, x: bool) -> PyResult<Bound<'_, PyAny>> {
    // SAFETY: a bool (one byte, 0 or 1, numpy's) on the stack.
    unsafe { numpy_scalar(py, (&x as *const bool).cast(), NPY_TYPES::NPY_BOOL) }
}

/// The result dict's keys, in its order, interned once.
pub(crate) fn result_keys(py: Python<'_>) -> &[Py<PyString>; 8] {
    static KEYS: PyOnceLock<[Py<PyString>; 8]> = PyOnceLock::new();
    KEYS.get_or_init(py, || RESULT_KEYS.map(|k| PyString::intern(py, k).unbind()))
}

/// The keys of `resolve_lab`'s dict, in order.
pub(crate) const RESULT_KEYS: [&str; 8] = [
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
pub(crate) fn view<'py>(
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
pub(crate) fn scalar<'py>(
    block: &Bound<'py, PyArray1<f64>>,
    at: usize,
    dtype: NPY_TYPES,
) -> PyResult<Bound<'py, PyAny>> {
    // SAFETY: `at` lies inside the block.
    unsafe { numpy_scalar(block.py(), block.data().add(at).cast(), dtype) }
}

/// A fresh result dict: a copy of a template with the eight keys (copying a dict of the
/// right size is cheaper than growing a new one key by key).
pub(crate) fn result_dict(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
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

/// Rows a chunk of [`resolve_checked`]: the outputs of 1024 rows (115 kB) are still in the
/// core's cache when they are checked.
pub(crate) const CHECK_ROWS: usize = 1024;

/// Whether `resolve_lab` checks its outputs chunk by chunk ([`resolve_checked`], the
/// default) or in one pass after all rows ([`Outputs::first_non_finite`]): a switch for
/// `python/bench/bench_resolve.py` to time both in one run.
pub(crate) static PER_CHUNK: AtomicBool = AtomicBool::new(true);

/// Chooses how `resolve_lab` checks that its outputs are finite: per chunk of 1024 rows
/// (True, the default) or in one pass after every row is written (False, the earlier way);
/// returns the previous choice. For the benchmark: both give the same results and errors.
#[pyfunction]
pub(crate) fn _check_outputs_per_chunk(#[pyo3(from_py_with = crate::args::on)] on: bool) -> bool {
    PER_CHUNK.swap(on, Ordering::Relaxed)
}

/// Why a row failed: the library refused it, or its outputs are not finite (the message).
pub(crate) enum RowFailure {
    Library(Error),
    NonFinite(String),
}

/// Rows [start, start + n) of the inputs.
struct Window<'a> {
    inputs: &'a Inputs,
    start: usize,
    n: usize,
}

impl LabRows for Window<'_> {
    fn len(&self) -> usize {
        self.n
    }

    #[inline(always)]
    fn row(&self, i: usize) -> Result<LabScene, Error> {
        self.inputs.row(self.start + i)
    }
}

/// `resolve_lab_into` chunk by chunk ([`CHECK_ROWS`] rows; over rayon's pool when
/// `parallel`), each chunk's outputs checked finite once, right after it is written (one
/// branch a chunk; the failing row is looked for only when a chunk fails): the first
/// failing row and why.
pub(crate) fn resolve_checked(
    setup: &BatchSetup,
    inputs: &Inputs,
    out: LabOutColumns<'_>,
    parallel: bool,
) -> Result<(), (usize, RowFailure)> {
    let n = inputs.len();
    let mut parts = Vec::with_capacity(n.div_ceil(CHECK_ROWS));
    let (mut rest, mut start) = (out, 0);
    while start < n {
        let k = CHECK_ROWS.min(n - start);
        let (head, tail) = rest.split_at(k);
        parts.push((start, head));
        rest = tail;
        start += k;
    }
    let chunk =
        |(start, cols): (usize, LabOutColumns<'_>)| checked_chunk(setup, inputs, start, cols);
    let failure = if parallel {
        parts
            .into_par_iter()
            .filter_map(chunk)
            .min_by_key(|(i, _)| *i)
    } else {
        parts.into_iter().find_map(chunk)
    };
    failure.map_or(Ok(()), Err)
}

/// One chunk: the library's rows, then the check of the rows it wrote.
fn checked_chunk(
    setup: &BatchSetup,
    inputs: &Inputs,
    start: usize,
    cols: LabOutColumns<'_>,
) -> Option<(usize, RowFailure)> {
    let k = cols.impulse.len();
    let window = Window {
        inputs,
        start,
        n: k,
    };
    let result = resolve_lab_into(
        setup,
        &window,
        LabOutColumns {
            va: &mut *cols.va,
            wa: &mut *cols.wa,
            vb: &mut *cols.vb,
            wb: &mut *cols.wb,
            impulse: &mut *cols.impulse,
            tangential_impulse: &mut *cols.tangential_impulse,
            sticks: &mut *cols.sticks,
            throw_angle_deg: &mut *cols.throw_angle_deg,
        },
    );
    // The rows before a refused one are written (resolve_lab_into's promise): an overflow
    // among them comes first.
    let written = result.as_ref().map_or_else(|(i, _)| *i, |_| k);
    let vectors = [
        &cols.va[..written],
        &cols.wa[..written],
        &cols.vb[..written],
        &cols.wb[..written],
    ];
    let scalars = [
        &cols.impulse[..written],
        &cols.tangential_impulse[..written],
    ];
    let finite = vectors.iter().all(|c| all_finite(c.as_flattened()))
        & scalars.iter().all(|c| all_finite(c));
    if !finite {
        return first_bad_row(&vectors, &scalars)
            .map(|(q, m)| (start + q, RowFailure::NonFinite(m)));
    }
    result
        .err()
        .map(|(i, e)| (start + i, RowFailure::Library(e)))
}

/// Whether every number of `xs` is finite: the exponent bits of each compared without a
/// branch, so the loop runs in SIMD registers (a fold of `is_finite` through chained
/// iterators ran value by value).
#[inline]
fn all_finite(xs: &[f64]) -> bool {
    const EXPONENT: u64 = 0x7ff0_0000_0000_0000;
    xs.iter().fold(0u64, |bad, x| {
        bad | u64::from(x.to_bits() & EXPONENT == EXPONENT)
    }) == 0
}

#[cold]
#[inline(never)]
fn first_bad_row(vectors: &[&[[f64; 3]]; 4], scalars: &[&[f64]; 2]) -> Option<(usize, String)> {
    (0..scalars[0].len()).find_map(|q| {
        non_finite_output(
            [vectors[0][q], vectors[1][q], vectors[2][q], vectors[3][q]],
            [scalars[0][q], scalars[1][q]],
        )
        .map(|m| (q, m))
    })
}
