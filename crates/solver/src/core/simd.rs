//! Run-time selection of wider vector instructions for the hot loops.
//!
//! The crate is built for the portable x86-64 baseline (SSE2), so that one
//! binary runs on any x86-64 CPU. The loops that dominate a solve outside
//! the FFTs (rustfft picks its own AVX kernels at run time) are compiled a
//! second time with AVX2 and FMA enabled ([`multiversion!`]), and that copy
//! runs when the CPU has both: the FFT products (`fft::apply_indexed`, with
//! the row transforms' packing and the spectral products), GMRES of the
//! Newton solvers (with the linearised system's product and
//! preconditioner) and the normal solver (`normal::solve_normal_with`).
//! The results are bit-identical either way: Rust neither fuses a multiply
//! and an add nor reorders a sum unless the code says so, so only the width
//! of the independent lanes changes.

use std::sync::atomic::{AtomicBool, Ordering};

/// Set by the tests that compare both copies ([`force_baseline`]).
static BASELINE: AtomicBool = AtomicBool::new(false);

/// Makes [`avx2_fma`] false (true) or restores detection (false): for tests
/// that check that both copies give bit-identical results. Other threads
/// see it too, which is harmless for that very reason.
#[cfg(test)]
pub(crate) fn force_baseline(on: bool) {
    BASELINE.store(on, Ordering::Relaxed);
}

/// Whether the CPU runs AVX2 and FMA (detected once; always false off
/// x86-64).
#[inline]
pub(crate) fn avx2_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        use std::sync::OnceLock;
        static HAS: OnceLock<bool> = OnceLock::new();
        !BASELINE.load(Ordering::Relaxed)
            && *HAS.get_or_init(|| {
                std::arch::is_x86_feature_detected!("avx2")
                    && std::arch::is_x86_feature_detected!("fma")
            })
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// `multiversion! { /// docs
/// fn name<T: Bound>(a: A, b: B) -> R => body }` defines `name`, which
/// runs the `#[inline(always)]` function `body` (same signature) compiled
/// with AVX2 and FMA when [`avx2_fma`] holds, as compiled for the baseline
/// otherwise.
macro_rules! multiversion {
    (
        $(#[$meta:meta])*
        $vis:vis fn $name:ident $(<$g:ident : $bound:path>)?
        ($($arg:ident : $ty:ty),* $(,)?) $(-> $ret:ty)? => $body:ident
    ) => {
        $(#[$meta])*
        $vis fn $name $(<$g: $bound>)? ($($arg: $ty),*) $(-> $ret)? {
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "avx2,fma")]
                #[allow(clippy::too_many_arguments)]
                fn avx2 $(<$g: $bound>)? ($($arg: $ty),*) $(-> $ret)? {
                    $body($($arg),*)
                }
                if $crate::core::simd::avx2_fma() {
                    // SAFETY: the CPU has AVX2 and FMA (checked at run
                    // time), all the target features `avx2` enables.
                    return unsafe { avx2($($arg),*) };
                }
            }
            $body($($arg),*)
        }
    };
}
pub(crate) use multiversion;
