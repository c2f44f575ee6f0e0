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
//! A load sweep follows the equilibrium path over load factors and stops at
//! the first loss of stability (where ω²₁ reaches zero).

use super::{continue_equilibrium, solve_equilibrium, Equilibrium, StaticSettings};
use crate::analysis::modal::{modal, modal_at_reference, ModalResult, ModalSettings, ModeKind};
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

/// One point of a load sweep.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SweepPoint {
    pub load_factor: f64,
    /// Elastic (non-zero) modes' frequencies, ascending [SI: Hz].
    pub frequencies_hz: Vec<f64>,
    /// Their eigenvalues ω² [SI: rad²/s²].
    pub eigenvalues: Vec<f64>,
    /// Zero-frequency modes at this load.
    pub rigid_modes: usize,
}

/// Frequencies over a range of load factors.
#[derive(Debug, Clone)]
pub struct LoadSweep {
    pub points: Vec<SweepPoint>,
    /// Why the sweep stopped early (e.g. loss of stability), if it did.
    pub stopped: Option<AnalysisError>,
}

/// `n` load factors from `a` to `b` inclusive (one point: `a`).
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    match n {
        0 => Vec::new(),
        1 => vec![a],
        _ => (0..n)
            .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
            .collect(),
    }
}

/// The first `modes` elastic modes at each load factor, following the
/// equilibrium path from one factor to the next. A failure of the statics
/// at some factor ends the sweep there (recorded in `stopped`); a failure
/// before the first point is returned as the error.
pub fn load_sweep(
    system: &System,
    factors: &[f64],
    modes: usize,
    statics: &StaticSettings,
    settings: &ModalSettings,
) -> Result<LoadSweep, AnalysisError> {
    let mut points = Vec::with_capacity(factors.len());
    let mut current: Option<Equilibrium> = None;
    let all = ModalSettings {
        modes: None,
        ..*settings
    };
    for &s in factors {
        let eq = match &current {
            None => solve_equilibrium(
                system,
                &StaticSettings {
                    load_scale: s,
                    ..*statics
                },
            ),
            Some(prev) => continue_equilibrium(system, prev, s, statics),
        };
        let eq = match eq {
            Ok(eq) => eq,
            Err(e) if current.is_some() => {
                return Ok(LoadSweep {
                    points,
                    stopped: Some(e),
                })
            }
            Err(e) => return Err(e),
        };
        let r = modal_at_equilibrium(system, &eq, &all)?;
        let elastic: Vec<_> = r
            .modes
            .iter()
            .filter(|m| m.kind != ModeKind::Rigid)
            .take(modes)
            .collect();
        points.push(SweepPoint {
            load_factor: s,
            frequencies_hz: elastic.iter().map(|m| m.frequency_hz).collect(),
            eigenvalues: elastic.iter().map(|m| m.eigenvalue).collect(),
            rigid_modes: r.rigid_modes,
        });
        current = Some(eq);
    }
    Ok(LoadSweep {
        points,
        stopped: None,
    })
}
