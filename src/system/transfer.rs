//! A deformed state carried from one design of an assembly to another
//! through material positions.
//!
//! Two designs of one assembly (the same beams, bodies and point masses by
//! id, real numbers changed: an attachment moved along a beam, a length, a
//! stiffness) can have different coordinate layouts: with
//! `nodes_at_attachments` a moved attachment moves its mesh node, and a node
//! that crosses a uniform-division node (or lands on one) changes the node
//! count. A coordinate vector of one design is then meaningless for the
//! other, and indexing it with the other's maps is wrong or out of bounds.
//!
//! [`System::transfer_from`] builds the other design's coordinates from the
//! deformed shape instead:
//! - a beam node at arc length s of a beam of length L takes the source
//!   beam's interpolated position r and slope r′ at the same *relative*
//!   material point s·L_src/L (the elements' own cubic Hermite fields,
//!   [`crate::mechanics::element::shape`]); the slope is rescaled by
//!   L_src/L so that the stretch |∂r/∂s| is the source's [–];
//! - a rigid body keeps its [x, y, θ] and a point mass its [x, y]
//!   [SI: m, m, rad];
//! - positions are moved between the two systems' origins (each system is
//!   assembled about its own model's centre of mass, [`System::origin`]).
//!
//! Where the two layouts agree and the lengths are equal, the result is the
//! source vector itself up to the origin shift: nodes land on nodes, where
//! the Hermite field interpolates its nodal values exactly.

use super::System;
use crate::mechanics::element::shape;
use nalgebra::Vector2;

pub use crate::error::TransferError;

impl System {
    /// The coordinates of this design holding the deformed state `q_from`
    /// of the design `from` (see the module doc).
    pub fn transfer_from(&self, from: &System, q_from: &[f64]) -> Result<Vec<f64>, TransferError> {
        if q_from.len() != from.ndof() {
            return Err(TransferError::Length {
                got: q_from.len(),
                expected: from.ndof(),
            });
        }
        let shift = from.origin - self.origin;
        let mut q = self.q0.clone();
        for b in &self.beams {
            let src =
                from.beams
                    .iter()
                    .find(|s| s.id == b.id)
                    .ok_or_else(|| TransferError::Missing {
                        kind: "beam",
                        id: b.id.clone(),
                    })?;
            let (l, l_src) = (beam_length(b), beam_length(src));
            let ratio = l_src / l;
            for (node, &s) in b.node_s.iter().enumerate() {
                let (k, xi) = src.locate(s * ratio);
                let dofs = src.element_dofs(k);
                let sv = shape(src.elements[k].le, xi);
                let (mut r, mut dr) = (Vector2::zeros(), Vector2::zeros());
                for a in 0..4 {
                    let v = Vector2::new(q_from[dofs[2 * a]], q_from[dofs[2 * a + 1]]);
                    r += sv.s[a] * v;
                    dr += sv.d1[a] * v;
                }
                let r = r + shift;
                let dr = dr * ratio;
                let i = b.dof0 + 4 * node;
                q[i..i + 4].copy_from_slice(&[r.x, r.y, dr.x, dr.y]);
            }
        }
        for r in &self.rigid_bodies {
            let src = from
                .rigid_bodies
                .iter()
                .find(|s| s.id == r.id)
                .ok_or_else(|| TransferError::Missing {
                    kind: "rigid body",
                    id: r.id.clone(),
                })?;
            let (i, j) = (r.dof0, src.dof0);
            q[i] = q_from[j] + shift.x;
            q[i + 1] = q_from[j + 1] + shift.y;
            q[i + 2] = q_from[j + 2];
        }
        for p in &self.point_masses {
            let src = from
                .point_masses
                .iter()
                .find(|s| s.id == p.id)
                .ok_or_else(|| TransferError::Missing {
                    kind: "point mass",
                    id: p.id.clone(),
                })?;
            q[p.dof0] = q_from[src.dof0] + shift.x;
            q[p.dof0 + 1] = q_from[src.dof0 + 1] + shift.y;
        }
        Ok(q)
    }
}

/// Arc length of a meshed beam [SI: m].
fn beam_length(b: &super::BeamMesh) -> f64 {
    b.node_s[b.node_s.len() - 1]
}

#[cfg(test)]
mod tests {
    use crate::model::Model;
    use crate::system::System;

    /// Moving an attachment moves its mesh node; the reference state of one
    /// design carried to the other is the other's reference (a straight
    /// beam is interpolated exactly by the cubics).
    #[test]
    fn reference_carries_to_reference_across_layouts() {
        let a = Model::switch_off_builtin();
        let mut b = a.to_model();
        b.springs[0].b.s = Some(0.023);
        let b = b.validated().expect("a valid design");
        let (sa, sb) = (System::new(&a), System::new(&b));
        assert_ne!(
            sa.beams[0].node_s, sb.beams[0].node_s,
            "the test needs meshes that differ"
        );
        let q = sb.transfer_from(&sa, &sa.q0).expect("same assembly");
        let l = sb.length_scale();
        for (x, y) in q.iter().zip(&sb.q0) {
            assert!((x - y).abs() <= 1e-14 * l.max(1.0), "{x} vs {y}");
        }
    }
}
