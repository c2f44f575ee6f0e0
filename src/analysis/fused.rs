//! Fused multiply-adds for the dense kernels of the eigen-solve.
//!
//! A kernel is written once, generic over `const FMA: bool`, with [`madd`]
//! for its multiply-adds; a wrapper compiled for AVX2 and FMA
//! (`#[target_feature]`) instantiates it with `FMA = true` and is called when
//! [`available`] says the CPU has both, the plain instance otherwise. The
//! two evaluate the same sums; the fused one rounds once per multiply-add,
//! so results may differ in the last bits. (The bisection kernel,
//! [`super::bisection`], picks its own variants the same way.)

/// a·b + c: one rounding when `FMA` (the caller must then run on a CPU
/// with FMA, or this becomes a slow library call), two otherwise.
#[inline(always)]
pub(crate) fn madd<const FMA: bool>(a: f64, b: f64, c: f64) -> f64 {
    if FMA {
        a.mul_add(b, c)
    } else {
        a * b + c
    }
}

/// Whether the AVX2+FMA instances may run on this CPU.
#[inline]
pub(crate) fn available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}
