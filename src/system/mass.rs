//! The constant mass matrix M [SI: kg for positions, kg·m for
//! position–slope couplings, kg·m² for slopes and rotations], assembled once
//! per [`System`] on first use and kept with its nonzero pattern.
//!
//! M depends only on the mesh, the sections and the body masses, all fixed
//! when the system is built, so it is cached rather than re-assembled by
//! every modal analysis. The kinetic form φᵀMφ [SI: kg m²/s² per (unit
//! amplitude)² …] runs over the nonzeros of the lower triangle (a beam node
//! couples with its neighbours only), not over all n² entries.

use super::System;
use crate::linalg::Scatter;
use faer::Mat;
use std::sync::OnceLock;

/// M as the nonzeros of its lower triangle; the dense matrix is formed only
/// when a small-problem path asks for it.
#[derive(Debug, Clone)]
pub struct MassMatrix {
    n: usize,
    /// (i, j, w·M_ij) for i ≥ j and M_ij ≠ 0, w = 2 off the diagonal, sorted
    /// by column then row.
    lower: Vec<(usize, usize, f64)>,
    dense: OnceLock<Mat<f64>>,
}

impl MassMatrix {
    /// Assemble M from the consistent element masses and the lumped rigid
    /// bodies and point masses, in memory proportional to the nonzeros.
    pub(super) fn assemble(system: &System) -> MassMatrix {
        let n = system.ndof();
        let mut entries: Vec<(usize, usize, f64)> = Vec::new();
        for b in &system.beams {
            for (k, e) in b.elements.iter().enumerate() {
                let local = e.mass();
                let dofs = b.element_dofs(k);
                for (i, &gi) in dofs.iter().enumerate() {
                    for (j, &gj) in dofs.iter().enumerate() {
                        if gi >= gj && local[(i, j)] != 0.0 {
                            entries.push((gi, gj, local[(i, j)]));
                        }
                    }
                }
            }
        }
        for r in &system.rigid_bodies {
            entries.push((r.dof0, r.dof0, r.mass));
            entries.push((r.dof0 + 1, r.dof0 + 1, r.mass));
            entries.push((r.dof0 + 2, r.dof0 + 2, r.inertia));
        }
        for p in &system.point_masses {
            entries.push((p.dof0, p.dof0, p.mass));
            entries.push((p.dof0 + 1, p.dof0 + 1, p.mass));
        }
        // Sum repeated positions (in assembly order, as a dense sum would).
        let entries = sorted_by_column_then_row(n, entries);
        let mut lower: Vec<(usize, usize, f64)> = Vec::with_capacity(entries.len());
        for (i, j, v) in entries {
            match lower.last_mut() {
                Some(last) if last.0 == i && last.1 == j => last.2 += v,
                _ => lower.push((i, j, v)),
            }
        }
        lower.retain(|e| e.2 != 0.0);
        for e in &mut lower {
            if e.0 != e.1 {
                e.2 *= 2.0;
            }
        }
        MassMatrix {
            n,
            lower,
            dense: OnceLock::new(),
        }
    }

    /// The diagonal entries M_ii.
    pub fn diagonal(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.n];
        for &(i, j, w) in &self.lower {
            if i == j {
                d[i] = w;
            }
        }
        d
    }

    /// y = M x over the nonzeros.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for &(i, j, w) in &self.lower {
            if i == j {
                y[i] += w * x[i];
            } else {
                let v = 0.5 * w;
                y[i] += v * x[j];
                y[j] += v * x[i];
            }
        }
    }

    /// Adds M into any assembly target (its nonzeros only).
    pub fn add_into(&self, out: &mut impl Scatter) {
        for &(i, j, w) in &self.lower {
            if i == j {
                out.add(i, i, w);
            } else {
                out.add(i, j, 0.5 * w);
                out.add(j, i, 0.5 * w);
            }
        }
    }

    /// The dense n × n matrix (formed on the first call: small problems only).
    pub fn dense(&self) -> &Mat<f64> {
        self.dense.get_or_init(|| {
            let mut m = Mat::zeros(self.n, self.n);
            self.add_into(&mut m);
            m
        })
    }

    /// The kinetic forms vᵀMv of many sparse vectors at once, in one pass
    /// over the nonzeros: `by_coord[i]` lists (vector, value) of every
    /// vector nonzero at coordinate i.
    pub fn sparse_quadratic_forms(&self, by_coord: &[Vec<(usize, f64)>], count: usize) -> Vec<f64> {
        let mut out = vec![0.0; count];
        for &(i, j, w) in &self.lower {
            for &(f, vi) in &by_coord[i] {
                if let Some(&(_, vj)) = by_coord[j].iter().find(|e| e.0 == f) {
                    out[f] += w * vi * vj;
                }
            }
        }
        out
    }

    /// φᵀ M φ over the nonzeros (four partial sums).
    pub fn quadratic_form(&self, phi: &[f64]) -> f64 {
        let mut acc = [0.0; 4];
        let chunks = self.lower.chunks_exact(4);
        let rest = chunks.remainder();
        for c in chunks {
            for (a, &(i, j, v)) in acc.iter_mut().zip(c) {
                *a += v * phi[i] * phi[j];
            }
        }
        for (a, &(i, j, v)) in acc.iter_mut().zip(rest) {
            *a += v * phi[i] * phi[j];
        }
        (acc[0] + acc[2]) + (acc[1] + acc[3])
    }
}

/// The entries in the order a stable sort by (column, row) gives, in time
/// linear in their number: a counting sort by column, then each column's
/// few entries stably by row (a comparison sort of a 100,000-element
/// beam's 3.6 million entries was a twelfth of its modal analysis).
fn sorted_by_column_then_row(
    n: usize,
    entries: Vec<(usize, usize, f64)>,
) -> Vec<(usize, usize, f64)> {
    let mut start = vec![0usize; n + 1];
    for &(_, j, _) in &entries {
        start[j + 1] += 1;
    }
    for j in 0..n {
        start[j + 1] += start[j];
    }
    let mut next = start.clone();
    let mut sorted = vec![(0, 0, 0.0); entries.len()];
    for e in entries {
        sorted[next[e.1]] = e;
        next[e.1] += 1;
    }
    for w in start.windows(2) {
        sorted[w[0]..w[1]].sort_by_key(|e| e.0);
    }
    sorted
}

#[cfg(test)]
mod tests {
    use crate::{Model, System};
    use proptest::prelude::*;

    proptest! {
        /// The counting sort orders entries, repeated positions included,
        /// exactly as the standard library's stable sort by (column, row).
        #[test]
        fn the_counting_sort_is_the_stable_sort(
            entries in prop::collection::vec((0usize..12, 0usize..12, -1.0f64..1.0), 0..300)
        ) {
            let mut stable = entries.clone();
            stable.sort_by_key(|&(i, j, _)| (j, i));
            prop_assert_eq!(super::sorted_by_column_then_row(12, entries), stable);
        }
    }

    #[test]
    fn sparse_quadratic_form_matches_the_dense_product() {
        let system = System::new(&Model::builtin());
        let n = system.ndof();
        let phi: Vec<f64> = (0..n).map(|i| (0.37 * i as f64).sin()).collect();
        let m = system.mass().dense();
        let dense: f64 = (0..n)
            .map(|i| phi[i] * (0..n).map(|j| m[(i, j)] * phi[j]).sum::<f64>())
            .sum();
        let sparse = system.mass().quadratic_form(&phi);
        assert!(
            (sparse - dense).abs() <= 1e-13 * dense.abs(),
            "φᵀMφ sparse {sparse:e} vs dense {dense:e}: relative difference above 1e-13"
        );
    }
}
