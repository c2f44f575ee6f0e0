//! Eigenvectors of a symmetric tridiagonal matrix T for given eigenvalues,
//! by inverse iteration (Wilkinson, *The Algebraic Eigenvalue Problem*,
//! ch. 9; Golub & Van Loan §8.2.2). In the modal analysis T is the
//! tridiagonal form of L⁻¹KL⁻ᵀ, eigenvalues ω² [SI: rad²/s²].
//!
//! T is scaled to ‖T‖∞ = 1 so that pivots, growth and tolerances are O(1).
//! For every wanted eigenvalue λⱼ, (T − σⱼI) yⱼ = bⱼ is solved by Gaussian
//! elimination with partial pivoting (a pivot below ε is raised to it), all
//! shifts side by side so that their recurrences are independent and
//! vectorize, from fixed quasi-random start vectors. Eigenvalues closer than
//! [`CLUSTER_GAP`]·‖T‖ to their neighbour form a cluster: after every solve
//! each vector is orthogonalized against the earlier vectors of its cluster
//! (classical Gram–Schmidt; a second pass where the first cancelled much of
//! the vector, the DGKS criterion) and normalized, and repeated shifts inside
//! a cluster are moved apart by 2ε‖T‖ so that each has its own
//! factorization. Iteration stops as soon as every vector grew to
//! ‖y‖ ≥ 1/(10nε), i.e. a residual ‖(T − σI)ŷ‖ ≤ 10nε‖T‖; with eigenvalues
//! from bisection (accurate to a few ε‖T‖) that is the first solve.
//! Orthogonalizing after the solve adds at most a unit residual per earlier
//! cluster member (their components in y are those of the start vector
//! divided by λₖ − σ), so the residual stays of order w·10nε‖T‖.
//!
//! Accuracy: residuals ‖Ty − λy‖ of order nε‖T‖; orthonormal to a few ε
//! inside a cluster. Across clusters a vector keeps components of order
//! ε‖T‖/gap ≤ 10²ε along the other eigenvectors (times the ratio of the
//! start vector's components, which a second solve would square away; the
//! wide cluster gap makes that unnecessary). The three rigid-body
//! modes of a free assembly (eigenvalues ~ε‖T‖, one cluster) come out as an
//! orthonormal basis of their invariant subspace.

use super::eigen::EigenFailure;
use super::small_eigen::{dot, Tridiagonal};

/// Eigenvalues closer than this fraction of ‖T‖∞ share a cluster (their
/// inverse-iteration vectors are orthogonalized against each other).
pub const CLUSTER_GAP: f64 = 1e-2;

/// A Gram–Schmidt pass that leaves less than this fraction of a vector's
/// norm is repeated (DGKS criterion).
const REORTHOGONALIZE: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Inverse-iteration steps allowed before giving up.
const MAX_INVERSE_STEPS: usize = 8;

/// T − σⱼI = PⱼLⱼUⱼ for several shifts at once, by Gaussian elimination
/// with partial pivoting (Uⱼ has two superdiagonals, Lⱼ is unit lower
/// bidiagonal). Every array is row-major n × shifts, so the loops over the
/// shifts are independent and vectorize; the pivot choice is a select on a
/// bit mask, not a branch (it is data-dependent and would mispredict).
struct MultiShiftLu {
    shifts: usize,
    inv_u0: Vec<f64>,
    u1: Vec<f64>,
    u2: Vec<f64>,
    mult: Vec<f64>,
    /// All ones where rows i and i+1 were swapped, else zero.
    swap: Vec<u64>,
}

/// `b` where `mask` is all ones, `a` where it is zero.
#[inline(always)]
fn select(mask: u64, a: f64, b: f64) -> f64 {
    f64::from_bits((a.to_bits() & !mask) | (b.to_bits() & mask))
}

impl MultiShiftLu {
    /// Factor T − σⱼI for every shift; pivots below `floor` are raised to it.
    fn factor(t: &Tridiagonal, shifts: &[f64], floor: f64) -> Self {
        let (n, w) = (t.diag.len(), shifts.len());
        let mut lu = MultiShiftLu {
            shifts: w,
            inv_u0: vec![0.0; n * w],
            u1: vec![0.0; n * w],
            u2: vec![0.0; n * w],
            mult: vec![0.0; n * w],
            swap: vec![0; n * w],
        };
        // 1/U₀ is stored; a pivot below the floor counts as ±floor.
        let big = 1.0 / floor;
        // The current row i of each factorization, at columns i and i+1.
        let mut a: Vec<f64> = shifts.iter().map(|s| t.diag[0] - s).collect();
        let mut b = vec![t.off.first().copied().unwrap_or(0.0); w];
        for i in 0..n - 1 {
            let (sub, beyond) = (t.off[i], t.off.get(i + 1).copied().unwrap_or(0.0));
            let r = i * w..(i + 1) * w;
            let (u0, u1, u2) = (
                &mut lu.inv_u0[r.clone()],
                &mut lu.u1[r.clone()],
                &mut lu.u2[r.clone()],
            );
            let (mult, swap) = (&mut lu.mult[r.clone()], &mut lu.swap[r]);
            let (a, b, shifts) = (&mut a[..w], &mut b[..w], &shifts[..w]);
            for j in 0..w {
                let next = t.diag[i + 1] - shifts[j];
                let sw = u64::from(a[j].abs() < sub.abs()).wrapping_neg();
                let piv = select(sw, a[j], sub);
                let other = select(sw, sub, a[j]);
                let inv = 1.0 / piv;
                // A zero pivot has a zero column below it: no elimination.
                let l = if piv == 0.0 { 0.0 } else { other * inv };
                u0[j] = if piv.abs() >= floor {
                    inv
                } else {
                    big.copysign(piv)
                };
                u1[j] = select(sw, b[j], next);
                u2[j] = select(sw, 0.0, beyond);
                (mult[j], swap[j]) = (l, sw);
                let na = select(sw, next - l * b[j], b[j] - l * next);
                b[j] = select(sw, beyond, -l * beyond);
                a[j] = na;
            }
        }
        for (u, &piv) in lu.inv_u0[(n - 1) * w..].iter_mut().zip(&a) {
            *u = if piv.abs() >= floor {
                1.0 / piv
            } else {
                big.copysign(piv)
            };
        }
        lu
    }

    /// Y ← (T − σⱼI)⁻¹ Y column by column (Y row-major n × shifts).
    fn solve(&self, y: &mut [f64]) {
        let w = self.shifts;
        let n = y.len() / w;
        for i in 0..n - 1 {
            let (top, bottom) = y[i * w..(i + 2) * w].split_at_mut(w);
            let (mult, swap) = (
                &self.mult[i * w..(i + 1) * w],
                &self.swap[i * w..(i + 1) * w],
            );
            for j in 0..w {
                let p = select(swap[j], top[j], bottom[j]);
                let q = select(swap[j], bottom[j], top[j]);
                top[j] = p;
                bottom[j] = q - mult[j] * p;
            }
        }
        for i in (0..n).rev() {
            let r = i * w..(i + 1) * w;
            let (inv, u1, u2) = (&self.inv_u0[r.clone()], &self.u1[r.clone()], &self.u2[r]);
            let (head, below) = y.split_at_mut((i + 1) * w);
            let yi = &mut head[i * w..];
            if i + 2 < n {
                let (y1, y2) = below.split_at(w);
                for j in 0..w {
                    yi[j] = (yi[j] - u1[j] * y1[j] - u2[j] * y2[j]) * inv[j];
                }
            } else if i + 1 < n {
                for j in 0..w {
                    yi[j] = (yi[j] - u1[j] * below[j]) * inv[j];
                }
            } else {
                for j in 0..w {
                    yi[j] *= inv[j];
                }
            }
        }
    }
}

/// Unit eigenvectors of T for the given eigenvalues (ascending), as a
/// row-major n × values.len() block (row i holds component i of every
/// vector).
pub fn tridiagonal_eigenvectors(t: &Tridiagonal, values: &[f64]) -> Result<Vec<f64>, EigenFailure> {
    let (n, w) = (t.diag.len(), values.len());
    if n <= 1 || w == 0 {
        return Ok(vec![1.0; n * w]);
    }
    // Work on T/‖T‖, so that pivots, growth and tolerances are O(1) and
    // nothing can overflow.
    let norm = t.norm_inf();
    if norm == 0.0 {
        // T = 0: every vector is an eigenvector; take the unit vectors.
        let mut y = vec![0.0; n * w];
        (0..w).for_each(|j| y[j * w + j] = 1.0);
        return Ok(y);
    }
    if !norm.is_finite() {
        return Err(EigenFailure::NoConvergence);
    }
    let scaled = Tridiagonal {
        diag: t.diag.iter().map(|d| d / norm).collect(),
        off: t.off.iter().map(|e| e / norm).collect(),
    };
    let floor = f64::EPSILON;
    let accept = 10.0 * n as f64 * f64::EPSILON;
    // Clusters and shifts (repeated shifts in a cluster moved apart).
    let mut cluster = vec![0; w];
    let mut shifts = vec![0.0; w];
    for j in 0..w {
        let lambda = values[j] / norm;
        if j > 0 && lambda - values[j - 1] / norm <= CLUSTER_GAP {
            cluster[j] = cluster[j - 1];
            shifts[j] = lambda.max(shifts[j - 1] + 2.0 * floor);
        } else {
            cluster[j] = j;
            shifts[j] = lambda;
        }
    }
    let lu = MultiShiftLu::factor(&scaled, &shifts, floor);
    let mut y = start_block(n, w);
    let mut accepted = vec![false; w];
    let (mut cols, mut growth) = (vec![0.0; n * w], vec![0.0; w]);
    for _ in 0..MAX_INVERSE_STEPS {
        lu.solve(&mut y);
        orthonormalize(&mut y, &mut cols, &cluster, &mut growth);
        for (a, &g) in accepted.iter_mut().zip(&growth) {
            if !(g.is_finite() && g > 0.0) {
                return Err(EigenFailure::NoConvergence);
            }
            *a |= g * accept >= 1.0;
        }
        if accepted.iter().all(|&a| a) {
            return Ok(y);
        }
    }
    Err(EigenFailure::NoConvergence)
}

/// Orthonormalize the columns of the row-major n × w block `y` in order,
/// each against the earlier columns of its cluster (classical Gram–Schmidt,
/// twice, on column copies in the scratch `cols`); returns in `norms` each
/// column's norm after orthogonalization, before normalization. A column
/// alone in its cluster is only normalized, in place.
fn orthonormalize(y: &mut [f64], cols: &mut [f64], cluster: &[usize], norms: &mut [f64]) {
    let w = cluster.len();
    let n = y.len() / w;
    norms.fill(0.0);
    for row in y.chunks_exact(w) {
        norms.iter_mut().zip(row).for_each(|(s, v)| *s += v * v);
    }
    norms.iter_mut().for_each(|s| *s = s.sqrt());
    // Lone columns are scaled below; clusters are orthonormalized here.
    let mut scale = vec![1.0; w];
    let mut start = 0;
    while start < w {
        let end = (start + 1..w)
            .find(|&j| cluster[j] != cluster[start])
            .unwrap_or(w);
        if end - start > 1 {
            orthonormalize_cluster(y, &mut cols[..n * (end - start)], start..end, norms);
        } else {
            scale[start] = 1.0 / norms[start];
        }
        start = end;
    }
    for row in y.chunks_exact_mut(w) {
        row.iter_mut().zip(&scale).for_each(|(v, s)| *v *= s);
    }
}

/// Classical Gram–Schmidt of the columns `range` of the row-major block `y`
/// (one cluster), through column-major copies in `cols`, with a second pass
/// for a column whose first pass cancelled more than 1 − 1/√2 of its norm
/// (Daniel, Gragg, Kaufman & Stewart, Math. Comp. 30 (1976) 772–795: twice
/// is enough, once is enough without that cancellation). `norms[range]`
/// holds the column norms before and, on return, after orthogonalization.
fn orthonormalize_cluster(
    y: &mut [f64],
    cols: &mut [f64],
    range: std::ops::Range<usize>,
    norms: &mut [f64],
) {
    let n = cols.len() / range.len();
    let w = y.len() / n;
    let first = range.start;
    for (i, row) in y.chunks_exact(w).enumerate() {
        for (c, &v) in row[range.clone()].iter().enumerate() {
            cols[c * n + i] = v;
        }
    }
    let mut coef = vec![0.0; range.len()];
    for c in 0..range.len() {
        let (earlier, rest) = cols.split_at_mut(c * n);
        let x = &mut rest[..n];
        let coef = &mut coef[..c];
        // The norm before orthogonalization (from the caller's pass).
        let mut before = norms[first + c];
        let mut norm = before;
        // (The cluster's first column has nothing to be orthogonal to.)
        let passes = if c == 0 { 0 } else { 2 };
        for _ in 0..passes {
            // All coefficients against the same x (independent dots), then
            // one pass of updates.
            for (k, q) in coef.iter_mut().zip(earlier.chunks_exact(n)) {
                *k = dot(q, x);
            }
            for (&k, q) in coef.iter().zip(earlier.chunks_exact(n)) {
                x.iter_mut().zip(q).for_each(|(a, b)| *a -= k * b);
            }
            norm = dot(x, x).sqrt();
            // DGKS: a second pass only if this one cancelled much of x.
            if norm >= REORTHOGONALIZE * before {
                break;
            }
            before = norm;
        }
        norms[first + c] = norm;
        let inv = 1.0 / norm;
        x.iter_mut().for_each(|a| *a *= inv);
    }
    for (i, row) in y.chunks_exact_mut(w).enumerate() {
        for (c, v) in row[range.clone()].iter_mut().enumerate() {
            *v = cols[c * n + i];
        }
    }
}

/// Fixed start vectors in [−0.5, 0.5) (an integer hash of row and
/// column, different for every column), row-major n × w.
fn start_block(n: usize, w: usize) -> Vec<f64> {
    const SCALE: f64 = 1.0 / (1u64 << 53) as f64;
    let mut y = Vec::with_capacity(n * w);
    for i in 1..=n as u64 {
        let hi = i.wrapping_mul(0x9e37_79b9_7f4a_7c15);
        y.extend((1..=w as u64).map(|j| {
            let h = hi.wrapping_add(j.wrapping_mul(0xbf58_476d_1ce4_e5b9));
            let h = (h ^ (h >> 29)).wrapping_mul(0x94d0_49bb_1331_11eb);
            // h >> 11 < 2⁵³ converts exactly, and as i64 in one instruction.
            ((h >> 11) as i64) as f64 * SCALE - 0.5
        }));
    }
    y
}
