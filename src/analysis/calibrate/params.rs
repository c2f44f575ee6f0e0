//! Model parameters that a calibration can fit, addressed by short name
//! (`height`, `blade.young`, `slot.mass`; the names, their units and their
//! resolution are [`crate::model::path::short`]'s).
//!
//! Default bounds are the initial value ×/÷ 4 (geometry, material, masses) or
//! ×/÷ 1000 (springs, whose useful range spans decades). With `keep_mass`,
//! changing a beam's height or width rescales its density so that ρ·h·w, and
//! so the beam's mass, stays at its initial value.

use super::error::CalibrationError;
use crate::model::path::resolve_short;
use crate::model::{Model, ValidModel};

/// What a parameter changes: a short name's target (get, set, unit and
/// JSON path are the model layer's).
pub use crate::model::path::Target as ParamTarget;

/// Factor f of the default bounds [x₀/f, x₀·f].
fn default_range_factor(target: ParamTarget) -> f64 {
    match target {
        ParamTarget::TorsionStiffness(_) | ParamTarget::SpringStiffness(_) => 1000.0,
        _ => 4.0,
    }
}

/// A parameter to fit, as the user names it.
#[derive(Debug, Clone, PartialEq)]
pub struct ParameterSpec {
    pub name: String,
    /// Bounds [lower, upper] in SI units; `None` = the default range.
    pub bounds: Option<(f64, f64)>,
}

impl ParameterSpec {
    pub fn named(name: impl Into<String>) -> Self {
        ParameterSpec {
            name: name.into(),
            bounds: None,
        }
    }
}

/// A resolved parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// Canonical name, e.g. `blade.height`.
    pub name: String,
    pub target: ParamTarget,
    pub initial: f64,
    pub lower: f64,
    pub upper: f64,
}

/// The parameters of one calibration and how they are applied to a model.
#[derive(Debug, Clone)]
pub struct ParameterSet {
    pub params: Vec<Parameter>,
    /// Keep each beam's mass when its section changes (density adjusts).
    pub keep_mass: bool,
    base: Model,
}

impl ParameterSet {
    /// Resolve the names against `model` (the immutable starting point).
    pub fn resolve(
        model: &Model,
        specs: &[ParameterSpec],
        keep_mass: bool,
    ) -> Result<ParameterSet, CalibrationError> {
        if specs.is_empty() {
            return Err(CalibrationError::NoParameters);
        }
        let mut params: Vec<Parameter> = Vec::with_capacity(specs.len());
        for spec in specs {
            let (name, target) = resolve_short(model, &spec.name)?;
            if let Some(p) = params.iter().find(|p| p.target == target) {
                return Err(CalibrationError::DuplicateParameter {
                    name: spec.name.clone(),
                    canonical: p.name.clone(),
                });
            }
            if keep_mass && matches!(target, ParamTarget::BeamDensity(_)) {
                return Err(CalibrationError::DensityWithKeepMass { name });
            }
            let initial = target.get(model);
            if !(initial > 0.0 && initial.is_finite()) {
                return Err(CalibrationError::NoInitialValue { name, initial });
            }
            let f = default_range_factor(target);
            let (lower, upper) = spec.bounds.unwrap_or((initial / f, initial * f));
            if !(lower > 0.0 && lower < upper && upper.is_finite()) {
                return Err(CalibrationError::InvalidBounds { name, lower, upper });
            }
            params.push(Parameter {
                name,
                target,
                initial,
                lower,
                upper,
            });
        }
        Ok(ParameterSet {
            params,
            keep_mass,
            base: model.clone(),
        })
    }

    /// Number of parameters.
    pub fn len(&self) -> usize {
        self.params.len()
    }

    pub fn is_empty(&self) -> bool {
        self.params.is_empty()
    }

    /// The starting model.
    pub fn base(&self) -> &Model {
        &self.base
    }

    /// Initial values, clamped into the bounds.
    pub fn start(&self) -> Vec<f64> {
        self.params
            .iter()
            .map(|p| p.initial.clamp(p.lower, p.upper))
            .collect()
    }

    /// A new model with the parameters at `values` (the base stays
    /// untouched), validated: the first problem of a model the values
    /// make invalid.
    pub fn apply(&self, values: &[f64]) -> Result<ValidModel, CalibrationError> {
        self.model_at(values)
            .validated()
            .map_err(|source| CalibrationError::InvalidModel {
                at: self.describe(values),
                source: Box::new(source),
            })
    }

    /// "blade.height = 1.1e-3, …": the parameters at `values`, for messages.
    pub fn describe(&self, values: &[f64]) -> String {
        self.params
            .iter()
            .zip(values)
            .map(|(p, v)| format!("{} = {v:e}", p.name))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The model with the parameters at `values`, not yet validated.
    pub(super) fn model_at(&self, values: &[f64]) -> Model {
        let mut m = self.base.clone();
        for (p, &v) in self.params.iter().zip(values) {
            p.target.set(&mut m, v);
        }
        if self.keep_mass {
            for (i, (b0, b)) in self.base.beams.iter().zip(m.beams.iter_mut()).enumerate() {
                let touched = self
                    .params
                    .iter()
                    .any(|p| p.target.section_beam() == Some(i));
                if touched {
                    b.material.density = b0.material.density * b0.section.area() / b.section.area();
                }
            }
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keep_mass_preserves_rho_h_w() {
        let m = Model::builtin();
        let set = ParameterSet::resolve(
            &m,
            &[
                ParameterSpec::named("height"),
                ParameterSpec::named("width"),
            ],
            true,
        )
        .unwrap();
        let f = set.apply(&[0.9e-3, 6.0e-3]).unwrap();
        let b0 = &m.beams[0];
        let b = &f.beams[0];
        let m0 = b0.material.density * b0.section.height * b0.section.width;
        let m1 = b.material.density * b.section.height * b.section.width;
        assert!(
            ((m1 - m0) / m0).abs() < 1e-14,
            "mass per length {m1} vs {m0}"
        );
    }
}
