//! `modal`'s document: the modes of the assembly linearized at its
//! reference configuration ([`ModalOutput`]) or at the static equilibrium
//! under its loads ([`PrestressedOutput`]), with each mode's damping
//! (Rayleigh ζ = α/(2ω) + βω/2, or complex modes when the model has
//! dampers) and, on request, the MAC against another mode set.
//!
//! Both documents say whether their state is an equilibrium
//! ([`EquilibriumCheck`]): only there are positive eigenvalues a vibration
//! and negative ones an instability (`unstable_modes`); at a state that is
//! none (the unloaded reference of a preloaded model) negative ones count
//! as `negative_modes`. A negative eigenvalue's `frequency_hz` is
//! −√|ω²|/2π, never 0. Pre-stressed modes are compared with the unstressed
//! mode of the same shape (mass-weighted MAC ≥ 0.9,
//! [`crate::analysis::prestress::PAIR_MAC`]), not of the same rank.

use crate::analysis::damped_modes::{mode_damping, ModeDamping};
use crate::analysis::modal::{EnergyFractions, EquilibriumCheck};
use crate::analysis::prestress::{prestressed_modal, PrestressedModal};
use crate::analysis::statics::StaticSettings;
use crate::analysis::{modal_at_reference, ModalResult, ModalSettings, Mode, ModeKind};
use crate::error::AnalysisError;
use crate::model::Model;
use crate::System;
use schemars::JsonSchema;
use serde::Serialize;

/// One mode of [`ModalOutput`]: the mode (its shape stays out of the
/// JSON) and its damping.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct ModeEntry {
    /// The mode (its keys sit beside the damping's).
    #[serde(flatten)]
    pub mode: Mode,
    /// Damping ratio ζ [–]; null for zero-frequency modes and negative
    /// eigenvalues.
    pub damping_ratio: Option<f64>,
    /// Damped frequency Im λ/2π of a complex mode [Hz]; null without
    /// dampers (Rayleigh damping only), when overdamped, or for a negative
    /// eigenvalue.
    pub damped_frequency_hz: Option<f64>,
}

/// MAC of this model's elastic modes (rows) against another mode set
/// (columns), on the translations at the export nodes.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct MacTable {
    /// Frequencies of the rows, this model's elastic modes [Hz].
    pub rows_hz: Vec<f64>,
    /// Frequencies of the columns, the other set's modes [Hz].
    pub columns_hz: Vec<f64>,
    /// MAC values, one row per row mode [–] (0 to 1).
    pub matrix: Vec<Vec<f64>>,
}

/// `modal --json`: the modes at the reference configuration.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct ModalOutput {
    /// Model name.
    pub model: String,
    /// Number of coordinates [–].
    pub dofs: usize,
    /// Number of constraint equations [–].
    pub constraints: usize,
    /// Dimension of the reduced (constrained) problem [–].
    pub reduced_dofs: usize,
    /// Labels of joints with redundant equations.
    pub redundant_constraints: Vec<String>,
    /// Number of zero-frequency modes, rigid motions and mechanisms [–].
    pub rigid_modes: usize,
    /// How many of the zero-frequency modes are mechanisms of the joints [–].
    pub mechanism_modes: usize,
    /// Reported modes with a negative eigenvalue at a verified equilibrium
    /// (kind `unstable`) [–].
    pub unstable_modes: usize,
    /// Reported modes with a negative eigenvalue at a state that is not an
    /// equilibrium (kind `negative`) [–].
    pub negative_modes: usize,
    /// Whether the reference configuration is an equilibrium.
    pub equilibrium: EquilibriumCheck,
    /// Frequency of the first bending mode [Hz]; null when none was computed.
    pub first_bending_hz: Option<f64>,
    /// Which eigensolver ran (`dense` or `sparse shift-invert Lanczos`).
    pub solver: String,
    /// The worst error bound of the lowest three elastic modes when above
    /// 1e-7 [–], else null.
    pub accuracy_warning: Option<f64>,
    /// The modes, ascending.
    pub modes: Vec<ModeEntry>,
    /// Whether a beam's material gives no Poisson ratio, so the shear
    /// estimate assumes one.
    pub poisson_assumed: bool,
    /// Whether the damping ratios come from complex modes (the model has
    /// dampers) rather than the Rayleigh formula.
    pub complex_modes: bool,
    /// MAC against another mode set (`--mac`), else null.
    pub mac: Option<MacTable>,
}

impl ModalOutput {
    /// The document of `result` (of `model`) with the modes' damping.
    pub fn new(model: &Model, result: &ModalResult, damping: &[ModeDamping]) -> Self {
        ModalOutput {
            model: model.name.clone(),
            dofs: result.dofs,
            constraints: result.constraints,
            reduced_dofs: result.reduced_dofs,
            redundant_constraints: result.redundant_constraints.clone(),
            rigid_modes: result.rigid_modes,
            mechanism_modes: result.mechanism_modes,
            unstable_modes: result.unstable_modes,
            negative_modes: result.negative_modes,
            equilibrium: result.equilibrium.clone(),
            first_bending_hz: result.first_bending().map(|m| m.frequency_hz),
            solver: result.solver.to_string(),
            accuracy_warning: result.accuracy_warning(),
            modes: entries(result, damping),
            poisson_assumed: crate::analysis::shear::poisson_assumed(model),
            complex_modes: damping.iter().any(|d| d.complex),
            mac: None,
        }
    }
}

fn entries(result: &ModalResult, damping: &[ModeDamping]) -> Vec<ModeEntry> {
    result
        .modes
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let d = mode_damping_of(m, damping.get(i));
            ModeEntry {
                mode: m.clone(),
                damping_ratio: d.damping_ratio,
                damped_frequency_hz: d.damped_frequency_hz,
            }
        })
        .collect()
}

/// A mode's damping; none for a negative eigenvalue (no vibration to damp).
fn mode_damping_of(m: &Mode, d: Option<&ModeDamping>) -> ModeDamping {
    match d {
        Some(d) if !m.kind.is_negative() => *d,
        _ => ModeDamping::default(),
    }
}

/// The warnings of a modal result at the reference (not an equilibrium,
/// unstable), one sentence each, for the run's `warnings`.
pub fn reference_warnings(result: &ModalResult) -> Vec<String> {
    result.warnings("the reference configuration")
}

/// The warning of a plain (reference) analysis of a model whose loads the
/// reference does not balance: the linearization leaves the applied loads
/// out (they act only through an equilibrium), so the modes are the
/// unstressed ones. `None` when the reference balances them, or when the
/// result already says it is not an equilibrium (gravity, preloads).
pub fn loads_left_out(system: &crate::System, result: &ModalResult) -> Option<String> {
    use crate::analysis::statics::balance::{unbalanced_force, BALANCE_TOLERANCE};
    if !result.equilibrium.balanced {
        return None;
    }
    // The loads that act before a run (a step at t = 0 is an excitation,
    // not a pre-stress).
    let start = crate::analysis::statics::start::START_TIME;
    let b = unbalanced_force(system, &system.q0, None, start, 1.0);
    if !b.is_balanced(BALANCE_TOLERANCE) {
        return Some(format!(
            "the reference does not balance the model's constant loads (unbalanced {:.3e} N on {}): the modes at the reference leave the loads out, so these are the unstressed modes; the pre-stressed analysis (prestress) linearizes at the loads' static equilibrium",
            b.unbalanced,
            system.dof_label(b.worst_dof)
        ));
    }
    // Balanced but loaded (a pendulum hanging under gravity, a string
    // pulled straight): the loads still stiffen the modes.
    let mut external = vec![0.0; system.ndof()];
    system.external_force(&system.q0, start, 1.0, &mut external);
    let what = match (
        system.gravity.norm() > 0.0,
        system
            .loads
            .iter()
            .any(|l| l.force.norm() > 0.0 && l.time.value(start) != 0.0),
    ) {
        (true, true) => "the constant loads and gravity act",
        (true, false) => "gravity acts",
        (false, _) => "the constant loads act",
    };
    external.iter().any(|f| *f != 0.0).then(|| {
        format!(
            "{what} at the reference, which balances them: the modes at the reference leave out the stiffening they cause (a pendulum's gravity, a string's tension), so these are the unstressed modes; the pre-stressed analysis (prestress) includes it"
        )
    })
}

/// The warnings of a pre-stressed analysis: the equilibrium's (unstable,
/// or not an equilibrium by the independent check) and the reference's.
pub fn prestressed_warnings(r: &PrestressedModal) -> Vec<String> {
    let mut w = r.prestressed.warnings("the static equilibrium");
    w.extend(
        r.reference
            .equilibrium
            .warning("the reference configuration (the unstressed modes' state)"),
    );
    w
}

/// The modal analysis of `model` at its reference configuration: the
/// modes (with their shapes, for exports) and the document.
pub fn modal(
    model: &Model,
    system: &System,
    settings: &ModalSettings,
) -> Result<(ModalResult, ModalOutput), AnalysisError> {
    let mut result = modal_at_reference(system, settings)?;
    crate::analysis::shear::annotate(model, system, &mut result);
    let damping = mode_damping(system, &system.reference(), &result, model.damping)?;
    let output = ModalOutput::new(model, &result, &damping);
    Ok((result, output))
}

/// One mode of [`PrestressedOutput`].
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct PrestressedMode {
    /// Mode number, 1-based [–].
    pub index: usize,
    /// Natural frequency at the equilibrium [Hz].
    pub frequency_hz: f64,
    /// Eigenvalue ω² at the equilibrium [rad²/s²].
    pub eigenvalue: f64,
    /// What the mode mostly does.
    pub kind: ModeKind,
    /// Strain-energy fractions [–].
    pub energy: EnergyFractions,
    /// The unstressed mode of the same shape: its number in the reference's
    /// modes (1-based) [–]; null when no reference mode reaches a MAC of 0.9.
    pub unstressed_index: Option<usize>,
    /// Its frequency at the reference, unstressed [Hz]; null when unpaired.
    pub unstressed_hz: Option<f64>,
    /// Mass-weighted MAC with the most similar unstressed mode (with its
    /// cluster of repeated values) [–]; at least 0.9 when paired, null when
    /// the reference has no modes.
    pub mac: Option<f64>,
    /// Relative shift from the paired unstressed frequency [%]; null when
    /// unpaired or where either frequency is not positive.
    pub shift_percent: Option<f64>,
    /// Damping ratio ζ [–]; null for zero-frequency modes.
    pub damping_ratio: Option<f64>,
    /// Damped frequency of a complex mode [Hz]; null without dampers or
    /// when overdamped.
    pub damped_frequency_hz: Option<f64>,
}

/// How the static equilibrium of a pre-stressed analysis was found.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct EquilibriumSummary {
    /// Load increments taken [–].
    pub load_steps: usize,
    /// Newton iterations in all [–].
    pub iterations: usize,
    /// Unbalanced force at the solution [N].
    pub residual_n: f64,
    /// Constraint violation at the solution [m, rad].
    pub constraint_violation: f64,
    /// The independent check of the balance at the solution.
    pub check: EquilibriumCheck,
}

/// `modal --prestress --json`: the modes at the static equilibrium beside
/// the unstressed ones.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct PrestressedOutput {
    /// Model name.
    pub model: String,
    /// Always true: this document is linearized at the equilibrium.
    pub prestress: bool,
    /// Factor on the applied loads (gravity is not scaled) [–].
    pub load_scale: f64,
    /// Number of coordinates [–].
    pub dofs: usize,
    /// Number of zero-frequency modes at the equilibrium [–].
    pub rigid_modes: usize,
    /// How many of them are mechanisms [–].
    pub mechanism_modes: usize,
    /// Reported modes with a negative eigenvalue at the equilibrium (kind
    /// `unstable`) [–].
    pub unstable_modes: usize,
    /// Reported modes with a negative eigenvalue where the independent
    /// check finds no equilibrium (kind `negative`) [–].
    pub negative_modes: usize,
    /// Whether the reference configuration (the unstressed modes' state)
    /// is an equilibrium.
    pub reference_equilibrium: EquilibriumCheck,
    /// First bending frequency at the equilibrium [Hz]; null if none.
    pub first_bending_hz: Option<f64>,
    /// First bending frequency unstressed [Hz]; null if none.
    pub unstressed_first_bending_hz: Option<f64>,
    /// The equilibrium's solution statistics.
    pub equilibrium: EquilibriumSummary,
    /// The modes at the equilibrium, ascending.
    pub modes: Vec<PrestressedMode>,
    /// Whether the damping ratios come from complex modes (the model has
    /// dampers) rather than the Rayleigh formula.
    pub complex_modes: bool,
}

impl PrestressedOutput {
    /// The document of `r` (of `model`) with the modes' damping.
    pub fn new(model: &Model, r: &PrestressedModal, damping: &[ModeDamping]) -> Self {
        let first = |res: &ModalResult| res.first_bending().map(|m| m.frequency_hz);
        let modes = r
            .prestressed
            .modes
            .iter()
            .enumerate()
            .map(|(i, m)| {
                let d = mode_damping_of(m, damping.get(i));
                let partner = r.partner(i);
                PrestressedMode {
                    index: i + 1,
                    frequency_hz: m.frequency_hz,
                    eigenvalue: m.eigenvalue,
                    kind: m.kind,
                    energy: m.energy,
                    unstressed_index: partner.map(|p| p.index),
                    unstressed_hz: partner.map(|p| p.frequency_hz),
                    mac: r.matches.get(i).copied().flatten().map(|m| m.mac),
                    shift_percent: r.shift_percent(i),
                    damping_ratio: d.damping_ratio,
                    damped_frequency_hz: d.damped_frequency_hz,
                }
            })
            .collect();
        PrestressedOutput {
            model: model.name.clone(),
            prestress: true,
            load_scale: r.equilibrium.load_scale,
            dofs: r.prestressed.dofs,
            rigid_modes: r.prestressed.rigid_modes,
            mechanism_modes: r.prestressed.mechanism_modes,
            unstable_modes: r.prestressed.unstable_modes,
            negative_modes: r.prestressed.negative_modes,
            reference_equilibrium: r.reference.equilibrium.clone(),
            first_bending_hz: first(&r.prestressed),
            unstressed_first_bending_hz: first(&r.reference),
            equilibrium: EquilibriumSummary {
                load_steps: r.equilibrium.steps,
                iterations: r.equilibrium.iterations,
                residual_n: r.equilibrium.residual,
                constraint_violation: r.equilibrium.constraint_violation,
                check: r.prestressed.equilibrium.clone(),
            },
            modes,
            complex_modes: damping.iter().any(|d| d.complex),
        }
    }
}

/// The modal analysis of `model` at the static equilibrium under its
/// loads (scaled by `statics.load_scale`): the analysis and the document.
pub fn prestressed(
    model: &Model,
    system: &System,
    statics: &StaticSettings,
    settings: &ModalSettings,
) -> Result<(PrestressedModal, PrestressedOutput), AnalysisError> {
    let r = prestressed_modal(system, statics, settings)?;
    let damping = mode_damping(
        system,
        &r.equilibrium.linearization(),
        &r.prestressed,
        model.damping,
    )?;
    let output = PrestressedOutput::new(model, &r, &damping);
    Ok((r, output))
}

/// Any document `modal --json` prints: at the reference, pre-stressed
/// (`--prestress`), or over load factors (`--sweep-load`, a sweep).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum ModalJson {
    Reference(ModalOutput),
    Prestressed(PrestressedOutput),
    LoadSweep(crate::analysis::sweep::SweepDocument),
}
