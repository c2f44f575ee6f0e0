//! The shifted matrix K − σM of [`super`]'s shift-invert Lanczos, on the
//! pattern of K and M together (repeated entries summed once), and its
//! factor [SI: λ = ω² in rad²/s²].
//!
//! One fill-reducing (AMD) analysis of the pattern serves every shift. A
//! shift below the spectrum makes K − σM positive definite and an LLᵀ
//! factors it. On a fine mesh of a stiff beam the factor's round-off,
//! of order ε times entries EI/Le³, exceeds σM near the lowest modes and
//! the LLᵀ breaks down: refined runs (where the factor is a preconditioner
//! and Lanczos' operator only) then take an LDLᵀ without pivoting on the
//! same analysis, at a Cholesky's cost; otherwise, and if that breaks down
//! too, faer's sparse LU (a pre-stressed state with an unstable direction).

use super::super::inertia::negative_eigenvalues;
use super::EigenFailure;
use crate::linalg::sparse::on_common_pattern;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LdltRef, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::SparseColMat;
use faer::sparse::SparseColMatRef;
use faer::{Conj, MatMut, Side};
use rayon::prelude::*;
use std::borrow::Cow;
use std::sync::Arc;

/// Columns per task of [`Shifted::solve_block`].
const SOLVE_COLUMNS: usize = 4;

/// The shifted matrix K − σM on a fixed pattern, factored.
pub(super) struct Shifted<'a> {
    /// K and M on their common pattern: the caller's own matrices where
    /// their patterns agree (a beam's K and M do), merged copies otherwise.
    k: Cow<'a, SparseColMat<usize, f64>>,
    m: Cow<'a, SparseColMat<usize, f64>>,
    /// The fill-reducing analysis of the pattern, made once and shared
    /// by every shift's LLᵀ and LDLᵀ.
    analysis: Option<Arc<SymbolicCholesky<usize>>>,
    /// Refined only: where Cholesky fails, an LDLᵀ before LU (see
    /// [`Shifted::factor`]).
    symmetric_fallback: bool,
    factor: Factor,
}

enum Factor {
    None,
    Cholesky(Box<Cholesky>),
    Lu(Box<Lu<usize, f64>>),
}

/// A sparse LLᵀ, or LDLᵀ without pivoting, of K − σM.
struct Cholesky {
    symbolic: Arc<SymbolicCholesky<usize>>,
    values: Vec<f64>,
    ldlt: bool,
}

impl Cholesky {
    /// LLᵀ (or LDLᵀ) of `a` on `symbolic`; None where it breaks down (a
    /// non-positive pivot for LLᵀ, a zero or non-finite one for LDLᵀ).
    fn new(
        symbolic: Arc<SymbolicCholesky<usize>>,
        a: SparseColMatRef<'_, usize, f64>,
        ldlt: bool,
    ) -> Option<Self> {
        let par = faer::get_global_parallelism();
        let mut values = vec![0.0f64; symbolic.len_val()];
        let scratch = if ldlt {
            symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default())
        } else {
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default())
        };
        let mut mem = MemBuffer::try_new(scratch).ok()?;
        let stack = MemStack::new(&mut mem);
        let ok = if ldlt {
            symbolic
                .factorize_numeric_ldlt(
                    &mut values,
                    a,
                    Side::Lower,
                    LdltRegularization::default(),
                    par,
                    stack,
                    Default::default(),
                )
                .is_ok()
        } else {
            symbolic
                .factorize_numeric_llt(
                    &mut values,
                    a,
                    Side::Lower,
                    LltRegularization::default(),
                    par,
                    stack,
                    Default::default(),
                )
                .is_ok()
        };
        (ok && values.iter().all(|v| v.is_finite())).then_some(Cholesky {
            symbolic,
            values,
            ldlt,
        })
    }

    fn solve_in_place(&self, x: MatMut<'_, f64>) {
        let par = faer::get_global_parallelism();
        let mut mem = MemBuffer::new(self.symbolic.solve_in_place_scratch::<f64>(x.ncols(), par));
        let stack = MemStack::new(&mut mem);
        if self.ldlt {
            LdltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
                Conj::No,
                x,
                par,
                stack,
            );
        } else {
            LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
                Conj::No,
                x,
                par,
                stack,
            );
        }
    }
}

impl<'a> Shifted<'a> {
    /// K and M (compressed, each column's rows sorted) on their common
    /// pattern; `symmetric_fallback`: an LDLᵀ before LU where the Cholesky
    /// breaks down (refined runs).
    pub(super) fn new(
        k: &'a SparseColMat<usize, f64>,
        m: &'a SparseColMat<usize, f64>,
        symmetric_fallback: bool,
    ) -> Result<Self, EigenFailure> {
        let same = {
            let (a, b) = (k.symbolic(), m.symbolic());
            a.col_ptr() == b.col_ptr() && a.row_idx() == b.row_idx()
        };
        let (k, m) = if same {
            (Cow::Borrowed(k), Cow::Borrowed(m))
        } else {
            let [kk, mm] = on_common_pattern(k, m);
            (Cow::Owned(kk), Cow::Owned(mm))
        };
        Ok(Shifted {
            k,
            m,
            analysis: None,
            symmetric_fallback,
            factor: Factor::None,
        })
    }

    /// K − σM on the common pattern.
    pub(super) fn matrix(&self, sigma: f64) -> Result<SparseColMat<usize, f64>, EigenFailure> {
        let values: Vec<f64> = self
            .k
            .val()
            .iter()
            .zip(self.m.val())
            .map(|(k, m)| k - sigma * m)
            .collect();
        let symbolic = self
            .k
            .symbolic()
            .to_owned()
            .map_err(|_| EigenFailure::Factorization)?;
        Ok(SparseColMat::new(symbolic, values))
    }

    /// M on the common pattern.
    pub(super) fn mass(&self) -> &SparseColMat<usize, f64> {
        &self.m
    }

    /// K on the common pattern.
    pub(super) fn stiffness(&self) -> &SparseColMat<usize, f64> {
        &self.k
    }

    /// How many eigenvalues of the pencil lie below σ (Sylvester's
    /// inertia of K − σM); σ is nudged up when it hits one exactly.
    pub(super) fn count_below(&self, sigma: f64) -> Result<usize, EigenFailure> {
        let mut s = sigma;
        for _ in 0..4 {
            match negative_eigenvalues(self.matrix(s)?.as_ref()) {
                Ok(count) => return Ok(count),
                Err(_) => s += 1e-9 * s.abs().max(f64::MIN_POSITIVE),
            }
        }
        Err(EigenFailure::Factorization)
    }

    pub(super) fn factor(&mut self, sigma: f64) -> Result<(), EigenFailure> {
        let a = self.matrix(sigma)?;
        if self.analysis.is_none() {
            self.analysis = Some(Arc::new(
                factorize_symbolic_cholesky(
                    a.symbolic(),
                    Side::Lower,
                    SymmetricOrdering::Amd,
                    Default::default(),
                )
                .map_err(|_| EigenFailure::Factorization)?,
            ));
        }
        let analysis = self.analysis.clone().expect("symbolic factorization");
        // Refined, the factor is a preconditioner and Lanczos' operator
        // only (the precise products set the accuracy); where round-off
        // of order ε|K| makes K − σM indefinite just above the shift, an
        // LDLᵀ on the same analysis costs a Cholesky's, LU about four.
        let cholesky = Cholesky::new(analysis.clone(), a.as_ref(), false).or_else(|| {
            self.symmetric_fallback
                .then(|| Cholesky::new(analysis, a.as_ref(), true))
                .flatten()
        });
        self.factor = match cholesky {
            Some(c) => Factor::Cholesky(Box::new(c)),
            None => Self::lu(a.as_ref())?,
        };
        Ok(())
    }

    fn lu(a: SparseColMatRef<'_, usize, f64>) -> Result<Factor, EigenFailure> {
        let s = SymbolicLu::try_new(a.symbolic()).map_err(|_| EigenFailure::Factorization)?;
        Ok(Factor::Lu(Box::new(
            Lu::try_new_with_symbolic(s, a).map_err(|_| EigenFailure::Factorization)?,
        )))
    }

    /// Solves for every column of `x` in place.
    /// Solves for every column of `x` in place, [`SOLVE_COLUMNS`] columns
    /// at a time on the pool's threads (the columns are independent, and
    /// fixed groups give the same result however many threads share them).
    pub(super) fn solve_block(&self, x: MatMut<'_, f64>) {
        x.par_col_chunks_mut(SOLVE_COLUMNS)
            .for_each(|x| match &self.factor {
                Factor::Cholesky(l) => l.solve_in_place(x),
                Factor::Lu(l) => l.solve_in_place(x),
                Factor::None => unreachable!("solve before factor"),
            });
    }

    pub(super) fn solve(&self, x: &mut [f64]) {
        let n = x.len();
        let col = MatMut::from_column_major_slice_mut(x, n, 1);
        match &self.factor {
            Factor::Cholesky(l) => l.solve_in_place(col),
            Factor::Lu(l) => l.solve_in_place(col),
            Factor::None => unreachable!("solve before factor"),
        }
    }
}
