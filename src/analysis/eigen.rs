//! Symmetric-definite generalized eigenproblem K x = λ M x.
//!
//! faer has no generalized symmetric solver, so M = L Lᵀ (Cholesky),
//! C = L⁻¹ K L⁻ᵀ, C y = λ y (self-adjoint eigen), x = L⁻ᵀ y. The vectors come
//! out mass-normalized (xᵀ M x = 1). Eigenvalues ascend.

use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par, Side};

/// Eigenvalues (ascending) and mass-normalized eigenvectors (columns).
#[derive(Debug, Clone)]
pub struct GeneralizedEigen {
    pub values: Vec<f64>,
    pub vectors: Mat<f64>,
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

/// Solve K x = λ M x for symmetric K and symmetric positive definite M.
pub fn solve_generalized(k: &Mat<f64>, m: &Mat<f64>) -> Result<GeneralizedEigen, EigenFailure> {
    let n = k.nrows();
    if n == 0 {
        return Ok(GeneralizedEigen {
            values: Vec::new(),
            vectors: Mat::zeros(0, 0),
        });
    }
    let p = par(n);
    let llt = match m.llt(Side::Lower) {
        Ok(f) => f,
        Err(_) => {
            return Err(EigenFailure::SingularMass {
                direction: null_direction(m),
            })
        }
    };
    let l = llt.L();
    // Reject a numerically singular factor too (tiny pivots from zero inertia).
    let dmax = (0..n).map(|i| l[(i, i)].abs()).fold(0.0, f64::max);
    if (0..n).any(|i| l[(i, i)].abs() <= 1e-7 * dmax) {
        return Err(EigenFailure::SingularMass {
            direction: null_direction(m),
        });
    }
    // W = L⁻¹ K, then C = L⁻¹ Wᵀ = L⁻¹ K L⁻ᵀ.
    let mut w = k.clone();
    solve_lower_triangular_in_place(l, w.as_mut(), p);
    let mut c = w.transpose().to_owned();
    solve_lower_triangular_in_place(l, c.as_mut(), p);
    let c = Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]));
    let (values, mut vectors) = symmetric_eigen_qr(&c, p)?;
    solve_upper_triangular_in_place(l.transpose(), vectors.as_mut(), p);
    Ok(GeneralizedEigen { values, vectors })
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
