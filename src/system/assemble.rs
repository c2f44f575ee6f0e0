//! Global assembly: mass matrix M, forces, tangent stiffness, constraints.
//!
//! Sign conventions (paper Eq. 12): M q̈ + C_qᵀ λ = Q_ext(q, t) − Q_int(q),
//! with Q_int = Q_s (beams) + ∂U/∂q (springs) and Q_ext = loads + gravity.
//! The tangent stiffness is K = ∂(Q_int − Q_ext)/∂q; a linearization about a
//! loaded state adds ∂(C_qᵀλ)/∂q.

use super::System;
use crate::linalg::null_space::NullSpace;
use crate::linalg::Scatter;
use crate::mechanics::anchor::Hess;
use crate::mechanics::cable_force::{elastic_forces_into, Wide, MAX_LANES};
use crate::mechanics::element::{EnergySplit, Mat8, Vec8};
use crate::mechanics::element_state::Displaced;
use crate::mechanics::joint::ConstraintJac;
use crate::mechanics::pair::{PairGrad, PairHess};
use faer::Mat;

/// Strain energy of a coordinate vector by kind [SI: J].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnergyBreakdown {
    /// Axial (membrane) energy of the beams.
    pub axial: f64,
    /// Bending energy of the beams.
    pub bending: f64,
    /// Energy of springs, torsion springs and contacts.
    pub springs: f64,
    /// Load stiffness and constraint-force (∂(C_qᵀλ)/∂q) terms; not strain
    /// energy, zero at an unloaded reference.
    pub other: f64,
    /// Quadratic forms only: an estimate of the form's round-off (beams:
    /// [`crate::mechanics::element::EnergySplit::roundoff`]; springs, loads and
    /// constraint forces: ε|v|ᵀ|H||v|) [SI: J].
    pub roundoff: f64,
}

impl EnergyBreakdown {
    pub fn total(&self) -> f64 {
        self.axial + self.bending + self.springs + self.other
    }
}

/// The state a linearization is taken at.
#[derive(Debug, Clone, Copy)]
pub struct Linearization<'a> {
    pub q: &'a [f64],
    /// Constraint multipliers; `None` = zero (unloaded reference).
    pub lambda: Option<&'a [f64]>,
    pub time: f64,
    /// Factor on the applied loads (not on gravity).
    pub load_scale: f64,
}

/// A scatter target that adds A φ for each shape instead of storing A.
/// K x for several x in reduced coordinates (x_full = N x), added into
/// reduced outputs (Nᵀ K N x): a [`Scatter`] of K's entries.
struct Products<'a, 'b, 'c> {
    basis: &'a NullSpace,
    xs: &'a [&'b [f64]],
    out: &'a mut [&'c mut [f64]],
}

impl Scatter for Products<'_, '_, '_> {
    #[inline]
    fn add(&mut self, i: usize, j: usize, v: f64) {
        for (o, x) in self.out.iter_mut().zip(self.xs) {
            let f = v * gather(self.basis, x, j);
            for &(r, z) in self.basis.row(i) {
                o[r] += z * f;
            }
        }
    }
}

/// Full coordinate g of N x.
#[inline]
fn gather(basis: &NullSpace, x: &[f64], g: usize) -> f64 {
    basis.row(g).iter().map(|&(r, z)| z * x[r]).sum()
}

/// Which internal forces a sum takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ForceParts {
    /// The beams' elastic forces and the members' (springs, torsion
    /// springs, contacts).
    All,
    /// The beams' elastic forces alone.
    Beams,
    /// The springs', torsion springs' and contacts' alone.
    Members,
}

fn element_vec(q: &[f64], dofs: &[usize; 8]) -> Vec8 {
    Vec8::from_fn(|i, _| q[dofs[i]])
}

impl System {
    /// The state at `q` of the element on `dofs`, as its displacement from
    /// its straight reference in q₀ ([`Displaced`]).
    pub fn element_state(&self, q: &[f64], dofs: &[usize; 8]) -> Displaced {
        Displaced::new(&element_vec(q, dofs), &element_vec(&self.q0, dofs))
    }
}

fn scatter_mat<const R: usize, const C: usize>(
    dofs: &[usize],
    local: &nalgebra::SMatrix<f64, R, C>,
    out: &mut impl Scatter,
) {
    for (i, &gi) in dofs.iter().enumerate() {
        for (j, &gj) in dofs.iter().enumerate() {
            out.add(gi, gj, local[(i, j)]);
        }
    }
}

impl System {
    /// The unloaded reference state: q₀, zero multipliers, t = 0, applied
    /// loads scaled by 0.
    pub fn reference(&self) -> Linearization<'_> {
        Linearization {
            q: &self.q0,
            lambda: None,
            time: 0.0,
            load_scale: 0.0,
        }
    }

    /// Constant mass matrix [SI: kg, kg m, kg m²] (a copy of the cached
    /// [`System::mass`]).
    pub fn mass_matrix(&self) -> Mat<f64> {
        self.mass().dense().clone()
    }

    /// Internal force Q_int(q) = Q_s + ∂U_springs/∂q, overwriting `out`.
    pub fn internal_force(&self, q: &[f64], out: &mut [f64]) {
        self.forces_into(q, None, ForceParts::All, out);
    }

    /// The internal forces of `parts` alone at `q`, overwriting `out`
    /// [SI: N, N m].
    pub fn internal_force_of(&self, parts: ForceParts, q: &[f64], out: &mut [f64]) {
        self.forces_into(q, None, parts, out);
    }

    /// M a + Q_int(q), overwriting `out`: the inertial and internal forces
    /// of the equations of motion, element by element [SI: N, N m].
    pub fn inertial_and_internal_force(&self, q: &[f64], a: &[f64], out: &mut [f64]) {
        self.forces_into(q, Some(a), ForceParts::All, out);
    }

    /// Compiled for the machine's vector extensions (AVX2 where the CPU
    /// has it, chosen at run time by `pulp`): a beam's elements four at a
    /// time, one per vector lane ([`elastic_forces_into`]), the rest one
    /// by one; the sums into `out` in element order. Rust never fuses a
    /// product and a sum, so the results are the same bits on every path.
    fn forces_into(&self, q: &[f64], a: Option<&[f64]>, parts: ForceParts, out: &mut [f64]) {
        pulp::Arch::new().dispatch(Forces {
            sys: self,
            q,
            a,
            parts,
            out,
        })
    }

    #[inline(always)]
    fn forces_into_here<S: pulp::Simd>(
        &self,
        simd: S,
        q: &[f64],
        a: Option<&[f64]>,
        parts: ForceParts,
        out: &mut [f64],
    ) {
        out.fill(0.0);
        let lanes = Wide::<S>::LANES;
        let beams = if parts == ForceParts::Members {
            &[][..]
        } else {
            &self.beams[..]
        };
        for b in beams {
            // Element k's 8 coordinates are q[dof0 + 4k..][..8].
            let mut k = 0;
            while k < b.elements.len() {
                let group = &b.elements[k..(k + lanes).min(b.elements.len())];
                // forces[c][j]: entry c of element k + j's force.
                let mut forces = [[0.0; MAX_LANES]; 8];
                let side_by_side = group.len() == lanes && (2..=MAX_LANES).contains(&lanes);
                if side_by_side {
                    let d0 = b.dof0 + 4 * k;
                    let packed = b.packed.get(k / MAX_LANES).map(|p| (p, k % MAX_LANES));
                    let q = &q[d0..d0 + 4 * lanes + 4];
                    elastic_forces_into(simd, group, packed, q, &mut forces);
                } else {
                    for (j, e) in group.iter().enumerate() {
                        let d0 = b.dof0 + 4 * (k + j);
                        let mut g = Vec8::zeros();
                        e.elastic_force_into(&Vec8::from_column_slice(&q[d0..d0 + 8]), &mut g);
                        for (f, g) in forces.iter_mut().zip(g.iter()) {
                            f[j] = *g;
                        }
                    }
                }
                // The sums in element order, as one element at a time.
                for (j, e) in group.iter().enumerate() {
                    let dofs = b.dof0 + 4 * (k + j)..b.dof0 + 4 * (k + j) + 8;
                    let mut f = Vec8::from_fn(|c, _| forces[c][j]);
                    if let Some(a) = a {
                        e.add_inertial_force(&Vec8::from_column_slice(&a[dofs.clone()]), &mut f);
                    }
                    for (o, fi) in out[dofs].iter_mut().zip(f.iter()) {
                        *o += fi;
                    }
                }
                k += group.len();
            }
        }
        if let Some(a) = a {
            for r in &self.rigid_bodies {
                let d = r.dof0;
                out[d] += r.mass * a[d];
                out[d + 1] += r.mass * a[d + 1];
                out[d + 2] += r.inertia * a[d + 2];
            }
            for p in &self.point_masses {
                out[p.dof0] += p.mass * a[p.dof0];
                out[p.dof0 + 1] += p.mass * a[p.dof0 + 1];
            }
        }
        if parts == ForceParts::Beams {
            return;
        }
        let mut g = PairGrad::zeros();
        for fe in self.elastic_elements() {
            fe.gradient(q, &mut g);
            for (i, d) in fe.pair().dofs().enumerate() {
                out[d] += g[i];
            }
        }
    }

    /// The largest entry any one member (a beam element, a spring, a
    /// torsion spring, a contact) exerts at `q`, each entry times its
    /// `weight` [SI: N when the weights turn moments into forces]. Members
    /// in balance with each other cancel in the assembled Q_int (two
    /// opposed preloaded springs, the elements of a tensioned beam); this is
    /// the size of the forces they carry. The beam elements' only with
    /// `parts` other than [`ForceParts::Members`], the springs' only with
    /// parts other than [`ForceParts::Beams`].
    pub fn largest_member_force(&self, parts: ForceParts, q: &[f64], weight: &[f64]) -> f64 {
        let mut largest = 0.0f64;
        let beams = if parts == ForceParts::Members {
            &[][..]
        } else {
            &self.beams[..]
        };
        for b in beams {
            for (k, e) in b.elements.iter().enumerate() {
                let d0 = b.dof0 + 4 * k;
                let mut f = Vec8::zeros();
                e.elastic_force_into(&Vec8::from_column_slice(&q[d0..d0 + 8]), &mut f);
                for (i, fi) in f.iter().enumerate() {
                    largest = largest.max((fi * weight[d0 + i]).abs());
                }
            }
        }
        if parts == ForceParts::Beams {
            return largest;
        }
        let mut g = PairGrad::zeros();
        for fe in self.elastic_elements() {
            fe.gradient(q, &mut g);
            for (i, d) in fe.pair().dofs().enumerate() {
                largest = largest.max((g[i] * weight[d]).abs());
            }
        }
        largest
    }

    /// The largest stiffness entry of any spring, torsion spring or contact
    /// at `q` [SI: N/m, or N m/rad]: with the model's size, the scale of
    /// their forces' round-off (a spring's k(l − l₀) loses ε k l).
    pub fn stiffest_member(&self, q: &[f64]) -> f64 {
        let mut h = PairHess::zeros();
        self.elastic_elements()
            .map(|fe| {
                fe.hessian(q, &mut h);
                h.iter().fold(0.0f64, |a, v| a.max(v.abs()))
            })
            .fold(0.0, f64::max)
    }

    /// External force Q_ext(q, t): loads × `load_scale` plus gravity, overwriting `out`.
    pub fn external_force(&self, q: &[f64], t: f64, load_scale: f64, out: &mut [f64]) {
        out.fill(0.0);
        for l in &self.loads {
            l.add_generalized_force(q, t, load_scale, out);
        }
        self.add_gravity(out);
    }

    /// Adds the (constant) gravity forces.
    pub fn add_gravity(&self, out: &mut [f64]) {
        let g = self.gravity;
        if g.x == 0.0 && g.y == 0.0 {
            return;
        }
        for b in &self.beams {
            for (k, e) in b.elements.iter().enumerate() {
                let f = e.distributed_force(g * b.section.rho_a);
                for (i, &d) in b.element_dofs(k).iter().enumerate() {
                    out[d] += f[i];
                }
            }
        }
        for r in &self.rigid_bodies {
            out[r.dof0] += r.mass * g.x;
            out[r.dof0 + 1] += r.mass * g.y;
        }
        for p in &self.point_masses {
            out[p.dof0] += p.mass * g.x;
            out[p.dof0 + 1] += p.mass * g.y;
        }
    }

    /// Tangent stiffness K = ∂(Q_int − Q_ext)/∂q (+ ∂(C_qᵀλ)/∂q if λ is
    /// given), overwriting `out` (n × n).
    pub fn tangent_stiffness(&self, at: &Linearization, out: &mut Mat<f64>) {
        out.fill(0.0);
        self.add_tangent_stiffness(at, out);
    }

    /// Adds the tangent stiffness of [`System::tangent_stiffness`] into any
    /// assembly target (a dense matrix, a triplet list, a projection).
    pub fn add_tangent_stiffness(&self, at: &Linearization, out: &mut impl Scatter) {
        let q = at.q;
        for b in &self.beams {
            for (k, e) in b.elements.iter().enumerate() {
                let dofs = b.element_dofs(k);
                let mut kt = Mat8::zeros();
                e.tangent_into(&element_vec(q, &dofs), &mut kt);
                scatter_mat(&dofs, &kt, out);
            }
        }
        self.add_tangent_stiffness_of_joints_and_loads(at, out);
    }

    /// The products K φ of the tangent stiffness of
    /// [`System::tangent_stiffness`] with several shapes, written into
    /// `out` (one per shape). The beams' part is formed from strain
    /// variations ([`crate::mechanics::element::CableElement::add_tangent_products`]):
    /// a smooth shape's nodal forces keep the precision of its strains
    /// where the assembled matrix's product cancels entries of order
    /// EI/Le³ (the residual of a mode of a 100,000-element cantilever
    /// would be all round-off).
    pub fn stiffness_products(
        &self,
        at: &Linearization,
        basis: &NullSpace,
        xs: &[&[f64]],
        out: &mut [&mut [f64]],
    ) {
        assert_eq!(xs.len(), out.len(), "one output per shape");
        for o in out.iter_mut() {
            o.fill(0.0);
        }
        let q = at.q;
        let mut des = vec![Vec8::zeros(); xs.len()];
        let mut forces = vec![Vec8::zeros(); xs.len()];
        for b in &self.beams {
            for (k, el) in b.elements.iter().enumerate() {
                let dofs = b.element_dofs(k);
                for (de, x) in des.iter_mut().zip(xs) {
                    *de = Vec8::from_fn(|i, _| gather(basis, x, dofs[i]));
                }
                forces.fill(Vec8::zeros());
                el.add_tangent_products(&self.element_state(q, &dofs), &des, &mut forces);
                for (o, f) in out.iter_mut().zip(&forces) {
                    for (i, &d) in dofs.iter().enumerate() {
                        for &(r, z) in basis.row(d) {
                            o[r] += z * f[i];
                        }
                    }
                }
            }
        }
        let mut products = Products { basis, xs, out };
        self.add_tangent_stiffness_of_joints_and_loads(at, &mut products);
    }

    /// The tangent's terms from springs, loads and (with λ) constraints.
    fn add_tangent_stiffness_of_joints_and_loads(
        &self,
        at: &Linearization,
        out: &mut impl Scatter,
    ) {
        let q = at.q;
        let mut h = PairHess::zeros();
        for fe in self.elastic_elements() {
            fe.hessian(q, &mut h);
            let dofs: Vec<usize> = fe.pair().dofs().collect();
            scatter_mat(&dofs, &h, out);
        }
        let mut hl = Hess::zeros();
        for l in &self.loads {
            l.load_stiffness(q, at.time, at.load_scale, &mut hl);
            scatter_mat(l.anchor.dofs(), &(-hl), out);
        }
        if let Some(lambda) = at.lambda {
            self.add_constraint_hessian(q, lambda, out);
        }
    }

    /// Stacked constraint residual C(q) (length = constraint_count).
    pub fn constraint_residual(&self, q: &[f64], out: &mut [f64]) {
        for (c, &row) in self.constraints.iter().zip(&self.constraint_rows) {
            c.residual(q, &mut out[row..row + c.rows()]);
        }
    }

    /// Constraint Jacobian C_q (m × n), overwriting `out`.
    pub fn constraint_jacobian(&self, q: &[f64], out: &mut Mat<f64>) {
        out.fill(0.0);
        self.add_constraint_jacobian(q, out);
    }

    /// Adds C_q (m × n) into any assembly target.
    pub fn add_constraint_jacobian(&self, q: &[f64], out: &mut impl Scatter) {
        let mut j = ConstraintJac::zeros();
        for (c, &row) in self.constraints.iter().zip(&self.constraint_rows) {
            j.fill(0.0);
            c.jacobian(q, &mut j);
            for (k, d) in c.pair().dofs().enumerate() {
                for r in 0..c.rows() {
                    out.add(row + r, d, j[(r, k)]);
                }
            }
        }
    }

    /// Adds the constraint forces C_qᵀλ into `out` (no dense C_q formed).
    pub fn add_constraint_forces(&self, q: &[f64], lambda: &[f64], out: &mut [f64]) {
        // Nothing to zero without a constraint (a free part's transient).
        if self.constraints.is_empty() {
            return;
        }
        let mut j = ConstraintJac::zeros();
        for (c, &row) in self.constraints.iter().zip(&self.constraint_rows) {
            c.jacobian(q, &mut j);
            for (k, d) in c.pair().dofs().enumerate() {
                out[d] += (0..c.rows())
                    .map(|r| j[(r, k)] * lambda[row + r])
                    .sum::<f64>();
            }
        }
    }

    /// Adds the viscous forces of dampers (∂(damping power)/∂q̇) into `out`
    /// and, if given, their q̇-Jacobian into `matrix` (any assembly target).
    /// Returns whether the system has any damper.
    pub fn add_damping<S: Scatter>(
        &self,
        q: &[f64],
        qd: &[f64],
        out: &mut [f64],
        mut matrix: Option<&mut S>,
    ) -> bool {
        // Nothing to zero or visit without a damper (a 2 KiB local Hessian
        // zeroed twice a step in every undamped transient).
        if !self.has_dampers() {
            return false;
        }
        let mut any = false;
        let (mut f, mut c) = (PairGrad::zeros(), PairHess::zeros());
        for fe in &self.force_elements {
            let mut v = PairGrad::zeros();
            for (i, d) in fe.pair().dofs().enumerate() {
                v[i] = qd[d];
            }
            if !fe.damping(q, &v, &mut f, &mut c) {
                continue;
            }
            any = true;
            let dofs: Vec<usize> = fe.pair().dofs().collect();
            for (i, &d) in dofs.iter().enumerate() {
                out[d] += f[i];
            }
            if let Some(m) = matrix.as_deref_mut() {
                scatter_mat(&dofs, &c, m);
            }
        }
        any
    }

    /// Adds the contacts' regularizing stiffness of static Newton
    /// iterations into `out` (see [`crate::mechanics::contact::ContactElement::regularization`]).
    pub fn add_contact_regularization(
        &self,
        q: &[f64],
        which: crate::mechanics::contact::Regularize,
        out: &mut impl Scatter,
    ) {
        let mut h = PairHess::zeros();
        for c in &self.contacts {
            if c.regularization(q, which, &mut h) {
                let dofs: Vec<usize> = crate::mechanics::spring::ForceElement::pair(c)
                    .dofs()
                    .collect();
                scatter_mat(&dofs, &h, out);
            }
        }
    }

    /// Whether the contacts' regularizations `a` and `b` give the same
    /// static Newton matrix at q (every contact regularized alike, see
    /// [`crate::mechanics::contact::ContactElement::regularized_alike`]).
    pub fn contacts_regularized_alike(
        &self,
        q: &[f64],
        a: crate::mechanics::contact::Regularize,
        b: crate::mechanics::contact::Regularize,
    ) -> bool {
        self.contacts.iter().all(|c| c.regularized_alike(q, a, b))
    }

    /// Adds ∂(C_qᵀλ)/∂q = Σ λᵢ ∂²Cᵢ/∂q² into `out`.
    pub fn add_constraint_hessian(&self, q: &[f64], lambda: &[f64], out: &mut impl Scatter) {
        let mut h = PairHess::zeros();
        for (c, &row) in self.constraints.iter().zip(&self.constraint_rows) {
            h.fill(0.0);
            c.hessian_dot(q, &lambda[row..row + c.rows()], &mut h);
            let dofs: Vec<usize> = c.pair().dofs().collect();
            scatter_mat(&dofs, &h, out);
        }
    }

    /// Elastic energy of the state q, by kind [SI: J].
    pub fn strain_energy(&self, q: &[f64]) -> EnergyBreakdown {
        let mut e = EnergyBreakdown::default();
        for b in &self.beams {
            for (k, el) in b.elements.iter().enumerate() {
                let s = el.strain_energy(&element_vec(q, &b.element_dofs(k)));
                e.axial += s.axial;
                e.bending += s.bending;
            }
        }
        e.springs = self.elastic_elements().map(|f| f.energy(q)).sum();
        e
    }

    /// The quadratic form ½ φᵀ K φ of the tangent stiffness at `at`, split
    /// by kind. Beam parts come from strain variations (see
    /// [`crate::mechanics::element::CableElement::quadratic_form`]), so the result keeps
    /// full relative precision for smooth shapes even on meshes with very
    /// short elements.
    pub fn stiffness_quadratic_form(&self, at: &Linearization, phi: &[f64]) -> EnergyBreakdown {
        let mut out = [EnergyBreakdown::default()];
        self.stiffness_quadratic_forms(at, &[phi], &mut out);
        out[0]
    }

    /// [`System::stiffness_quadratic_form`] of several shapes, written into
    /// `out` (one entry per shape). Each element's state quantities and each
    /// spring's Hessian are evaluated once for all shapes.
    pub fn stiffness_quadratic_forms(
        &self,
        at: &Linearization,
        phis: &[&[f64]],
        out: &mut [EnergyBreakdown],
    ) {
        assert_eq!(phis.len(), out.len(), "one output per shape");
        out.fill(EnergyBreakdown::default());
        let q = at.q;
        let mut des = vec![Vec8::zeros(); phis.len()];
        let mut split = vec![EnergySplit::default(); phis.len()];
        for b in &self.beams {
            for (k, el) in b.elements.iter().enumerate() {
                let dofs = b.element_dofs(k);
                for (de, phi) in des.iter_mut().zip(phis) {
                    *de = element_vec(phi, &dofs);
                }
                split.fill(EnergySplit::default());
                el.add_quadratic_forms(&self.element_state(q, &dofs), &des, &mut split);
                for (e, s) in out.iter_mut().zip(&split) {
                    e.axial += s.axial;
                    e.bending += s.bending;
                    e.roundoff += s.roundoff;
                }
            }
        }
        let local = |phi: &[f64], dofs: &mut dyn Iterator<Item = usize>| {
            let mut v = PairGrad::zeros();
            for (i, d) in dofs.enumerate() {
                v[i] = phi[d];
            }
            v
        };
        let mut h = PairHess::zeros();
        for fe in self.elastic_elements() {
            fe.hessian(q, &mut h);
            for (e, phi) in out.iter_mut().zip(phis) {
                let v = local(phi, &mut fe.pair().dofs());
                e.springs += 0.5 * v.dot(&(h * v));
                e.roundoff += 0.5 * f64::EPSILON * v.abs().dot(&(h.abs() * v.abs()));
            }
        }
        let mut hl = Hess::zeros();
        for l in &self.loads {
            l.load_stiffness(q, at.time, at.load_scale, &mut hl);
            for (e, phi) in out.iter_mut().zip(phis) {
                let v = local(phi, &mut l.anchor.dofs().iter().copied());
                let v8 = v.fixed_rows::<8>(0);
                e.other -= 0.5 * v8.dot(&(hl * v8));
                e.roundoff += 0.5 * f64::EPSILON * v8.abs().dot(&(hl.abs() * v8.abs()));
            }
        }
        if let Some(lambda) = at.lambda {
            for (c, &row) in self.constraints.iter().zip(&self.constraint_rows) {
                h.fill(0.0);
                c.hessian_dot(q, &lambda[row..row + c.rows()], &mut h);
                for (e, phi) in out.iter_mut().zip(phis) {
                    let v = local(phi, &mut c.pair().dofs());
                    e.other += 0.5 * v.dot(&(h * v));
                    e.roundoff += 0.5 * f64::EPSILON * v.abs().dot(&(h.abs() * v.abs()));
                }
            }
        }
    }

    /// Kinetic-energy form φᵀ M φ [SI: kg m² …].
    pub fn mass_quadratic_form(&self, mass: &Mat<f64>, phi: &[f64]) -> f64 {
        let n = self.ndof();
        (0..n)
            .map(|i| phi[i] * (0..n).map(|j| mass[(i, j)] * phi[j]).sum::<f64>())
            .sum()
    }
}

/// [`System::forces_into`]'s arguments, for `pulp`'s dispatch.
struct Forces<'a> {
    sys: &'a System,
    q: &'a [f64],
    a: Option<&'a [f64]>,
    parts: ForceParts,
    out: &'a mut [f64],
}

impl pulp::WithSimd for Forces<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, simd: S) {
        self.sys
            .forces_into_here(simd, self.q, self.a, self.parts, self.out)
    }
}
