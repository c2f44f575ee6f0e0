//! Construction of a [`System`] from a [`ValidModel`]: its assembled
//! model, read with the references validation resolved
//! ([`crate::model::valid`]).

use super::{
    BeamMesh, PointMassDofs, ReleasedJoint, ReleasedSupport, RigidDofs, SensorPoint, System,
    PACKED_ELEMENTS,
};
use crate::mechanics::anchor::{perp, Anchor};
use crate::mechanics::cable_force::PackedElements;
use crate::mechanics::contact::law::NormalLaw;
use crate::mechanics::contact::{ContactElement, ContactKind};
use crate::mechanics::element::{CableElement, CableSection};
use crate::mechanics::joint::{Constraint, Pin, Slider, Weld};
use crate::mechanics::load::PointLoad;
use crate::mechanics::pair::Pair;
use crate::mechanics::spring::{LinearSpring, TorsionSpring};
use crate::model::resolved::{ResolvedContactKind, ResolvedJointKind, ResolvedPoint, SpringLength};
use crate::model::valid::Assembly;
use crate::model::{LoadFrame, Model, PointSpec, SegmentOwner, Side, ValidModel};
use nalgebra::Vector2;

/// Relative distance below which an attachment node merges with a mesh node.
const NODE_MERGE_TOLERANCE: f64 = 1e-9;

fn v2(a: [f64; 2]) -> Vector2<f64> {
    Vector2::new(a[0], a[1])
}

/// Every point spec of the model, for meshing.
fn all_points(model: &Model) -> impl Iterator<Item = &PointSpec> {
    let joints = model.joints.iter().flat_map(|j| [&j.a, &j.b]);
    let springs = model.springs.iter().flat_map(|s| [&s.a, &s.b]);
    joints
        .chain(springs)
        .chain(model.loads.iter().map(|l| &l.at))
        .chain(model.sensors.iter().map(|s| &s.at))
        .chain(model.contacts.iter().map(|c| c.point()))
}

/// Node arc lengths: uniform division plus attachment points, plus the
/// `extra` arc lengths asked for on this beam (whatever
/// `nodes_at_attachments` says).
fn mesh_nodes(model: &Model, beam: &crate::model::Beam, extra: &[f64]) -> Vec<f64> {
    let l = beam.length;
    let n = beam.elements;
    let mut s: Vec<f64> = (0..=n).map(|k| l * k as f64 / n as f64).collect();
    if beam.nodes_at_attachments || !extra.is_empty() {
        let attachments = all_points(model)
            .filter(|p| beam.nodes_at_attachments && p.beam.as_deref() == Some(beam.id.as_str()))
            .filter_map(|p| p.s);
        s.extend(
            attachments
                .chain(extra.iter().copied())
                .map(|x| x.clamp(0.0, l)),
        );
        s.sort_by(f64::total_cmp);
        s.dedup_by(|a, b| (*a - *b).abs() <= NODE_MERGE_TOLERANCE * l);
        // Keep the exact end points.
        s[0] = 0.0;
        *s.last_mut().expect("at least two nodes") = l;
    }
    s
}

impl System {
    /// Assemble a validated model. Beams marked `rigid` become rigid
    /// bodies first ([`Model::with_rigid_beams`]).
    ///
    /// The system is assembled relative to the model's centre of mass
    /// ([`Model::centre_of_mass`], kept as [`System::origin`]): inside,
    /// positions are O(the assembly's size) wherever the model sits.
    pub fn new(model: &ValidModel) -> System {
        System::with_nodes(model, &[])
    }

    /// [`System::new`] with a mesh node at each of the material points
    /// `nodes` too, given as (beam index, arc length [SI: m]): a point that
    /// is not a mesh node is made one, as for attachments.
    pub fn with_nodes(model: &ValidModel, nodes: &[(usize, f64)]) -> System {
        let assembly = model.assembly();
        let mut sys = System::assemble(assembly, nodes);
        sys.origin = v2(assembly.origin);
        sys
    }

    fn assemble(assembly: &Assembly, nodes: &[(usize, f64)]) -> System {
        let model = &assembly.model;
        let mut dof = 0;
        let mut q0 = Vec::new();
        let mut beams = Vec::new();
        for (index, b) in model.beams.iter().enumerate() {
            let extra: Vec<f64> = nodes.iter().filter(|n| n.0 == index).map(|n| n.1).collect();
            let node_s = mesh_nodes(model, b, &extra);
            let section = CableSection::of(&b.section, &b.material);
            let elements: Vec<CableElement> = node_s
                .windows(2)
                .map(|w| CableElement::new(w[1] - w[0], section))
                .collect();
            let packed = if elements.len() <= PACKED_ELEMENTS {
                PackedElements::of_beam(&elements)
            } else {
                Vec::new()
            };
            let t = v2(b.tangent());
            let start = v2(b.start);
            for &s in &node_s {
                let p = start + t * s;
                q0.extend_from_slice(&[p.x, p.y, t.x, t.y]);
            }
            beams.push(BeamMesh {
                id: b.id.clone(),
                dof0: dof,
                section,
                elements,
                packed,
                start,
                tangent: t,
                node_s,
            });
            dof = q0.len();
        }
        let mut rigid_bodies = Vec::new();
        for r in &model.rigid_bodies {
            rigid_bodies.push(RigidDofs {
                id: r.id.clone(),
                dof0: dof,
                mass: r.mass,
                inertia: r.inertia,
            });
            q0.extend_from_slice(&[r.position[0], r.position[1], r.angle_deg.to_radians()]);
            dof = q0.len();
        }
        let mut point_masses = Vec::new();
        for p in &model.point_masses {
            point_masses.push(PointMassDofs {
                id: p.id.clone(),
                dof0: dof,
                mass: p.mass,
            });
            q0.extend_from_slice(&p.position);
            dof = q0.len();
        }
        let mut sys = System {
            name: model.name.clone(),
            beams,
            rigid_bodies,
            point_masses,
            constraints: Vec::new(),
            force_elements: Vec::new(),
            contacts: Vec::new(),
            loads: Vec::new(),
            sensors: Vec::new(),
            gravity: v2(model.gravity),
            q0,
            origin: Vector2::zeros(),
            constraint_rows: Vec::new(),
            released: Vec::new(),
            ndof: dof,
            nrows: 0,
            mass: std::sync::OnceLock::new(),
        };
        sys.add_joints(assembly);
        sys.add_springs(assembly);
        sys.add_loads_and_sensors(assembly);
        sys.add_contacts(assembly);
        sys
    }

    fn add_contacts(&mut self, assembly: &Assembly) {
        let model = &assembly.model;
        for (c, r) in model.contacts.iter().zip(&assembly.resolution.contacts) {
            let seg = c.segment();
            let owner = r.owner;
            let end = |local: [f64; 2]| match owner {
                SegmentOwner::Ground => Anchor::Ground {
                    position: v2(local),
                },
                SegmentOwner::Body(i) => {
                    let d = self.rigid_bodies[i].dof0;
                    Anchor::Rigid {
                        dofs: [d, d + 1, d + 2],
                        local: v2(local),
                    }
                }
            };
            let point = self.anchor(&r.point);
            let kind = match r.kind {
                ResolvedContactKind::PinSlot { clearance } => ContactKind::PinSlot { clearance },
                ResolvedContactKind::PointLine { radius, side } => {
                    let side = match side {
                        Some(Side::Left) => 1.0,
                        Some(Side::Right) => -1.0,
                        None => {
                            // The side the point starts on (validated: off the line).
                            let (a, b) = model.segment_global(seg, owner);
                            let (a, b) = (v2(a), v2(b));
                            let t = (b - a).normalize();
                            let h = perp(t).dot(&(point.position(&self.q0) - a));
                            h.signum()
                        }
                    };
                    ContactKind::PointLine { radius, side }
                }
            };
            self.contacts.push(ContactElement::new(
                c.id().to_string(),
                kind,
                [end(seg.from), end(seg.to)],
                point,
                NormalLaw::new(c.law()),
                c.friction(),
                &self.q0,
            ));
        }
    }

    /// Anchor of a point resolved in this system's model
    /// ([`ValidModel::resolve_point`]; a rigid body's centre for
    /// `{"body": id}` without `local`).
    pub fn anchor_of(&self, target: &ResolvedPoint) -> Anchor {
        self.anchor(target)
    }

    /// Anchor of a point resolved in this system's model: `index` of its
    /// body's kind (its mesh, its coordinates), a rigid body's centre
    /// without `local`.
    fn anchor(&self, target: &ResolvedPoint) -> Anchor {
        match *target {
            ResolvedPoint::Beam { index, s } => self.beams[index].anchor_at(s),
            ResolvedPoint::Rigid { index, local } => {
                let dof0 = self.rigid_bodies[index].dof0;
                Anchor::Rigid {
                    dofs: [dof0, dof0 + 1, dof0 + 2],
                    local: local.map_or_else(Vector2::zeros, v2),
                }
            }
            ResolvedPoint::PointMass { index } => {
                let dof0 = self.point_masses[index].dof0;
                Anchor::PointMass {
                    dofs: [dof0, dof0 + 1],
                }
            }
            ResolvedPoint::Ground { position } => Anchor::Ground {
                position: v2(position),
            },
        }
    }

    /// The anchors of a joint's or a spring's two points. In a joint, a
    /// rigid-body point without `local` is where the other point starts.
    fn pair(&self, model: &Model, a: &ResolvedPoint, b: &ResolvedPoint, joint: bool) -> Pair {
        let (a, b) = if joint {
            let (pa, pb) = (b.explicit_position(model), a.explicit_position(model));
            (at_partner(model, *a, pa), at_partner(model, *b, pb))
        } else {
            (*a, *b)
        };
        Pair {
            a: self.anchor(&a),
            b: self.anchor(&b),
        }
    }

    fn add_joints(&mut self, assembly: &Assembly) {
        let model = &assembly.model;
        for (i, (j, r)) in model
            .joints
            .iter()
            .zip(&assembly.resolution.joints)
            .enumerate()
        {
            let label = j.id.clone().unwrap_or_else(|| format!("joints[{i}]"));
            let pair = self.pair(model, &r.a, &r.b, true);
            let angle_a = if pair.a.has_angle() {
                pair.a.angle(&self.q0)
            } else {
                0.0
            };
            let constraint = self.constraints.len();
            let (c, torsion): (Box<dyn Constraint>, _) = match r.kind {
                ResolvedJointKind::Pin { torsion, release } => {
                    let pin = Pin {
                        label: label.clone(),
                        pair: pair.clone(),
                    };
                    if let Some(time) = release {
                        self.released.push(ReleasedSupport {
                            constraint,
                            time,
                            joint: ReleasedJoint::Pin(pin.clone()),
                        });
                    }
                    (Box::new(pin), torsion)
                }
                ResolvedJointKind::Weld => {
                    let offset = pair.b.angle(&self.q0) - angle_a;
                    let weld = Weld {
                        label: label.clone(),
                        pair: pair.clone(),
                        offset,
                    };
                    (Box::new(weld), None)
                }
                ResolvedJointKind::Slider { axis, release } => {
                    let axis = v2(axis).normalize();
                    let normal0 = Vector2::new(-axis.y, axis.x);
                    let slider = Slider {
                        label: label.clone(),
                        pair: pair.clone(),
                        normal0,
                        angle0: angle_a,
                    };
                    if let Some(time) = release {
                        self.released.push(ReleasedSupport {
                            constraint,
                            time,
                            joint: ReleasedJoint::Slider(slider.clone()),
                        });
                    }
                    (Box::new(slider), None)
                }
            };
            self.constraint_rows.push(self.nrows);
            self.nrows += c.rows();
            self.constraints.push(c);
            if let Some(t) = torsion {
                let offset = pair.b.angle(&self.q0) - angle_a;
                self.force_elements.push(Box::new(TorsionSpring {
                    label: format!("{label} torsion"),
                    pair,
                    stiffness: t.stiffness,
                    damping: t.damping,
                    offset,
                }));
            }
        }
    }

    fn add_springs(&mut self, assembly: &Assembly) {
        let model = &assembly.model;
        for (i, (s, r)) in model
            .springs
            .iter()
            .zip(&assembly.resolution.springs)
            .enumerate()
        {
            let pair = self.pair(model, &r.a, &r.b, false);
            let length = pair.separation(&self.q0).norm();
            let free_length = match r.length {
                SpringLength::Free(l0) => l0,
                SpringLength::Preload(f) => length - f / s.stiffness,
            };
            self.force_elements.push(Box::new(LinearSpring {
                label: s.id.clone().unwrap_or_else(|| format!("springs[{i}]")),
                pair,
                stiffness: s.stiffness,
                damping: s.damping,
                free_length,
            }));
        }
    }

    fn add_loads_and_sensors(&mut self, assembly: &Assembly) {
        let model = &assembly.model;
        for (i, (l, target)) in model
            .loads
            .iter()
            .zip(&assembly.resolution.loads)
            .enumerate()
        {
            let anchor = self.anchor(target);
            let f = v2(l.force);
            let force = match (l.frame, target) {
                (LoadFrame::Beam, ResolvedPoint::Beam { index, .. }) => {
                    let t = self.beams[*index].tangent;
                    t * f.x + Vector2::new(-t.y, t.x) * f.y
                }
                _ => f,
            };
            let label = l.id.clone().unwrap_or_else(|| format!("loads[{i}]"));
            self.loads.push(PointLoad {
                label,
                anchor,
                force,
                time: l.time,
            });
        }
        for (s, target) in model.sensors.iter().zip(&assembly.resolution.sensors) {
            let (beam, arc) = match *target {
                ResolvedPoint::Beam { index, s } => (Some(index), Some(s)),
                _ => (None, None),
            };
            self.sensors.push(SensorPoint {
                id: s.id.clone(),
                anchor: self.anchor(target),
                beam,
                quantity: s.quantity,
                frame: s.frame,
                direction: v2(s.direction).normalize(),
                s: arc,
            });
        }
    }
}

/// A joint's point, with a rigid-body point without `local` placed where
/// the other point starts (`partner`, its initial global position), in the
/// body frame of its body in `model`.
fn at_partner(model: &Model, p: ResolvedPoint, partner: Option<[f64; 2]>) -> ResolvedPoint {
    match (p, partner) {
        (ResolvedPoint::Rigid { index, local: None }, Some(partner)) => {
            let body = &model.rigid_bodies[index];
            let (s, c) = body.angle_deg.to_radians().sin_cos();
            let d = v2(partner) - v2(body.position);
            ResolvedPoint::Rigid {
                index,
                local: Some([c * d.x + s * d.y, -s * d.x + c * d.y]),
            }
        }
        _ => p,
    }
}
