//! The body as nodes with three translations each: the form a 3D
//! multibody code's reduced body takes (Exudyn's `FEMinterface`: node
//! positions, a mass and a stiffness matrix over 3 translations per node,
//! and the basis over the same).
//!
//! Every coordinate maps onto node translations u, δu = T δq:
//! - a beam node [r, r'] becomes its node r and a virtual node r + h r'
//!   (h half the beam's mean element length [SI: m]): an invertible map,
//!   r' = (v − r)/h, that moves both nodes alike under a rigid motion;
//! - a rigid body [x, y, θ] becomes two nodes at c ± d e (e its x axis at
//!   the linearization state, d = √(J/m) [SI: m]), each of mass m/2: they
//!   reproduce its mass, centre of mass and inertia exactly;
//! - a point mass [x, y] is one node.
//!
//! The mass over u: a beam's T⁻ᵀ M T⁻¹ (its consistent mass is the same
//! in x and y, and so is T, so it is M_s ⊗ I₂), the rigid bodies' and
//! point masses' nodes lumped; M₃ = M_s ⊗ I₃ [SI: kg]. The stiffness is
//! T⁺ᵀ K T⁺ (T⁺ the left inverse: for a rigid body c = (p₁ + p₂)/2,
//! θ = n·(p₁ − p₂)/2d), in the plane: zero rows and columns for z
//! [SI: N/m]. Tᵀ M₃ T = M and Tᵀ K₃ T = K, so any basis Ψ over q, mapped
//! to Ψ₃ = T Ψ (zero in z), gives the same reduced matrices
//! Ψ₃ᵀ M₃ Ψ₃ = ΨᵀMΨ, Ψ₃ᵀ K₃ Ψ₃ = ΨᵀKΨ. A rigid body's two nodes can
//! also move apart along their line, which no Ψ₃ does: K₃ is zero there.

use crate::linalg::Scatter;
use crate::system::Linearization;
use crate::System;
use faer::Mat;

/// What a node stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum NodeKind {
    /// A beam node's position.
    BeamNode,
    /// A beam node's virtual node r + h r'.
    Virtual,
    /// One of a rigid body's two nodes.
    RigidBody,
    /// A point mass.
    PointMass,
}

/// The 3D node form of a body (module doc).
#[derive(Debug, Clone)]
pub struct NodeForm {
    /// Node positions in the model's frame, z = 0 [SI: m].
    pub positions: Vec<[f64; 3]>,
    pub kinds: Vec<NodeKind>,
    /// M₃ (3N × 3N) as (row, column, value), both triangles [SI: kg].
    pub mass: Vec<(usize, usize, f64)>,
    /// K₃ (3N × 3N) as (row, column, value) [SI: N/m].
    pub stiffness: Vec<(usize, usize, f64)>,
    /// Ψ₃ = T Ψ (3N × m) [SI: m per unit modal coordinate].
    pub basis: Mat<f64>,
    /// Per beam node coordinate g (its rx), the node and virtual node.
    beam_nodes: Vec<(usize, [usize; 2])>,
}

/// δu = T δq as rows: per coordinate of q its (u index, weight) list, and
/// the left inverse T⁺ likewise per u index... kept as the two maps.
struct Maps {
    /// u = T q: per u index, (q index, weight).
    forward: Vec<Vec<(usize, f64)>>,
    /// q = T⁺ u: per q index, (u index, weight).
    inverse: Vec<Vec<(usize, f64)>>,
}

/// Accumulates Aᵤ = T⁺ᵀ A T⁺ from the entries of A over q.
struct Pulled<'a> {
    inverse: &'a [Vec<(usize, f64)>],
    out: std::collections::BTreeMap<(usize, usize), f64>,
}

impl Scatter for Pulled<'_> {
    fn add(&mut self, i: usize, j: usize, v: f64) {
        if v == 0.0 {
            return;
        }
        for &(a, wa) in &self.inverse[i] {
            for &(b, wb) in &self.inverse[j] {
                *self.out.entry((a, b)).or_insert(0.0) += wa * v * wb;
            }
        }
    }
}

impl NodeForm {
    /// The node form of `system` at `at` and the basis `basis` (n × m).
    pub fn new(system: &System, at: &Linearization, basis: &Mat<f64>) -> NodeForm {
        let q = at.q;
        let n = system.ndof();
        let mut positions = Vec::new();
        let mut kinds = Vec::new();
        let mut beam_nodes = Vec::new();
        let mut maps = Maps {
            forward: Vec::new(),
            inverse: vec![Vec::new(); n],
        };
        // Lumped node masses (rigid bodies, point masses): (u node, mass).
        let mut lumped: Vec<(usize, f64)> = Vec::new();
        let origin = system.origin;
        let mut push = |p: [f64; 2], kind: NodeKind, positions: &mut Vec<[f64; 3]>| {
            positions.push([p[0] + origin.x, p[1] + origin.y, 0.0]);
            kinds.push(kind);
            positions.len() - 1
        };
        for b in &system.beams {
            let length = b.node_s[b.node_s.len() - 1];
            let h = 0.5 * length / b.elements.len() as f64;
            for k in 0..b.node_count() {
                let g = b.dof0 + 4 * k;
                let r = [q[g], q[g + 1]];
                let v = [r[0] + h * q[g + 2], r[1] + h * q[g + 3]];
                let a = push(r, NodeKind::BeamNode, &mut positions);
                let c = push(v, NodeKind::Virtual, &mut positions);
                beam_nodes.push((g, [a, c]));
                for axis in 0..2 {
                    maps.forward.push(vec![(g + axis, 1.0)]);
                }
                for axis in 0..2 {
                    maps.forward.push(vec![(g + axis, 1.0), (g + 2 + axis, h)]);
                }
                for axis in 0..2 {
                    maps.inverse[g + axis] = vec![(2 * a + axis, 1.0)];
                    maps.inverse[g + 2 + axis] =
                        vec![(2 * c + axis, 1.0 / h), (2 * a + axis, -1.0 / h)];
                }
            }
        }
        for body in &system.rigid_bodies {
            let g = body.dof0;
            let d = (body.inertia / body.mass).sqrt();
            let (s, c) = q[g + 2].sin_cos();
            let (e, nrm) = ([c, s], [-s, c]);
            let p1 = push(
                [q[g] + d * e[0], q[g + 1] + d * e[1]],
                NodeKind::RigidBody,
                &mut positions,
            );
            let p2 = push(
                [q[g] - d * e[0], q[g + 1] - d * e[1]],
                NodeKind::RigidBody,
                &mut positions,
            );
            for (node, sign) in [(p1, 1.0), (p2, -1.0)] {
                for (axis, n_axis) in nrm.iter().enumerate() {
                    maps.forward
                        .push(vec![(g + axis, 1.0), (g + 2, sign * d * n_axis)]);
                }
                lumped.push((node, 0.5 * body.mass));
            }
            for axis in 0..2 {
                maps.inverse[g + axis] = vec![(2 * p1 + axis, 0.5), (2 * p2 + axis, 0.5)];
            }
            maps.inverse[g + 2] = (0..2)
                .flat_map(|axis| {
                    let w = nrm[axis] / (2.0 * d);
                    [(2 * p1 + axis, w), (2 * p2 + axis, -w)]
                })
                .collect();
        }
        for p in &system.point_masses {
            let g = p.dof0;
            let node = push([q[g], q[g + 1]], NodeKind::PointMass, &mut positions);
            for axis in 0..2 {
                maps.forward.push(vec![(g + axis, 1.0)]);
                maps.inverse[g + axis] = vec![(2 * node + axis, 1.0)];
            }
            lumped.push((node, p.mass));
        }
        // The beams' mass over u (x–x entries only: M_s ⊗ I₂), lumped
        // masses added, then ⊗ I₃.
        // Only the beams' coordinates pull through T⁺: the rigid bodies'
        // and point masses' nodes are lumped below.
        let mut beam_inverse = vec![Vec::new(); n];
        for b in &system.beams {
            let range = b.dof0..b.dof0 + 4 * b.node_count();
            beam_inverse[range.clone()].clone_from_slice(&maps.inverse[range]);
        }
        let mut beam_mass = Pulled {
            inverse: &beam_inverse,
            out: Default::default(),
        };
        system.mass().add_into(&mut beam_mass);
        let mut mass = Vec::new();
        for (&(a, b), &v) in &beam_mass.out {
            if a % 2 == 0 && b % 2 == 0 && v != 0.0 {
                for axis in 0..3 {
                    mass.push((3 * (a / 2) + axis, 3 * (b / 2) + axis, v));
                }
            }
        }
        for &(node, m) in &lumped {
            for axis in 0..3 {
                mass.push((3 * node + axis, 3 * node + axis, m));
            }
        }
        let mut stiff = Pulled {
            inverse: &maps.inverse,
            out: Default::default(),
        };
        system.add_tangent_stiffness(at, &mut stiff);
        let stiffness = stiff
            .out
            .iter()
            .filter(|e| *e.1 != 0.0)
            .map(|(&(a, b), &v)| (3 * (a / 2) + a % 2, 3 * (b / 2) + b % 2, v))
            .collect();
        let nodes = positions.len();
        let mut basis3 = Mat::<f64>::zeros(3 * nodes, basis.ncols());
        for (u, row) in maps.forward.iter().enumerate() {
            let i = 3 * (u / 2) + u % 2;
            for j in 0..basis.ncols() {
                basis3[(i, j)] = row.iter().map(|&(g, w)| w * basis[(g, j)]).sum();
            }
        }
        NodeForm {
            positions,
            kinds,
            mass,
            stiffness,
            basis: basis3,
            beam_nodes,
        }
    }

    /// The node and virtual node of the beam node whose rx coordinate is
    /// `g`.
    pub fn beam_node(&self, g: usize) -> Option<[usize; 2]> {
        self.beam_nodes.iter().find(|e| e.0 == g).map(|e| e.1)
    }
}
