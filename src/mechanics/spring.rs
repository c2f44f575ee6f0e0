//! Springs and dampers between two anchors.
//!
//! - [`LinearSpring`]: force along the line of its points,
//!   tension T = k (l − l₀) + c l̇ [SI: N], energy ½ k (l − l₀)².
//! - [`TorsionSpring`]: on a pin, moment M = k_t φ + c_t φ̇ [SI: N m] with
//!   φ = θ_b − θ_a − Δ₀ [rad], energy ½ k_t φ².
//!
//! Both expose the elastic energy, its gradient (the generalized internal
//! force, `∂U/∂q`) and its Hessian (the spring's tangent stiffness, including
//! the geometric part from the force turning with the line), plus the damping
//! force and its q̇-Jacobian. Everything is written into local pair buffers.

use crate::mechanics::pair::{Pair, PairGrad, PairHess, PairJac2};

/// An elastic element with optional viscous damping.
pub trait ForceElement: std::fmt::Debug + Send + Sync {
    fn label(&self) -> &str;
    fn pair(&self) -> &Pair;
    /// Elastic energy [SI: J].
    fn energy(&self, q: &[f64]) -> f64;
    /// Elastic force or moment (tension positive) [SI: N or N m].
    fn elastic_force(&self, q: &[f64]) -> f64;
    /// ∂U/∂q (local), overwritten.
    fn gradient(&self, q: &[f64], out: &mut PairGrad);
    /// ∂²U/∂q² (local), overwritten.
    fn hessian(&self, q: &[f64], out: &mut PairHess);
    /// Whether the element has a damper (when not, [`ForceElement::damping`]
    /// is always `false`).
    fn has_damper(&self) -> bool;
    /// Damping force c ṡ ∂s/∂q (local, overwritten) and its q̇-Jacobian
    /// c ∂s/∂q ∂s/∂qᵀ; `false` when the element has no damper.
    fn damping(
        &self,
        q: &[f64],
        qd_local: &PairGrad,
        force: &mut PairGrad,
        matrix: &mut PairHess,
    ) -> bool;
}

/// A damper on the rate ṡ = gᵀq̇ of a scalar s(q) with gradient g:
/// force c ṡ g and q̇-Jacobian c g gᵀ.
fn viscous(g: &PairGrad, c: f64, qd: &PairGrad, force: &mut PairGrad, matrix: &mut PairHess) {
    *force = g * (c * g.dot(qd));
    *matrix = g * g.transpose() * c;
}

/// Translational spring-damper.
#[derive(Debug, Clone)]
pub struct LinearSpring {
    pub label: String,
    pub pair: Pair,
    /// Stiffness [SI: N/m].
    pub stiffness: f64,
    /// Damping [SI: N s/m].
    pub damping: f64,
    /// Free length [SI: m].
    pub free_length: f64,
}

impl LinearSpring {
    /// Length and dl/dq (local).
    fn length_gradient(&self, q: &[f64], jac: &mut PairJac2, grad: &mut PairGrad) -> f64 {
        let d = self.pair.separation(q);
        let l = d.norm();
        self.pair.separation_jacobian(q, jac);
        *grad = jac.transpose() * (d / l);
        l
    }
}

impl ForceElement for LinearSpring {
    fn label(&self) -> &str {
        &self.label
    }
    fn pair(&self) -> &Pair {
        &self.pair
    }
    fn energy(&self, q: &[f64]) -> f64 {
        let dl = self.pair.separation(q).norm() - self.free_length;
        0.5 * self.stiffness * dl * dl
    }
    fn elastic_force(&self, q: &[f64]) -> f64 {
        self.stiffness * (self.pair.separation(q).norm() - self.free_length)
    }
    fn gradient(&self, q: &[f64], out: &mut PairGrad) {
        let mut jac = PairJac2::zeros();
        let l = self.length_gradient(q, &mut jac, out);
        *out *= self.stiffness * (l - self.free_length);
    }
    fn hessian(&self, q: &[f64], out: &mut PairHess) {
        let d = self.pair.separation(q);
        let (mut jac, mut g) = (PairJac2::zeros(), PairGrad::zeros());
        let l = self.length_gradient(q, &mut jac, &mut g);
        let u = d / l;
        let tension = self.stiffness * (l - self.free_length);
        let transverse = nalgebra::Matrix2::identity() - u * u.transpose();
        *out =
            g * g.transpose() * self.stiffness + jac.transpose() * transverse * jac * (tension / l);
        self.pair.separation_hessian_dot(q, u * tension, out);
    }
    fn has_damper(&self) -> bool {
        self.damping != 0.0
    }
    fn damping(
        &self,
        q: &[f64],
        qd: &PairGrad,
        force: &mut PairGrad,
        matrix: &mut PairHess,
    ) -> bool {
        if self.damping == 0.0 {
            return false;
        }
        let (mut jac, mut g) = (PairJac2::zeros(), PairGrad::zeros());
        self.length_gradient(q, &mut jac, &mut g);
        viscous(&g, self.damping, qd, force, matrix);
        true
    }
}

/// Torsional spring-damper of a pin.
#[derive(Debug, Clone)]
pub struct TorsionSpring {
    pub label: String,
    pub pair: Pair,
    /// Stiffness [SI: N m/rad].
    pub stiffness: f64,
    /// Damping [SI: N m s/rad].
    pub damping: f64,
    /// Unstressed relative angle θ_b − θ_a [rad].
    pub offset: f64,
}

impl ForceElement for TorsionSpring {
    fn label(&self) -> &str {
        &self.label
    }
    fn pair(&self) -> &Pair {
        &self.pair
    }
    fn energy(&self, q: &[f64]) -> f64 {
        let phi = self.pair.relative_angle(q, self.offset);
        0.5 * self.stiffness * phi * phi
    }
    fn elastic_force(&self, q: &[f64]) -> f64 {
        self.stiffness * self.pair.relative_angle(q, self.offset)
    }
    fn gradient(&self, q: &[f64], out: &mut PairGrad) {
        self.pair.relative_angle_derivatives(q, out, None);
        *out *= self.elastic_force(q);
    }
    fn hessian(&self, q: &[f64], out: &mut PairHess) {
        let mut g = PairGrad::zeros();
        self.pair.relative_angle_derivatives(q, &mut g, Some(out));
        *out *= self.elastic_force(q);
        *out += g * g.transpose() * self.stiffness;
    }
    fn has_damper(&self) -> bool {
        self.damping != 0.0
    }
    fn damping(
        &self,
        q: &[f64],
        qd: &PairGrad,
        force: &mut PairGrad,
        matrix: &mut PairHess,
    ) -> bool {
        if self.damping == 0.0 {
            return false;
        }
        let mut g = PairGrad::zeros();
        self.pair.relative_angle_derivatives(q, &mut g, None);
        viscous(&g, self.damping, qd, force, matrix);
        true
    }
}
