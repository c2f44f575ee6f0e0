//! Contacts in the time integration: the dissipative contact forces in the
//! residual and their Jacobians in the iteration matrix, the impact speed
//! each hysteresis law needs, impact statistics, and the step control at
//! contact onset.
//!
//! Impact speed δ̇⁻: a contact open at the start of a step that closes in
//! it takes the approach speed at the step's start, max(δ̇(t₀), 0); the
//! value is then kept for the whole impact (the law floors it at its
//! `min_impact_velocity`). A contact already closed at t = 0 (a pre-stressed
//! equilibrium) has had no impact: it is elastic, F = Kδⁿ with no
//! hysteresis term (friction, if any, on that force), until it first
//! separates (δ ≤ 0 at the end of an accepted step); every later closing is
//! an impact with its measured approach speed. A contact that never opens
//! stays elastic (the model's Rayleigh damping damps the structure).
//!
//! Step control (as DyS shortens the step at contact onset): a step in
//! which a contact closes is accepted only if its first penetration δ₁ is at
//! most [`ONSET_FRACTION`] of the impact's expected largest penetration
//! δ_max (an impact at the approach speed of the contact's effective mass
//! on the elastic law: ½mv² = Kδⁿ⁺¹/(n + 1), see
//! [`crate::mechanics::contact::law::NormalLaw::max_penetration`]); otherwise it is
//! repeated with a shorter step. While an impact lasts, steps are held to
//! 1/[`STEPS_PER_IMPACT`] of its expected duration ≈ 3 δ_max/v (Hertz:
//! 2.94 δ_max/v; linear: π δ_max/v).

use crate::linalg::Scatter;
use crate::mechanics::contact::Dissipation;
use crate::mechanics::pair::PairGrad;
use crate::mechanics::spring::ForceElement;
use crate::system::System;

/// Largest first penetration, as a fraction of the expected δ_max.
pub const ONSET_FRACTION: f64 = 0.02;
/// Steps per expected impact duration.
pub const STEPS_PER_IMPACT: f64 = 25.0;

/// What a run saw of one contact.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct ContactStats {
    /// The contact's id in the model.
    pub id: String,
    /// Largest penetration [SI: m] (0 if it never closed).
    #[serde(rename = "max_penetration_m")]
    pub max_penetration: f64,
    /// Largest normal force [SI: N].
    #[serde(rename = "max_force_n")]
    pub max_force: f64,
    /// Number of closings during the run (a contact closed at t = 0 does
    /// not count).
    pub impacts: usize,
    /// Energy dissipated by its damping and friction [SI: J].
    #[serde(rename = "dissipated_j")]
    pub dissipated: f64,
    /// The normal force F(δ, δ̇) at the output sample times [SI: N]
    /// (filled by [`crate::analysis::simulate::simulate`]; empty from the
    /// integrator alone).
    pub force_n: Vec<f64>,
}

/// The contact state of a transient: which contacts are closed, their
/// impact speeds, and the statistics.
#[derive(Debug, Clone)]
pub struct ContactTracker {
    closed: Vec<bool>,
    /// δ̇⁻ of each contact for the current step [SI: m/s]; `None` while a
    /// contact closed since the start has not separated (elastic).
    pub impact: Vec<Option<f64>>,
    /// Each contact's normal force F(δ, δ̇) at the last accepted state
    /// [SI: N] (0 when open).
    pub force: Vec<f64>,
    /// Effective masses [SI: kg] (step control).
    mass: Vec<f64>,
    pub stats: Vec<ContactStats>,
    /// Upper bound on the step while impacts last [SI: s].
    pub step_limit: f64,
    /// When each contact's current impact started [SI: s] (`None`: open,
    /// or closed since the start of the run).
    impact_start: Vec<Option<f64>>,
}

impl ContactTracker {
    /// The tracker at the initial state q.
    pub fn new(sys: &System, q: &[f64]) -> ContactTracker {
        let diag = sys.mass().diagonal();
        let closed: Vec<bool> = sys
            .contacts
            .iter()
            .map(|c| c.penetration(q) > 0.0)
            .collect();
        ContactTracker {
            impact: sys
                .contacts
                .iter()
                .zip(&closed)
                .map(|(c, &on)| (!on).then_some(c.law.min_impact_velocity))
                .collect(),
            force: sys.contacts.iter().map(|c| c.elastic_force(q)).collect(),
            mass: sys
                .contacts
                .iter()
                .map(|c| c.effective_mass(q, &diag))
                .collect(),
            stats: sys
                .contacts
                .iter()
                .zip(&closed)
                .map(|(c, &on)| ContactStats {
                    id: c.label.clone(),
                    max_penetration: if on { c.penetration(q) } else { 0.0 },
                    ..ContactStats::default()
                })
                .collect(),
            impact_start: vec![None; closed.len()],
            closed,
            step_limit: f64::INFINITY,
        }
    }

    /// Prepare a step from (q, v): open contacts take their current
    /// approach speed as the impact speed they would close with.
    pub fn begin_step(&mut self, sys: &System, q: &[f64], v: &[f64]) {
        for (i, c) in sys.contacts.iter().enumerate() {
            if !self.closed[i] {
                self.impact[i] = Some(c.rate(q, v).max(0.0));
            }
        }
    }

    /// Check a step from `q0` to (q1, v1) of length h: `Some(shorter
    /// step)` if a contact closed too deep, else `None` (then
    /// [`ContactTracker::accept`]).
    pub fn onset_check(&self, sys: &System, q1: &[f64], h: f64) -> Option<f64> {
        let mut shrink: f64 = 1.0;
        for (i, c) in sys.contacts.iter().enumerate() {
            if self.closed[i] {
                continue;
            }
            let delta = c.penetration(q1);
            if delta <= 0.0 {
                continue;
            }
            let speed = self.impact[i].unwrap_or(0.0).max(c.law.min_impact_velocity);
            let allowed = ONSET_FRACTION * c.law.max_penetration(self.mass[i], speed);
            if delta > allowed {
                shrink = shrink.min((allowed / delta).clamp(0.1, 0.5));
            }
        }
        (shrink < 1.0).then_some(h * shrink)
    }

    /// Record an accepted step of length h ending at (t, q, v).
    pub fn accept(&mut self, sys: &System, (t, q, v): (f64, &[f64], &[f64]), h: f64) {
        self.step_limit = f64::INFINITY;
        let mut d = Dissipation::default();
        for (i, c) in sys.contacts.iter().enumerate() {
            let delta = c.penetration(q);
            let closed = delta > 0.0;
            if closed && !self.closed[i] {
                self.stats[i].impacts += 1;
                self.impact_start[i] = Some(t - h);
            }
            self.closed[i] = closed;
            if !closed {
                self.impact_start[i] = None;
                self.force[i] = 0.0;
                continue;
            }
            let local = local_velocity(c.pair().dofs(), v);
            c.dissipation(q, &local, self.impact[i], &mut d);
            let s = &mut self.stats[i];
            s.max_penetration = s.max_penetration.max(delta);
            s.max_force = s.max_force.max(d.normal_force);
            s.dissipated += h * d.force.dot(&local);
            self.force[i] = d.normal_force;
            // Short steps while an impact lasts (twice its expected
            // duration); a contact at rest keeps the nominal step.
            let speed = self.impact[i].unwrap_or(0.0).max(c.law.min_impact_velocity);
            let duration = 3.0 * c.law.max_penetration(self.mass[i], speed) / speed;
            if let Some(t0) = self.impact_start[i] {
                if t - t0 < 2.0 * duration {
                    self.step_limit = self.step_limit.min(duration / STEPS_PER_IMPACT);
                }
            }
        }
    }
}

fn local_velocity(dofs: impl Iterator<Item = usize>, v: &[f64]) -> PairGrad {
    let mut local = PairGrad::zeros();
    for (i, d) in dofs.enumerate() {
        local[i] = v[d];
    }
    local
}

/// Adds the contacts' dissipative forces at (q, v) into `out` and, if
/// given, (s_q ∂/∂q + s_v ∂/∂q̇) of them into `matrix`.
pub fn add_contact_dissipation<S: Scatter>(
    sys: &System,
    q: &[f64],
    v: &[f64],
    impact: &[Option<f64>],
    out: &mut [f64],
    mut matrix: Option<(f64, f64, &mut S)>,
) {
    if sys.contacts.is_empty() {
        // No 4 KiB of contact scratch zeroed at every residual.
        return;
    }
    let mut d = Dissipation::default();
    for (c, &w) in sys.contacts.iter().zip(impact) {
        let local = local_velocity(c.pair().dofs(), v);
        if !c.dissipation(q, &local, w, &mut d) {
            continue;
        }
        let dofs = || c.pair().dofs().enumerate();
        for (i, gi) in dofs() {
            out[gi] += d.force[i];
        }
        if let Some((sq, sv, m)) = matrix.as_mut() {
            for (i, gi) in dofs() {
                for (j, gj) in dofs() {
                    m.add(gi, gj, *sq * d.dq[(i, j)] + *sv * d.dv[(i, j)]);
                }
            }
        }
    }
}
