//! Rayleigh–Ritz on a subspace given by a few columns over many
//! coordinates: the reduced models of component-mode synthesis.
//!
//! The columns V (n × c) may be linearly dependent (constraint modes that
//! span the rigid motions once those are projected out). The caller gives
//! them at a common scale (e.g. unit M-norm *before* any projection), and
//! they are used as given: the Gram matrix G = VᵀMV is diagonalized and
//! the eigenvectors whose eigenvalue falls below [`DEPENDENT`] · max are
//! dropped, so Q = V W Λ^-½ is an M-orthonormal basis of the span. A
//! column that a projection reduced to round-off is dropped with them;
//! scaling it back up to unit norm would make its round-off (which keeps
//! neither the projection nor the constraints) a direction of the span. Then the
//! Ritz problem QᵀKQ y = μ y (ordinary: Q is M-orthonormal) gives the Ritz
//! vectors Q Y, M-orthonormal and K-orthogonal, ascending in μ [SI: ω² in
//! rad²/s² for a stiffness K and a mass M].

use super::dense::symmetric_eigen_qr;
use super::EigenFailure;
use faer::{Mat, Par};

/// Relative Gram eigenvalue below which a direction of the span counts as
/// dependent (a singular value of 1e-5 of unit-norm columns: far above the
/// round-off of exactly dependent ones, far below any independent one).
pub const DEPENDENT: f64 = 1e-10;

/// The Ritz vectors of the span of `v` (columns at a common scale, module
/// doc): columns of unit M-norm, K-orthogonal, ascending, and their Ritz
/// values.
/// `mass`/`stiffness` apply M and K to a column.
pub fn ritz_basis(
    v: &Mat<f64>,
    mass: &dyn Fn(&[f64], &mut [f64]),
    stiffness: &dyn Fn(&[f64], &mut [f64]),
) -> Result<(Vec<f64>, Mat<f64>), EigenFailure> {
    let (n, c) = (v.nrows(), v.ncols());
    let mut mv = Mat::<f64>::zeros(n, c);
    for j in 0..c {
        mass(v.col_as_slice(j), mv.col_as_slice_mut(j));
    }
    let gram = symmetric(&(v.transpose() * &mv));
    let (values, vectors) = symmetric_eigen_qr(&gram, Par::Seq)?;
    let largest = values.iter().fold(0.0f64, |a, &b| a.max(b));
    let kept: Vec<usize> = (0..c)
        .filter(|&i| values[i] > DEPENDENT * largest)
        .collect();
    let w = Mat::from_fn(c, kept.len(), |i, j| {
        vectors[(i, kept[j])] / values[kept[j]].sqrt()
    });
    let q = v * &w;
    let mut kq = Mat::<f64>::zeros(n, q.ncols());
    for j in 0..q.ncols() {
        stiffness(q.col_as_slice(j), kq.col_as_slice_mut(j));
    }
    let reduced = symmetric(&(q.transpose() * &kq));
    let (mu, y) = symmetric_eigen_qr(&reduced, Par::Seq)?;
    Ok((mu, &q * &y))
}

/// (A + Aᵀ)/2.
pub fn symmetric(a: &Mat<f64>) -> Mat<f64> {
    Mat::from_fn(a.nrows(), a.ncols(), |i, j| 0.5 * (a[(i, j)] + a[(j, i)]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_dependent_column_is_dropped_and_the_ritz_values_are_exact_on_an_invariant_span() {
        // M = diag(1, 2, 3), K = diag(2, 8, 27): eigenvalues 2, 4, 9 along
        // the axes. Columns e0, e1 and e0 + e1 (dependent) span an
        // invariant subspace: Ritz values 2 and 4 exactly, two columns.
        let (m, k) = ([1.0, 2.0, 3.0], [2.0, 8.0, 27.0]);
        let v = Mat::from_fn(3, 3, |i, j| match (i, j) {
            (0, 0) | (1, 1) | (0, 2) | (1, 2) => 1.0,
            _ => 0.0,
        });
        let mass = |x: &[f64], y: &mut [f64]| (0..3).for_each(|i| y[i] = m[i] * x[i]);
        let stiff = |x: &[f64], y: &mut [f64]| (0..3).for_each(|i| y[i] = k[i] * x[i]);
        let (mu, q) = ritz_basis(&v, &mass, &stiff).expect("Ritz");
        assert_eq!(q.ncols(), 2, "the dependent column is dropped");
        assert!(
            (mu[0] - 2.0).abs() < 1e-14 && (mu[1] - 4.0).abs() < 1e-14,
            "{mu:?}"
        );
        for j in 0..2 {
            let norm: f64 = (0..3).map(|i| m[i] * q[(i, j)] * q[(i, j)]).sum();
            assert!(
                (norm - 1.0).abs() < 1e-14,
                "column {j} M-normalized: {norm}"
            );
        }
    }

    #[test]
    fn a_column_reduced_to_round_off_is_dropped_not_rescaled() {
        // Columns e0, e1 and a round-off remnant (1e-15 along e2): the span
        // is e0, e1, the remnant is not a direction of it.
        let (m, k) = ([1.0, 2.0, 3.0], [2.0, 8.0, 27.0]);
        let v = Mat::from_fn(3, 3, |i, j| match (i, j) {
            (0, 0) | (1, 1) => 1.0,
            (2, 2) => 1e-15,
            _ => 0.0,
        });
        let mass = |x: &[f64], y: &mut [f64]| (0..3).for_each(|i| y[i] = m[i] * x[i]);
        let stiff = |x: &[f64], y: &mut [f64]| (0..3).for_each(|i| y[i] = k[i] * x[i]);
        let (mu, q) = ritz_basis(&v, &mass, &stiff).expect("Ritz");
        assert_eq!(q.ncols(), 2, "the remnant is dropped: {mu:?}");
    }
}
