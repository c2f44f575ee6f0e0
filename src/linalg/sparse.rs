//! Assembly targets and compressed sparse matrices.
//!
//! Elements, springs and joints compute small dense blocks; the system adds
//! them entry by entry into a [`Scatter`] target: a dense faer matrix for
//! small problems, a [`Triplets`] list for large ones (duplicates are summed
//! when the list is compressed into a faer `SparseColMat`). Memory of a
//! triplet list and of the compressed matrix is proportional to the
//! nonzeros.

use faer::sparse::{SparseColMat, SymbolicSparseColMat, Triplet};
use faer::{Mat, MatMut, MatRef};
use rayon::prelude::*;

/// Something an assembly can add matrix entries into.
pub trait Scatter {
    /// A[i, j] += v.
    fn add(&mut self, i: usize, j: usize, v: f64);
}

impl Scatter for Mat<f64> {
    #[inline]
    fn add(&mut self, i: usize, j: usize, v: f64) {
        self[(i, j)] += v;
    }
}

/// A list of (row, column, value) entries of an nrows × ncols matrix;
/// repeated positions add up.
#[derive(Debug, Clone, Default)]
pub struct Triplets {
    nrows: usize,
    ncols: usize,
    entries: Vec<Triplet<usize, usize, f64>>,
}

impl Scatter for Triplets {
    #[inline]
    fn add(&mut self, i: usize, j: usize, v: f64) {
        if v != 0.0 {
            self.entries.push(Triplet::new(i, j, v));
        }
    }
}

impl Triplets {
    /// An empty nrows × ncols list.
    pub fn new(nrows: usize, ncols: usize) -> Self {
        Triplets {
            nrows,
            ncols,
            entries: Vec::new(),
        }
    }

    pub fn nrows(&self) -> usize {
        self.nrows
    }

    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// The entries as added (not summed).
    pub fn entries(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        self.entries.iter().map(|t| (t.row, t.col, t.val))
    }

    /// Number of stored entries (before summation).
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Compressed-column matrix with repeated entries summed.
    pub fn to_sparse(&self) -> SparseColMat<usize, f64> {
        // Indices are in range by construction of every caller; a failure is
        // an out-of-memory condition.
        SparseColMat::try_new_from_triplets(self.nrows, self.ncols, &self.entries)
            .expect("triplet indices within the matrix")
    }

    /// The dense matrix (for small problems and tests).
    pub fn to_dense(&self) -> Mat<f64> {
        let mut m = Mat::zeros(self.nrows, self.ncols);
        for t in &self.entries {
            m[(t.row, t.col)] += t.val;
        }
        m
    }
}

/// y = A x for a compressed-column A.
pub fn mul_vec(a: &SparseColMat<usize, f64>, x: &[f64], y: &mut [f64]) {
    y.fill(0.0);
    let a = a.as_ref();
    for (j, &xj) in x.iter().enumerate().take(a.ncols()) {
        if xj == 0.0 {
            continue;
        }
        for (i, v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
            y[i] += v * xj;
        }
    }
}

/// Y = A X for a compressed-column A and a block X of several columns,
/// reading A once: each entry of A meets all the columns at once (row j of
/// X gathered, rows of Y accumulated row-major in `scratch`, which keeps
/// its allocation from call to call: a fresh block of a large model costs
/// its page faults), and each column of Y is summed in the order
/// [`mul_vec`] sums it, so that the two agree to the last bit (for finite
/// entries: mul_vec skips a zero x, which adds ±0 here). The columns go
/// [`BLOCK_COLUMNS`] at a time: the scratch stays a few columns' size
/// (a 16-column block of a 100,000-element model would take 51 MB).
pub fn mul_block(
    a: &SparseColMat<usize, f64>,
    x: MatRef<'_, f64>,
    mut y: MatMut<'_, f64>,
    scratch: &mut Vec<f64>,
) {
    let mut start = 0;
    while start < x.ncols() {
        let k = BLOCK_COLUMNS.min(x.ncols() - start);
        mul_columns(
            a,
            x.subcols(start, k),
            y.as_mut().subcols_mut(start, k),
            scratch,
        );
        start += k;
    }
}

/// Columns of [`mul_block`] taken together.
pub const BLOCK_COLUMNS: usize = 4;

fn mul_columns(
    a: &SparseColMat<usize, f64>,
    x: MatRef<'_, f64>,
    mut y: MatMut<'_, f64>,
    scratch: &mut Vec<f64>,
) {
    let k = x.ncols();
    if k == 1 {
        let x = x.col(0).try_as_col_major().expect("a column is contiguous");
        let y = y.col_mut(0).try_as_col_major_mut().expect("contiguous");
        mul_vec(a, x.as_slice(), y.as_slice_mut());
        return;
    }
    let a = a.as_ref();
    let n = a.nrows();
    scratch.clear();
    scratch.resize(n * k, 0.0);
    let mut xj = vec![0.0; k];
    for j in 0..a.ncols().min(x.nrows()) {
        for (c, v) in xj.iter_mut().enumerate() {
            *v = x[(j, c)];
        }
        for (i, v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
            for (y, x) in scratch[i * k..(i + 1) * k].iter_mut().zip(&xj) {
                *y += v * x;
            }
        }
    }
    for (r, row) in scratch.chunks_exact(k).enumerate() {
        for (c, &v) in row.iter().enumerate() {
            y[(r, c)] = v;
        }
    }
}

/// Rows per task of the products shared among the pool's threads
/// ([`mul_symmetric`], [`mul_symmetric_block`], the Lanczos basis'
/// re-orthogonalization): fixed, so that the result is the same however
/// many threads share the rows.
pub const ROWS_PER_TASK: usize = 1 << 14;

/// y = A x for a symmetric compressed-column A (column j read as row j),
/// each yⱼ one dot product of column j with x, the rows shared among the
/// pool's threads: no scattered writes, and every yⱼ summed in the same
/// order however the rows are shared. For A's rounding asymmetry (its
/// (i, j) and (j, i) entries summed in different orders) this is Aᵀx, a
/// change of ε|A||x|. Two cores stream a large A nearly twice as fast as
/// one (a 100,000-element beam's M is 77 MB).
pub fn mul_symmetric(a: &SparseColMat<usize, f64>, x: &[f64], y: &mut [f64]) {
    let a = a.as_ref();
    y.par_chunks_mut(ROWS_PER_TASK)
        .enumerate()
        .for_each(|(t, ys)| {
            let j0 = t * ROWS_PER_TASK;
            for (jj, yj) in ys.iter_mut().enumerate() {
                let j = j0 + jj;
                *yj = a
                    .row_idx_of_col(j)
                    .zip(a.val_of_col(j))
                    .fold(0.0, |s, (i, v)| s + v * x[i]);
            }
        });
}

/// Y = A X for a symmetric compressed-column A: every column of Y is
/// [`mul_symmetric`]'s to the bit, A read once per [`BLOCK_COLUMNS`]
/// columns.
pub fn mul_symmetric_block(a: &SparseColMat<usize, f64>, x: MatRef<'_, f64>, y: MatMut<'_, f64>) {
    let a = a.as_ref();
    let k = x.ncols();
    let cols: Vec<&[f64]> = (0..k)
        .map(|c| {
            x.col(c)
                .try_as_col_major()
                .expect("a column is contiguous")
                .as_slice()
        })
        .collect();
    y.par_row_chunks_mut(ROWS_PER_TASK)
        .enumerate()
        .for_each(|(t, mut ys)| {
            let j0 = t * ROWS_PER_TASK;
            for c0 in (0..k).step_by(BLOCK_COLUMNS) {
                let group = &cols[c0..(c0 + BLOCK_COLUMNS).min(k)];
                for jj in 0..ys.nrows() {
                    let j = j0 + jj;
                    let mut acc = [0.0; BLOCK_COLUMNS];
                    for (i, v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
                        for (s, x) in acc.iter_mut().zip(group) {
                            *s += v * x[i];
                        }
                    }
                    for (c, s) in acc.iter().take(group.len()).enumerate() {
                        ys[(jj, c0 + c)] = *s;
                    }
                }
            }
        });
}

/// A and B on the pattern of both together (sorted row indices in every
/// column, as faer's compressed matrices keep them), explicit zeros where
/// only the other has an entry: a pencil whose two matrices share one
/// pattern shares one symbolic factorization, and no copy of it is made.
pub fn on_common_pattern(
    a: &SparseColMat<usize, f64>,
    b: &SparseColMat<usize, f64>,
) -> [SparseColMat<usize, f64>; 2] {
    let (a, b) = (a.as_ref(), b.as_ref());
    let n = a.ncols();
    let mut col_ptr = Vec::with_capacity(n + 1);
    col_ptr.push(0usize);
    let (mut rows, mut av, mut bv) = (Vec::new(), Vec::new(), Vec::new());
    for j in 0..n {
        let (ra, va) = (a.row_idx_of_col_raw(j), a.val_of_col(j));
        let (rb, vb) = (b.row_idx_of_col_raw(j), b.val_of_col(j));
        let (mut p, mut q) = (0, 0);
        while p < ra.len() || q < rb.len() {
            let (i, x, y) = match (ra.get(p), rb.get(q)) {
                (Some(&i), Some(&k)) if i == k => {
                    p += 1;
                    q += 1;
                    (i, va[p - 1], vb[q - 1])
                }
                (Some(&i), Some(&k)) if i < k => {
                    p += 1;
                    (i, va[p - 1], 0.0)
                }
                (Some(&i), None) => {
                    p += 1;
                    (i, va[p - 1], 0.0)
                }
                (_, Some(&k)) => {
                    q += 1;
                    (k, 0.0, vb[q - 1])
                }
                (None, None) => unreachable!("loop condition"),
            };
            rows.push(i);
            av.push(x);
            bv.push(y);
        }
        col_ptr.push(rows.len());
    }
    let symbolic = SymbolicSparseColMat::new_checked(a.nrows(), n, col_ptr, None, rows);
    [
        SparseColMat::new(symbolic.clone(), av),
        SparseColMat::new(symbolic, bv),
    ]
}

/// The diagonal of a square compressed-column matrix.
pub fn diagonal(a: &SparseColMat<usize, f64>) -> Vec<f64> {
    let a = a.as_ref();
    (0..a.ncols())
        .map(|j| {
            a.row_idx_of_col(j)
                .zip(a.val_of_col(j))
                .filter(|(i, _)| *i == j)
                .map(|(_, v)| *v)
                .sum()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeated_entries_add_up_and_products_match_the_dense_matrix() {
        let mut t = Triplets::new(3, 3);
        for (i, j, v) in [
            (0, 0, 2.0),
            (0, 0, 1.0),
            (1, 2, -4.0),
            (2, 1, 0.5),
            (2, 2, 7.0),
        ] {
            t.add(i, j, v);
        }
        let (s, d) = (t.to_sparse(), t.to_dense());
        assert_eq!(d[(0, 0)], 3.0, "repeated (0, 0) entries summed");
        let x = [1.0, -2.0, 3.0];
        let mut y = [0.0; 3];
        mul_vec(&s, &x, &mut y);
        for i in 0..3 {
            let dense: f64 = (0..3).map(|j| d[(i, j)] * x[j]).sum();
            assert_eq!(y[i], dense, "row {i} of A x, sparse against dense");
        }
        assert_eq!(diagonal(&s), vec![3.0, 0.0, 7.0], "diagonal of A");
        // The block product, column by column, is mul_vec's to the bit.
        let xb = Mat::from_fn(3, 4, |r, c| {
            (r as f64 + 1.0) * (c as f64 - 1.5) + 0.1 * c as f64
        });
        let mut yb = Mat::zeros(3, 4);
        mul_block(&s, xb.as_ref(), yb.as_mut(), &mut Vec::new());
        for c in 0..4 {
            let xc: Vec<f64> = (0..3).map(|r| xb[(r, c)]).collect();
            mul_vec(&s, &xc, &mut y);
            for r in 0..3 {
                assert_eq!(yb[(r, c)].to_bits(), y[r].to_bits(), "column {c} row {r}");
            }
        }
    }

    /// The symmetric products: against the dense product to round-off, and
    /// the block's columns against the vector product to the bit, on a
    /// matrix with more rows than one task takes.
    #[test]
    fn symmetric_products_match_the_dense_matrix_and_each_other() {
        let n = 2 * ROWS_PER_TASK + 37;
        let mut t = Triplets::new(n, n);
        for i in 0..n {
            t.add(i, i, 4.0 + (i % 7) as f64);
            if i + 1 < n {
                let v = -1.0 - 0.01 * (i % 13) as f64;
                t.add(i, i + 1, v);
                t.add(i + 1, i, v);
            }
            if i + 5 < n {
                t.add(i, i + 5, 0.25);
                t.add(i + 5, i, 0.25);
            }
        }
        let s = t.to_sparse();
        let xb = Mat::from_fn(n, 6, |r, c| ((r * (c + 1)) as f64 * 0.37).sin());
        let mut yb = Mat::zeros(n, 6);
        mul_symmetric_block(&s, xb.as_ref(), yb.as_mut());
        let mut y = vec![0.0; n];
        for c in 0..6 {
            let xc: Vec<f64> = (0..n).map(|r| xb[(r, c)]).collect();
            mul_symmetric(&s, &xc, &mut y);
            let at = |i: isize| -> f64 {
                if i < 0 || i as usize >= n {
                    0.0
                } else {
                    xc[i as usize]
                }
            };
            for r in 0..n {
                assert_eq!(yb[(r, c)].to_bits(), y[r].to_bits(), "column {c} row {r}");
                // Row r of the band written out by hand.
                let i = r as isize;
                let off = |a: usize, b: usize| -1.0 - 0.01 * (a.min(b) % 13) as f64;
                let mut dense = (4.0 + (r % 7) as f64) * xc[r];
                if r + 1 < n {
                    dense += off(r, r + 1) * xc[r + 1];
                }
                if r > 0 {
                    dense += off(r - 1, r) * xc[r - 1];
                }
                dense += 0.25 * (at(i + 5) + at(i - 5));
                assert!(
                    (y[r] - dense).abs() <= 1e-14 * 8.0,
                    "row {r} of column {c}: {} against {dense}",
                    y[r]
                );
            }
        }
    }
}
