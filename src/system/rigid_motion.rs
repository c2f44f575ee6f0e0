//! Rigid motions of the assembly's bodies: the kinematic candidates for
//! zero-frequency modes.
//!
//! Every body (a whole beam, a rigid body, a point mass) can translate and
//! turn without straining; bodies joined by welds move as one rigid
//! cluster (union–find over the welds, so a welded frame of a thousand
//! beams is one cluster). A cluster's motions at the state q are the
//! fields, in the global coordinates:
//! - translation along x and along y [SI: m per m];
//! - rotation about the cluster's centroid c, scaled by its size ℓ
//!   [SI: m per m]: a point r moves by ℓ⁻¹·ẑ × (r − c)·ℓ = ẑ × (r − c),
//!   a beam slope r' by ẑ × r', a rigid body's angle by 1.
//!
//! A point mass has no orientation, so a point mass alone contributes its
//! two translations only. The columns are sparse: each is nonzero on its
//! cluster's coordinates only.

use super::System;
use crate::mechanics::anchor::Anchor;

/// A sparse column over the global coordinates: (coordinate, value).
pub type SparseColumn = Vec<(usize, f64)>;

/// The rigid clusters and their motion fields.
#[derive(Debug, Clone)]
pub struct RigidMotions {
    /// Number of rigid clusters.
    pub clusters: usize,
    /// Two or three fields per cluster.
    pub fields: Vec<SparseColumn>,
    /// The cluster of every coordinate (`usize::MAX` for none).
    pub cluster_of_dof: Vec<usize>,
}

/// A body's coordinates: its kind decides how a rotation moves them.
#[derive(Clone, Copy)]
enum Body {
    /// Beam nodes from `dof0`, 4 coordinates each [rx, ry, r'x, r'y].
    Beam { dof0: usize, nodes: usize },
    /// Rigid body [x, y, θ].
    Rigid { dof0: usize },
    /// Point mass [x, y].
    Point { dof0: usize },
}

fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

impl System {
    /// The x coordinate of every material point with a position (beam
    /// nodes, rigid bodies, point masses); its y follows it [SI: m].
    pub fn point_coordinates(&self) -> impl Iterator<Item = usize> + '_ {
        self.bodies().into_iter().flat_map(points)
    }

    fn bodies(&self) -> Vec<Body> {
        let mut bodies: Vec<Body> = self
            .beams
            .iter()
            .map(|b| Body::Beam {
                dof0: b.dof0,
                nodes: b.node_count(),
            })
            .collect();
        bodies.extend(
            self.rigid_bodies
                .iter()
                .map(|r| Body::Rigid { dof0: r.dof0 }),
        );
        bodies.extend(
            self.point_masses
                .iter()
                .map(|p| Body::Point { dof0: p.dof0 }),
        );
        bodies
    }

    /// The rigid-motion fields of every weld cluster at the state q.
    pub fn rigid_motions(&self, q: &[f64]) -> RigidMotions {
        let bodies = self.bodies();
        let mut body_of = vec![usize::MAX; self.ndof()];
        for (k, b) in bodies.iter().enumerate() {
            let range = match *b {
                Body::Beam { dof0, nodes } => dof0..dof0 + 4 * nodes,
                Body::Rigid { dof0 } => dof0..dof0 + 3,
                Body::Point { dof0 } => dof0..dof0 + 2,
            };
            body_of[range].fill(k);
        }
        let body_at = |a: &Anchor| a.dofs().first().map(|&d| body_of[d]);
        let mut parent: Vec<usize> = (0..bodies.len()).collect();
        for c in self.constraints.iter().filter(|c| c.rigid()) {
            if let (Some(a), Some(b)) = (body_at(&c.pair().a), body_at(&c.pair().b)) {
                let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
                if ra != rb {
                    parent[ra.max(rb)] = ra.min(rb);
                }
            }
        }
        let mut members: Vec<Vec<usize>> = vec![Vec::new(); bodies.len()];
        for k in 0..bodies.len() {
            let root = find(&mut parent, k);
            members[root].push(k);
        }
        let mut fields = Vec::new();
        let mut clusters = 0;
        let mut cluster_of_body = vec![usize::MAX; bodies.len()];
        for group in members.iter().filter(|m| !m.is_empty()) {
            for &k in group {
                cluster_of_body[k] = clusters;
            }
            clusters += 1;
            fields.extend(cluster_fields(group.iter().map(|&k| bodies[k]), q));
        }
        let cluster_of_dof = body_of
            .iter()
            .map(|&k| cluster_of_body.get(k).copied().unwrap_or(usize::MAX))
            .collect();
        RigidMotions {
            clusters,
            fields,
            cluster_of_dof,
        }
    }
}

impl System {
    /// The rigid motions of the whole assembly as one body (translations
    /// along x and y, the rotation about the centroid of its points) at
    /// the state q: what a zero mode that is not a mechanism is made of.
    pub fn assembly_motions(&self, q: &[f64]) -> Vec<SparseColumn> {
        cluster_fields(self.bodies().into_iter(), q)
    }
}

/// Positions (coordinate of x) of a body's material points that a rotation
/// moves, and its slope or angle coordinates.
fn points(body: Body) -> impl Iterator<Item = usize> {
    let (start, count, stride) = match body {
        Body::Beam { dof0, nodes } => (dof0, nodes, 4),
        Body::Rigid { dof0 } => (dof0, 1, 3),
        Body::Point { dof0 } => (dof0, 1, 2),
    };
    (0..count).map(move |k| start + stride * k)
}

fn cluster_fields(bodies: impl Iterator<Item = Body> + Clone, q: &[f64]) -> Vec<SparseColumn> {
    let (mut tx, mut ty) = (Vec::new(), Vec::new());
    let (mut cx, mut cy, mut count) = (0.0, 0.0, 0.0);
    for b in bodies.clone() {
        for i in points(b) {
            tx.push((i, 1.0));
            ty.push((i + 1, 1.0));
            cx += q[i];
            cy += q[i + 1];
            count += 1.0;
        }
    }
    let (cx, cy) = (cx / count, cy / count);
    let mut rot = Vec::new();
    let mut oriented = false;
    for b in bodies {
        for i in points(b) {
            rot.push((i, -(q[i + 1] - cy)));
            rot.push((i + 1, q[i] - cx));
        }
        match b {
            Body::Beam { dof0, nodes } => {
                oriented = true;
                for k in 0..nodes {
                    let i = dof0 + 4 * k + 2;
                    rot.push((i, -q[i + 1]));
                    rot.push((i + 1, q[i]));
                }
            }
            Body::Rigid { dof0 } => {
                oriented = true;
                rot.push((dof0 + 2, 1.0));
            }
            Body::Point { .. } => {}
        }
    }
    rot.retain(|e| e.1 != 0.0);
    let mut out = vec![tx, ty];
    // A lone point (or coincident points without orientation) cannot turn.
    if oriented || rot.iter().any(|e| e.1 != 0.0) {
        out.push(rot);
    }
    out
}
