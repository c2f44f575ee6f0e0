//! How far Euler–Bernoulli beam theory (the ANCF cable elements) is from
//! Timoshenko theory for each bending mode, estimated from the mode's own
//! shape.
//!
//! Timoshenko theory adds rotary inertia (kinetic energy ½ρI∫θ̇²) and shear
//! flexibility (bending stiffness seen through EI/(κGA) of shear
//! compliance). To first order in r² = I/A (= h²/12 for a rectangle) both
//! lower ω² in proportion to ∫w′² of the bending shape, the rotary part by
//! ρI∫w′²/T and the shear part E/(κG) times that, so that for one beam
//!
//!   Δf/f ≈ −½ r² (∫w′² / ∫w²) (1 + E/(κG)),   G = E/(2(1 + ν)), κ = 5/6,
//!
//! (exact to first order for a sinusoidal shape: the simply supported
//! beam). In an assembly the beam's ρA∫w² is replaced by the whole mode's
//! kinetic norm φᵀMφ (rigid bodies and point masses move with the mode but
//! add no rotary or shear correction), and the beams' contributions add:
//!
//!   Δf/f ≈ −½ Σ_beams ρA r² (1 + 2(1 + ν)/κ) ∫w′² ds / φᵀMφ.
//!
//! w is the displacement normal to the beam's reference axis, w′ its
//! derivative along the arc length s [SI: m]; the result is a relative
//! frequency change [–], negative (Euler–Bernoulli frequencies are high).
//! Poisson's ratio ν is the material's `poisson`, [`DEFAULT_POISSON`] when
//! the model does not give one.

use super::{ModalResult, ModeKind};
use crate::mechanics::element::{gauss01, shape};
use crate::model::Model;
use crate::system::System;
use nalgebra::Vector2;

/// Timoshenko shear coefficient κ of a rectangular section.
pub const SHEAR_COEFFICIENT: f64 = 5.0 / 6.0;
/// Poisson's ratio ν used when a material does not give `poisson`.
pub const DEFAULT_POISSON: f64 = 0.3;
/// |Δf/f| above which the report warns that beam theory limits a mode.
pub const WARNING_LEVEL: f64 = 0.01;
/// |Δf/f| past which the first-order estimate says only that the mode is
/// far beyond beam theory (a height typed in mm gave "68775.5 %").
pub const FIRST_ORDER_REACH: f64 = 0.5;

/// One sentence for each mode of `result` whose Euler–Bernoulli frequency
/// is more than [`WARNING_LEVEL`] above Timoshenko theory's estimate.
pub fn beam_theory_warnings(result: &crate::analysis::ModalResult) -> Vec<String> {
    result
        .modes
        .iter()
        .filter_map(|m| {
            let e = m.shear_estimate.filter(|e| e.abs() > WARNING_LEVEL)?;
            Some(if e.abs() > FIRST_ORDER_REACH {
                format!(
                    "mode {} ({:.1} Hz): beam theory does not hold for it: shear and rotary inertia (Timoshenko) would lower it by more than half (the first-order estimate, {:.3e} %, is past its reach); are the section's sizes in metres?",
                    m.index,
                    m.frequency_hz,
                    -100.0 * e,
                )
            } else {
                format!(
                    "mode {} ({:.1} Hz): beam theory limits it: shear and rotary inertia (Timoshenko) would lower it by about {:.1} %, more than the {:.0} %",
                    m.index,
                    m.frequency_hz,
                    -100.0 * e,
                    100.0 * WARNING_LEVEL
                )
            })
        })
        .collect()
}

/// The estimate Δf/f for the mode `phi` (global coordinates) of `system`;
/// `poisson(beam id)` gives each beam's ν. `None` when φᵀMφ is not
/// positive (no motion).
pub fn shear_estimate(system: &System, poisson: &dyn Fn(&str) -> f64, phi: &[f64]) -> Option<f64> {
    let mut sum = 0.0;
    for beam in &system.beams {
        let section = beam.section;
        if section.ea <= 0.0 {
            continue;
        }
        let r2 = section.ei / section.ea;
        let factor = 1.0 + 2.0 * (1.0 + poisson(&beam.id)) / SHEAR_COEFFICIENT;
        let normal = Vector2::new(-beam.tangent.y, beam.tangent.x);
        let mut slope2 = 0.0;
        for (k, element) in beam.elements.iter().enumerate() {
            let dofs = beam.element_dofs(k);
            for (xi, weight) in gauss01(3) {
                let d1 = shape(element.le, xi).d1;
                let mut dr = Vector2::zeros();
                for i in 0..4 {
                    dr += d1[i] * Vector2::new(phi[dofs[2 * i]], phi[dofs[2 * i + 1]]);
                }
                slope2 += dr.dot(&normal).powi(2) * weight * element.le;
            }
        }
        sum += section.rho_a * r2 * factor * slope2;
    }
    let norm = system.mass().quadratic_form(phi);
    (norm > 0.0).then(|| -0.5 * sum / norm)
}

/// Sets `shear_estimate` of every bending mode of `result` (a modal
/// analysis of `system`, built from `model`); other modes keep `None`.
pub fn annotate(model: &Model, system: &System, result: &mut ModalResult) {
    let poisson = |id: &str| {
        model
            .beams
            .iter()
            .find(|b| b.id == id)
            .and_then(|b| b.material.poisson)
            .unwrap_or(DEFAULT_POISSON)
    };
    for mode in &mut result.modes {
        if mode.kind == ModeKind::Bending {
            mode.shear_estimate = shear_estimate(system, &poisson, &mode.shape);
        }
    }
}

/// Whether any beam of `model` leaves `poisson` out (the report then says
/// that ν = 0.3 was assumed).
pub fn poisson_assumed(model: &Model) -> bool {
    model.beams.iter().any(|b| b.material.poisson.is_none())
}
