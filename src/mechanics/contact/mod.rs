//! Compliant unilateral contacts between a point P (a pin centre or a
//! rounded point: any anchor) and a segment A–B fixed in a rigid body or
//! in the ground.
//!
//! Geometry, in the global frame at the state q: t = the segment's unit
//! tangent turned with its body, n = perp(t), d = P − A, τ = t·d along
//! the segment, h = n·d its signed distance from the segment's line
//! [SI: m].
//! - pin–slot (clearance c = width/2 − r): over the flat part (0 ≤ τ ≤ L)
//!   δ = |h| − c; beyond an end E (A or B) the cap, δ = |P − E| − c.
//! - point–line (radius r, side s = ±1): δ = r − s·h while 0 ≤ τ ≤ L; no
//!   contact off the segment.
//!
//! The penetration δ(q) [SI: m] comes with its gradient ∇δ and Hessian
//! ∇²δ in the pair's local coordinates (the segment body's, then the
//! point's). The flat part is the slider's n(θ)·(P − A) (see
//! [`crate::mechanics::joint::Slider`]), so the turning normal and the body rotation
//! are in ∇²δ; a cap is a distance between two material points, whose
//! Hessian has the curvature term Jᵀ(I − uuᵀ)J/|P − E|.
//!
//! The elastic force F_e(δ) (see [`law`]) acts as a nonlinear spring with
//! potential U(δ): a [`ForceElement`], so statics, the tangent of a modal
//! analysis about an equilibrium (F_e'∇δ∇δᵀ + F_e∇²δ; inactive contacts
//! drop out) and the energy balance include it like any spring. The
//! dissipative rest (hysteresis damping, friction) depends on the velocity
//! and on the impact speed, a state of the transient, and is added there by
//! [`ContactElement::dissipation`].

pub mod law;

use crate::mechanics::anchor::perp;
use crate::mechanics::anchor::Anchor;
use crate::mechanics::joint::{Constraint, ConstraintJac, Slider};
use crate::mechanics::pair::{Pair, PairGrad, PairHess, PairJac2};
use crate::mechanics::spring::ForceElement;
use law::{NormalForce, NormalLaw};
use nalgebra::{Matrix2, Vector2};

/// Which kind of contact, with its sizes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactKind {
    /// Clearance c = width/2 − pin radius [SI: m].
    PinSlot { clearance: f64 },
    /// Radius [SI: m] and side s = ±1 (+1: left of from→to).
    PointLine { radius: f64, side: f64 },
}

/// The penetration at a state.
#[derive(Debug, Clone, PartialEq)]
pub struct Gap {
    /// δ [SI: m]; > 0 in contact.
    pub delta: f64,
    /// ∂δ/∂q (local).
    pub grad: PairGrad,
    /// Unit direction in which δ grows when P moves (global).
    pub normal: Vector2<f64>,
}

/// The dissipative generalized force of a contact and its Jacobians
/// (local, overwritten).
#[derive(Debug, Clone, Default)]
pub struct Dissipation {
    /// Force on the left-hand side of the equations of motion [SI: N, N m].
    pub force: PairGrad,
    /// ∂force/∂q.
    pub dq: PairHess,
    /// ∂force/∂q̇.
    pub dv: PairHess,
    /// The total normal force F(δ, δ̇) [SI: N].
    pub normal_force: f64,
}

/// A contact, assembled.
#[derive(Debug, Clone)]
pub struct ContactElement {
    pub label: String,
    pub kind: ContactKind,
    /// n(θ)·(P − A), A the body point at `from`: its pair is the contact's.
    line: Slider,
    /// The body point at `to` with P.
    to: Pair,
    /// Unit tangent from→to at the reference (global).
    tangent0: Vector2<f64>,
    /// Segment length [SI: m].
    length: f64,
    pub law: NormalLaw,
    /// (μ, regularization speed [SI: m/s]).
    pub friction: Option<(f64, f64)>,
}

fn rotate(phi: f64, v: Vector2<f64>) -> Vector2<f64> {
    let (s, c) = phi.sin_cos();
    Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

impl ContactElement {
    /// Length of the contact's segment [SI: m].
    pub fn length(&self) -> f64 {
        self.length
    }

    /// A contact between the segment `[from, to]` (anchors of its body, or
    /// of the ground) and the point `point`, at the reference state `q0`.
    pub fn new(
        label: String,
        kind: ContactKind,
        [from, to]: [Anchor; 2],
        point: Anchor,
        law: NormalLaw,
        friction: Option<(f64, f64)>,
        q0: &[f64],
    ) -> ContactElement {
        let (a, b) = (from.position(q0), to.position(q0));
        let length = (b - a).norm();
        let tangent0 = (b - a) / length;
        let angle0 = if from.has_angle() {
            from.angle(q0)
        } else {
            0.0
        };
        let line = Slider {
            label: label.clone(),
            pair: Pair {
                a: from,
                b: point.clone(),
            },
            normal0: perp(tangent0),
            angle0,
        };
        ContactElement {
            label,
            kind,
            line,
            to: Pair { a: to, b: point },
            tangent0,
            length,
            law,
            friction,
        }
    }

    /// The segment's current unit tangent.
    fn tangent(&self, q: &[f64]) -> Vector2<f64> {
        let a = &self.line.pair.a;
        let phi = if a.has_angle() {
            a.angle(q) - self.line.angle0
        } else {
            0.0
        };
        rotate(phi, self.tangent0)
    }

    /// The penetration at q, with ∇²δ added into `hess` if given (it must
    /// be zeroed by the caller); `None` when a point–line contact's point
    /// is off its segment.
    pub fn gap(&self, q: &[f64], hess: Option<&mut PairHess>) -> Option<Gap> {
        let pair = &self.line.pair;
        let d = pair.separation(q);
        let tau = self.tangent(q).dot(&d);
        let on_segment = (0.0..=self.length).contains(&tau);
        let flat = |scale: f64, offset: f64, hess: Option<&mut PairHess>| {
            let n = self.line.normal(q);
            let mut jac = ConstraintJac::zeros();
            self.line.jacobian(q, &mut jac);
            let grad: PairGrad = jac.row(0).transpose() * scale;
            if let Some(h) = hess {
                let mut hh = PairHess::zeros();
                self.line.hessian_dot(q, &[scale], &mut hh);
                *h += hh;
            }
            Gap {
                delta: scale * n.dot(&d) + offset,
                grad,
                normal: n * scale,
            }
        };
        match self.kind {
            ContactKind::PointLine { radius, side } => {
                on_segment.then(|| flat(-side, radius, hess))
            }
            ContactKind::PinSlot { clearance } => {
                if on_segment {
                    let s = if self.line.normal(q).dot(&d) >= 0.0 {
                        1.0
                    } else {
                        -1.0
                    };
                    return Some(flat(s, -clearance, hess));
                }
                let cap = if tau < 0.0 { pair } else { &self.to };
                let e = cap.separation(q);
                let l = e.norm();
                if l == 0.0 {
                    return Some(Gap {
                        delta: -clearance,
                        grad: PairGrad::zeros(),
                        normal: Vector2::zeros(),
                    });
                }
                let u = e / l;
                let mut jac = PairJac2::zeros();
                cap.separation_jacobian(q, &mut jac);
                if let Some(h) = hess {
                    let transverse = Matrix2::identity() - u * u.transpose();
                    *h += jac.transpose() * transverse * jac / l;
                    cap.separation_hessian_dot(q, u, h);
                }
                Some(Gap {
                    delta: l - clearance,
                    grad: jac.transpose() * u,
                    normal: u,
                })
            }
        }
    }

    /// The penetration δ [SI: m] (−∞ off a point–line segment).
    pub fn penetration(&self, q: &[f64]) -> f64 {
        self.gap(q, None).map_or(f64::NEG_INFINITY, |g| g.delta)
    }

    /// The penetration rate δ̇ = ∇δ·q̇ [SI: m/s] (0 when off the segment).
    pub fn rate(&self, q: &[f64], qd: &[f64]) -> f64 {
        self.gap(q, None).map_or(0.0, |g| {
            self.line
                .pair
                .dofs()
                .enumerate()
                .map(|(i, d)| g.grad[i] * qd[d])
                .sum()
        })
    }

    /// An effective mass of the contact direction [SI: kg]:
    /// 1/Σᵢ(∂δ/∂qᵢ)²/Mᵢᵢ over its coordinates (each body alone, joints
    /// ignored): the scale of impact penetrations, for step control.
    pub fn effective_mass(&self, q: &[f64], mass_diagonal: &[f64]) -> f64 {
        let Some(g) = self.gap(q, None) else {
            return f64::INFINITY;
        };
        let mobility: f64 = self
            .line
            .pair
            .dofs()
            .enumerate()
            .filter(|&(_, d)| mass_diagonal[d] > 0.0)
            .map(|(i, d)| g.grad[i] * g.grad[i] / mass_diagonal[d])
            .sum();
        if mobility > 0.0 {
            1.0 / mobility
        } else {
            f64::INFINITY
        }
    }

    /// The dissipative force (hysteresis damping beyond F_e, and friction)
    /// at (q, q̇), `qd` in local coordinates, with the impact speed
    /// `impact` [SI: m/s]; `false` when the contact is open. `impact` is
    /// `None` for a contact closed since the start that has not separated
    /// yet (a pre-stressed contact has had no impact): its normal force is
    /// the elastic F_e alone, so only friction (on F_e) remains.
    pub fn dissipation(
        &self,
        q: &[f64],
        qd: &PairGrad,
        impact: Option<f64>,
        out: &mut Dissipation,
    ) -> bool {
        let mut hess = PairHess::zeros();
        let Some(g) = self.gap(q, Some(&mut hess)) else {
            return false;
        };
        if g.delta <= 0.0 {
            return false;
        }
        let rate = g.grad.dot(qd);
        let (r, total) = match impact {
            Some(w) => (
                self.law.dissipative(g.delta, rate, w),
                self.law.total(g.delta, rate, w),
            ),
            None => (NormalForce::default(), self.law.elastic(g.delta)),
        };
        let outer = g.grad * g.grad.transpose();
        out.force = g.grad * r.force;
        out.dv = outer * r.d_rate;
        out.dq = outer * r.d_delta + hess * r.force + g.grad * (hess * qd).transpose() * r.d_rate;
        out.normal_force = total.force;
        if let Some((mu, vs)) = self.friction {
            if total.force > 0.0 && mu > 0.0 {
                let gt = self.slip_gradient(q, &g);
                let vt = gt.dot(qd);
                let root = (vt * vt + vs * vs).sqrt();
                let phi = vt / root;
                let dphi = vs * vs / (root * root * root);
                out.force += gt * (mu * total.force * phi);
                out.dv += gt * gt.transpose() * (mu * total.force * dphi)
                    + gt * g.grad.transpose() * (mu * phi * total.d_rate);
                out.dq += gt * g.grad.transpose() * (mu * phi * total.d_delta);
            }
        }
        true
    }

    /// ∂v_t/∂q̇: the slip speed of P along the contact's tangent, relative
    /// to the segment body's material point under P,
    /// v_t = t·(J q̇ − θ̇ perp(P − A)).
    fn slip_gradient(&self, q: &[f64], g: &Gap) -> PairGrad {
        let pair = &self.line.pair;
        let t = perp(g.normal);
        let d = pair.separation(q);
        let mut jac = PairJac2::zeros();
        pair.separation_jacobian(q, &mut jac);
        let mut gt: PairGrad = jac.transpose() * t;
        if pair.a.has_angle() {
            let mut ga = PairGrad::zeros();
            pair.angle_a_gradient(q, &mut ga);
            gt -= ga * t.dot(&perp(d));
        }
        gt
    }
}

impl ForceElement for ContactElement {
    fn label(&self) -> &str {
        &self.label
    }
    fn pair(&self) -> &Pair {
        &self.line.pair
    }
    fn energy(&self, q: &[f64]) -> f64 {
        self.law.energy(self.penetration(q))
    }
    fn elastic_force(&self, q: &[f64]) -> f64 {
        self.law.elastic(self.penetration(q)).force
    }
    fn gradient(&self, q: &[f64], out: &mut PairGrad) {
        out.fill(0.0);
        if let Some(g) = self.gap(q, None) {
            *out = g.grad * self.law.elastic(g.delta).force;
        }
    }
    fn hessian(&self, q: &[f64], out: &mut PairHess) {
        out.fill(0.0);
        let mut hess = PairHess::zeros();
        if let Some(g) = self.gap(q, Some(&mut hess)) {
            let f = self.law.elastic(g.delta);
            if f.force > 0.0 || f.d_delta > 0.0 {
                *out = g.grad * g.grad.transpose() * f.d_delta + hess * f.force;
            }
        }
    }
    fn has_damper(&self) -> bool {
        false
    }
    fn damping(&self, _: &[f64], _: &PairGrad, _: &mut PairGrad, _: &mut PairHess) -> bool {
        false
    }
}

/// Which contacts the regularizing stiffness of a static Newton matrix
/// ([`ContactElement::regularization`]) is added for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Regularize {
    /// Open contacts, and closed ones whose tangent is below it.
    OpenAndBarelyClosed,
    /// Open contacts only.
    OpenOnly,
    /// Open contacts within their own size of touching only. An open
    /// contact farther away adds, regularized, a stiffness along its normal
    /// that can swamp a soft structure's own (a pendulum's 19 N/m against
    /// 4.7e5 N/m, the stop 190 mm away), and Newton stalls; nothing settles
    /// onto it in one Newton step, and where the structure holds itself
    /// the exact tangent is regular.
    NearOnly,
}

impl ContactElement {
    /// The regularizing stiffness of static Newton iterations [SI: N/m]:
    /// the law's tangent at a penetration of 1e-3 of the contact's own
    /// size (the clearance of a slot, the radius of a point, or 1 µm).
    pub fn regularizing_stiffness(&self) -> f64 {
        self.law.elastic(1e-3 * self.size()).d_delta
    }

    /// The contact's own size [SI: m]: the clearance of a slot, the radius
    /// of a point, or 1 µm.
    fn size(&self) -> f64 {
        let size = match self.kind {
            ContactKind::PinSlot { clearance } => clearance,
            ContactKind::PointLine { radius, .. } => radius,
        };
        if size > 0.0 {
            size
        } else {
            1e-6
        }
    }

    /// Adds (k_r − F_e')⁺ ∇δ∇δᵀ, k_r the regularizing stiffness, into
    /// `out` (local): a Newton matrix that stays regular while the contact
    /// is open or barely closed (F_e' = nKδⁿ⁻¹ → 0 as δ → 0). Only the
    /// iteration matrix of statics gets it, never the residual, so the
    /// equilibrium found is exact; but where the equilibrium itself is
    /// barely closed (a stiff law at a small force: K = 1e11 N/m^1.5 at
    /// 1.5 N is δ = 6e-8 m against the regularizing 5e-7 m of a 0.5 mm pad)
    /// the matrix is off by up to k_r/F_e' and Newton's method converges
    /// only linearly, so [`Regularize::OpenOnly`] leaves a closed contact
    /// its exact tangent.
    pub fn regularization(&self, q: &[f64], which: Regularize, out: &mut PairHess) -> bool {
        let Some(g) = self.gap(q, None) else {
            return false;
        };
        let extra = self.regularizing_stiffness() - self.law.elastic(g.delta).d_delta;
        if !self.regularized_at(g.delta, extra, which) {
            return false;
        }
        *out = g.grad * g.grad.transpose() * extra;
        true
    }

    /// Whether the regularizations `a` and `b` give this contact the same
    /// stiffness at q (both none, or both the same (k_r − F_e')⁺): a static
    /// Newton matrix is then the same under either.
    pub fn regularized_alike(&self, q: &[f64], a: Regularize, b: Regularize) -> bool {
        let Some(g) = self.gap(q, None) else {
            return true;
        };
        let extra = self.regularizing_stiffness() - self.law.elastic(g.delta).d_delta;
        self.regularized_at(g.delta, extra, a) == self.regularized_at(g.delta, extra, b)
    }

    /// Whether `which` regularizes the contact at penetration `delta`, where
    /// the regularization would add `extra` [SI: N/m].
    fn regularized_at(&self, delta: f64, extra: f64, which: Regularize) -> bool {
        let excluded = match which {
            Regularize::NearOnly => delta > 0.0 || -delta > self.size(),
            Regularize::OpenOnly => delta > 0.0,
            Regularize::OpenAndBarelyClosed => false,
        };
        !excluded && extra > 0.0
    }
}
