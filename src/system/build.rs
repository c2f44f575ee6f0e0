//! Construction of a [`System`] from a validated [`Model`].

use super::{BeamMesh, PointMassDofs, ReleasedSupport, RigidDofs, SensorPoint, System};
use crate::mechanics::anchor::{perp, Anchor};
use crate::mechanics::contact::law::NormalLaw;
use crate::mechanics::contact::{ContactElement, ContactKind};
use crate::mechanics::element::{CableElement, CableSection};
use crate::mechanics::joint::{Constraint, Pin, Slider, Weld};
use crate::mechanics::load::PointLoad;
use crate::mechanics::pair::Pair;
use crate::mechanics::spring::{LinearSpring, TorsionSpring};
use crate::model::{
    Contact, JointType, LoadFrame, Model, Placement, PointSpec, PointTarget, SegmentOwner, Side,
};
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

/// Node arc lengths: uniform division plus attachment points.
fn mesh_nodes(model: &Model, beam: &crate::model::Beam) -> Vec<f64> {
    let l = beam.length;
    let n = beam.elements;
    let mut s: Vec<f64> = (0..=n).map(|k| l * k as f64 / n as f64).collect();
    if beam.nodes_at_attachments {
        let extra = all_points(model)
            .filter(|p| p.beam.as_deref() == Some(beam.id.as_str()))
            .filter_map(|p| p.s);
        s.extend(extra.map(|x| x.clamp(0.0, l)));
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
    pub fn new(model: &Model) -> System {
        if model.beams.iter().any(|b| b.rigid) {
            return System::centred(&model.with_rigid_beams());
        }
        System::centred(model)
    }

    fn centred(model: &Model) -> System {
        let c = model.centre_of_mass();
        let mut sys = System::assemble(&model.placed(&Placement::translation([-c[0], -c[1]])));
        sys.origin = v2(c);
        sys
    }

    fn assemble(model: &Model) -> System {
        let mut dof = 0;
        let mut q0 = Vec::new();
        let mut beams = Vec::new();
        for b in &model.beams {
            let node_s = mesh_nodes(model, b);
            let section = CableSection::of(&b.section, &b.material);
            let elements = node_s
                .windows(2)
                .map(|w| CableElement::new(w[1] - w[0], section))
                .collect();
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
        sys.add_joints(model);
        sys.add_springs(model);
        sys.add_loads_and_sensors(model);
        sys.add_contacts(model);
        sys
    }

    fn add_contacts(&mut self, model: &Model) {
        for c in &model.contacts {
            let seg = c.segment();
            let owner = model.segment_owner(seg, "").expect("validated");
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
            let target = model.resolve(c.point(), "point").expect("validated");
            let point = self.anchor(&target, None);
            let kind = match c {
                Contact::PinSlot {
                    pin_radius, slot, ..
                } => ContactKind::PinSlot {
                    clearance: 0.5 * slot.width.expect("validated") - pin_radius,
                },
                Contact::PointLine { radius, side, .. } => {
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
                    ContactKind::PointLine {
                        radius: *radius,
                        side,
                    }
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

    /// Anchor of a resolved point (a rigid body's centre for `{"body": id}`
    /// without `local`).
    pub fn anchor_of(&self, target: &PointTarget) -> Anchor {
        self.anchor(target, None)
    }

    /// Anchor of a resolved point; `partner` is the other point's initial
    /// position for `{"body": id}` without `local` inside a joint.
    fn anchor(&self, target: &PointTarget, partner: Option<[f64; 2]>) -> Anchor {
        match *target {
            PointTarget::Beam { index, s, .. } => self.beams[index].anchor_at(s),
            PointTarget::Rigid { body, index, local } => {
                let dof0 = self.rigid_bodies[index].dof0;
                let local = match (local, partner) {
                    (Some(l), _) => v2(l),
                    (None, Some(p)) => {
                        let (s, c) = body.angle_deg.to_radians().sin_cos();
                        let d = v2(p) - v2(body.position);
                        Vector2::new(c * d.x + s * d.y, -s * d.x + c * d.y)
                    }
                    (None, None) => Vector2::zeros(),
                };
                Anchor::Rigid {
                    dofs: [dof0, dof0 + 1, dof0 + 2],
                    local,
                }
            }
            PointTarget::PointMass { index, .. } => {
                let dof0 = self.point_masses[index].dof0;
                Anchor::PointMass {
                    dofs: [dof0, dof0 + 1],
                }
            }
            PointTarget::Ground { position } => Anchor::Ground {
                position: v2(position),
            },
        }
    }

    fn resolve_pair(&self, model: &Model, a: &PointSpec, b: &PointSpec, joint: bool) -> Pair {
        let ta = model.resolve(a, "a").expect("validated");
        let tb = model.resolve(b, "b").expect("validated");
        let (pa, pb) = if joint {
            (tb.explicit_position(), ta.explicit_position())
        } else {
            (None, None)
        };
        Pair {
            a: self.anchor(&ta, pa),
            b: self.anchor(&tb, pb),
        }
    }

    fn add_joints(&mut self, model: &Model) {
        for (i, j) in model.joints.iter().enumerate() {
            let label = j.id.clone().unwrap_or_else(|| format!("joints[{i}]"));
            let pair = self.resolve_pair(model, &j.a, &j.b, true);
            let angle_a = if pair.a.has_angle() {
                pair.a.angle(&self.q0)
            } else {
                0.0
            };
            let c: Box<dyn Constraint> = match j.kind {
                JointType::Pin => Box::new(Pin {
                    label: label.clone(),
                    pair: pair.clone(),
                }),
                JointType::Weld => {
                    let offset = pair.b.angle(&self.q0) - angle_a;
                    Box::new(Weld {
                        label: label.clone(),
                        pair: pair.clone(),
                        offset,
                    })
                }
                JointType::Slider => {
                    let axis = v2(j.axis.expect("validated")).normalize();
                    let normal0 = Vector2::new(-axis.y, axis.x);
                    Box::new(Slider {
                        label: label.clone(),
                        pair: pair.clone(),
                        normal0,
                        angle0: angle_a,
                    })
                }
            };
            if let Some(time) = j.release {
                self.released.push(ReleasedSupport {
                    constraint: self.constraints.len(),
                    time,
                });
            }
            self.constraint_rows.push(self.nrows);
            self.nrows += c.rows();
            self.constraints.push(c);
            if j.torsion_stiffness.is_some() || j.torsion_damping.is_some() {
                let offset = pair.b.angle(&self.q0) - angle_a;
                self.force_elements.push(Box::new(TorsionSpring {
                    label: format!("{label} torsion"),
                    pair,
                    stiffness: j.torsion_stiffness.unwrap_or(0.0),
                    damping: j.torsion_damping.unwrap_or(0.0),
                    offset,
                }));
            }
        }
    }

    fn add_springs(&mut self, model: &Model) {
        for (i, s) in model.springs.iter().enumerate() {
            let pair = self.resolve_pair(model, &s.a, &s.b, false);
            let length = pair.separation(&self.q0).norm();
            let free_length = match (s.free_length, s.preload) {
                (Some(l0), _) => l0,
                (None, Some(f)) => length - f / s.stiffness,
                (None, None) => unreachable!("validated"),
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

    fn add_loads_and_sensors(&mut self, model: &Model) {
        for (i, l) in model.loads.iter().enumerate() {
            let target = model.resolve(&l.at, "at").expect("validated");
            let anchor = self.anchor(&target, None);
            let f = v2(l.force);
            let force = match (l.frame, &target) {
                (LoadFrame::Beam, PointTarget::Beam { index, .. }) => {
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
        for s in &model.sensors {
            let target = model.resolve(&s.at, "at").expect("validated");
            let (beam, arc) = match target {
                PointTarget::Beam { index, s, .. } => (Some(index), Some(s)),
                _ => (None, None),
            };
            self.sensors.push(SensorPoint {
                id: s.id.clone(),
                anchor: self.anchor(&target, None),
                beam,
                quantity: s.quantity,
                frame: s.frame,
                direction: v2(s.direction).normalize(),
                s: arc,
            });
        }
    }
}
