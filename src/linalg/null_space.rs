//! An orthonormal basis N of null(C_q): the free motions of a constrained
//! assembly, q = N q_r.
//!
//! Entries that sum to round-off of their terms (64 ε of the row's largest
//! term) are dropped. Rows of C_q are then normalized, so a rotational row [rad] and a
//! positional row [m] weigh alike. Rows that share a coordinate are grouped
//! (union–find over coordinates); each group touches a small set of
//! coordinates, and its null space is found there: redundant rows by
//! Gram–Schmidt (named, so a second clamp of a node is reported), the basis
//! as the trailing columns of the Householder Q of the independent rows
//! (faer's QR). Coordinates no row touches map to themselves. N is then
//! block diagonal up to a permutation: orthonormal, with as many nonzeros as
//! the groups' blocks, so a frame of a thousand welds costs a thousand small
//! QRs instead of one dense n × n problem.
//!
//! N is stored per full coordinate as a short list of (reduced index,
//! weight); projections NᵀAN are formed during assembly through
//! [`Projected`], which maps every entry A_ij onto the reduced coordinates.

use super::sparse::Scatter;
use super::vector::{dot, norm2};
use faer::Mat;

/// Relative size below which a Gram–Schmidt remainder marks a dependent row
/// (the square root of a relative singular value of 1e-10).
pub const RANK_TOLERANCE: f64 = 1e-10;

/// The null-space map q = N q_r.
#[derive(Debug, Clone)]
pub struct NullSpace {
    n: usize,
    dim: usize,
    /// Entries of full coordinate g: `map[start[g]..start[g + 1]]`.
    start: Vec<usize>,
    map: Vec<(usize, f64)>,
    /// Rows of C_q that depend linearly on other rows of their group.
    pub redundant_rows: Vec<usize>,
    /// 1/dᵢ² of a column scaling D (see [`NullSpace::scaled`]).
    inv_scale2: Option<Vec<f64>>,
}

/// One group of coupled constraint rows.
struct Group {
    rows: Vec<usize>,
    coords: Vec<usize>,
}

impl NullSpace {
    /// Null space of the m × n matrix given by its entries (repeated
    /// positions add up).
    pub fn new(m: usize, n: usize, entries: impl Iterator<Item = (usize, usize, f64)>) -> Self {
        // Rows as sorted (coordinate, value) lists.
        let mut rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); m];
        for (i, j, v) in entries {
            rows[i].push((j, v));
        }
        for row in &mut rows {
            // Entries that cancel to round-off of their terms are zero: a
            // row of such remainders must not be normalized into a constraint.
            let raw = row.iter().fold(0.0f64, |a, e| a.max(e.1.abs()));
            row.sort_by_key(|e| e.0);
            row.dedup_by(|b, a| {
                if a.0 == b.0 {
                    a.1 += b.1;
                    true
                } else {
                    false
                }
            });
            row.retain(|e| e.1.abs() > 64.0 * f64::EPSILON * raw);
            let norm = row.iter().map(|e| e.1 * e.1).sum::<f64>().sqrt();
            if norm > 0.0 {
                row.iter_mut().for_each(|e| e.1 /= norm);
            }
        }
        let groups = group_rows(&rows, n);
        let mut touched = vec![false; n];
        for g in &groups {
            for &c in &g.coords {
                touched[c] = true;
            }
        }
        // Reduced index: untouched coordinates first, in order, then each
        // group's basis columns.
        let mut lists: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        let mut dim = 0;
        for (g, list) in lists.iter_mut().enumerate() {
            if !touched[g] {
                list.push((dim, 1.0));
                dim += 1;
            }
        }
        let mut redundant_rows = Vec::new();
        for group in &groups {
            let d = group.coords.len();
            let local = |c: usize| group.coords.binary_search(&c).expect("coordinate of group");
            // Row-major block of the group's rows on its coordinates.
            let mut block = vec![0.0; group.rows.len() * d];
            for (r, &i) in group.rows.iter().enumerate() {
                for &(c, v) in &rows[i] {
                    block[r * d + local(c)] = v;
                }
            }
            let dependent = dependent_rows(&block, group.rows.len(), d);
            redundant_rows.extend(dependent.iter().map(|&r| group.rows[r]));
            let basis = null_basis(&block, d, &dependent);
            for (k, &c) in group.coords.iter().enumerate() {
                for col in 0..basis.ncols() {
                    let z = basis[(k, col)];
                    if z != 0.0 {
                        lists[c].push((dim + col, z));
                    }
                }
            }
            dim += basis.ncols();
        }
        redundant_rows.sort_unstable();
        let mut start = Vec::with_capacity(n + 1);
        let mut map = Vec::new();
        start.push(0);
        for list in lists {
            map.extend(list);
            start.push(map.len());
        }
        NullSpace {
            n,
            dim,
            start,
            map,
            redundant_rows,
            inv_scale2: None,
        }
    }

    /// The free motions q = D N q̃ of C_q with the coordinates scaled by D
    /// = diag(d): N is an orthonormal basis of null(C_q D), so that
    /// coordinates of different units (positions [m] beside slopes and
    /// angles [–]) weigh alike when d brings them to one scale (positions
    /// divided by the model's size). [`NullSpace::row`] and
    /// [`NullSpace::expand`] give D N, [`NullSpace::restrict`] Nᵀ D⁻¹,
    /// and [`Projected`] (DN)ᵀ A (DN).
    pub fn scaled(
        m: usize,
        n: usize,
        entries: impl Iterator<Item = (usize, usize, f64)>,
        d: &[f64],
    ) -> Self {
        let mut ns = NullSpace::new(m, n, entries.map(|(i, j, v)| (i, j, v * d[j])));
        for (g, &dg) in d.iter().enumerate().take(n) {
            for e in &mut ns.map[ns.start[g]..ns.start[g + 1]] {
                e.1 *= dg;
            }
        }
        ns.inv_scale2 = Some(d.iter().map(|x| 1.0 / (x * x)).collect());
        ns
    }

    /// Null space of a dense m × n matrix.
    pub fn from_dense(cq: &Mat<f64>) -> Self {
        let (m, n) = (cq.nrows(), cq.ncols());
        let entries = (0..n).flat_map(move |j| (0..m).map(move |i| (i, j, cq[(i, j)])));
        NullSpace::new(m, n, entries.filter(|e| e.2 != 0.0))
    }

    /// Number of free (reduced) coordinates.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Row g of N: (reduced index, weight) pairs.
    #[inline]
    pub fn row(&self, g: usize) -> &[(usize, f64)] {
        &self.map[self.start[g]..self.start[g + 1]]
    }

    /// q = N q_r.
    pub fn expand(&self, qr: &[f64]) -> Vec<f64> {
        (0..self.n)
            .map(|g| self.row(g).iter().map(|&(r, z)| z * qr[r]).sum())
            .collect()
    }

    /// Nᵀ v (Nᵀ D⁻¹ v when scaled: the reduced coordinates of q = D N q̃).
    pub fn restrict(&self, v: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.dim];
        for (g, &vg) in v.iter().enumerate() {
            let vg = self.inv_scale2.as_ref().map_or(vg, |s| vg * s[g]);
            for &(r, z) in self.row(g) {
                out[r] += z * vg;
            }
        }
        out
    }

    /// Nᵀ v (with a scaling D, (DN)ᵀ v): a full vector of generalized
    /// forces in the reduced coordinates, as [`Projected`] maps a matrix.
    pub fn project_forces(&self, v: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.dim];
        self.project_forces_into(v, &mut out);
        out
    }

    /// [`Self::project_forces`] into a caller's buffer of the reduced size.
    pub fn project_forces_into(&self, v: &[f64], out: &mut [f64]) {
        out.fill(0.0);
        for (g, &vg) in v.iter().enumerate() {
            for &(r, z) in self.row(g) {
                out[r] += z * vg;
            }
        }
    }

    /// NᵀAN of a dense symmetric n × n matrix (symmetrized).
    pub fn project_dense(&self, a: &Mat<f64>) -> Mat<f64> {
        let mut out = Mat::zeros(self.dim, self.dim);
        {
            let mut p = Projected::new(self, &mut out);
            for j in 0..self.n {
                for (i, &v) in a.col_as_slice(j).iter().enumerate() {
                    p.add(i, j, v);
                }
            }
        }
        symmetrize(&mut out);
        out
    }
}

/// (A + Aᵀ)/2 in place.
pub fn symmetrize(a: &mut Mat<f64>) {
    let n = a.nrows();
    for j in 0..n {
        for i in j + 1..n {
            let v = 0.5 * (a[(i, j)] + a[(j, i)]);
            a[(i, j)] = v;
            a[(j, i)] = v;
        }
    }
}

/// An assembly target that receives entries of a full n × n matrix A and
/// adds NᵀAN into `inner`.
pub struct Projected<'a, S: Scatter> {
    ns: &'a NullSpace,
    inner: &'a mut S,
}

impl<'a, S: Scatter> Projected<'a, S> {
    pub fn new(ns: &'a NullSpace, inner: &'a mut S) -> Self {
        Projected { ns, inner }
    }
}

impl<S: Scatter> Scatter for Projected<'_, S> {
    #[inline]
    fn add(&mut self, i: usize, j: usize, v: f64) {
        if v == 0.0 {
            return;
        }
        for &(r, zr) in self.ns.row(i) {
            for &(s, zs) in self.ns.row(j) {
                self.inner.add(r, s, zr * v * zs);
            }
        }
    }
}

/// Groups of rows connected through shared coordinates, each with its sorted
/// coordinates; rows in ascending order within a group.
fn group_rows(rows: &[Vec<(usize, f64)>], n: usize) -> Vec<Group> {
    // Union–find over coordinates; a row joins all its coordinates.
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for row in rows {
        if let Some(&(first, _)) = row.first() {
            for &(c, _) in &row[1..] {
                let (a, b) = (find(&mut parent, first), find(&mut parent, c));
                if a != b {
                    parent[a.max(b)] = a.min(b);
                }
            }
        }
    }
    let mut group_of = vec![usize::MAX; n];
    let mut groups: Vec<Group> = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        let Some(&(first, _)) = row.first() else {
            // A zero row constrains nothing: redundant on its own.
            groups.push(Group {
                rows: vec![i],
                coords: Vec::new(),
            });
            continue;
        };
        let root = find(&mut parent, first);
        if group_of[root] == usize::MAX {
            group_of[root] = groups.len();
            groups.push(Group {
                rows: Vec::new(),
                coords: Vec::new(),
            });
        }
        let g = &mut groups[group_of[root]];
        g.rows.push(i);
        g.coords.extend(row.iter().map(|e| e.0));
    }
    for g in &mut groups {
        g.coords.sort_unstable();
        g.coords.dedup();
    }
    groups
}

/// Rows of a row-normalized, row-major m × d block that depend on earlier
/// rows (modified Gram–Schmidt in row order, twice).
fn dependent_rows(rows: &[f64], m: usize, d: usize) -> Vec<usize> {
    if d == 0 {
        return (0..m).collect();
    }
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
        let norm = norm2(&r);
        if norm <= RANK_TOLERANCE.sqrt() {
            dependent.push(i);
        } else {
            basis.extend(r.iter().map(|x| x / norm));
        }
    }
    dependent
}

/// Orthonormal basis (d × (d − r)) of the vectors orthogonal to the r
/// independent rows of the row-major block: the trailing columns of the
/// full Q of B = [independent rows as columns] = Q R (Householder QR;
/// nalgebra's, sequential, since the blocks are small: a group couples the
/// few coordinates of one joint or a short chain of joints).
fn null_basis(rows: &[f64], d: usize, dependent: &[usize]) -> Mat<f64> {
    if d == 0 {
        return Mat::zeros(0, 0);
    }
    let m = rows.len() / d;
    let independent: Vec<usize> = (0..m).filter(|i| !dependent.contains(i)).collect();
    let r = independent.len();
    if r == 0 {
        return Mat::identity(d, d);
    }
    // Pad B with d − r unit columns so the thin Q of the padded matrix is
    // the full Q of B; Householder QR keeps B's column space in the first r.
    let b = nalgebra::DMatrix::from_fn(d, d, |i, j| {
        if j < r {
            rows[independent[j] * d + i]
        } else {
            0.0
        }
    });
    let q = b.qr().q();
    Mat::from_fn(d, d - r, |i, j| q[(i, r + j)])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_orthonormal_annihilated_by_the_rows_and_names_a_repeated_row() {
        // Rows: x0 = x1 (twice, the second scaled), x2 + 2 x3 = 0; x4 free.
        let entries = [
            (0, 0, 1.0),
            (0, 1, -1.0),
            (1, 0, 3.0),
            (1, 1, -3.0),
            (2, 2, 1.0),
            (2, 3, 2.0),
        ];
        let ns = NullSpace::new(3, 5, entries.iter().copied());
        assert_eq!(ns.dim(), 3, "5 coordinates, 2 independent rows");
        assert_eq!(ns.redundant_rows, vec![1], "the scaled repeat is redundant");
        let cols: Vec<Vec<f64>> = (0..3)
            .map(|k| ns.expand(&(0..3).map(|r| f64::from(r == k)).collect::<Vec<_>>()))
            .collect();
        for (a, ca) in cols.iter().enumerate() {
            assert!((ca[0] - ca[1]).abs() < 1e-15, "column {a}: x0 = x1");
            assert!(
                (ca[2] + 2.0 * ca[3]).abs() < 1e-15,
                "column {a}: x2 + 2x3 = 0"
            );
            for (b, cb) in cols.iter().enumerate() {
                let expect = f64::from(a == b);
                assert!((dot(ca, cb) - expect).abs() < 1e-15, "NᵀN[{a},{b}]");
            }
        }
        let v: Vec<f64> = (0..5).map(|i| i as f64 + 0.5).collect();
        let back = ns.restrict(&v);
        let dense: Vec<f64> = cols.iter().map(|c| dot(c, &v)).collect();
        for (x, y) in back.iter().zip(&dense) {
            assert!((x - y).abs() < 1e-14, "Nᵀv against the columns");
        }
    }
}
