//! Unit sanity of a model: values that are valid numbers but not a
//! plausible engineering solid in SI units, or beams outside the beam
//! theory the elements implement. These are warnings, never errors: an
//! unusual material or a stubby beam may be meant.
//!
//! - **Slenderness**: Euler–Bernoulli theory (the ANCF cable elements)
//!   leaves out shear deformation and rotary inertia, whose relative effect
//!   on a bending frequency grows as (h/L)². Above h/L ≈ 0.05 it is a few
//!   per cent; above h/L = 0.1 the model is no longer a beam (and a height
//!   typed in millimetres into a metre field looks exactly like this).
//! - **Material**: engineering solids have Young's modulus E from about
//!   1e5 Pa (soft rubber) to 1e13 Pa (beyond diamond's 1.2e12), density ρ
//!   from 10 kg/m³ (light foams) to 25,000 kg/m³ (beyond osmium's 22,600),
//!   and bar-wave speed √(E/ρ) from about 5 m/s to 20,000 m/s. E typed in
//!   MPa or ρ in g/cm³ falls outside.

use super::Model;

/// h/L above which a beam is reported (module doc).
pub const MAX_SLENDERNESS: f64 = 0.1;
/// Plausible Young's modulus [SI: Pa].
pub const YOUNG_RANGE: (f64, f64) = (1e5, 1e13);
/// Plausible density [SI: kg/m³].
pub const DENSITY_RANGE: (f64, f64) = (10.0, 25_000.0);
/// Plausible bar-wave speed √(E/ρ) [SI: m/s].
pub const WAVE_SPEED_RANGE: (f64, f64) = (5.0, 20_000.0);

/// One implausible value, with the JSON path of the value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UnitWarning {
    #[error("{path}: height/length = {ratio:.3} is above {max} (beam `{beam}`): Euler–Bernoulli beam theory no longer holds and the frequencies come out high; is the height in metres?", max = MAX_SLENDERNESS)]
    Slender {
        path: String,
        beam: String,
        ratio: f64,
    },
    #[error("{path}: Young's modulus {value:e} Pa is outside {:e}–{:e} Pa: is the model in SI units?", YOUNG_RANGE.0, YOUNG_RANGE.1)]
    Young { path: String, value: f64 },
    #[error("{path}: density {value} kg/m³ is outside {}–{} kg/m³: is the model in SI units?", DENSITY_RANGE.0, DENSITY_RANGE.1)]
    Density { path: String, value: f64 },
    #[error("{path}: the wave speed √(E/ρ) = {} m/s is outside {}–{} m/s: is the model in SI units?", crate::model::number::significant(*value, 4), WAVE_SPEED_RANGE.0, WAVE_SPEED_RANGE.1)]
    WaveSpeed { path: String, value: f64 },
}

fn outside(value: f64, (lo, hi): (f64, f64)) -> bool {
    !(lo..=hi).contains(&value)
}

impl Model {
    /// The unit-sanity warnings of this model (module doc), in the order of
    /// its beams.
    pub fn unit_warnings(&self) -> Vec<UnitWarning> {
        let mut warnings = Vec::new();
        for (i, b) in self.beams.iter().enumerate() {
            let ratio = b.section.height / b.length;
            if ratio > MAX_SLENDERNESS {
                warnings.push(UnitWarning::Slender {
                    path: format!("beams[{i}].section.height"),
                    beam: b.id.clone(),
                    ratio,
                });
            }
            let (e, rho) = (b.material.young, b.material.density);
            let material = format!("beams[{i}].material");
            if outside(e, YOUNG_RANGE) {
                warnings.push(UnitWarning::Young {
                    path: format!("{material}.young"),
                    value: e,
                });
            }
            if outside(rho, DENSITY_RANGE) {
                warnings.push(UnitWarning::Density {
                    path: format!("{material}.density"),
                    value: rho,
                });
            }
            let c = (e / rho).sqrt();
            if outside(c, WAVE_SPEED_RANGE) {
                warnings.push(UnitWarning::WaveSpeed {
                    path: material,
                    value: c,
                });
            }
        }
        warnings
    }
}
