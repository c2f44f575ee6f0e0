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
use faer::Mat;

/// M, dense and as the nonzeros of its lower triangle.
#[derive(Debug, Clone)]
pub struct MassMatrix {
    dense: Mat<f64>,
    /// (i, j, w·M_ij) for i ≥ j and M_ij ≠ 0, w = 2 off the diagonal.
    lower: Vec<(usize, usize, f64)>,
}

impl MassMatrix {
    /// Assemble M from the consistent element masses and the lumped rigid
    /// bodies and point masses.
    pub(super) fn assemble(system: &System) -> MassMatrix {
        let n = system.ndof();
        let mut m = Mat::zeros(n, n);
        for b in &system.beams {
            for (k, e) in b.elements.iter().enumerate() {
                let local = e.mass();
                let dofs = b.element_dofs(k);
                for (i, &gi) in dofs.iter().enumerate() {
                    for (j, &gj) in dofs.iter().enumerate() {
                        m[(gi, gj)] += local[(i, j)];
                    }
                }
            }
        }
        for r in &system.rigid_bodies {
            m[(r.dof0, r.dof0)] += r.mass;
            m[(r.dof0 + 1, r.dof0 + 1)] += r.mass;
            m[(r.dof0 + 2, r.dof0 + 2)] += r.inertia;
        }
        for p in &system.point_masses {
            m[(p.dof0, p.dof0)] += p.mass;
            m[(p.dof0 + 1, p.dof0 + 1)] += p.mass;
        }
        let mut lower = Vec::new();
        for j in 0..n {
            for (i, &v) in m.col_as_slice(j).iter().enumerate().skip(j) {
                if v != 0.0 {
                    lower.push((i, j, if i == j { v } else { 2.0 * v }));
                }
            }
        }
        MassMatrix { dense: m, lower }
    }

    /// The dense n × n matrix.
    pub fn dense(&self) -> &Mat<f64> {
        &self.dense
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

#[cfg(test)]
mod tests {
    use crate::{Model, System};

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
