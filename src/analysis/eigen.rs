//! Symmetric-definite generalized eigenproblem K x = λ M x [SI: λ = ω² in
//! rad²/s² for a stiffness K and a mass M].
//!
//! Cholesky reduction: M = L Lᵀ, C = L⁻¹ K L⁻ᵀ, C y = λ y, x = L⁻ᵀ y. The
//! vectors come out mass-normalized (xᵀ M x = 1). The lowest `wanted`
//! eigenvalues are returned, ascending, with their vectors; what is known of
//! the rest of the spectrum (its largest |λ|, how many eigenvalues lie near
//! zero) comes with them as a [`Spectrum`].
//!
//! Up to [`IN_HOUSE_ALL_MAX`] coordinates, or [`IN_HOUSE_MAX`] when at most
//! a quarter of the vectors are wanted, everything is done in this crate:
//! - up to 64 coordinates on CPUs with AVX2 or AVX-512, L and C from the
//!   windowed kernels of `analysis/standard_form.rs`, C full and ready for
//!   the windowed Householder kernel;
//! - otherwise an envelope Cholesky (the reduced mass matrix of a beam
//!   model is nearly banded) and C's lower triangle from row-wise
//!   substitutions ([`Cholesky`]);
//! - then [`super::small_eigen`] (Householder tridiagonalization, bisection
//!   for the wanted eigenvalues, inverse-iteration vectors).
//!
//! Above it faer's blocked factorizations and the QR algorithm with all
//! vectors are faster. All paths are backward stable, so the eigenvalues
//! carry absolute errors of order ε‖C‖.

#[cfg(target_arch = "x86_64")]
use super::householder::from_padded;
use super::householder::HouseholderTridiagonal;
#[cfg(target_arch = "x86_64")]
use super::simd::Isa;
use super::small_eigen::{dot, eigenpairs_of, SturmCounts};
#[cfg(target_arch = "x86_64")]
use super::standard_form::{WindowedFactor, WINDOWED_MAX};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par, Side};

/// The lowest eigenvalues (ascending) and their mass-normalized eigenvectors
/// (columns, one per value).
#[derive(Debug, Clone)]
pub struct GeneralizedEigen {
    pub values: Vec<f64>,
    pub vectors: Mat<f64>,
    pub spectrum: Spectrum,
}

impl GeneralizedEigen {
    /// Number of eigenvalues of the whole spectrum with |λ| ≤ `tol`, when
    /// known. The returned values are the lowest, so when the last of them
    /// lies above `tol` every eigenvalue within it was returned and they are
    /// counted directly; otherwise the spectrum is asked (two Sturm counts).
    pub fn count_within(&self, tol: f64) -> Option<usize> {
        match self.values.last() {
            Some(&last) if last > tol => {
                Some(self.values.iter().filter(|v| v.abs() <= tol).count())
            }
            _ => self.spectrum.count_within(tol),
        }
    }
}

/// What a solver knows of the eigenvalues beyond those it returned.
#[derive(Debug, Clone)]
pub enum Spectrum {
    /// Every eigenvalue, ascending.
    All(Vec<f64>),
    /// Sturm counts of the tridiagonal form, and the largest |λ| (to a
    /// relative 2⁻³⁰ unless it was among the wanted values).
    Counts { counts: SturmCounts, max_abs: f64 },
    /// Nothing beyond the returned values (a partial solver).
    Partial,
}

impl Spectrum {
    /// Largest |λ| of the whole spectrum, when known.
    pub fn max_abs(&self) -> Option<f64> {
        match self {
            Spectrum::All(v) => Some(v.iter().fold(0.0f64, |a, x| a.max(x.abs()))),
            Spectrum::Counts { max_abs, .. } => Some(*max_abs),
            Spectrum::Partial => None,
        }
    }

    /// Number of eigenvalues with |λ| ≤ `tol`, when known.
    pub fn count_within(&self, tol: f64) -> Option<usize> {
        match self {
            Spectrum::All(v) => Some(v.iter().filter(|x| x.abs() <= tol).count()),
            Spectrum::Counts { counts, .. } => Some(counts.count_within(tol)),
            Spectrum::Partial => None,
        }
    }
}

/// Why the generalized problem could not be solved.
#[derive(Debug, Clone, PartialEq)]
pub enum EigenFailure {
    /// M is not positive definite; the vector spans (approximately) its null direction.
    SingularMass {
        direction: Vec<f64>,
    },
    NoConvergence,
}

fn par(n: usize) -> Par {
    if n >= 256 {
        Par::rayon(0)
    } else {
        Par::Seq
    }
}

/// Size up to which the in-house solver ([`super::small_eigen`]) is used
/// when at most a quarter of the vectors are wanted.
pub const IN_HOUSE_MAX: usize = 160;

/// Size up to which the in-house solver is used for any number of vectors.
///
/// Measured on a matrix whose eigenvalues form one cluster (the worst case
/// for inverse iteration), M = I; in-house with vectors for all / for 12
/// eigenvalues against faer's QR algorithm with all vectors (without the
/// reduction): n = 40 94 / 38 / 117 µs, n = 48 143 / 51 / 164 µs; for 12
/// vectors n = 100 231 / 956 µs, n = 160 775 / 2846 µs (busy 2-core host,
/// best of 7). Re-orthogonalization costs O(n·w²) in a cluster of w
/// vectors, so faer wins for many vectors and large n.
pub const IN_HOUSE_ALL_MAX: usize = 48;

/// Solve K x = λ M x for symmetric K and symmetric positive definite M: the
/// lowest `wanted` eigenvalues with M-normalized vectors.
pub fn solve_generalized(
    k: &Mat<f64>,
    m: &Mat<f64>,
    wanted: usize,
) -> Result<GeneralizedEigen, EigenFailure> {
    let n = k.nrows();
    let wanted = wanted.min(n);
    if n == 0 {
        return Ok(GeneralizedEigen {
            values: Vec::new(),
            vectors: Mat::zeros(0, 0),
            spectrum: Spectrum::All(Vec::new()),
        });
    }
    if n > IN_HOUSE_ALL_MAX && (n > IN_HOUSE_MAX || 4 * wanted > n) {
        return solve_generalized_faer(k, m, wanted);
    }
    let singular = || EigenFailure::SingularMass {
        direction: null_direction(m),
    };
    let (factor, h) = standard_form(k, m).ok_or_else(singular)?;
    // Reject a numerically singular factor too (tiny pivots from zero inertia).
    if factor.min_pivot_ratio() <= SINGULAR_PIVOT {
        return Err(singular());
    }
    // Should the inverse iteration not converge (not seen on any model so
    // far), the faer path gets its chance.
    let Ok(mut eig) = eigenpairs_of(h, wanted) else {
        return solve_generalized_faer(k, m, wanted);
    };
    factor.backward_rows(&mut eig.vectors, wanted);
    let y = &eig.vectors;
    Ok(GeneralizedEigen {
        values: eig.values,
        vectors: Mat::from_fn(n, wanted, |i, j| y[i * wanted + j]),
        spectrum: Spectrum::Counts {
            counts: eig.spectrum,
            max_abs: eig.max_abs,
        },
    })
}

/// The Cholesky factor of M from one of the two reductions.
enum Factor {
    Envelope(Cholesky),
    #[cfg(target_arch = "x86_64")]
    Windowed(WindowedFactor),
}

impl Factor {
    fn min_pivot_ratio(&self) -> f64 {
        match self {
            Factor::Envelope(l) => l.min_pivot_ratio(),
            #[cfg(target_arch = "x86_64")]
            Factor::Windowed(l) => l.min_pivot_ratio(),
        }
    }

    fn backward_rows(&self, b: &mut [f64], w: usize) {
        match self {
            Factor::Envelope(l) => l.backward_rows(b, w),
            #[cfg(target_arch = "x86_64")]
            Factor::Windowed(l) => l.backward_rows(b, w),
        }
    }
}

/// C = L⁻¹KL⁻ᵀ (M = L Lᵀ) reduced to tridiagonal form, as
/// [`solve_generalized`] does it for sizes up to [`IN_HOUSE_MAX`]; None if M
/// is not positive definite. (For benchmarks of that stage.)
pub fn tridiagonal_form(k: &Mat<f64>, m: &Mat<f64>) -> Option<HouseholderTridiagonal> {
    standard_form(k, m).map(|(_, h)| h)
}

/// M = L Lᵀ and C = L⁻¹KL⁻ᵀ reduced to tridiagonal form: the windowed
/// kernels ([`super::standard_form`]) up to their size on SIMD CPUs, the
/// envelope kernels otherwise. None if M is not positive definite.
fn standard_form(k: &Mat<f64>, m: &Mat<f64>) -> Option<(Factor, HouseholderTridiagonal)> {
    let n = m.nrows();
    #[cfg(target_arch = "x86_64")]
    {
        let isa = Isa::detect();
        if n <= WINDOWED_MAX && isa != Isa::Portable {
            let (l, c) = super::standard_form::standard_form(k, m, isa).ok()?;
            return Some((Factor::Windowed(l), from_padded(c, isa)));
        }
    }
    let l = Cholesky::factor(m)?;
    let h = HouseholderTridiagonal::new(l.reduce(k), n);
    Some((Factor::Envelope(l), h))
}

/// first[i]: the leftmost nonzero of row i of the symmetric `m` (its lower
/// triangle read), the envelope a Cholesky factor keeps. A select, not a
/// branch: the nonzero pattern is irregular and a branch mispredicts.
pub(crate) fn row_envelope(m: &Mat<f64>) -> Vec<usize> {
    let n = m.nrows();
    let mut first: Vec<usize> = (0..n).collect();
    for j in (0..n).rev() {
        let below = &m.col_as_slice(j)[j + 1..];
        for (f, &v) in first[j + 1..].iter_mut().zip(below) {
            *f = if v != 0.0 { j } else { *f };
        }
    }
    first
}

/// B ← L⁻ᵀ B for a row-major n × w block, with L[j, k] = `l(j, k)` nonzero
/// only from column `first[j]` of row j on: row j is divided by Lⱼⱼ, then
/// taken off the earlier rows it couples to.
pub(crate) fn backward_rows(
    first: &[usize],
    l: impl Fn(usize, usize) -> f64,
    b: &mut [f64],
    w: usize,
) {
    for j in (0..first.len()).rev() {
        let (head, rest) = b.split_at_mut(j * w);
        let xj = &mut rest[..w];
        let inv = 1.0 / l(j, j);
        xj.iter_mut().for_each(|t| *t *= inv);
        for k in first[j]..j {
            let ljk = l(j, k);
            if ljk != 0.0 {
                let target = &mut head[k * w..(k + 1) * w];
                target.iter_mut().zip(&*xj).for_each(|(t, s)| *t -= ljk * s);
            }
        }
    }
}

/// A Cholesky pivot Lᵢᵢ ≤ this × maxⱼ Lⱼⱼ marks M as singular.
const SINGULAR_PIVOT: f64 = 1e-7;

/// The faer path for large n: Cholesky, triangular solves and the QR
/// algorithm with all vectors.
fn solve_generalized_faer(
    k: &Mat<f64>,
    m: &Mat<f64>,
    wanted: usize,
) -> Result<GeneralizedEigen, EigenFailure> {
    let n = k.nrows();
    let p = par(n);
    let singular = || EigenFailure::SingularMass {
        direction: null_direction(m),
    };
    let llt = m.llt(Side::Lower).map_err(|_| singular())?;
    let l = llt.L();
    let dmax = (0..n).map(|i| l[(i, i)].abs()).fold(0.0, f64::max);
    if (0..n).any(|i| l[(i, i)].abs() <= SINGULAR_PIVOT * dmax) {
        return Err(singular());
    }
    // W = L⁻¹ K, then C = L⁻¹ Wᵀ = L⁻¹ K L⁻ᵀ.
    let mut w = k.clone();
    solve_lower_triangular_in_place(l, w.as_mut(), p);
    let mut c = w.transpose().to_owned();
    solve_lower_triangular_in_place(l, c.as_mut(), p);
    let c = Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]));
    let (values, vectors) = symmetric_eigen_qr(&c, p)?;
    let mut vectors = vectors.subcols(0, wanted).to_owned();
    solve_upper_triangular_in_place(l.transpose(), vectors.as_mut(), p);
    Ok(GeneralizedEigen {
        values: values[..wanted].to_vec(),
        vectors,
        spectrum: Spectrum::All(values),
    })
}

/// M = L Lᵀ by the envelope (skyline) Cholesky algorithm, rows of L stored
/// contiguously: row i is nonzero only from the first nonzero column of row
/// i of M, so a banded mass matrix costs O(n b²), not O(n³).
pub struct Cholesky {
    n: usize,
    /// Row-major n × n; row i holds L[i, first[i]..=i].
    l: Vec<f64>,
    first: Vec<usize>,
    /// 1 / L[i, i].
    inv_diag: Vec<f64>,
}

impl Cholesky {
    /// None unless every pivot is positive and finite (lower triangle of m read).
    pub fn factor(m: &Mat<f64>) -> Option<Cholesky> {
        let n = m.nrows();
        let first = row_envelope(m);
        let mut l = vec![0.0; n * n];
        let mut inv_diag = vec![0.0; n];
        for i in 0..n {
            let (done, rest) = l.split_at_mut(i * n);
            let row = &mut rest[..n];
            let fi = first[i];
            for j in fi..i {
                let f = fi.max(first[j]);
                let lj = &done[j * n..j * n + j + 1];
                let s = m[(i, j)] - dot(&row[f..j], &lj[f..j]);
                row[j] = s * inv_diag[j];
            }
            let pivot = m[(i, i)] - dot(&row[fi..i], &row[fi..i]);
            if !(pivot > 0.0 && pivot.is_finite()) {
                return None;
            }
            row[i] = pivot.sqrt();
            inv_diag[i] = 1.0 / row[i];
        }
        Some(Cholesky {
            n,
            l,
            first,
            inv_diag,
        })
    }

    fn row(&self, i: usize) -> &[f64] {
        &self.l[i * self.n..i * self.n + i + 1]
    }

    /// minᵢ Lᵢᵢ / maxᵢ Lᵢᵢ.
    fn min_pivot_ratio(&self) -> f64 {
        let d = (0..self.n).map(|i| self.row(i)[i]);
        let (lo, hi) = d.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        lo / hi
    }

    /// C = L⁻¹ K L⁻ᵀ, column-major n × n, lower triangle only (the upper
    /// triangle holds intermediate values).
    ///
    /// Both triangular solves run row by row on row-major blocks, Y = L⁻¹K
    /// as Y[r, :] = (K[r, :] − Σₖ L[r,k] Y[k, :]) / L[r,r] (K[r, :] = K[:, r]
    /// by symmetry), then C = L⁻¹Yᵀ the same way; L's envelope limits k. In the second solve, row r
    /// of C is formed from column r on only: C[r, r..] needs C[k, r..] of the
    /// earlier rows and nothing left of column r, and C[r, r..] read as
    /// column-major storage is the lower triangle. That halves the second
    /// solve, and the rows that couple to everything (the constrained
    /// coordinates, last) cost almost nothing there.
    pub fn reduce(&self, k: &Mat<f64>) -> Vec<f64> {
        let n = self.n;
        let mut y = Vec::with_capacity(n * n);
        for r in 0..n {
            y.extend_from_slice(k.col_as_slice(r));
        }
        self.forward_rows(&mut y, n, false);
        // y row-major is Yᵀ column-major; transpose so rows of Yᵀ are contiguous.
        let mut c = vec![0.0; n * n];
        for (i, row) in y.chunks_exact(n).enumerate() {
            for (j, &v) in row.iter().enumerate() {
                c[j * n + i] = v;
            }
        }
        self.forward_rows(&mut c, n, true);
        c
    }

    /// B ← L⁻¹ B for a row-major n × w block, row r from column 0 on, or
    /// from column r on (`lower`). Row r's columns go in tiles of up to
    /// eight held in registers while every source row k (L's envelope) is
    /// subtracted in order, so the rounding is that of one axpy per source
    /// row, with one load and store of the target per tile. Multiply-adds
    /// are fused where the CPU can ([`super::fused`]).
    fn forward_rows(&self, b: &mut [f64], w: usize, lower: bool) {
        #[cfg(target_arch = "x86_64")]
        if super::fused::available() {
            // SAFETY: the CPU has the features the function is compiled for.
            return unsafe { self.forward_rows_fma(b, w, lower) };
        }
        self.forward_rows_with::<false>(b, w, lower);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn forward_rows_fma(&self, b: &mut [f64], w: usize, lower: bool) {
        self.forward_rows_with::<true>(b, w, lower);
    }

    #[inline(always)]
    fn forward_rows_with<const FMA: bool>(&self, b: &mut [f64], w: usize, lower: bool) {
        for r in 0..self.n {
            let (done, rest) = b.split_at_mut(r * w);
            let first = self.first[r];
            let rows = Sources {
                done,
                w,
                first,
                coef: &self.row(r)[first..r],
                inv: self.inv_diag[r],
            };
            let mut col = if lower { r } else { 0 };
            while col < w {
                let target = &mut rest[col..w];
                col += match target.len() {
                    8.. => rows.tile::<8, FMA>(target, col),
                    4..=7 => rows.tile::<4, FMA>(target, col),
                    _ => rows.tile::<1, FMA>(target, col),
                };
            }
        }
    }

    /// B ← L⁻ᵀ B for a row-major n × w block.
    pub(crate) fn backward_rows(&self, b: &mut [f64], w: usize) {
        backward_rows(&self.first, |j, k| self.row(j)[k], b, w);
    }
}

/// The rows already solved in [`Cholesky::forward_rows`] and the
/// coefficients of row r on them: L[r, first..r] and 1/L[r, r].
struct Sources<'a> {
    done: &'a [f64],
    w: usize,
    first: usize,
    coef: &'a [f64],
    inv: f64,
}

impl Sources<'_> {
    /// target[..TW] ← (target − Σₖ L[r,k] B[k, col..col+TW]) / L[r,r];
    /// returns TW.
    #[inline(always)]
    fn tile<const TW: usize, const FMA: bool>(&self, target: &mut [f64], col: usize) -> usize {
        let mut acc = [0.0; TW];
        acc.copy_from_slice(&target[..TW]);
        for (i, &l) in self.coef.iter().enumerate() {
            let s = &self.done[(self.first + i) * self.w + col..][..TW];
            for t in 0..TW {
                acc[t] = super::fused::madd::<FMA>(-l, s[t], acc[t]);
            }
        }
        for t in 0..TW {
            target[t] = acc[t] * self.inv;
        }
        TW
    }
}

/// Eigenvalues (ascending) and eigenvectors of a symmetric matrix by the
/// tridiagonal QR algorithm.
///
/// faer's default switches to divide and conquer from n = 128, and that path
/// lost the zero eigenvalues of a free 32-element beam (ω² = 1.7e5 instead of
/// ~0.1 rad²/s², where the eigenvalue-only path, nalgebra and LAPACK agree),
/// so the QR algorithm is forced for every size.
pub fn symmetric_eigen_qr(c: &Mat<f64>, par: Par) -> Result<(Vec<f64>, Mat<f64>), EigenFailure> {
    use faer::dyn_stack::{MemBuffer, MemStack};
    use faer::linalg::evd::{self, ComputeEigenvectors, SelfAdjointEvdParams};
    let n = c.nrows();
    let mut params: SelfAdjointEvdParams = faer::auto!(f64);
    params.recursion_threshold = usize::MAX;
    let mut s = faer::diag::Diag::<f64>::zeros(n);
    let mut u = Mat::<f64>::zeros(n, n);
    let req = evd::self_adjoint_evd_scratch::<f64>(n, ComputeEigenvectors::Yes, par, params.into());
    let mut buf = MemBuffer::new(req);
    evd::self_adjoint_evd(
        c.as_ref(),
        s.as_mut(),
        Some(u.as_mut()),
        par,
        MemStack::new(&mut buf),
        params.into(),
    )
    .map_err(|_| EigenFailure::NoConvergence)?;
    Ok(((0..n).map(|i| s[i]).collect(), u))
}

/// Eigenvector of the smallest eigenvalue of a symmetric matrix.
fn null_direction(m: &Mat<f64>) -> Vec<f64> {
    let sym = Mat::from_fn(m.nrows(), m.ncols(), |i, j| 0.5 * (m[(i, j)] + m[(j, i)]));
    match sym.self_adjoint_eigen(Side::Lower) {
        Ok(e) => (0..m.nrows()).map(|i| e.U()[(i, 0)]).collect(),
        Err(_) => vec![0.0; m.nrows()],
    }
}
