//! The lowest modes of a large sparse pencil K x = λ M x by shift-invert
//! Lanczos on faer's sparse factorizations [SI: λ = ω² in rad²/s²].
//!
//! The operator is S = (K − σM)⁻¹M, self-adjoint in the M inner product;
//! its eigenvalues θ = 1/(λ − σ) are largest for the λ nearest the shift.
//! K − σM is factored by faer's sparse Cholesky (its symbolic analysis and
//! fill-reducing ordering computed once for the pattern of K and M together
//! and reused for every shift), when refined by an LDLᵀ on the same
//! analysis where round-off breaks the Cholesky, or by faer's sparse LU
//! when it is indefinite (a pre-stressed state with an unstable
//! direction); see [`shifted`].
//!
//! The shift is negative and scaled to the model: starting from
//! σ = −√ε·maxᵢ Kᵢᵢ/Mᵢᵢ (refined runs: from 16ε of that scale, near
//! what the factor resolves at all), one solve u = S b gives the Rayleigh quotient
//! ρ = uᵀKu/uᵀMu (formed as uᵀMb/uᵀMu + σ, free of cancellation in K) ≥ λ₁,
//! after four such inverse-iteration steps with the same factor; while
//! |σ| > 1.5ρ the shift moves to −ρ and K − σM is factored again (a shift
//! far below λ₁ would make the low θ = 1/(λ − σ) a cluster). A model of 25 µm and one of 25 m,
//! a stiff beam and a cable with h/L = 1e-5, all end with σ within a small
//! factor of their own lowest ω². A negative σ keeps K − σM definite when K
//! is semi-definite, so the zero modes need no special care in the factor.
//!
//! Known zero modes (M-orthonormal columns Z) are deflated: every Krylov
//! vector is made M-orthogonal to them, so the iteration sees only the
//! elastic spectrum. Full re-orthogonalization in the M inner product:
//! after the three-term recurrence, classical Gram–Schmidt against the
//! whole basis at once (two matrix–vector products with the basis and one
//! product M w), repeated only while a pass removes more than half of w;
//! the Ritz problem is solved by
//! [`super::dense::symmetric_eigen_qr`]. The basis grows until the wanted
//! Ritz pairs have residual estimates |βⱼ sⱼᵢ| ≤ tolerance·|θᵢ| (a short
//! Lanczos, no restarts: shift-invert converges in a few steps per mode; an
//! invariant subspace found early is left for a fresh M-orthogonal vector).

mod refine;
mod shifted;

use super::dense::symmetric_eigen_qr;
use super::sparse::{diagonal, mul_symmetric, Triplets, ROWS_PER_TASK};
use super::vector::{axpy, dot_long as dot};
use super::EigenFailure;
use faer::linalg::matmul::matmul;
use faer::sparse::SparseColMat;
use faer::{Accum, Mat, MatMut, MatRef, Par};
use rayon::prelude::*;
use refine::{refine, Refinement};
use shifted::Shifted;

/// Refined runs: the first shift in units of ε·maxᵢ Kᵢᵢ/Mᵢᵢ.
const START_RESOLUTIONS: f64 = 16.0;

/// Inverse-iteration steps per trial shift.
const INVERSE_STEPS: usize = 4;

/// Ritz values are checked for convergence every this many Lanczos steps
/// (each check is a dense eigen-solve of the tridiagonal matrix).
const CHECK_EVERY: usize = 4;

/// Settings of [`lowest_modes`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KrylovSettings {
    /// Number of (non-deflated) modes wanted.
    pub wanted: usize,
    /// Relative residual estimate at which a Ritz pair counts as converged.
    pub tolerance: f64,
    /// Largest Krylov basis before giving up.
    pub max_basis: usize,
}

impl KrylovSettings {
    pub fn new(wanted: usize) -> Self {
        KrylovSettings {
            wanted,
            tolerance: 1e-11,
            max_basis: 400,
        }
    }
}

/// Products K x with several vectors x at once, formed more precisely
/// than the assembled K allows (e.g. from strain variations): the
/// refinement's residuals and Rayleigh–Ritz projections use them.
pub type StiffnessProducts<'a> = dyn Fn(&[&[f64]], &mut [&mut [f64]]) + 'a;

/// Modes computed beside the wanted ones when refining: the gap above the
/// highest wanted mode, and room for the block iteration.
const GUARD: usize = 4;

/// Largest number of refinement steps (block Davidson with the factor as
/// preconditioner; two or three are typical).
const REFINE_STEPS: usize = 8;

/// Lowest eigenpairs of the pencil outside the deflated space.
#[derive(Debug, Clone)]
pub struct KrylovModes {
    /// Eigenvalues λ, ascending.
    pub values: Vec<f64>,
    /// M-normalized vectors, one column per value.
    pub vectors: Mat<f64>,
    /// The final shift σ.
    pub shift: f64,
    /// Krylov basis size used.
    pub steps: usize,
    /// Numeric factorizations of K − σM.
    pub factorizations: usize,
    /// Refined only: a bound on |θ − λ| per mode from the residual of the
    /// precise products, θ the returned value (empty otherwise).
    pub residuals: Vec<f64>,
    /// Refined only: the next eigenvalues above the wanted ones (their
    /// gap bounds the wanted ones' errors).
    pub guard_values: Vec<f64>,
    /// Whether Sylvester's count confirmed that no eigenvalue below the
    /// highest one returned was skipped (refined: only when the factor's
    /// own perturbation of the pencil, measured on the refined modes, is
    /// far below the gap the count is taken in).
    pub certified: bool,
    /// Refined only: the largest change of an eigenvalue from the factor's
    /// pencil to the refined one [SI: λ units].
    pub perturbation: f64,
}

/// The pencil, its shifted factor and the deflation space.
struct Operator<'a> {
    shifted: Shifted<'a>,
    /// Z and M Z (M-orthonormal deflation vectors).
    z: Vec<Vec<f64>>,
    mz: Vec<Vec<f64>>,
    scratch: Vec<f64>,
}

impl Operator<'_> {
    /// M (on the factor's pattern).
    fn m(&self) -> &SparseColMat<usize, f64> {
        self.shifted.mass()
    }

    /// Adds M-orthonormal vectors to the deflated space.
    fn deflate_also(&mut self, vectors: &Mat<f64>) {
        for c in 0..vectors.ncols() {
            let z = vectors.col_as_slice(c).to_vec();
            let mut mz = vec![0.0; z.len()];
            mul_symmetric(self.shifted.mass(), &z, &mut mz);
            self.z.push(z);
            self.mz.push(mz);
        }
    }

    /// x ← x − Z (MZ)ᵀ x.
    fn deflate(&self, x: &mut [f64]) {
        for (z, mz) in self.z.iter().zip(&self.mz) {
            let c = dot(mz, x);
            axpy(-c, z, x);
        }
    }

    fn m_dot(&mut self, x: &[f64], y: &[f64]) -> f64 {
        mul_symmetric(self.shifted.mass(), x, &mut self.scratch);
        dot(&self.scratch, y)
    }
}

/// The lowest `settings.wanted` eigenpairs of (K, M) that are M-orthogonal
/// to the columns of `deflate` (themselves M-orthonormal eigenvectors).
pub fn lowest_modes(
    k: &Triplets,
    m: &Triplets,
    deflate: &[Vec<f64>],
    settings: &KrylovSettings,
) -> Result<KrylovModes, EigenFailure> {
    modes(&k.to_sparse(), &m.to_sparse(), deflate, settings, None)
}

/// [`lowest_modes`], then refined with precise products K x: the factor
/// of K − σM carries a backward error of ε times its entries, which on a
/// fine mesh of a stiff beam (entries EI/Le³, 3.5e17 at 100,000
/// elements of 1 m of steel) moves the lowest eigenvalues by more than
/// themselves. Lanczos on that factor gives a subspace; block Davidson
/// steps (Rayleigh–Ritz with the precise products on the modes and their
/// preconditioned residuals P⁻¹(Kx − θMx), P the factor) then converge to
/// the pencil's own modes, the factor's error acting only as a
/// preconditioner's. Residuals are returned in the M⁻¹ norm.
pub fn lowest_modes_refined(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    deflate: &[Vec<f64>],
    settings: &KrylovSettings,
    products: &StiffnessProducts,
) -> Result<KrylovModes, EigenFailure> {
    modes(k, m, deflate, settings, Some(products))
}

fn modes(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    deflate: &[Vec<f64>],
    settings: &KrylovSettings,
    products: Option<&StiffnessProducts>,
) -> Result<KrylovModes, EigenFailure> {
    let n = k.nrows();
    let available = n.saturating_sub(deflate.len());
    let wanted_out = settings.wanted.min(available);
    let wanted = if products.is_some() {
        (wanted_out + GUARD).min(available)
    } else {
        wanted_out
    };
    let shifted = Shifted::new(k, m, products.is_some())?;
    let md = diagonal(shifted.mass());
    if let Some(i) = md.iter().position(|&v| !(v > 0.0 && v.is_finite())) {
        let mut direction = vec![0.0; n];
        direction[i] = 1.0;
        return Err(EigenFailure::SingularMass { direction });
    }
    if wanted_out == 0 {
        return Ok(KrylovModes {
            values: Vec::new(),
            vectors: Mat::zeros(n, 0),
            shift: 0.0,
            steps: 0,
            factorizations: 0,
            residuals: Vec::new(),
            guard_values: Vec::new(),
            certified: true,
            perturbation: 0.0,
        });
    }
    let kd = diagonal(shifted.stiffness());
    let lmax = kd
        .iter()
        .zip(&md)
        .fold(0.0f64, |a, (k, m)| a.max((k / m).abs()));
    // Refined, the walk starts near the factor's own resolution, a few
    // ε·max Kᵢᵢ/Mᵢᵢ: no shift below it resolves more, and the block
    // iteration does the rest; otherwise at √ε of that scale.
    let start = if products.is_some() {
        START_RESOLUTIONS * f64::EPSILON
    } else {
        f64::EPSILON.sqrt()
    };
    let mut sigma = -start * lmax.max(f64::MIN_POSITIVE);
    let mz = deflate
        .iter()
        .map(|z| {
            let mut out = vec![0.0; n];
            mul_symmetric(shifted.mass(), z, &mut out);
            out
        })
        .collect();
    let mut op = Operator {
        shifted,
        z: deflate.to_vec(),
        mz,
        scratch: vec![0.0; n],
    };
    // A smooth start with every component present, deflated.
    let mut b: Vec<f64> = (0..n).map(|i| 1.0 + 0.5 * (1.7 * i as f64).sin()).collect();
    op.deflate(&mut b);
    let mut u = vec![0.0; n];
    // M b and M u kept beside b and u: one product with M per step.
    let (mut mb, mut mu) = (vec![0.0; n], vec![0.0; n]);
    mul_symmetric(op.shifted.mass(), &b, &mut mb);
    let mut factorizations = 0;
    // Refined, the shift need only be of the right order: the block
    // iteration, not Lanczos, sets the accuracy.
    let shifts = 12;
    for _ in 0..shifts {
        op.shifted.factor(sigma)?;
        factorizations += 1;
        // A few inverse-iteration steps with this factor, so that ρ
        // approaches the lowest ω² rather than the start vector's mean.
        let mut rho = f64::INFINITY;
        for _ in 0..INVERSE_STEPS {
            // u = S b.
            u.copy_from_slice(&mb);
            op.shifted.solve(&mut u);
            op.deflate(&mut u);
            mul_symmetric(op.shifted.mass(), &u, &mut mu);
            let (umb, umu) = (dot(&u, &mb), dot(&u, &mu));
            rho = umb / umu + sigma;
            let scale = 1.0 / umu.sqrt();
            b.iter_mut().zip(&u).for_each(|(bi, ui)| *bi = ui * scale);
            mb.iter_mut().zip(&mu).for_each(|(bi, ui)| *bi = ui * scale);
        }
        if let Some(products) = products {
            // The iterate's Rayleigh quotient from the precise products:
            // the factor's own estimate carries its error, which on a fine
            // mesh exceeds λ₁ and walks the shift far below it.
            let mut kb = vec![0.0; n];
            products(&[&b], &mut [&mut kb]);
            rho = dot(&b, &kb) / dot(&b, &mb);
        }
        if !(rho.is_finite()) || rho <= 0.0 || -sigma <= 1.5 * rho {
            break;
        }
        sigma = -rho;
    }
    // The walk's vectors go before the basis grows (a few MB each on a
    // large model; only u starts Lanczos).
    drop((b, mb, mu, md, kd));
    let (mut values, mut vectors, mut steps) = lanczos(&mut op, &u, wanted, sigma, settings)?;
    if let Some(products) = products {
        let refined = refine(
            &mut op,
            products,
            Refinement {
                wanted: wanted_out,
                deflated: deflate.len(),
                sigma,
                steps,
                factorizations,
            },
            values.clone(),
            vectors,
        )?;
        if refined.values.len() == wanted_out && refined.residuals.iter().all(|b| b.is_finite()) {
            return Ok(refined);
        }
        // The block lost directions, or a mode has no other mode to take a
        // gap to (a small problem whose wanted and guard modes fill it):
        // Lanczos' own result (computed again, the same: its vectors were
        // the refinement's start, not kept beside it on a large model),
        // certified below.
        (values, vectors, steps) = lanczos(&mut op, &u, wanted, sigma, settings)?;
    }
    let wanted = wanted_out;
    values.truncate(wanted);
    vectors = vectors.subcols(0, values.len()).to_owned();
    // The certificate: no eigenvalue below the highest one found was
    // skipped (a start vector poor in some mode, or the second copy of a
    // repeated value). Each missing one is searched for from a fresh start
    // M-orthogonal to everything found, and the lowest `wanted` kept.
    for round in 0..8 {
        let Some(&top) = values.last() else { break };
        let above = top + 1e-8 * top.abs().max(f64::MIN_POSITIVE);
        let zeros = if above > 0.0 { deflate.len() } else { 0 };
        let below = op.shifted.count_below(above)?;
        factorizations += 1;
        let missing = below.saturating_sub(values.len() + zeros);
        if missing == 0 {
            break;
        }
        op.deflate_also(&vectors);
        let fresh: Vec<f64> = (0..n)
            .map(|i| (2.3 * i as f64 + 0.7 * round as f64 + 0.1).sin())
            .collect();
        let more = missing.min(n.saturating_sub(op.z.len()));
        if more == 0 {
            break;
        }
        let (v2, x2, s2) = lanczos(&mut op, &fresh, more, sigma, settings)?;
        steps += s2;
        let mut all: Vec<(f64, Vec<f64>)> = (0..values.len())
            .map(|c| (values[c], vectors.col_as_slice(c).to_vec()))
            .chain((0..v2.len()).map(|c| (v2[c], x2.col_as_slice(c).to_vec())))
            .collect();
        all.sort_by(|a, b| a.0.total_cmp(&b.0));
        all.truncate(wanted);
        values = all.iter().map(|a| a.0).collect();
        vectors = Mat::from_fn(n, all.len(), |r, c| all[c].1[r]);
        // The deflated space returns to the known zero modes.
        op.z.truncate(deflate.len());
        op.mz.truncate(deflate.len());
    }
    Ok(KrylovModes {
        values,
        vectors,
        shift: sigma,
        steps,
        factorizations,
        residuals: Vec::new(),
        guard_values: Vec::new(),
        certified: true,
        perturbation: 0.0,
    })
}

/// The Lanczos basis V, in blocks of [`CHUNK`] columns, so that
/// re-orthogonalization is matrix–vector products reading the basis once,
/// not one dot product and one update per column, and the basis grows
/// without copying. M V is not kept (at 100,000 elements it was a third of
/// the run's peak memory): a pass takes M w instead.
struct Basis {
    n: usize,
    len: usize,
    v: Vec<Mat<f64>>,
}

/// Columns per block of [`Basis`].
const CHUNK: usize = 16;

impl Basis {
    fn new(n: usize) -> Self {
        Basis {
            n,
            len: 0,
            v: Vec::new(),
        }
    }

    fn len(&self) -> usize {
        self.len
    }

    /// Appends v.
    fn push(&mut self, v: &[f64]) {
        let (b, c) = (self.len / CHUNK, self.len % CHUNK);
        if c == 0 {
            self.v.push(Mat::zeros(self.n, CHUNK));
        }
        self.v[b].col_as_slice_mut(c).copy_from_slice(v);
        self.len += 1;
    }

    /// Column j.
    fn column(&self, j: usize) -> &[f64] {
        self.v[j / CHUNK].col_as_slice(j % CHUNK)
    }

    /// The used columns of block b.
    fn block(&self, b: usize) -> MatRef<'_, f64> {
        let cols = (self.len - b * CHUNK).min(CHUNK);
        self.v[b].subcols(0, cols)
    }

    /// w ← w − V Vᵀ (M w), given M w: one classical Gram–Schmidt pass in
    /// the M inner product. The rows go [`ROWS_PER_TASK`] at a time to the
    /// pool's threads (two cores stream the basis nearly twice as fast as
    /// one): each task's partial coefficients are summed in row order, so
    /// the result is the same however many threads share them.
    fn orthogonalize(&self, w: &mut [f64], mw: &[f64]) {
        let len = self.len;
        // All coefficients from the w given, then the update.
        let partial: Vec<Vec<f64>> = mw
            .par_chunks(ROWS_PER_TASK)
            .enumerate()
            .map(|(t, mw)| {
                let r0 = t * ROWS_PER_TASK;
                let mw = MatRef::from_column_major_slice(mw, mw.len(), 1);
                let mut c = Mat::zeros(len, 1);
                for b in 0..self.v.len() {
                    let v = self.block(b).subrows(r0, mw.nrows());
                    let part = c.as_mut().subrows_mut(b * CHUNK, v.ncols());
                    matmul(part, Accum::Replace, v.transpose(), mw, 1.0, Par::Seq);
                }
                c.col_as_slice(0).to_vec()
            })
            .collect();
        let mut c = Mat::<f64>::zeros(len, 1);
        for p in &partial {
            c.col_as_slice_mut(0)
                .iter_mut()
                .zip(p)
                .for_each(|(a, b)| *a += b);
        }
        w.par_chunks_mut(ROWS_PER_TASK)
            .enumerate()
            .for_each(|(t, w)| {
                let r0 = t * ROWS_PER_TASK;
                let rows = w.len();
                let mut w = MatMut::from_column_major_slice_mut(w, rows, 1);
                for b in 0..self.v.len() {
                    let v = self.block(b).subrows(r0, rows);
                    let cb = c.as_ref().subrows(b * CHUNK, v.ncols());
                    matmul(w.as_mut(), Accum::Add, v, cb, -1.0, Par::Seq);
                }
            });
    }

    /// V Y for a j × k matrix Y.
    fn combine(&self, y: MatRef<'_, f64>) -> Mat<f64> {
        let mut out = Mat::zeros(self.n, y.ncols());
        for b in 0..self.v.len() {
            let v = self.block(b);
            let rows = y.subrows(b * CHUNK, v.ncols());
            matmul(out.as_mut(), Accum::Add, v, rows, 1.0, Par::Seq);
        }
        out
    }
}

/// Makes w M-orthogonal to the basis: classical Gram–Schmidt against the
/// whole basis, repeated while a pass removes more than half of w's
/// squared M-norm (Daniel, Gragg, Kaufman and Stewart's test: after a pass
/// that keeps most of w, what is left of the basis in it is round-off of
/// round-off). `mw` is M w on entry and on return; returns wᵀ M w.
fn reorthogonalize(op: &Operator, basis: &Basis, w: &mut [f64], mw: &mut [f64]) -> f64 {
    let mut before = dot(w, mw);
    for _ in 0..3 {
        basis.orthogonalize(w, mw);
        mul_symmetric(op.shifted.mass(), w, mw);
        let after = dot(w, mw);
        if after >= 0.5 * before {
            return after;
        }
        before = after;
    }
    before
}

/// Lanczos with full re-orthogonalization in the M inner product from
/// `start`; returns the wanted lowest λ = σ + 1/θ, their M-normalized
/// vectors and the basis size.
fn lanczos(
    op: &mut Operator,
    start: &[f64],
    wanted: usize,
    sigma: f64,
    settings: &KrylovSettings,
) -> Result<(Vec<f64>, Mat<f64>, usize), EigenFailure> {
    let n = start.len();
    let limit = settings.max_basis.max(wanted + 2).min(n - op.z.len());
    let mut basis = Basis::new(n);
    let (mut alpha, mut beta): (Vec<f64>, Vec<f64>) = (Vec::new(), Vec::new());
    let mut v = start.to_vec();
    op.deflate(&mut v);
    let norm = op.m_dot(&v, &v).sqrt();
    if norm.is_nan() || norm <= 0.0 {
        return Err(EigenFailure::NoConvergence);
    }
    v.iter_mut().for_each(|x| *x /= norm);
    let mut w = vec![0.0; n];
    let mut mw = vec![0.0; n];
    // M v beside v: formed here for the start, then M w / β with v = w / β.
    let mut mv = vec![0.0; n];
    mul_symmetric(op.shifted.mass(), &v, &mut mv);
    loop {
        // w = S v.
        basis.push(&v);
        w.copy_from_slice(&mv);
        op.shifted.solve(&mut w);
        op.deflate(&mut w);
        // The three-term recurrence, then the whole basis against the
        // round-off it leaves (w M-orthogonal to the basis, and so to the
        // deflated space, which the basis is M-orthogonal to).
        let j = basis.len();
        let a = dot(&mv, &w);
        axpy(-a, &v, &mut w);
        if let Some(&b) = beta.last() {
            axpy(-b, basis.column(j - 2), &mut w);
        }
        mul_symmetric(op.shifted.mass(), &w, &mut mw);
        let b2 = reorthogonalize(op, &basis, &mut w, &mut mw);
        alpha.push(a);
        let b = b2.max(0.0).sqrt();
        let done = j >= wanted && (j - wanted).is_multiple_of(CHECK_EVERY) && {
            let (theta, s) = ritz(&alpha, &beta)?;
            let order = wanted_order(&theta, sigma);
            order
                .iter()
                .take(wanted)
                .all(|&i| (b * s[(j - 1, i)]).abs() <= settings.tolerance * theta[i].abs())
        };
        let breakdown = b <= 1e-14 * a.abs().max(f64::MIN_POSITIVE);
        if breakdown && !done && j < limit {
            // An invariant subspace (the start was already an eigenvector,
            // e.g. after the shift's inverse iterations): go on from a fresh
            // vector M-orthogonal to it, with a zero coupling in T.
            let mut fresh: Vec<f64> = (0..n)
                .map(|i| (2.3 * i as f64 + 0.7 * j as f64).sin())
                .collect();
            op.deflate(&mut fresh);
            let mut mf = vec![0.0; n];
            mul_symmetric(op.shifted.mass(), &fresh, &mut mf);
            let norm = reorthogonalize(op, &basis, &mut fresh, &mut mf)
                .max(0.0)
                .sqrt();
            if norm > 0.0 {
                beta.push(0.0);
                v = fresh.iter().map(|x| x / norm).collect();
                mv = mf.iter().map(|x| x / norm).collect();
                continue;
            }
        }
        let exhausted = breakdown || j >= limit;
        if done || exhausted {
            let (theta, s) = ritz(&alpha, &beta)?;
            let order = wanted_order(&theta, sigma);
            let count = wanted.min(order.len());
            let values = order
                .iter()
                .take(count)
                .map(|&i| sigma + 1.0 / theta[i])
                .collect();
            let y = Mat::from_fn(j, count, |r, c| s[(r, order[c])]);
            let vectors = basis.combine(y.as_ref());
            if !done && count < wanted {
                return Err(EigenFailure::NoConvergence);
            }
            return Ok((values, vectors, j));
        }
        beta.push(b);
        v.iter_mut().zip(&w).for_each(|(vi, wi)| *vi = wi / b);
        mv.iter_mut().zip(&mw).for_each(|(mvi, mwi)| *mvi = mwi / b);
    }
}

/// Ritz values θ and vectors of the tridiagonal (α, β).
fn ritz(alpha: &[f64], beta: &[f64]) -> Result<(Vec<f64>, Mat<f64>), EigenFailure> {
    let j = alpha.len();
    let t = Mat::from_fn(j, j, |r, c| {
        if r == c {
            alpha[r]
        } else if r.abs_diff(c) == 1 {
            beta[r.min(c)]
        } else {
            0.0
        }
    });
    symmetric_eigen_qr(&t, Par::Seq)
}

/// Ritz indices by ascending λ = σ + 1/θ (θ ≠ 0).
fn wanted_order(theta: &[f64], sigma: f64) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..theta.len()).filter(|&i| theta[i] != 0.0).collect();
    idx.sort_by(|&a, &b| (sigma + 1.0 / theta[a]).total_cmp(&(sigma + 1.0 / theta[b])));
    idx
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::Scatter;

    /// Free–free chain of n masses and n − 1 springs: one zero mode
    /// (uniform translation), ω²_j = 2k/m (1 − cos(jπ/n)), j = 1…n−1.
    #[test]
    fn free_chain_with_the_translation_deflated() {
        let (n, k, m) = (400, 5.0, 2e-3);
        let (mut kt, mut mt) = (Triplets::new(n, n), Triplets::new(n, n));
        for i in 0..n - 1 {
            kt.add(i, i, k);
            kt.add(i + 1, i + 1, k);
            kt.add(i, i + 1, -k);
            kt.add(i + 1, i, -k);
        }
        for i in 0..n {
            mt.add(i, i, m);
        }
        let z = vec![vec![1.0 / (n as f64 * m).sqrt(); n]];
        let modes = lowest_modes(&kt, &mt, &z, &KrylovSettings::new(6)).expect("converges");
        for (j, &v) in modes.values.iter().enumerate() {
            let exact =
                2.0 * k / m * (1.0 - (std::f64::consts::PI * (j + 1) as f64 / n as f64).cos());
            assert!(
                (v - exact).abs() <= 1e-9 * exact,
                "ω²_{} = {v:e}, chain formula {exact:e}",
                j + 1
            );
        }
        assert!(modes.shift < 0.0, "negative shift");
    }
}
