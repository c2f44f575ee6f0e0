//! Short names of model parameters: `[ID.][GROUP.]PROPERTY`.
//!
//! | property | group | where | unit |
//! |---|---|---|---|
//! | `height`, `width` | `section` | a beam's rectangular section | m |
//! | `young` | `material` | a beam's Young's modulus | Pa |
//! | `density` | `material` | a beam's density | kg/m³ |
//! | `mass` | | a rigid body or a point mass | kg |
//! | `inertia` | | a rigid body (about its centre of mass) | kg m² |
//! | `torsion_stiffness` | | a pin joint's torsion spring | N m/rad |
//! | `stiffness` | | a translational spring | N/m |
//! | `force_x`, `force_y` | | a load's force, one component | N |
//!
//! `ID` is the element's id (`blade.height`, `slot.mass`), or `joints[i]` /
//! `springs[i]` for elements without one; it may be left out when exactly
//! one element has the property (`height` on a model with one beam). Each
//! short name is a [`Target`]: a typed handle on the number that reads and
//! writes the [`Model`] directly and knows its JSON path.

use super::error::PathError;
use super::{NumberPath, Step};
use crate::model::Model;

/// One property a short name can end with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Property {
    pub name: &'static str,
    /// The group it may be written with (`blade.section.height`).
    pub group: Option<&'static str>,
    /// SI unit.
    pub unit: &'static str,
}

/// The properties of short names.
pub const PROPERTIES: &[Property] = &[
    prop("height", Some("section"), "m"),
    prop("width", Some("section"), "m"),
    prop("young", Some("material"), "Pa"),
    prop("density", Some("material"), "kg/m³"),
    prop("mass", None, "kg"),
    prop("inertia", None, "kg m²"),
    prop("torsion_stiffness", None, "N m/rad"),
    prop("stiffness", None, "N/m"),
    prop("force_x", None, "N"),
    prop("force_y", None, "N"),
];

const fn prop(name: &'static str, group: Option<&'static str>, unit: &'static str) -> Property {
    Property { name, group, unit }
}

/// The number a short name stands for; the index is the element's position
/// in its list of the model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// Section height of beam `i` [SI: m].
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
    /// Component `axis` (0: x, 1: y) of load `i`'s force [SI: N].
    LoadForce(usize, usize),
}

impl Target {
    /// The property this target is, from [`PROPERTIES`].
    pub fn property(self) -> &'static Property {
        let name = match self {
            Target::BeamHeight(_) => "height",
            Target::BeamWidth(_) => "width",
            Target::BeamYoung(_) => "young",
            Target::BeamDensity(_) => "density",
            Target::RigidMass(_) | Target::PointMass(_) => "mass",
            Target::RigidInertia(_) => "inertia",
            Target::TorsionStiffness(_) => "torsion_stiffness",
            Target::SpringStiffness(_) => "stiffness",
            Target::LoadForce(_, 0) => "force_x",
            Target::LoadForce(_, _) => "force_y",
        };
        PROPERTIES
            .iter()
            .find(|p| p.name == name)
            .expect("every target has a property")
    }

    /// SI unit, for reports.
    pub fn unit(self) -> &'static str {
        self.property().unit
    }

    /// The value in `model` (an absent torsion spring reads 0).
    pub fn get(self, model: &Model) -> f64 {
        match self {
            Target::BeamHeight(i) => model.beams[i].section.height,
            Target::BeamWidth(i) => model.beams[i].section.width,
            Target::BeamYoung(i) => model.beams[i].material.young,
            Target::BeamDensity(i) => model.beams[i].material.density,
            Target::RigidMass(i) => model.rigid_bodies[i].mass,
            Target::RigidInertia(i) => model.rigid_bodies[i].inertia,
            Target::PointMass(i) => model.point_masses[i].mass,
            Target::TorsionStiffness(i) => model.joints[i].torsion_stiffness.unwrap_or(0.0),
            Target::SpringStiffness(i) => model.springs[i].stiffness,
            Target::LoadForce(i, axis) => model.loads[i].force[axis],
        }
    }

    /// Sets the value in `model`.
    pub fn set(self, model: &mut Model, value: f64) {
        match self {
            Target::BeamHeight(i) => model.beams[i].section.height = value,
            Target::BeamWidth(i) => model.beams[i].section.width = value,
            Target::BeamYoung(i) => model.beams[i].material.young = value,
            Target::BeamDensity(i) => model.beams[i].material.density = value,
            Target::RigidMass(i) => model.rigid_bodies[i].mass = value,
            Target::RigidInertia(i) => model.rigid_bodies[i].inertia = value,
            Target::PointMass(i) => model.point_masses[i].mass = value,
            Target::TorsionStiffness(i) => model.joints[i].torsion_stiffness = Some(value),
            Target::SpringStiffness(i) => model.springs[i].stiffness = value,
            Target::LoadForce(i, axis) => model.loads[i].force[axis] = value,
        }
    }

    /// The number's path in the model file, elements by index
    /// (`beams[0].section.height`).
    pub fn path(self) -> NumberPath {
        if let Target::LoadForce(i, axis) = self {
            return NumberPath::new(vec![
                Step::Key("loads".into()),
                Step::Index(i),
                Step::Key("force".into()),
                Step::Index(axis),
            ]);
        }
        let (list, i) = match self {
            Target::BeamHeight(i)
            | Target::BeamWidth(i)
            | Target::BeamYoung(i)
            | Target::BeamDensity(i) => ("beams", i),
            Target::RigidMass(i) | Target::RigidInertia(i) => ("rigid_bodies", i),
            Target::PointMass(i) => ("point_masses", i),
            Target::TorsionStiffness(i) => ("joints", i),
            Target::SpringStiffness(i) => ("springs", i),
            Target::LoadForce(i, _) => ("loads", i),
        };
        let p = self.property();
        let mut steps = vec![Step::Key(list.into()), Step::Index(i)];
        steps.extend(p.group.map(|g| Step::Key(g.into())));
        steps.push(Step::Key(p.name.into()));
        NumberPath::new(steps)
    }

    /// The beam whose section this target changes (height or width).
    pub fn section_beam(self) -> Option<usize> {
        match self {
            Target::BeamHeight(i) | Target::BeamWidth(i) => Some(i),
            _ => None,
        }
    }
}

/// Every short name of the model, canonical form (`ID.PROPERTY`), element
/// by element.
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
    for (label, _) in candidates(model, "torsion_stiffness", false) {
        out.push(format!("{label}.torsion_stiffness"));
    }
    for (label, _) in candidates(model, "stiffness", false) {
        out.push(format!("{label}.stiffness"));
    }
    for p in ["force_x", "force_y"] {
        for (label, _) in candidates(model, p, false) {
            out.push(format!("{label}.{p}"));
        }
    }
    out
}

/// The elements that have property `prop`, with their labels; joints
/// without a torsion spring only when `by_id` (named explicitly).
fn candidates(model: &Model, prop: &str, by_id: bool) -> Vec<(String, Target)> {
    let labelled = |id: Option<&String>, list: &str, i: usize| {
        id.cloned().unwrap_or_else(|| format!("{list}[{i}]"))
    };
    let mut out = Vec::new();
    match prop {
        "height" | "width" | "young" | "density" => {
            for (i, b) in model.beams.iter().enumerate() {
                let t = match prop {
                    "height" => Target::BeamHeight(i),
                    "width" => Target::BeamWidth(i),
                    "young" => Target::BeamYoung(i),
                    _ => Target::BeamDensity(i),
                };
                out.push((b.id.clone(), t));
            }
        }
        "mass" => {
            for (i, r) in model.rigid_bodies.iter().enumerate() {
                out.push((r.id.clone(), Target::RigidMass(i)));
            }
            for (i, p) in model.point_masses.iter().enumerate() {
                out.push((p.id.clone(), Target::PointMass(i)));
            }
        }
        "inertia" => {
            for (i, r) in model.rigid_bodies.iter().enumerate() {
                out.push((r.id.clone(), Target::RigidInertia(i)));
            }
        }
        "torsion_stiffness" => {
            for (i, j) in model.joints.iter().enumerate() {
                if by_id || j.torsion_stiffness.is_some() {
                    let label = labelled(j.id.as_ref(), "joints", i);
                    out.push((label, Target::TorsionStiffness(i)));
                }
            }
        }
        "force_x" | "force_y" => {
            let axis = usize::from(prop == "force_y");
            for (i, l) in model.loads.iter().enumerate() {
                if by_id || l.force[axis] != 0.0 {
                    let label = labelled(l.id.as_ref(), "loads", i);
                    out.push((label, Target::LoadForce(i, axis)));
                }
            }
        }
        _ => {
            for (i, s) in model.springs.iter().enumerate() {
                let label = labelled(s.id.as_ref(), "springs", i);
                out.push((label, Target::SpringStiffness(i)));
            }
        }
    }
    out
}

/// Parses `[ID.][GROUP.]PROPERTY` into the canonical name (`blade.height`)
/// and its target.
pub fn resolve_short(model: &Model, name: &str) -> Result<(String, Target), PathError> {
    let unknown = || PathError::UnknownShortName {
        name: name.to_string(),
        available: available_names(model),
    };
    let trimmed = name.trim();
    let (head, last) = match trimmed.rsplit_once('.') {
        Some((h, l)) => (Some(h), l),
        None => (None, trimmed),
    };
    let p = PROPERTIES
        .iter()
        .find(|p| p.name == last)
        .ok_or_else(unknown)?;
    // Strip an optional group ("section", "material") from the head.
    let id = match (head, p.group) {
        (Some(h), Some(g)) if h == g => None,
        (Some(h), Some(g)) => match h.strip_suffix(g).and_then(|x| x.strip_suffix('.')) {
            Some(id) => Some(id),
            None => Some(h),
        },
        (h, _) => h,
    };
    let mut found = candidates(model, p.name, id.is_some());
    let chosen = match id {
        Some(id) => found.into_iter().find(|(l, _)| l == id),
        None if found.len() <= 1 => found.pop(),
        None => {
            return Err(PathError::Ambiguous {
                name: name.to_string(),
                candidates: found
                    .iter()
                    .map(|(l, _)| format!("{l}.{}", p.name))
                    .collect(),
            })
        }
    };
    let (label, target) = chosen.ok_or_else(unknown)?;
    Ok((format!("{label}.{}", p.name), target))
}
