//! The dense symmetric-definite generalized eigenproblem K x = λ M x, for
//! problems small enough to hold as dense matrices [SI: λ = ω² in rad²/s²
//! for a stiffness K and a mass M].
//!
//! Jacobi scaling first: D = diag(M)^-½, so the scaled mass D M D has a unit
//! diagonal whatever the units of the coordinates (positions in m, slopes,
//! angles in rad) and the size of the model (µm or km). Then faer's
//! Cholesky D M D = L Lᵀ, C = L⁻¹ (D K D) L⁻ᵀ, faer's self-adjoint
//! eigensolver on C with the QR algorithm (faer switches to divide and
//! conquer from n = 128, which lost the zero cluster of a free beam in an
//! earlier release), and x = D L⁻ᵀ y, mass-normalized (xᵀ M x = 1).
//!
//! M counts as singular when a diagonal entry is not positive or a pivot of
//! the scaled factor falls below [`SINGULAR_PIVOT`]: a test on a unit-diagonal
//! matrix, so independent of units, size and mass scale.

use super::EigenFailure;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd::{self, ComputeEigenvectors, SelfAdjointEvdParams};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par};

/// A squared Cholesky pivot of the Jacobi-scaled mass below this marks M as
/// singular (a unit-diagonal matrix: its smallest eigenvalue is at most
/// this).
pub const SINGULAR_PIVOT: f64 = 1e-12;

/// The lowest eigenvalues (ascending) and their mass-normalized
/// eigenvectors (columns, one per value).
#[derive(Debug, Clone)]
pub struct GeneralizedEigen {
    pub values: Vec<f64>,
    pub vectors: Mat<f64>,
    /// The factor of M the solve used, for solves with M afterwards.
    pub mass: MassFactor,
}

/// M = D⁻¹ L Lᵀ D⁻¹ (D = diag(M)^-½, L the Cholesky factor of D M D).
#[derive(Debug, Clone)]
pub struct MassFactor {
    l: Mat<f64>,
    d: Vec<f64>,
}

impl MassFactor {
    /// X ← M⁻¹ X = D L⁻ᵀ L⁻¹ D X.
    pub fn solve_in_place(&self, x: &mut Mat<f64>) {
        let p = par(self.d.len());
        let scale = |x: &mut Mat<f64>| {
            for j in 0..x.ncols() {
                for (v, di) in x.col_as_slice_mut(j).iter_mut().zip(&self.d) {
                    *v *= di;
                }
            }
        };
        scale(x);
        solve_lower_triangular_in_place(self.l.as_ref(), x.as_mut(), p);
        solve_upper_triangular_in_place(self.l.transpose(), x.as_mut(), p);
        scale(x);
    }
}

/// D = diag(M)^-½; a diagonal entry that is not positive is a coordinate
/// without mass (the singular direction).
pub fn jacobi_scaling(m: &Mat<f64>) -> Result<Vec<f64>, EigenFailure> {
    let n = m.nrows();
    let mut d = vec![0.0; n];
    for (i, di) in d.iter_mut().enumerate() {
        let mii = m[(i, i)];
        if !(mii > 0.0 && mii.is_finite()) {
            let mut direction = vec![0.0; n];
            direction[i] = 1.0;
            return Err(EigenFailure::SingularMass { direction });
        }
        *di = 1.0 / mii.sqrt();
    }
    Ok(d)
}

fn par(n: usize) -> Par {
    if n >= 256 {
        Par::rayon(0)
    } else {
        Par::Seq
    }
}

/// Solve K x = λ M x for symmetric K and symmetric positive definite M: the
/// lowest `wanted` eigenvalues with M-normalized vectors.
pub fn solve_generalized(
    k: &Mat<f64>,
    m: &Mat<f64>,
    wanted: usize,
) -> Result<GeneralizedEigen, EigenFailure> {
    let n = k.nrows();
    let wanted = wanted.min(n);
    let d = jacobi_scaling(m)?;
    let p = par(n);
    let scaled_m = Mat::from_fn(n, n, |i, j| d[i] * m[(i, j)] * d[j]);
    let singular = || EigenFailure::SingularMass {
        direction: lowest_direction(&scaled_m, &d),
    };
    let (factor, c) = {
        let factor = cholesky_lower(&scaled_m, p).ok_or_else(singular)?;
        // W = L⁻¹ D K D, then C = L⁻¹ Wᵀ = L⁻¹ (DKD) L⁻ᵀ, symmetrized.
        let mut w = Mat::from_fn(n, n, |i, j| d[i] * k[(i, j)] * d[j]);
        solve_lower_triangular_in_place(factor.as_ref(), w.as_mut(), p);
        let mut c = w.transpose().to_owned();
        solve_lower_triangular_in_place(factor.as_ref(), c.as_mut(), p);
        let c = Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]));
        (factor, c)
    };
    let l = factor.as_ref();
    if (0..n).any(|i| l[(i, i)] * l[(i, i)] <= SINGULAR_PIVOT) {
        return Err(singular());
    }
    let (values, vectors) = symmetric_eigen_qr(&c, p)?;
    let mut vectors = vectors.subcols(0, wanted).to_owned();
    solve_upper_triangular_in_place(l.transpose(), vectors.as_mut(), p);
    for j in 0..wanted {
        for (i, &di) in d.iter().enumerate() {
            vectors[(i, j)] *= di;
        }
    }
    Ok(GeneralizedEigen {
        values: values[..wanted].to_vec(),
        vectors,
        mass: MassFactor { l: factor, d },
    })
}

/// The eigenvalues of the pencil (K, M), ascending, without vectors: the
/// same Jacobi scaling and Cholesky reduction as [`solve_generalized`],
/// then the symmetric eigenvalues alone (a few times less work on a dense
/// pencil of tens of coordinates).
pub fn generalized_eigenvalues(k: &Mat<f64>, m: &Mat<f64>) -> Result<Vec<f64>, EigenFailure> {
    let n = k.nrows();
    let d = jacobi_scaling(m)?;
    let p = par(n);
    let scaled_m = Mat::from_fn(n, n, |i, j| d[i] * m[(i, j)] * d[j]);
    let singular = || EigenFailure::SingularMass {
        direction: lowest_direction(&scaled_m, &d),
    };
    let factor = cholesky_lower(&scaled_m, p).ok_or_else(singular)?;
    let l = factor.as_ref();
    if (0..n).any(|i| l[(i, i)] * l[(i, i)] <= SINGULAR_PIVOT) {
        return Err(singular());
    }
    let mut w = Mat::from_fn(n, n, |i, j| d[i] * k[(i, j)] * d[j]);
    solve_lower_triangular_in_place(l, w.as_mut(), p);
    let mut c = w.transpose().to_owned();
    solve_lower_triangular_in_place(l, c.as_mut(), p);
    // nalgebra's eigenvalues-only path (faer's spends as much on the QR
    // sweeps at this size as with vectors).
    let c = nalgebra::DMatrix::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]));
    let mut values: Vec<f64> = c.symmetric_eigenvalues().iter().copied().collect();
    if values.iter().any(|v| !v.is_finite()) {
        return Err(EigenFailure::NoConvergence);
    }
    values.sort_by(f64::total_cmp);
    Ok(values)
}

/// Eigenvalues (ascending) and M-normalized vectors of a tiny pencil
/// (a few rigid-motion candidates), by nalgebra's Cholesky and symmetric
/// eigensolver: faer's blocked kernels cost more in dispatch than the work
/// at this size. Same Jacobi scaling and singular test as
/// [`solve_generalized`].
pub fn solve_generalized_small(
    k: &Mat<f64>,
    m: &Mat<f64>,
) -> Result<(Vec<f64>, Mat<f64>), EigenFailure> {
    let n = k.nrows();
    let d = jacobi_scaling(m)?;
    let ms = nalgebra::DMatrix::from_fn(n, n, |i, j| d[i] * m[(i, j)] * d[j]);
    let ks = nalgebra::DMatrix::from_fn(n, n, |i, j| d[i] * k[(i, j)] * d[j]);
    let singular = |ms: &nalgebra::DMatrix<f64>| {
        let e = nalgebra::SymmetricEigen::new(ms.clone());
        let i = e.eigenvalues.imin();
        EigenFailure::SingularMass {
            direction: (0..n).map(|r| d[r] * e.eigenvectors[(r, i)]).collect(),
        }
    };
    let Some(chol) = nalgebra::Cholesky::new(ms.clone()) else {
        return Err(singular(&ms));
    };
    let l = chol.l();
    if (0..n).any(|i| l[(i, i)] * l[(i, i)] <= SINGULAR_PIVOT) {
        return Err(singular(&ms));
    }
    let w = l
        .solve_lower_triangular(&ks)
        .ok_or(EigenFailure::NoConvergence)?;
    let c = l
        .solve_lower_triangular(&w.transpose())
        .ok_or(EigenFailure::NoConvergence)?;
    let c = (&c + c.transpose()) * 0.5;
    let e = nalgebra::SymmetricEigen::new(c);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| e.eigenvalues[a].total_cmp(&e.eigenvalues[b]));
    let y = nalgebra::DMatrix::from_fn(n, n, |r, c| e.eigenvectors[(r, order[c])]);
    let x = l
        .transpose()
        .solve_upper_triangular(&y)
        .ok_or(EigenFailure::NoConvergence)?;
    Ok((
        order.iter().map(|&i| e.eigenvalues[i]).collect(),
        Mat::from_fn(n, n, |r, c| d[r] * x[(r, c)]),
    ))
}

/// The lower Cholesky factor L of a symmetric positive definite matrix
/// (lower triangle read), L Lᵀ = A, with an explicit parallelism (small
/// problems run sequentially: a thread pool costs more than the work);
/// `None` if A is not positive definite.
pub fn cholesky_lower(a: &Mat<f64>, par: Par) -> Option<Mat<f64>> {
    use faer::linalg::cholesky::llt::factor::{cholesky_in_place, cholesky_in_place_scratch};
    let n = a.nrows();
    let mut l = a.clone();
    let mut buf = MemBuffer::new(cholesky_in_place_scratch::<f64>(n, par, Default::default()));
    cholesky_in_place(
        l.as_mut(),
        Default::default(),
        par,
        MemStack::new(&mut buf),
        Default::default(),
    )
    .ok()?;
    for j in 0..n {
        for i in 0..j {
            l[(i, j)] = 0.0;
        }
    }
    Some(l)
}

/// Eigenvalues (ascending) and eigenvectors of a symmetric matrix by
/// faer's tridiagonal QR algorithm (divide and conquer disabled).
pub fn symmetric_eigen_qr(c: &Mat<f64>, par: Par) -> Result<(Vec<f64>, Mat<f64>), EigenFailure> {
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

/// D v for the eigenvector v of the smallest eigenvalue of the scaled mass.
fn lowest_direction(scaled_m: &Mat<f64>, d: &[f64]) -> Vec<f64> {
    match symmetric_eigen_qr(scaled_m, Par::Seq) {
        Ok((_, u)) => d.iter().enumerate().map(|(i, di)| di * u[(i, 0)]).collect(),
        Err(_) => vec![0.0; d.len()],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain of springs k between masses m: ω² = 2k/m (1 − cos(jπ/(n+1))),
    /// with fixed ends; scaled by `size` in mass to check scale freedom.
    #[test]
    fn fixed_chain_frequencies_at_any_mass_scale() {
        let n = 12;
        for mass in [1e-18, 1.0, 1e12] {
            let stiffness = 3.0;
            let k = Mat::from_fn(n, n, |i, j| match i.abs_diff(j) {
                0 => 2.0 * stiffness,
                1 => -stiffness,
                _ => 0.0,
            });
            let m = Mat::from_fn(n, n, |i, j| if i == j { mass } else { 0.0 });
            let e = solve_generalized(&k, &m, 4).expect("positive definite");
            for (j, &v) in e.values.iter().enumerate() {
                let exact = 2.0 * stiffness / mass
                    * (1.0 - (std::f64::consts::PI * (j + 1) as f64 / (n + 1) as f64).cos());
                assert!(
                    (v - exact).abs() <= 1e-13 * exact,
                    "mass {mass:e}: ω²_{j} = {v:e}, chain formula {exact:e}"
                );
                let norm: f64 = (0..n).map(|i| e.vectors[(i, j)].powi(2) * mass).sum();
                assert!((norm - 1.0).abs() < 1e-13, "xᵀMx = {norm}");
            }
            // The values alone, shifted below zero (an indefinite pencil,
            // as a statics tangent past buckling): the chain formula again.
            let shift = 2.5 * stiffness / mass * (1.0 - (std::f64::consts::PI / 13.0).cos());
            let ks = Mat::from_fn(n, n, |i, j| k[(i, j)] - shift * m[(i, j)]);
            let values = generalized_eigenvalues(&ks, &m).expect("definite mass");
            for (j, &v) in values.iter().enumerate() {
                let exact = 2.0 * stiffness / mass
                    * (1.0 - (std::f64::consts::PI * (j + 1) as f64 / (n + 1) as f64).cos())
                    - shift;
                assert!(
                    (v - exact).abs() <= 1e-12 * (exact.abs() + shift),
                    "mass {mass:e}: shifted ω²_{j} = {v:e}, chain formula {exact:e}"
                );
            }
        }
    }

    #[test]
    fn a_massless_coordinate_is_named() {
        let k = Mat::<f64>::identity(3, 3);
        let m = Mat::from_fn(3, 3, |i, j| if i == j && i != 1 { 1.0 } else { 0.0 });
        match solve_generalized(&k, &m, 3) {
            Err(EigenFailure::SingularMass { direction }) => {
                assert_eq!(direction, vec![0.0, 1.0, 0.0], "coordinate 1 has no mass")
            }
            other => panic!("expected a singular mass, got {other:?}"),
        }
    }
}
