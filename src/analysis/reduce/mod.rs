//! Reduced flexible bodies: the assembly's motions condensed onto a few
//! shapes, for a multibody code that moves the body on a floating frame
//! (Exudyn's `ObjectFFRFreducedOrder`).
//!
//! The body is the system as given (the caller removes the ground
//! supports): beams, rigid bodies, point masses, the joints between them
//! and their springs. Its motions are q = R a + Ψ η about the
//! linearization state: R the rigid motions of the whole assembly, which
//! the floating frame carries (x, y translation and the rotation, [SI: m
//! per m]), and Ψ the flexible basis, M-orthogonal to R (RᵀMΨ = 0, what
//! Exudyn's `excludeRigidBodyMotion` does), so no motion is counted twice.
//! Every column keeps the joints: C_q Ψ = 0 (all shapes are built in the
//! joints' null space). The interface is a set of beam nodes, four
//! coordinates each [rx, ry, r'x, r'y].
//!
//! - **Craig–Bampton**: the constraint modes (for each interface
//!   coordinate, the motion of least strain energy with that coordinate at
//!   1 and the others at 0; they contain the rigid motions) and the lowest
//!   `modes` fixed-interface modes (every interface coordinate held).
//! - **Free-interface** (MacNeal's residual flexibility): the lowest
//!   `modes` elastic modes of the free body, plus for each interface
//!   coordinate its residual attachment mode, the static response to a
//!   unit force there with inertia relief, less what the kept modes give
//!   (G f − Σ φφᵀf/ω², G the flexibility on the motions M-orthogonal to
//!   the zero modes). The kept modes stay exact: the residual modes are
//!   M- and K-orthogonal to them.
//!
//! The columns, scaled to unit M-norm and then with R projected out
//! (v − R RᵀM v, R M-orthonormal), are then turned into their Ritz vectors
//! (a column that was a rigid motion is left as round-off and dropped) ([`crate::linalg::subspace`]):
//! Ψ is M-orthonormal and K-orthogonal, so the reduced mass ΨᵀMΨ is the
//! identity [SI: kg m² … per unit² of modal coordinate, here 1] and the
//! reduced stiffness ΨᵀKΨ = diag(ω²) [SI: rad²/s²].

mod check;
mod held;
mod nodes;

pub use check::{check, rigid_stiffening, CheckCondition, ReductionCheck};
pub use nodes::{NodeForm, NodeKind};

use crate::analysis::modal::{modal, EigenMethod, ModalSettings};
use crate::linalg::subspace::ritz_basis;
use crate::system::Linearization;
use crate::System;
use faer::Mat;

/// How the basis is built.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ReductionMethod {
    /// Constraint modes + fixed-interface modes.
    CraigBampton,
    /// Free modes + residual attachment modes.
    FreeInterface,
}

impl ReductionMethod {
    /// The name as written in requests and documents.
    pub fn name(self) -> &'static str {
        match self {
            ReductionMethod::CraigBampton => "craig-bampton",
            ReductionMethod::FreeInterface => "free-interface",
        }
    }
}

/// Why a reduction failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReduceError {
    /// An interface coordinate is not free to move (a support or a joint
    /// fixes it, or ties it to another interface coordinate).
    #[error("interface coordinate {coordinate} is not free: a joint or support fixes it or ties it to another interface coordinate")]
    InterfaceNotFree { coordinate: String },
    /// With the interface held the body still moves freely (a mechanism
    /// the interface does not stop), or it is unstable there.
    #[error("with every interface coordinate held the body still has a motion without positive stiffness (a mechanism the interface does not hold, or an unstable pre-stress): add an interface point on that part")]
    NotHeld,
    /// More component modes asked for than the component problem has.
    #[error("{requested} component modes asked for: the {problem} problem has {available}")]
    TooManyModes {
        requested: usize,
        available: usize,
        /// "fixed-interface" or "free body's elastic".
        problem: &'static str,
    },
    /// The body has no elastic motion left.
    #[error("the body has no elastic motion to reduce")]
    NoFreedom,
    /// An eigen-solve failed.
    #[error("the eigen solver did not converge ({size}×{size} problem)")]
    Eigen { size: usize },
    /// The free body's modal analysis failed.
    #[error(transparent)]
    Modal(#[from] crate::error::AnalysisError),
}

/// The reduced body.
#[derive(Debug, Clone)]
pub struct Reduction {
    pub method: ReductionMethod,
    /// The interface coordinates, 4 per point [rx, ry, r'x, r'y].
    pub interface: Vec<usize>,
    /// The rigid motions the frame carries (n × r, M-orthonormal).
    pub rigid: Mat<f64>,
    /// The flexible basis Ψ (n × m), M-orthonormal, K-orthogonal, RᵀMΨ = 0.
    pub basis: Mat<f64>,
    /// Reduced stiffness diagonal ΨᵀKΨ [SI: rad²/s²] (the reduced mass is
    /// the identity).
    pub eigenvalues: Vec<f64>,
    /// The component modes the basis was built from: fixed-interface
    /// (Craig–Bampton) or free (free-interface) ω² [SI: rad²/s²].
    pub component_eigenvalues: Vec<f64>,
}

impl Reduction {
    /// Number of flexible coordinates.
    pub fn size(&self) -> usize {
        self.basis.ncols()
    }

    /// The reduced mass ΨᵀMΨ (the identity up to round-off), recomputed.
    pub fn mass(&self, system: &System) -> Mat<f64> {
        project(&self.basis, &|x, y| system.mass().mul_vec(x, y))
    }

    /// The reduced stiffness ΨᵀKΨ at `at`, recomputed.
    pub fn stiffness(&self, system: &System, at: &Linearization) -> Mat<f64> {
        let k = held::full_stiffness(system, at);
        project(&self.basis, &|x, y| held::apply(&k, x, y))
    }
}

/// VᵀAV (symmetrized) for A applied by `a`.
pub(crate) fn project(v: &Mat<f64>, a: &dyn Fn(&[f64], &mut [f64])) -> Mat<f64> {
    let mut av = Mat::<f64>::zeros(v.nrows(), v.ncols());
    for j in 0..v.ncols() {
        a(v.col_as_slice(j), av.col_as_slice_mut(j));
    }
    crate::linalg::subspace::symmetric(&(v.transpose() * &av))
}

/// The rigid motions of the whole assembly at `q`, M-orthonormal (n × r).
pub fn rigid_motions(system: &System, q: &[f64]) -> Mat<f64> {
    let n = system.ndof();
    let mass = system.mass();
    let mut cols: Vec<Vec<f64>> = Vec::new();
    let mut mv = vec![0.0; n];
    for field in system.assembly_motions(q) {
        let mut v = vec![0.0; n];
        for (i, x) in field {
            v[i] += x;
        }
        for _ in 0..2 {
            for c in &cols {
                mass.mul_vec(c, &mut mv);
                let d = crate::linalg::vector::dot(&v, &mv);
                crate::linalg::vector::axpy(-d, c, &mut v);
            }
        }
        let norm = mass.quadratic_form(&v).max(0.0).sqrt();
        if norm > 0.0 {
            crate::linalg::vector::scale(1.0 / norm, &mut v);
            cols.push(v);
        }
    }
    Mat::from_fn(n, cols.len(), |i, j| cols[j][i])
}

/// v ← v − R RᵀM v for every column of v.
fn exclude_rigid(system: &System, rigid: &Mat<f64>, v: &mut Mat<f64>) {
    let n = v.nrows();
    let mut mv = vec![0.0; n];
    for j in 0..v.ncols() {
        for _ in 0..2 {
            system.mass().mul_vec(v.col_as_slice(j), &mut mv);
            for r in 0..rigid.ncols() {
                let d = crate::linalg::vector::dot(rigid.col_as_slice(r), &mv);
                for i in 0..n {
                    v[(i, j)] -= d * rigid[(i, r)];
                }
            }
        }
    }
}

/// Reduces the body `system` linearized at `at` onto the interface
/// coordinates `interface` (4 per point) with `modes` component modes.
/// With `frame_carries_rigid` the basis leaves the assembly's rigid
/// motions to the multibody code's floating frame (M-orthogonal to them);
/// without (a body that keeps its supports, whose frame is fixed) it
/// spans every motion the constraints allow.
/// `label` names an interface coordinate (by its position in
/// `interface`) in errors.
pub fn reduce(
    system: &System,
    at: &Linearization,
    interface: &[usize],
    method: ReductionMethod,
    modes: usize,
    frame_carries_rigid: bool,
    label: &dyn Fn(usize) -> String,
) -> Result<Reduction, ReduceError> {
    let n = system.ndof();
    let rigid = if frame_carries_rigid {
        rigid_motions(system, at.q)
    } else {
        Mat::zeros(n, 0)
    };
    let available = available_modes(system, at, interface, method, rigid.ncols());
    if modes > available {
        return Err(ReduceError::TooManyModes {
            requested: modes,
            available,
            problem: match method {
                ReductionMethod::CraigBampton => "fixed-interface",
                ReductionMethod::FreeInterface => "free body's elastic",
            },
        });
    }
    let k_full = held::full_stiffness(system, at);
    let (columns, component) = match method {
        ReductionMethod::CraigBampton => {
            let mut cols = held::constraint_modes(system, at, &k_full, interface, label)?;
            let (values, shapes) = held::held_modes(system, at, interface, modes)?;
            cols.extend(shapes);
            (cols, values)
        }
        ReductionMethod::FreeInterface => free_interface(system, at, interface, modes)?,
    };
    if columns.is_empty() {
        return Err(ReduceError::NoFreedom);
    }
    // Unit M-norm *before* the rigid motions are projected out: a column
    // that is (nearly) a rigid motion, such as a constraint mode of a
    // single interface point, shrinks to round-off and the Ritz step drops
    // it as dependent instead of scaling its round-off back up.
    let mut v = Mat::from_fn(n, columns.len(), |i, j| columns[j][i]);
    let mut mv = vec![0.0; n];
    for j in 0..v.ncols() {
        system.mass().mul_vec(v.col_as_slice(j), &mut mv);
        let norm = crate::linalg::vector::dot(v.col_as_slice(j), &mv)
            .max(0.0)
            .sqrt();
        if norm > 0.0 {
            crate::linalg::vector::scale(1.0 / norm, v.col_as_slice_mut(j));
        }
    }
    exclude_rigid(system, &rigid, &mut v);
    let (eigenvalues, basis) = ritz_basis(&v, &|x, y| system.mass().mul_vec(x, y), &|x, y| {
        held::apply(&k_full, x, y)
    })
    .map_err(|_| ReduceError::Eigen { size: v.ncols() })?;
    if basis.ncols() == 0 {
        return Err(ReduceError::NoFreedom);
    }
    Ok(Reduction {
        method,
        interface: interface.to_vec(),
        rigid,
        basis,
        eigenvalues,
        component_eigenvalues: component,
    })
}

/// How many component modes `method` can have: the fixed-interface
/// problem's coordinates (Craig–Bampton) or the free body's less its
/// `rigid` motions (free-interface).
fn available_modes(
    system: &System,
    at: &Linearization,
    interface: &[usize],
    method: ReductionMethod,
    rigid: usize,
) -> usize {
    match method {
        ReductionMethod::CraigBampton => held::held_space(system, at.q, interface).dim(),
        ReductionMethod::FreeInterface => held::held_space(system, at.q, &[])
            .dim()
            .saturating_sub(rigid),
    }
}

/// The free-interface columns: the lowest `modes` elastic modes of the
/// free body and the residual attachment modes of the interface
/// coordinates (module doc), with the kept modes' ω².
fn free_interface(
    system: &System,
    at: &Linearization,
    interface: &[usize],
    modes: usize,
) -> Result<(Vec<Vec<f64>>, Vec<f64>), ReduceError> {
    let free = |count: usize| {
        modal(
            system,
            at,
            &ModalSettings {
                modes: Some(count),
                method: EigenMethod::Auto,
            },
        )
    };
    let mut result = free(modes + 3)?;
    if result.rigid_modes + modes > modes + 3 {
        result = free(result.rigid_modes + modes)?;
    }
    let zero: Vec<Vec<f64>> = result
        .modes
        .iter()
        .filter(|m| m.kind.is_zero())
        .map(|m| m.shape.clone())
        .collect();
    let kept: Vec<(f64, Vec<f64>)> = result
        .modes
        .iter()
        .filter(|m| !m.kind.is_zero())
        .map(|m| (m.eigenvalue, m.shape.clone()))
        .collect();
    let residual = held::residual_modes(system, at, interface, &zero, &kept)?;
    // Mechanisms (zero modes that are not rigid motions) are free motions
    // the frame does not carry: they stay in the basis.
    let mut cols: Vec<Vec<f64>> = result
        .modes
        .iter()
        .filter(|m| m.kind == crate::analysis::ModeKind::Mechanism)
        .map(|m| m.shape.clone())
        .collect();
    let values = kept.iter().map(|k| k.0).collect();
    cols.extend(kept.into_iter().map(|k| k.1));
    cols.extend(residual);
    Ok((cols, values))
}
