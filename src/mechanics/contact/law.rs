//! Normal-force laws of a compliant contact: F(δ, δ̇) [SI: N] from the
//! penetration δ [SI: m] and its rate δ̇ [SI: m/s].
//!
//! - `linear`: F = kδ + dδ̇.
//! - `hertz`: F = Kδⁿ.
//! - hysteresis laws (Lankarani–Nikravesh, Hunt–Crossley, Flores):
//!   F = Kδⁿ(1 + ξ δ̇/δ̇⁻), δ̇⁻ the approach speed at the start of the
//!   impact (never below the law's minimum).
//!
//! F is clamped at 0: a contact pulls nothing, so a damped contact
//! separates before δ returns to 0. The elastic part F_e = Kδⁿ (kδ) has
//! the potential U = Kδⁿ⁺¹/(n + 1) and is what statics and modal analysis
//! see; the rest, F − F_e, is dissipative and acts in the transient only.

use crate::model::{ContactLaw, LawModel, DEFAULT_MIN_IMPACT_VELOCITY};

/// A law with its parameters resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalLaw {
    pub model: LawModel,
    /// k [SI: N/m] or K [SI: N/mⁿ].
    pub stiffness: f64,
    /// n [–] (1 for `linear`).
    pub exponent: f64,
    /// d [SI: N s/m] (`linear`).
    pub damping: f64,
    /// ξ [–] (hysteresis laws).
    pub xi: f64,
    /// δ̇⁻ floor [SI: m/s].
    pub min_impact_velocity: f64,
}

/// A normal force and its partial derivatives.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NormalForce {
    /// [SI: N]
    pub force: f64,
    /// ∂F/∂δ [SI: N/m]
    pub d_delta: f64,
    /// ∂F/∂δ̇ [SI: N s/m]
    pub d_rate: f64,
}

impl NormalLaw {
    pub fn new(law: &ContactLaw) -> NormalLaw {
        NormalLaw {
            model: law.model,
            stiffness: law.stiffness,
            exponent: law.exponent(),
            damping: law.damping.unwrap_or(0.0),
            xi: law.xi(),
            min_impact_velocity: law
                .min_impact_velocity
                .unwrap_or(DEFAULT_MIN_IMPACT_VELOCITY),
        }
    }

    /// Whether the law depends on δ̇ (and so on the impact velocity).
    pub fn is_damped(&self) -> bool {
        self.damping > 0.0 || self.xi > 0.0
    }

    /// The elastic part F_e = Kδⁿ and dF_e/dδ (zero for δ ≤ 0).
    pub fn elastic(&self, delta: f64) -> NormalForce {
        if delta <= 0.0 {
            return NormalForce::default();
        }
        let n = self.exponent;
        let dn1 = if n == 1.0 { 1.0 } else { delta.powf(n - 1.0) };
        NormalForce {
            force: self.stiffness * dn1 * delta,
            d_delta: n * self.stiffness * dn1,
            d_rate: 0.0,
        }
    }

    /// U = Kδⁿ⁺¹/(n + 1) [SI: J] (zero for δ ≤ 0).
    pub fn energy(&self, delta: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        self.elastic(delta).force * delta / (self.exponent + 1.0)
    }

    /// The full force F(δ, δ̇) ≥ 0 with the impact speed `impact` (δ̇⁻,
    /// floored at the law's minimum).
    pub fn total(&self, delta: f64, rate: f64, impact: f64) -> NormalForce {
        let e = self.elastic(delta);
        if delta <= 0.0 {
            return e;
        }
        let f = match self.model {
            LawModel::Linear => NormalForce {
                force: e.force + self.damping * rate,
                d_delta: e.d_delta,
                d_rate: self.damping,
            },
            LawModel::Hertz => e,
            _ => {
                let c = self.xi / impact.abs().max(self.min_impact_velocity);
                NormalForce {
                    force: e.force * (1.0 + c * rate),
                    d_delta: e.d_delta * (1.0 + c * rate),
                    d_rate: e.force * c,
                }
            }
        };
        if f.force > 0.0 {
            f
        } else {
            NormalForce::default()
        }
    }

    /// The dissipative remainder F − F_e and its derivatives.
    pub fn dissipative(&self, delta: f64, rate: f64, impact: f64) -> NormalForce {
        let (t, e) = (self.total(delta, rate, impact), self.elastic(delta));
        NormalForce {
            force: t.force - e.force,
            d_delta: t.d_delta - e.d_delta,
            d_rate: t.d_rate,
        }
    }

    /// The largest penetration of an impact at speed v₀ of a mass m on the
    /// elastic part alone [SI: m]: ½mv₀² = Kδⁿ⁺¹/(n + 1).
    pub fn max_penetration(&self, mass: f64, speed: f64) -> f64 {
        let n = self.exponent;
        ((n + 1.0) * mass * speed * speed / (2.0 * self.stiffness)).powf(1.0 / (n + 1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(model: LawModel, restitution: Option<f64>) -> NormalLaw {
        NormalLaw::new(&ContactLaw {
            model,
            stiffness: 1e9,
            damping: None,
            exponent: None,
            restitution,
            min_impact_velocity: None,
        })
    }

    #[test]
    fn derivatives_match_central_differences() {
        for (model, c) in [
            (LawModel::Hertz, None),
            (LawModel::LankaraniNikravesh, Some(0.7)),
            (LawModel::HuntCrossley, Some(0.7)),
            (LawModel::Flores, Some(0.7)),
        ] {
            let l = law(model, c);
            let (d, r, v) = (2e-6, -0.3, 0.5);
            let f = l.total(d, r, v);
            let (hd, hr) = (1e-6 * d, 1e-6);
            let fd = (l.total(d + hd, r, v).force - l.total(d - hd, r, v).force) / (2.0 * hd);
            let fr = (l.total(d, r + hr, v).force - l.total(d, r - hr, v).force) / (2.0 * hr);
            assert!((f.d_delta - fd).abs() <= 1e-7 * fd.abs(), "{model:?} ∂F/∂δ");
            assert!(
                (f.d_rate - fr).abs() <= 1e-6 * fr.abs().max(1.0),
                "{model:?} ∂F/∂δ̇"
            );
            // The energy is the integral of the elastic force: dU/dδ = F_e.
            let du = (l.energy(d + hd) - l.energy(d - hd)) / (2.0 * hd);
            assert!(
                (du - l.elastic(d).force).abs() <= 1e-7 * du,
                "{model:?} dU/dδ"
            );
        }
    }

    #[test]
    fn the_force_never_pulls() {
        let l = law(LawModel::Flores, Some(0.3));
        // A fast separation at a small penetration: Kδⁿ(1 + ξδ̇/δ̇⁻) < 0.
        let f = l.total(1e-7, -10.0, 0.1);
        assert_eq!(f, NormalForce::default());
        assert!(l.dissipative(1e-7, -10.0, 0.1).force < 0.0);
    }
}
