//! The linear half of the modal model's fit, and the refinement of the
//! poles by variable projection (see [`super::lsfd`] for the model).
//!
//! **Linear part.** For given poles the model Ĥ = A c is linear in its
//! coefficients c: per pole (Re R, Im R) and, with records, (Re D, Im D) of
//! the cut-off decay, then U, L and the other residual terms
//! ([`Band::powers`]). The rows of A are (Re, Im) per bin, weighted as
//! the band weighs its bins ([`Band::rows`]). c is the least-squares
//! solution by Householder QR of A with its columns scaled to unit norm
//! (zero columns left out, their coefficients 0), or by SVD when R is near
//! singular (two poles on top of each other).
//!
//! **Refinement.** The misfit f(θ) = A(θ) c(θ) − b, c eliminated, is
//! minimised over the poles' parts θ = (Re s₁, Im s₁, …) by
//! Levenberg–Marquardt ([`lm::solve`]). Its Jacobian is the exact one of
//! variable projection (Golub and Pereyra 1973): with P⊥ = I − A A⁺,
//! ∂f/∂θ = P⊥ (∂A/∂θ) c − (A⁺)ᵀ (∂A/∂θ)ᵀ f, each column O(rows × columns)
//! from the QR already made. (Kaufman's simplification, the first term
//! alone, stalled a weak pole beside a large misfit.) When R is near
//! singular the Jacobian is taken by forward differences instead.
//!
//! Units: s in 1/s; R in FRF unit × 1/s, D in FRF unit × 1/s, U in FRF
//! unit, L in FRF unit × 1/s²; f and the rows in the FRF's unit (weighted).

use std::f64::consts::PI;

use nalgebra::{DMatrix, DVector, Dyn, QR};
use realfft::num_complex::Complex64;

use super::lm;
use super::lsfd::{Band, Residues, TRUNCATION_FLOOR};
use super::pole_basis::PoleFactor;

/// A linear least-squares fit of the coefficients of given poles.
pub struct Projection {
    pub fitted: Residues,
    /// Per bin, the weighted misfit row(k)·(H_k − Ĥ_k).
    pub residual: Vec<Complex64>,
    /// The QR factorization of the scaled used columns, when R was
    /// regular (Q is formed only if a Jacobian is asked for), and the
    /// columns used with their norms.
    factors: Option<QR<f64, Dyn, Dyn>>,
    used: Vec<(usize, f64)>,
}

/// Whether pole `p` has a cut-off term in the fit of `band`.
fn has_cutoff(band: Band<'_>, p: Complex64) -> bool {
    band.truncation.is_some() && (p.re * band.record_s).exp() > TRUNCATION_FLOOR
}

/// The design matrix of the coefficients of `poles` (module doc): rows
/// (Re, Im) per bin, columns (Re R_r, Im R_r) per pole, then (Re D_r,
/// Im D_r) per pole with records, then the residual terms, U and L.
pub(crate) fn design(band: Band<'_>, poles: &[Complex64]) -> DMatrix<f64> {
    let np = poles.len();
    let cols = band.per_pole() * np + 2 + band.powers.len();
    let mut a = DMatrix::<f64>::zeros(2 * band.bins.len(), cols);
    let i = Complex64::new(0.0, 1.0);
    let factors: Vec<PoleFactor> = poles.iter().map(|p| band.basis.factor(*p)).collect();
    let cut: Vec<bool> = poles.iter().map(|p| has_cutoff(band, *p)).collect();
    for (k, (f, _)) in band.bins.iter().enumerate() {
        let w = band.weight(k);
        let at = band.basis.at(*f);
        let at_cut = at.cutoff();
        for (r, p) in factors.iter().enumerate() {
            // R = x + iy: R g + R̄ g' = x·(g + g') + y·i(g − g').
            let (g1, g2) = (at.term(*p), at.term(p.conj()));
            let (cx, cy) = (g1 + g2, i * (g1 - g2));
            a[(2 * k, 2 * r)] = cx.re;
            a[(2 * k + 1, 2 * r)] = cx.im;
            a[(2 * k, 2 * r + 1)] = cy.re;
            a[(2 * k + 1, 2 * r + 1)] = cy.im;
            if cut[r] {
                let (t1, t2) = if at_cut == at {
                    (g1, g2)
                } else {
                    (at_cut.term(*p), at_cut.term(p.conj()))
                };
                let (dx, dy) = (w * (t1 + t2), w * i * (t1 - t2));
                a[(2 * k, 2 * np + 2 * r)] = dx.re;
                a[(2 * k + 1, 2 * np + 2 * r)] = dx.im;
                a[(2 * k, 2 * np + 2 * r + 1)] = dy.re;
                a[(2 * k + 1, 2 * np + 2 * r + 1)] = dy.im;
            }
        }
        a[(2 * k, cols - 2)] = 1.0;
        let om = 2.0 * PI * f;
        a[(2 * k, cols - 1)] = if *f != 0.0 { -1.0 / (om * om) } else { 0.0 };
        if *f != 0.0 {
            let jw = Complex64::new(0.0, om);
            for (q, n) in band.powers.iter().enumerate() {
                let c = jw.powi(*n);
                let col = cols - 2 - band.powers.len() + q;
                a[(2 * k, col)] = c.re;
                a[(2 * k + 1, col)] = c.im;
            }
        }
        let row = band.row(k);
        if row != 1.0 {
            a.row_mut(2 * k).scale_mut(row);
            a.row_mut(2 * k + 1).scale_mut(row);
        }
    }
    a
}

/// The measured FRF of the band as (Re, Im) per bin, weighted.
fn measured(band: Band<'_>) -> DVector<f64> {
    DVector::from_iterator(
        2 * band.bins.len(),
        band.bins
            .iter()
            .enumerate()
            .flat_map(|(k, (_, h))| [band.row(k) * h.re, band.row(k) * h.im]),
    )
}

/// Smallest direction of the coefficients' least squares kept, relative to
/// the largest (the QR's diagonal, then the SVD's singular values, of the
/// column-scaled design): with the decays cut off at a short record's end
/// the columns of a pole's residue and cut-off are nearly dependent, and
/// directions kept down to 1e-10 let the coefficients of noise-free records
/// grow and cancel (a tuning fork's residues 300 times too large).
const PROJ_RCOND: f64 = 1e-6;

/// The least-squares fit of the coefficients of `poles` to `band`
/// (module doc).
pub fn project(band: Band<'_>, poles: &[Complex64]) -> Projection {
    solve(band, poles.len(), design(band, poles))
}

/// The least-squares fit of the coefficients of a design `a` of `np`
/// poles, laid out as [`design`]'s, to `band`: for a design whose pole
/// columns were changed (the residues tied to their cut-off decays,
/// `measured::cut_off`).
pub(crate) fn solve(band: Band<'_>, np: usize, a: DMatrix<f64>) -> Projection {
    let b = measured(band);
    let cols = a.ncols();
    let used: Vec<(usize, f64)> = (0..cols)
        .map(|j| (j, a.column(j).norm()))
        .filter(|(_, n)| *n > 0.0)
        .collect();
    let k = used.len();
    let scaled = || DMatrix::from_fn(a.nrows(), k, |i, c| a[(i, used[c].0)] / used[c].1);
    let qr = scaled().qr();
    let r = qr.r();
    let largest = r.diagonal().iter().fold(0.0_f64, |mx, d| mx.max(d.abs()));
    let regular = r.diagonal().iter().all(|d| d.abs() > PROJ_RCOND * largest);
    let solved = if regular {
        let mut qtb = b.clone();
        qr.q_tr_mul(&mut qtb);
        r.solve_upper_triangular(&qtb.rows(0, k).into_owned())
    } else {
        None
    };
    let factors = solved.is_some().then_some(qr);
    let y = solved.unwrap_or_else(|| {
        // Near singular (rare): the scaled columns again, for the SVD.
        scaled()
            .svd(true, true)
            .solve(&b, PROJ_RCOND * largest)
            .unwrap_or_else(|_| DVector::zeros(k))
    });
    let mut x = DVector::zeros(cols);
    for (c, (j, n)) in used.iter().enumerate() {
        x[*j] = y[c] / n;
    }
    let fit = &a * &x;
    let residual = (0..band.bins.len())
        .map(|q| Complex64::new(b[2 * q] - fit[2 * q], b[2 * q + 1] - fit[2 * q + 1]))
        .collect();
    Projection {
        fitted: coefficients(band, np, &x),
        residual,
        factors,
        used,
    }
}

/// The coefficient vector `x` of the design's columns as residues.
fn coefficients(band: Band<'_>, np: usize, x: &DVector<f64>) -> Residues {
    let cols = x.len();
    let pair = |c: usize| Complex64::new(x[c], x[c + 1]);
    Residues {
        residues: (0..np).map(|r| pair(2 * r)).collect(),
        truncation: if band.truncation.is_some() {
            (0..np).map(|r| pair(2 * np + 2 * r)).collect()
        } else {
            Vec::new()
        },
        upper: x[cols - 2],
        lower: x[cols - 1],
        powers: (band.powers.iter().enumerate())
            .map(|(q, n)| (*n, x[cols - 2 - band.powers.len() + q]))
            .collect(),
    }
}

/// Calls `visit(k, j, ∂A)` for every bin k and pole j with ∂A/∂(Re s_j)
/// and ∂A/∂(Im s_j) in the pole's columns at that bin: per column (Re R,
/// Im R, Re D, Im D), the complex entry of the bin (weighted by the row;
/// the cut-off's by W too).
fn for_each_derivative(
    band: Band<'_>,
    poles: &[Complex64],
    mut visit: impl FnMut(usize, usize, &[[Complex64; 4]; 2]),
) {
    let i = Complex64::new(0.0, 1.0);
    let factors: Vec<PoleFactor> = poles.iter().map(|p| band.basis.factor(*p)).collect();
    for k in 0..band.bins.len() {
        let at = band.basis.at(band.bins[k].0);
        let cut = at.cutoff();
        let (w, row) = (band.weight(k), band.row(k));
        for (j, p) in factors.iter().enumerate() {
            let (d1, d2) = (at.term_derivative(*p), at.term_derivative(p.conj()));
            let (e1, e2) = if cut == at {
                (w * d1, w * d2)
            } else {
                (
                    w * cut.term_derivative(*p),
                    w * cut.term_derivative(p.conj()),
                )
            };
            // Column x·(g + ḡ'): ∂Re s → d1 + d2, ∂Im s → i(d1 − d2);
            // column y·i(g − ḡ'): ∂Re s → i(d1 − d2), ∂Im s → −(d1 + d2).
            let (rs, rd) = (row * (d1 + d2), row * i * (d1 - d2));
            let (ts, td) = (row * (e1 + e2), row * i * (e1 - e2));
            visit(k, j, &[[rs, rd, ts, td], [rd, -rs, td, -ts]]);
        }
    }
}

/// A pole's coefficients (Re R, Im R, Re D, Im D) in `fitted`.
fn pole_coefficients(fitted: &Residues, j: usize) -> [f64; 4] {
    let d = fitted.truncation.get(j).copied().unwrap_or_default();
    [fitted.residues[j].re, fitted.residues[j].im, d.re, d.im]
}

/// ∂(model)/∂(Re s_j, Im s_j) per bin (rows Re, Im, weighted), the
/// coefficients held: (∂A/∂θ) c.
pub(crate) fn pole_jacobian(
    band: Band<'_>,
    poles: &[Complex64],
    fitted: &Residues,
) -> DMatrix<f64> {
    let mut jac = DMatrix::<f64>::zeros(2 * band.bins.len(), 2 * poles.len());
    let coef: Vec<[f64; 4]> = (0..poles.len())
        .map(|j| pole_coefficients(fitted, j))
        .collect();
    for_each_derivative(band, poles, |k, j, parts| {
        for (part, dcol) in parts.iter().enumerate() {
            let v: Complex64 = dcol.iter().zip(coef[j]).map(|(d, c)| d * c).sum();
            jac[(2 * k, 2 * j + part)] = v.re;
            jac[(2 * k + 1, 2 * j + part)] = v.im;
        }
    });
    jac
}

/// ∂f/∂θ of variable projection (module doc) at `poles`, from their
/// projection; None when it holds no regular factorization.
fn projected_jacobian(
    band: Band<'_>,
    poles: &[Complex64],
    pr: &Projection,
) -> Option<DMatrix<f64>> {
    let qr = pr.factors.as_ref()?;
    let (q, r) = (qr.q(), qr.r());
    let np = poles.len();
    // Position of each design column among the used ones; a pole's D
    // columns are used only when it has a cut-off term.
    let mut slot = vec![None; band.per_pole() * np + 2 + band.powers.len()];
    for (c, (j, _)) in pr.used.iter().enumerate() {
        slot[*j] = Some(c);
    }
    let live: Vec<[Option<usize>; 4]> = (0..np)
        .map(|j| {
            let columns = [2 * j, 2 * j + 1, 2 * np + 2 * j, 2 * np + 2 * j + 1];
            std::array::from_fn(|c| {
                (c < 2 || has_cutoff(band, poles[j]))
                    .then(|| slot[columns[c]])
                    .flatten()
            })
        })
        .collect();
    // First term's (∂A)c, and u = (∂A)ᵀ f, f = −residual (model − data).
    let held = pole_jacobian(band, poles, &pr.fitted);
    let mut u = DMatrix::<f64>::zeros(pr.used.len(), 2 * np);
    for_each_derivative(band, poles, |k, j, parts| {
        let f = -pr.residual[k];
        for (part, dcol) in parts.iter().enumerate() {
            for (d, at) in dcol.iter().zip(live[j]) {
                if let Some(at) = at {
                    u[(at, 2 * j + part)] += d.re * f.re + d.im * f.im;
                }
            }
        }
    });
    let mut jac = DMatrix::<f64>::zeros(held.nrows(), 2 * np);
    for col in 0..2 * np {
        // P⊥ v = v − Q Qᵀ v.
        let v = held.column(col);
        let first = v - &q * q.tr_mul(&v);
        // (A⁺)ᵀ u = Q R⁻ᵀ (S u), S = diag(1/‖column‖).
        let su = DVector::from_iterator(
            pr.used.len(),
            pr.used
                .iter()
                .enumerate()
                .map(|(c, (_, n))| u[(c, col)] / n),
        );
        let y = r.tr_solve_upper_triangular(&su)?;
        jac.set_column(col, &(first - &q * y));
    }
    Some(jac)
}

/// The modal model's misfit as a least-squares problem in the poles'
/// parts x = (Re s₁, Im s₁, Re s₂, …) (module doc).
struct PoleRefinement<'a> {
    band: Band<'a>,
}

fn poles_of(x: &[f64]) -> Vec<Complex64> {
    x.chunks(2).map(|c| Complex64::new(c[0], c[1])).collect()
}

/// One evaluated point: the misfit (model − data, (Re, Im) per bin) and
/// its projection.
struct Point {
    misfit: DVector<f64>,
    projection: Projection,
}

impl lm::Problem for PoleRefinement<'_> {
    type Point = Point;
    type Error = std::convert::Infallible;

    fn evaluate(&mut self, x: &[f64]) -> Result<Point, Self::Error> {
        let projection = project(self.band, &poles_of(x));
        let misfit = DVector::from_iterator(
            2 * projection.residual.len(),
            projection.residual.iter().flat_map(|r| [-r.re, -r.im]),
        );
        Ok(Point { misfit, projection })
    }

    fn residuals(&self, point: &Point) -> DVector<f64> {
        point.misfit.clone()
    }

    /// The variable-projection Jacobian (module doc), or forward
    /// differences of the projected misfit, step 1e-7 |s|, when the
    /// factorization is not regular.
    fn jacobian(
        &mut self,
        x: &[f64],
        point: &Point,
        r: &DVector<f64>,
    ) -> Result<DMatrix<f64>, Self::Error> {
        if let Some(jac) = projected_jacobian(self.band, &poles_of(x), &point.projection) {
            return Ok(jac);
        }
        Ok(self.differences(x, r))
    }
}

impl PoleRefinement<'_> {
    /// Forward differences of the projected misfit, step 1e-7 |s| for
    /// each pole's parts.
    fn differences(&mut self, x: &[f64], r: &DVector<f64>) -> DMatrix<f64> {
        let mut jac = DMatrix::<f64>::zeros(r.len(), x.len());
        for j in 0..x.len() {
            let mut xj = x.to_vec();
            let step = 1e-7 * Complex64::new(x[j / 2 * 2], x[j / 2 * 2 + 1]).norm();
            xj[j] += step;
            let Ok(point) = lm::Problem::evaluate(self, &xj);
            jac.set_column(j, &((point.misfit - r) / step));
        }
        jac
    }
}

/// Settings of the refinement's Levenberg–Marquardt loop: μ from 10⁻³,
/// ×4 on a rejected trial, ÷3 (down to 10⁻¹²) on a taken step; at most 50
/// taken steps, 10 rejected trials in a row, or a taken step that lowers
/// the misfit by 10⁻¹² of itself.
const REFINE: lm::Settings = lm::Settings {
    initial_damping: lm::Scale::Absolute(1e-3),
    grow: 4.0,
    shrink: 3.0,
    damping_floor: lm::Scale::Absolute(1e-12),
    damping_ceiling: f64::INFINITY,
    max_rejections: 10,
    step_tolerance: 0.0,
    min_relative_decrease: 1e-12,
    max_evaluations: usize::MAX,
    max_iterations: 50,
};

/// The loop also stops when a step would move no pole's part by more than
/// this fraction of the largest |s|: 1e-13 of it is far below what any
/// record resolves, and at round-off the trials that follow are rejected
/// one after another (18 of 28 evaluations in `benches/frf.rs` were).
pub const STEP_TOLERANCE: f64 = 1e-13;

/// Nonlinear least-squares refinement of the poles (module doc).
pub fn refine(band: Band<'_>, poles: &mut [Complex64]) {
    refine_some(band, poles, |_| true);
}

/// [`refine`] of the poles `free(i)` says, the others held where they are
/// (their residues still fitted).
pub fn refine_some(band: Band<'_>, poles: &mut [Complex64], free: impl Fn(usize) -> bool) {
    if poles.is_empty() {
        return;
    }
    let mut problem = PoleRefinement { band };
    let x0: Vec<f64> = poles.iter().flat_map(|p| [p.re, p.im]).collect();
    let bound = |sign: f64| -> Vec<f64> {
        x0.iter()
            .enumerate()
            .map(|(k, &v)| if free(k / 2) { sign * f64::INFINITY } else { v })
            .collect()
    };
    let (lower, upper) = (bound(-1.0), bound(1.0));
    let Ok(start) = lm::Problem::evaluate(&mut problem, &x0);
    let scale = poles.iter().fold(0.0_f64, |m, p| m.max(p.norm()));
    let settings = lm::Settings {
        step_tolerance: STEP_TOLERANCE * scale,
        ..REFINE
    };
    let Ok(out) = lm::solve(&mut problem, x0, start, &lower, &upper, &settings);
    poles.copy_from_slice(&poles_of(&out.x));
}

/// The analytic Jacobian against the forward differences of the
/// projected misfit it replaced.
#[cfg(test)]
mod tests;
