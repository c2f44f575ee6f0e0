//! A cable element's state as the precise linearization sees it: its
//! displacement from its straight, stress-free reference.
//!
//! Every beam of a model is straight in its reference: r'₀ = t₀ (a unit
//! tangent) and r''₀ = 0 along it, exactly. Its stored coordinates are not:
//! a node at p₀ + s t₀ is rounded to ε|r| [SI: m], so the stored nodes of a
//! beam that is not along an axis zigzag by that much, and r'' formed from
//! them has a component across the beam of ε|r|/Le² (2.5e-7 /m at 50,000
//! elements of a 1.5 m ruler turned 30°). That is no curvature, but it
//! enters κ, ∂κ/∂r' and ∂²κ/∂r'², and it moved the ruler's frequencies by
//! up to 2.4e-9 against the same ruler along x, past the bounds printed.
//!
//! [`Displaced`] holds the state as t₀ and the displacement u = e − e₀
//! [SI: m, –]. At a quadrature point
//!
//! ```text
//! r' = t₀ + Σᵢ d1ᵢ uᵢ,      r'' = Σᵢ d2ᵢ uᵢ
//! ```
//!
//! (the reference's own terms sum to t₀ and 0 exactly), with the two
//! position terms of each sum taken as one difference. So the reference is
//! exactly straight and stress-free whatever its angle, and a state's r'
//! and r'' carry the round-off of its displacement's terms, not of the
//! nodes' absolute positions. [`super::element::CableElement`]'s precise
//! products and quadratic forms take this state; its forces and assembled
//! tangent (the transient's and the statics' path) take the absolute
//! coordinates.

use super::element::{
    combine_variation, perp_neg, variation_size, BendingPoint, CableElement, CableSection, Vec8,
    AXIAL_POINTS, BENDING_POINTS,
};
use nalgebra::{Vector2, Vector4};

/// An element's state: its straight reference's tangent and its
/// displacement from that reference (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Displaced {
    /// The reference's unit tangent t₀ [–].
    t0: Vector2<f64>,
    /// The displacement u = e − e₀ [SI: m at positions, – at slopes].
    u: Vec8,
}

impl Displaced {
    /// The state `e` of an element whose straight reference is `reference`
    /// (both as `[rA, r'A, rB, r'B]`; the reference's two slopes are its
    /// tangent).
    pub fn new(e: &Vec8, reference: &Vec8) -> Self {
        debug_assert!(
            reference[2] == reference[6] && reference[3] == reference[7],
            "a straight reference has one slope: {reference:?}"
        );
        Displaced {
            t0: Vector2::new(reference[2], reference[3]),
            u: e - reference,
        }
    }

    /// r' at a point with shape derivatives `d1`.
    #[inline]
    fn slope(&self, d1: &Vector4<f64>) -> Vector2<f64> {
        self.t0 + combine_variation(&self.u, d1)
    }

    /// r'' at a point with shape second derivatives `d2`.
    #[inline]
    fn second(&self, d2: &Vector4<f64>) -> Vector2<f64> {
        combine_variation(&self.u, d2)
    }

    /// The sizes of the terms r' (`with_tangent`) or r'' is summed from,
    /// per component: ε times this is its round-off.
    #[inline]
    fn terms_xy(&self, d: &Vector4<f64>, with_tangent: bool) -> Vector2<f64> {
        debug_assert_eq!(d[2], -d[0], "opposite position weights");
        let u = |i: usize| Vector2::new(self.u[2 * i], self.u[2 * i + 1]);
        let base = if with_tangent {
            self.t0.abs()
        } else {
            Vector2::zeros()
        };
        base + (u(0) - u(2)).abs() * d[0].abs() + u(1).abs() * d[1].abs() + u(3).abs() * d[3].abs()
    }

    /// The size of the terms r' is summed from.
    #[inline]
    fn slope_terms(&self, d1: &Vector4<f64>) -> f64 {
        self.t0.norm() + variation_size(&self.u, d1)
    }
}

/// The state at an axial quadrature point: unit tangent and normal of r',
/// ½wEA, the tension factor ½wEA·ε/l and its round-off.
pub(super) struct AxialPoint {
    pub(super) t: Vector2<f64>,
    pub(super) n: Vector2<f64>,
    pub(super) stretch: f64,
    pub(super) tension: f64,
    pub(super) noise: f64,
}

/// The state at a bending quadrature point, ½wEI and its curvature's round-off.
pub(super) struct BendingStatePoint {
    pub(super) point: BendingPoint,
    pub(super) c: f64,
    pub(super) noise: f64,
    /// The size of r''s terms over |r'|: ε times this is r''s relative
    /// round-off.
    pub(super) slope_noise: f64,
}

pub(super) struct StatePoints {
    pub(super) axial: [AxialPoint; AXIAL_POINTS],
    pub(super) bending: [BendingStatePoint; BENDING_POINTS],
}

impl CableElement {
    /// The state's quantities at every quadrature point, shared by the
    /// quadratic forms and the products of the tangent.
    ///
    /// The state's own strain and curvature carry the round-off of the
    /// sums that form r' and r'' (module doc): a tension or curvature of
    /// that size is not a stress, and the forms are uncertain by it times
    /// their second-order terms. The curvature's is taken per component (a
    /// displacement along the beam leaves κ exactly zero); an axial strain
    /// below the round-off of forming r' is snapped to zero, the stress-free
    /// state it stands for, and carries none.
    pub(super) fn state_points(&self, s: &Displaced) -> StatePoints {
        let CableSection { ea, ei, .. } = self.section;
        let axial = std::array::from_fn(|k| {
            let d1 = &self.axial[k].d1;
            let r1 = s.slope(d1);
            let l = r1.norm();
            let size = s.slope_terms(d1);
            let eps = l - 1.0;
            let eps = if eps.abs() <= 4.0 * f64::EPSILON * size {
                0.0
            } else {
                eps
            };
            // The stretch term is axial; the tension term ε/l·|δr'⊥|²
            // acts on transverse motion (a string's stiffness) and
            // counts as bending.
            let stretch = 0.5 * self.axial[k].w * ea;
            let noise = if eps == 0.0 {
                0.0
            } else {
                stretch * f64::EPSILON * size / (l * l)
            };
            AxialPoint {
                t: r1 / l,
                n: perp_neg(r1) / l,
                stretch,
                tension: stretch * eps / l,
                noise,
            }
        });
        let bending = std::array::from_fn(|k| {
            let qp = &self.bending[k];
            let r1 = s.slope(&qp.d1);
            let r2 = snapped_second_derivative(s.second(&qp.d2), variation_size(&s.u, &qp.d2), r1);
            let point = BendingPoint::of(r1, r2);
            let (n1, n2) = (s.terms_xy(&qp.d1, true), s.terms_xy(&qp.d2, false));
            let noise = f64::EPSILON * (point.p.abs().dot(&n1) + point.q.abs().dot(&n2));
            let slope_noise = s.slope_terms(&qp.d1) / r1.norm().max(f64::MIN_POSITIVE);
            BendingStatePoint {
                point,
                c: 0.5 * qp.w * ei,
                noise,
                slope_noise,
            }
        });
        StatePoints { axial, bending }
    }
}

/// r'' with its component along r' snapped to zero when below the
/// round-off of forming it (4 ε times the size of its terms, `size`), as
/// the axial strain is: it is a stretch gradient, which κ sees only
/// through ∂κ/∂r' (r''s round-off along a beam of 100,000 elements moved
/// f₁ by 8e-9). The component across is the curvature, which a small
/// vibration's state has of this size and keeps.
#[inline]
fn snapped_second_derivative(r2: Vector2<f64>, size: f64, r1: Vector2<f64>) -> Vector2<f64> {
    let l = r1.norm();
    if l == 0.0 {
        return r2;
    }
    let tol = 4.0 * f64::EPSILON * size;
    let (t, n) = (r1 / l, Vector2::new(-r1.y, r1.x) / l);
    let (along, across) = (t.dot(&r2), n.dot(&r2));
    let along = if along.abs() <= tol { 0.0 } else { along };
    t * along + n * across
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A straight element at any angle and place, undisplaced: r' is its
    /// tangent and r'' zero, exactly, at every point, so its strain,
    /// curvature and their round-off are zero.
    #[test]
    fn the_reference_is_straight_and_stress_free_at_any_angle() {
        let el = CableElement::new(3e-5, CableSection::rectangle(70e9, 2700.0, 1.5e-3, 0.03));
        for deg in [0.0f64, 17.0, 30.0, 45.0, 133.0] {
            let t = Vector2::new(deg.to_radians().cos(), deg.to_radians().sin());
            let e0 = CableElement::straight(el.le, Vector2::new(-0.3, 0.4) + t * 0.7, t);
            let points = el.state_points(&Displaced::new(&e0, &e0));
            for p in &points.axial {
                assert_eq!((p.tension, p.noise), (0.0, 0.0), "{deg}°");
            }
            for p in &points.bending {
                assert_eq!((p.point.kappa, p.noise), (0.0, 0.0), "{deg}°");
            }
        }
    }
}
