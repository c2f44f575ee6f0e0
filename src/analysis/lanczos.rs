//! Lowest eigenpairs of K x = λ M x by shift-invert Lanczos, for large
//! reduced problems where only a few modes [SI: ω² in rad²/s²] are wanted.
//!
//! Operator: Op = (K + σM)⁻¹ M, self-adjoint in the M-inner product for any
//! non-singular shift; its eigenvalues θ = 1/(λ + σ) make the lowest λ the
//! largest θ when K + σM is positive definite. K + σM is factored once by
//! [`BandLu`] (banded after reverse Cuthill–McKee), so a step costs one band
//! solve, one sparse product with M and the re-orthogonalization.
//!
//! Shift: σ = [`SHIFT_FRACTION`] · λ̂_max with λ̂_max = maxᵢ Kᵢᵢ/Mᵢᵢ (a
//! Rayleigh quotient, so ≤ λ_max, and within a modest factor of it for
//! beams). The lowest elastic ω² of a beam model sits 8–11 decades below its
//! highest (element-scale axial modes), so σ lands at the order of the first
//! elastic eigenvalues: rigid modes (λ = 0) become θ = 1/σ, well separated
//! yet not so dominant that the solve's round-off swamps elastic components
//! (cond(K + σM) ≈ λ_max/σ = 1e10). If the factorization is singular (σ hit
//! an eigenvalue) σ is multiplied by π and the factorization retried; if a
//! converged θ is negative, K has eigenvalues below −σ (a pre-stressed
//! indefinite K) and the run is repeated with σ beyond them.
//!
//! Lanczos: block size 1, full re-orthogonalization (twice) in the M-inner
//! product, deterministic start vectors (M-normalized ones plus an LCG
//! perturbation). All Lanczos vectors of all runs form one M-orthonormal
//! basis V and the projection H = Vᵀ M Op V is kept in full, so Rayleigh–Ritz
//! (by [`symmetric_eigen_qr`]) over the whole basis is exact even across
//! restarts. A run that has not converged is continued (the Krylov space is
//! enlarged); once the wanted pairs converge, a fresh start vector is added to
//! catch further members of a multiple eigenvalue (block size 1 finds one
//! vector per eigenvalue per run: a free body has a triple λ = 0), until a
//! fresh run changes nothing. Convergence is checked on the explicit
//! residual ‖K x − λ M x‖.

use super::band::{BandLu, Csr};
use super::eigen::{
    solve_generalized, symmetric_eigen_qr, EigenFailure, GeneralizedEigen, Spectrum,
};
use faer::{Mat, Par};

/// σ as a fraction of the estimate of the largest eigenvalue (see module docs).
pub const SHIFT_FRACTION: f64 = 1e-10;

/// Normwise backward error ‖Kx − λMx‖ / ‖|K||x| + |λ||M||x|‖ below which a
/// pair counts as converged. The scale is what rounding in forming Kx leaves
/// (≈ ε·λ_max‖Mx‖, which for a beam's first mode is 1e-5–1e-7 of λ‖Mx‖), so
/// the tolerance is a few million ε: measured, the purified Ritz vectors
/// of 300- and 500-element beams stagnate at 1e-15–7e-11 in this measure.
pub const RESIDUAL_TOLERANCE: f64 = 1e-9;

/// Largest λ̂_max = maxᵢ Kᵢᵢ/Mᵢᵢ over the coordinates with positive mass.
pub fn max_eigenvalue_estimate(k: &Mat<f64>, m: &Mat<f64>) -> f64 {
    (0..k.nrows())
        .filter(|&i| m[(i, i)] > 0.0)
        .map(|i| (k[(i, i)] / m[(i, i)]).abs())
        .fold(0.0, f64::max)
}

struct Problem {
    k: Csr,
    m: Csr,
    n: usize,
}

/// The `count` lowest eigenpairs (ascending, M-normalized vectors).
pub fn lowest_modes(
    k: &Mat<f64>,
    m: &Mat<f64>,
    count: usize,
) -> Result<GeneralizedEigen, EigenFailure> {
    let n = k.nrows();
    let count = count.min(n);
    let lmax = max_eigenvalue_estimate(k, m);
    let p = Problem {
        k: Csr::from_dense(k),
        m: Csr::from_dense(m),
        n,
    };
    let mut sigma = SHIFT_FRACTION * lmax.max(f64::MIN_POSITIVE);
    for _ in 0..8 {
        let lu = match BandLu::factor(&Csr::combine(k, sigma, m)) {
            Ok(lu) => lu,
            Err(_) => {
                sigma *= std::f64::consts::PI;
                continue;
            }
        };
        match run(&p, &lu, sigma, count)? {
            Outcome::Done(e) => {
                // σ far below the first elastic eigenvalue leaves A = K + σM
                // ill-conditioned (λ̂_max/σ); repeat once with σ at that
                // eigenvalue, keeping the first result if the repeat fails.
                let zero = 1e4 * f64::EPSILON * lmax;
                let first = e.values.iter().copied().find(|v| v.abs() > zero);
                if let Some(elastic) = first.filter(|&v| v > 100.0 * sigma) {
                    if let Ok(lu) = BandLu::factor(&Csr::combine(k, elastic, m)) {
                        if let Ok(Outcome::Done(better)) = run(&p, &lu, elastic, count) {
                            return Ok(better);
                        }
                    }
                }
                return Ok(e);
            }
            Outcome::BelowShift(lowest) => sigma = 2.0 * (-lowest).max(sigma) + sigma,
        }
    }
    Err(EigenFailure::NoConvergence)
}

enum Outcome {
    Done(GeneralizedEigen),
    /// A converged eigenvalue lies below −σ.
    BelowShift(f64),
}

/// Deterministic pseudo-random sequence (64-bit LCG) in [−0.5, 0.5).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

struct Basis {
    v: Vec<Vec<f64>>,
    mv: Vec<Vec<f64>>,
    /// h[j][i] = v_iᵀ M Op v_j for i ≤ j (column j of H, upper part).
    h: Vec<Vec<f64>>,
}

impl Basis {
    /// M-orthogonalize w against the basis twice; returns the coefficients.
    fn orthogonalize(&self, w: &mut [f64]) -> Vec<f64> {
        let mut c = vec![0.0; self.v.len()];
        for _ in 0..2 {
            for (i, (v, mv)) in self.v.iter().zip(&self.mv).enumerate() {
                let a = dot(mv, w);
                c[i] += a;
                w.iter_mut().zip(v).for_each(|(x, y)| *x -= a * y);
            }
        }
        c
    }

    /// Append w/‖w‖_M; false if w has (numerically) vanished.
    fn push(&mut self, p: &Problem, mut w: Vec<f64>, reference: f64) -> bool {
        let mut mw = vec![0.0; p.n];
        p.m.mul(&w, &mut mw);
        let norm = dot(&w, &mw).max(0.0).sqrt();
        if norm.is_nan() || norm <= 1e-10 * reference {
            return false;
        }
        w.iter_mut().for_each(|x| *x /= norm);
        mw.iter_mut().for_each(|x| *x /= norm);
        self.v.push(w);
        self.mv.push(mw);
        true
    }

    fn fresh(&mut self, p: &Problem, rng: &mut Lcg) -> bool {
        for _ in 0..4 {
            let mut w: Vec<f64> = (0..p.n).map(|_| 1.0 + rng.next()).collect();
            let mut mw = vec![0.0; p.n];
            p.m.mul(&w, &mut mw);
            let reference = dot(&w, &mw).max(0.0).sqrt();
            self.orthogonalize(&mut w);
            if self.push(p, w, reference) {
                return true;
            }
        }
        false
    }
}

fn run(p: &Problem, lu: &BandLu, sigma: f64, count: usize) -> Result<Outcome, EigenFailure> {
    let n = p.n;
    let chunk = (2 * count + 20).max(40).min(n);
    let max_dim = (8 * count + 200).min(n);
    let mut rng = Lcg(0x9e37_79b9_7f4a_7c15);
    let mut basis = Basis {
        v: Vec::new(),
        mv: Vec::new(),
        h: Vec::new(),
    };
    if !basis.fresh(p, &mut rng) {
        return Err(EigenFailure::NoConvergence);
    }
    let mut work = vec![0.0; n];
    let mut previous: Option<Vec<f64>> = None;
    let mut target = chunk;
    // Index of the vector whose Op-image continues the recurrence.
    loop {
        // Extend the Krylov recurrence from the last vector up to `target`.
        while basis.v.len() < target.min(max_dim) {
            let j = basis.v.len() - 1;
            let mut w = basis.mv[j].clone();
            lu.solve(&mut w, &mut work);
            let reference = dot(&basis.mv[j], &w).abs().max(
                // ‖Op v_j‖_M scale: θ of order 1/σ at most.
                f64::MIN_POSITIVE,
            );
            let c = basis.orthogonalize(&mut w);
            basis.h.push(c);
            if !basis.push(p, w, reference) && !basis.fresh(p, &mut rng) {
                break;
            }
        }
        // The last vector has no column yet: compute it (no new vector).
        let dim = basis.v.len();
        while basis.h.len() < dim {
            let j = basis.h.len();
            let mut w = basis.mv[j].clone();
            lu.solve(&mut w, &mut work);
            basis.h.push(basis.orthogonalize(&mut w));
        }
        let h = Mat::from_fn(dim, dim, |i, j| {
            let (a, b) = if i <= j { (i, j) } else { (j, i) };
            basis.h[b][a]
        });
        let (theta, s) = symmetric_eigen_qr(&h, Par::Seq)?;
        // Lowest λ = largest θ > 0; a converged θ < 0 means λ < −σ. Ritz
        // values at round-off level of the largest |θ| are discarded.
        let cut = 1e3 * f64::EPSILON * theta.iter().fold(0.0f64, |a, t| a.max(t.abs()));
        let mut pairs: Vec<(f64, usize)> = theta
            .iter()
            .enumerate()
            .filter(|(_, &t)| t.abs() > cut)
            .map(|(i, &t)| (1.0 / t - sigma, i))
            .collect();
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        let take = count.min(pairs.len());
        // Ritz vectors, each purified by one more application of Op (damps
        // the components along high modes, which a tiny Op-residual leaves
        // large in K x − λ M x), then Rayleigh–Ritz of (K, M) on their span.
        let mut x: Vec<Vec<f64>> = Vec::with_capacity(take);
        for &(_, i) in pairs.iter().take(take) {
            let mut y = vec![0.0; n];
            for (col, v) in basis.v.iter().enumerate() {
                let a = s[(col, i)];
                y.iter_mut().zip(v).for_each(|(yr, vr)| *yr += a * vr);
            }
            let mut my = vec![0.0; n];
            p.m.mul(&y, &mut my);
            lu.solve(&mut my, &mut work);
            x.push(my);
        }
        let (kx, mx): (Vec<Vec<f64>>, Vec<Vec<f64>>) = x
            .iter()
            .map(|xi| {
                let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
                p.k.mul(xi, &mut a);
                p.m.mul(xi, &mut b);
                (a, b)
            })
            .unzip();
        let kp = Mat::from_fn(take, take, |i, j| {
            0.5 * (dot(&x[i], &kx[j]) + dot(&x[j], &kx[i]))
        });
        let mp = Mat::from_fn(take, take, |i, j| {
            0.5 * (dot(&x[i], &mx[j]) + dot(&x[j], &mx[i]))
        });
        let small = solve_generalized(&kp, &mp, take).map_err(|_| EigenFailure::NoConvergence)?;
        let values = small.values;
        let mut vectors = Mat::zeros(n, take);
        let mut converged = take == count;
        let mut lowest_negative: Option<f64> = None;
        let (mut kv, mut mv) = (vec![0.0; n], vec![0.0; n]);
        let (mut ka, mut ma) = (vec![0.0; n], vec![0.0; n]);
        for (c, &lambda) in values.iter().enumerate() {
            let mut v = vec![0.0; n];
            for (xi, r) in x.iter().enumerate() {
                let a = small.vectors[(xi, c)];
                v.iter_mut().zip(r).for_each(|(vr, xr)| *vr += a * xr);
            }
            p.k.mul(&v, &mut kv);
            p.m.mul(&v, &mut mv);
            let res = kv
                .iter()
                .zip(&mv)
                .map(|(a, b)| (a - lambda * b).powi(2))
                .sum::<f64>()
                .sqrt();
            // Normwise backward error: ‖Kx − λMx‖ against ‖|K||x| + |λ||M||x|‖.
            p.k.mul_abs(&v, &mut ka);
            p.m.mul_abs(&v, &mut ma);
            let scale = ka
                .iter()
                .zip(&ma)
                .map(|(a, b)| (a + lambda.abs() * b).powi(2))
                .sum::<f64>()
                .sqrt();
            let ok = res <= RESIDUAL_TOLERANCE * scale;
            if lambda < -sigma && ok {
                lowest_negative = Some(lowest_negative.map_or(lambda, |l: f64| l.min(lambda)));
            }
            converged &= ok;
            for r in 0..n {
                vectors[(r, c)] = v[r];
            }
        }
        if let Some(l) = lowest_negative {
            return Ok(Outcome::BelowShift(l));
        }
        // The whole space spanned: Rayleigh–Ritz is then as exact as a dense
        // solve, whatever the residual test says.
        if dim >= n && take == count {
            return Ok(Outcome::Done(GeneralizedEigen {
                values,
                vectors,
                spectrum: Spectrum::Partial,
            }));
        }
        if converged {
            let same = previous.as_ref().is_some_and(|prev| {
                prev.len() == values.len()
                    && prev
                        .iter()
                        .zip(&values)
                        .all(|(a, b)| (a - b).abs() <= 1e-8 * (b.abs() + sigma))
            });
            if same || dim >= max_dim {
                return Ok(Outcome::Done(GeneralizedEigen {
                    values,
                    vectors,
                    spectrum: Spectrum::Partial,
                }));
            }
            previous = Some(values);
            // Look for further members of multiple eigenvalues.
            if !basis.fresh(p, &mut rng) {
                return Ok(Outcome::Done(GeneralizedEigen {
                    values: previous.unwrap_or_default(),
                    vectors,
                    spectrum: Spectrum::Partial,
                }));
            }
            target = basis.v.len() + (count + 10).max(20);
        } else {
            if dim >= max_dim {
                return Err(EigenFailure::NoConvergence);
            }
            target = dim + chunk;
            // Continue the recurrence from the last vector: its column of H
            // was computed above; the next vector follows from it.
            let j = dim - 1;
            let mut w = basis.mv[j].clone();
            lu.solve(&mut w, &mut work);
            let reference = dot(&basis.mv[j], &w).abs().max(f64::MIN_POSITIVE);
            basis.orthogonalize(&mut w);
            if !basis.push(p, w, reference) && !basis.fresh(p, &mut rng) {
                return Err(EigenFailure::NoConvergence);
            }
        }
    }
}
