//! Zero-frequency modes counted from the kinematics of the assembly.
//!
//! A zero mode moves without straining anything. Such a motion is rigid on
//! every body, so it lies in the span V of the bodies' rigid motions
//! ([`crate::System::rigid_motions`], weld clusters merged) that satisfy the
//! linearized constraints, C_q V a = 0. Among those, the ones with zero
//! stiffness are the null space of the small pencil (VᵀK_tV, VᵀMV), K_t
//! the full tangent at the linearization state: at an unloaded reference
//! only springs stiffen a rigid motion; under pre-stress gravity, preloads
//! and the constraint forces do too, so a pendulum under gravity keeps its
//! frequency.
//!
//! VᵀK_tV is formed from the cancellation-free energy form
//! ([`crate::System::stiffness_quadratic_forms`], by polarization), which
//! also estimates its own round-off R
//! ([`crate::system::EnergyBreakdown::roundoff`]): strain variations that
//! cancel nodal terms of size s carry ε·s, so a rigid motion's form is
//! ~ε²·(the energy of those sizes), and stress terms (tension, curvature,
//! preloads, constraint forces) carry ε of their size, and the state's own
//! strain and curvature carry the rounding of the nodal values they are
//! formed from (a straight reference is stress-free only to that rounding,
//! which a tension EA·ε₀ makes visible). A stiffness μ = ω²
//! of a candidate counts as zero when |μ| ≤ 64 R/m, m its mass. A pendulum
//! under gravity sits at ~1/(64 ε) times its threshold (its stiffness is a
//! stress term), a rigid motion of a free 2,000-element beam at ≤ R/m.
//!
//! The rank of C_q V is decided on columns of unit kinetic energy
//! (√(VᵀMV) = 1 each: translations and rotations, small and large bodies
//! weigh alike) and unit-norm rows, by the same grouped Gram–Schmidt/QR as
//! the constraint null space. Joints inside one weld cluster are left out:
//! the cluster's rigid motions satisfy them by construction.
//!
//! Each zero mode is then labelled: the span of the zero modes is split
//! into its intersection with the rigid motions of the whole assembly
//! (`rigid`) and the M-orthogonal rest (`mechanism`: a lever free on its
//! pin), by the principal angles between the two spaces.

use crate::linalg::dense::solve_generalized_small;
use crate::linalg::null_space::NullSpace;
use crate::linalg::vector::dot;
use crate::linalg::{EigenFailure, Triplets};
use crate::system::{EnergyBreakdown, Linearization, System};

/// Zero modes of a linearization.
#[derive(Debug, Clone, Default)]
pub struct ZeroModes {
    /// Mass-normalized shapes in the global coordinates (φᵀMφ = 1),
    /// M-orthogonal: the rigid motions of the whole assembly first, then
    /// the mechanisms.
    pub shapes: Vec<Vec<f64>>,
    /// How many of `shapes` (the first ones) move the whole assembly
    /// rigidly; the others are mechanisms of the joints.
    pub rigid: usize,
    /// Rigid clusters of bodies (bodies joined by welds count as one).
    pub clusters: usize,
    /// Rigid motions that satisfy the constraints (the candidates).
    pub candidates: usize,
}

/// Round-off factor of the zero test.
const ZERO_FACTOR: f64 = 64.0;

/// The zero modes of the system linearized at `at`; `cq` holds C_q there.
pub fn zero_modes(
    system: &System,
    at: &Linearization,
    cq: &Triplets,
) -> Result<ZeroModes, EigenFailure> {
    let n = system.ndof();
    let motions = system.rigid_motions(at.q);
    let c = motions.fields.len();
    // B = C_q V (m × c), its columns scaled by the size of their terms.
    let mut by_coord: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    for (f, field) in motions.fields.iter().enumerate() {
        for &(i, v) in field {
            by_coord[i].push((f, v));
        }
    }
    // Rows of joints inside one rigid cluster are left out: the cluster's
    // rigid motions satisfy them by construction (both points move with the
    // same rigid motion), and their rows of C_q V are only the rounding of
    // the model's own coordinates (a weld's two points a rounding apart
    // after a placement 1 m away) that must not pass for a constraint.
    let mut internal = vec![false; cq.nrows()];
    for (c, &row) in system.constraints.iter().zip(&system.constraint_rows) {
        let pair = c.pair();
        let cluster = |dofs: &[usize]| dofs.first().map(|&d| motions.cluster_of_dof[d]);
        if let (Some(a), Some(b)) = (cluster(pair.a.dofs()), cluster(pair.b.dofs())) {
            if a == b {
                internal[row..row + c.rows()].fill(true);
            }
        }
    }
    let mut b: Vec<(usize, usize, f64)> = Vec::new();
    for (i, j, v) in cq.entries().filter(|&(i, _, _)| !internal[i]) {
        for &(f, w) in &by_coord[j] {
            b.push((i, f, v * w));
        }
    }
    // Column scale: each field's own mass norm √(VᵀMV), so every column
    // is a motion of unit kinetic energy (translations and rotations, small
    // bodies and large ones, weigh alike). A column of round-off (a
    // rotation about a point the constraints do not move) then stays
    // round-off against the row's other terms and is dropped with them.
    let mass = system.mass();
    let col_norm: Vec<f64> = mass
        .sparse_quadratic_forms(&by_coord, c)
        .into_iter()
        .map(|m| if m > 0.0 { m.sqrt() } else { 1.0 })
        .collect();
    let kernel = NullSpace::new(
        cq.nrows(),
        c,
        b.iter().map(|&(i, f, v)| (i, f, v / col_norm[f])),
    );
    let r = kernel.dim();
    // Candidate motions u_k = V a_k in the global coordinates.
    let mut u: Vec<Vec<f64>> = Vec::with_capacity(r);
    for k in 0..r {
        let mut e = vec![0.0; r];
        e[k] = 1.0;
        let a = kernel.expand(&e);
        let mut uk = vec![0.0; n];
        for (f, &af) in a.iter().enumerate() {
            if af != 0.0 {
                for &(i, v) in &motions.fields[f] {
                    uk[i] += af / col_norm[f] * v;
                }
            }
        }
        u.push(uk);
    }
    // Unit mass for every candidate, so the forms below are ω²-sized.
    let mut scratch = vec![0.0; n];
    for uk in &mut u {
        mass.mul_vec(uk, &mut scratch);
        let m = dot(uk, &scratch);
        if m > 0.0 {
            let inv = 1.0 / m.sqrt();
            uk.iter_mut().for_each(|x| *x *= inv);
        }
    }
    let out = |shapes: Vec<Vec<f64>>| {
        let (shapes, rigid) = rigid_first(system, at.q, shapes);
        ZeroModes {
            shapes,
            rigid,
            clusters: motions.clusters,
            candidates: r,
        }
    };
    if r == 0 {
        return Ok(out(Vec::new()));
    }
    // Mass and stiffness of the candidates.
    let mu: Vec<Vec<f64>> = u
        .iter()
        .map(|x| {
            let mut y = vec![0.0; n];
            mass.mul_vec(x, &mut y);
            y
        })
        .collect();
    let mv = faer::Mat::from_fn(r, r, |i, j| 0.5 * (dot(&u[i], &mu[j]) + dot(&u[j], &mu[i])));
    let mut shapes: Vec<Vec<f64>> = u.clone();
    let mut pairs = Vec::new();
    for i in 0..r {
        for j in i + 1..r {
            shapes.push(u[i].iter().zip(&u[j]).map(|(a, b)| a + b).collect());
            pairs.push((i, j));
        }
    }
    let refs: Vec<&[f64]> = shapes.iter().map(Vec::as_slice).collect();
    let mut energies = vec![EnergyBreakdown::default(); refs.len()];
    system.stiffness_quadratic_forms(at, &refs, &mut energies);
    let form = |e: &EnergyBreakdown| 2.0 * e.total();
    let mut kv = faer::Mat::zeros(r, r);
    let mut noise = 0.0f64;
    for i in 0..r {
        kv[(i, i)] = form(&energies[i]);
        noise = noise.max(2.0 * energies[i].roundoff / mv[(i, i)]);
    }
    for (p, &(i, j)) in pairs.iter().enumerate() {
        let e = &energies[r + p];
        let v = 0.5 * (form(e) - kv[(i, i)] - kv[(j, j)]);
        kv[(i, j)] = v;
        kv[(j, i)] = v;
        noise = noise.max(2.0 * e.roundoff / (mv[(i, i)] + mv[(j, j)]));
    }
    let (values, vectors) = solve_generalized_small(&kv, &mv).map_err(|e| match e {
        // A massless free motion: report it in the global coordinates.
        EigenFailure::SingularMass { direction } => {
            let mut full = vec![0.0; n];
            for (a, ui) in direction.iter().zip(&u) {
                full.iter_mut().zip(ui).for_each(|(s, x)| *s += a * x);
            }
            EigenFailure::SingularMass { direction: full }
        }
        other => other,
    })?;
    let zero = ZERO_FACTOR * noise;
    let mut result = Vec::new();
    for (k, &value) in values.iter().enumerate() {
        if value.abs() <= zero {
            let mut shape = vec![0.0; n];
            for (i, ui) in u.iter().enumerate() {
                let a = vectors[(i, k)];
                shape.iter_mut().zip(ui).for_each(|(s, x)| *s += a * x);
            }
            result.push(shape);
        }
    }
    Ok(out(result))
}

/// Cosine of the principal angle above which a zero mode counts as a
/// rigid motion of the whole assembly.
const RIGID_COSINE: f64 = 1.0 - 1e-6;

/// The zero modes Z (M-orthonormal) re-based so that the first r span
/// their intersection with the rigid motions G of the whole assembly
/// (all bodies as one, about the assembly's centre): the principal
/// vectors of ZᵀMĜ, Ĝ an M-orthonormal basis of G, with cosine 1. The
/// rest, M-orthogonal to those, are mechanisms. Returns (shapes, r).
fn rigid_first(system: &System, q: &[f64], z: Vec<Vec<f64>>) -> (Vec<Vec<f64>>, usize) {
    let k = z.len();
    if k == 0 {
        return (z, 0);
    }
    let n = system.ndof();
    let mass = system.mass();
    let m_apply = |x: &[f64]| {
        let mut y = vec![0.0; n];
        mass.mul_vec(x, &mut y);
        y
    };
    // Ĝ: the assembly's rigid fields, M-orthonormalized (twice).
    let mut g: Vec<Vec<f64>> = Vec::new();
    for field in system.assembly_motions(q) {
        let mut v = vec![0.0; n];
        for (i, x) in field {
            v[i] = x;
        }
        let size = dot(&v, &m_apply(&v)).sqrt();
        for _ in 0..2 {
            for w in &g {
                let c = dot(w, &m_apply(&v));
                v.iter_mut().zip(w).for_each(|(a, b)| *a -= c * b);
            }
        }
        let norm = dot(&v, &m_apply(&v)).max(0.0).sqrt();
        if norm > 1e-8 * size {
            v.iter_mut().for_each(|x| *x /= norm);
            g.push(v);
        }
    }
    let mz: Vec<Vec<f64>> = z.iter().map(|x| m_apply(x)).collect();
    let p = nalgebra::DMatrix::from_fn(k, g.len(), |i, j| dot(&mz[i], &g[j]));
    let svd = p.svd(true, false);
    let u = svd.u.expect("left singular vectors");
    let common: Vec<usize> = (0..svd.singular_values.len())
        .filter(|&i| svd.singular_values[i] >= RIGID_COSINE)
        .collect();
    let combine = |a: &[f64]| -> Vec<f64> {
        let mut s = vec![0.0; n];
        for (c, x) in a.iter().zip(&z) {
            s.iter_mut().zip(x).for_each(|(si, xi)| *si += c * xi);
        }
        s
    };
    let mut shapes: Vec<Vec<f64>> = common
        .iter()
        .map(|&i| combine(u.column(i).as_slice()))
        .collect();
    // The complement of those directions in the coefficient space.
    let mut proj = nalgebra::DMatrix::<f64>::identity(k, k);
    for &i in &common {
        let c = u.column(i);
        proj -= c * c.transpose();
    }
    let eig = nalgebra::SymmetricEigen::new(proj);
    for j in 0..k {
        if eig.eigenvalues[j] > 0.5 {
            shapes.push(combine(eig.eigenvectors.column(j).as_slice()));
        }
    }
    (shapes, common.len())
}
