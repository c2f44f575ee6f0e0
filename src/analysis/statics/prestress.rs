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
//! Load sweeps are parameter studies ([`crate::analysis::sweep`] with a
//! `load_scale:` parameter): each factor's equilibrium is solved from the
//! reference, and a factor past a loss of stability fails alone.

use super::{solve_equilibrium, Equilibrium, StaticSettings};
use crate::analysis::modal::{modal, modal_at_reference, ModalResult, ModalSettings};
use crate::error::AnalysisError;
use crate::system::System;

/// Modes at the equilibrium beside those at the unloaded reference.
#[derive(Debug, Clone)]
pub struct PrestressedModal {
    pub equilibrium: Equilibrium,
    /// Linearized at the reference configuration, λ = 0.
    pub reference: ModalResult,
    /// Linearized at the equilibrium with its multipliers.
    pub prestressed: ModalResult,
}

impl PrestressedModal {
    /// Relative shift of mode i (sorted by frequency) [%]; `None` where the
    /// reference mode has zero frequency.
    pub fn shift_percent(&self, i: usize) -> Option<f64> {
        let f0 = self.reference.modes.get(i)?.frequency_hz;
        let f = self.prestressed.modes.get(i)?.frequency_hz;
        (f0 > 0.0).then(|| 100.0 * (f - f0) / f0)
    }
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
    Ok(PrestressedModal {
        equilibrium,
        reference,
        prestressed,
    })
}
