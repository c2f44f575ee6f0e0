//! How many eigenvalues of a symmetric pencil lie below a shift: the
//! certificate that an iterative eigensolver skipped none.
//!
//! Sylvester's law of inertia: with A = K − σM = P L D Lᵀ Pᵀ (L unit lower
//! triangular, P a fill-reducing permutation) a congruence, A and D have
//! the same count of negative values, and for M positive definite the
//! negative eigenvalues of A are exactly the eigenvalues λ < σ of
//! K x = λ M x. D comes from faer's simplicial sparse LDLᵀ (no pivoting;
//! the symbolic analysis and ordering are those of faer's Cholesky).
//! σ must not be an eigenvalue: a zero pivot is reported, and the caller
//! moves the shift.

use super::EigenFailure;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SparseColMatRef;
use faer::{Par, Side};

/// The number of negative pivots of the LDLᵀ factorization of the
/// symmetric matrix `a` (its lower triangle is read): its count of
/// negative eigenvalues.
pub fn negative_eigenvalues(a: SparseColMatRef<'_, usize, f64>) -> Result<usize, EigenFailure> {
    let symbolic = factorize_symbolic_cholesky(
        a.symbolic(),
        Side::Lower,
        SymmetricOrdering::Amd,
        CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SIMPLICIAL,
            ..Default::default()
        },
    )
    .map_err(|_| EigenFailure::Factorization)?;
    let mut values = vec![0.0f64; symbolic.len_val()];
    let mut mem = MemBuffer::new(
        symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()),
    );
    symbolic
        .factorize_numeric_ldlt(
            &mut values,
            a,
            Side::Lower,
            LdltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        )
        .map_err(|_| EigenFailure::Factorization)?;
    let SymbolicCholeskyRaw::Simplicial(s) = symbolic.raw() else {
        return Err(EigenFailure::Factorization);
    };
    // Each column of the simplicial factor starts with its diagonal: D_jj.
    let (col_ptr, row_idx) = (s.col_ptr(), s.row_idx());
    let mut negative = 0;
    for (j, &p) in col_ptr.iter().take(a.nrows()).enumerate() {
        if row_idx[p] != j {
            return Err(EigenFailure::Factorization);
        }
        let d = values[p];
        if !d.is_finite() || d == 0.0 {
            return Err(EigenFailure::Factorization);
        }
        if d < 0.0 {
            negative += 1;
        }
    }
    Ok(negative)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::sparse::Triplets;
    use crate::linalg::Scatter;

    /// A free chain of n unit masses and unit springs has the eigenvalues
    /// 2(1 − cos(jπ/n)), j = 0…n−1; the count below σ is the number of
    /// them below σ (σ = 1 would make the first pivot exactly zero).
    #[test]
    fn counts_the_chain_eigenvalues_below_a_shift() {
        let n = 50;
        let exact: Vec<f64> = (0..n)
            .map(|j| 2.0 * (1.0 - (std::f64::consts::PI * j as f64 / n as f64).cos()))
            .collect();
        for sigma in [-0.5, 0.01, 0.3, 1.1, 2.5, 3.9, 4.5] {
            let mut a = Triplets::new(n, n);
            for i in 0..n - 1 {
                a.add(i, i, 1.0);
                a.add(i + 1, i + 1, 1.0);
                a.add(i, i + 1, -1.0);
                a.add(i + 1, i, -1.0);
            }
            for i in 0..n {
                a.add(i, i, -sigma);
            }
            let count = negative_eigenvalues(a.to_sparse().as_ref()).expect("factors");
            let expected = exact.iter().filter(|&&l| l < sigma).count();
            assert_eq!(count, expected, "σ = {sigma}");
        }
    }
}
