//! The reduced body's own check: its modes against the full model's under
//! a boundary condition other than the one its basis was built with, so
//! that the check can fail.
//!
//! - Craig–Bampton (built with the interface held): every interface point
//!   free. The zero modes (as many as the full model counts from its
//!   kinematics) are left out of both; the elastic ones are compared.
//!   Under a pre-stress the full model's rigid motions that the preload
//!   stiffens (a rotation against a preload that no support balances any
//!   more) are modes mostly of rigid motion, more than half of φᵀMφ in
//!   the rigid motions' span. The floating frame carries them at 0 Hz, so
//!   they are listed apart (`frame_hz`), and the comparison starts at the
//!   elastic modes on both sides.
//! - Free-interface (built free): the first interface point held (its four
//!   coordinates, position and slope: a weld to the ground that also fixes
//!   the slope's length, as `add_flexible_body(..., hold_slope_length=True)`
//!   does in Exudyn with two ground joints on the node and its virtual node).
//!
//! The reduced model is the body's motions q = [R Ψ] η with its mass
//! [R Ψ]ᵀ M [R Ψ] and, as the multibody code's floating frame has it, the
//! stiffness ΨᵀKΨ on the modal coordinates alone (a pre-stress's RᵀKR and
//! RᵀKΨ are lost there, and so here: [`rigid_stiffening`]); a held point adds the rows of
//! its coordinates as constraints on η. Frequencies f = √ω²/2π [Hz]
//! (negative for ω² < 0), error (f_reduced − f_full)/f_full [–]: Ritz's
//! bound makes it ≥ 0 up to round-off.

use super::{held, project, ReduceError, Reduction};
use crate::analysis::modal::{modal, EigenMethod, ModalSettings};
use crate::linalg::dense::solve_generalized;
use crate::linalg::null_space::NullSpace;
use crate::system::Linearization;
use crate::System;
use faer::Mat;

/// The boundary condition of a check.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, schemars::JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum CheckCondition {
    /// Every interface point free: `{"kind": "free"}`.
    Free,
    /// The interface point numbered `point` (1-based, as the report prints
    /// it) held (position and slope): `{"kind": "held", "point": 1}`.
    Held { point: usize },
}

/// The modes of the reduced body and of the full model under one
/// condition.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct ReductionCheck {
    pub condition: CheckCondition,
    /// Zero-frequency modes of the full model left out of the comparison
    /// (rigid motions when free, mechanisms the held point leaves free).
    pub zero_modes: usize,
    /// The full model's modes that are mostly a rigid motion of the whole
    /// body (more than half of their mass-weighted motion), turned elastic
    /// by a pre-stress [SI: Hz]. The multibody code's floating frame
    /// carries these motions at 0 Hz (the import's limit), so they are
    /// listed here and not compared; negative (ω² < 0, −√|ω²|/2π) where a
    /// compression softens the motion. Empty without a pre-stress.
    pub frame_hz: Vec<f64>,
    /// The full model's frequencies [SI: Hz].
    pub full_hz: Vec<f64>,
    /// The reduced body's frequencies [SI: Hz].
    pub reduced_hz: Vec<f64>,
    /// (reduced − full)/full per mode [–].
    pub relative_error: Vec<f64>,
}

fn hz(omega2: f64) -> f64 {
    omega2.signum() * omega2.abs().sqrt() / (2.0 * std::f64::consts::PI)
}

/// Compares up to `count` modes of `reduction` with the full `system` at
/// `at` under `condition`.
pub fn check(
    system: &System,
    at: &Linearization,
    reduction: &Reduction,
    condition: CheckCondition,
    count: usize,
) -> Result<ReductionCheck, ReduceError> {
    let n = system.ndof();
    let (r, m) = (reduction.rigid.ncols(), reduction.basis.ncols());
    let whole = Mat::from_fn(n, r + m, |i, j| {
        if j < r {
            reduction.rigid[(i, j)]
        } else {
            reduction.basis[(i, j - r)]
        }
    });
    let k_full = held::full_stiffness(system, at);
    let mb = project(&whole, &|x, y| system.mass().mul_vec(x, y));
    // The stiffness acts on the modal coordinates only, as in the
    // multibody code's floating frame: the rigid motions' rows and columns
    // (RᵀKR, RᵀKΨ: non-zero only with a pre-stress) are not kept, so the
    // check shows what the import gives.
    let mut kb = project(&whole, &|x, y| held::apply(&k_full, x, y));
    for i in 0..r + m {
        for j in 0..r {
            kb[(i, j)] = 0.0;
            kb[(j, i)] = 0.0;
        }
    }
    let eigen = |k: &Mat<f64>, m: &Mat<f64>| {
        solve_generalized(k, m, k.nrows())
            .map(|e| e.values)
            .map_err(|_| ReduceError::Eigen { size: k.nrows() })
    };
    let mut frame_hz = Vec::new();
    let (zero_modes, full, reduced) = match condition {
        CheckCondition::Free => {
            let settings = |modes| ModalSettings {
                modes: Some(modes),
                method: EigenMethod::Auto,
            };
            // z zero modes, r − z rigid motions a pre-stress stiffened,
            // then the elastic ones.
            let want = |z: usize| count + z.max(r).max(3);
            let first = modal(system, at, &settings(want(0)))?;
            let z = first.rigid_modes;
            let result = if want(z) > want(0) {
                modal(system, at, &settings(want(z)))?
            } else {
                first
            };
            let mut full = Vec::new();
            for mode in result.modes.iter().filter(|m| !m.kind.is_zero()) {
                if rigid_fraction(system, &reduction.rigid, &mode.shape) > 0.5 {
                    frame_hz.push(hz(mode.eigenvalue));
                } else {
                    full.push(mode.eigenvalue);
                }
            }
            let reduced = eigen(&kb, &mb)?;
            let skip = z.max(r).min(reduced.len());
            (z, full, reduced[skip..].to_vec())
        }
        CheckCondition::Held { point } => {
            let index = point.saturating_sub(1);
            let coords = &reduction.interface[4 * index..4 * index + 4];
            // Mechanisms left free by the held point are zero modes of
            // both: left out, as the free check leaves out rigid motions.
            let z = held::held_zero_modes(system, at, coords)?;
            let (full, _) = held::held_modes(system, at, coords, count + z)?;
            let rows = Mat::from_fn(4, r + m, |a, j| whole[(coords[a], j)]);
            let ns = NullSpace::from_dense(&rows);
            let (kh, mh) = (ns.project_dense(&kb), ns.project_dense(&mb));
            let reduced = eigen(&kh, &mh)?;
            let skip = |v: Vec<f64>| v[z.min(v.len())..].to_vec();
            (z, skip(full), skip(reduced))
        }
    };
    let count = count.min(full.len()).min(reduced.len());
    let full_hz: Vec<f64> = full[..count].iter().map(|&w| hz(w)).collect();
    let reduced_hz: Vec<f64> = reduced[..count].iter().map(|&w| hz(w)).collect();
    let relative_error = full_hz
        .iter()
        .zip(&reduced_hz)
        .map(|(f, g)| (g - f) / f)
        .collect();
    Ok(ReductionCheck {
        condition,
        zero_modes,
        frame_hz,
        full_hz,
        reduced_hz,
        relative_error,
    })
}

/// The share of a mass-normalized shape φ (φᵀMφ = 1) that is a rigid
/// motion of the whole body: Σⱼ (rⱼᵀMφ)² over the M-orthonormal rigid
/// motions rⱼ [–], between 0 and 1.
fn rigid_fraction(system: &System, rigid: &Mat<f64>, shape: &[f64]) -> f64 {
    let mut m_phi = vec![0.0; shape.len()];
    system.mass().mul_vec(shape, &mut m_phi);
    (0..rigid.ncols())
        .map(|j| {
            let c: f64 = (0..shape.len()).map(|i| rigid[(i, j)] * m_phi[i]).sum();
            c * c
        })
        .sum()
}

/// The pre-stress stiffening that the frame's rigid motions lose in the
/// multibody code: the ω² of RᵀKR largest in magnitude, with its sign (R
/// M-orthonormal, so these are the rigid motions' own ω² under the
/// pre-stress; negative where a compression softens them) [SI: rad²/s²].
/// Zero without a pre-stress (K R = 0) or without rigid motions.
pub fn rigid_stiffening(system: &System, at: &Linearization, reduction: &Reduction) -> f64 {
    if reduction.rigid.ncols() == 0 {
        return 0.0;
    }
    let k_full = held::full_stiffness(system, at);
    let kr = project(&reduction.rigid, &|x, y| held::apply(&k_full, x, y));
    solve_generalized(&kr, &Mat::identity(kr.nrows(), kr.ncols()), kr.nrows())
        .map(|e| {
            e.values
                .iter()
                .fold(0.0f64, |a, &v| if v.abs() > a.abs() { v } else { a })
        })
        .unwrap_or(0.0)
}
