//! Dense LU factorization with partial pivoting for the small iteration
//! matrices of the time integrator (tens to a few hundred unknowns).
//!
//! Row-major, factor once, solve many times without allocating: the time
//! loop reuses one factorization over many steps, so the back-substitution is
//! the kernel that matters. faer's general LU is faster for large matrices but
//! its per-call overhead dominates at n ≈ 50.
//!
//! The unknowns are first reordered symmetrically by reverse Cuthill–McKee
//! (computed once, from the pattern of the first matrix) so that a constraint
//! sits next to the coordinates it touches; the factors of the banded beam
//! blocks then stay banded. The factors are kept column by column, only
//! from the first to the last non-zero of each column, and the
//! substitutions run by columns (independent updates instead of a chain of
//! short dot products: 850 → 520 ns for the built-in assembly's 50 unknowns).

/// An LU factorization P A = L U (unit lower L) of a square matrix.
#[derive(Debug, Clone)]
pub struct DenseLu {
    n: usize,
    /// The matrix as filled by the caller (original order), row-major.
    input: Vec<f64>,
    /// Symmetric reordering: position k holds original unknown order[k].
    order: Vec<usize>,
    /// L (strictly lower) and U (upper) of the reordered matrix, row-major.
    lu: Vec<f64>,
    perm: Vec<usize>,
    /// Per column j: one past the last non-zero row of L (rows j+1..) and
    /// the first non-zero row of U (rows ..j), so the substitutions skip
    /// the structural zeros of banded blocks.
    l_end: Vec<usize>,
    u_top: Vec<usize>,
    /// Reciprocal pivots.
    inv_diag: Vec<f64>,
    /// The used parts of L and U, column by column, contiguous: column j's
    /// L part starts at `packed_start[j]` (length l_end[j] − j − 1), its U
    /// part follows (length j − u_top[j]).
    packed: Vec<f64>,
    packed_start: Vec<usize>,
    /// Composite of the ordering and the pivoting: solve position k reads
    /// right-hand side entry `gather[k]`.
    gather: Vec<usize>,
}

/// The matrix is singular to working precision at this pivot column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingularPivot {
    pub column: usize,
}

impl DenseLu {
    /// An empty factorization of size n (call [`DenseLu::factor`]).
    pub fn new(n: usize) -> Self {
        DenseLu {
            n,
            input: vec![0.0; n * n],
            order: Vec::new(),
            lu: vec![0.0; n * n],
            perm: (0..n).collect(),
            l_end: vec![0; n],
            u_top: vec![0; n],
            inv_diag: vec![1.0; n],
            packed: Vec::new(),
            packed_start: vec![0; n + 1],
            gather: vec![0; n],
        }
    }

    pub fn size(&self) -> usize {
        self.n
    }

    /// Row-major storage to fill with the matrix before [`DenseLu::factor`].
    pub fn matrix_mut(&mut self) -> &mut [f64] {
        &mut self.input
    }

    /// Factor the matrix stored by [`DenseLu::matrix_mut`] in place.
    pub fn factor(&mut self) -> Result<(), SingularPivot> {
        let n = self.n;
        if self.order.len() != n {
            self.order = reverse_cuthill_mckee(&self.input, n);
        }
        for (k, &i) in self.order.iter().enumerate() {
            for (l, &j) in self.order.iter().enumerate() {
                self.lu[k * n + l] = self.input[i * n + j];
            }
        }
        for (i, p) in self.perm.iter_mut().enumerate() {
            *p = i;
        }
        let scale = self.lu.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let a = &mut self.lu;
        for k in 0..n {
            let mut p = k;
            let mut best = a[k * n + k].abs();
            for i in k + 1..n {
                let v = a[i * n + k].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            if best <= f64::EPSILON * scale * n as f64 || !best.is_finite() {
                return Err(SingularPivot {
                    column: self.order[k],
                });
            }
            if p != k {
                for j in 0..n {
                    a.swap(k * n + j, p * n + j);
                }
                self.perm.swap(k, p);
            }
            let pivot = a[k * n + k];
            let (upper, lower) = a.split_at_mut((k + 1) * n);
            // Only up to the pivot row's last non-zero (banded blocks).
            let row_k = &upper[k * n + k + 1..k * n + n];
            let width = row_k.iter().rposition(|&u| u != 0.0).map_or(0, |j| j + 1);
            let row_k = &row_k[..width];
            for i in 0..n - k - 1 {
                let row = &mut lower[i * n..i * n + n];
                if row[k] != 0.0 {
                    let f = row[k] / pivot;
                    row[k] = f;
                    axpy(&mut row[k + 1..k + 1 + width], row_k, f);
                }
            }
        }
        let a = &self.lu;
        self.packed.clear();
        for j in 0..n {
            let column = |i: usize| a[i * n + j];
            self.l_end[j] = (j + 1..n)
                .rev()
                .find(|&i| column(i) != 0.0)
                .map_or(j + 1, |i| i + 1);
            self.u_top[j] = (0..j).find(|&i| column(i) != 0.0).unwrap_or(j);
            self.inv_diag[j] = 1.0 / column(j);
            self.packed_start[j] = self.packed.len();
            self.packed.extend((j + 1..self.l_end[j]).map(column));
            self.packed.extend((self.u_top[j]..j).map(column));
        }
        self.packed_start[n] = self.packed.len();
        for k in 0..n {
            self.gather[k] = self.order[self.perm[k]];
        }
        Ok(())
    }

    /// Solve A x = b in place (b becomes x); `work` has length n.
    ///
    /// Column-oriented substitutions: once an unknown is known, its column
    /// is subtracted from the rows it reaches (independent updates, so the
    /// loop is bound by throughput rather than by a chain of dot products).
    pub fn solve_in_place(&self, b: &mut [f64], work: &mut [f64]) {
        let n = self.n;
        let work = &mut work[..n];
        for (w, &g) in work.iter_mut().zip(&self.gather) {
            *w = b[g];
        }
        let packed = &self.packed[..];
        for j in 0..n {
            let (p, end) = (self.packed_start[j], self.l_end[j]);
            let (head, tail) = work.split_at_mut(j + 1);
            let x = head[j];
            if x != 0.0 {
                axpy(&mut tail[..end - j - 1], &packed[p..p + end - j - 1], x);
            }
        }
        for j in (0..n).rev() {
            let p = self.packed_start[j] + self.l_end[j] - j - 1;
            let top = self.u_top[j];
            let (head, tail) = work.split_at_mut(j);
            let x = tail[0] * self.inv_diag[j];
            tail[0] = x;
            axpy(&mut head[top..], &packed[p..self.packed_start[j + 1]], x);
        }
        for (&i, &w) in self.order.iter().zip(work.iter()) {
            b[i] = w;
        }
    }
}

/// Reverse Cuthill–McKee ordering of the symmetric pattern of `a` (n × n):
/// breadth-first from a least-connected unknown, neighbours by increasing
/// degree, reversed. Disconnected parts follow one another.
fn reverse_cuthill_mckee(a: &[f64], n: usize) -> Vec<usize> {
    let adjacency: Vec<Vec<usize>> = (0..n)
        .map(|i| {
            (0..n)
                .filter(|&j| j != i && (a[i * n + j] != 0.0 || a[j * n + i] != 0.0))
                .collect()
        })
        .collect();
    rcm_order(&adjacency)
}

/// Reverse Cuthill–McKee ordering of a graph given by its adjacency lists
/// (symmetric, no self-loops): breadth-first from a least-connected
/// vertex, neighbours by increasing degree, reversed; disconnected parts
/// follow one another.
pub(crate) fn rcm_order(adjacency: &[Vec<usize>]) -> Vec<usize> {
    let n = adjacency.len();
    let mut visited = vec![false; n];
    let mut order = Vec::with_capacity(n);
    while order.len() < n {
        let start = (0..n)
            .filter(|&i| !visited[i])
            .min_by_key(|&i| adjacency[i].len())
            .expect("an unvisited vertex");
        visited[start] = true;
        let mut head = order.len();
        order.push(start);
        while head < order.len() {
            let mut next: Vec<usize> = adjacency[order[head]]
                .iter()
                .copied()
                .filter(|&j| !visited[j])
                .collect();
            next.sort_by_key(|&j| adjacency[j].len());
            for j in next {
                visited[j] = true;
                order.push(j);
            }
            head += 1;
        }
    }
    order.reverse();
    order
}

/// y ← y − a·x over equal lengths.
#[inline(always)]
fn axpy(y: &mut [f64], a: &[f64], x: f64) {
    for (y, a) in y.iter_mut().zip(a) {
        *y -= a * x;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_system_that_needs_pivoting() {
        // A = [[0, 2, 1], [1, 1, 0], [3, 0, 1]], x = [1, −2, 3] → b = A x.
        let a = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let x = [1.0, -2.0, 3.0];
        let mut b: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| a[i * 3 + j] * x[j]).sum())
            .collect();
        let mut lu = DenseLu::new(3);
        lu.matrix_mut().copy_from_slice(&a);
        lu.factor().unwrap();
        let mut w = vec![0.0; 3];
        lu.solve_in_place(&mut b, &mut w);
        for i in 0..3 {
            assert!((b[i] - x[i]).abs() < 1e-14, "x[{i}] = {} vs {}", b[i], x[i]);
        }
    }

    #[test]
    fn reports_a_singular_matrix() {
        let mut lu = DenseLu::new(2);
        lu.matrix_mut().copy_from_slice(&[1.0, 2.0, 2.0, 4.0]);
        assert!(
            lu.factor().is_err(),
            "rank-1 matrix must be reported singular"
        );
    }
}
