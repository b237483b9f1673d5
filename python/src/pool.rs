//! Memory of batches kept for the next batch: the copies of their inputs and the values of
//! their results.
//!
//! A batch of 10 000 states of an arm's ∂ID reads 1.7 MB of inputs and returns 7.8 MB of
//! results. Memory that large, allocated afresh at each call, comes from the operating system
//! as untouched pages (glibc serves it by `mmap`, or gives the top of its heap back when it is
//! freed), so that the first write of every 4 KB page faults: a third of such a batch's time
//! went to page faults (docs/python.md, "Memory kept between batches"). Buffers of
//! [`MIN_BYTES`] or more are therefore kept here when their arrays are freed, at most
//! [`MAX_KEPT`] of them and [`MAX_BYTES`] in all, and the next batch takes the smallest that
//! fits (at most twice the size asked for). A result array owns its buffer through a small
//! Python object ([`Values`]) that returns it here when the array is freed. A buffer that
//! cannot be allocated is a Python `MemoryError`, never an abort.

use std::sync::{Mutex, MutexGuard};

use numpy::ndarray::{ArrayViewD, IxDyn};
use numpy::PyArrayDyn;
use pyo3::exceptions::{PyMemoryError, PyRuntimeError};
use pyo3::prelude::*;

/// Buffers smaller than this are left to the allocator, which reuses small blocks itself
/// (glibc's default threshold for serving memory by `mmap`).
const MIN_BYTES: usize = 128 * 1024;

/// The most buffers kept.
const MAX_KEPT: usize = 8;

/// The most memory kept, in all.
const MAX_BYTES: usize = 256 * 1024 * 1024;

/// The buffers kept.
static KEPT: Mutex<Vec<Vec<f64>>> = Mutex::new(Vec::new());

/// The kept buffers (a poisoned lock is taken as it is: a buffer list cannot be left
/// half-changed).
fn kept() -> MutexGuard<'static, Vec<Vec<f64>>> {
    KEPT.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// A buffer of `len` values: the smallest kept one that holds them and is not more than twice
/// as large, else a new one; a `MemoryError` when it cannot be allocated. Its values are those
/// a previous batch left, or zeros: the caller writes every one.
pub(crate) fn take(len: usize) -> PyResult<Vec<f64>> {
    let reused = if len.saturating_mul(8) >= MIN_BYTES {
        let mut kept = kept();
        let fit = (0..kept.len())
            .filter(|&k| (len..=len.saturating_mul(2)).contains(&kept[k].capacity()))
            .min_by_key(|&k| kept[k].capacity());
        fit.map(|k| kept.remove(k))
    } else {
        None
    };
    let mut buffer = reused.unwrap_or_default();
    if let Some(more) = len.checked_sub(buffer.len()) {
        buffer.try_reserve_exact(more).map_err(|e| {
            PyMemoryError::new_err(format!("cannot allocate {len} float64 values: {e}"))
        })?;
    }
    buffer.resize(len, 0.0);
    Ok(buffer)
}

/// Keeps `buffer` for a later batch when it is large enough, the one kept longest making room.
pub(crate) fn give_back(buffer: Vec<f64>) {
    let bytes = |b: &Vec<f64>| b.capacity() * 8;
    if !(MIN_BYTES..=MAX_BYTES).contains(&bytes(&buffer)) {
        return;
    }
    let mut kept = kept();
    while !kept.is_empty()
        && (kept.len() >= MAX_KEPT
            || kept.iter().map(bytes).sum::<usize>() + bytes(&buffer) > MAX_BYTES)
    {
        kept.remove(0);
    }
    kept.push(buffer);
}

/// The owner of a result array's values: it gives them back to the pool when the array, whose
/// base it is, is freed.
#[pyclass(frozen, module = "rne._rne", name = "_BatchValues")]
pub(crate) struct Values {
    values: Vec<f64>,
}

impl Drop for Values {
    fn drop(&mut self) {
        give_back(std::mem::take(&mut self.values));
    }
}

/// `values` as a C-contiguous numpy array of `shape`, owning them.
pub(crate) fn into_array<'py>(
    py: Python<'py>,
    values: Vec<f64>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let (pointer, len) = (values.as_ptr(), values.len());
    let owner = Bound::new(py, Values { values })?;
    // SAFETY: `pointer` and `len` are the owner's vector's, which is never changed, grown or
    // read again until the owner is freed (its `Drop` moves it out), and the owner outlives the
    // array (it is the array's base). Nothing else holds a reference to the values.
    let values = unsafe { std::slice::from_raw_parts(pointer, len) };
    let view = ArrayViewD::from_shape(IxDyn(shape), values)
        .map_err(|e| PyRuntimeError::new_err(format!("internal error in rne: {e}")))?;
    // SAFETY: as above: the vector is not reallocated while `owner` lives, and `owner` is the
    // returned array's base, dropped only after it.
    Ok(unsafe { PyArrayDyn::borrow_from_array(&view, owner.into_any()) })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A large buffer given back is the one taken next for a length it holds (up to half its
    /// size); small ones are not kept, and at the limit the ones kept longest make room.
    #[test]
    fn large_buffers_are_reused_and_small_ones_are_not_kept() {
        let len = MIN_BYTES / 8 * 4;
        let buffer = take(len).unwrap();
        assert_eq!(buffer.len(), len);
        let address = buffer.as_ptr();
        give_back(buffer);
        let again = take(len / 2 + MIN_BYTES / 8).unwrap();
        assert_eq!(again.as_ptr(), address, "the kept buffer is reused");
        assert_eq!(again.len(), len / 2 + MIN_BYTES / 8);
        give_back(again);
        let smaller = take(MIN_BYTES / 8).unwrap();
        assert_ne!(
            smaller.as_ptr(),
            address,
            "a buffer over twice the size is left kept"
        );
        let small = take(16).unwrap();
        let small_address = small.as_ptr();
        give_back(small);
        assert!(kept().iter().all(|b| b.as_ptr() != small_address));
        for _ in 0..MAX_KEPT + 2 {
            give_back(vec![0.0; len]);
        }
        assert_eq!(kept().len(), MAX_KEPT, "the ones kept longest made room");
        assert!(
            take(usize::MAX / 4).is_err(),
            "more than memory can hold is an error"
        );
    }
}
