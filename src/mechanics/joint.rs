//! Joints: holonomic constraints C(q) = 0 between two anchors.
//!
//! - [`Pin`]: r_b − r_a = 0 [SI: m], 2 rows.
//! - [`Weld`]: the pin rows plus wrap(θ_b − θ_a − Δ₀) = 0 [rad], 3 rows.
//!   For a beam the angle is that of its slope r', so a weld fixes the
//!   direction of the slope but not its length (no axial strain is forbidden).
//! - [`Slider`]: n(θ_a)·(r_b − r_a) = 0 [SI: m], 1 row; n is the axis normal,
//!   turning with a's orientation.
//!
//! Each constraint writes its residual, its local Jacobian (rows × 16) and
//! the λ-weighted Hessian Σ λᵢ ∂²Cᵢ/∂q² (16 × 16) into caller buffers; the
//! last one gives the ∂(C_qᵀλ)/∂q term of a linearization about a loaded state.

use crate::mechanics::anchor::perp;
use crate::mechanics::pair::{Pair, PairGrad, PairHess, PairJac2, MAX_PAIR_DOFS};
use nalgebra::{SMatrix, Vector2};

/// Most rows of one joint.
pub const MAX_ROWS: usize = 3;
/// Local constraint Jacobian.
pub type ConstraintJac = SMatrix<f64, MAX_ROWS, MAX_PAIR_DOFS>;

/// A holonomic constraint between the two anchors of a pair.
pub trait Constraint: std::fmt::Debug + Send + Sync {
    /// Name for messages.
    fn label(&self) -> &str;
    /// The two anchors.
    fn pair(&self) -> &Pair;
    /// Number of equations.
    fn rows(&self) -> usize;
    /// Whether equation `row` is an angle [rad] (else a length [SI: m]).
    fn row_is_angle(&self, row: usize) -> bool;
    /// The first of two rows that form a plane vector (x, y) in the global
    /// frame and so turn with a rigid rotation of the whole system; `None`
    /// when every row is a rotation-invariant scalar.
    fn vector_rows(&self) -> Option<usize>;
    /// Whether the joint holds its two bodies together rigidly (a weld):
    /// they then move as one rigid cluster in the kinematic count of zero
    /// modes.
    fn rigid(&self) -> bool;
    /// C(q) into `out[..rows]`.
    fn residual(&self, q: &[f64], out: &mut [f64]);
    /// For a joint that holds point b on a line through point a (a
    /// slider), the line's unit direction at q; `None` for the others.
    fn line_direction(&self, _q: &[f64]) -> Option<Vector2<f64>> {
        None
    }
    /// ∂C/∂q (local) into the first `rows` rows of `out`.
    fn jacobian(&self, q: &[f64], out: &mut ConstraintJac);
    /// Adds Σᵢ λᵢ ∂²Cᵢ/∂q² (local) into `out`.
    fn hessian_dot(&self, q: &[f64], lambda: &[f64], out: &mut PairHess);
}

/// Revolute joint.
#[derive(Debug, Clone)]
pub struct Pin {
    pub label: String,
    pub pair: Pair,
}

impl Constraint for Pin {
    fn rigid(&self) -> bool {
        false
    }
    fn label(&self) -> &str {
        &self.label
    }
    fn pair(&self) -> &Pair {
        &self.pair
    }
    fn rows(&self) -> usize {
        2
    }
    fn row_is_angle(&self, _row: usize) -> bool {
        false
    }
    fn vector_rows(&self) -> Option<usize> {
        Some(0)
    }
    fn residual(&self, q: &[f64], out: &mut [f64]) {
        let d = self.pair.separation(q);
        out[0] = d.x;
        out[1] = d.y;
    }
    fn jacobian(&self, q: &[f64], out: &mut ConstraintJac) {
        let mut j = PairJac2::zeros();
        self.pair.separation_jacobian(q, &mut j);
        out.fixed_rows_mut::<2>(0).copy_from(&j);
    }
    fn hessian_dot(&self, q: &[f64], lambda: &[f64], out: &mut PairHess) {
        self.pair
            .separation_hessian_dot(q, Vector2::new(lambda[0], lambda[1]), out);
    }
}

impl Pin {
    /// The force the pin exerts on its point b [SI: N] at its multipliers
    /// λ (its whole reaction: that force, and its opposite on a).
    pub fn point_reaction(&self, lambda: &[f64]) -> Vector2<f64> {
        -Vector2::new(lambda[0], lambda[1])
    }
}

/// Rigid connection.
#[derive(Debug, Clone)]
pub struct Weld {
    pub label: String,
    pub pair: Pair,
    /// Initial θ_b − θ_a [rad].
    pub offset: f64,
}

impl Constraint for Weld {
    fn rigid(&self) -> bool {
        true
    }
    fn label(&self) -> &str {
        &self.label
    }
    fn pair(&self) -> &Pair {
        &self.pair
    }
    fn rows(&self) -> usize {
        3
    }
    fn row_is_angle(&self, row: usize) -> bool {
        row == 2
    }
    fn vector_rows(&self) -> Option<usize> {
        Some(0)
    }
    fn residual(&self, q: &[f64], out: &mut [f64]) {
        let d = self.pair.separation(q);
        out[0] = d.x;
        out[1] = d.y;
        out[2] = self.pair.relative_angle(q, self.offset);
    }
    fn jacobian(&self, q: &[f64], out: &mut ConstraintJac) {
        let mut j = PairJac2::zeros();
        self.pair.separation_jacobian(q, &mut j);
        out.fixed_rows_mut::<2>(0).copy_from(&j);
        let mut g = PairGrad::zeros();
        self.pair.relative_angle_derivatives(q, &mut g, None);
        out.row_mut(2).copy_from(&g.transpose());
    }
    fn hessian_dot(&self, q: &[f64], lambda: &[f64], out: &mut PairHess) {
        self.pair
            .separation_hessian_dot(q, Vector2::new(lambda[0], lambda[1]), out);
        let (mut g, mut h) = (PairGrad::zeros(), PairHess::zeros());
        self.pair
            .relative_angle_derivatives(q, &mut g, Some(&mut h));
        *out += h * lambda[2];
    }
}

/// Point b on a line through a, turning with a.
#[derive(Debug, Clone)]
pub struct Slider {
    pub label: String,
    pub pair: Pair,
    /// Unit normal of the axis at the initial configuration (global).
    pub normal0: Vector2<f64>,
    /// Initial angle of anchor a [rad].
    pub angle0: f64,
}

impl Slider {
    /// The axis normal, turned with anchor a since the reference.
    pub fn normal(&self, q: &[f64]) -> Vector2<f64> {
        let phi = self.pair.a.angle(q) - self.angle0;
        let (s, c) = phi.sin_cos();
        Vector2::new(
            c * self.normal0.x - s * self.normal0.y,
            s * self.normal0.x + c * self.normal0.y,
        )
    }
}

impl Constraint for Slider {
    fn rigid(&self) -> bool {
        false
    }
    fn line_direction(&self, q: &[f64]) -> Option<Vector2<f64>> {
        // The normal turned back by a quarter turn.
        let n = self.normal(q);
        Some(Vector2::new(n.y, -n.x))
    }
    fn label(&self) -> &str {
        &self.label
    }
    fn pair(&self) -> &Pair {
        &self.pair
    }
    fn rows(&self) -> usize {
        1
    }
    fn row_is_angle(&self, _row: usize) -> bool {
        false
    }
    fn vector_rows(&self) -> Option<usize> {
        None
    }
    fn residual(&self, q: &[f64], out: &mut [f64]) {
        out[0] = self.normal(q).dot(&self.pair.separation(q));
    }
    fn jacobian(&self, q: &[f64], out: &mut ConstraintJac) {
        let n = self.normal(q);
        let d = self.pair.separation(q);
        let mut j = PairJac2::zeros();
        self.pair.separation_jacobian(q, &mut j);
        let mut g = PairGrad::zeros();
        self.pair.angle_a_gradient(q, &mut g);
        let row = j.transpose() * n + g * perp(n).dot(&d);
        out.row_mut(0).copy_from(&row.transpose());
    }
    fn hessian_dot(&self, q: &[f64], lambda: &[f64], out: &mut PairHess) {
        let l = lambda[0];
        let n = self.normal(q);
        let np = perp(n);
        let d = self.pair.separation(q);
        let mut j = PairJac2::zeros();
        self.pair.separation_jacobian(q, &mut j);
        let (mut g, mut h) = (PairGrad::zeros(), PairHess::zeros());
        self.pair.angle_a_derivatives(q, &mut g, &mut h);
        let jn = j.transpose() * np;
        *out += (g * g.transpose() * (-n.dot(&d))
            + h * np.dot(&d)
            + g * jn.transpose()
            + jn * g.transpose())
            * l;
        self.pair.separation_hessian_dot(q, n * l, out);
    }
}

impl Slider {
    /// The force the slider exerts on its point b [SI: N] at (q, λ) (its
    /// whole reaction: that force, and its opposite on a).
    pub fn point_reaction(&self, q: &[f64], lambda: &[f64]) -> Vector2<f64> {
        -self.normal(q) * lambda[0]
    }
}
