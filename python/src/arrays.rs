//! Reading the arrays a kernel is called with: one state as a 1-D array, N states as a 2-D
//! (N, width) array; float64 read in place when C-contiguous and copied otherwise; integers and
//! float32 converted exactly; every other type, shape or length, and every NaN or infinity, a
//! Python exception that names the argument.

use std::ffi::c_int;

use numpy::npyffi::NPY_TYPES;
use numpy::{
    PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

use crate::pool;

/// An argument read as float64 values, state after state.
pub(crate) struct Array<'py> {
    /// The array (kept alive while its values are read in place).
    array: Bound<'py, PyArrayDyn<f64>>,
    /// The values, copied: for N states (read with the GIL released) and for an array that is
    /// not C-contiguous. `None`: one C-contiguous state, read in place.
    copy: Option<Vec<f64>>,
    /// The number of states of a 2-D array; `None` for one state (1-D).
    pub states: Option<usize>,
}

impl<'py> Array<'py> {
    /// Reads `object`, the argument `name`, as states of `width` values each.
    pub fn read(object: &Bound<'py, PyAny>, name: &str, width: usize) -> PyResult<Array<'py>> {
        let array = float64(object, name)?;
        let states = states(array.shape(), name, width)?;
        // One C-contiguous state is read in place; every other array is copied in row order
        // (`as_array` iterates in logical order; `as_slice` would also accept Fortran order).
        let copy = match (states.is_none(), array.is_c_contiguous()) {
            (true, true) => None,
            (_, c_order) => Some(copy(&array, name, c_order)?),
        };
        let read = Array {
            array,
            copy,
            states,
        };
        read.check_finite(name, width)?;
        Ok(read)
    }

    /// The values, state after state.
    pub fn values(&self) -> &[f64] {
        match &self.copy {
            Some(copy) => copy,
            // SAFETY: the array is a C-contiguous float64 array, and one state: its values are
            // read only by code that holds the GIL until it is done with them and runs no
            // Python code meanwhile (one state's kernel call, the parameters' setters), so no
            // Python thread can write them while the slice lives. (A batch is copied before the
            // GIL is released.)
            None => unsafe { self.array.as_slice() }.unwrap_or_default(),
        }
    }
    /// An error naming the first NaN or infinity.
    fn check_finite(&self, name: &str, width: usize) -> PyResult<()> {
        let values = self.values();
        // Every value tested without a branch per value (vectorised: a batch's arrays hold
        // hundreds of thousands); only a failing array is searched for its first bad entry.
        if values.iter().fold(true, |finite, x| finite & x.is_finite()) {
            return Ok(());
        }
        match values.iter().position(|x| !x.is_finite()) {
            None => Ok(()),
            Some(k) => Err(PyValueError::new_err(format!(
                "`{name}{}` is {}; every value must be finite",
                match self.states {
                    Some(_) => format!("[{}, {}]", k / width.max(1), k % width.max(1)),
                    None => format!("[{k}]"),
                },
                values[k]
            ))),
        }
    }
}

impl Drop for Array<'_> {
    /// A batch's copy is kept for the next batch (`pool`).
    fn drop(&mut self) {
        if let Some(copy) = self.copy.take() {
            pool::give_back(copy);
        }
    }
}

/// The number of states of an array of `shape`: `None` for one state (1-D of `width`),
/// `Some(N)` for a 2-D (N, `width`) array.
fn states(shape: &[usize], name: &str, width: usize) -> PyResult<Option<usize>> {
    match *shape {
        [n] if n == width => Ok(None),
        [n, w] if w == width => Ok(Some(n)),
        [n] => Err(PyValueError::new_err(format!(
            "`{name}` has {n} values; the robot needs {width}"
        ))),
        [_, w] => Err(PyValueError::new_err(format!(
            "`{name}` has rows of {w} values; the robot needs {width} (an (N, {width}) array is N states)"
        ))),
        _ => Err(PyValueError::new_err(format!(
            "`{name}` must be 1-D ({width},) for one state or 2-D (N, {width}) for N states; got shape {shape:?}"
        ))),
    }
}

/// The values of `array` in row order, in a buffer from the pool: one copy of its memory when
/// it is C-contiguous (`contiguous`), else element by element in logical order.
fn copy(array: &Bound<'_, PyArrayDyn<f64>>, name: &str, contiguous: bool) -> PyResult<Vec<f64>> {
    let read = array
        .try_readonly()
        .map_err(|e| PyValueError::new_err(format!("`{name}` cannot be read: {e}")))?;
    let mut values = pool::take(read.len())?;
    match read.as_slice() {
        Ok(from) if contiguous => values.copy_from_slice(from),
        _ => {
            for (to, &from) in values.iter_mut().zip(read.as_array().iter()) {
                *to = from;
            }
        }
    }
    Ok(values)
}

/// `object` as a float64 array: itself when it is an aligned float64 array in this machine's
/// byte order (checked by its dtype's number, without numpy's general dtype comparison: the
/// path of every call), else converted by numpy when its values are integers or floats (a
/// list, a float32, integer, big-endian or unaligned array); a `TypeError` for anything else
/// (booleans, complex numbers, strings, objects).
fn float64<'py>(object: &Bound<'py, PyAny>, name: &str) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    if let Ok(array) = object.cast::<PyUntypedArray>() {
        let dtype = array.dtype();
        let native = dtype.is_native_byteorder() != Some(false);
        if dtype.num() == NPY_TYPES::NPY_DOUBLE as c_int && native && array.is_aligned() {
            // SAFETY: a numpy array whose elements are aligned native float64 values, which is
            // what `PyArrayDyn<f64>` stands for (rust-numpy's own check compares the dtype
            // with float64's through numpy).
            return Ok(unsafe { array.cast_unchecked::<PyArrayDyn<f64>>() }.clone());
        }
    }
    let py = object.py();
    let numpy = py.import("numpy")?;
    let array = match object.cast::<PyUntypedArray>() {
        Ok(array) => array.clone(),
        Err(_) => numpy
            .call_method1("asarray", (object,))
            .map_err(|e| {
                PyValueError::new_err(format!("`{name}` cannot be read as an array: {e}"))
            })?
            .cast_into::<PyUntypedArray>()?,
    };
    let dtype = array.dtype();
    if !matches!(dtype.kind(), b'f' | b'i' | b'u') {
        return Err(PyTypeError::new_err(format!(
            "`{name}` must hold real numbers (float64; integers and other floats are converted); got {} of dtype {}",
            object.get_type().name()?,
            dtype.str()?
        )));
    }
    Ok(array
        .call_method1("astype", ("float64",))?
        .cast_into::<PyArrayDyn<f64>>()?)
}
