//! A validated model as a type: [`ValidModel`].
//!
//! A `ValidModel` is obtained only through validation
//! ([`Model::validated`], [`ValidModel::new`], or reading a model:
//! [`Model::from_json`], [`Model::from_file`], [`Model::builtin`],
//! [`Model::switch_off_builtin`]); its fields are private and it gives out
//! its model read-only (`Deref<Target = Model>`). What it guarantees:
//!
//! - **The model passed [`Model::validate`]** when it was made, and has not
//!   changed since: every id a point, joint, spring, load, sensor or
//!   contact names exists (and is unique), every point gives exactly one
//!   of beam, body or ground with an arc length inside its beam, every
//!   physical value is finite and in range, joint points coincide (a
//!   slider's lie on its axis), a slider has an axis, a spring has its free
//!   length or its preload (and a positive free length), a slot has a
//!   width wider than its pin, only pins and sliders are released.
//! - **Its assembly is resolved**: the model [`crate::System::new`]
//!   assembles — beams marked `rigid` replaced by their rigid bodies
//!   ([`Model::with_rigid_beams`]), the whole moved so that its centre of
//!   mass is at the origin ([`Model::centre_of_mass`], [`Model::placed`])
//!   — is kept with what validation found out about every reference of it
//!   ([`super::resolved`]: bodies by index, joint kinds with their axes and
//!   releases, spring lengths, contact owners and clearances). The
//!   assembly reads those answers; it looks nothing up and has no error
//!   path.
//!
//! To change a model, take it out ([`ValidModel::into_model`],
//! [`ValidModel::to_model`]), edit it and validate it again: an edit that
//! breaks it (a joint on a missing body, a slider without an axis) is the
//! validation error naming the JSON path, never a panic in the assembly.
//!
//! The resolution of the assembled model is that of the model as written,
//! carried through the two changes (both keep every id and every list's
//! order): a point on a rigid beam at arc length s becomes the point
//! (s − L/2, 0) of the beam's rigid body ([`Model::rigid_point`], the same
//! arithmetic), the other beams keep their points under their new indices,
//! rigid bodies and point masses keep theirs (the rigid beams' bodies come
//! after the model's own), and ground points and slider axes are moved
//! with the model ([`Placement::point`], [`Placement::turn`], as
//! [`Model::placed`] moves them). So the model is validated once, as the
//! user wrote it (the messages name its paths), and its large lists are
//! not searched twice.

use super::placement::Placement;
use super::resolved::{
    Resolution, ResolvedContact, ResolvedJoint, ResolvedJointKind, ResolvedPoint, ResolvedSpring,
};
use super::types::{Model, PointSpec};
use crate::error::InvalidModel;

/// A model that passed validation, with its resolved assembly (see the
/// module doc for what it guarantees).
#[derive(Debug, Clone)]
pub struct ValidModel {
    model: Model,
    assembly: Assembly,
}

/// The model [`crate::System::new`] assembles and its resolved references.
#[derive(Debug, Clone)]
pub(crate) struct Assembly {
    /// The model with its rigid beams as rigid bodies, moved so that its
    /// centre of mass is at the origin.
    pub model: Model,
    /// That centre of mass in the model's own frame [SI: m].
    pub origin: [f64; 2],
    /// The references of `model`.
    pub resolution: Resolution,
    /// Where each beam of the model as written went.
    beams: Vec<BeamPlace>,
    /// The move that centres the model.
    placement: Placement,
}

/// Where a beam of the model as written is in the assembled model.
#[derive(Debug, Clone, Copy, PartialEq)]
enum BeamPlace {
    /// `beams[i]` of the assembled model.
    Flexible(usize),
    /// `rigid_bodies[i]` of the assembled model.
    Rigid(usize),
}

impl Model {
    /// The model validated ([`Model::validate`]): a [`ValidModel`], or the
    /// first problem with its JSON path.
    pub fn validated(self) -> Result<ValidModel, InvalidModel> {
        ValidModel::new(self)
    }
}

impl ValidModel {
    /// Validates `model` and resolves its assembly (module doc).
    pub fn new(model: Model) -> Result<ValidModel, InvalidModel> {
        let resolution = model
            .resolution()
            .map_err(|(path, problem)| InvalidModel { path, problem })?;
        let assembly = Assembly::new(&model, resolution);
        Ok(ValidModel { model, assembly })
    }

    /// The model, to edit (validate it again to use it).
    pub fn into_model(self) -> Model {
        self.model
    }

    /// A copy of the model, to edit (validate it again to use it).
    pub fn to_model(&self) -> Model {
        self.model.clone()
    }

    /// A point of this model (`path` its JSON path for the message)
    /// resolved in the assembled model: what [`crate::System::anchor_of`]
    /// of this model's system takes. The problem when it does not resolve
    /// ([`Model::resolve`]).
    pub fn resolve_point(&self, p: &PointSpec, path: &str) -> Result<ResolvedPoint, InvalidModel> {
        let target = self
            .model
            .resolve(p, path)
            .map_err(|(path, problem)| InvalidModel { path, problem })?;
        Ok(self
            .assembly
            .point(&self.model, ResolvedPoint::from(&target), p))
    }

    /// The assembled model and its references.
    pub(crate) fn assembly(&self) -> &Assembly {
        &self.assembly
    }
}

impl std::ops::Deref for ValidModel {
    type Target = Model;

    fn deref(&self) -> &Model {
        &self.model
    }
}

impl AsRef<Model> for ValidModel {
    fn as_ref(&self) -> &Model {
        &self.model
    }
}

/// Two valid models are equal when their models are (the assembly follows
/// from the model).
impl PartialEq for ValidModel {
    fn eq(&self, other: &Self) -> bool {
        self.model == other.model
    }
}

/// A valid model serializes as its model (a valid model file).
impl serde::Serialize for ValidModel {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.model.serialize(serializer)
    }
}

impl From<ValidModel> for Model {
    fn from(v: ValidModel) -> Model {
        v.model
    }
}

impl Assembly {
    /// The assembly of `model`, whose references validation resolved to
    /// `resolution` (module doc).
    fn new(model: &Model, resolution: Resolution) -> Assembly {
        let converted;
        let base = if model.beams.iter().any(|b| b.rigid) {
            converted = model.with_rigid_beams();
            &converted
        } else {
            model
        };
        let c = base.centre_of_mass();
        let placement = Placement::translation([-c[0], -c[1]]);
        let (mut flexible, mut rigid) = (0, model.rigid_bodies.len());
        let beams = model
            .beams
            .iter()
            .map(|b| {
                let (counter, place): (&mut usize, fn(usize) -> BeamPlace) = if b.rigid {
                    (&mut rigid, BeamPlace::Rigid)
                } else {
                    (&mut flexible, BeamPlace::Flexible)
                };
                *counter += 1;
                place(*counter - 1)
            })
            .collect();
        let mut assembly = Assembly {
            model: base.placed(&placement),
            origin: c,
            resolution: Resolution {
                joints: Vec::new(),
                springs: Vec::new(),
                loads: Vec::new(),
                sensors: Vec::new(),
                contacts: Vec::new(),
            },
            beams,
            placement,
        };
        let point = |p: ResolvedPoint, spec: &PointSpec| assembly.point(model, p, spec);
        let joints = resolution
            .joints
            .iter()
            .zip(&model.joints)
            .map(|(r, j)| ResolvedJoint {
                a: point(r.a, &j.a),
                b: point(r.b, &j.b),
                kind: match r.kind {
                    ResolvedJointKind::Slider { axis, release } => ResolvedJointKind::Slider {
                        axis: placement.turn(axis),
                        release,
                    },
                    other => other,
                },
            })
            .collect();
        let springs = resolution
            .springs
            .iter()
            .zip(&model.springs)
            .map(|(r, s)| ResolvedSpring {
                a: point(r.a, &s.a),
                b: point(r.b, &s.b),
                length: r.length,
            })
            .collect();
        let loads = resolution
            .loads
            .iter()
            .zip(&model.loads)
            .map(|(&r, l)| point(r, &l.at))
            .collect();
        let sensors = resolution
            .sensors
            .iter()
            .zip(&model.sensors)
            .map(|(&r, s)| point(r, &s.at))
            .collect();
        let contacts = resolution
            .contacts
            .iter()
            .zip(&model.contacts)
            .map(|(r, c)| ResolvedContact {
                owner: r.owner,
                point: point(r.point, c.point()),
                kind: r.kind,
            })
            .collect();
        assembly.resolution = Resolution {
            joints,
            springs,
            loads,
            sensors,
            contacts,
        };
        assembly
    }

    /// The point `p` of `model` (the model as written), given there as
    /// `spec`, in the assembled model.
    fn point(&self, model: &Model, p: ResolvedPoint, spec: &PointSpec) -> ResolvedPoint {
        match p {
            ResolvedPoint::Beam { index, s } => match self.beams[index] {
                BeamPlace::Flexible(i) => ResolvedPoint::Beam { index: i, s },
                // As `Model::rigid_point`: the arc length as written.
                BeamPlace::Rigid(i) => ResolvedPoint::Rigid {
                    index: i,
                    local: Some(model.beams[index].rigid_local(spec.s.unwrap_or(s))),
                },
            },
            ResolvedPoint::Ground { position } => ResolvedPoint::Ground {
                position: self.placement.point(position),
            },
            other => other,
        }
    }
}
