//! The model's FRF at a sensor, for the overlay on a measured one: modal
//! superposition of the elastic modes (rigid modes left out, as a
//! co-rotated vibrometer does not see them),
//!
//!   H(ω) = (iω)^p Σ_r s_r l_r / (ω_r² − ω² + 2iζ_r ω_r ω),
//!
//! with the mass-normalised shapes φ_r (φᵀMφ = 1): s_r the sensor point's
//! modal displacement along its measuring direction, l_r the load point's
//! along the first load's force direction, ζ_r the model's damping ratio
//! and p = 0, 1, 2 for displacement, velocity, acceleration. Units: m/N
//! times (1/s)^p.

use nalgebra::Vector2;
use realfft::num_complex::Complex64;

use crate::analysis::ModalResult;
use crate::model::SensorFrame;
use crate::system::System;

/// Why the model's FRF cannot be formed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ModelFrfError {
    #[error("the model has no sensor `{id}` (sensors: {available})")]
    UnknownSensor { id: String, available: String },
    #[error("the model has no load to excite it (the FRF is per newton of its first load)")]
    NoLoad,
}

/// H at `frequency_hz` (see the module doc); `zeta(ω_r)` gives each
/// mode's damping ratio; `power` is 0, 1 or 2.
pub fn model_frf(
    system: &System,
    modal: &ModalResult,
    sensor: &str,
    zeta: impl Fn(f64) -> f64,
    power: i32,
    frequency_hz: &[f64],
) -> Result<Vec<Complex64>, ModelFrfError> {
    let s = system
        .sensors
        .iter()
        .find(|p| p.id == sensor)
        .ok_or_else(|| ModelFrfError::UnknownSensor {
            id: sensor.to_string(),
            available: system
                .sensors
                .iter()
                .map(|p| p.id.clone())
                .collect::<Vec<_>>()
                .join(", "),
        })?;
    let load = system.loads.first().ok_or(ModelFrfError::NoLoad)?;
    let dir = match (s.frame, s.beam) {
        (SensorFrame::Corotated, Some(b)) => {
            let t = system.beams[b].tangent;
            t * s.direction.x + Vector2::new(-t.y, t.x) * s.direction.y
        }
        _ => s.direction,
    };
    let ldir = load.force / load.force.norm().max(f64::MIN_POSITIVE);
    let terms: Vec<(f64, f64, f64)> = modal
        .modes
        .iter()
        .filter(|m| !m.kind.is_zero())
        .map(|m| {
            let sr = dir.dot(&s.anchor.velocity(&system.q0, &m.shape));
            let lr = ldir.dot(&load.anchor.velocity(&system.q0, &m.shape));
            let w = 2.0 * std::f64::consts::PI * m.frequency_hz;
            (w, sr * lr, zeta(w))
        })
        .collect();
    Ok(frequency_hz
        .iter()
        .map(|f| {
            let w = 2.0 * std::f64::consts::PI * f;
            let h: Complex64 = terms
                .iter()
                .map(|&(wr, a, z)| a / Complex64::new(wr * wr - w * w, 2.0 * z * wr * w))
                .sum();
            h * Complex64::new(0.0, w).powi(power)
        })
        .collect())
}
