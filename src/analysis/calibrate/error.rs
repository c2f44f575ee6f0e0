//! Why a calibration (`ancf-modal calibrate`) failed.

use crate::analysis::impulse::ImpulseError;
use crate::analysis::ModeKind;
use crate::error::{AnalysisError, InvalidModel};
use crate::model::path::PathError;

/// "mode at 6819.3 Hz: ∂f/∂ln(blade.height) = 6819.3 Hz, …; relative
/// singular values 1.41, 1.3e-16".
fn identifiability_details(
    parameters: &[String],
    frequencies_hz: &[f64],
    sensitivities_hz: &[Vec<f64>],
    singular_values: &[f64],
) -> String {
    let rows: Vec<String> = frequencies_hz
        .iter()
        .zip(sensitivities_hz)
        .map(|(f, row)| {
            let cols: Vec<String> = parameters
                .iter()
                .zip(row)
                .map(|(p, d)| format!("∂f/∂ln({p}) = {d:.4e} Hz"))
                .collect();
            format!("mode at {f:.3} Hz: {}", cols.join(", "))
        })
        .collect();
    let sv: Vec<String> = singular_values.iter().map(|s| format!("{s:.3e}")).collect();
    let why = if parameters.len() > frequencies_hz.len() {
        "more parameters than targets"
    } else {
        "the relative sensitivities are (nearly) linearly dependent"
    };
    format!(
        "{why}; {}; singular values of ∂ln f/∂ln p: {}",
        rows.join("; "),
        sv.join(", ")
    )
}

/// Why a calibration (`ancf-modal calibrate`) failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CalibrationError {
    #[error("no parameter to fit")]
    NoParameters,
    #[error("no target frequency (and no `reference` in the model)")]
    NoTargets,
    #[error("target frequency must be positive and finite, got {value:?} Hz")]
    TargetNotPositive { value: f64 },
    /// A parameter name the model does not have, or an ambiguous one.
    #[error(transparent)]
    Parameter(#[from] PathError),
    #[error("parameter `{name}` is given twice (as `{canonical}`)")]
    DuplicateParameter { name: String, canonical: String },
    #[error(
        "`{name}` cannot be fitted while the mass is kept: the density follows the section there"
    )]
    DensityWithKeepMass { name: String },
    #[error(
        "`{name}` is {initial:?} in the model; a fitted parameter needs a positive starting value"
    )]
    NoInitialValue { name: String, initial: f64 },
    #[error("bounds of `{name}` must satisfy 0 < lower < upper < ∞, got [{lower:?}, {upper:?}]")]
    InvalidBounds {
        name: String,
        lower: f64,
        upper: f64,
    },
    #[error("{modes} mode numbers for {targets} targets (one mode number per target)")]
    ModeCount { modes: usize, targets: usize },
    #[error("the model has no {kind} mode number {number} ({available} {kind} modes computed){}", if *unstressed_of_prestressed { "; these are the unstressed modes of a pre-stressed model (its loads or gravity stiffen it only at its static equilibrium): the pre-stressed fit (prestress) fits the modes there" } else { "" })]
    ModeNotFound {
        kind: ModeKind,
        number: usize,
        available: usize,
        /// The modes were the unstressed ones of a model whose reference
        /// does not balance its loads (set by the command, which knows).
        unstressed_of_prestressed: bool,
    },
    #[error("`{parameter}` does not affect the chosen mode ({frequency_hz:.3} Hz): ∂ln f/∂ln p = {relative_sensitivity:.2e}")]
    NoEffect {
        parameter: String,
        frequency_hz: f64,
        relative_sensitivity: f64,
    },
    #[error("target {target_hz} Hz is out of reach for `{parameter}` in [{lower:e}, {upper:e}]: the mode goes from {lower_hz:.3} Hz to {upper_hz:.3} Hz there ({})", unreachable_hint(*unstressed_of_prestressed, parameter, *target_hz, (*lower_hz, *upper_hz), beyond.as_deref().copied()))]
    Unreachable {
        parameter: String,
        target_hz: f64,
        lower: f64,
        upper: f64,
        lower_hz: f64,
        upper_hz: f64,
        /// The fit was to the unstressed modes of a model whose reference
        /// does not balance its loads (set by the command, which knows).
        unstressed_of_prestressed: bool,
        /// (p, f Hz): the mode at [`BEYOND_BOUNDS`] times past the bound
        /// nearer the target, when the model can be solved there.
        /// (Boxed: the error is returned on every path.)
        beyond: Option<Box<(f64, f64)>>,
    },
    #[error("the targets {targets_hz:?} Hz cannot be met within the bounds: the closest fit gives {achieved_hz:?} Hz at {}", parameters.iter().map(|(n, v)| format!("{n} = {v:e}")).collect::<Vec<_>>().join(", "))]
    NotReached {
        parameters: Vec<(String, f64)>,
        targets_hz: Vec<f64>,
        achieved_hz: Vec<f64>,
    },
    #[error("the parameters {} are not identifiable from {} target frequenc{}: {}", parameters.join(", "), frequencies_hz.len(), if frequencies_hz.len() == 1 { "y" } else { "ies" }, identifiability_details(parameters, frequencies_hz, sensitivities_hz, singular_values))]
    NotIdentifiable {
        parameters: Vec<String>,
        frequencies_hz: Vec<f64>,
        sensitivities_hz: Vec<Vec<f64>>,
        singular_values: Vec<f64>,
    },
    #[error("no convergence after {evaluations} evaluations (residual {residual_hz:.3e} Hz)")]
    NotConverged {
        evaluations: usize,
        residual_hz: f64,
    },
    #[error(
        "the `{method}` method has no sensitivities; it fits one parameter to one target only"
    )]
    NeedsSensitivities { method: &'static str },
    /// The parameter values make the model invalid (e.g. a joint
    /// coordinate that moves one point of a joint only).
    #[error("the model is not valid at {at}")]
    InvalidModel {
        at: String,
        source: Box<InvalidModel>,
    },
    #[error("analysis failed at {at}")]
    Analysis { at: String, source: AnalysisError },
    #[error("the impulse experiment failed at {at}")]
    Impulse { at: String, source: ImpulseError },
    #[error("the impulse experiment shows no first bending peak at {at}")]
    NoImpulsePeak { at: String },
    #[error("the impulse method identifies the first bending mode only (asked for {kind} mode(s) {numbers:?}): the eigen method fits the others")]
    ImpulseMode { kind: ModeKind, numbers: Vec<usize> },
}

/// How far past the bound nearer an unreachable target the mode is probed,
/// as a factor on the bound (module [`CalibrationError::Unreachable`]).
pub const BEYOND_BOUNDS: f64 = 1e3;

/// What an unreachable target's message advises: the pre-stress when the
/// unstressed modes of a pre-stressed model were fitted, then what the
/// mode does a factor [`BEYOND_BOUNDS`] past the bounds: wider bounds
/// when it passes the target there, else that it may never (a pendulum's
/// frequency is capped whatever its inertia: "widen the bounds" misled a
/// user).
fn unreachable_hint(
    unstressed_of_prestressed: bool,
    parameter: &str,
    target_hz: f64,
    (lower_hz, upper_hz): (f64, f64),
    beyond: Option<(f64, f64)>,
) -> String {
    let nearer = if (lower_hz - target_hz).abs() < (upper_hz - target_hz).abs() {
        lower_hz
    } else {
        upper_hz
    };
    let past = match beyond {
        Some((p, f)) if (f - target_hz).signum() != (nearer - target_hz).signum() => {
            format!("the bounds must be widened: at `{parameter}` = {p:e} the mode is at {f:.3} Hz")
        }
        Some((p, f)) => format!(
            "even at `{parameter}` = {p:e} the mode is at {f:.3} Hz, short of the target: it may have a limit that no value of `{parameter}` passes"
        ),
        None => "the bounds must be widened".to_string(),
    };
    if unstressed_of_prestressed {
        format!("these are the unstressed modes of a pre-stressed model: the pre-stressed fit (prestress) fits the modes of its static equilibrium; or {past}")
    } else {
        past
    }
}
