//! Modal analysis of the pre-stressed assembly: linearized at its static
//! equilibrium instead of the unloaded reference.
//!
//! At an equilibrium (q*, λ*) the stiffness is
//!
//! ```text
//! K = ∂(Q_int − Q_ext)/∂q + ∂(C_qᵀλ*)/∂q
//! ```
//!
//! - the tangent of the beams' elastic forces at the deformed state (material
//!   part plus the geometric part of the axial force N = EA ε [SI: N]);
//! - the springs' Hessians, whose geometric part T/l (I − uuᵀ) turns a
//!   loaded spring's force with its line;
//! - the load stiffness of dead loads on rigid-body points;
//! - the constraint term Σ λᵢ ∂²Cᵢ/∂q², which is zero at an unloaded
//!   reference but not where the joints carry load (a pendulum hanging from
//!   its pin gets its whole restoring stiffness m g d from it).
//!
//! It is the Hessian of the Lagrangian U − W + λᵀC of conservative forces,
//! hence symmetric. The eigenproblem is then the one of [`super::modal`].
//!
//! **Shifts by shape.** A pre-stressed mode is compared with the unstressed
//! mode of the same shape, not of the same rank (closed contacts and
//! pre-stress reorder modes): the mass-weighted MAC
//! (φᵀMψ)²/(φᵀMφ · ψᵀMψ) against every unstressed mode, summed over a
//! cluster of repeated unstressed values (the zero modes, or ω² within 1e-6:
//! only their span is determined), picks the partner; a MAC of at least
//! [`PAIR_MAC`] pairs them, below it the mode has no partner and no shift.
//! Both mode sets are M-orthonormal, so by Bessel's inequality at most one
//! pre-stressed mode can reach a MAC above ½ with one unstressed cluster:
//! the pairing is one-to-one without an assignment step.
//!
//! Load sweeps are parameter studies ([`crate::analysis::sweep`] with a
//! `load_scale:` parameter): each factor's equilibrium is solved from the
//! reference, and a factor past a loss of stability fails alone.

use super::{solve_equilibrium, Equilibrium, StaticSettings};
use crate::analysis::modal::{modal, modal_at_reference, ModalResult, ModalSettings, Mode};
use crate::error::AnalysisError;
use crate::linalg::vector::dot;
use crate::system::System;

/// MAC from which a pre-stressed mode and an unstressed one count as the
/// same shape [–].
pub const PAIR_MAC: f64 = 0.9;

/// The unstressed mode most like a pre-stressed one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeMatch {
    /// Index into the reference's modes (0-based) of the best match.
    pub reference: usize,
    /// Mass-weighted MAC with it (with its cluster of repeated values) [–].
    pub mac: f64,
}

impl ShapeMatch {
    /// Whether the match is a pair (MAC ≥ [`PAIR_MAC`]).
    pub fn paired(&self) -> bool {
        self.mac >= PAIR_MAC
    }
}

/// Modes at the equilibrium beside those at the unloaded reference.
#[derive(Debug, Clone)]
pub struct PrestressedModal {
    pub equilibrium: Equilibrium,
    /// Linearized at the reference configuration, λ = 0.
    pub reference: ModalResult,
    /// Linearized at the equilibrium with its multipliers.
    pub prestressed: ModalResult,
    /// For each pre-stressed mode, its best unstressed match (`None` when
    /// the reference has no modes).
    pub matches: Vec<Option<ShapeMatch>>,
}

impl PrestressedModal {
    /// The pre-stressed and unstressed results side by side, each
    /// pre-stressed mode matched by shape (module doc).
    pub fn new(
        system: &System,
        equilibrium: Equilibrium,
        reference: ModalResult,
        prestressed: ModalResult,
    ) -> Self {
        let matches = match_shapes(system, &reference, &prestressed);
        PrestressedModal {
            equilibrium,
            reference,
            prestressed,
            matches,
        }
    }

    /// The unstressed partner of pre-stressed mode i (0-based), if paired.
    pub fn partner(&self, i: usize) -> Option<&Mode> {
        let m = self.matches.get(i).copied().flatten()?;
        m.paired().then(|| self.reference.modes.get(m.reference))?
    }

    /// Relative shift of pre-stressed mode i from its unstressed partner
    /// [%]; `None` without a partner or where either frequency is not
    /// positive (zero modes, negative eigenvalues).
    pub fn shift_percent(&self, i: usize) -> Option<f64> {
        let f0 = self.partner(i)?.frequency_hz;
        let f = self.prestressed.modes.get(i)?.frequency_hz;
        (f0 > 0.0 && f > 0.0).then(|| 100.0 * (f - f0) / f0)
    }
}

/// Best unstressed match of each pre-stressed mode (module doc).
pub fn match_shapes(
    system: &System,
    reference: &ModalResult,
    prestressed: &ModalResult,
) -> Vec<Option<ShapeMatch>> {
    let mass = system.mass();
    let n = system.ndof();
    let weighted: Vec<Vec<f64>> = reference
        .modes
        .iter()
        .map(|m| {
            let mut y = vec![0.0; n];
            mass.mul_vec(&m.shape, &mut y);
            y
        })
        .collect();
    let norms: Vec<f64> = reference
        .modes
        .iter()
        .zip(&weighted)
        .map(|(m, y)| dot(&m.shape, y))
        .collect();
    // Clusters of the reference: the zero modes, and values within 1e-6.
    let cluster_of: Vec<usize> = {
        let mut ids = Vec::with_capacity(reference.modes.len());
        for (k, m) in reference.modes.iter().enumerate() {
            let id = match k.checked_sub(1).map(|j| (j, &reference.modes[j])) {
                Some((j, prev))
                    if (prev.kind.is_zero() && m.kind.is_zero())
                        || (m.eigenvalue - prev.eigenvalue).abs() <= 1e-6 * m.eigenvalue.abs() =>
                {
                    ids[j]
                }
                _ => k,
            };
            ids.push(id);
        }
        ids
    };
    prestressed
        .modes
        .iter()
        .map(|p| {
            let pp = mass.quadratic_form(&p.shape);
            let single: Vec<f64> = weighted
                .iter()
                .zip(&norms)
                .map(|(y, &nn)| {
                    let c = dot(&p.shape, y);
                    c * c / (pp * nn).max(f64::MIN_POSITIVE)
                })
                .collect();
            let mut cluster = vec![0.0; single.len()];
            for (k, &v) in single.iter().enumerate() {
                cluster[cluster_of[k]] += v;
            }
            let best = (0..single.len()).max_by(|&a, &b| {
                cluster[cluster_of[a]]
                    .total_cmp(&cluster[cluster_of[b]])
                    .then(single[a].total_cmp(&single[b]))
            })?;
            Some(ShapeMatch {
                reference: best,
                mac: cluster[cluster_of[best]].min(1.0),
            })
        })
        .collect()
}

/// Modal analysis linearized at an equilibrium.
pub fn modal_at_equilibrium(
    system: &System,
    equilibrium: &Equilibrium,
    settings: &ModalSettings,
) -> Result<ModalResult, AnalysisError> {
    modal(system, &equilibrium.linearization(), settings)
}

/// Equilibrium, then the modes there and at the reference.
pub fn prestressed_modal(
    system: &System,
    statics: &StaticSettings,
    settings: &ModalSettings,
) -> Result<PrestressedModal, AnalysisError> {
    let equilibrium = solve_equilibrium(system, statics)?;
    let prestressed = modal_at_equilibrium(system, &equilibrium, settings)?;
    let reference = modal_at_reference(system, settings)?;
    Ok(PrestressedModal::new(
        system,
        equilibrium,
        reference,
        prestressed,
    ))
}
