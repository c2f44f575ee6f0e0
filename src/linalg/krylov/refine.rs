//! Block Davidson refinement of Lanczos' modes with precise stiffness
//! products (see [`super::lowest_modes_refined`]): Rayleigh–Ritz on the
//! Ritz block X and its preconditioned residuals W = P⁻¹(KX − MXΘ), with the
//! shifted factor P = K − σM only as preconditioner, so the accuracy is the
//! products' (element-wise strain variations), not the factor's. Each
//! mode's bound is |θ − λ| ≤ 2η²(|θ − σ| + δ)/δ with η² = rᵀP⁻¹r and δ the
//! gap to the nearest other Ritz value [SI: λ = ω² in rad²/s²]; then the
//! certificate: Sylvester's count below a point in the gap above the wanted
//! modes, when the factor's perturbation is far below that gap.

use super::{EigenFailure, KrylovModes, Operator, StiffnessProducts, GUARD, REFINE_STEPS};
use crate::linalg::dense::symmetric_eigen_qr;
use crate::linalg::sparse::{mul_symmetric_block, BLOCK_COLUMNS};
use crate::linalg::vector::scrambled;
use faer::sparse::SparseColMat;
use faer::{Mat, Par};
use rayon::prelude::*;

/// The relative bound on θ at which the refinement stops: 1e-10 on ω² is
/// 5e-11 on a frequency, far below the 1e-9 (and the 1e-5 refusal) the
/// printed bounds are held to; a further block step (a sixth of a
/// 100,000-element run) would only push it to ~1e-12.
const RESOLVED: f64 = 1e-10;

/// What [`refine`] needs to know of the run before it.
pub(super) struct Refinement {
    pub(super) wanted: usize,
    pub(super) deflated: usize,
    pub(super) sigma: f64,
    pub(super) steps: usize,
    pub(super) factorizations: usize,
}

/// Blocks of n rows reused from step to step: a fresh block of a large
/// model (51 MB at 100,000 elements and 16 columns) costs its page faults,
/// which were a third of the refinement's time. Contents of a block taken
/// are stale; every user overwrites them.
struct Pool {
    n: usize,
    free: Vec<Mat<f64>>,
}

impl Pool {
    fn new(n: usize) -> Self {
        Pool {
            n,
            free: Vec::new(),
        }
    }

    /// An n × k block of stale values.
    fn take(&mut self, k: usize) -> Mat<f64> {
        let mut m = self.free.pop().unwrap_or_else(|| Mat::zeros(0, 0));
        m.truncate(m.nrows().min(self.n), m.ncols().min(k));
        m.resize_with(self.n, k, |_, _| 0.0);
        m
    }

    fn give(&mut self, m: Mat<f64>) {
        self.free.push(m);
    }

    /// X ← X A + W B, in place where X has at least A's columns (rows a
    /// chunk at a time, so that no second block of X's size is held); in
    /// a block of the pool otherwise.
    fn combine_into(
        &mut self,
        x: &mut Mat<f64>,
        a: faer::MatRef<'_, f64>,
        w: Option<(faer::MatRef<'_, f64>, faer::MatRef<'_, f64>)>,
    ) {
        let (n, k) = (x.nrows(), a.ncols());
        if x.ncols() < k || x.ncols() == 0 {
            let mut out = self.take(k);
            let accum = if x.ncols() == 0 {
                out.fill(0.0);
                faer::Accum::Add
            } else {
                faer::Accum::Replace
            };
            let (out_ref, x_ref) = (out.as_mut(), x.as_ref());
            faer::linalg::matmul::matmul(out_ref, accum, x_ref, a, 1.0, Par::Seq);
            if let Some((w, b)) = w {
                let out_ref = out.as_mut();
                faer::linalg::matmul::matmul(out_ref, faer::Accum::Add, w, b, 1.0, Par::Seq);
            }
            self.give(std::mem::replace(x, out));
            return;
        }
        // Row chunks shared among the pool's threads (each chunk's
        // products are the same however they are shared).
        x.as_mut()
            .par_row_chunks_mut(ROW_CHUNK)
            .enumerate()
            .for_each_init(
                || Mat::<f64>::zeros(ROW_CHUNK.min(n), k),
                |chunk, (t, xr)| {
                    let (r0, rows) = (t * ROW_CHUNK, xr.nrows());
                    let mut c = chunk.as_mut().subrows_mut(0, rows);
                    faer::linalg::matmul::matmul(
                        c.as_mut(),
                        faer::Accum::Replace,
                        xr.as_ref(),
                        a,
                        1.0,
                        Par::Seq,
                    );
                    if let Some((w, b)) = w {
                        let wr = w.subrows(r0, rows);
                        faer::linalg::matmul::matmul(
                            c.as_mut(),
                            faer::Accum::Add,
                            wr,
                            b,
                            1.0,
                            Par::Seq,
                        );
                    }
                    xr.subcols_mut(0, k).copy_from(c.as_ref());
                },
            );
        x.truncate(n, k);
    }

    /// Wᵀ M W, [`BLOCK_COLUMNS`] columns of M W at a time (no block of W's
    /// size held).
    fn gram_m(&mut self, m: &SparseColMat<usize, f64>, w: &Mat<f64>) -> Mat<f64> {
        let k = w.ncols();
        let mut g = Mat::zeros(k, k);
        let mut mw = Mat::<f64>::zeros(w.nrows(), BLOCK_COLUMNS.min(k));
        let mut c0 = 0;
        while c0 < k {
            let c = BLOCK_COLUMNS.min(k - c0);
            let mut part = mw.as_mut().subcols_mut(0, c);
            mul_symmetric_block(m, w.as_ref().subcols(c0, c), part.as_mut());
            faer::linalg::matmul::matmul(
                g.as_mut().subcols_mut(c0, c),
                faer::Accum::Replace,
                w.transpose(),
                part.as_ref(),
                1.0,
                Par::Seq,
            );
            c0 += c;
        }
        g
    }

    /// M W for every column, into a block of the pool.
    fn m_block(&mut self, m: &SparseColMat<usize, f64>, w: &Mat<f64>) -> Mat<f64> {
        let mut out = self.take(w.ncols());
        mul_symmetric_block(m, w.as_ref(), out.as_mut());
        out
    }

    /// K W for every column by the precise products, into a block of the
    /// pool.
    fn k_block(&mut self, products: &StiffnessProducts, w: &Mat<f64>) -> Mat<f64> {
        let refs: Vec<&[f64]> = (0..w.ncols()).map(|c| w.col_as_slice(c)).collect();
        let mut kw = self.take(w.ncols());
        let mut out: Vec<&mut [f64]> = kw
            .as_mut()
            .col_iter_mut()
            .map(|c| {
                c.try_as_col_major_mut()
                    .expect("a column is contiguous")
                    .as_slice_mut()
            })
            .collect();
        products(&refs, &mut out);
        kw
    }
}

/// Rows per chunk of [`Pool::combine_into`] (16 columns of them fit a
/// core's L2 cache).
const ROW_CHUNK: usize = 2048;

/// A B (small blocks).
fn mm(a: faer::MatRef<'_, f64>, b: faer::MatRef<'_, f64>) -> Mat<f64> {
    let mut out = Mat::zeros(a.nrows(), b.ncols());
    faer::linalg::matmul::matmul(out.as_mut(), faer::Accum::Replace, a, b, 1.0, Par::Seq);
    out
}

/// out ← out − A B, in place (no temporary block).
fn sub_mm(out: &mut Mat<f64>, a: faer::MatRef<'_, f64>, b: faer::MatRef<'_, f64>) {
    faer::linalg::matmul::matmul(out.as_mut(), faer::Accum::Add, a, b, -1.0, Par::Seq);
}

/// Makes the columns of `w` deflated, M-orthogonal to X (M X given) and
/// M-orthonormal among themselves (deflation and block Gram–Schmidt, then
/// the Gram matrix's eigenvectors, dropping directions that vanish). A
/// direction is dropped when less than 1e-7 of its length survives:
/// normalizing what is left of it would blow its round-off up, zero modes
/// included, into a spurious Ritz value.
///
/// A second pass follows unless the first one provably left nothing to
/// clean (each pass reads the block several times; on a large model a
/// pass is a sixth of a refinement step):
/// - X took out less than what is left of every column (Daniel, Gragg,
///   Kaufman and Stewart's test; with X M-orthonormal, the removed part's
///   squared M-norm is |c|² of the coefficients c = (MX)ᵀw, what is left is
///   the Gram matrix's diagonal), so what remains of X in it is round-off
///   of round-off;
/// - the Gram matrix's condition is at most [`ONE_PASS_CONDITION`], so its
///   inverse square root leaves the columns M-orthonormal to ε times it.
fn orthonormalize_against(
    op: &Operator,
    pool: &mut Pool,
    x: &Mat<f64>,
    mx: &Mat<f64>,
    mut w: Mat<f64>,
) -> Result<Mat<f64>, EigenFailure> {
    let m = op.m();
    for pass in 0..2 {
        for c in 0..w.ncols() {
            op.deflate(w.col_as_slice_mut(c));
        }
        let removed: Vec<f64> = if x.ncols() > 0 {
            let c = mm(mx.transpose(), w.as_ref());
            sub_mm(&mut w, x.as_ref(), c.as_ref());
            (0..c.ncols())
                .map(|j| c.col_as_slice(j).iter().map(|v| v * v).sum())
                .collect()
        } else {
            vec![0.0; w.ncols()]
        };
        let g = pool.gram_m(m, &w);
        let g = Mat::from_fn(g.nrows(), g.ncols(), |i, j| 0.5 * (g[(i, j)] + g[(j, i)]));
        let (vals, vecs) = symmetric_eigen_qr(&g, Par::Seq)?;
        let top = vals.iter().fold(0.0f64, |a, &v| a.max(v));
        let keep: Vec<usize> = (0..vals.len())
            .filter(|&i| vals[i] > 1e-14 * top && vals[i] > 0.0)
            .collect();
        let t = Mat::from_fn(vecs.nrows(), keep.len(), |r, c| {
            vecs[(r, keep[c])] / vals[keep[c]].sqrt()
        });
        pool.combine_into(&mut w, t.as_ref(), None);
        let kept_most = removed.iter().enumerate().all(|(j, &r)| r <= g[(j, j)]);
        let bottom = vals.iter().fold(f64::INFINITY, |a, &v| a.min(v));
        let conditioned = keep.len() == vals.len() && top <= ONE_PASS_CONDITION * bottom;
        if pass == 0 && kept_most && conditioned {
            break;
        }
    }
    Ok(w)
}

/// The largest condition of the Gram matrix after which one pass of
/// [`orthonormalize_against`] suffices: its columns are then M-orthonormal
/// to ~1e-13, a relative change of the Rayleigh–Ritz values far below the
/// 1e-10 the refinement resolves.
const ONE_PASS_CONDITION: f64 = 1e3;

/// Block Davidson refinement of Lanczos' modes with precise products
/// (see [`lowest_modes_refined`]), then the certificate.
pub(super) fn refine(
    op: &mut Operator,
    products: &StiffnessProducts,
    run: Refinement,
    lanczos_values: Vec<f64>,
    lanczos_vectors: Mat<f64>,
) -> Result<KrylovModes, EigenFailure> {
    let n = lanczos_vectors.nrows();
    let mut p = lanczos_values.len();
    let mut factorizations = run.factorizations;
    let deflate_block = |op: &Operator, w: &mut Mat<f64>| {
        for c in 0..w.ncols() {
            op.deflate(w.col_as_slice_mut(c));
        }
    };
    let mut pool = Pool::new(n);
    let empty = Mat::<f64>::zeros(n, 0);
    let mut start = lanczos_vectors;
    deflate_block(op, &mut start);
    // The state: Ritz vectors X, K X, M X and values θ. Starting from an
    // empty block, the first extension is the Lanczos block itself.
    let (mut x, mut kx, mut mx) = (empty.clone(), empty.clone(), empty.clone());
    let mut theta: Vec<f64> = Vec::new();
    let mut pending = Some(start);
    let mut bounds: Vec<f64> = Vec::new();
    let mut certified = false;
    let mut perturbation = 0.0f64;
    for round in 0..3 {
        let mut previous_worst = f64::INFINITY;
        for step in 0..=REFINE_STEPS {
            if let Some(w) = pending.take() {
                // Rayleigh–Ritz on [X, W] with the precise products.
                let w = orthonormalize_against(op, &mut pool, &x, &mx, w)?;
                // M X is formed again below: its block serves K W.
                pool.give(std::mem::replace(&mut mx, Mat::zeros(0, 0)));
                let kw = pool.k_block(products, &w);
                let (q, s) = (x.ncols(), x.ncols() + w.ncols());
                let xkw = mm(x.transpose(), kw.as_ref());
                let wkw = mm(w.transpose(), kw.as_ref());
                let a = Mat::from_fn(s, s, |i, j| match (i < q, j < q) {
                    (true, true) => {
                        if i == j {
                            theta[i]
                        } else {
                            0.0
                        }
                    }
                    (true, false) => xkw[(i, j - q)],
                    (false, true) => xkw[(j, i - q)],
                    (false, false) => 0.5 * (wkw[(i - q, j - q)] + wkw[(j - q, i - q)]),
                });
                let (vals, vecs) = symmetric_eigen_qr(&a, Par::Seq)?;
                let mut order: Vec<usize> = (0..s).collect();
                order.sort_by(|&i, &j| vals[i].total_cmp(&vals[j]));
                let keep = p.min(s);
                theta = order.iter().take(keep).map(|&i| vals[i]).collect();
                let y_top = Mat::from_fn(q, keep, |r, c| vecs[(r, order[c])]);
                let y_bot = Mat::from_fn(s - q, keep, |r, c| vecs[(q + r, order[c])]);
                if q == 0 {
                    // The first extension: X and K X are W's and K W's
                    // own blocks, turned in place.
                    pool.give(std::mem::replace(&mut x, w));
                    pool.give(std::mem::replace(&mut kx, kw));
                    pool.combine_into(&mut x, y_bot.as_ref(), None);
                    pool.combine_into(&mut kx, y_bot.as_ref(), None);
                } else {
                    let w_part = (w.as_ref(), y_bot.as_ref());
                    let k_part = (kw.as_ref(), y_bot.as_ref());
                    pool.combine_into(&mut x, y_top.as_ref(), Some(w_part));
                    pool.combine_into(&mut kx, y_top.as_ref(), Some(k_part));
                    pool.give(w);
                    pool.give(kw);
                }
                mx = pool.m_block(op.m(), &x);
            }
            if step == REFINE_STEPS {
                break;
            }
            // Residuals r = Kx − θMx, the preconditioned w = P⁻¹r made
            // M-orthogonal to the block (r is Euclidean-orthogonal to it
            // by Galerkin, so (K − σM)⁻¹r is M-orthogonal to the block's
            // modes; P is accurate away from the lowest modes).
            let keep = x.ncols();
            let mut w = pool.take(keep);
            for (j, &t) in theta.iter().enumerate().take(keep) {
                let (kxj, mxj) = (kx.col_as_slice(j), mx.col_as_slice(j));
                for ((wij, k), m) in w.col_as_slice_mut(j).iter_mut().zip(kxj).zip(mxj) {
                    *wij = k - t * m;
                }
            }
            op.shifted.solve_block(w.as_mut());
            deflate_block(op, &mut w);
            let c = mm(mx.transpose(), w.as_ref());
            sub_mm(&mut w, x.as_ref(), c.as_ref());
            bounds = (0..keep)
                .map(|j| {
                    // |θ − λ| ≤ η² (|θ − σ| + δ)/δ with η² = rᵀ(K − σM)⁻¹r
                    // and δ the gap to the nearest other eigenvalue (a
                    // component cₖ of x along mode k adds cₖ²|λₖ − λ| to the
                    // Rayleigh quotient's error and cₖ²(λₖ − θ)²/(λₖ − σ)
                    // to η²); twice that for P standing in for K − σM.
                    // r formed again (no block kept for it).
                    let (kxj, mxj, wj) =
                        (kx.col_as_slice(j), mx.col_as_slice(j), w.col_as_slice(j));
                    let eta2 = (0..n)
                        .map(|i| (kxj[i] - theta[j] * mxj[i]) * wj[i])
                        .sum::<f64>()
                        .abs();
                    let t = theta[j];
                    let gap = theta
                        .iter()
                        .enumerate()
                        .filter(|&(i, v)| i != j && (v - t).abs() > 1e-6 * t.abs())
                        .map(|(_, v)| (v - t).abs())
                        .fold(f64::INFINITY, f64::min);
                    if gap.is_finite() {
                        2.0 * eta2 * ((t - run.sigma).abs() + gap) / gap
                    } else {
                        f64::INFINITY
                    }
                })
                .collect();
            let worst = bounds
                .iter()
                .zip(&theta)
                .take(run.wanted)
                .fold(0.0f64, |a, (b, t)| a.max(b / t.abs()));
            let stalled = worst >= 0.5 * previous_worst;
            if worst <= RESOLVED || stalled || step + 1 == REFINE_STEPS {
                pool.give(w);
                break;
            }
            previous_worst = worst;
            // Only the modes not yet resolved (the wanted ones and the
            // guard) extend the block: a resolved mode's correction is
            // round-off, and each column costs its precise product.
            let active: Vec<usize> = (0..keep)
                .filter(|&j| bounds[j] > RESOLVED * theta[j].abs() || bounds[j].is_nan())
                .collect();
            for (c, &j) in active.iter().enumerate() {
                if c != j {
                    let (mut to, from) = w.as_mut().two_cols_mut(c, j);
                    to.copy_from(from.as_ref());
                }
            }
            w.truncate(n, active.len());
            pending = Some(w);
        }
        // The spare blocks go before the count's factorization.
        pool.free.clear();
        // The factor's perturbation of the pencil, as seen on these modes.
        perturbation = lanczos_values
            .iter()
            .zip(&theta)
            .fold(0.0f64, |a, (l, t)| a.max((l - t).abs()));
        // The certificate: the count below a point in the gap above the
        // wanted modes, when the factor's perturbation is far below that gap.
        let w = run.wanted.min(theta.len());
        if w == 0 {
            certified = true;
            break;
        }
        let top = theta[w - 1];
        let (tau, half_gap) = match theta.get(w) {
            Some(&next) if next > top => (0.5 * (top + next), 0.5 * (next - top)),
            _ => {
                let d = 1e-8 * top.abs().max(f64::MIN_POSITIVE);
                (top + d, d)
            }
        };
        if 10.0 * perturbation >= half_gap {
            break;
        }
        let zeros = if tau > 0.0 { run.deflated } else { 0 };
        let below = op.shifted.count_below(tau)?;
        factorizations += 1;
        let missing = below.saturating_sub(w + zeros);
        if missing == 0 {
            certified = true;
            break;
        }
        // Modes were skipped: go on with fresh directions (one per missing
        // mode and a few more) beside the found ones.
        p += missing;
        pending = Some(Mat::from_fn(n, missing + GUARD, |i, c| {
            scrambled(i, round * 7 + c)
        }));
    }
    let w = run.wanted.min(theta.len());
    let guard_values = theta[w..].to_vec();
    let vectors = x.subcols(0, w).to_owned();
    bounds.truncate(w);
    theta.truncate(w);
    Ok(KrylovModes {
        values: theta,
        vectors,
        shift: run.sigma,
        steps: run.steps,
        factorizations,
        residuals: bounds,
        guard_values,
        certified,
        perturbation,
    })
}
