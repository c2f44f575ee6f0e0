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

/// Scratch vectors for the step's energy terms (length n each), and the
/// damping force at the end of the last step booked: the next step's
/// start, unless contact step control took that step back (the cache is
/// keyed by the state's time and coordinates).
pub(super) struct StepLedger {
    difference: Vec<f64>,
    product: Vec<f64>,
    /// The damping force at a step's start, and at its end.
    start_force: Vec<f64>,
    end_force: Vec<f64>,
    /// The state `end_force` belongs to, and whether any damping acts.
    end_t: f64,
    end_q: Vec<f64>,
    end_any: bool,
}

impl StepLedger {
    pub(super) fn new(n: usize) -> Self {
        StepLedger {
            difference: vec![0.0; n],
            product: vec![0.0; n],
            start_force: vec![0.0; n],
            end_force: vec![0.0; n],
            end_t: f64::NAN,
            end_q: vec![0.0; n],
            end_any: false,
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
    /// D₀ is the last step's D₁ when `from` is that step's end: one force
    /// evaluation a step (two cost a Rayleigh-damped fork 37 % of its run).
    pub(super) fn damping_dissipation(
        &mut self,
        sys: &System,
        mut rayleigh: Option<&mut RayleighForce>,
        from: &State,
        to: &State,
    ) -> f64 {
        if rayleigh.is_none() && !sys.has_dampers() {
            // No damping force at any state: no books to keep.
            return 0.0;
        }
        if !(self.end_t == from.t && self.end_q == from.q) {
            self.end_any = damping_force(sys, rayleigh.as_deref_mut(), from, &mut self.end_force);
        }
        std::mem::swap(&mut self.start_force, &mut self.end_force);
        let any_start = self.end_any;
        self.end_any = damping_force(sys, rayleigh, to, &mut self.end_force);
        self.end_t = to.t;
        self.end_q.copy_from_slice(&to.q);
        if !(any_start || self.end_any) {
            return 0.0;
        }
        (self.start_force.iter().zip(&self.end_force))
            .zip(to.q.iter().zip(&from.q))
            .map(|((f0, f1), (q1, q0))| 0.5 * (f0 + f1) * (q1 - q0))
            .sum()
    }
}

/// out = D(q, q̇) of `st`, the springs' dampers and the Rayleigh force;
/// whether any damping acts.
fn damping_force(
    sys: &System,
    rayleigh: Option<&mut RayleighForce>,
    st: &State,
    out: &mut [f64],
) -> bool {
    out.fill(0.0);
    let springs = sys.add_damping(&st.q, &st.v, out, None::<&mut Positions>);
    match rayleigh {
        Some(r) => {
            r.add_force(sys, &st.q, &st.v, out);
            true
        }
        None => springs,
    }
}
