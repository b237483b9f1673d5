//! What the processor running the code supports, found at run time.
//!
//! A portable x86-64 build targets SSE2, whose arithmetic instructions overwrite one of their
//! operands: a value still needed must first be copied, which costs an instruction and a
//! register, and a kernel of thousands of operations then keeps more of its values on the
//! stack. The generated kernels that large (the derivatives; `DISPATCH_FROM` in
//! `rne-codegen-core`) are therefore compiled twice, for the build's target and with AVX and
//! AVX2, whose instructions name a separate destination, and call the second where
//! [`has_avx2`] says the processor runs it. Both perform the same IEEE-754 operations in the
//! same order (neither adds fused multiply-add), so they return the same bits.

use core::sync::atomic::{AtomicU8, Ordering};

const UNKNOWN: u8 = 0;
const ABSENT: u8 = 1;
const PRESENT: u8 = 2;

/// [`has_avx2`]'s answer once found.
static AVX2: AtomicU8 = AtomicU8::new(UNKNOWN);

/// Whether this processor and operating system run AVX and AVX2 instructions: CPUID reports
/// AVX and OSXSAVE (leaf 1, ECX bits 28 and 27) and AVX2 (leaf 7, EBX bit 5), and the
/// operating system saves the SSE and AVX registers (XCR0 bits 1 and 2), as Intel's manual
/// (vol. 1, §14.3) asks one to check. Found on the first call and remembered; `false` off
/// x86-64.
#[inline]
pub fn has_avx2() -> bool {
    match AVX2.load(Ordering::Relaxed) {
        PRESENT => true,
        ABSENT => false,
        _ => find_avx2(),
    }
}

#[cold]
fn find_avx2() -> bool {
    let present = avx2_supported();
    AVX2.store(if present { PRESENT } else { ABSENT }, Ordering::Relaxed);
    present
}

#[cfg(target_arch = "x86_64")]
fn avx2_supported() -> bool {
    use core::arch::x86_64::{__cpuid, __cpuid_count, _xgetbv};
    const OSXSAVE: u32 = 1 << 27;
    const AVX: u32 = 1 << 28;
    const AVX2: u32 = 1 << 5;
    const SSE_AND_AVX_STATE: u64 = 0b110;
    // CPUID exists on every x86-64 processor; leaf 7 where leaf 0 says so.
    #[allow(unused_unsafe)]
    let (highest, ecx) = unsafe { (__cpuid(0).eax, __cpuid(1).ecx) };
    if highest < 7 || ecx & (OSXSAVE | AVX) != OSXSAVE | AVX {
        return false;
    }
    #[allow(unused_unsafe)]
    let ebx = unsafe { __cpuid_count(7, 0) }.ebx;
    if ebx & AVX2 == 0 {
        return false;
    }
    // SAFETY: XGETBV is available: OSXSAVE says the operating system enabled it.
    let xcr0 = unsafe { _xgetbv(0) };
    xcr0 & SSE_AND_AVX_STATE == SSE_AND_AVX_STATE
}

#[cfg(not(target_arch = "x86_64"))]
fn avx2_supported() -> bool {
    false
}

#[cfg(test)]
mod tests {
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn avx2_is_found_as_the_standard_library_finds_it() {
        let expected = std::is_x86_feature_detected!("avx2");
        assert_eq!(super::has_avx2(), expected);
        assert_eq!(super::has_avx2(), expected, "the remembered answer");
    }
}
