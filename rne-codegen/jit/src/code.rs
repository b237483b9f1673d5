//! Compiled code: the one module of rne-jit with `unsafe`.
//!
//! [`Code`] owns the executable memory of one model's kernels (a Cranelift `JITModule`) and
//! frees it when dropped. [`Entry`] is one compiled function; [`Entry::call`] is the only call
//! into compiled code, and [`sin_cos_array`] the only function compiled code calls.
//!
//! # Safety argument
//! Every compiled function has the signature [`KernelFn`]: six pointers, to q, q̇, q̈, τ, the
//! parameters, the outputs and a scratch array. `lower.rs` generates code that reads
//! `input[k]` only for the inputs `Symbol`s of its program name, writes `out[k]` only for its
//! outputs and `scratch[k]` only for the slots it planned, and calls nothing but
//! [`sin_cos_array`] with pointers into its own stack frame and counts it wrote itself. A
//! function lowered with output blocks ([`Extents::blocks`] of them) takes as `out` the
//! address of a table of that many addresses, reads the table's entries and writes
//! `block[k]` only below its extent. Those extents are recorded in [`Extents`] when the
//! program is lowered; [`Entry::call`] takes slices (for blocks, a slice per block, from
//! which it builds the table on its own stack) and refuses any shorter than them, so every
//! access of the compiled code is inside a live Rust slice. Scalars are `f64`; no pointer escapes the call. The code memory is
//! written once (`finalize_definitions`) and then only executed, so calls from several
//! threads at once share nothing mutable: `Code` is `Send` and `Sync`. An `Entry` is only
//! reachable through the model that owns its `Code` (crate-private, `Copy` but never stored
//! elsewhere), so it is never called after the memory is freed.

use cranelift_jit::JITModule;

/// The signature of every compiled function.
pub(crate) type KernelFn = unsafe extern "C" fn(
    q: *const f64,
    qd: *const f64,
    qdd: *const f64,
    tau: *const f64,
    parameters: *const f64,
    out: *mut f64,
    scratch: *mut f64,
);

/// The arrays a compiled function reads and writes, each at least as long as its extent.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Arrays<'a> {
    pub q: &'a [f64],
    pub qd: &'a [f64],
    pub qdd: &'a [f64],
    pub tau: &'a [f64],
    pub parameters: &'a [f64],
}

#[cfg(test)]
impl Arrays<'static> {
    /// No inputs at all (tests' stand-ins and kernels of joint angles only).
    pub(crate) const NONE: Arrays<'static> = Arrays {
        q: &[],
        qd: &[],
        qdd: &[],
        tau: &[],
        parameters: &[],
    };
}

/// How far into each array a compiled function reaches: one past the largest index.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Extents {
    pub q: usize,
    pub qd: usize,
    pub qdd: usize,
    pub tau: usize,
    pub parameters: usize,
    /// Of `out`, or of each output block when there are blocks.
    pub out: usize,
    pub scratch: usize,
    /// The number of output blocks: 0 when `out` is the outputs' array itself.
    pub blocks: usize,
}

/// The most output blocks a function may be lowered with.
pub(crate) const MAX_BLOCKS: usize = 4;

/// Where a compiled function writes its outputs.
pub(crate) enum Out<'a, 'b> {
    /// One array.
    Whole(&'a mut [f64]),
    /// One array per output block, written from value `at` of each on.
    Blocks {
        blocks: &'a mut [&'b mut [f64]],
        at: usize,
    },
}

impl<'b> Out<'_, 'b> {
    /// The same outputs, borrowed again (for the functions of a kernel in turn).
    pub(crate) fn reborrow(&mut self) -> Out<'_, 'b> {
        match self {
            Out::Whole(out) => Out::Whole(out),
            Out::Blocks { blocks, at } => Out::Blocks { blocks, at: *at },
        }
    }
}

/// One compiled function.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Entry {
    function: KernelFn,
    extents: Extents,
}

impl Entry {
    /// Wraps the finalized function at `address`, lowered with `extents`.
    ///
    /// # Safety
    /// `address` is a function of [`KernelFn`]'s signature finalized in a [`Code`] that
    /// outlives every call, generated to stay within `extents` (module docs).
    pub(crate) unsafe fn new(address: *const u8, extents: Extents) -> Entry {
        // SAFETY: the caller's contract.
        let function = unsafe { std::mem::transmute::<*const u8, KernelFn>(address) };
        Entry { function, extents }
    }

    /// Runs the function, or `None` when an array is shorter than what it reaches or `out`
    /// is not the kind of outputs it was lowered for.
    #[inline]
    pub(crate) fn call(
        &self,
        arrays: Arrays<'_>,
        out: Out<'_, '_>,
        scratch: &mut [f64],
    ) -> Option<()> {
        let e = self.extents;
        let fits = arrays.q.len() >= e.q
            && arrays.qd.len() >= e.qd
            && arrays.qdd.len() >= e.qdd
            && arrays.tau.len() >= e.tau
            && arrays.parameters.len() >= e.parameters
            && scratch.len() >= e.scratch;
        let mut table = [std::ptr::null_mut::<f64>(); MAX_BLOCKS];
        let out = match out {
            Out::Whole(out) if fits && e.blocks == 0 && out.len() >= e.out => out.as_mut_ptr(),
            Out::Blocks { blocks, at }
                if fits && e.blocks > 0 && e.blocks == blocks.len() && e.blocks <= MAX_BLOCKS =>
            {
                for (entry, block) in table.iter_mut().zip(blocks.iter_mut()) {
                    if block.len() < at.checked_add(e.out)? {
                        return None;
                    }
                    *entry = block[at..].as_mut_ptr();
                }
                table.as_mut_ptr().cast::<f64>()
            }
            _ => return None,
        };
        // SAFETY: every array is at least as long as the code reaches into it, and for blocks
        // `out` is a table of the blocks' addresses, each at least its extent long (module
        // docs); the code is alive while `self` is reachable.
        unsafe {
            (self.function)(
                arrays.q.as_ptr(),
                arrays.qd.as_ptr(),
                arrays.qdd.as_ptr(),
                arrays.tau.as_ptr(),
                arrays.parameters.as_ptr(),
                out,
                scratch.as_mut_ptr(),
            );
        }
        Some(())
    }
}

/// The executable memory of one model's kernels, freed on drop.
pub(crate) struct Code {
    module: Option<JITModule>,
}

impl Code {
    /// Takes ownership of a module whose functions are finalized.
    pub(crate) fn new(module: JITModule) -> Code {
        Code {
            module: Some(module),
        }
    }
}

impl Drop for Code {
    fn drop(&mut self) {
        if let Some(module) = self.module.take() {
            // SAFETY: the entries into this module are only reachable through the model
            // being dropped, so none runs now or later.
            unsafe { module.free_memory() };
        }
    }
}

// SAFETY: after `finalize_definitions` the module's memory is only executed and, at drop,
// freed; nothing of it is mutated while the model is shared (module docs).
unsafe impl Send for Code {}
// SAFETY: as for `Send`: `&Code` gives no access to the module at all.
unsafe impl Sync for Code {}

/// `sines[i], cosines[i] = sin_cos(angles[i])` for i < n, bit for bit the runtime's `sin_cos`
/// (computed by `sin_cos_array::<N>`, which gives the same bits, as the emitted Rust does):
/// what compiled kernels call for their joints' sines and cosines.
///
/// # Safety
/// `angles`, `sines` and `cosines` point to `n` valid `f64` each (the compiled kernels pass
/// arrays of their own stack frame).
pub(crate) unsafe extern "C" fn sin_cos_array(
    angles: *const f64,
    n: usize,
    sines: *mut f64,
    cosines: *mut f64,
) {
    // SAFETY: the caller's contract.
    let (angles, sines, cosines) = unsafe {
        (
            std::slice::from_raw_parts(angles, n),
            std::slice::from_raw_parts_mut(sines, n),
            std::slice::from_raw_parts_mut(cosines, n),
        )
    };
    // As the emitted Rust: all angles by one `sin_cos_array::<N>` (pairs through SSE2), in
    // chunks of 16, rather than fours and the rest one by one.
    let mut k = 0;
    while k < n {
        let m = (n - k).min(16);
        by_count(
            &angles[k..k + m],
            &mut sines[k..k + m],
            &mut cosines[k..k + m],
        );
        k += m;
    }
}

/// `angle`, read by itself: compiled code has just stored the angles one by one (8 bytes
/// each), and a 16-byte load of two of them, as the pairs of `sin_cos_array` would be read,
/// cannot take its value from those two stores and waits until they reach the cache.
fn read_alone(angle: &f64) -> f64 {
    // SAFETY: `angle` is a valid, aligned `f64` (a reference); a volatile read is a plain
    // 8-byte load that the compiler may not merge with its neighbour's.
    unsafe { std::ptr::read_volatile(angle) }
}

/// `values` into `to`, each value read and written by itself: `sin_cos_array` has just stored
/// its results two by two (16 bytes each), and a copy of the array as a block reads 16 bytes
/// across two of those stores, a load that waits until they reach the cache, as in
/// [`read_alone`].
fn write_alone(values: &[f64], to: &mut [f64]) {
    for (value, to) in values.iter().zip(to) {
        // SAFETY: `to` is a valid, aligned `f64` (a mutable reference); a volatile write is a
        // plain 8-byte store, and the value's 8-byte load is not merged with its neighbour's.
        unsafe { std::ptr::write_volatile(to, *value) };
    }
}

/// `rne_runtime::sin_cos_array::<N>` for `N = angles.len()` (1 to 16).
fn by_count(angles: &[f64], sines: &mut [f64], cosines: &mut [f64]) {
    macro_rules! dispatch {
        ($($n:literal)*) => {
            match angles.len() {
                $($n => {
                    let x: [f64; $n] = std::array::from_fn(|i| read_alone(&angles[i]));
                    let (s, c) = rne_runtime::sin_cos_array(&x);
                    write_alone(&s, sines);
                    write_alone(&c, cosines);
                })*
                _ => unreachable!("1 to 16 angles"),
            }
        };
    }
    dispatch!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16);
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// The first block address the stand-in function below was given, as an integer.
    static SEEN: AtomicUsize = AtomicUsize::new(0);

    /// A stand-in for compiled code lowered with blocks: records the table's first entry.
    unsafe extern "C" fn record(
        _: *const f64,
        _: *const f64,
        _: *const f64,
        _: *const f64,
        _: *const f64,
        out: *mut f64,
        _: *mut f64,
    ) {
        // SAFETY: `Entry::call` passes a table of at least one address for a function with
        // blocks (the only kind these tests let it call).
        let first = unsafe { *out.cast::<*mut f64>() };
        SEEN.store(first as usize, Ordering::SeqCst);
    }

    fn entry(blocks: usize) -> Entry {
        let extents = Extents {
            out: 4,
            blocks,
            ..Extents::default()
        };
        // SAFETY: `record` has the kernels' signature and lives for the whole program; it
        // reads the table only, which `call` builds for an entry with blocks.
        unsafe { Entry::new(record as *const u8, extents) }
    }

    /// `entry` called with output blocks `blocks`, written from value `at` on.
    fn call_blocks(entry: &Entry, blocks: &mut [&mut [f64]], at: usize) -> Option<()> {
        entry.call(Arrays::NONE, Out::Blocks { blocks, at }, &mut [])
    }

    /// A call with blocks reaches the code only with as many blocks as it was lowered for,
    /// each long enough from `at` on, and hands it their addresses from `at`; outputs of the
    /// other kind are refused.
    #[test]
    fn blocks_are_checked_before_the_code_is_called() {
        let arrays = Arrays::NONE;
        let (mut a, mut b) = (vec![0.0; 10], vec![0.0; 10]);
        let two = entry(2);
        assert!(two.call(arrays, Out::Whole(&mut a), &mut []).is_none());
        assert!(
            call_blocks(&two, &mut [&mut a], 0).is_none(),
            "one block of two"
        );
        assert!(
            call_blocks(&two, &mut [&mut a, &mut b[..5]], 2).is_none(),
            "5 values from 2: short of 4"
        );
        assert!(
            call_blocks(&entry(0), &mut [], 0).is_none(),
            "no blocks: no table"
        );
        SEEN.store(0, Ordering::SeqCst);
        let expected = a[6..].as_ptr() as usize;
        assert!(call_blocks(&two, &mut [&mut a, &mut b], 6).is_some());
        assert_eq!(SEEN.load(Ordering::SeqCst), expected);
    }
}
