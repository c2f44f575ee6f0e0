//! Lowest eigenpairs of a small dense symmetric matrix C (in the modal
//! analysis C = L⁻¹KL⁻ᵀ, so its eigenvalues are ω² [SI: rad²/s²]).
//!
//! Three steps, each a textbook algorithm (Golub & Van Loan, *Matrix
//! Computations*, §5.1, §8.3, §8.2; Wilkinson, *The Algebraic Eigenvalue
//! Problem*, ch. 9):
//!
//! 1. **Householder tridiagonalization** C = Q T Qᵀ on contiguous
//!    column-major storage, reading the lower triangle only. Step k reflects
//!    the part of column k below the diagonal onto its first entry and applies
//!    the reflector to the trailing block as one symmetric rank-2 update
//!    (p = βA v, w = p − ½β(pᵀv) v, A ← A − v wᵀ − w vᵀ). The reflector
//!    vectors stay in the columns they annihilated; Q is never formed.
//!    Cost 4n³/3 flops.
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

use super::back_transform::{apply_q, Reflectors};
pub use super::bisection::SturmCounts;
use super::eigen::EigenFailure;
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

/// C = Q T Qᵀ with Q = H₀H₁⋯H_{n−2}, Hₖ = I − βₖ vₖ vₖᵀ acting on rows k+1…n−1.
#[derive(Debug, Clone)]
pub struct HouseholderTridiagonal {
    n: usize,
    /// Column k, rows k+1…n−1, holds vₖ (first entry 1); column-major n × n.
    reflectors: Vec<f64>,
    /// βₖ (0 where no reflection was needed).
    beta: Vec<f64>,
    /// The tridiagonal T.
    pub t: Tridiagonal,
}

impl HouseholderTridiagonal {
    /// Reduce the symmetric n × n matrix `a` (column-major; only its lower
    /// triangle is read), reusing its storage for the reflectors.
    pub fn new(mut a: Vec<f64>, n: usize) -> Self {
        assert_eq!(a.len(), n * n, "column-major n × n storage");
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
            reflectors: a,
            beta,
            t: Tridiagonal { diag, off },
        }
    }

    /// Y ← Q Y for a row-major n × w block: eigenvectors of T become
    /// eigenvectors of C ([`super::back_transform`]).
    pub fn apply_q(&self, y: &mut [f64], w: usize) {
        let reflectors = Reflectors {
            n: self.n,
            vectors: &self.reflectors,
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
    let count = count.min(n);
    let h = HouseholderTridiagonal::new(a, n);
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
