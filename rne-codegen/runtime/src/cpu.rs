//! What the processor running the code supports, found at run time.
//!
//! A portable x86-64 build targets SSE2, whose arithmetic instructions overwrite one of their
//! operands: a value still needed must be copied first, and with 16 registers the copies
//! crowd out the values of a kernel of thousands of operations, which then go to the stack
//! and back. The generated kernels that large (the derivatives; `DISPATCH_FROM` in
//! `rne-codegen-core`'s `emit`) are therefore compiled twice, for the build's target and with
//! AVX, whose instructions name a separate destination, and call the second where
//! [`has_avx`] says the processor runs it. Both perform the same IEEE-754 operations in the
//! same order (AVX adds no fused multiply-add), so they return the same bits.

use core::sync::atomic::{AtomicU8, Ordering};

const UNKNOWN: u8 = 0;
const ABSENT: u8 = 1;
const PRESENT: u8 = 2;

/// [`has_avx`]'s answer once found.
static AVX: AtomicU8 = AtomicU8::new(UNKNOWN);

/// Whether this processor and operating system run AVX instructions: CPUID reports AVX and
/// OSXSAVE (leaf 1, ECX bits 28 and 27), and the operating system saves the SSE and AVX
/// registers (XCR0 bits 1 and 2), as Intel's manual (vol. 1, §14.3) asks one to check. Found
/// on the first call and remembered; `false` off x86-64.
#[inline]
pub fn has_avx() -> bool {
    match AVX.load(Ordering::Relaxed) {
        PRESENT => true,
        ABSENT => false,
        _ => find_avx(),
    }
}

#[cold]
fn find_avx() -> bool {
    let present = avx_supported();
    AVX.store(if present { PRESENT } else { ABSENT }, Ordering::Relaxed);
    present
}

#[cfg(target_arch = "x86_64")]
fn avx_supported() -> bool {
    use core::arch::x86_64::{__cpuid, _xgetbv};
    const OSXSAVE: u32 = 1 << 27;
    const AVX: u32 = 1 << 28;
    const SSE_AND_AVX_STATE: u64 = 0b110;
    // CPUID exists on every x86-64 processor.
    #[allow(unused_unsafe)]
    let ecx = unsafe { __cpuid(1) }.ecx;
    if ecx & (OSXSAVE | AVX) != OSXSAVE | AVX {
        return false;
    }
    // SAFETY: XGETBV is available: OSXSAVE says the operating system enabled it.
    let xcr0 = unsafe { _xgetbv(0) };
    xcr0 & SSE_AND_AVX_STATE == SSE_AND_AVX_STATE
}

#[cfg(not(target_arch = "x86_64"))]
fn avx_supported() -> bool {
    false
}

#[cfg(test)]
mod tests {
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn avx_is_found_as_the_standard_library_finds_it() {
        let expected = std::is_x86_feature_detected!("avx");
        assert_eq!(super::has_avx(), expected);
        assert_eq!(super::has_avx(), expected, "the remembered answer");
    }
}
