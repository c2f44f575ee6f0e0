//! The elastic force `Q_s = ∂U/∂e` of a cable element (see
//! [`super::element`] for the element, its energy and units [SI: N]).
//!
//! Point by point in arrays (the slopes r' at the quadrature points, their
//! lengths, the tensions; the curvatures κ = (r' × r'')/|r'|² and their
//! gradients): the operations of [`super::element`]'s `axial_strain` and
//! `BendingPoint` on the same values in the same order, bit for bit, with
//! the square roots and divisions of several points side by side for the
//! vector units. The nodes' sizes |nodeᵢ| of the strain's snapping
//! threshold are formed once for all points. The bulk of a transient step
//! of a bare beam.

use super::element::{CableElement, CableSection, Vec8, AXIAL_POINTS, BENDING_POINTS};

/// The shape derivatives of an element's quadrature points, indexed
/// [shape function][point] (the arrays the force runs over).
#[derive(Debug, Clone)]
pub(super) struct ForceTables {
    pub(super) axial_d1: [[f64; AXIAL_POINTS]; 4],
    pub(super) bending_d1: [[f64; BENDING_POINTS]; 4],
    pub(super) bending_d2: [[f64; BENDING_POINTS]; 4],
}

/// Σᵢ xᵢ d[i][k] in the order of the element's `combine`: one component of
/// r' or r'' at point k from the nodes' components x.
#[inline(always)]
fn at<const N: usize>(d: &[[f64; N]; 4], k: usize, x: &[f64; 4]) -> f64 {
    x[0] * d[0][k] + x[1] * d[1][k] + x[2] * d[2][k] + x[3] * d[3][k]
}

impl CableElement {
    /// Elastic force `Q_s = ∂U/∂e`, added into `out`.
    #[inline(always)]
    pub fn elastic_force_into(&self, e: &Vec8, out: &mut Vec8) {
        let CableSection { ea, ei, .. } = self.section;
        let (ex, ey) = ([e[0], e[2], e[4], e[6]], [e[1], e[3], e[5], e[7]]);
        let node_size: [f64; 4] = std::array::from_fn(|i| (ex[i] * ex[i] + ey[i] * ey[i]).sqrt());
        const A: usize = AXIAL_POINTS;
        let d1 = &self.tables.axial_d1;
        let (mut fx, mut fy) = ([0.0; A], [0.0; A]);
        for k in 0..A {
            let (x, y) = (at(d1, k, &ex), at(d1, k, &ey));
            let l = (x * x + y * y).sqrt();
            let size = d1[0][k].abs() * node_size[0]
                + d1[1][k].abs() * node_size[1]
                + d1[2][k].abs() * node_size[2]
                + d1[3][k].abs() * node_size[3];
            let eps = l - 1.0;
            let eps = if eps.abs() <= 4.0 * f64::EPSILON * size {
                0.0
            } else {
                eps
            };
            let s = self.axial[k].w * ea * eps / l;
            (fx[k], fy[k]) = (x * s, y * s);
        }
        for k in 0..A {
            for i in 0..4 {
                out[2 * i] += d1[i][k] * fx[k];
                out[2 * i + 1] += d1[i][k] * fy[k];
            }
        }
        const B: usize = BENDING_POINTS;
        let (d1, d2) = (&self.tables.bending_d1, &self.tables.bending_d2);
        // κ = c/g and its gradients p = ∂κ/∂r', q = ∂κ/∂r'' per point.
        let (mut px, mut py, mut qx, mut qy) = ([0.0; B], [0.0; B], [0.0; B], [0.0; B]);
        let mut cc = [0.0; B];
        for k in 0..B {
            let (r1x, r1y) = (at(d1, k, &ex), at(d1, k, &ey));
            let (r2x, r2y) = (at(d2, k, &ex), at(d2, k, &ey));
            let g = r1x * r1x + r1y * r1y;
            let c = r1x * r2y + r1y * -r2x;
            let kappa = c / g;
            let t = 2.0 * c / (g * g);
            cc[k] = self.bending[k].w * ei * kappa;
            (px[k], py[k]) = (r2y / g - r1x * t, -r2x / g - r1y * t);
            (qx[k], qy[k]) = (-r1y / g, r1x / g);
        }
        for k in 0..B {
            for i in 0..4 {
                out[2 * i] += cc[k] * (px[k] * d1[i][k] + qx[k] * d2[i][k]);
                out[2 * i + 1] += cc[k] * (py[k] * d1[i][k] + qy[k] * d2[i][k]);
            }
        }
    }
}
