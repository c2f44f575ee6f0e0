//! Reduction of a constrained linear problem to its free coordinates.
//!
//! Given C_q (m × n), an orthonormal basis N of null(C_q) is built so that
//! K_r = NᵀKN, M_r = NᵀMN. Only the coordinates that some constraint touches
//! need the factorization (Householder QR of the independent rows); all
//! others map to themselves, so N stays sparse and the
//! reduction costs O(n²) instead of O(n³). Rows are normalized first, so a
//! rotational row [rad] and a positional row [m] weigh alike; constraints
//! whose rows add nothing (e.g. a second clamp of the same node) are named.

use super::householder::reflector;
use super::small_eigen::dot;
use faer::Mat;

/// Relative singular value below which a constraint row is dependent.
pub const RANK_TOLERANCE: f64 = 1e-10;

/// The null-space map q = N q_r.
#[derive(Debug, Clone)]
pub struct NullSpace {
    /// Coordinates no constraint touches (identity part of N).
    pub free: Vec<usize>,
    /// Coordinates touched by constraints.
    pub involved: Vec<usize>,
    /// Basis of the null space on `involved` (|involved| × k).
    pub basis: Mat<f64>,
    /// Rows of C_q that are linearly dependent on earlier rows.
    pub redundant_rows: Vec<usize>,
}

impl NullSpace {
    /// Null space of C_q (m × n).
    pub fn new(cq: &Mat<f64>) -> NullSpace {
        let (m, n) = (cq.nrows(), cq.ncols());
        // Column j of C_q is contiguous (column-major): touched if any entry is nonzero.
        let touched: Vec<bool> = (0..n)
            .map(|j| cq.col_as_slice(j).iter().any(|&v| v != 0.0))
            .collect();
        let involved: Vec<usize> = (0..n).filter(|&j| touched[j]).collect();
        let free: Vec<usize> = (0..n).filter(|&j| !touched[j]).collect();
        let d = involved.len();
        // Rows restricted to the involved coordinates and normalized,
        // row-major m × d.
        let mut rows = vec![0.0; m * d];
        for (k, &g) in involved.iter().enumerate() {
            for (i, &v) in cq.col_as_slice(g).iter().enumerate() {
                rows[i * d + k] = v;
            }
        }
        for row in rows.chunks_exact_mut(d.max(1)) {
            // (A zero row stays zero and counts as dependent below.)
            let norm = dot(row, row).sqrt();
            if norm > 0.0 {
                let inv = 1.0 / norm;
                row.iter_mut().for_each(|v| *v *= inv);
            }
        }
        let redundant_rows = dependent_rows(&rows, m, d);
        let basis = null_basis(&rows, d, &redundant_rows);
        NullSpace {
            free,
            involved,
            basis,
            redundant_rows,
        }
    }

    /// Number of free (reduced) coordinates.
    pub fn dim(&self) -> usize {
        self.free.len() + self.basis.ncols()
    }

    /// NᵀAN for a symmetric n × n matrix A: the free–free block copied,
    /// then AZ on the involved columns (one axpy per nonzero of Z) for the
    /// free–basis block and ZᵀAZ (symmetrized) for the basis block.
    pub fn project(&self, a: &Mat<f64>) -> Mat<f64> {
        let (f, k, n) = (self.free.len(), self.basis.ncols(), a.nrows());
        let mut out = Mat::zeros(f + k, f + k);
        let runs = free_runs(&self.free);
        for (j, &gj) in self.free.iter().enumerate() {
            let (src, dst) = (a.col_as_slice(gj), out.col_as_slice_mut(j));
            for &(at, from, len) in &runs {
                dst[at..at + len].copy_from_slice(&src[from..from + len]);
            }
        }
        if k == 0 {
            return out;
        }
        // az[:, c] = A Z[:, c] over the involved coordinates (n × k, column-major).
        let mut az = vec![0.0; n * k];
        for (c, col) in az.chunks_exact_mut(n).enumerate() {
            for (r, &g) in self.involved.iter().enumerate() {
                let z = self.basis[(r, c)];
                if z != 0.0 {
                    col.iter_mut()
                        .zip(a.col_as_slice(g))
                        .for_each(|(t, s)| *t += z * s);
                }
            }
        }
        for (c, col) in az.chunks_exact(n).enumerate() {
            let dst = &mut out.col_as_slice_mut(f + c)[..f];
            for &(at, from, len) in &runs {
                dst[at..at + len].copy_from_slice(&col[from..from + len]);
            }
            for (i, &gi) in self.free.iter().enumerate() {
                out[(f + c, i)] = col[gi];
            }
        }
        // (AZ) restricted to the involved rows, d × k column-major; then
        // ZᵀAZ from contiguous dot products, symmetrized.
        let d = self.involved.len();
        let mut az_inv = vec![0.0; d * k];
        for (dst, col) in az_inv.chunks_exact_mut(d).zip(az.chunks_exact(n)) {
            for (t, &g) in dst.iter_mut().zip(&self.involved) {
                *t = col[g];
            }
        }
        let zaz =
            |c1: usize, c2: usize| dot(self.basis.col_as_slice(c1), &az_inv[c2 * d..(c2 + 1) * d]);
        for c1 in 0..k {
            for c2 in 0..=c1 {
                let v = 0.5 * (zaz(c1, c2) + zaz(c2, c1));
                out[(f + c1, f + c2)] = v;
                out[(f + c2, f + c1)] = v;
            }
        }
        out
    }

    /// Nᵀv: a full-length vector restricted to the reduced coordinates
    /// (the transpose of [`NullSpace::expand`]).
    pub fn restrict(&self, v: &[f64]) -> Vec<f64> {
        let mut out: Vec<f64> = self.free.iter().map(|&g| v[g]).collect();
        for k in 0..self.basis.ncols() {
            out.push(
                self.involved
                    .iter()
                    .enumerate()
                    .map(|(r, &g)| self.basis[(r, k)] * v[g])
                    .sum(),
            );
        }
        out
    }

    /// q = N q_r (n = total coordinates).
    pub fn expand(&self, qr: &[f64], n: usize) -> Vec<f64> {
        let mut q = vec![0.0; n];
        for (i, &g) in self.free.iter().enumerate() {
            q[g] = qr[i];
        }
        // Σₖ Z[:, k] q_r[f + k] on the involved coordinates, column by column.
        let f = self.free.len();
        for (k, &x) in qr[f..].iter().enumerate().take(self.basis.ncols()) {
            for (&g, &z) in self.involved.iter().zip(self.basis.col_as_slice(k)) {
                q[g] += z * x;
            }
        }
        q
    }
}

/// Runs of consecutive coordinates in an ascending index list, as
/// (position in the list, first coordinate, length): the free–free block of
/// a projection is then a few contiguous copies per column.
fn free_runs(free: &[usize]) -> Vec<(usize, usize, usize)> {
    let mut runs: Vec<(usize, usize, usize)> = Vec::new();
    for (i, &g) in free.iter().enumerate() {
        match runs.last_mut() {
            Some((at, from, len)) if *from + *len == g && *at + *len == i => *len += 1,
            _ => runs.push((i, g, 1)),
        }
    }
    runs
}

/// Orthonormal basis (d × (d − r)) of the vectors orthogonal to the r
/// independent rows of the row-major m × d block `rows`: Householder QR of
/// those rows as columns, B = Q R, whose last d − r columns of Q are the
/// basis.
fn null_basis(rows: &[f64], d: usize, dependent: &[usize]) -> Mat<f64> {
    // The independent rows, each the column of B it becomes (d long).
    let m = rows.len().checked_div(d).unwrap_or(0);
    let mut b: Vec<f64> = Vec::with_capacity(rows.len());
    for i in (0..m).filter(|i| !dependent.contains(i)) {
        b.extend_from_slice(&rows[i * d..(i + 1) * d]);
    }
    let r = b.len().checked_div(d).unwrap_or(0);
    // Reflector j acts on entries j…d−1 and stays in column j: (vⱼ, βⱼ).
    let mut beta = vec![0.0; r];
    for j in 0..r {
        let (done, rest) = b.split_at_mut((j + 1) * d);
        let v = &mut done[j * d + j..];
        beta[j] = reflector(v).1;
        for other in rest.chunks_exact_mut(d) {
            householder_apply(v, beta[j], &mut other[j..]);
        }
    }
    let mut basis = Mat::zeros(d, d - r);
    for c in 0..d - r {
        let q = basis.col_as_slice_mut(c);
        q[r + c] = 1.0;
        for j in (0..r).rev() {
            householder_apply(&b[j * d + j..(j + 1) * d], beta[j], &mut q[j..]);
        }
    }
    basis
}

/// x ← (I − β v vᵀ) x.
fn householder_apply(v: &[f64], beta: f64, x: &mut [f64]) {
    let s = beta * dot(v, x);
    x.iter_mut().zip(v).for_each(|(xi, vi)| *xi -= s * vi);
}

/// Rows of a row-normalized, row-major m × d block that depend on earlier
/// rows (modified Gram–Schmidt in row order, twice).
fn dependent_rows(rows: &[f64], m: usize, d: usize) -> Vec<usize> {
    let mut basis: Vec<f64> = Vec::with_capacity(rows.len());
    let mut dependent = Vec::new();
    let mut r = vec![0.0; d];
    for i in 0..m {
        r.copy_from_slice(&rows[i * d..(i + 1) * d]);
        for _ in 0..2 {
            for b in basis.chunks_exact(d) {
                let p = dot(&r, b);
                r.iter_mut().zip(b).for_each(|(x, y)| *x -= p * y);
            }
        }
        let norm = dot(&r, &r).sqrt();
        if norm <= RANK_TOLERANCE.sqrt() {
            dependent.push(i);
        } else {
            basis.extend(r.iter().map(|x| x / norm));
        }
    }
    dependent
}
