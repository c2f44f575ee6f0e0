//! Factorizations of the integrator's iteration matrix, on faer.
//!
//! - [`DenseLu`]: faer's dense LU with partial pivoting
//!   (`linalg::lu::partial_pivoting`), factored in place in one preallocated
//!   matrix, and the inverse formed from it, so that a solve is one
//!   vectorized matrix–vector product ([`MatVec`]); one reused scratch
//!   buffer: the time loop does not allocate.
//! - [`SparseLu`]: faer's sparse LU (COLAMD column order, simplicial or
//!   supernodal by faer's own choice) on a compressed-column matrix whose
//!   pattern is fixed when the integrator is built; the symbolic
//!   factorization is computed once for that pattern and every
//!   refactorization is numeric only, into reused storage. No dense n × n
//!   matrix: memory is proportional to the nonzeros of the matrix and of its
//!   factors.
//!
//! Both are filled through [`Scatter`] ([`Factorization`] is itself an
//! assembly target), so the integrator assembles one way for both.

use super::scaling::Equilibration;
use crate::linalg::Scatter;
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::lu::partial_pivoting::{factor, inverse};
use faer::perm::PermRef;
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, Mat, MatMut, Par};

/// Why a factorization failed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FactorFailure {
    /// No usable pivot in this column (an unknown of the matrix).
    Singular { column: usize },
    /// Out of memory.
    Memory,
}

/// A dense LU factorization P A = L U of a square matrix, and the inverse
/// A⁻¹ = U⁻¹ L⁻¹ P formed from it; a solve is one matrix–vector product.
///
/// Why the inverse: the time loop solves with one factorization about a
/// hundred times (one solve per Newton iteration, one factorization per
/// ~100 steps), and at the built-in assembly's 50 unknowns faer's two
/// recursive triangular solves cost ~2.7 µs against ~0.3 µs for one
/// vectorized matrix–vector product. `cargo bench --bench impulse`, the
/// default impulse (100 ms at 1 µs; the former hand-written banded LU:
/// 251 ms): 521 ms with `partial_pivoting::solve::solve_in_place`, 256 ms
/// with the inverse (whole `ancf-modal impulse` runs interleaved with the
/// former build on the same loaded machine: min 234 against 240 ms, median
/// 271 against 271 ms). The product was then faer's row-major one; it is
/// now [`MatVec`], column by column in registers, which took the solve
/// from 20 % to 8–9 % of the bare blade's impulse (`perf record`). Forming
/// A⁻¹ costs about one more factorization.
/// Its solutions carry an error of the same order, cond(A)·ε, which only
/// enters the Newton corrections: the residual is always exact.
pub struct DenseLu {
    /// The matrix as assembled, then its factors (L strictly below the
    /// diagonal with a unit diagonal implied, U on and above it).
    a: Mat<f64>,
    /// A⁻¹ column by column, each column padded with zeros to `stride`
    /// entries, the equilibration's scales folded in (powers of two: the
    /// same bits as applying them to b and x).
    inverse: Vec<f64>,
    /// Entries per stored column: n rounded up to whole vector registers.
    stride: usize,
    /// The instruction set the product runs in (chosen once, at run time).
    arch: pulp::Arch,
    /// The inverse before it is stored ((A⁻¹)ᵀ of the scaled matrix).
    inverse_t: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    /// Scratch of the factorization and of forming the inverse.
    mem: MemBuffer,
    /// The solution while it is formed (`stride` entries).
    x: Vec<f64>,
    /// Per column, the pivot size below which it counts as singular.
    tiny: Vec<f64>,
    /// The scales the matrix is factored with ([`Equilibration`]).
    scales: Equilibration,
    /// The matrix as assembled, kept while the balanced one is tried.
    unscaled: Mat<f64>,
}

impl DenseLu {
    /// A zero n × n matrix to assemble into.
    pub fn new(n: usize) -> Self {
        let req = StackReq::any_of(&[
            factor::lu_in_place_scratch::<usize, f64>(n, n, Par::Seq, Default::default()),
            inverse::inverse_scratch::<usize, f64>(n, Par::Seq),
        ]);
        DenseLu {
            a: Mat::zeros(n, n),
            inverse: vec![0.0; padded(n) * n],
            stride: padded(n),
            arch: pulp::Arch::new(),
            inverse_t: Mat::zeros(n, n),
            perm: (0..n).collect(),
            perm_inv: (0..n).collect(),
            mem: MemBuffer::new(req),
            x: vec![0.0; padded(n)],
            tiny: vec![0.0; n],
            scales: Equilibration::new(n),
            unscaled: Mat::zeros(n, n),
        }
    }

    /// Factor the assembled matrix in place and form its inverse. A pivot
    /// at or below n·ε times the largest entry of its column in A counts
    /// as singular (only rows are exchanged, so the column is an unknown of
    /// the original matrix). Column-relative, because the blocks differ in
    /// scale by many orders: a beam slope's mass is ρA·Le³/105 against a
    /// constraint row of order one, so a fine mesh's matrix passes a test
    /// relative to its largest entry only by luck (the former LU's test
    /// rejected a 200-element cantilever at t = 0).
    pub fn factor(&mut self) -> Result<(), FactorFailure> {
        let n = self.a.nrows();
        let a = &self.a;
        self.scales.compute(|f| {
            for j in 0..n {
                for (i, &v) in a.col(j).iter().enumerate() {
                    if v != 0.0 {
                        f(i, j, v);
                    }
                }
            }
        });
        self.unscaled.copy_from(&self.a);
        for j in 0..n {
            let c = self.scales.scale[j];
            for (v, r) in self.a.col_mut(j).iter_mut().zip(&self.scales.scale) {
                *v *= r * c;
            }
        }
        if self.factor_as_is().is_ok() {
            return Ok(());
        }
        // The units' own scale decides where the balanced one fails.
        self.a.copy_from(&self.unscaled);
        self.scales.reset();
        self.factor_as_is()
    }

    /// Factors `a` as it stands (the pivot test, the inverse).
    fn factor_as_is(&mut self) -> Result<(), FactorFailure> {
        let n = self.a.nrows();
        let eps = f64::EPSILON * n as f64;
        for (t, j) in self.tiny.iter_mut().zip(0..n) {
            *t = eps * self.a.col(j).norm_max();
        }
        factor::lu_in_place(
            self.a.as_mut(),
            &mut self.perm,
            &mut self.perm_inv,
            Par::Seq,
            MemStack::new(&mut self.mem),
            Default::default(),
        );
        let pivot_ok = |k: usize| {
            let p = self.a[(k, k)].abs();
            p > self.tiny[k] && p.is_finite()
        };
        if let Some(column) = (0..n).find(|&k| !pivot_ok(k)) {
            return Err(FactorFailure::Singular { column });
        }
        inverse::inverse(
            self.inverse_t.as_mut().transpose_mut(),
            self.a.as_ref(),
            self.a.as_ref(),
            PermRef::new_checked(&self.perm, &self.perm_inv, n),
            Par::Seq,
            MemStack::new(&mut self.mem),
        );
        // A⁻¹ = D (D A D)⁻¹ D, column j of A⁻¹ row j of (A⁻¹)ᵀ.
        let d = &self.scales.scale;
        for (j, col) in self.inverse.chunks_exact_mut(self.stride).enumerate() {
            for (i, v) in col[..n].iter_mut().enumerate() {
                *v = d[i] * self.inverse_t[(j, i)] * d[j];
            }
        }
        Ok(())
    }

    /// b ← A⁻¹ b.
    pub fn solve_in_place(&mut self, b: &mut [f64]) {
        let n = self.a.nrows();
        self.arch.dispatch(MatVec {
            a: &self.inverse,
            stride: self.stride,
            b: &b[..n],
            x: &mut self.x,
        });
        b[..n].copy_from_slice(&self.x[..n]);
    }
}

/// The most `f64`s a vector register holds (512 bits).
const MAX_LANES: usize = 8;

/// n rounded up to whole vector registers of any width.
fn padded(n: usize) -> usize {
    n.div_ceil(MAX_LANES) * MAX_LANES
}

/// x ← A b for A stored column by column, `stride` entries a column (a
/// multiple of the register width, the padding zero): x is formed as
/// Σⱼ A₍:,ⱼ₎ bⱼ, blocks of rows held in registers across all j, with fused
/// multiply–adds where the CPU has them. At n = 36 (the bare blade) this
/// is ~5× faer's row-major product, whose per-row dot products end in a
/// horizontal sum each.
struct MatVec<'a> {
    a: &'a [f64],
    stride: usize,
    b: &'a [f64],
    x: &'a mut [f64],
}

impl pulp::WithSimd for MatVec<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, simd: S) {
        let MatVec { a, stride, b, x } = self;
        let (x, _) = S::as_mut_simd_f64s(x);
        let vectors = x.len();
        let mut first = 0;
        while first + 4 <= vectors {
            rows::<S, 4>(simd, a, stride, b, first, x);
            first += 4;
        }
        match vectors - first {
            3 => rows::<S, 3>(simd, a, stride, b, first, x),
            2 => rows::<S, 2>(simd, a, stride, b, first, x),
            1 => rows::<S, 1>(simd, a, stride, b, first, x),
            _ => {}
        }
    }
}

/// Registers `first..first + R` of x ← A b (see [`MatVec`]): two sets of
/// accumulators, the even columns' and the odd ones', so that 2R chains of
/// multiply–adds run at once (a chain waits four cycles a step).
#[inline(always)]
fn rows<S: pulp::Simd, const R: usize>(
    simd: S,
    a: &[f64],
    stride: usize,
    b: &[f64],
    first: usize,
    x: &mut [S::f64s],
) {
    let zero = simd.splat_f64s(0.0);
    let (mut even, mut odd) = ([zero; R], [zero; R]);
    let add = |acc: &mut [S::f64s; R], column: &[f64], bj: f64| {
        let (column, _) = S::as_simd_f64s(column);
        let bj = simd.splat_f64s(bj);
        for (acc, &c) in acc.iter_mut().zip(&column[first..first + R]) {
            *acc = simd.mul_add_f64s(c, bj, *acc);
        }
    };
    for (columns, bj) in a.chunks_exact(2 * stride).zip(b.chunks_exact(2)) {
        let (c0, c1) = columns.split_at(stride);
        add(&mut even, c0, bj[0]);
        add(&mut odd, c1, bj[1]);
    }
    if b.len() % 2 == 1 {
        let last = b.len() - 1;
        add(&mut even, &a[last * stride..][..stride], b[last]);
    }
    for ((x, e), o) in x[first..first + R].iter_mut().zip(even).zip(odd) {
        *x = simd.add_f64s(e, o);
    }
}

/// A sparse LU factorization of a square matrix with a fixed pattern.
pub struct SparseLu {
    pattern: SymbolicSparseColMat<usize>,
    /// Values of the pattern's entries, in its compressed-column order.
    values: Vec<f64>,
    /// Entries added outside the pattern since the last factorization;
    /// the pattern grows by them (and the symbolic factorization is
    /// renewed) before the next one. The integrator's pattern covers every
    /// entry its assembly writes, so this stays empty in practice.
    outside: Vec<(usize, usize, f64)>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    factor_mem: MemBuffer,
    solve_mem: MemBuffer,
    factored: bool,
    /// Scratch of the singularity probe.
    probe: Vec<f64>,
    /// The scales the matrix is factored with ([`Equilibration`]).
    scales: Equilibration,
    /// The values as assembled, kept while the balanced ones are tried.
    unscaled: Vec<f64>,
}

impl SparseLu {
    /// The n × n pattern of the given (row, column) positions (repeats
    /// allowed), with its symbolic factorization; all values zero.
    pub fn new(n: usize, positions: &[(usize, usize)]) -> Result<Self, FactorFailure> {
        let pattern = compress(n, positions.iter().copied());
        let symbolic = factorize_symbolic_lu(pattern.as_ref(), Default::default())
            .map_err(|_| FactorFailure::Memory)?;
        let (factor_mem, solve_mem) = scratch(&symbolic)?;
        Ok(SparseLu {
            values: vec![0.0; pattern.row_idx().len()],
            pattern,
            outside: Vec::new(),
            symbolic,
            numeric: NumericLu::new(),
            factor_mem,
            solve_mem,
            factored: false,
            probe: vec![0.0; n],
            scales: Equilibration::new(n),
            unscaled: Vec::new(),
        })
    }

    /// Number of stored entries of the pattern.
    #[cfg(test)]
    pub fn nonzeros(&self) -> usize {
        self.values.len()
    }

    fn size(&self) -> usize {
        self.pattern.nrows()
    }

    fn clear(&mut self) {
        self.values.fill(0.0);
        self.outside.clear();
        self.factored = false;
    }

    fn add(&mut self, i: usize, j: usize, v: f64) {
        let p = self.pattern.as_ref();
        let range = p.col_range(j);
        match p.row_idx()[range.clone()].binary_search(&i) {
            Ok(k) => self.values[range.start + k] += v,
            Err(_) if v != 0.0 => self.outside.push((i, j, v)),
            Err(_) => {}
        }
    }

    /// Merge the entries added outside the pattern into it and renew the
    /// symbolic factorization.
    fn grow(&mut self) -> Result<(), FactorFailure> {
        let n = self.size();
        let old = self.pattern.as_ref();
        let mut entries: Vec<(usize, usize, f64)> = (0..n)
            .flat_map(|j| {
                old.row_idx()[old.col_range(j)]
                    .iter()
                    .zip(&self.values[old.col_range(j)])
                    .map(move |(&i, &v)| (i, j, v))
            })
            .collect();
        entries.append(&mut self.outside);
        let pattern = compress(n, entries.iter().map(|&(i, j, _)| (i, j)));
        self.symbolic = factorize_symbolic_lu(pattern.as_ref(), Default::default())
            .map_err(|_| FactorFailure::Memory)?;
        (self.factor_mem, self.solve_mem) = scratch(&self.symbolic)?;
        self.numeric = NumericLu::new();
        self.pattern = pattern;
        self.values = vec![0.0; self.pattern.row_idx().len()];
        for (i, j, v) in entries {
            self.add(i, j, v);
        }
        Ok(())
    }

    /// Factor the assembled values (numeric factorization on the stored
    /// symbolic one).
    pub fn factor(&mut self) -> Result<(), FactorFailure> {
        if !self.outside.is_empty() {
            self.grow()?;
        }
        let p = self.pattern.as_ref();
        let values = &self.values;
        self.scales.compute(|f| {
            for j in 0..p.ncols() {
                for (&i, &v) in p.row_idx()[p.col_range(j)]
                    .iter()
                    .zip(&values[p.col_range(j)])
                {
                    f(i, j, v);
                }
            }
        });
        self.unscaled.clone_from(&self.values);
        for j in 0..p.ncols() {
            let c = self.scales.scale[j];
            for (&i, v) in p.row_idx()[p.col_range(j)]
                .iter()
                .zip(&mut self.values[p.col_range(j)])
            {
                *v *= self.scales.scale[i] * c;
            }
        }
        if self.factor_as_is().is_ok() {
            return Ok(());
        }
        // The units' own scale decides where the balanced one fails.
        self.values.clone_from(&self.unscaled);
        self.scales.reset();
        self.factor_as_is()
    }

    /// Factors the values as they stand (numeric factorization, the
    /// singularity probe).
    fn factor_as_is(&mut self) -> Result<(), FactorFailure> {
        let a = SparseColMatRef::new(self.pattern.as_ref(), &self.values);
        let result = self.symbolic.factorize_numeric_lu(
            &mut self.numeric,
            a,
            Par::Seq,
            MemStack::new(&mut self.factor_mem),
            Default::default(),
        );
        match result {
            Ok(_) => {
                self.factored = true;
                self.probe()
            }
            Err(faer::sparse::linalg::LuError::SymbolicSingular { index }) => {
                let (order, _) = self.symbolic.col_perm().arrays();
                Err(FactorFailure::Singular {
                    column: order.get(index).copied().unwrap_or(index),
                })
            }
            Err(faer::sparse::linalg::LuError::Generic(_)) => Err(FactorFailure::Memory),
        }
    }

    /// faer's sparse LU stops only at a structurally empty pivot column; a
    /// numerically zero pivot shows as non-finite factors. Solve
    /// A x = A·1 once and name the first unknown that is not finite.
    fn probe(&mut self) -> Result<(), FactorFailure> {
        let mut x = std::mem::take(&mut self.probe);
        x.fill(0.0);
        let p = self.pattern.as_ref();
        for j in 0..self.size() {
            for (&i, &v) in p.row_idx()[p.col_range(j)]
                .iter()
                .zip(&self.values[p.col_range(j)])
            {
                x[i] += v;
            }
        }
        self.solve_scaled(&mut x);
        let bad = x.iter().position(|v| !v.is_finite());
        self.probe = x;
        match bad {
            Some(column) => {
                self.factored = false;
                Err(FactorFailure::Singular { column })
            }
            None => Ok(()),
        }
    }

    /// b ← A⁻¹ b (after a successful [`SparseLu::factor`]).
    pub fn solve_in_place(&mut self, b: &mut [f64]) {
        self.scales.apply(b);
        self.solve_scaled(b);
        self.scales.apply(b);
    }

    /// b ← (D A D)⁻¹ b: the factored (scaled) matrix's solve.
    fn solve_scaled(&mut self, b: &mut [f64]) {
        assert!(self.factored, "solve before a successful factorization");
        let n = self.size();
        LuRef::new_unchecked(&self.symbolic, &self.numeric).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(b, n, 1),
            Par::Seq,
            MemStack::new(&mut self.solve_mem),
        );
    }
}

/// Scratch buffers of the numeric factorization and of a one-column solve.
fn scratch(symbolic: &SymbolicLu<usize>) -> Result<(MemBuffer, MemBuffer), FactorFailure> {
    let f = symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default());
    let s = symbolic.solve_in_place_scratch::<f64>(1, Par::Seq);
    let alloc = |r| MemBuffer::try_new(r).map_err(|_| FactorFailure::Memory);
    Ok((alloc(f)?, alloc(s)?))
}

/// The n × n compressed-column pattern of the positions (sorted, unique).
fn compress(
    n: usize,
    positions: impl Iterator<Item = (usize, usize)>,
) -> SymbolicSparseColMat<usize> {
    let mut by_column: Vec<(usize, usize)> = positions.map(|(i, j)| (j, i)).collect();
    by_column.sort_unstable();
    by_column.dedup();
    let mut col_ptr = vec![0usize; n + 1];
    for &(j, _) in &by_column {
        col_ptr[j + 1] += 1;
    }
    for j in 0..n {
        col_ptr[j + 1] += col_ptr[j];
    }
    let row_idx = by_column.into_iter().map(|(_, i)| i).collect();
    SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx)
}

/// The iteration matrix's factorization on one path or the other. It is an
/// assembly target: [`Factorization::clear`], add the matrix, then
/// [`Factorization::factor`].
pub enum Factorization {
    Dense(Box<DenseLu>),
    Sparse(Box<SparseLu>),
}

impl Factorization {
    /// Order of the matrix.
    pub fn size(&self) -> usize {
        match self {
            Factorization::Dense(d) => d.a.nrows(),
            Factorization::Sparse(s) => s.size(),
        }
    }

    /// Zero the matrix (keeping the sparse pattern).
    pub fn clear(&mut self) {
        match self {
            Factorization::Dense(d) => d.a.fill(0.0),
            Factorization::Sparse(s) => s.clear(),
        }
    }

    pub fn factor(&mut self) -> Result<(), FactorFailure> {
        match self {
            Factorization::Dense(d) => d.factor(),
            Factorization::Sparse(s) => s.factor(),
        }
    }

    /// b ← A⁻¹ b.
    pub fn solve_in_place(&mut self, b: &mut [f64]) {
        match self {
            Factorization::Dense(d) => d.solve_in_place(b),
            Factorization::Sparse(s) => s.solve_in_place(b),
        }
    }

    pub fn is_sparse(&self) -> bool {
        matches!(self, Factorization::Sparse(_))
    }
}

impl Scatter for Factorization {
    #[inline]
    fn add(&mut self, i: usize, j: usize, v: f64) {
        match self {
            Factorization::Dense(d) => d.a[(i, j)] += v,
            Factorization::Sparse(s) => s.add(i, j, v),
        }
    }
}

/// The positions an assembly writes, values ignored (zeros included): the
/// structural pattern of a sparse matrix.
#[derive(Debug, Default)]
pub struct Positions(pub Vec<(usize, usize)>);

impl Scatter for Positions {
    #[inline]
    fn add(&mut self, i: usize, j: usize, _: f64) {
        self.0.push((i, j));
    }
}

/// A block of a larger matrix: entry (i, j) added as scale·v at
/// (row0 + i, col0 + j), and, if mirrored, also at (col0 + j, row0 + i)
/// (both off-diagonal blocks of a symmetric saddle-point matrix at once).
pub struct Placed<'a, S: Scatter> {
    target: &'a mut S,
    row0: usize,
    col0: usize,
    scale: f64,
    mirrored: bool,
}

impl<'a, S: Scatter> Placed<'a, S> {
    /// scale·A at the origin.
    pub fn scaled(target: &'a mut S, scale: f64) -> Self {
        Placed {
            target,
            row0: 0,
            col0: 0,
            scale,
            mirrored: false,
        }
    }

    /// A at (row0, 0) and Aᵀ at (0, row0).
    pub fn mirrored(target: &'a mut S, row0: usize) -> Self {
        Placed {
            target,
            row0,
            col0: 0,
            scale: 1.0,
            mirrored: true,
        }
    }
}

impl<S: Scatter> Scatter for Placed<'_, S> {
    #[inline]
    fn add(&mut self, i: usize, j: usize, v: f64) {
        let (r, c, v) = (self.row0 + i, self.col0 + j, self.scale * v);
        self.target.add(r, c, v);
        if self.mirrored {
            self.target.add(c, r, v);
        }
    }
}

/// y += scale·A x for the matrix A an assembly writes, without storing A.
pub struct Product<'a> {
    pub x: &'a [f64],
    pub y: &'a mut [f64],
    pub scale: f64,
}

impl Scatter for Product<'_> {
    #[inline]
    fn add(&mut self, i: usize, j: usize, v: f64) {
        self.y[i] += self.scale * v * self.x[j];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A = [[0, 2, 1], [1, 1, 0], [3, 0, 1]] (needs pivoting), x = [1, −2, 3].
    fn system() -> ([[f64; 3]; 3], [f64; 3], Vec<f64>) {
        let a = [[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 1.0]];
        let x = [1.0, -2.0, 3.0];
        let b = (0..3)
            .map(|i| (0..3).map(|j| a[i][j] * x[j]).sum())
            .collect();
        (a, x, b)
    }

    #[test]
    fn dense_and_sparse_solve_a_system_that_needs_pivoting() {
        let (a, x, b) = system();
        let positions: Vec<(usize, usize)> = (0..3)
            .flat_map(|i| (0..3).map(move |j| (i, j)))
            .filter(|&(i, j)| a[i][j] != 0.0)
            .collect();
        for mut f in [
            Factorization::Dense(Box::new(DenseLu::new(3))),
            Factorization::Sparse(Box::new(SparseLu::new(3, &positions).unwrap())),
        ] {
            for _ in 0..2 {
                // Twice: the second factorization reuses every buffer.
                f.clear();
                for (i, j) in &positions {
                    f.add(*i, *j, a[*i][*j]);
                }
                f.factor().unwrap();
                let mut y = b.clone();
                f.solve_in_place(&mut y);
                for i in 0..3 {
                    assert!(
                        (y[i] - x[i]).abs() < 1e-14,
                        "sparse {}: x[{i}] = {} vs {}",
                        f.is_sparse(),
                        y[i],
                        x[i]
                    );
                }
            }
        }
    }

    #[test]
    fn sparse_pattern_grows_by_entries_outside_it() {
        let (a, x, b) = system();
        // Start from the diagonal only: the rest arrives outside the pattern.
        let mut f = SparseLu::new(3, &[(0, 0), (1, 1), (2, 2)]).unwrap();
        for (i, row) in a.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                f.add(i, j, v);
            }
        }
        f.factor().unwrap();
        let mut y = b.clone();
        f.solve_in_place(&mut y);
        for i in 0..3 {
            assert!((y[i] - x[i]).abs() < 1e-14, "x[{i}] = {} vs {}", y[i], x[i]);
        }
        assert_eq!(f.nonzeros(), 7, "pattern grown to the 7 nonzeros of A");
    }

    #[test]
    fn both_report_a_singular_matrix() {
        let positions = [(0, 0), (0, 1), (1, 0), (1, 1)];
        for mut f in [
            Factorization::Dense(Box::new(DenseLu::new(2))),
            Factorization::Sparse(Box::new(SparseLu::new(2, &positions).unwrap())),
        ] {
            // Rank one, and a zero column.
            for (i, j, v) in [(0, 0, 1.0), (1, 0, 2.0)] {
                f.add(i, j, v);
            }
            assert!(
                matches!(f.factor(), Err(FactorFailure::Singular { .. })),
                "sparse {}: a matrix with a zero column is singular",
                f.is_sparse()
            );
        }
    }

    proptest::proptest! {
        /// Any size (every register tail of the vectorized product, odd
        /// and even counts), rows and columns scaled over six orders as a
        /// beam's positions against its slopes and a constraint's rows: the
        /// dense solve's x satisfies A x = b to round-off (backward error
        /// below 1e-13 of |A||x| row by row), as faer's sparse LU's does.
        /// (Their x differ by more than that where the scales spread:
        /// 1.5e-12 of x at n = 17, as cond(A) allows.)
        #[test]
        fn dense_solve_is_a_solution_at_any_size(
            n in 1usize..60,
            seed in 0u64..1000,
        ) {
            let mut state = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            let mut next = move || {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            };
            let scale: Vec<f64> = (0..n).map(|_| 10f64.powf(6.0 * next())).collect();
            let mut a = vec![vec![0.0; n]; n];
            for (i, row) in a.iter_mut().enumerate() {
                for (j, v) in row.iter_mut().enumerate() {
                    let d = if i == j { 2.0 * n as f64 } else { next() };
                    *v = scale[i] * d * scale[j];
                }
            }
            let x: Vec<f64> = (0..n).map(|_| next()).collect();
            let b: Vec<f64> = a.iter().map(|row| row.iter().zip(&x).map(|(a, x)| a * x).sum()).collect();
            let positions: Vec<(usize, usize)> = (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).collect();
            for mut f in [
                Factorization::Dense(Box::new(DenseLu::new(n))),
                Factorization::Sparse(Box::new(SparseLu::new(n, &positions).unwrap())),
            ] {
                for &(i, j) in &positions {
                    f.add(i, j, a[i][j]);
                }
                f.factor().unwrap();
                let mut y = b.clone();
                f.solve_in_place(&mut y);
                for (i, row) in a.iter().enumerate() {
                    let r: f64 = row.iter().zip(&y).map(|(a, y)| a * y).sum::<f64>() - b[i];
                    let size: f64 = row.iter().zip(&y).map(|(a, y)| (a * y).abs()).sum();
                    proptest::prop_assert!(
                        r.abs() <= 1e-13 * size.max(f64::MIN_POSITIVE),
                        "n = {n}, sparse {}: row {i} residual {r:e} of {size:e}",
                        f.is_sparse()
                    );
                }
            }
        }
    }
}
