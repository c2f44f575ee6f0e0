//! Conserved quantities of a state: kinetic energy ½ q̇ᵀMq̇ [SI: J], linear
//! momentum [SI: kg m/s] and angular momentum about the origin
//! [SI: kg m²/s]. For a beam, p = ∫ρA ṙ dx and L = ∫ρA r × ṙ dx, integrated
//! exactly (4-point Gauss: r and ṙ are cubic in x).
//!
//! The total potential energy of a static state,
//! Π(q) = U_beams(q) + U_springs(q) − W_loads(q) − W_gravity(q) [SI: J],
//! measured from the reference q₀: loads are dead forces (fixed direction),
//! so their work is F·(r(q) − r(q₀)); gravity's generalized force is
//! constant, so its work is Q_gᵀ(q − q₀).

use super::System;
use crate::mechanics::element::{gauss01, shape};
use nalgebra::Vector2;

impl System {
    /// Total potential energy Π(q) − Π_loads(q₀) (see the module doc) with
    /// the loads at time `t` times `load_scale`; springs, torsion springs
    /// and contacts count with their elastic energy.
    pub fn potential_energy(&self, q: &[f64], t: f64, load_scale: f64) -> f64 {
        let strain = self.strain_energy(q);
        let mut pi = strain.axial + strain.bending + strain.springs;
        for l in &self.loads {
            let f = l.force_at(t) * load_scale;
            pi -= f.dot(&(l.anchor.position(q) - l.anchor.position(&self.q0)));
        }
        let mut g = vec![0.0; q.len()];
        self.add_gravity(&mut g);
        pi -= g
            .iter()
            .zip(q.iter().zip(&self.q0))
            .map(|(gi, (a, b))| gi * (a - b))
            .sum::<f64>();
        pi
    }

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
