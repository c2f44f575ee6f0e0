//! The assembly with some of its coordinates held: its lowest modes
//! (Craig–Bampton's fixed-interface modes, and the full model a check
//! compares with) and its static responses to displacements of the held
//! coordinates (the constraint modes).
//!
//! Everything is in the null space of the joints' Jacobian C_q with the
//! held coordinates added as rows (B, one unit row per held coordinate):
//! q = N_h y with C_q N_h = 0 and B N_h = 0 ([`NullSpace`], positions
//! scaled by the model's size as in `modal`). The stiffness there,
//! K_h = N_hᵀ K N_h [SI: N/m and N m/rad], must be positive definite: the
//! held coordinates must stop every free motion of the body.

use super::ReduceError;
use crate::linalg::dense::solve_generalized;
use crate::linalg::krylov::{lowest_modes, KrylovSettings};
use crate::linalg::null_space::{symmetrize, NullSpace, Projected};
use crate::linalg::sparse::mul_vec;
use crate::linalg::{Scatter, Triplets};
use crate::system::Linearization;
use crate::System;
use faer::linalg::solvers::Solve;
use faer::sparse::SparseColMat;
use faer::{Mat, Side};

/// Up to this many free coordinates the held modes are solved densely.
const DENSE_MAX: usize = 300;

/// The null space of C_q and the `held` coordinates' unit rows.
pub(super) fn held_space(system: &System, q: &[f64], held: &[usize]) -> NullSpace {
    let n = system.ndof();
    let cq = held_jacobian(system, q, held);
    let mut d = vec![1.0; n];
    let size = system.length_scale();
    for i in system.point_coordinates() {
        d[i] = size;
        d[i + 1] = size;
    }
    NullSpace::scaled(cq.nrows(), n, cq.entries(), &d)
}

/// C_q with a row (a unit) for each `held` coordinate below the joints'.
fn held_jacobian(system: &System, q: &[f64], held: &[usize]) -> Triplets {
    let m = system.constraint_count();
    let mut cq = Triplets::new(m + held.len(), system.ndof());
    system.add_constraint_jacobian(q, &mut cq);
    for (r, &g) in held.iter().enumerate() {
        cq.add(m + r, g, 1.0);
    }
    cq
}

/// How many zero-frequency modes (mechanisms the held coordinates leave
/// free) the system has with `held` fixed, counted from its kinematics
/// ([`crate::analysis::zero_modes`]), not from small eigenvalues.
pub(super) fn held_zero_modes(
    system: &System,
    at: &Linearization,
    held: &[usize],
) -> Result<usize, ReduceError> {
    let cq = held_jacobian(system, at.q, held);
    crate::analysis::zero_modes::zero_modes(system, at, &cq)
        .map(|z| z.shapes.len())
        .map_err(|_| ReduceError::Eigen {
            size: system.ndof(),
        })
}

/// The full tangent K at `at` (n × n, compressed).
pub(super) fn full_stiffness(system: &System, at: &Linearization) -> SparseColMat<usize, f64> {
    let n = system.ndof();
    let mut k = Triplets::new(n, n);
    system.add_tangent_stiffness(at, &mut k);
    k.to_sparse()
}

/// y = K x for the compressed K.
pub(super) fn apply(k: &SparseColMat<usize, f64>, x: &[f64], y: &mut [f64]) {
    mul_vec(k, x, y);
}

/// (D N)ᵀ v: the generalized force v on the free coordinates of `ns`.
fn project_force(ns: &NullSpace, v: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; ns.dim()];
    for (g, &vg) in v.iter().enumerate() {
        for &(r, z) in ns.row(g) {
            out[r] += z * vg;
        }
    }
    out
}

/// The lowest `wanted` modes of the assembly with `held` coordinates
/// held: ω² [SI: rad²/s²] ascending and M-normalized shapes over the
/// model's coordinates.
pub(super) fn held_modes(
    system: &System,
    at: &Linearization,
    held: &[usize],
    wanted: usize,
) -> Result<(Vec<f64>, Vec<Vec<f64>>), ReduceError> {
    let ns = held_space(system, at.q, held);
    let dim = ns.dim();
    let wanted = wanted.min(dim);
    let (values, vectors) = if dim <= DENSE_MAX {
        let (mut k, mut m) = (Mat::zeros(dim, dim), Mat::zeros(dim, dim));
        system.add_tangent_stiffness(at, &mut Projected::new(&ns, &mut k));
        system.mass().add_into(&mut Projected::new(&ns, &mut m));
        symmetrize(&mut k);
        symmetrize(&mut m);
        let e = solve_generalized(&k, &m, wanted).map_err(|_| ReduceError::Eigen { size: dim })?;
        (e.values, e.vectors)
    } else {
        let (mut k, mut m) = (Triplets::new(dim, dim), Triplets::new(dim, dim));
        system.add_tangent_stiffness(at, &mut Projected::new(&ns, &mut k));
        system.mass().add_into(&mut Projected::new(&ns, &mut m));
        let r = lowest_modes(&k, &m, &[], &KrylovSettings::new(wanted))
            .map_err(|_| ReduceError::Eigen { size: dim })?;
        (r.values, r.vectors)
    };
    let shapes = (0..values.len())
        .map(|i| ns.expand(vectors.col_as_slice(i)))
        .collect();
    Ok((values, shapes))
}

/// Craig–Bampton's constraint modes: for each interface coordinate j the
/// motion of least strain energy with that coordinate at 1, the other
/// interface coordinates at 0 and the joints kept (C_q q = 0), one column
/// each over the model's coordinates [SI: m or – per unit of coordinate
/// j].
///
/// q = q_p + N_h y: q_p = N Gᵀ(GGᵀ)⁻¹eⱼ is a particular motion in the
/// joints' null space N with G = B N the interface rows of N, and
/// K_h y = −N_hᵀ K q_p. `label` names an interface coordinate in errors.
pub(super) fn constraint_modes(
    system: &System,
    at: &Linearization,
    k_full: &SparseColMat<usize, f64>,
    interface: &[usize],
    label: &dyn Fn(usize) -> String,
) -> Result<Vec<Vec<f64>>, ReduceError> {
    let n = system.ndof();
    let free = held_space(system, at.q, &[]);
    let held = held_space(system, at.q, interface);
    if free.dim() < held.dim() + interface.len() {
        // Some interface coordinate is not free: a support or a joint
        // fixes it, or two interface points are tied together.
        let dependent = first_dependent(&free, interface);
        return Err(ReduceError::InterfaceNotFree {
            coordinate: label(dependent),
        });
    }
    let p = interface.len();
    // G Gᵀ (p × p) from the sparse interface rows of N.
    let rows: Vec<&[(usize, f64)]> = interface.iter().map(|&g| free.row(g)).collect();
    let ggt = nalgebra::DMatrix::from_fn(p, p, |a, b| sparse_dot(rows[a], rows[b]));
    let chol = nalgebra::Cholesky::new(ggt).ok_or_else(|| ReduceError::InterfaceNotFree {
        coordinate: label(first_dependent(&free, interface)),
    })?;
    let dim = held.dim();
    let mut kh = Triplets::new(dim, dim);
    system.add_tangent_stiffness(at, &mut Projected::new(&held, &mut kh));
    let kh = kh.to_sparse();
    let factor = kh
        .sp_cholesky(Side::Lower)
        .map_err(|_| ReduceError::NotHeld)?;
    let mut rhs = Mat::<f64>::zeros(dim, p);
    let mut particular = Vec::with_capacity(p);
    let mut kq = vec![0.0; n];
    for j in 0..p {
        let mut e = nalgebra::DVector::zeros(p);
        e[j] = 1.0;
        let c = chol.solve(&e);
        let mut x = vec![0.0; free.dim()];
        for (a, row) in rows.iter().enumerate() {
            for &(r, z) in row.iter() {
                x[r] += z * c[a];
            }
        }
        let qp = free.expand(&x);
        apply(k_full, &qp, &mut kq);
        for (dst, v) in rhs
            .col_as_slice_mut(j)
            .iter_mut()
            .zip(project_force(&held, &kq))
        {
            *dst = -v;
        }
        particular.push(qp);
    }
    factor.solve_in_place(rhs.as_mut());
    Ok(particular
        .into_iter()
        .enumerate()
        .map(|(j, mut qp)| {
            let y = held.expand(rhs.col_as_slice(j));
            for (a, b) in qp.iter_mut().zip(y) {
                *a += b;
            }
            // Exactly the prescribed interface values.
            for (a, &g) in interface.iter().enumerate() {
                qp[g] = if a == j { 1.0 } else { 0.0 };
            }
            qp
        })
        .collect())
}

fn sparse_dot(a: &[(usize, f64)], b: &[(usize, f64)]) -> f64 {
    a.iter()
        .map(|&(r, x)| b.iter().filter(|e| e.0 == r).map(|e| e.1 * x).sum::<f64>())
        .sum()
}

/// The first interface coordinate whose row of N depends on the earlier
/// ones (Gram–Schmidt): the one not free.
fn first_dependent(free: &NullSpace, interface: &[usize]) -> usize {
    let dim = free.dim();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for (a, &g) in interface.iter().enumerate() {
        let mut v = vec![0.0; dim];
        for &(r, z) in free.row(g) {
            v[r] = z;
        }
        let norm0 = crate::linalg::vector::norm2(&v);
        for b in &basis {
            let d = crate::linalg::vector::dot(&v, b);
            crate::linalg::vector::axpy(-d, b, &mut v);
        }
        let norm = crate::linalg::vector::norm2(&v);
        if norm <= 1e-8 * norm0 || norm0 == 0.0 {
            return a;
        }
        crate::linalg::vector::scale(1.0 / norm, &mut v);
        basis.push(v);
    }
    0
}

/// The residual attachment modes of the free body: for each interface
/// coordinate j, x = G f̃ with f̃ = eⱼ − M Z Zᵀeⱼ (inertia relief against
/// the M-orthonormal zero modes Z) and x M-orthogonal to Z, less the kept
/// modes' share Σ φ φᵀeⱼ/ω² [SI: m/N or 1/N per unit force].
///
/// K x = f̃ is singular on Z; with x = N y it is solved as the saddle
/// system [K_r  c; cᵀ  0] [y; μ] = [Nᵀf̃; 0], c = NᵀM Z (faer's sparse LU).
pub(super) fn residual_modes(
    system: &System,
    at: &Linearization,
    interface: &[usize],
    zero: &[Vec<f64>],
    kept: &[(f64, Vec<f64>)],
) -> Result<Vec<Vec<f64>>, ReduceError> {
    let n = system.ndof();
    let free = held_space(system, at.q, &[]);
    let dim = free.dim();
    let nz = zero.len();
    let mut a = Triplets::new(dim + nz, dim + nz);
    system.add_tangent_stiffness(at, &mut Projected::new(&free, &mut a));
    let mut mz = vec![vec![0.0; n]; nz];
    for (z, out) in zero.iter().zip(&mut mz) {
        system.mass().mul_vec(z, out);
    }
    for (k, v) in mz.iter().enumerate() {
        for (r, c) in project_force(&free, v).into_iter().enumerate() {
            if c != 0.0 {
                a.add(r, dim + k, c);
                a.add(dim + k, r, c);
            }
        }
    }
    let lu = a.to_sparse().sp_lu().map_err(|_| ReduceError::NotHeld)?;
    let p = interface.len();
    let mut rhs = Mat::<f64>::zeros(dim + nz, p);
    for (j, &g) in interface.iter().enumerate() {
        let mut f = vec![0.0; n];
        f[g] = 1.0;
        for (z, m) in zero.iter().zip(&mz) {
            crate::linalg::vector::axpy(-z[g], m, &mut f);
        }
        for (r, v) in project_force(&free, &f).into_iter().enumerate() {
            rhs[(r, j)] = v;
        }
    }
    lu.solve_in_place(rhs.as_mut());
    Ok(interface
        .iter()
        .enumerate()
        .map(|(j, &g)| {
            let mut x = free.expand(&rhs.col_as_slice(j)[..dim]);
            for (w2, phi) in kept {
                crate::linalg::vector::axpy(-phi[g] / w2, phi, &mut x);
            }
            x
        })
        .collect())
}
