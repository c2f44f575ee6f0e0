//! The energy books of one step, in the scheme's own discrete terms.
//!
//! With M constant and M a = Q at both ends of a step (generalized-α
//! satisfies the equations of motion at every step's end), the kinetic
//! energy changes by
//!
//! ΔT = ½(v₀ + v₁)ᵀMΔv = ½(Q₀ + Q₁)ᵀΔq − D_num,
//! D_num = ½(a₀ + a₁)ᵀMΔq − ½(v₀ + v₁)ᵀMΔv [SI: J].
//!
//! Each force's share ½(Q₀ + Q₁)ᵀΔq is its work over the step by the
//! trapezoidal rule in q: for the internal forces of a quadratic energy it
//! is −ΔU exactly, for the loads it is their work, for the Rayleigh
//! damping C q̇ the energy it absorbs, and for the joints' reactions
//! C_qᵀλ it vanishes with linear constraints. D_num is then the energy the
//! integrator itself removes: zero for the trapezoidal rule (ρ∞ = 1, where
//! Δq = h(v₀ + v₁)/2 and Δv = h(a₀ + a₁)/2), positive when the high
//! frequencies are damped (ρ∞ < 1). What is left of the balance once these
//! terms are booked is the quadrature's error on nonlinear forces and the
//! joints' work: the run's error proper, which a smaller step reduces.

use super::rayleigh::RayleighForce;
use super::solver::Positions;
use super::State;
use crate::system::System;

/// Scratch vectors for the step's energy terms (length n each).
pub(super) struct StepLedger {
    difference: Vec<f64>,
    product: Vec<f64>,
}

impl StepLedger {
    pub(super) fn new(n: usize) -> Self {
        StepLedger {
            difference: vec![0.0; n],
            product: vec![0.0; n],
        }
    }

    /// D_num of the step `from` → `to` [SI: J] (see the module's docs).
    pub(super) fn numerical_dissipation(&mut self, sys: &System, from: &State, to: &State) -> f64 {
        let mass = sys.mass();
        let mut d = 0.0;
        for (dq, (q1, q0)) in self.difference.iter_mut().zip(to.q.iter().zip(&from.q)) {
            *dq = q1 - q0;
        }
        mass.mul_vec(&self.difference, &mut self.product);
        for (m_dq, (a1, a0)) in self.product.iter().zip(to.a.iter().zip(&from.a)) {
            d += 0.5 * (a0 + a1) * m_dq;
        }
        for (dv, (v1, v0)) in self.difference.iter_mut().zip(to.v.iter().zip(&from.v)) {
            *dv = v1 - v0;
        }
        mass.mul_vec(&self.difference, &mut self.product);
        for (m_dv, (v1, v0)) in self.product.iter().zip(to.v.iter().zip(&from.v)) {
            d -= 0.5 * (v0 + v1) * m_dv;
        }
        d
    }

    /// The energy the model's damping absorbs over the step `from` → `to`,
    /// ½(D₀ + D₁)ᵀΔq [SI: J]: the springs' dampers and the Rayleigh
    /// damping C q̇ (the contacts book their own, [`super::contacts`]).
    pub(super) fn damping_dissipation(
        &mut self,
        sys: &System,
        mut rayleigh: Option<&mut RayleighForce>,
        from: &State,
        to: &State,
    ) -> f64 {
        self.product.fill(0.0);
        let mut any = false;
        for st in [from, to] {
            any |= sys.add_damping(&st.q, &st.v, &mut self.product, None::<&mut Positions>);
            if let Some(r) = rayleigh.as_deref_mut() {
                r.add_force(sys, &st.q, &st.v, &mut self.product);
                any = true;
            }
        }
        if !any {
            return 0.0;
        }
        self.product
            .iter()
            .zip(to.q.iter().zip(&from.q))
            .map(|(f, (q1, q0))| 0.5 * f * (q1 - q0))
            .sum()
    }
}
