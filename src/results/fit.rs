//! The documents of the fitting and checking commands: `calibrate`
//! (parameters fitted to target frequencies), `convergence` (mesh
//! refinement of the bending frequencies, O(h⁴)) and `frf` (measured
//! hammer records: H1, H2, coherence, the LSCF fit, and optionally the
//! model's FRF at a sensor beside them).

use crate::analysis::calibrate::transient::TransientCalibration;
use crate::analysis::calibrate::CalibrationResult;
use crate::analysis::convergence::{ConvergenceData, ReferenceKind};
use crate::measured::analysis::FrfAnalysis;
use crate::measured::ResponseQuantity;
use crate::model::{RayleighDamping, ValidModel};
use crate::signal::fit::{DiagramPole, RejectReason};
use crate::System;
use schemars::JsonSchema;
use serde::Serialize;

use super::finite;

/// `calibrate --json` (also `identify`'s `calibration`): the calibration
/// with the names of the model and of the fitted model.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct CalibrationOutput {
    /// Model name.
    pub model: String,
    /// The fitted model's name.
    pub fitted_model: String,
    /// The calibration (its keys sit beside `model`).
    #[serde(flatten)]
    pub result: CalibrationResult,
}

impl CalibrationOutput {
    /// The document of `r`, a calibration of `model_name`.
    pub fn new(model_name: &str, r: &CalibrationResult) -> Self {
        CalibrationOutput {
            model: model_name.to_string(),
            fitted_model: r.fitted_model.name.clone(),
            result: r.clone(),
        }
    }
}

/// `calibrate --quantity … --json` / `calibrate --trajectory … --json`:
/// the calibration to a transient beside the model's name.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct TransientCalibrationOutput {
    /// Model name.
    pub model: String,
    /// The calibration (its keys sit beside `model`).
    #[serde(flatten)]
    pub result: TransientCalibration,
}

/// Any document `calibrate --json` prints: to frequencies, or to a
/// transient (`--quantity`, `--trajectory`).
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum CalibrateJson {
    Frequencies(CalibrationOutput),
    Transient(TransientCalibrationOutput),
}

/// `convergence --json`.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct ConvergenceOutput {
    /// Model name.
    pub model: String,
    /// What the errors are measured against: `exact` (Euler–Bernoulli) or
    /// `finest_mesh`.
    pub reference: ReferenceKind,
    /// The reference in words.
    pub reference_note: String,
    /// Reference frequencies of the bending modes [Hz].
    pub reference_hz: Vec<f64>,
    /// Elements per beam of each mesh [–].
    pub elements: Vec<usize>,
    /// Coordinates of each mesh [–].
    pub coordinates: Vec<usize>,
    /// Bending frequencies, one row per mode, one column per mesh [Hz].
    pub frequencies_hz: Vec<Vec<f64>>,
    /// Relative errors against the reference, as `frequencies_hz` [–];
    /// null where undefined.
    pub relative_errors: Vec<Vec<Option<f64>>>,
    /// Observed order of convergence between the two finest meshes with a
    /// positive error, per mode [–] (about 4 for Hermite cubics); null
    /// where none is defined.
    pub observed_order: Vec<Option<f64>>,
}

impl ConvergenceOutput {
    /// The document of `data`.
    pub fn new(data: &ConvergenceData) -> Self {
        ConvergenceOutput {
            model: data.model.clone(),
            reference: data.reference_kind,
            reference_note: reference_note(data),
            reference_hz: data.reference_hz.clone(),
            elements: data.elements.clone(),
            coordinates: data.coordinates.clone(),
            frequencies_hz: data.frequencies_hz.clone(),
            relative_errors: data
                .errors
                .iter()
                .map(|row| row.iter().copied().map(finite).collect())
                .collect(),
            observed_order: last_orders(data).into_iter().map(finite).collect(),
        }
    }
}

/// What the errors of `data` are measured against, in words.
pub fn reference_note(data: &ConvergenceData) -> String {
    match data.reference_kind {
        ReferenceKind::Exact => {
            String::from("Euler–Bernoulli free-free beam, f = (βL)²/(2πL²)·√(EI/ρA)")
        }
        ReferenceKind::FinestMesh => format!(
            "the finest mesh ({} elements): the model has no analytic solution, so the errors are estimates",
            data.elements.last().copied().unwrap_or_default()
        ),
    }
}

/// Observed orders between the two finest meshes with a positive error
/// (NaN where there is none).
pub fn last_orders(data: &ConvergenceData) -> Vec<f64> {
    (0..data.errors.len())
        .map(|k| {
            (0..data.elements.len().saturating_sub(1))
                .rev()
                .map(|i| data.observed_order(k, i))
                .find(|p| p.is_finite())
                .unwrap_or(f64::NAN)
        })
        .collect()
}

/// A fitted mode of the measured records.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct FittedPeak {
    /// Undamped natural frequency [Hz].
    pub frequency_hz: f64,
    /// Damping ratio ζ [–]; null when the records do not resolve it
    /// (`damping_upper_bound` then holds what they allow): a fitted value
    /// there is no measurement.
    pub damping_ratio: Option<f64>,
    /// |Ĥ| of the fitted model, all its terms, at the mode's damped
    /// frequency [FRF unit] (near a close mode it holds that mode's
    /// contribution too: it is what the FRF reads there, not the mode's own
    /// peak |R|/σ); null when the damping is not resolved
    /// (`magnitude_lower_bound` then holds what the records allow).
    pub magnitude: Option<f64>,
    /// The mode's residue, real and imaginary part [FRF unit × rad/s].
    pub residue: [f64; 2],
    /// The largest damping ratio the records allow [–], when they do not
    /// resolve it (the mode rings past their end with no decay they can
    /// measure; `damping_ratio` is then null); null when they do.
    pub damping_upper_bound: Option<f64>,
    /// The smallest |H| at the peak the records allow [FRF unit], when
    /// they do not resolve the damping (|R|/(ζ_max ω): `magnitude` is then
    /// null); null when they do.
    pub magnitude_lower_bound: Option<f64>,
    /// Whether the mode makes its own peak of the fitted |Ĥ|: its own term
    /// at least half of |Ĥ| at its frequency, or a local maximum of |Ĥ|
    /// within its half-power half-width. A mode that makes none is a term
    /// the fit needs beside another mode's peak (it bends that skirt), not
    /// a resonance the records show.
    pub own_peak: bool,
}

/// A pole the fit found and did not report.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct RejectedPeak {
    /// Its frequency [Hz].
    pub frequency_hz: f64,
    /// Its damping ratio [–].
    pub damping_ratio: f64,
    /// Why it was rejected (a key).
    pub reason: RejectReason,
    /// Why, in words.
    pub why: String,
}

/// The model's FRF at a sensor beside the measured one (`frf --model M
/// --at SENSOR`).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct ModelOverlay {
    /// Model name.
    pub model: String,
    /// Sensor id.
    pub sensor: String,
    /// The model's Rayleigh damping; null when it has none.
    pub damping: Option<RayleighDamping>,
    /// The damping ratio assumed for every mode when the model has no
    /// damping [–]; else null.
    pub assumed_damping_ratio: Option<f64>,
    /// H at the measured frequencies, real and imaginary part per
    /// newton of the model's first load [FRF unit].
    pub h: Vec<[f64; 2]>,
}

/// ζ assumed for the model's FRF when the model has no damping [–].
pub const OVERLAY_DAMPING_RATIO: f64 = 0.005;
/// Modes the model's FRF sums (rigid ones included) [–].
pub const OVERLAY_MODES: usize = 30;

/// Why the model's FRF could not be computed.
#[derive(Debug, thiserror::Error)]
pub enum OverlayError {
    #[error(transparent)]
    Analysis(#[from] crate::error::AnalysisError),
    #[error(transparent)]
    Frf(#[from] crate::analysis::model_frf::ModelFrfError),
}

impl ModelOverlay {
    /// The model's FRF at `sensor` at `frequency_hz` as receptance,
    /// mobility or accelerance (`q`), from its lowest [`OVERLAY_MODES`]
    /// modes with the model's Rayleigh damping, or ζ =
    /// [`OVERLAY_DAMPING_RATIO`] for every mode without it.
    pub fn new(
        model: &ValidModel,
        sensor: &str,
        q: ResponseQuantity,
        frequency_hz: &[f64],
    ) -> Result<(Self, Vec<realfft::num_complex::Complex64>), OverlayError> {
        let system = System::new(model);
        let modal = crate::analysis::modal_at_reference(
            &system,
            &crate::analysis::ModalSettings {
                modes: Some(OVERLAY_MODES),
                ..Default::default()
            },
        )?;
        let damping = model.damping;
        let zeta = |w: f64| damping.map_or(OVERLAY_DAMPING_RATIO, |d| d.ratio(w));
        let power = match q {
            ResponseQuantity::Displacement => 0,
            ResponseQuantity::Velocity => 1,
            ResponseQuantity::Acceleration => 2,
        };
        let h = crate::analysis::model_frf::model_frf(
            &system,
            &modal,
            sensor,
            zeta,
            power,
            frequency_hz,
        )?;
        let overlay = ModelOverlay {
            model: model.name.clone(),
            sensor: sensor.to_string(),
            damping,
            assumed_damping_ratio: damping.is_none().then_some(OVERLAY_DAMPING_RATIO),
            h: h.iter().map(|c| [c.re, c.im]).collect(),
        };
        Ok((overlay, h))
    }

    /// The overlay's legend label.
    pub fn label(&self) -> String {
        match self.damping {
            Some(_) => format!("model {} at {}", self.model, self.sensor),
            None => format!(
                "model {} at {} (ζ = {} % assumed)",
                self.model,
                self.sensor,
                100.0 * OVERLAY_DAMPING_RATIO
            ),
        }
    }
}

/// `frf --json`.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct FrfOutput {
    /// The measurement files, in the order given.
    pub files: Vec<String>,
    /// The force and response channel of each time record, by name
    /// (CSV header or UFF label), in file order; empty for FRF records.
    pub channels: Vec<[String; 2]>,
    /// Sampling rate of the time records [Hz]; null for FRF records.
    pub sample_rate_hz: Option<f64>,
    /// Hits averaged [–]; null for FRF records.
    pub averages: Option<usize>,
    /// Window of the time records; null for FRF records.
    pub window: Option<String>,
    /// Decay rate of an exponential window, removed from the fit [1/s];
    /// null otherwise.
    pub window_decay_rate: Option<f64>,
    /// What the response measures: displacement, velocity or acceleration.
    pub response_quantity: String,
    /// Unit of the FRF (m/N, m/s/N or m/s²/N).
    pub frf_unit: String,
    /// FRF estimator the fit uses (`H1` or `H2`).
    pub estimator: String,
    /// Fit band [Hz].
    pub band_hz: [f64; 2],
    /// How the band's upper end was chosen (a key).
    pub band_end: String,
    /// The fitting method in words.
    pub method: String,
    /// What the fit took the data for: `continuous` (an FRF on a frequency
    /// axis), `sampled` (records sampled without a low-pass: discrete-time
    /// poles) or `filtered` (records low-pass filtered before sampling:
    /// continuous-time poles); for records, the better fit of the last two.
    pub pole_basis: String,
    /// Frequency lines [Hz].
    pub frequency_hz: Vec<f64>,
    /// H1 per line, real and imaginary part [FRF unit]; null where not finite.
    pub h1: Vec<Option<[f64; 2]>>,
    /// H2 per line [FRF unit]; null without time records.
    pub h2: Option<Vec<Option<[f64; 2]>>>,
    /// Coherence per line [–]; null without time records.
    pub coherence: Option<Vec<Option<f64>>>,
    /// The identified modes.
    pub peaks: Vec<FittedPeak>,
    /// The poles found and not reported, with the reason.
    pub rejected: Vec<RejectedPeak>,
    /// The stabilization diagram's poles.
    pub stabilization: Vec<DiagramPole>,
    /// The model's FRF beside it (`--model`, `--at`); else null.
    pub model_frf: Option<ModelOverlay>,
}

fn pair(c: &realfft::num_complex::Complex64) -> Option<[f64; 2]> {
    (c.re.is_finite() && c.im.is_finite()).then_some([c.re, c.im])
}

impl FrfOutput {
    /// The document of `a`, with the response quantity `q` and the model
    /// overlay.
    pub fn new(a: &FrfAnalysis, q: ResponseQuantity, model_frf: Option<ModelOverlay>) -> Self {
        let e = a.estimate.as_ref();
        FrfOutput {
            files: a.files.iter().map(|f| f.display().to_string()).collect(),
            channels: a.channels.clone(),
            sample_rate_hz: e.map(|e| e.sample_rate_hz),
            averages: e.map(|e| e.averages),
            window: e.map(|e| e.window.to_string()),
            window_decay_rate: e.map(|e| e.window_decay_rate),
            response_quantity: q.name().to_string(),
            frf_unit: q.frf_unit().to_string(),
            estimator: a.settings.estimator.name().to_string(),
            band_hz: [a.band.0, a.band.1],
            band_end: a.band_end.key().to_string(),
            method: "LSCF (z-domain common denominator) with stabilization, poles refined by nonlinear least squares".to_string(),
            pole_basis: a.fit.settings.basis.key().to_string(),
            frequency_hz: a.frequency_hz.clone(),
            h1: a.h1.iter().map(pair).collect(),
            h2: a.h2.as_ref().map(|h| h.iter().map(pair).collect()),
            coherence: a
                .coherence
                .as_ref()
                .map(|c| c.iter().map(|v| finite(*v)).collect()),
            peaks: a
                .fit
                .modes
                .iter()
                .map(|m| FittedPeak {
                    frequency_hz: m.frequency_hz,
                    damping_ratio: m.damping_bound.is_none().then_some(m.damping_ratio),
                    magnitude: m.damping_bound.is_none().then_some(m.magnitude),
                    residue: [m.residue.re, m.residue.im],
                    damping_upper_bound: m.damping_bound,
                    magnitude_lower_bound: m.magnitude_lower_bound(),
                    own_peak: crate::measured::experiment::is_fitted_peak(&a.fit, m),
                })
                .collect(),
            rejected: a
                .rejected
                .iter()
                .map(|r| RejectedPeak {
                    frequency_hz: r.frequency_hz,
                    damping_ratio: r.damping_ratio,
                    reason: r.reason,
                    why: r.reason.describe().to_string(),
                })
                .collect(),
            stabilization: a.fit.diagram.clone(),
            model_frf,
        }
    }
}
