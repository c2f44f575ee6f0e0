//! Explicit SIMD vectors for the dense kernels that the compiler does not
//! vectorize well on its own (the windowed Householder reduction,
//! [`super::householder`]).
//!
//! A kernel is written once, generic over [`Lanes`], and instantiated in a
//! wrapper compiled for the matching CPU features (`#[target_feature]`);
//! [`Isa::detect`] says at run time which instance may run. Only x86-64 has
//! instances; elsewhere the portable kernels are used. Every operation is
//! element-wise and rounds like its scalar counterpart, except the fused
//! multiply-adds, which round once.

/// The instruction sets a kernel can be instantiated for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Isa {
    /// Plain scalar code (any CPU).
    Portable,
    /// AVX2 with FMA: four f64 per vector.
    #[cfg(target_arch = "x86_64")]
    Avx2,
    /// AVX-512F: eight f64 per vector.
    #[cfg(target_arch = "x86_64")]
    Avx512,
}

impl Isa {
    /// The widest instruction set this CPU has.
    pub(crate) fn detect() -> Isa {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx512f")
                && std::arch::is_x86_feature_detected!("fma")
            {
                return Isa::Avx512;
            }
            if std::arch::is_x86_feature_detected!("avx2")
                && std::arch::is_x86_feature_detected!("fma")
            {
                return Isa::Avx2;
            }
        }
        Isa::Portable
    }

    /// Every instruction set this CPU can run, narrowest first (for tests
    /// that compare the instances).
    #[cfg(test)]
    pub(crate) fn all_available() -> Vec<Isa> {
        let mut all = vec![Isa::Portable];
        #[cfg(target_arch = "x86_64")]
        {
            let best = Isa::detect();
            if best != Isa::Portable {
                all.push(Isa::Avx2);
            }
            if best == Isa::Avx512 {
                all.push(Isa::Avx512);
            }
        }
        all
    }
}

/// A vector of `WIDTH` f64 lanes and the operations the kernels need.
///
/// # Safety
/// Every method needs the CPU features of its implementation; callers run
/// them only inside a `#[target_feature]` function that enables them.
/// `load` and `store` need `WIDTH` readable (writable) f64 at the pointer,
/// with no alignment requirement.
#[cfg(target_arch = "x86_64")]
pub(crate) trait Lanes {
    type V: Copy;
    const WIDTH: usize;
    unsafe fn zero() -> Self::V;
    unsafe fn splat(x: f64) -> Self::V;
    unsafe fn load(p: *const f64) -> Self::V;
    unsafe fn store(p: *mut f64, v: Self::V);
    unsafe fn add(a: Self::V, b: Self::V) -> Self::V;
    unsafe fn mul(a: Self::V, b: Self::V) -> Self::V;
    /// a·b + c, rounded once.
    unsafe fn madd(a: Self::V, b: Self::V, c: Self::V) -> Self::V;
    /// c − a·b, rounded once.
    unsafe fn nmadd(a: Self::V, b: Self::V, c: Self::V) -> Self::V;
    /// Sum of the lanes.
    unsafe fn sum(a: Self::V) -> f64;
    /// Lanes p[0], p[stride], p[2·stride], … (stride ≥ 0, in f64).
    unsafe fn gather(p: *const f64, stride: usize) -> Self::V;
    /// A vector whose first z lanes are 0 and the others 1 (z ≤ WIDTH): a
    /// multiplier that masks the rows above a window's first valid row.
    #[inline(always)]
    unsafe fn leading_zeros(z: usize) -> Self::V {
        debug_assert!(z <= Self::WIDTH);
        Self::load(ZEROS_THEN_ONES.as_ptr().add(8 - z))
    }
}

/// Eight zeros, then eight ones: loaded from 8 − z, the first z lanes are 0.
#[cfg(target_arch = "x86_64")]
const ZEROS_THEN_ONES: [f64; 16] = [
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0,
];

/// `$f::<$S, NV>(args…)` for NV = `$nv` in 1…8: a kernel over a row block
/// of NV vectors, its accumulators in registers.
#[cfg(target_arch = "x86_64")]
macro_rules! by_vectors {
    ($f:ident, $S:ty, $nv:expr, $($arg:expr),*) => {
        match $nv {
            1 => $f::<$S, 1>($($arg),*),
            2 => $f::<$S, 2>($($arg),*),
            3 => $f::<$S, 3>($($arg),*),
            4 => $f::<$S, 4>($($arg),*),
            5 => $f::<$S, 5>($($arg),*),
            6 => $f::<$S, 6>($($arg),*),
            7 => $f::<$S, 7>($($arg),*),
            _ => $f::<$S, 8>($($arg),*),
        }
    };
}
#[cfg(target_arch = "x86_64")]
pub(crate) use by_vectors;

#[cfg(target_arch = "x86_64")]
pub(crate) use x86::{Avx2, Avx512};

#[cfg(target_arch = "x86_64")]
mod x86 {
    use super::Lanes;
    use std::arch::x86_64::*;

    /// AVX2 + FMA, four lanes.
    pub(crate) struct Avx2;

    /// AVX-512F, eight lanes.
    pub(crate) struct Avx512;

    impl Lanes for Avx2 {
        type V = __m256d;
        const WIDTH: usize = 4;
        #[inline(always)]
        unsafe fn zero() -> __m256d {
            _mm256_setzero_pd()
        }
        #[inline(always)]
        unsafe fn splat(x: f64) -> __m256d {
            _mm256_set1_pd(x)
        }
        #[inline(always)]
        unsafe fn load(p: *const f64) -> __m256d {
            _mm256_loadu_pd(p)
        }
        #[inline(always)]
        unsafe fn store(p: *mut f64, v: __m256d) {
            _mm256_storeu_pd(p, v)
        }
        #[inline(always)]
        unsafe fn add(a: __m256d, b: __m256d) -> __m256d {
            _mm256_add_pd(a, b)
        }
        #[inline(always)]
        unsafe fn mul(a: __m256d, b: __m256d) -> __m256d {
            _mm256_mul_pd(a, b)
        }
        #[inline(always)]
        unsafe fn madd(a: __m256d, b: __m256d, c: __m256d) -> __m256d {
            _mm256_fmadd_pd(a, b, c)
        }
        #[inline(always)]
        unsafe fn nmadd(a: __m256d, b: __m256d, c: __m256d) -> __m256d {
            _mm256_fnmadd_pd(a, b, c)
        }
        #[inline(always)]
        unsafe fn sum(a: __m256d) -> f64 {
            let pair = _mm_add_pd(_mm256_castpd256_pd128(a), _mm256_extractf128_pd(a, 1));
            _mm_cvtsd_f64(_mm_add_sd(pair, _mm_unpackhi_pd(pair, pair)))
        }
        #[inline(always)]
        unsafe fn gather(p: *const f64, stride: usize) -> __m256d {
            let s = stride as i64;
            _mm256_i64gather_pd::<8>(p, _mm256_setr_epi64x(0, s, 2 * s, 3 * s))
        }
    }

    impl Lanes for Avx512 {
        type V = __m512d;
        const WIDTH: usize = 8;
        #[inline(always)]
        unsafe fn zero() -> __m512d {
            _mm512_setzero_pd()
        }
        #[inline(always)]
        unsafe fn splat(x: f64) -> __m512d {
            _mm512_set1_pd(x)
        }
        #[inline(always)]
        unsafe fn load(p: *const f64) -> __m512d {
            _mm512_loadu_pd(p)
        }
        #[inline(always)]
        unsafe fn store(p: *mut f64, v: __m512d) {
            _mm512_storeu_pd(p, v)
        }
        #[inline(always)]
        unsafe fn add(a: __m512d, b: __m512d) -> __m512d {
            _mm512_add_pd(a, b)
        }
        #[inline(always)]
        unsafe fn mul(a: __m512d, b: __m512d) -> __m512d {
            _mm512_mul_pd(a, b)
        }
        #[inline(always)]
        unsafe fn madd(a: __m512d, b: __m512d, c: __m512d) -> __m512d {
            _mm512_fmadd_pd(a, b, c)
        }
        #[inline(always)]
        unsafe fn nmadd(a: __m512d, b: __m512d, c: __m512d) -> __m512d {
            _mm512_fnmadd_pd(a, b, c)
        }
        #[inline(always)]
        unsafe fn sum(a: __m512d) -> f64 {
            _mm512_reduce_add_pd(a)
        }
        #[inline(always)]
        unsafe fn gather(p: *const f64, stride: usize) -> __m512d {
            let s = stride as i64;
            let offsets = _mm512_setr_epi64(0, s, 2 * s, 3 * s, 4 * s, 5 * s, 6 * s, 7 * s);
            _mm512_i64gather_pd::<8>(offsets, p)
        }
    }
}
