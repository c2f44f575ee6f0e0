//! Model parameters that a calibration can fit, addressed by name.
//!
//! A name is a path into the [`Model`]: `[ID.][GROUP.]PROPERTY`.
//!
//! | property | where | unit |
//! |---|---|---|
//! | `height`, `width` (group `section`) | a beam's rectangular section | m |
//! | `young`, `density` (group `material`) | a beam's material | Pa, kg/m³ |
//! | `mass` | a rigid body or a point mass | kg |
//! | `inertia` | a rigid body (about its centre of mass) | kg m² |
//! | `torsion_stiffness` | a pin joint's torsion spring | N m/rad |
//! | `stiffness` | a translational spring | N/m |
//!
//! `ID` is the element's id (`blade.height`, `slot.mass`), or `joints[i]` /
//! `springs[i]` for elements without one; it may be left out when exactly one
//! element has the property (`height` on a model with one beam).
//!
//! Default bounds are the initial value ×/÷ 4 (geometry, material, masses) or
//! ×/÷ 1000 (springs, whose useful range spans decades). With `keep_mass`,
//! changing a beam's height or width rescales its density so that ρ·h·w, and
//! so the beam's mass, stays at its initial value.

use super::error::CalibrationError;
use crate::model::Model;

/// What a parameter changes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamTarget {
    /// Section height of beam `i` (model order) [SI: m].
    BeamHeight(usize),
    /// Section width of beam `i` [SI: m].
    BeamWidth(usize),
    /// Young's modulus of beam `i` [SI: Pa].
    BeamYoung(usize),
    /// Density of beam `i` [SI: kg/m³].
    BeamDensity(usize),
    /// Mass of rigid body `i` [SI: kg].
    RigidMass(usize),
    /// Moment of inertia of rigid body `i` [SI: kg m²].
    RigidInertia(usize),
    /// Mass of point mass `i` [SI: kg].
    PointMass(usize),
    /// Torsion stiffness of joint `i` [SI: N m/rad].
    TorsionStiffness(usize),
    /// Stiffness of spring `i` [SI: N/m].
    SpringStiffness(usize),
}

impl ParamTarget {
    /// SI unit, for reports.
    pub fn unit(self) -> &'static str {
        match self {
            ParamTarget::BeamHeight(_) | ParamTarget::BeamWidth(_) => "m",
            ParamTarget::BeamYoung(_) => "Pa",
            ParamTarget::BeamDensity(_) => "kg/m³",
            ParamTarget::RigidMass(_) | ParamTarget::PointMass(_) => "kg",
            ParamTarget::RigidInertia(_) => "kg m²",
            ParamTarget::TorsionStiffness(_) => "N m/rad",
            ParamTarget::SpringStiffness(_) => "N/m",
        }
    }

    /// Factor of the default bounds [x₀/f, x₀·f].
    fn default_range_factor(self) -> f64 {
        match self {
            ParamTarget::TorsionStiffness(_) | ParamTarget::SpringStiffness(_) => 1000.0,
            _ => 4.0,
        }
    }

    /// The value in `model`.
    pub fn get(self, model: &Model) -> f64 {
        match self {
            ParamTarget::BeamHeight(i) => model.beams[i].section.height,
            ParamTarget::BeamWidth(i) => model.beams[i].section.width,
            ParamTarget::BeamYoung(i) => model.beams[i].material.young,
            ParamTarget::BeamDensity(i) => model.beams[i].material.density,
            ParamTarget::RigidMass(i) => model.rigid_bodies[i].mass,
            ParamTarget::RigidInertia(i) => model.rigid_bodies[i].inertia,
            ParamTarget::PointMass(i) => model.point_masses[i].mass,
            ParamTarget::TorsionStiffness(i) => model.joints[i].torsion_stiffness.unwrap_or(0.0),
            ParamTarget::SpringStiffness(i) => model.springs[i].stiffness,
        }
    }

    /// Set the value in `model`.
    pub fn set(self, model: &mut Model, value: f64) {
        match self {
            ParamTarget::BeamHeight(i) => model.beams[i].section.height = value,
            ParamTarget::BeamWidth(i) => model.beams[i].section.width = value,
            ParamTarget::BeamYoung(i) => model.beams[i].material.young = value,
            ParamTarget::BeamDensity(i) => model.beams[i].material.density = value,
            ParamTarget::RigidMass(i) => model.rigid_bodies[i].mass = value,
            ParamTarget::RigidInertia(i) => model.rigid_bodies[i].inertia = value,
            ParamTarget::PointMass(i) => model.point_masses[i].mass = value,
            ParamTarget::TorsionStiffness(i) => model.joints[i].torsion_stiffness = Some(value),
            ParamTarget::SpringStiffness(i) => model.springs[i].stiffness = value,
        }
    }

    /// The value's JSON path in the model file, elements by index
    /// (`beams[0].section.height`); how `sweep --param` uses these names.
    pub fn json_path(self) -> String {
        match self {
            ParamTarget::BeamHeight(i) => format!("beams[{i}].section.height"),
            ParamTarget::BeamWidth(i) => format!("beams[{i}].section.width"),
            ParamTarget::BeamYoung(i) => format!("beams[{i}].material.young"),
            ParamTarget::BeamDensity(i) => format!("beams[{i}].material.density"),
            ParamTarget::RigidMass(i) => format!("rigid_bodies[{i}].mass"),
            ParamTarget::RigidInertia(i) => format!("rigid_bodies[{i}].inertia"),
            ParamTarget::PointMass(i) => format!("point_masses[{i}].mass"),
            ParamTarget::TorsionStiffness(i) => format!("joints[{i}].torsion_stiffness"),
            ParamTarget::SpringStiffness(i) => format!("springs[{i}].stiffness"),
        }
    }

    /// The beam whose section this parameter changes (height or width).
    pub fn section_beam(self) -> Option<usize> {
        match self {
            ParamTarget::BeamHeight(i) | ParamTarget::BeamWidth(i) => Some(i),
            _ => None,
        }
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
            let (name, target) = resolve_name(model, &spec.name)?;
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
            let f = target.default_range_factor();
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

    /// A new model with the parameters at `values` (the base stays untouched).
    pub fn apply(&self, values: &[f64]) -> Model {
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

/// Every parameter name of the model, canonical form.
pub fn available_names(model: &Model) -> Vec<String> {
    let mut out = Vec::new();
    for b in &model.beams {
        for p in ["height", "width", "young", "density"] {
            out.push(format!("{}.{p}", b.id));
        }
    }
    for r in &model.rigid_bodies {
        out.push(format!("{}.mass", r.id));
        out.push(format!("{}.inertia", r.id));
    }
    for p in &model.point_masses {
        out.push(format!("{}.mass", p.id));
    }
    for (i, j) in model.joints.iter().enumerate() {
        if j.torsion_stiffness.is_some() {
            out.push(format!("{}.torsion_stiffness", joint_label(model, i)));
        }
    }
    for i in 0..model.springs.len() {
        out.push(format!("{}.stiffness", spring_label(model, i)));
    }
    out
}

fn joint_label(model: &Model, i: usize) -> String {
    model.joints[i]
        .id
        .clone()
        .unwrap_or_else(|| format!("joints[{i}]"))
}

fn spring_label(model: &Model, i: usize) -> String {
    model.springs[i]
        .id
        .clone()
        .unwrap_or_else(|| format!("springs[{i}]"))
}

/// The property a name ends with, and the group it may be written with.
fn property(last: &str) -> Option<(&'static str, Option<&'static str>)> {
    Some(match last {
        "height" => ("height", Some("section")),
        "width" => ("width", Some("section")),
        "young" => ("young", Some("material")),
        "density" => ("density", Some("material")),
        "mass" => ("mass", None),
        "inertia" => ("inertia", None),
        "torsion_stiffness" => ("torsion_stiffness", None),
        "stiffness" => ("stiffness", None),
        _ => return None,
    })
}

/// Parse `[ID.][GROUP.]PROPERTY` into the canonical name and target.
pub fn resolve_name(model: &Model, name: &str) -> Result<(String, ParamTarget), CalibrationError> {
    let unknown = || CalibrationError::UnknownParameter {
        name: name.to_string(),
        available: available_names(model),
    };
    let trimmed = name.trim();
    let (head, last) = match trimmed.rsplit_once('.') {
        Some((h, l)) => (Some(h), l),
        None => (None, trimmed),
    };
    let (prop, group) = property(last).ok_or_else(unknown)?;
    // Strip an optional group ("section", "material") from the head.
    let id = match (head, group) {
        (Some(h), Some(g)) if h == g => None,
        (Some(h), Some(g)) => match h.strip_suffix(g).and_then(|x| x.strip_suffix('.')) {
            Some(id) => Some(id),
            None => Some(h),
        },
        (h, _) => h,
    };
    let mut candidates: Vec<(String, ParamTarget)> = Vec::new();
    match prop {
        "height" | "width" | "young" | "density" => {
            for (i, b) in model.beams.iter().enumerate() {
                let t = match prop {
                    "height" => ParamTarget::BeamHeight(i),
                    "width" => ParamTarget::BeamWidth(i),
                    "young" => ParamTarget::BeamYoung(i),
                    _ => ParamTarget::BeamDensity(i),
                };
                candidates.push((b.id.clone(), t));
            }
        }
        "mass" => {
            for (i, r) in model.rigid_bodies.iter().enumerate() {
                candidates.push((r.id.clone(), ParamTarget::RigidMass(i)));
            }
            for (i, p) in model.point_masses.iter().enumerate() {
                candidates.push((p.id.clone(), ParamTarget::PointMass(i)));
            }
        }
        "inertia" => {
            for (i, r) in model.rigid_bodies.iter().enumerate() {
                candidates.push((r.id.clone(), ParamTarget::RigidInertia(i)));
            }
        }
        "torsion_stiffness" => {
            for (i, j) in model.joints.iter().enumerate() {
                // Without an id, only joints that have a torsion spring qualify.
                if id.is_some() || j.torsion_stiffness.is_some() {
                    candidates.push((joint_label(model, i), ParamTarget::TorsionStiffness(i)));
                }
            }
        }
        _ => {
            for i in 0..model.springs.len() {
                candidates.push((spring_label(model, i), ParamTarget::SpringStiffness(i)));
            }
        }
    }
    let chosen = match id {
        Some(id) => candidates.into_iter().find(|(l, _)| l == id),
        None if candidates.len() == 1 => candidates.pop(),
        None if candidates.is_empty() => None,
        None => {
            return Err(CalibrationError::AmbiguousParameter {
                name: name.to_string(),
                candidates: candidates
                    .iter()
                    .map(|(l, _)| format!("{l}.{prop}"))
                    .collect(),
            })
        }
    };
    let (label, target) = chosen.ok_or_else(unknown)?;
    Ok((format!("{label}.{prop}"), target))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_resolve_in_all_spellings() {
        let m = Model::builtin();
        for n in [
            "height",
            "blade.height",
            "section.height",
            "blade.section.height",
        ] {
            let (name, t) = resolve_name(&m, n).expect(n);
            assert_eq!(name, "blade.height");
            assert_eq!(t, ParamTarget::BeamHeight(0));
        }
        assert_eq!(
            resolve_name(&m, "blade.material.young").unwrap().1,
            ParamTarget::BeamYoung(0)
        );
        assert_eq!(
            resolve_name(&m, "pad.mass").unwrap().1,
            ParamTarget::PointMass(0)
        );
        assert_eq!(
            resolve_name(&m, "inertia").unwrap().1,
            ParamTarget::RigidInertia(0)
        );
        assert!(matches!(
            resolve_name(&m, "mass"),
            Err(CalibrationError::AmbiguousParameter { .. })
        ));
        assert!(matches!(
            resolve_name(&m, "blade.colour"),
            Err(CalibrationError::UnknownParameter { .. })
        ));
        assert!(matches!(
            resolve_name(&m, "wing.height"),
            Err(CalibrationError::UnknownParameter { .. })
        ));
    }

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
        let f = set.apply(&[0.9e-3, 6.0e-3]);
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
