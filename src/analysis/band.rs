//! Sparse storage and a banded LU factorization for large reduced problems.
//!
//! The reduced stiffness and mass of a beam model are banded (a node couples
//! only to its neighbours) apart from a small block of constrained
//! coordinates. [`BandLu`] reorders the unknowns symmetrically by reverse
//! Cuthill–McKee (from the non-zero pattern), then factors P A = L U with
//! partial pivoting inside the band: with lower bandwidth b the upper band of
//! U grows to at most 2b, and the elimination touches only the band, so the
//! cost is O(n·b²) and the storage O(n·b). Units are those of the matrix.

use faer::Mat;

/// A square matrix in compressed sparse row form (exact zeros dropped).
#[derive(Debug, Clone)]
pub struct Csr {
    n: usize,
    row_start: Vec<usize>,
    cols: Vec<usize>,
    vals: Vec<f64>,
}

impl Csr {
    /// `a + s·b` of two dense square matrices, keeping the non-zeros (O(n²)).
    pub fn combine(a: &Mat<f64>, s: f64, b: &Mat<f64>) -> Csr {
        let n = a.nrows();
        let mut row_start = Vec::with_capacity(n + 1);
        let (mut cols, mut vals) = (Vec::new(), Vec::new());
        row_start.push(0);
        for i in 0..n {
            for j in 0..n {
                let (x, y) = (a[(i, j)], b[(i, j)]);
                if x != 0.0 || y != 0.0 {
                    cols.push(j);
                    vals.push(x + s * y);
                }
            }
            row_start.push(cols.len());
        }
        Csr {
            n,
            row_start,
            cols,
            vals,
        }
    }

    /// The non-zeros of a dense square matrix.
    pub fn from_dense(a: &Mat<f64>) -> Csr {
        let zero = Mat::zeros(a.nrows(), a.ncols());
        Csr::combine(a, 0.0, &zero)
    }

    pub fn n(&self) -> usize {
        self.n
    }

    /// y = A x.
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        for (i, yi) in y.iter_mut().enumerate().take(self.n) {
            let r = self.row_start[i]..self.row_start[i + 1];
            *yi = self.cols[r.clone()]
                .iter()
                .zip(&self.vals[r])
                .map(|(&j, v)| v * x[j])
                .sum();
        }
    }

    /// y = |A| |x| (entrywise absolute values: the round-off scale of A x).
    pub fn mul_abs(&self, x: &[f64], y: &mut [f64]) {
        for (i, yi) in y.iter_mut().enumerate().take(self.n) {
            let r = self.row_start[i]..self.row_start[i + 1];
            *yi = self.cols[r.clone()]
                .iter()
                .zip(&self.vals[r])
                .map(|(&j, v)| (v * x[j]).abs())
                .sum();
        }
    }

    /// Diagonal entry i.
    pub fn diagonal(&self, i: usize) -> f64 {
        let r = self.row_start[i]..self.row_start[i + 1];
        self.cols[r.clone()]
            .iter()
            .zip(&self.vals[r])
            .find(|(&j, _)| j == i)
            .map_or(0.0, |(_, &v)| v)
    }
}

/// The matrix is singular to working precision at this (reordered) column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingularBand {
    pub column: usize,
}

/// P A Q = L U of a sparse matrix with a symmetric RCM ordering Q and row
/// pivoting P confined to the band.
#[derive(Debug, Clone)]
pub struct BandLu {
    n: usize,
    /// Position k holds original unknown `order[k]`.
    order: Vec<usize>,
    /// Lower bandwidth after reordering.
    kl: usize,
    /// Row width of the band storage: columns i − kl ..= i + 2kl.
    width: usize,
    /// U (and, before elimination, A) row-major in band storage.
    band: Vec<f64>,
    /// Multipliers of column k: rows k+1 ..= k+kl, stored at k·kl.
    lower: Vec<f64>,
    /// Row swapped with row k at step k.
    pivot: Vec<usize>,
}

impl BandLu {
    /// Reorder and factor `a`.
    pub fn factor(a: &Csr) -> Result<BandLu, SingularBand> {
        let n = a.n;
        let order = reverse_cuthill_mckee(a);
        let mut position = vec![0; n];
        for (k, &i) in order.iter().enumerate() {
            position[i] = k;
        }
        let mut kl = 0;
        for i in 0..n {
            for &j in &a.cols[a.row_start[i]..a.row_start[i + 1]] {
                kl = kl.max(position[i].abs_diff(position[j]));
            }
        }
        let width = 3 * kl + 1;
        let mut band = vec![0.0; n * width];
        for i in 0..n {
            let pi = position[i];
            for idx in a.row_start[i]..a.row_start[i + 1] {
                let pj = position[a.cols[idx]];
                band[pi * width + pj + kl - pi] += a.vals[idx];
            }
        }
        let mut lu = BandLu {
            n,
            order,
            kl,
            width,
            band,
            lower: vec![0.0; n * kl],
            pivot: vec![0; n],
        };
        let mut row_max = vec![0.0f64; n];
        for i in 0..n {
            for v in &a.vals[a.row_start[i]..a.row_start[i + 1]] {
                row_max[position[i]] = row_max[position[i]].max(v.abs());
            }
        }
        lu.eliminate(&row_max)?;
        Ok(lu)
    }

    /// Lower bandwidth after reordering.
    pub fn bandwidth(&self) -> usize {
        self.kl
    }

    fn at(&self, i: usize, j: usize) -> usize {
        i * self.width + j + self.kl - i
    }

    /// Singular if a pivot is ≤ n·ε times the largest original entry of its
    /// column (columns differ in units: positions vs slopes; A symmetric,
    /// so row maxima are column maxima).
    fn eliminate(&mut self, row_max: &[f64]) -> Result<(), SingularBand> {
        let (n, kl) = (self.n, self.kl);
        for (k, &col_max) in row_max.iter().enumerate() {
            let last_row = (k + kl).min(n - 1);
            let last_col = (k + 2 * kl).min(n - 1);
            let p = (k..=last_row)
                .max_by(|&a, &b| {
                    let (x, y) = (self.band[self.at(a, k)], self.band[self.at(b, k)]);
                    x.abs().total_cmp(&y.abs())
                })
                .unwrap_or(k);
            self.pivot[k] = p;
            let piv = self.band[self.at(p, k)];
            if piv.is_nan() || piv.abs() <= n as f64 * f64::EPSILON * col_max {
                return Err(SingularBand { column: k });
            }
            if p != k {
                for j in k..=last_col {
                    let (a, b) = (self.at(k, j), self.at(p, j));
                    self.band.swap(a, b);
                }
            }
            let row_k = self.at(k, k);
            for i in k + 1..=last_row {
                let f = self.band[self.at(i, k)] / piv;
                self.lower[k * kl + (i - k - 1)] = f;
                if f == 0.0 {
                    continue;
                }
                let row_i = self.at(i, k);
                for d in 1..=(last_col - k) {
                    self.band[row_i + d] -= f * self.band[row_k + d];
                }
            }
        }
        Ok(())
    }

    /// Solve A x = b in place (`work` has length n).
    pub fn solve(&self, b: &mut [f64], work: &mut [f64]) {
        let (n, kl) = (self.n, self.kl);
        for (k, &i) in self.order.iter().enumerate() {
            work[k] = b[i];
        }
        for k in 0..n {
            work.swap(k, self.pivot[k]);
            let wk = work[k];
            let last_row = (k + kl).min(n - 1);
            let l = &self.lower[k * kl..k * kl + (last_row - k)];
            for (wi, li) in work[k + 1..=last_row].iter_mut().zip(l) {
                *wi -= li * wk;
            }
        }
        for k in (0..n).rev() {
            let last_col = (k + 2 * kl).min(n - 1);
            let row = self.at(k, k);
            let mut s = work[k];
            for d in 1..=(last_col - k) {
                s -= self.band[row + d] * work[k + d];
            }
            work[k] = s / self.band[row];
        }
        for (k, &i) in self.order.iter().enumerate() {
            b[i] = work[k];
        }
    }
}

/// Reverse Cuthill–McKee ordering of the symmetric pattern of `a`.
fn reverse_cuthill_mckee(a: &Csr) -> Vec<usize> {
    let n = a.n;
    let mut adj: Vec<Vec<usize>> = vec![Vec::new(); n];
    for i in 0..n {
        for &j in &a.cols[a.row_start[i]..a.row_start[i + 1]] {
            if i != j {
                adj[i].push(j);
                adj[j].push(i);
            }
        }
    }
    for l in &mut adj {
        l.sort_unstable();
        l.dedup();
    }
    super::lu::rcm_order(&adj)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_banded_system_needing_pivots_and_reordering() {
        // Tridiagonal with zero diagonal in a scrambled numbering plus one
        // dense row/column (a "constraint"): x known, b = A x.
        let n = 40;
        let perm: Vec<usize> = (0..n).map(|i| (i * 17 + 5) % n).collect();
        let mut a = Mat::<f64>::zeros(n, n);
        for i in 0..n {
            a[(perm[i], perm[i])] = if i % 3 == 0 { 0.0 } else { 2.0 + i as f64 };
            if i + 1 < n {
                a[(perm[i], perm[i + 1])] = 1.0 + 0.1 * i as f64;
                a[(perm[i + 1], perm[i])] = -0.5;
            }
        }
        for i in 0..n {
            a[(perm[n - 1], perm[i])] += 0.3;
            a[(perm[i], perm[n - 1])] += 0.7;
        }
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin() + 0.1).collect();
        let mut b: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| a[(i, j)] * x[j]).sum())
            .collect();
        let lu = BandLu::factor(&Csr::from_dense(&a)).expect("non-singular");
        let mut w = vec![0.0; n];
        lu.solve(&mut b, &mut w);
        for i in 0..n {
            assert!((b[i] - x[i]).abs() < 1e-12, "x[{i}] = {} vs {}", b[i], x[i]);
        }
    }

    #[test]
    fn reports_a_singular_matrix() {
        let a = Mat::from_fn(3, 3, |i, j| ((i + 1) * (j + 1)) as f64);
        assert!(
            BandLu::factor(&Csr::from_dense(&a)).is_err(),
            "rank-1 matrix"
        );
    }
}
