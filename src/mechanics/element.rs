//! The planar ANCF cable element (gradient-deficient Euler–Bernoulli beam).
//!
//! Element coordinates `e = [rA, r'A, rB, r'B]` (8 values [SI: m, –]):
//! positions and slopes ∂r/∂x of its two nodes, x the reference arc length.
//! The position field is `r(x) = Σ Sᵢ(ξ) eᵢ`, ξ = x/Le, with the Hermite cubics
//! S1 = 1−3ξ²+2ξ³, S2 = Le(ξ−2ξ²+ξ³), S3 = 3ξ²−2ξ³, S4 = Le(ξ³−ξ²).
//!
//! Elastic energy (Gerstmayr & Irschik 2008):
//! `U = ½∫(EA ε² + EI κ²) dx`, ε = |r'| − 1, κ = (r' × r'')/|r'|².
//! [`CableElement::elastic_force_into`] returns `Q_s = ∂U/∂e`
//! ([`super::cable_force`]) and
//! [`CableElement::tangent_into`] its exact derivative `K = ∂Q_s/∂e`.
//! The mass matrix `ρA Le ∫ SᵀS dξ` is constant.
//!
//! Quadrature: 5 Gauss points for the axial part (exact for the linear part,
//! whose integrand is of degree 4) and 3 for bending (degree 2).

use super::cable_force::ForceTables;
use super::element_state::Displaced;
use crate::model::{Material, Section};
use nalgebra::{Matrix2, Matrix4, SMatrix, SVector, Vector2, Vector4};

/// 8×8 element matrix.
pub type Mat8 = SMatrix<f64, 8, 8>;
/// Element coordinate vector.
pub type Vec8 = SVector<f64, 8>;

/// Section properties of a cable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CableSection {
    /// Axial stiffness EA [SI: N].
    pub ea: f64,
    /// Bending stiffness EI [SI: N m²].
    pub ei: f64,
    /// Mass per length ρA [SI: kg/m].
    pub rho_a: f64,
}

impl CableSection {
    /// The model's rectangular `section` in `material` (the properties of
    /// [`Section`]).
    pub fn of(section: &Section, material: &Material) -> Self {
        CableSection {
            ea: section.axial_stiffness(material.young),
            ei: section.bending_stiffness(material.young),
            rho_a: section.mass_per_length(material.density),
        }
    }

    /// Rectangular section of height `h` (bending plane) and width `w`
    /// [SI: m], Young's modulus `young` [SI: Pa], density `density` [SI:
    /// kg/m³].
    pub fn rectangle(young: f64, density: f64, h: f64, w: f64) -> Self {
        let material = Material {
            young,
            density,
            poisson: None,
        };
        CableSection::of(
            &Section {
                height: h,
                width: w,
            },
            &material,
        )
    }
}

/// Hermite shape functions at ξ: values, d/dx and d²/dx² (x = ξ Le).
#[derive(Debug, Clone, Copy)]
pub struct ShapeValues {
    pub s: Vector4<f64>,
    pub d1: Vector4<f64>,
    pub d2: Vector4<f64>,
}

/// Evaluate the shape functions of an element of length `le` at `xi`.
pub fn shape(le: f64, xi: f64) -> ShapeValues {
    let (x2, x3) = (xi * xi, xi * xi * xi);
    let s = Vector4::new(
        1.0 - 3.0 * x2 + 2.0 * x3,
        le * (xi - 2.0 * x2 + x3),
        3.0 * x2 - 2.0 * x3,
        le * (x3 - x2),
    );
    let d1 = Vector4::new(
        (-6.0 * xi + 6.0 * x2) / le,
        1.0 - 4.0 * xi + 3.0 * x2,
        (6.0 * xi - 6.0 * x2) / le,
        3.0 * x2 - 2.0 * xi,
    );
    let d2 = Vector4::new(
        (-6.0 + 12.0 * xi) / (le * le),
        (-4.0 + 6.0 * xi) / le,
        (6.0 - 12.0 * xi) / (le * le),
        (6.0 * xi - 2.0) / le,
    );
    ShapeValues { s, d1, d2 }
}

/// Gauss–Legendre points and weights on [0, 1].
pub fn gauss01(n: usize) -> Vec<(f64, f64)> {
    let (x, w): (&[f64], &[f64]) = match n {
        1 => (&[0.0], &[2.0]),
        2 => (&[-0.5773502691896257, 0.5773502691896257], &[1.0, 1.0]),
        3 => (
            &[-0.7745966692414834, 0.0, 0.7745966692414834],
            &[5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0],
        ),
        4 => (
            &[
                -0.8611363115940526,
                -0.3399810435848563,
                0.3399810435848563,
                0.8611363115940526,
            ],
            &[
                0.3478548451374538,
                0.6521451548625461,
                0.6521451548625461,
                0.3478548451374538,
            ],
        ),
        5 => (
            &[
                -0.906179845938664,
                -0.5384693101056831,
                0.0,
                0.5384693101056831,
                0.906179845938664,
            ],
            &[
                0.23692688505618908,
                0.47862867049936647,
                0.5688888888888889,
                0.47862867049936647,
                0.23692688505618908,
            ],
        ),
        _ => panic!("Gauss rule with {n} points is not tabulated"),
    };
    x.iter()
        .zip(w)
        .map(|(x, w)| (0.5 * (x + 1.0), 0.5 * w))
        .collect()
}

/// Shape derivatives at one quadrature point, weight already times Le.
#[derive(Debug, Clone, Copy)]
pub(super) struct QuadPoint {
    pub(super) w: f64,
    pub(super) d1: Vector4<f64>,
    pub(super) d2: Vector4<f64>,
}

pub(super) const AXIAL_POINTS: usize = 5;
pub(super) const BENDING_POINTS: usize = 3;

/// One cable element: length, section and its precomputed quadrature data.
#[derive(Debug, Clone)]
pub struct CableElement {
    /// Reference length [SI: m].
    pub le: f64,
    pub section: CableSection,
    pub(super) axial: [QuadPoint; AXIAL_POINTS],
    pub(super) bending: [QuadPoint; BENDING_POINTS],
    /// ρA Le ∫ SᵢSⱼ dξ over the four shape functions [SI: kg, kg m, kg m²];
    /// the element mass matrix is this times I₂.
    mass4: Matrix4<f64>,
    /// The quadrature points' shape derivatives by shape function.
    pub(super) tables: ForceTables,
}

/// Strain energy of an element split by kind [SI: J].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnergySplit {
    pub axial: f64,
    pub bending: f64,
    /// Quadratic forms only: an estimate of the form's round-off [SI: J].
    /// The strain variations cancel nodal terms of size Σᵢ|d1ᵢ||δnodeᵢ|
    /// (and the same with d2), so they carry an error ε times that, and the
    /// form ε² times the energy those sizes would give; the stress terms
    /// (tension, curvature) carry ε of their magnitude.
    pub roundoff: f64,
}

#[inline]
fn node(e: &Vec8, i: usize) -> Vector2<f64> {
    Vector2::new(e[2 * i], e[2 * i + 1])
}

#[inline]
fn combine(e: &Vec8, c: &Vector4<f64>) -> Vector2<f64> {
    node(e, 0) * c[0] + node(e, 1) * c[1] + node(e, 2) * c[2] + node(e, 3) * c[3]
}

/// [`combine`] of a variation, with the two position terms taken as one
/// difference when their weights are opposite (they are, exactly, for
/// d/dx and d²/dx² of the Hermite cubics): c₀(δr_A − δr_B) carries the
/// round-off of the difference, not of the two nodal terms of size
/// |c₀||δr| that cancel to it (on a 1e-5 m element, 1e10 times less for
/// the curvature of a smooth mode).
#[inline]
pub(super) fn combine_variation(de: &Vec8, c: &Vector4<f64>) -> Vector2<f64> {
    if c[2] == -c[0] {
        (node(de, 0) - node(de, 2)) * c[0] + node(de, 1) * c[1] + node(de, 3) * c[3]
    } else {
        combine(de, c)
    }
}

/// Σᵢ |cᵢ| |nodeᵢ|: the size of the nodal terms a combination cancels.
#[inline]
fn nodal_size(de: &Vec8, c: &Vector4<f64>) -> f64 {
    (0..4).map(|i| c[i].abs() * node(de, i).norm()).sum()
}

/// The sum of the sizes of the terms [`combine_variation`] adds: its
/// round-off is ε times this.
#[inline]
pub(super) fn variation_size(de: &Vec8, c: &Vector4<f64>) -> f64 {
    if c[2] == -c[0] {
        c[0].abs() * (node(de, 0) - node(de, 2)).norm()
            + c[1].abs() * node(de, 1).norm()
            + c[3].abs() * node(de, 3).norm()
    } else {
        (0..4).map(|i| c[i].abs() * node(de, i).norm()).sum()
    }
}

/// The slope r' at an axial quadrature point, its length l and the axial
/// strain l − 1, snapped to zero when it is below the round-off of forming
/// r' from the nodal values (4 ε Σᵢ |d1ᵢ| |nodeᵢ|, relative to l).
///
/// A stress-free straight element gives l = 1 ± a few ε; that ε-sized strain
/// is a tension of ε·EA, which on a cable of h/L = 1e-5 is 3e-5 of its
/// bending stiffness EI/L² and showed up as a 2e-5 error of f₁ (and as a
/// stiffness of the rigid rotation of a 2,000-element beam).
#[inline]
fn axial_strain(e: &Vec8, d1: &Vector4<f64>) -> (Vector2<f64>, f64, f64) {
    let r1 = combine(e, d1);
    let l = r1.norm();
    let size: f64 = (0..4).map(|i| d1[i].abs() * node(e, i).norm()).sum();
    let eps = l - 1.0;
    let eps = if eps.abs() <= 4.0 * f64::EPSILON * size {
        0.0
    } else {
        eps
    };
    (r1, l, eps)
}

/// out[node i] += c[i] g, the two position terms as ± one product when
/// their weights are opposite (the force pair of a difference).
#[inline]
fn add_spread(out: &mut Vec8, c: &Vector4<f64>, g: Vector2<f64>) {
    let f0 = g * c[0];
    let f2 = if c[2] == -c[0] { -f0 } else { g * c[2] };
    for (i, f) in [(0, f0), (1, g * c[1]), (2, f2), (3, g * c[3])] {
        out[2 * i] += f.x;
        out[2 * i + 1] += f.y;
    }
}

/// `J a` with J = [[0, 1], [−1, 0]], so that `bᵀ J a = b × a`… written out:
/// returns [a_y, −a_x]; r' × r'' = r'ᵀ [r''_y, −r''_x].
#[inline]
pub(super) fn perp_neg(a: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(a.y, -a.x)
}

impl CableElement {
    pub fn new(le: f64, section: CableSection) -> Self {
        let make = |(xi, w): (f64, f64)| {
            let sv = shape(le, xi);
            QuadPoint {
                w: w * le,
                d1: sv.d1,
                d2: sv.d2,
            }
        };
        let ax = gauss01(AXIAL_POINTS);
        let bd = gauss01(BENDING_POINTS);
        let mut mass4 = Matrix4::zeros();
        for (xi, w) in gauss01(4) {
            let s = shape(le, xi).s;
            mass4 += s * s.transpose() * (section.rho_a * le * w);
        }
        let axial: [QuadPoint; AXIAL_POINTS] = std::array::from_fn(|i| make(ax[i]));
        let bending: [QuadPoint; BENDING_POINTS] = std::array::from_fn(|i| make(bd[i]));
        let tables = ForceTables {
            axial_d1: std::array::from_fn(|i| axial.map(|qp| qp.d1[i])),
            bending_d1: std::array::from_fn(|i| bending.map(|qp| qp.d1[i])),
            bending_d2: std::array::from_fn(|i| bending.map(|qp| qp.d2[i])),
        };
        CableElement {
            le,
            section,
            axial,
            bending,
            mass4,
            tables,
        }
    }

    /// Reference coordinates of a straight element from `p0` along unit tangent `t`.
    pub fn straight(le: f64, p0: Vector2<f64>, t: Vector2<f64>) -> Vec8 {
        let p1 = p0 + t * le;
        Vec8::from_column_slice(&[p0.x, p0.y, t.x, t.y, p1.x, p1.y, t.x, t.y])
    }

    /// Consistent mass matrix `ρA Le ∫ SᵀS dξ` (each 4×4 entry times I₂).
    pub fn mass(&self) -> Mat8 {
        let mut m = Mat8::zeros();
        for i in 0..4 {
            for j in 0..4 {
                m[(2 * i, 2 * j)] = self.mass4[(i, j)];
                m[(2 * i + 1, 2 * j + 1)] = self.mass4[(i, j)];
            }
        }
        m
    }

    /// Adds the inertial force M a of element accelerations `a` into `out`
    /// [SI: N].
    #[inline(always)]
    pub fn add_inertial_force(&self, a: &Vec8, out: &mut Vec8) {
        for i in 0..4 {
            let (mut fx, mut fy) = (0.0, 0.0);
            for j in 0..4 {
                fx += self.mass4[(i, j)] * a[2 * j];
                fy += self.mass4[(i, j)] * a[2 * j + 1];
            }
            out[2 * i] += fx;
            out[2 * i + 1] += fy;
        }
    }

    /// Generalized force of a uniform body force `f` per length [SI: N/m]: ∫ Sᵀ f dx.
    pub fn distributed_force(&self, f: Vector2<f64>) -> Vec8 {
        let mut q = Vec8::zeros();
        for (xi, w) in gauss01(3) {
            let s = shape(self.le, xi).s;
            for i in 0..4 {
                q[2 * i] += w * self.le * s[i] * f.x;
                q[2 * i + 1] += w * self.le * s[i] * f.y;
            }
        }
        q
    }

    /// Strain energy split into axial and bending parts [SI: J].
    pub fn strain_energy(&self, e: &Vec8) -> EnergySplit {
        let mut out = EnergySplit::default();
        for qp in &self.axial {
            let (_, _, eps) = axial_strain(e, &qp.d1);
            out.axial += 0.5 * qp.w * self.section.ea * eps * eps;
        }
        for qp in &self.bending {
            let (r1, r2) = (combine(e, &qp.d1), combine(e, &qp.d2));
            let kappa = r1.dot(&perp_neg(r2)) / r1.norm_squared();
            out.bending += 0.5 * qp.w * self.section.ei * kappa * kappa;
        }
        out
    }

    /// Tangent stiffness `∂Q_s/∂e` split into its axial and bending parts,
    /// each added into its buffer. Both parts are symmetric: the node blocks
    /// (i, j ≥ i) are summed over the quadrature points and mirrored once.
    pub fn tangent_parts_into(&self, e: &Vec8, axial: &mut Mat8, bending: &mut Mat8) {
        let CableSection { ea, ei, .. } = self.section;
        let mut ka = [[Matrix2::zeros(); 4]; 4];
        for qp in &self.axial {
            let (r1, l, eps) = axial_strain(e, &qp.d1);
            let t = r1 / l;
            let ttt = t * t.transpose();
            let a = (ttt + (Matrix2::identity() - ttt) * (eps / l)) * (qp.w * ea);
            for (i, row) in ka.iter_mut().enumerate() {
                for (j, blk) in row.iter_mut().enumerate().skip(i) {
                    *blk += a * (qp.d1[i] * qp.d1[j]);
                }
            }
        }
        let mut kb = [[Matrix2::zeros(); 4]; 4];
        for qp in &self.bending {
            let b = BendingPoint::new(e, qp);
            // Block (i, j): c [gᵢgⱼᵀ + κ (d1ᵢd1ⱼ H11 + d1ᵢd2ⱼ H12 + d2ᵢd1ⱼ H12ᵀ)]
            // with gᵢ = p d1ᵢ + q d2ᵢ; the j-dependent part of the first two
            // Hessian terms is uⱼ = cκ (d1ⱼ H11 + d2ⱼ H12), formed once per j.
            let c = qp.w * ei;
            let g: [Vector2<f64>; 4] = std::array::from_fn(|i| b.p * qp.d1[i] + b.q * qp.d2[i]);
            let (a11, a12) = (b.h11 * (c * b.kappa), b.h12 * (c * b.kappa));
            let a21 = a12.transpose();
            let u: [Matrix2<f64>; 4] = std::array::from_fn(|j| a11 * qp.d1[j] + a12 * qp.d2[j]);
            for i in 0..4 {
                let cg = g[i] * c;
                for j in i..4 {
                    kb[i][j] +=
                        cg * g[j].transpose() + u[j] * qp.d1[i] + a21 * (qp.d2[i] * qp.d1[j]);
                }
            }
        }
        for (out, k) in [(axial, &ka), (bending, &kb)] {
            for (i, row) in k.iter().enumerate() {
                for (j, blk) in row.iter().enumerate().skip(i) {
                    let mut dst = out.fixed_view_mut::<2, 2>(2 * i, 2 * j);
                    dst += blk;
                    if j > i {
                        let mut mirror = out.fixed_view_mut::<2, 2>(2 * j, 2 * i);
                        mirror += blk.transpose();
                    }
                }
            }
        }
    }

    /// The quadratic form ½ δeᵀ K δe of the tangent at `state`, split into its
    /// axial part (stretching) and its transverse part (bending, plus the
    /// geometric stiffness of the axial force), evaluated from the strain
    /// variations at the
    /// quadrature points. Unlike a product with the assembled matrix, this
    /// does not cancel large stiffness entries against each other: a rigid
    /// motion of a short element gives exactly zero, so Rayleigh quotients of
    /// smooth modes keep full relative precision on any mesh.
    pub fn quadratic_form(&self, state: &Displaced, de: &Vec8) -> EnergySplit {
        let mut out = [EnergySplit::default()];
        self.add_quadratic_forms(state, std::slice::from_ref(de), &mut out);
        out[0]
    }

    /// [`CableElement::quadratic_form`] of several variations at one state,
    /// added into `out` (one entry per variation): the state's quantities at
    /// each quadrature point (|r'|, curvature and its derivatives) are
    /// computed once for all of them.
    pub fn add_quadratic_forms(&self, state: &Displaced, des: &[Vec8], out: &mut [EnergySplit]) {
        assert_eq!(des.len(), out.len(), "one output per variation");
        let points = self.state_points(state);
        for (de, o) in des.iter().zip(out.iter_mut()) {
            let (mut ax, mut bd, mut cancel, mut stress) = (0.0, 0.0, 0.0, 0.0);
            let (mut state, mut first) = (0.0, 0.0);
            for (qp, p) in self.axial.iter().zip(&points.axial) {
                let d1 = combine_variation(de, &qp.d1);
                let (along, across) = (p.t.dot(&d1), p.n.dot(&d1));
                ax += p.stretch * along * along;
                bd += p.tension * across * across;
                // The second-order term from the nodal values' own sizes
                // (a rigid motion of stored, rounded nodes strains a short
                // element by ε|r|/Le), the first-order one from the terms
                // the difference form adds.
                let nodal = nodal_size(de, &qp.d1);
                cancel += p.stretch * nodal * nodal;
                let vs = variation_size(de, &qp.d1);
                first += 2.0 * (p.stretch * along.abs() + p.tension.abs() * across.abs()) * vs;
                stress += (p.tension * across * across).abs();
                state += p.noise * across * across;
            }
            for (qp, p) in self.bending.iter().zip(&points.bending) {
                let b = &p.point;
                let (d1, d2) = (combine_variation(de, &qp.d1), combine_variation(de, &qp.d2));
                let dk = b.p.dot(&d1) + b.q.dot(&d2);
                let second = d1.dot(&(b.h11 * d1)) + 2.0 * d1.dot(&(b.h12 * d2));
                bd += p.c * (dk * dk + b.kappa * second);
                let dk_nodal =
                    b.p.norm() * nodal_size(de, &qp.d1) + b.q.norm() * nodal_size(de, &qp.d2);
                cancel += p.c * dk_nodal * dk_nodal;
                let dk_size = b.p.norm() * variation_size(de, &qp.d1)
                    + b.q.norm() * variation_size(de, &qp.d2);
                first += 2.0 * p.c * dk.abs() * dk_size;
                // p and q carry the relative round-off of the state's r'.
                first += 4.0
                    * p.c
                    * dk.abs()
                    * p.slope_noise
                    * (b.p.norm() * d1.norm() + b.q.norm() * d2.norm());
                stress += (p.c * b.kappa * second).abs();
                state += p.c * p.noise * second.abs();
            }
            o.axial += ax;
            o.bending += bd;
            o.roundoff += f64::EPSILON * (f64::EPSILON * cancel + first + stress) + state;
        }
    }

    /// K δe of the tangent at `state` for each variation, added into `out`
    /// (one per variation): the gradient of [`CableElement::quadratic_form`],
    /// formed from the strain variations at the quadrature points and
    /// their stresses, so that a smooth variation's nodal forces carry the
    /// round-off of its strains, not of the stiffness entries (of order
    /// EI/Le³) that a product with the matrix cancels.
    pub fn add_tangent_products(&self, state: &Displaced, des: &[Vec8], out: &mut [Vec8]) {
        assert_eq!(des.len(), out.len(), "one output per variation");
        let points = self.state_points(state);
        for (de, o) in des.iter().zip(out.iter_mut()) {
            // ∂U₂/∂r' and ∂U₂/∂r'' per point, spread by the shape derivatives.
            for (qp, p) in self.axial.iter().zip(&points.axial) {
                let d1 = combine_variation(de, &qp.d1);
                let (along, across) = (p.t.dot(&d1), p.n.dot(&d1));
                let g1 = p.t * (2.0 * p.stretch * along) + p.n * (2.0 * p.tension * across);
                add_spread(o, &qp.d1, g1);
            }
            for (qp, p) in self.bending.iter().zip(&points.bending) {
                let b = &p.point;
                let (d1, d2) = (combine_variation(de, &qp.d1), combine_variation(de, &qp.d2));
                let dk = b.p.dot(&d1) + b.q.dot(&d2);
                let ck = p.c * b.kappa;
                let g1 = b.p * (2.0 * p.c * dk)
                    + ((b.h11 + b.h11.transpose()) * d1 + b.h12 * d2 * 2.0) * ck;
                let g2 = b.q * (2.0 * p.c * dk) + b.h12.transpose() * d1 * (2.0 * ck);
                add_spread(o, &qp.d1, g1);
                add_spread(o, &qp.d2, g2);
            }
        }
    }

    /// Tangent stiffness `∂Q_s/∂e`, added into `out`.
    pub fn tangent_into(&self, e: &Vec8, out: &mut Mat8) {
        let mut bending = Mat8::zeros();
        self.tangent_parts_into(e, out, &mut bending);
        *out += bending;
    }
}

/// Curvature and its first and second derivatives with respect to (r', r'').
pub(super) struct BendingPoint {
    pub(super) kappa: f64,
    /// ∂κ/∂r'
    pub(super) p: Vector2<f64>,
    /// ∂κ/∂r''
    pub(super) q: Vector2<f64>,
    /// ∂²κ/∂r'²
    pub(super) h11: Matrix2<f64>,
    /// ∂²κ/∂r'∂r''
    pub(super) h12: Matrix2<f64>,
}

impl BendingPoint {
    /// At the element's state, as the forces and the assembled tangent
    /// see it (smooth in the state: a transient's Newton needs that).
    #[inline]
    fn new(e: &Vec8, qp: &QuadPoint) -> Self {
        let r1 = combine(e, &qp.d1);
        Self::of(r1, combine(e, &qp.d2))
    }

    #[inline]
    pub(super) fn of(r1: Vector2<f64>, r2: Vector2<f64>) -> Self {
        let g = r1.norm_squared();
        let jr2 = perp_neg(r2); // ∂c/∂r'
        let jtr1 = Vector2::new(-r1.y, r1.x); // ∂c/∂r''
        let c = r1.dot(&jr2);
        let kappa = c / g;
        let g2 = g * g;
        let p = jr2 / g - r1 * (2.0 * c / g2);
        let q = jtr1 / g;
        let h11 = -(jr2 * r1.transpose() + r1 * jr2.transpose()) * (2.0 / g2)
            - Matrix2::identity() * (2.0 * c / g2)
            + r1 * r1.transpose() * (8.0 * c / (g2 * g));
        // ∂/∂r'' of p: J/g − 2 r' (Jᵀr')ᵀ/g², J = [[0, 1], [−1, 0]].
        let h12 = Matrix2::new(0.0, 1.0, -1.0, 0.0) / g - r1 * jtr1.transpose() * (2.0 / g2);
        BendingPoint {
            kappa,
            p,
            q,
            h11,
            h12,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The strain-form product K δe equals the assembled tangent times δe
    /// (to round-off of the tangent's entries) at a curved, stretched state,
    /// and gives exactly zero for a rigid translation of the element.
    #[test]
    fn tangent_products_match_the_tangent_matrix() {
        let el = CableElement::new(0.013, CableSection::rectangle(70e9, 2700.0, 2e-3, 5e-3));
        let e = Vec8::from_column_slice(&[0.1, 0.2, 0.95, 0.31, 0.113, 0.2035, 0.97, 0.28]);
        let mut k = Mat8::zeros();
        el.tangent_into(&e, &mut k);
        let des = [
            Vec8::from_fn(|i, _| (1.3 * i as f64).sin()),
            Vec8::from_fn(|i, _| (0.7 * i as f64 + 0.2).cos()),
        ];
        let reference = CableElement::straight(el.le, Vector2::new(0.1, 0.2), Vector2::x());
        let state = Displaced::new(&e, &reference);
        let mut out = [Vec8::zeros(); 2];
        el.add_tangent_products(&state, &des, &mut out);
        for (de, o) in des.iter().zip(&out) {
            let expected = k * de;
            let scale = k.abs().max() * de.abs().max();
            for i in 0..8 {
                assert!(
                    (o[i] - expected[i]).abs() <= 1e-12 * scale,
                    "entry {i}: {} against {}",
                    o[i],
                    expected[i]
                );
            }
        }
        let shift = Vec8::from_column_slice(&[0.3, -0.2, 0.0, 0.0, 0.3, -0.2, 0.0, 0.0]);
        let mut rigid = [Vec8::zeros()];
        el.add_tangent_products(&state, &[shift], &mut rigid);
        assert!(rigid[0].iter().all(|&v| v == 0.0), "{:?}", rigid[0]);
    }
}
