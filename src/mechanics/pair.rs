//! Relative kinematics of two anchors: the building block of joints and
//! springs. Local coordinates are a's followed by b's (at most 16); results
//! go into fixed-size buffers that the caller scatters with [`Pair::dofs`].

use crate::mechanics::anchor::{Anchor, Grad, Hess, PosJac, MAX_ANCHOR_DOFS};
use nalgebra::{SMatrix, SVector, Vector2};

/// Most local coordinates of a pair.
pub const MAX_PAIR_DOFS: usize = 2 * MAX_ANCHOR_DOFS;
pub type PairGrad = SVector<f64, MAX_PAIR_DOFS>;
pub type PairHess = SMatrix<f64, MAX_PAIR_DOFS, MAX_PAIR_DOFS>;
pub type PairJac2 = SMatrix<f64, 2, MAX_PAIR_DOFS>;

/// Two anchors, a and b.
#[derive(Debug, Clone)]
pub struct Pair {
    pub a: Anchor,
    pub b: Anchor,
}

/// Wrap an angle to (−π, π].
pub fn wrap_angle(x: f64) -> f64 {
    x.sin().atan2(x.cos())
}

impl Pair {
    /// Global indices of the local coordinates (a's, then b's).
    pub fn dofs(&self) -> impl Iterator<Item = usize> + '_ {
        self.a.dofs().iter().chain(self.b.dofs()).copied()
    }

    /// Number of local coordinates.
    pub fn ndof(&self) -> usize {
        self.a.ndof() + self.b.ndof()
    }

    /// r_b − r_a.
    pub fn separation(&self, q: &[f64]) -> Vector2<f64> {
        self.b.position(q) - self.a.position(q)
    }

    /// d(r_b − r_a)/dq (local), columns past `ndof` are zero.
    pub fn separation_jacobian(&self, q: &[f64], out: &mut PairJac2) {
        out.fill(0.0);
        let (na, nb) = (self.a.ndof(), self.b.ndof());
        let mut ja = PosJac::zeros();
        let mut jb = PosJac::zeros();
        self.a.position_jacobian(q, &mut ja);
        self.b.position_jacobian(q, &mut jb);
        for k in 0..na {
            out.set_column(k, &(-ja.column(k)));
        }
        for k in 0..nb {
            out.set_column(na + k, &jb.column(k));
        }
    }

    /// Adds wᵀ ∂²(r_b − r_a)/∂q² into `out`.
    pub fn separation_hessian_dot(&self, q: &[f64], w: Vector2<f64>, out: &mut PairHess) {
        let na = self.a.ndof();
        let mut h = Hess::zeros();
        self.a.position_hessian_dot(q, -w, &mut h);
        add_block(out, &h, 0, na);
        h.fill(0.0);
        self.b.position_hessian_dot(q, w, &mut h);
        add_block(out, &h, na, self.b.ndof());
    }

    /// θ_b − θ_a − offset, wrapped to (−π, π].
    pub fn relative_angle(&self, q: &[f64], offset: f64) -> f64 {
        wrap_angle(self.b.angle(q) - self.a.angle(q) - offset)
    }

    /// Gradient and (optionally) Hessian of θ_b − θ_a (local, overwritten).
    pub fn relative_angle_derivatives(
        &self,
        q: &[f64],
        grad: &mut PairGrad,
        hess: Option<&mut PairHess>,
    ) {
        grad.fill(0.0);
        let (na, nb) = (self.a.ndof(), self.b.ndof());
        let (mut ga, mut gb) = (Grad::zeros(), Grad::zeros());
        match hess {
            Some(h) => {
                h.fill(0.0);
                let (mut ha, mut hb) = (Hess::zeros(), Hess::zeros());
                self.a.angle_derivatives(q, &mut ga, Some(&mut ha));
                self.b.angle_derivatives(q, &mut gb, Some(&mut hb));
                add_block(h, &(-ha), 0, na);
                add_block(h, &hb, na, nb);
            }
            None => {
                self.a.angle_derivatives(q, &mut ga, None);
                self.b.angle_derivatives(q, &mut gb, None);
            }
        }
        for k in 0..na {
            grad[k] = -ga[k];
        }
        for k in 0..nb {
            grad[na + k] = gb[k];
        }
    }

    /// Gradient and Hessian of the anchor a's angle alone, in the pair's
    /// local layout.
    pub fn angle_a_derivatives(&self, q: &[f64], grad: &mut PairGrad, hess: &mut PairHess) {
        let na = self.a.ndof();
        let (mut ga, mut ha) = (Grad::zeros(), Hess::zeros());
        self.a.angle_derivatives(q, &mut ga, Some(&mut ha));
        grad.fill(0.0);
        hess.fill(0.0);
        grad.rows_mut(0, na).copy_from(&ga.rows(0, na));
        add_block(hess, &ha, 0, na);
    }

    /// Gradient of the anchor a's angle alone, in the pair's local layout
    /// (the Hessian's 16 × 16 left out: Jacobians need only this).
    pub fn angle_a_gradient(&self, q: &[f64], grad: &mut PairGrad) {
        let na = self.a.ndof();
        let mut ga = Grad::zeros();
        self.a.angle_derivatives(q, &mut ga, None);
        grad.fill(0.0);
        grad.rows_mut(0, na).copy_from(&ga.rows(0, na));
    }
}

fn add_block(out: &mut PairHess, h: &Hess, at: usize, n: usize) {
    let mut dst = out.view_mut((at, at), (n, n));
    dst += h.view((0, 0), (n, n));
}
