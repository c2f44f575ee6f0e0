//! The assembled system: the global coordinate vector q and the maps from
//! bodies, joints, springs and loads to it (the paper's Boolean matrices,
//! done as index lists).
//!
//! Layout of q: every beam's nodes in order, 4 coordinates per node
//! [rx, ry, r'x, r'y] [SI: m, m, –, –]; then each rigid body [x, y, θ]
//! [SI: m, m, rad]; then each point mass [x, y] [SI: m].
//!
//! Beams are meshed with `elements` equal elements, plus (with
//! `nodes_at_attachments`) a node at every point where a joint, spring, load
//! or sensor attaches, so that concentrated masses and welds sit on nodes.

mod assemble;
mod build;
mod energy;
mod mass;
mod release;
mod rigid_motion;
mod supports;
mod transfer;

pub use assemble::{EnergyBreakdown, ForceParts, Linearization};
pub use mass::MassMatrix;
pub use release::{ReleasedJoint, ReleasedSupport};
pub use rigid_motion::{RigidMotions, SparseColumn};
pub use supports::FreeBody;
pub use transfer::TransferError;

use crate::mechanics::anchor::Anchor;
use crate::mechanics::cable_force::PackedElements;
use crate::mechanics::contact::ContactElement;
use crate::mechanics::element::{CableElement, CableSection};
use crate::mechanics::joint::Constraint;
use crate::mechanics::load::PointLoad;
use crate::mechanics::spring::ForceElement;
use crate::model::{SensorFrame, SensorQuantity};
use nalgebra::Vector2;
use std::sync::OnceLock;

/// The most elements a beam has its constants packed for (at 432 bytes an
/// element, 1.8 MB): a transient's beams, not a 100,000-element modal mesh.
pub const PACKED_ELEMENTS: usize = 4096;

/// A meshed beam.
#[derive(Debug, Clone)]
pub struct BeamMesh {
    pub id: String,
    /// Arc length of each node [SI: m], increasing, first 0, last L.
    pub node_s: Vec<f64>,
    /// Index of the beam's first coordinate in q.
    pub dof0: usize,
    pub section: CableSection,
    pub elements: Vec<CableElement>,
    /// The elements' constants lane by lane, for the forces of elements
    /// side by side; empty past [`PACKED_ELEMENTS`] elements (the forces
    /// then gather them from `elements`).
    pub packed: Vec<PackedElements>,
    /// Reference position of node 0 [SI: m] and unit tangent.
    pub start: Vector2<f64>,
    pub tangent: Vector2<f64>,
}

impl BeamMesh {
    /// Global indices of element k's 8 coordinates.
    pub fn element_dofs(&self, k: usize) -> [usize; 8] {
        std::array::from_fn(|i| self.dof0 + 4 * k + i)
    }

    /// Element and local coordinate ξ of arc length s.
    pub fn locate(&self, s: f64) -> (usize, f64) {
        let last = self.elements.len() - 1;
        let k = match self.node_s.partition_point(|&x| x <= s) {
            0 => 0,
            i => (i - 1).min(last),
        };
        let xi = (s - self.node_s[k]) / self.elements[k].le;
        (k, xi.clamp(0.0, 1.0))
    }

    /// Anchor of the material point at arc length s.
    pub fn anchor_at(&self, s: f64) -> Anchor {
        let (k, xi) = self.locate(s);
        Anchor::beam(self.element_dofs(k), self.elements[k].le, xi)
    }

    pub fn node_count(&self) -> usize {
        self.node_s.len()
    }

    /// Total mass [SI: kg].
    pub fn mass(&self) -> f64 {
        self.section.rho_a * self.node_s[self.node_s.len() - 1]
    }
}

/// A rigid body's place in q.
#[derive(Debug, Clone)]
pub struct RigidDofs {
    pub id: String,
    pub dof0: usize,
    pub mass: f64,
    pub inertia: f64,
}

/// A point mass's place in q.
#[derive(Debug, Clone)]
pub struct PointMassDofs {
    pub id: String,
    pub dof0: usize,
    pub mass: f64,
}

/// A sensor resolved to an anchor.
#[derive(Debug, Clone)]
pub struct SensorPoint {
    pub id: String,
    pub anchor: Anchor,
    /// Beam index for the co-rotated frame.
    pub beam: Option<usize>,
    pub quantity: SensorQuantity,
    pub frame: SensorFrame,
    /// Unit measuring direction (global, or in the beam's initial frame).
    pub direction: Vector2<f64>,
    /// Reference arc length on the beam, if on a beam [SI: m].
    pub s: Option<f64>,
}

/// The assembled multibody system.
#[derive(Debug)]
pub struct System {
    pub name: String,
    pub beams: Vec<BeamMesh>,
    pub rigid_bodies: Vec<RigidDofs>,
    pub point_masses: Vec<PointMassDofs>,
    pub constraints: Vec<Box<dyn Constraint>>,
    pub force_elements: Vec<Box<dyn ForceElement>>,
    /// Unilateral contacts (their elastic part acts like a spring).
    pub contacts: Vec<ContactElement>,
    pub loads: Vec<PointLoad>,
    pub sensors: Vec<SensorPoint>,
    /// Gravitational acceleration [SI: m/s²].
    pub gravity: Vector2<f64>,
    /// Reference (initial) coordinates, positions relative to `origin`.
    pub q0: Vec<f64>,
    /// Where the model's frame has the system's origin [SI: m]: the
    /// model's centre of mass. A position in the model's own frame is the
    /// system's position plus this ([`System::user_point`]).
    pub origin: Vector2<f64>,
    /// First row of each constraint in the stacked C.
    pub constraint_rows: Vec<usize>,
    /// Joints that hold until a transient releases them (in constraint order).
    pub released: Vec<ReleasedSupport>,
    ndof: usize,
    nrows: usize,
    /// M, assembled on first use (the masses are fixed once built).
    mass: OnceLock<MassMatrix>,
}

impl System {
    /// Number of coordinates.
    pub fn ndof(&self) -> usize {
        self.ndof
    }

    /// Number of constraint equations.
    pub fn constraint_count(&self) -> usize {
        self.nrows
    }

    /// The constant mass matrix, assembled on the first call.
    pub fn mass(&self) -> &MassMatrix {
        self.mass.get_or_init(|| MassMatrix::assemble(self))
    }

    /// Human-readable name of coordinate i, e.g. `beam blade node 3 r'x`.
    pub fn dof_label(&self, i: usize) -> String {
        for b in &self.beams {
            let n = 4 * b.node_count();
            if (b.dof0..b.dof0 + n).contains(&i) {
                let k = i - b.dof0;
                let name = ["rx", "ry", "r'x", "r'y"][k % 4];
                return format!(
                    "beam `{}` node {} (s = {:.4} mm) {name}",
                    b.id,
                    k / 4,
                    1e3 * b.node_s[k / 4]
                );
            }
        }
        for r in &self.rigid_bodies {
            if (r.dof0..r.dof0 + 3).contains(&i) {
                let name = ["x", "y", "rotation"][i - r.dof0];
                return format!("rigid body `{}` {name}", r.id);
            }
        }
        for p in &self.point_masses {
            if (p.dof0..p.dof0 + 2).contains(&i) {
                return format!("point mass `{}` {}", p.id, ["x", "y"][i - p.dof0]);
            }
        }
        format!("coordinate {i}")
    }

    /// JSON path of the model value that gives coordinate i its mass,
    /// e.g. `rigid_bodies[0].inertia`.
    pub fn dof_model_path(&self, i: usize) -> String {
        for (k, b) in self.beams.iter().enumerate() {
            if (b.dof0..b.dof0 + 4 * b.node_count()).contains(&i) {
                return format!("beams[{k}].material.density");
            }
        }
        for (k, r) in self.rigid_bodies.iter().enumerate() {
            if (r.dof0..r.dof0 + 3).contains(&i) {
                let key = if i == r.dof0 + 2 { "inertia" } else { "mass" };
                return format!("rigid_bodies[{k}].{key}");
            }
        }
        for (k, p) in self.point_masses.iter().enumerate() {
            if (p.dof0..p.dof0 + 2).contains(&i) {
                return format!("point_masses[{k}].mass");
            }
        }
        String::from("$")
    }

    /// Numbers the constraints' rows again after constraints were removed.
    fn renumber_constraints(&mut self) {
        self.constraint_rows.clear();
        let mut rows = 0;
        for c in &self.constraints {
            self.constraint_rows.push(rows);
            rows += c.rows();
        }
        self.nrows = rows;
    }

    /// Whether any spring or torsion spring has a damper.
    pub fn has_dampers(&self) -> bool {
        self.force_elements.iter().any(|f| f.has_damper())
    }

    /// Springs, torsion springs and the elastic part of the contacts: every
    /// element with a potential.
    pub fn elastic_elements(&self) -> impl Iterator<Item = &dyn ForceElement> {
        self.force_elements
            .iter()
            .map(|f| f.as_ref())
            .chain(self.contacts.iter().map(|c| c as &dyn ForceElement))
    }

    /// A length for the assembly [SI: m]: the larger of the longest beam
    /// and the diagonal of the box around all reference positions; 1 m if
    /// both vanish. Tolerances and the scaling of position coordinates
    /// against slopes and angles are taken relative to it.
    pub fn length_scale(&self) -> f64 {
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        let mut any = false;
        for i in self.point_coordinates() {
            any = true;
            for axis in 0..2 {
                lo[axis] = lo[axis].min(self.q0[i + axis]);
                hi[axis] = hi[axis].max(self.q0[i + axis]);
            }
        }
        let diag = if any {
            (hi[0] - lo[0]).hypot(hi[1] - lo[1])
        } else {
            0.0
        };
        let beam = self
            .beams
            .iter()
            .map(|b| b.node_s[b.node_s.len() - 1])
            .fold(0.0, f64::max);
        let l = diag.max(beam);
        if l > 0.0 {
            l
        } else {
            1.0
        }
    }

    /// A position of the system's frame in the model's own frame [SI: m].
    pub fn user_point(&self, p: Vector2<f64>) -> Vector2<f64> {
        p + self.origin
    }

    /// The largest axial stiffness EA of the beams [SI: N] (0 without
    /// beams): the scale of the elastic forces' round-off.
    pub fn stiffest_ea(&self) -> f64 {
        self.beams.iter().map(|b| b.section.ea).fold(0.0, f64::max)
    }

    /// Total mass [SI: kg].
    pub fn total_mass(&self) -> f64 {
        self.beams.iter().map(BeamMesh::mass).sum::<f64>()
            + self.rigid_bodies.iter().map(|r| r.mass).sum::<f64>()
            + self.point_masses.iter().map(|p| p.mass).sum::<f64>()
    }
}
