//! The floating-point environment every claim of this crate assumes (IEEE 754 binary32
//! and binary64, round to nearest even, gradual underflow: no flush-to-zero, no
//! denormals-are-zero), checked around every call into a plugin. On x86-64 that is
//! the MXCSR register of the calling thread; elsewhere nothing is checked.

/// MXCSR: flush-to-zero (bit 15), denormals-are-zero (bit 6), rounding control
/// (bits 13-14, 0 = to nearest).
#[cfg(target_arch = "x86_64")]
const NONSTANDARD: u32 = 1 << 15 | 1 << 6 | 3 << 13;

/// Reset this thread's environment to the standard one; true when it was not.
#[cfg(target_arch = "x86_64")]
#[inline]
pub fn reset() -> bool {
    #[allow(deprecated)]
    // SAFETY: SSE is part of x86-64; reading MXCSR and clearing these bits (which
    // only restores the default rounding and underflow) cannot fault.
    unsafe {
        let c = std::arch::x86_64::_mm_getcsr();
        if c & NONSTANDARD != 0 {
            std::arch::x86_64::_mm_setcsr(c & !NONSTANDARD);
            return true;
        }
    }
    false
}

#[cfg(not(target_arch = "x86_64"))]
#[inline]
pub fn reset() -> bool {
    false
}
