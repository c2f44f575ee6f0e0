//! Reduction of K x = λ M x to standard form, C y = λ y with M = L Lᵀ,
//! C = L⁻¹ K L⁻ᵀ and x = L⁻ᵀ y, for small dense problems on CPUs with AVX2
//! or AVX-512 (in the modal analysis K in N/m-like units, M in kg-like
//! units, λ = ω² [SI: rad²/s²]).
//!
//! The matrices live in columns padded to a multiple of eight rows and
//! aligned to 64 bytes ([`Padded`]), and every step is a stream of whole
//! vectors down a column, masked where it starts above the rows it may
//! change:
//! - **Cholesky**, right-looking: column k is scaled by 1/Lₖₖ, then every
//!   later column j with Lⱼₖ ≠ 0 loses Lⱼₖ times it, from row j down.
//! - **W = K L⁻ᵀ**, left-looking over the columns of W:
//!   W[:, j] = (K[:, j] − Σₖ Lⱼₖ W[:, k]) / Lⱼⱼ with k over row j's envelope
//!   (the first nonzero of row j of M on), the column held in registers,
//!   in place of K.
//! - **C = Wᵀ L⁻ᵀ** the same way, after a transposition: W = (L⁻¹K)ᵀ, so
//!   this is L⁻¹ K L⁻ᵀ. C comes out full (both triangles, symmetric up to
//!   rounding) in the layout the windowed Householder kernel
//!   ([`super::householder`]) works on.
//!
//! For n ≤ 64 this beats the envelope kernels of [`super::eigen::Cholesky`]
//! although it uses only M's envelope and none of K's zeros: on the
//! built-in model's 40 × 40 problem 3.6 µs against 6.9 µs for the envelope
//! factor and reduction, which also leave the Householder kernel a 0.6 µs
//! mirror of the lower triangle (scratch harness, best of 15 × 2000). The
//! short rows of a nearly banded matrix cost more in loop overhead than in
//! arithmetic. Every step is backward stable like its envelope
//! counterpart; the two differ by rounding.

use super::eigen::{backward_rows, row_envelope};
use super::householder::Padded;
#[cfg(target_arch = "x86_64")]
use super::simd::{by_vectors, Isa, Lanes};
use faer::Mat;

/// Largest size the windowed reduction is used for.
pub(crate) const WINDOWED_MAX: usize = 64;

/// L of M = L Lᵀ, in the lower triangle of padded storage.
pub(crate) struct WindowedFactor {
    /// L in the lower triangle; above it, garbage.
    l: Padded,
    /// Row j of L is nonzero from column `first[j]` on (M's envelope).
    first: Vec<usize>,
}

/// M was not numerically positive definite at this pivot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct NotPositive;

/// Factor M and form C (full, with the Householder kernel's scratch
/// column after it); `isa` must be one this CPU has, not portable.
pub(crate) fn standard_form(
    k: &Mat<f64>,
    m: &Mat<f64>,
    isa: Isa,
) -> Result<(WindowedFactor, Padded), NotPositive> {
    let n = m.nrows();
    assert!(
        n <= WINDOWED_MAX && k.nrows() == n && isa != Isa::Portable,
        "windowed reduction: n = {n} ≤ {WINDOWED_MAX} on a SIMD CPU"
    );
    let mut l = Padded::from_columns(m, 0);
    let mut c = Padded::zeros(n, 1);
    let first = row_envelope(m);
    let mut w = Padded::from_columns(k, l.ld - n);
    let work = Work {
        n,
        ld: l.ld,
        first: &first,
    };
    // SAFETY: the CPU has `isa`; every buffer is ld × n (+ scratch) with
    // ld a multiple of 8 and zero padding rows.
    unsafe {
        match isa {
            Isa::Avx512 => reduce_avx512(&work, l.matrix_mut(), w.matrix_mut(), c.matrix_mut()),
            _ => reduce_avx2(&work, l.matrix_mut(), w.matrix_mut(), c.matrix_mut()),
        }?;
    }
    Ok((WindowedFactor { l, first }, c))
}

impl WindowedFactor {
    /// minᵢ Lᵢᵢ / maxᵢ Lᵢᵢ.
    pub(crate) fn min_pivot_ratio(&self) -> f64 {
        let (lo, hi) = (0..self.l.n)
            .map(|i| self.l.get(i, i))
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        lo / hi
    }

    /// B ← L⁻ᵀ B for a row-major n × w block (back to M's coordinates).
    pub(crate) fn backward_rows(&self, b: &mut [f64], w: usize) {
        backward_rows(&self.first, |j, k| self.l.get(j, k), b, w);
    }
}

/// Sizes and sparsity the kernels share.
#[cfg(target_arch = "x86_64")]
struct Work<'a> {
    n: usize,
    ld: usize,
    first: &'a [usize],
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,fma")]
unsafe fn reduce_avx512(
    w: &Work,
    l: &mut [f64],
    k: &mut [f64],
    c: &mut [f64],
) -> Result<(), NotPositive> {
    reduce::<super::simd::Avx512>(w, l, k, c)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn reduce_avx2(
    w: &Work,
    l: &mut [f64],
    k: &mut [f64],
    c: &mut [f64],
) -> Result<(), NotPositive> {
    reduce::<super::simd::Avx2>(w, l, k, c)
}

/// # Safety
/// The CPU has `S`'s features; `l` (M) and `c` (zeros) are ld × n
/// column-major with zero padding rows, ld a multiple of 8, and `k` (K)
/// ld × ld (zero padding columns too, so that its rows can be read whole).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn reduce<S: Lanes>(
    w: &Work,
    l: &mut [f64],
    k: &mut [f64],
    c: &mut [f64],
) -> Result<(), NotPositive> {
    let (n, ld) = (w.n, w.ld);
    debug_assert!(ld % 8 == 0 && l.len() >= ld * n && k.len() >= ld * ld && c.len() >= ld * n);
    cholesky::<S>(w, l.as_mut_ptr())?;
    // W = K L⁻ᵀ in place of K, then C = Wᵀ L⁻ᵀ with Wᵀ's columns gathered
    // from W's rows.
    let kp = k.as_mut_ptr();
    right_solve::<S>(w, l.as_ptr(), kp, Start::InPlace);
    right_solve::<S>(w, l.as_ptr(), c.as_mut_ptr(), Start::RowsOf(kp));
    Ok(())
}

/// The vector starting at `s` (a multiple of the width) with its lanes
/// above row `from` zeroed.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn masked<S: Lanes>(p: *const f64, s: usize, from: usize) -> S::V {
    let x = S::load(p.add(s));
    if from > s {
        S::mul(x, S::leading_zeros(from - s))
    } else {
        x
    }
}

/// M = L Lᵀ in place (lower triangle), right-looking.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn cholesky<S: Lanes>(w: &Work, a: *mut f64) -> Result<(), NotPositive> {
    let (n, ld, width) = (w.n, w.ld, S::WIDTH);
    for k in 0..n {
        let col = a.add(k * ld);
        let pivot = *col.add(k);
        if !(pivot > 0.0 && pivot.is_finite()) {
            return Err(NotPositive);
        }
        let d = pivot.sqrt();
        let inv = S::splat(1.0 / d);
        let mut s = (k + 1) / width * width;
        while s < ld {
            S::store(col.add(s), S::mul(S::load(col.add(s)), inv));
            s += width;
        }
        for j in k + 1..n {
            let ljk = *col.add(j);
            if ljk == 0.0 {
                continue;
            }
            let (target, f) = (a.add(j * ld), S::splat(ljk));
            let mut s = j / width * width;
            let first = masked::<S>(col, s, j);
            S::store(target.add(s), S::nmadd(first, f, S::load(target.add(s))));
            s += width;
            while s < ld {
                S::store(
                    target.add(s),
                    S::nmadd(S::load(col.add(s)), f, S::load(target.add(s))),
                );
                s += width;
            }
        }
        // The pivot goes in last: a scalar store into a vector that is
        // loaded again right after would stall the load (no forwarding).
        *col.add(k) = d;
    }
    Ok(())
}

/// Where [`right_solve`] takes column j of A from.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
enum Start {
    /// A itself (overwritten column by column).
    InPlace,
    /// Row j of this ld × ld matrix (A = its transpose).
    RowsOf(*const f64),
}

/// A ← A L⁻ᵀ column by column, in row blocks of up to eight vectors.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn right_solve<S: Lanes>(w: &Work, l: *const f64, a: *mut f64, start: Start) {
    let mut s = 0;
    while s < w.ld {
        let nv = ((w.ld - s) / S::WIDTH).min(8);
        by_vectors!(right_solve_block, S, nv, w, l, a, start, s);
        s += nv * S::WIDTH;
    }
}

/// Rows s…s+NV·W of A ← A L⁻ᵀ: column j is A's minus Lⱼₖ times the
/// earlier columns of the result over row j's envelope (two sets of
/// accumulators, alternate k), over Lⱼⱼ; the column is in registers before
/// it is overwritten.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn right_solve_block<S: Lanes, const NV: usize>(
    w: &Work,
    l: *const f64,
    c: *mut f64,
    start: Start,
    s: usize,
) {
    let (ld, width) = (w.ld, S::WIDTH);
    for j in 0..w.n {
        let mut even = [S::zero(); NV];
        let mut odd = [S::zero(); NV];
        for (v, e) in even.iter_mut().enumerate() {
            let row = s + v * width;
            *e = match start {
                Start::InPlace => S::load(c.add(j * ld + row)),
                Start::RowsOf(t) => S::gather(t.add(row * ld + j), ld),
            };
        }
        let mut k = w.first[j];
        while k + 1 < j {
            let (l0, l1) = (
                S::splat(*l.add(k * ld + j)),
                S::splat(*l.add((k + 1) * ld + j)),
            );
            let (c0, c1) = (c.add(k * ld + s), c.add((k + 1) * ld + s));
            for v in 0..NV {
                even[v] = S::nmadd(S::load(c0.add(v * width)), l0, even[v]);
                odd[v] = S::nmadd(S::load(c1.add(v * width)), l1, odd[v]);
            }
            k += 2;
        }
        if k < j {
            let (l0, c0) = (S::splat(*l.add(k * ld + j)), c.add(k * ld + s));
            for (v, e) in even.iter_mut().enumerate() {
                *e = S::nmadd(S::load(c0.add(v * width)), l0, *e);
            }
        }
        let inv = S::splat(1.0 / *l.add(j * ld + j));
        for v in 0..NV {
            S::store(
                c.add(j * ld + s + v * width),
                S::mul(S::add(even[v], odd[v]), inv),
            );
        }
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use crate::analysis::eigen::Cholesky;

    /// A banded SPD "mass" with a dense border (like a beam with constrained
    /// coordinates ordered last) and a symmetric "stiffness" of the same
    /// shape; entries spread over decades.
    fn pencil(n: usize) -> (Mat<f64>, Mat<f64>) {
        let border = n.min(3);
        let coupled = |i: usize, j: usize| i.abs_diff(j) <= 3 || i.max(j) >= n - border;
        let m = Mat::from_fn(n, n, |i, j| {
            if i == j {
                4.0 + (i % 5) as f64 * 1e-3
            } else if coupled(i, j) {
                0.3 / (1.0 + i.abs_diff(j) as f64)
            } else {
                0.0
            }
        });
        let k = Mat::from_fn(n, n, |i, j| {
            let g = 10f64.powi((i.min(j) % 7) as i32);
            if i == j {
                3.0 * g
            } else if coupled(i, j) {
                -g / (1.0 + (i + j) as f64)
            } else {
                0.0
            }
        });
        (k, m)
    }

    /// Every SIMD instance gives the L and C of the envelope kernels
    /// (Cholesky::factor and ::reduce, written independently) to 20nε
    /// relative to the largest entry, for one and several row blocks.
    #[test]
    fn windowed_form_equals_the_envelope_kernels() {
        for isa in Isa::all_available()
            .into_iter()
            .filter(|&i| i != Isa::Portable)
        {
            for n in [1, 2, 5, 8, 13, 40, 64] {
                let (k, m) = pencil(n);
                let (form, cw) = standard_form(&k, &m, isa).unwrap();
                let l = Cholesky::factor(&m).unwrap();
                let c = l.reduce(&k);
                let cmax = c.iter().fold(0.0f64, |a, v| a.max(v.abs()));
                let tol = 20.0 * n as f64 * f64::EPSILON;
                for j in 0..n {
                    for i in j..n {
                        let (got, want) = (cw.get(i, j), c[j * n + i]);
                        assert!(
                            (got - want).abs() <= tol * cmax,
                            "{isa:?}, n = {n}: C[{i},{j}] {got:e} vs {want:e}"
                        );
                        let upper = cw.get(j, i);
                        assert!(
                            (upper - want).abs() <= tol * cmax,
                            "{isa:?}, n = {n}: C[{j},{i}] {upper:e} vs {want:e}"
                        );
                    }
                }
                // L⁻ᵀ on the unit vectors against the envelope factor's.
                let mut a: Vec<f64> = (0..n * n)
                    .map(|i| f64::from(u8::from(i % (n + 1) == 0)))
                    .collect();
                let mut b = a.clone();
                form.backward_rows(&mut a, n);
                l.backward_rows(&mut b, n);
                let bmax = b.iter().fold(0.0f64, |x, v| x.max(v.abs()));
                for (x, y) in a.iter().zip(&b) {
                    assert!(
                        (x - y).abs() <= tol * bmax,
                        "{isa:?}, n = {n}: L⁻ᵀ {x:e} vs {y:e}"
                    );
                }
            }
        }
    }

    /// A mass matrix with a zero direction is refused, not factored.
    #[test]
    fn singular_mass_is_refused() {
        for isa in Isa::all_available()
            .into_iter()
            .filter(|&i| i != Isa::Portable)
        {
            let (k, mut m) = pencil(12);
            for i in 0..12 {
                m[(i, 7)] = 0.0;
                m[(7, i)] = 0.0;
            }
            assert!(standard_form(&k, &m, isa).is_err(), "{isa:?}");
        }
    }
}
