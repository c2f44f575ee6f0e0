//! Conserved quantities of a state: kinetic energy ½ q̇ᵀMq̇ [SI: J], linear
//! momentum [SI: kg m/s] and angular momentum about the origin
//! [SI: kg m²/s]. For a beam, p = ∫ρA ṙ dx and L = ∫ρA r × ṙ dx, integrated
//! exactly (4-point Gauss: r and ṙ are cubic in x).

use super::System;
use crate::mechanics::element::{gauss01, shape};
use nalgebra::Vector2;

impl System {
    /// ½ q̇ᵀ M q̇ with a precomputed mass matrix.
    pub fn kinetic_energy(&self, mass: &faer::Mat<f64>, v: &[f64]) -> f64 {
        0.5 * self.mass_quadratic_form(mass, v)
    }

    /// Linear momentum and angular momentum about the origin.
    pub fn momentum(&self, q: &[f64], v: &[f64]) -> (Vector2<f64>, f64) {
        let (mut p, mut l) = (Vector2::zeros(), 0.0);
        let gauss = gauss01(4);
        for b in &self.beams {
            for (k, el) in b.elements.iter().enumerate() {
                let dofs = b.element_dofs(k);
                for &(xi, w) in &gauss {
                    let s = shape(el.le, xi).s;
                    let (mut r, mut rd) = (Vector2::zeros(), Vector2::zeros());
                    for i in 0..4 {
                        r += Vector2::new(q[dofs[2 * i]], q[dofs[2 * i + 1]]) * s[i];
                        rd += Vector2::new(v[dofs[2 * i]], v[dofs[2 * i + 1]]) * s[i];
                    }
                    let dm = b.section.rho_a * el.le * w;
                    p += rd * dm;
                    l += dm * (r.x * rd.y - r.y * rd.x);
                }
            }
        }
        for rb in &self.rigid_bodies {
            let (r, rd) = (
                Vector2::new(q[rb.dof0], q[rb.dof0 + 1]),
                Vector2::new(v[rb.dof0], v[rb.dof0 + 1]),
            );
            p += rd * rb.mass;
            l += rb.mass * (r.x * rd.y - r.y * rd.x) + rb.inertia * v[rb.dof0 + 2];
        }
        for pm in &self.point_masses {
            let (r, rd) = (
                Vector2::new(q[pm.dof0], q[pm.dof0 + 1]),
                Vector2::new(v[pm.dof0], v[pm.dof0 + 1]),
            );
            p += rd * pm.mass;
            l += pm.mass * (r.x * rd.y - r.y * rd.x);
        }
        (p, l)
    }
}
