//! Lowest eigenpairs of a small dense symmetric matrix C (in the modal
//! analysis C = L⁻¹KL⁻ᵀ, so its eigenvalues are ω² [SI: rad²/s²]).
//!
//! Three steps, each a textbook algorithm (Golub & Van Loan, *Matrix
//! Computations*, §5.1, §8.3, §8.2; Wilkinson, *The Algebraic Eigenvalue
//! Problem*, ch. 9):
//!
//! 1. **Householder tridiagonalization** C = Q T Qᵀ
//!    ([`super::householder`]): one reflector per column, applied to the
//!    trailing block as a symmetric rank-2 update; the reflector vectors stay
//!    in the columns they annihilated and Q is never formed. The matrix goes
//!    in as its lower triangle, column-major.
//! 2. **The lowest `count` eigenvalues and the largest** of T by bisection
//!    on Sturm counts ([`super::bisection`]), sixteen side by side, O(n) per
//!    count and at most 54 counts each. The Sturm counts stay available
//!    afterwards, so the number of eigenvalues in any interval (e.g. the
//!    zero eigenvalues beyond those asked for) costs two counts.
//! 3. **Eigenvectors of the lowest `count` eigenvalues only**, by inverse
//!    iteration on T ([`super::inverse_iteration`]), then back-transformed
//!    x = Q y by the stored reflectors, four at a time in the compact WY
//!    form ([`super::back_transform`]; 2n² flops a vector).
//!
//! Accuracy: every step is backward stable, so the eigenvalues carry an
//! absolute error of a small multiple of ε‖C‖, as the QR algorithm does.
//! The vectors have residuals ‖Cx − λx‖ of order nε‖C‖ and are
//! orthonormal to a few ε inside a cluster; across clusters (gap ≥
//! 10⁻²‖C‖) orthogonality is of order ε‖C‖/gap ≤ 10²ε. A multiple
//! eigenvalue — the three rigid-body modes of a free assembly sit at
//! ~ε‖C‖ — gets an orthonormal basis of its invariant subspace rather than
//! one vector repeated. The gain over the QR algorithm with vectors (6n³
//! flops for the rotations) is that only the wanted pairs are computed.

pub use super::bisection::SturmCounts;
use super::eigen::EigenFailure;
pub use super::householder::HouseholderTridiagonal;
pub use super::inverse_iteration::{tridiagonal_eigenvectors, CLUSTER_GAP};

/// A symmetric tridiagonal matrix.
#[derive(Debug, Clone, PartialEq)]
pub struct Tridiagonal {
    /// Diagonal d (n).
    pub diag: Vec<f64>,
    /// Off-diagonal e (n − 1): T[i+1, i] = T[i, i+1] = e[i].
    pub off: Vec<f64>,
}

impl Tridiagonal {
    /// ‖T‖∞ (largest absolute row sum).
    pub fn norm_inf(&self) -> f64 {
        let n = self.diag.len();
        (0..n)
            .map(|i| {
                let below = if i + 1 < n { self.off[i].abs() } else { 0.0 };
                let above = if i > 0 { self.off[i - 1].abs() } else { 0.0 };
                self.diag[i].abs() + below + above
            })
            .fold(0.0, f64::max)
    }
}

/// a·b with four partial sums (no serial chain of additions).
#[inline]
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    let len = a.len().min(b.len());
    let (a, b) = (&a[..len], &b[..len]);
    let split = len - len % 4;
    let mut acc = [0.0; 4];
    for (a4, b4) in a[..split].chunks_exact(4).zip(b[..split].chunks_exact(4)) {
        for t in 0..4 {
            acc[t] += a4[t] * b4[t];
        }
    }
    let mut s = (acc[0] + acc[2]) + (acc[1] + acc[3]);
    for i in split..len {
        s += a[i] * b[i];
    }
    s
}

/// The lowest eigenvalues (ascending) of a symmetric matrix with their unit
/// eigenvectors, row-major n × count (row i holds component i of every
/// vector), and the Sturm counts of its tridiagonal form for the rest of
/// the spectrum.
#[derive(Debug, Clone)]
pub struct LowestEigen {
    pub values: Vec<f64>,
    pub vectors: Vec<f64>,
    /// Largest |λ| of the whole spectrum (relative accuracy 2⁻³⁰ if it is
    /// not among the lowest `count`).
    pub max_abs: f64,
    pub spectrum: SturmCounts,
}

/// Eigen-decomposition of the symmetric n × n matrix `a` (column-major,
/// lower triangle read, storage consumed): the lowest `count` eigenvalues
/// with vectors.
pub fn lowest_eigenpairs(a: Vec<f64>, n: usize, count: usize) -> Result<LowestEigen, EigenFailure> {
    eigenpairs_of(HouseholderTridiagonal::new(a, n), count)
}

/// [`lowest_eigenpairs`] of a matrix already in tridiagonal form.
pub(crate) fn eigenpairs_of(
    h: HouseholderTridiagonal,
    count: usize,
) -> Result<LowestEigen, EigenFailure> {
    let n = h.t.diag.len();
    let count = count.min(n);
    let spectrum = SturmCounts::new(&h.t)?;
    let (values, largest) = spectrum.lowest_and_largest(count);
    // The accurate value when the largest is among the wanted ones.
    let top = match values.last() {
        Some(&v) if values.len() == n => v,
        _ => largest,
    };
    let max_abs = values.first().map_or(0.0, |v: &f64| v.abs()).max(top.abs());
    let mut vectors = tridiagonal_eigenvectors(&h.t, &values)?;
    if count > 0 {
        h.apply_q(&mut vectors, count);
    }
    Ok(LowestEigen {
        values,
        vectors,
        max_abs,
        spectrum,
    })
}
