//! Householder tridiagonalization C = Q T Qᵀ of a dense symmetric matrix
//! (Golub & Van Loan, *Matrix Computations*, §8.3.1). In the modal analysis
//! C = L⁻¹KL⁻ᵀ, in units of ω² [SI: rad²/s²]; Q is orthogonal.
//!
//! Step k reflects the part of column k below the diagonal onto its first
//! entry, Hₖ = I − βₖ vₖ vₖᵀ, and applies the reflector to the trailing block
//! as one symmetric rank-2 update: p = βA v, w = p − ½β(pᵀv) v,
//! A ← A − v wᵀ − w vᵀ. The reflector vectors stay in the columns they
//! annihilated; Q is never formed. Cost 4n³/3 flops (lower triangle) or
//! 2n³ (full storage).
//!
//! Two kernels compute the same reduction:
//! - **portable**: the lower triangle only, column-major with stride n; the
//!   product A v comes from one dot-and-axpy pass per column.
//! - **windowed** (x86-64 with AVX2+FMA or AVX-512, chosen at run time): the
//!   full symmetric matrix, columns padded to a multiple of eight rows and
//!   aligned to 64 bytes. Step k works on a window of whole vectors that
//!   ends at the padded column end and starts at or just above row k+1; the
//!   rows of the window above k+1 are masked out of v and w, the padding
//!   rows stay zero. Then A v is a sum of columns (no horizontal sums) with
//!   v and the accumulators in registers, and the update streams each column
//!   once through registers. Twice the update flops of the lower triangle,
//!   but at n = 40 (the built-in model) 5.0–5.5 µs against 12.4–13.5 µs,
//!   mirror of the lower triangle included: the lower triangle's short,
//!   ragged loops cost more than the arithmetic.
//!
//! Both are backward stable: T is exactly orthogonally similar to C + E with
//! ‖E‖ of order nε‖C‖, so T's eigenvalues carry absolute errors of that
//! order. The two kernels round differently; their T agree to that order.

use super::back_transform::{apply_q, Reflectors};
use super::simd::Isa;
#[cfg(target_arch = "x86_64")]
use super::simd::{by_vectors, Lanes};
use super::small_eigen::{dot, Tridiagonal};

/// C = Q T Qᵀ with Q = H₀H₁⋯H_{n−2}, Hₖ = I − βₖ vₖ vₖᵀ acting on rows k+1…n−1.
#[derive(Debug, Clone)]
pub struct HouseholderTridiagonal {
    n: usize,
    /// Column k (stride `ld`, from `offset` on), rows k+1…n−1, holds vₖ
    /// (first entry 1).
    storage: Vec<f64>,
    offset: usize,
    ld: usize,
    /// βₖ (0 where no reflection was needed).
    beta: Vec<f64>,
    /// The tridiagonal T.
    pub t: Tridiagonal,
}

impl HouseholderTridiagonal {
    /// Reduce the symmetric n × n matrix `a` (column-major; only its lower
    /// triangle is read) with the fastest kernel this CPU can run.
    pub fn new(a: Vec<f64>, n: usize) -> Self {
        Self::with_isa(a, n, Isa::detect())
    }

    /// Reduce with the kernel for `isa` (the CPU must have it).
    pub(crate) fn with_isa(a: Vec<f64>, n: usize, isa: Isa) -> Self {
        assert_eq!(a.len(), n * n, "column-major n × n storage");
        match isa {
            Isa::Portable => lower_triangle(a, n),
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 | Isa::Avx512 => windowed(&a, n, isa),
        }
    }

    /// Y ← Q Y for a row-major n × w block: eigenvectors of T become
    /// eigenvectors of C ([`super::back_transform`]).
    pub fn apply_q(&self, y: &mut [f64], w: usize) {
        let reflectors = Reflectors {
            n: self.n,
            ld: self.ld,
            vectors: &self.storage[self.offset..],
            beta: &self.beta,
        };
        apply_q(&reflectors, y, w);
    }
}

/// Overwrites x with v (v₀ = 1) such that (I − β v vᵀ) x = α e₁; returns (α, β).
pub(crate) fn reflector(x: &mut [f64]) -> (f64, f64) {
    let x0 = x[0];
    let mut rest = dot(&x[1..], &x[1..]);
    let mut scale = 1.0;
    if rest != 0.0 && !(1e-250..=1e250).contains(&rest) {
        // Sum of squares out of range: rescale by the largest entry.
        scale = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        rest = x[1..].iter().map(|v| (v / scale).powi(2)).sum();
    }
    if rest == 0.0 {
        x[0] = 1.0;
        return (x0, 0.0);
    }
    let y0 = x0 / scale;
    let norm = scale * (y0 * y0 + rest).sqrt();
    let alpha = if x0 > 0.0 { -norm } else { norm };
    let u0 = x0 - alpha;
    let inv = 1.0 / u0;
    x[0] = 1.0;
    x[1..].iter_mut().for_each(|v| *v *= inv);
    (alpha, -u0 / alpha)
}

/// The portable kernel: lower triangle, stride n, storage reused.
fn lower_triangle(mut a: Vec<f64>, n: usize) -> HouseholderTridiagonal {
    let mut diag = vec![0.0; n];
    let mut off = vec![0.0; n.saturating_sub(1)];
    let mut beta = vec![0.0; n.saturating_sub(1)];
    let mut work = vec![0.0; n];
    for k in 0..n.saturating_sub(1) {
        let (head, tail) = a.split_at_mut((k + 1) * n);
        let column = &mut head[k * n..];
        diag[k] = column[k];
        let v = &mut column[k + 1..];
        let (alpha, b) = reflector(v);
        off[k] = alpha;
        beta[k] = b;
        if b != 0.0 {
            rank2_update(tail, n, k + 1, v, b, &mut work[..n - k - 1]);
        }
    }
    if n > 0 {
        diag[n - 1] = a[n * n - 1];
    }
    HouseholderTridiagonal {
        n,
        storage: a,
        offset: 0,
        ld: n,
        beta,
        t: Tridiagonal { diag, off },
    }
}

/// A ← H A H on the trailing block (rows and columns `start`…n−1 of the
/// column-major storage whose columns from `start` on are `tail`), lower
/// triangle only.
fn rank2_update(tail: &mut [f64], n: usize, start: usize, v: &[f64], beta: f64, p: &mut [f64]) {
    let m = n - start;
    // p = β A v from the lower triangle: column j gives A[j.., j]·v[j..] to
    // p[j] and A[j+1.., j] v[j] to p[j+1..].
    p.fill(0.0);
    for j in 0..m {
        let col = &tail[j * n + start + j..(j + 1) * n];
        let vj = v[j];
        let (pj, below) = p[j..].split_at_mut(1);
        pj[0] += col[0] * vj + dot_axpy(&col[1..], &v[j + 1..], vj, below);
    }
    p.iter_mut().for_each(|x| *x *= beta);
    let half = 0.5 * beta * dot(p, v);
    p.iter_mut().zip(v).for_each(|(x, vi)| *x -= half * vi);
    for j in 0..m {
        let col = &mut tail[j * n + start + j..(j + 1) * n];
        let (vj, wj) = (v[j], p[j]);
        let len = col.len();
        let (vs, ws) = (&v[j..j + len], &p[j..j + len]);
        for i in 0..len {
            col[i] -= vs[i] * wj + ws[i] * vj;
        }
    }
}

/// Returns a·x while adding a·alpha to y (one pass over a).
fn dot_axpy(a: &[f64], x: &[f64], alpha: f64, y: &mut [f64]) -> f64 {
    let len = a.len();
    let (x, y) = (&x[..len], &mut y[..len]);
    let (mut s0, mut s1, mut s2, mut s3) = (0.0, 0.0, 0.0, 0.0);
    let split = len - len % 4;
    let mut i = 0;
    while i < split {
        s0 += a[i] * x[i];
        s1 += a[i + 1] * x[i + 1];
        s2 += a[i + 2] * x[i + 2];
        s3 += a[i + 3] * x[i + 3];
        y[i] += a[i] * alpha;
        y[i + 1] += a[i + 1] * alpha;
        y[i + 2] += a[i + 2] * alpha;
        y[i + 3] += a[i + 3] * alpha;
        i += 4;
    }
    let mut s = (s0 + s2) + (s1 + s3);
    for i in split..len {
        s += a[i] * x[i];
        y[i] += a[i] * alpha;
    }
    s
}

/// Rows per padded column: a multiple of every vector width.
#[cfg(target_arch = "x86_64")]
const PAD: usize = 8;

/// Vectors per row block of the windowed kernel (registers for the
/// accumulators, v and w).
#[cfg(target_arch = "x86_64")]
const BLOCK_VECTORS: usize = 8;

/// A square column-major matrix in columns padded with zero rows to a
/// multiple of [`PAD`] and aligned to 64 bytes, followed by `extra` scratch
/// columns: the storage of the windowed kernels.
#[cfg(target_arch = "x86_64")]
#[derive(Debug)]
pub(crate) struct Padded {
    storage: Vec<f64>,
    offset: usize,
    /// Column stride (n rounded up to a multiple of [`PAD`]).
    pub ld: usize,
    pub n: usize,
    extra: usize,
}

#[cfg(target_arch = "x86_64")]
impl Padded {
    /// Zeros, n × n plus `extra` columns.
    pub(crate) fn zeros(n: usize, extra: usize) -> Self {
        let ld = n.div_ceil(PAD) * PAD;
        let storage = vec![0.0; ld * (n + extra) + PAD - 1];
        let offset = storage.as_ptr().align_offset(64).min(PAD - 1);
        Padded {
            storage,
            offset,
            ld,
            n,
            extra,
        }
    }

    /// A copy of the square matrix `a`.
    pub(crate) fn from_columns(a: &faer::Mat<f64>, extra: usize) -> Self {
        let mut p = Padded::zeros(a.nrows(), extra);
        let (n, ld) = (p.n, p.ld);
        for (j, dst) in p.matrix_mut().chunks_exact_mut(ld).take(n).enumerate() {
            dst[..n].copy_from_slice(a.col_as_slice(j));
        }
        p
    }

    /// The symmetric matrix whose lower triangle is that of the
    /// column-major n × n `lower`.
    fn from_lower(lower: &[f64], n: usize, extra: usize) -> Self {
        let mut p = Padded::zeros(n, extra);
        let ld = p.ld;
        let a = p.matrix_mut();
        for j in 0..n {
            a[j * ld + j..j * ld + n].copy_from_slice(&lower[j * n + j..(j + 1) * n]);
            for i in j + 1..n {
                a[i * ld + j] = lower[j * n + i];
            }
        }
        p
    }

    /// The matrix and the scratch columns, ld × (n + extra).
    pub(crate) fn matrix_mut(&mut self) -> &mut [f64] {
        let len = self.ld * (self.n + self.extra);
        &mut self.storage[self.offset..self.offset + len]
    }

    /// Entry (i, j).
    pub(crate) fn get(&self, i: usize, j: usize) -> f64 {
        self.storage[self.offset + j * self.ld + i]
    }
}

/// The windowed kernel on the lower triangle `lower` (mirrored first).
#[cfg(target_arch = "x86_64")]
fn windowed(lower: &[f64], n: usize, isa: Isa) -> HouseholderTridiagonal {
    from_padded(Padded::from_lower(lower, n, 1), isa)
}

/// The windowed kernel in place on a full symmetric matrix with one scratch
/// column; `isa` must be one this CPU has, not portable.
#[cfg(target_arch = "x86_64")]
pub(crate) fn from_padded(mut storage: Padded, isa: Isa) -> HouseholderTridiagonal {
    assert!(
        storage.extra >= 1 && isa != Isa::Portable,
        "scratch column, SIMD CPU"
    );
    let (n, ld) = (storage.n, storage.ld);
    let mut t = Tridiagonal {
        diag: vec![0.0; n],
        off: vec![0.0; n.saturating_sub(1)],
    };
    let mut beta = vec![0.0; n.saturating_sub(1)];
    let shape = Window { n, ld };
    let (a, p) = storage.matrix_mut()[..ld * (n + 1)].split_at_mut(ld * n);
    // SAFETY: `isa` is one this CPU has; `a` is ld × n with ld a multiple
    // of PAD and zero padding rows, and `p` holds ld entries.
    unsafe {
        match isa {
            Isa::Avx512 => reduce_avx512(shape, a, p, &mut t, &mut beta),
            _ => reduce_avx2(shape, a, p, &mut t, &mut beta),
        }
    }
    let Padded {
        storage, offset, ..
    } = storage;
    HouseholderTridiagonal {
        n,
        storage,
        offset,
        ld,
        beta,
        t,
    }
}

/// Size and column stride of the windowed kernel's storage.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
struct Window {
    n: usize,
    ld: usize,
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,fma")]
unsafe fn reduce_avx512(
    w: Window,
    a: &mut [f64],
    p: &mut [f64],
    t: &mut Tridiagonal,
    beta: &mut [f64],
) {
    reduce_windowed::<super::simd::Avx512>(w, a, p, t, beta)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn reduce_avx2(
    w: Window,
    a: &mut [f64],
    p: &mut [f64],
    t: &mut Tridiagonal,
    beta: &mut [f64],
) {
    reduce_windowed::<super::simd::Avx2>(w, a, p, t, beta)
}

/// # Safety
/// The CPU has `S`'s features; `a` is `w.ld × w.n` column-major with
/// `w.ld` a multiple of [`PAD`] and ≥ n, rows n… zero; `p.len() ≥ w.ld`.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn reduce_windowed<S: Lanes>(
    w: Window,
    a: &mut [f64],
    p: &mut [f64],
    t: &mut Tridiagonal,
    beta: &mut [f64],
) {
    let Window { n, ld } = w;
    debug_assert!(ld % PAD == 0 && ld >= n && a.len() >= ld * n && p.len() >= ld);
    let (ap, pp) = (a.as_mut_ptr(), p.as_mut_ptr());
    let width = S::WIDTH;
    for k in 0..n.saturating_sub(1) {
        let first = k + 1;
        t.diag[k] = a[k * ld + k];
        // The window: whole vectors from s0 ≤ first to the padded end.
        let vectors = (ld - first).div_ceil(width);
        let s0 = ld - vectors * width;
        let col = ap.add(k * ld + s0);
        let (alpha, b) = window_reflector::<S>(col, vectors, first - s0)
            .unwrap_or_else(|| reflector(&mut a[k * ld + first..k * ld + n]));
        t.off[k] = alpha;
        beta[k] = b;
        if b == 0.0 {
            continue;
        }
        let v = ap.add(k * ld) as *const f64;
        // Lanes of the first vector above row `first` are masked out.
        let mask = S::leading_zeros(first - s0);
        let mut s = s0;
        while s < ld {
            let nv = ((ld - s) / width).min(BLOCK_VECTORS);
            by_vectors!(times_v, S, nv, ap, ld, s, first..n, v, b, pp);
            s += nv * width;
        }
        // w = p − ½β(pᵀv) v, masked like v.
        let masked = |c: usize, x: S::V| if c == 0 { S::mul(x, mask) } else { x };
        let mut pv = S::zero();
        for c in 0..vectors {
            let vc = masked(c, S::load(v.add(s0 + c * width)));
            pv = S::madd(S::load(pp.add(s0 + c * width)), vc, pv);
        }
        let half = S::splat(-0.5 * b * S::sum(pv));
        for c in 0..vectors {
            let vc = masked(c, S::load(v.add(s0 + c * width)));
            let wc = S::madd(half, vc, S::load(pp.add(s0 + c * width)));
            S::store(pp.add(s0 + c * width), masked(c, wc));
        }
        let mut s = s0;
        while s < ld {
            let nv = ((ld - s) / width).min(BLOCK_VECTORS);
            let m = if s == s0 { mask } else { S::splat(1.0) };
            by_vectors!(rank2, S, nv, ap, ld, s, first..n, v, pp, m);
            s += nv * width;
        }
    }
    if n > 0 {
        t.diag[n - 1] = a[(n - 1) * ld + n - 1];
    }
}

/// The reflector of the window `col` (from row s0, `vectors` long) for rows
/// s0 + head… (rows s0 + head + 1… are its tail), in place: the window is
/// scaled (rows above the head are garbage afterwards and never read
/// again) and the head set to 1. `None` when the tail's sum of squares is
/// zero or outside [1e-250, 1e250]; the scalar [`reflector`] then handles
/// the column.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn window_reflector<S: Lanes>(
    col: *mut f64,
    vectors: usize,
    head: usize,
) -> Option<(f64, f64)> {
    let width = S::WIDTH;
    let below = S::leading_zeros(head + 1);
    let mut squares = S::zero();
    for c in 0..vectors {
        let mut x = S::load(col.add(c * width));
        if c == 0 {
            x = S::mul(x, below);
        }
        squares = S::madd(x, x, squares);
    }
    let rest = S::sum(squares);
    if !(1e-250..=1e250).contains(&rest) {
        return None;
    }
    let x0 = *col.add(head);
    let norm = (x0 * x0 + rest).sqrt();
    let alpha = if x0 > 0.0 { -norm } else { norm };
    let u0 = x0 - alpha;
    let inv = S::splat(1.0 / u0);
    for c in 0..vectors {
        S::store(col.add(c * width), S::mul(S::load(col.add(c * width)), inv));
    }
    *col.add(head) = 1.0;
    Some((alpha, -u0 / alpha))
}

/// p[s…s+NV·W) = β Σⱼ vⱼ A[s…, j] over the columns `cols`, with two sets of
/// accumulators (alternate columns) so that the additions do not wait on
/// each other.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn times_v<S: Lanes, const NV: usize>(
    a: *const f64,
    ld: usize,
    s: usize,
    cols: std::ops::Range<usize>,
    v: *const f64,
    beta: f64,
    p: *mut f64,
) {
    let width = S::WIDTH;
    let mut even = [S::zero(); NV];
    let mut odd = [S::zero(); NV];
    let mut j = cols.start;
    while j + 1 < cols.end {
        let (c0, c1) = (a.add(j * ld + s), a.add((j + 1) * ld + s));
        let (v0, v1) = (S::splat(*v.add(j)), S::splat(*v.add(j + 1)));
        for c in 0..NV {
            even[c] = S::madd(S::load(c0.add(c * width)), v0, even[c]);
            odd[c] = S::madd(S::load(c1.add(c * width)), v1, odd[c]);
        }
        j += 2;
    }
    if j < cols.end {
        let c0 = a.add(j * ld + s);
        let v0 = S::splat(*v.add(j));
        for (c, e) in even.iter_mut().enumerate() {
            *e = S::madd(S::load(c0.add(c * width)), v0, *e);
        }
    }
    let b = S::splat(beta);
    for c in 0..NV {
        S::store(p.add(s + c * width), S::mul(S::add(even[c], odd[c]), b));
    }
}

/// A[s…s+NV·W, j] −= v wⱼ + w vⱼ for the columns `cols`; `mask` multiplies
/// the first vector of v (w is masked already).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn rank2<S: Lanes, const NV: usize>(
    a: *mut f64,
    ld: usize,
    s: usize,
    cols: std::ops::Range<usize>,
    v: *const f64,
    w: *const f64,
    mask: S::V,
) {
    let width = S::WIDTH;
    let mut vv = [S::zero(); NV];
    let mut ww = [S::zero(); NV];
    for c in 0..NV {
        vv[c] = S::load(v.add(s + c * width));
        ww[c] = S::load(w.add(s + c * width));
    }
    vv[0] = S::mul(vv[0], mask);
    for j in cols {
        let col = a.add(j * ld + s);
        let (vj, wj) = (S::splat(*v.add(j)), S::splat(*w.add(j)));
        for c in 0..NV {
            let x = S::load(col.add(c * width));
            S::store(
                col.add(c * width),
                S::nmadd(ww[c], vj, S::nmadd(vv[c], wj, x)),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::bisection::SturmCounts;

    /// A = Q diag(λ) Qᵀ with λᵢ = scale·(i − n/3)/n (some negative, one
    /// pair close) and Q a product of n pseudo-random reflectors.
    fn with_spectrum(n: usize, scale: f64) -> (Vec<f64>, Vec<f64>) {
        let values: Vec<f64> = (0..n)
            .map(|i| scale * (i as f64 - n as f64 / 3.0) / n as f64)
            .collect();
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            a[i * n + i] = values[i];
        }
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..n.min(6) {
            let u: Vec<f64> = (0..n)
                .map(|_| {
                    seed ^= seed << 13;
                    seed ^= seed >> 7;
                    seed ^= seed << 17;
                    (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
                })
                .collect();
            let uu = dot(&u, &u);
            // A ← H A H, H = I − 2uuᵀ/uᵀu.
            for pass in 0..2 {
                for c in 0..n {
                    let at = |r: usize| if pass == 0 { r * n + c } else { c * n + r };
                    let s = 2.0 * (0..n).map(|r| u[r] * a[at(r)]).sum::<f64>() / uu;
                    for r in 0..n {
                        a[at(r)] -= s * u[r];
                    }
                }
            }
        }
        let mut sorted = values;
        sorted.sort_by(f64::total_cmp);
        (a, sorted)
    }

    /// Every kernel this CPU runs: T has A's eigenvalues to 10nε‖A‖, and
    /// Q T Qᵀ = A to the same order (Q applied to the identity), for sizes
    /// with one and several row blocks and partial vectors, and for scales
    /// whose sums of squares leave [1e-250, 1e250] (scalar reflectors).
    #[test]
    fn every_kernel_is_an_orthogonal_similarity() {
        for isa in Isa::all_available() {
            for n in [1, 2, 3, 5, 8, 9, 17, 33, 40, 64, 71] {
                for scale in [1.0, 1e9, 1e-140, 1e140] {
                    let (a, values) = with_spectrum(n, scale);
                    let norm = scale;
                    let tol = 10.0 * n as f64 * f64::EPSILON * norm;
                    let h = HouseholderTridiagonal::with_isa(a.clone(), n, isa);
                    let (got, _) = SturmCounts::new(&h.t).unwrap().lowest_and_largest(n);
                    for (g, v) in got.iter().zip(&values) {
                        assert!(
                            (g - v).abs() <= tol,
                            "{isa:?}, n = {n}, scale {scale:e}: eigenvalue {g:e} vs {v:e}"
                        );
                    }
                    // Q (row-major n × n) from the identity; then Q T Qᵀ.
                    let mut q = vec![0.0; n * n];
                    (0..n).for_each(|i| q[i * n + i] = 1.0);
                    h.apply_q(&mut q, n);
                    let tq = |i: usize, c: usize| {
                        let mut x = h.t.diag[c] * q[i * n + c];
                        if c > 0 {
                            x += h.t.off[c - 1] * q[i * n + c - 1];
                        }
                        if c + 1 < n {
                            x += h.t.off[c] * q[i * n + c + 1];
                        }
                        x
                    };
                    for i in 0..n {
                        for j in 0..=i {
                            let qtq: f64 = (0..n).map(|c| tq(i, c) * q[j * n + c]).sum();
                            let err = (qtq - a[j * n + i]).abs();
                            assert!(
                                err <= tol,
                                "{isa:?}, n = {n}, scale {scale:e}: (QTQᵀ − A)[{i},{j}] = {err:e}"
                            );
                        }
                    }
                }
            }
        }
    }

    /// A matrix that is already tridiagonal needs no reflection (β = 0 at
    /// every step); every kernel returns it unchanged.
    #[test]
    fn a_tridiagonal_matrix_is_left_alone() {
        let n = 13;
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            a[i * n + i] = 2.0 + i as f64;
            if i + 1 < n {
                a[i * n + i + 1] = -1.0 - 0.1 * i as f64;
            }
        }
        for isa in Isa::all_available() {
            let h = HouseholderTridiagonal::with_isa(a.clone(), n, isa);
            for i in 0..n {
                assert_eq!(h.t.diag[i], a[i * n + i], "{isa:?}: diagonal {i}");
                if i + 1 < n {
                    assert_eq!(h.t.off[i], a[i * n + i + 1], "{isa:?}: off-diagonal {i}");
                }
            }
        }
    }
}
