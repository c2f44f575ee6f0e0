//! Material points of the assembly ("anchors") and their kinematics.
//!
//! An anchor maps the global coordinates q to a position r(q) [SI: m] and,
//! where the body has one, an orientation angle θ(q) [rad]:
//! - beam point at ξ of an element: r = S(ξ) e, θ = atan2(r'_y, r'_x);
//! - rigid body point: r = x + R(θ) u, angle θ;
//! - point mass: r = x (no angle);
//! - ground: constant.
//!
//! Joints, springs and loads are built from these primitives. Each anchor
//! touches at most [`MAX_ANCHOR_DOFS`] coordinates; its derivatives are
//! written into fixed-size local buffers that the system scatters.

use crate::mechanics::element::{shape, ShapeValues};
use nalgebra::{SMatrix, SVector, Vector2};

/// Most coordinates one anchor depends on (an ANCF element).
pub const MAX_ANCHOR_DOFS: usize = 8;

/// Local Jacobian of a position (2 × up to 8).
pub type PosJac = SMatrix<f64, 2, MAX_ANCHOR_DOFS>;
/// Local gradient (up to 8).
pub type Grad = SVector<f64, MAX_ANCHOR_DOFS>;
/// Local Hessian (up to 8 × 8).
pub type Hess = SMatrix<f64, MAX_ANCHOR_DOFS, MAX_ANCHOR_DOFS>;

/// A resolved material point.
#[derive(Debug, Clone)]
pub enum Anchor {
    Ground {
        position: Vector2<f64>,
    },
    /// Point at `xi` of the element whose 8 coordinates are `dofs`.
    Beam {
        dofs: [usize; 8],
        shape: ShapeValues,
    },
    /// Point `local` of the rigid body with coordinates `dofs` = [x, y, θ].
    Rigid {
        dofs: [usize; 3],
        local: Vector2<f64>,
    },
    /// Point mass with coordinates `dofs` = [x, y].
    PointMass {
        dofs: [usize; 2],
    },
}

#[inline]
fn rot(theta: f64, v: Vector2<f64>) -> Vector2<f64> {
    let (s, c) = theta.sin_cos();
    Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// Counter-clockwise rotation by 90°.
#[inline]
pub fn perp(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v.y, v.x)
}

impl Anchor {
    /// A point of a beam element of length `le` at ξ = `xi`.
    pub fn beam(dofs: [usize; 8], le: f64, xi: f64) -> Anchor {
        Anchor::Beam {
            dofs,
            shape: shape(le, xi),
        }
    }

    /// Global coordinates this anchor depends on, in local order.
    pub fn dofs(&self) -> &[usize] {
        match self {
            Anchor::Ground { .. } => &[],
            Anchor::Beam { dofs, .. } => dofs,
            Anchor::Rigid { dofs, .. } => dofs,
            Anchor::PointMass { dofs } => dofs,
        }
    }

    /// Number of local coordinates.
    pub fn ndof(&self) -> usize {
        match self {
            Anchor::Ground { .. } => 0,
            Anchor::Beam { .. } => 8,
            Anchor::Rigid { .. } => 3,
            Anchor::PointMass { .. } => 2,
        }
    }

    /// Whether the anchor has an orientation.
    pub fn has_angle(&self) -> bool {
        !matches!(self, Anchor::PointMass { .. })
    }

    /// Position r(q).
    pub fn position(&self, q: &[f64]) -> Vector2<f64> {
        match self {
            Anchor::Ground { position } => *position,
            Anchor::Beam { dofs, shape } => combine(q, dofs, &shape.s.into()),
            Anchor::Rigid { dofs, local } => {
                Vector2::new(q[dofs[0]], q[dofs[1]]) + rot(q[dofs[2]], *local)
            }
            Anchor::PointMass { dofs } => Vector2::new(q[dofs[0]], q[dofs[1]]),
        }
    }

    /// Velocity ṙ = (∂r/∂q) q̇.
    pub fn velocity(&self, q: &[f64], qd: &[f64]) -> Vector2<f64> {
        // A beam point moves with its shape functions: the Jacobian's
        // product below without its zero half (the same sums, same bits).
        if let Anchor::Beam { dofs, shape } = self {
            return combine(qd, dofs, &shape.s.into());
        }
        let mut jac = PosJac::zeros();
        self.position_jacobian(q, &mut jac);
        let mut v = Vector2::zeros();
        for (k, &d) in self.dofs().iter().enumerate() {
            v += jac.column(k) * qd[d];
        }
        v
    }

    /// Acceleration r̈ = (∂r/∂q) q̈ + (d/dt ∂r/∂q) q̇ (the second term is the
    /// centripetal part of a rigid-body point).
    pub fn acceleration(&self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Vector2<f64> {
        let mut r = self.velocity(q, qdd);
        if let Anchor::Rigid { dofs, local } = self {
            r -= rot(q[dofs[2]], *local) * qd[dofs[2]].powi(2);
        }
        r
    }

    /// ∂r/∂q into the first `ndof` columns of `out` (others untouched).
    pub fn position_jacobian(&self, q: &[f64], out: &mut PosJac) {
        match self {
            Anchor::Ground { .. } => {}
            Anchor::Beam { shape, .. } => {
                for i in 0..4 {
                    out[(0, 2 * i)] = shape.s[i];
                    out[(1, 2 * i)] = 0.0;
                    out[(0, 2 * i + 1)] = 0.0;
                    out[(1, 2 * i + 1)] = shape.s[i];
                }
            }
            Anchor::Rigid { dofs, local } => {
                let d = perp(rot(q[dofs[2]], *local));
                out.fixed_view_mut::<2, 3>(0, 0)
                    .copy_from(&SMatrix::<f64, 2, 3>::new(1.0, 0.0, d.x, 0.0, 1.0, d.y));
            }
            Anchor::PointMass { .. } => {
                out.fixed_view_mut::<2, 2>(0, 0)
                    .copy_from(&SMatrix::<f64, 2, 2>::identity());
            }
        }
    }

    /// Adds Σᵢ wᵢ ∂²rᵢ/∂q² into `out` (non-zero only for rigid bodies).
    pub fn position_hessian_dot(&self, q: &[f64], w: Vector2<f64>, out: &mut Hess) {
        if let Anchor::Rigid { dofs, local } = self {
            out[(2, 2)] -= w.dot(&rot(q[dofs[2]], *local));
        }
    }

    /// Slope r' of a beam point (d r / d x).
    fn slope(q: &[f64], dofs: &[usize; 8], shape: &ShapeValues) -> Vector2<f64> {
        combine(q, dofs, &shape.d1.into())
    }

    /// Orientation angle θ(q) [rad]; beams give atan2 of the slope, in (−π, π].
    /// Point masses have none (validation keeps them out of angle uses).
    pub fn angle(&self, q: &[f64]) -> f64 {
        match self {
            Anchor::Ground { .. } => 0.0,
            Anchor::Beam { dofs, shape } => {
                let r1 = Self::slope(q, dofs, shape);
                r1.y.atan2(r1.x)
            }
            Anchor::Rigid { dofs, .. } => q[dofs[2]],
            Anchor::PointMass { .. } => unreachable!("a point mass has no orientation"),
        }
    }

    /// ∂θ/∂q into `grad` and, if given, ∂²θ/∂q² into `hess` (both overwritten
    /// in the first `ndof` entries).
    pub fn angle_derivatives(&self, q: &[f64], grad: &mut Grad, hess: Option<&mut Hess>) {
        match self {
            Anchor::Ground { .. } | Anchor::PointMass { .. } => {}
            Anchor::Rigid { .. } => {
                grad.fixed_rows_mut::<3>(0)
                    .copy_from(&nalgebra::Vector3::new(0.0, 0.0, 1.0));
                if let Some(h) = hess {
                    h.fixed_view_mut::<3, 3>(0, 0).fill(0.0);
                }
            }
            Anchor::Beam { dofs, shape } => {
                let r1 = Self::slope(q, dofs, shape);
                let g = r1.norm_squared();
                let dtheta = perp(r1) / g; // (−r'_y, r'_x)/|r'|²
                for i in 0..4 {
                    grad[2 * i] = shape.d1[i] * dtheta.x;
                    grad[2 * i + 1] = shape.d1[i] * dtheta.y;
                }
                if let Some(h) = hess {
                    let (x, y) = (r1.x, r1.y);
                    let g2 = g * g;
                    let hxx = 2.0 * x * y / g2;
                    let hxy = (y * y - x * x) / g2;
                    let hr = nalgebra::Matrix2::new(hxx, hxy, hxy, -hxx);
                    for i in 0..4 {
                        for j in 0..4 {
                            let blk = hr * (shape.d1[i] * shape.d1[j]);
                            h.fixed_view_mut::<2, 2>(2 * i, 2 * j).copy_from(&blk);
                        }
                    }
                }
            }
        }
    }
}

#[inline]
fn combine(q: &[f64], dofs: &[usize; 8], c: &[f64; 4]) -> Vector2<f64> {
    let mut r = Vector2::zeros();
    for i in 0..4 {
        r.x += c[i] * q[dofs[2 * i]];
        r.y += c[i] * q[dofs[2 * i + 1]];
    }
    r
}
