//! `identify`, the main job: the modal analysis, the impulse experiment
//! (half-sine hammer pulse, sensor, FFT) and their first bending
//! frequencies beside the experiment's, the paper's Table 3 when the
//! model's reference is the paper's.
//!
//! The experiment is, in this order: the fitted mode of measured records
//! nearest the model's first bending frequency among those that are a
//! peak of the fitted spectrum ([`crate::measured::experiment`]); the
//! model's `reference`; none. Errors are given both ways, (f − exp)/exp
//! and the paper's (exp − f)/f, in percent.

use super::{CalibrationOutput, ImpulseOutput, ModalOutput};
use crate::analysis::impulse::ImpulseResult;
use crate::measured::analysis::FrfAnalysis;
use crate::model::reference::{self, Errors};
use crate::model::{JointType, Model, PointSpec};
use schemars::JsonSchema;
use serde::Serialize;

/// Modes `identify` computes (rigid ones included) [–].
pub const IDENTIFY_MODES: usize = 12;

/// What the model's first bending frequency is compared with.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct Experiment {
    /// Its row label: `measured (frf fit)`, `experiment (paper Table 3)`,
    /// `experiment (SOURCE)` or `experiment (model reference)`.
    pub label: String,
    /// Its first bending frequency [Hz].
    pub frequency_hz: f64,
}

/// Whether the model's reference is the paper's Table 3 (then the paper's
/// own model rows belong in the comparison).
pub fn names_the_paper(model: &Model) -> bool {
    model
        .reference
        .as_ref()
        .is_some_and(|r| r.source.to_ascii_lowercase().contains("paper"))
}

/// The index in `measured.fit.modes` of the mode taken as the experiment:
/// a peak of the fitted spectrum nearest the model's eigenvalue first
/// bending frequency `eigen_hz` ([`crate::measured::experiment::choose`]).
pub fn measured_mode(measured: &FrfAnalysis, eigen_hz: Option<f64>) -> Option<usize> {
    crate::measured::experiment::choose(&measured.fit, eigen_hz.unwrap_or(0.0))
}

/// The experiment (module doc) for a model whose eigenvalue first bending
/// frequency is `eigen_hz`; `paper` says whether it is the paper's Table 3.
pub fn choose_experiment(
    model: &Model,
    eigen_hz: Option<f64>,
    measured: Option<&FrfAnalysis>,
) -> (Option<Experiment>, bool) {
    let paper = names_the_paper(model) && measured.is_none();
    let experiment = match (measured, &model.reference) {
        (Some(a), _) => measured_mode(a, eigen_hz).map(|j| {
            (
                "measured (frf fit)".to_string(),
                a.fit.modes[j].frequency_hz,
            )
        }),
        (None, Some(r)) if paper => Some(("experiment (paper Table 3)".into(), r.first_bending_hz)),
        (None, Some(r)) if !r.source.trim().is_empty() => Some((
            format!("experiment ({})", r.source.trim()),
            r.first_bending_hz,
        )),
        (None, Some(r)) => Some(("experiment (model reference)".into(), r.first_bending_hz)),
        (None, None) => None,
    };
    (
        experiment.map(|(label, frequency_hz)| Experiment {
            label,
            frequency_hz,
        }),
        paper,
    )
}

/// One row of the comparison.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct TableRow {
    /// Where the frequency comes from.
    pub source: String,
    /// First bending frequency [Hz]; null when that source has none.
    pub first_bending_hz: Option<f64>,
    /// (f − exp)/exp [%]; null without an experiment.
    pub error_percent: Option<f64>,
    /// (exp − f)/f [%], the paper's convention; null without an experiment.
    pub paper_error_percent: Option<f64>,
}

/// The comparison: the experiment, the eigenvalue, the impulse's FFT
/// (corrected and raw), and with `paper` the paper's ANCF and ANSYS rows.
pub fn comparison_table(
    experiment: Option<&Experiment>,
    eigen_hz: Option<f64>,
    impulse: &ImpulseResult,
    paper: bool,
) -> Vec<TableRow> {
    let table3 = reference::table3();
    let mut rows: Vec<(String, Option<f64>)> = Vec::new();
    if let Some(e) = experiment {
        rows.push((e.label.clone(), Some(e.frequency_hz)));
    }
    rows.push(("this tool, eigenvalue".into(), eigen_hz));
    rows.push((
        "this tool, impulse + FFT (corrected)".into(),
        impulse.first_bending.map(|f| f.corrected_hz),
    ));
    rows.push((
        "this tool, impulse + FFT (raw)".into(),
        impulse.first_bending.map(|f| f.raw_hz),
    ));
    if paper {
        rows.push(("paper, ANCF".into(), Some(table3.ancf_hz)));
        rows.push(("paper, ANSYS BEAM188".into(), Some(table3.ansys_hz)));
    }
    let exp = experiment.map(|e| e.frequency_hz);
    rows.into_iter()
        .map(|(source, f)| {
            let errors = f.zip(exp).map(|(f, e)| Errors::new(f, e));
            TableRow {
                source,
                first_bending_hz: f,
                error_percent: errors.map(|e| e.error_percent),
                paper_error_percent: errors.map(|e| e.paper_error_percent),
            }
        })
        .collect()
}

/// How the model is held: "free-free", or the kinds of its ground
/// connections ("clamped", "pinned", "roller", "spring-supported").
pub fn supports(model: &Model) -> String {
    let mut kinds: Vec<&str> = Vec::new();
    let grounded = |a: &PointSpec, b: &PointSpec| a.ground.is_some() || b.ground.is_some();
    for j in &model.joints {
        if grounded(&j.a, &j.b) {
            kinds.push(match j.kind {
                JointType::Weld => "clamped",
                JointType::Pin => "pinned",
                JointType::Slider => "roller",
            });
        }
    }
    if model.springs.iter().any(|s| grounded(&s.a, &s.b)) {
        kinds.push("spring-supported");
    }
    kinds.dedup();
    if kinds.is_empty() {
        "free-free".into()
    } else {
        kinds.join(", ")
    }
}

/// A mode fitted to the measured records.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct MeasuredPeak {
    /// Undamped natural frequency [Hz].
    pub frequency_hz: f64,
    /// Damping ratio ζ [–].
    pub damping_ratio: f64,
    /// |H| at the mode [FRF unit].
    pub magnitude: f64,
}

/// The measured records `identify --measured` compared with.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct MeasuredSummary {
    /// The measurement files.
    pub files: Vec<String>,
    /// Fit band [Hz].
    pub band_hz: [f64; 2],
    /// The fitted modes.
    pub peaks: Vec<MeasuredPeak>,
}

impl MeasuredSummary {
    /// The summary of `a`.
    pub fn new(a: &FrfAnalysis) -> Self {
        MeasuredSummary {
            files: a.files.iter().map(|f| f.display().to_string()).collect(),
            band_hz: [a.band.0, a.band.1],
            peaks: a
                .fit
                .modes
                .iter()
                .map(|m| MeasuredPeak {
                    frequency_hz: m.frequency_hz,
                    damping_ratio: m.damping_ratio,
                    magnitude: m.magnitude,
                })
                .collect(),
        }
    }
}

/// `identify --json` (and `summary.json`).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct IdentifyOutput {
    /// Model name.
    pub model: String,
    /// How the model is held (`free-free`, `clamped`, …).
    pub supports: String,
    /// The experiment's first bending frequency [Hz]; null without one.
    pub experiment_hz: Option<f64>,
    /// The comparison, one row per source.
    pub table: Vec<TableRow>,
    /// Where the reference comes from; null without one.
    pub reference_source: Option<String>,
    /// The measured records (`--measured`); else null.
    pub measured: Option<MeasuredSummary>,
    /// The modal analysis.
    pub modal: ModalOutput,
    /// The impulse experiment.
    pub impulse: ImpulseOutput,
    /// The equivalent-geometry fit (`--calibrate`); else null.
    pub calibration: Option<CalibrationOutput>,
}

impl IdentifyOutput {
    /// The document of the parts `identify` computed.
    pub fn new(
        model: &Model,
        modal: ModalOutput,
        impulse: &ImpulseResult,
        measured: Option<&FrfAnalysis>,
        calibration: Option<&crate::analysis::calibrate::CalibrationResult>,
    ) -> Self {
        let (experiment, paper) = choose_experiment(model, modal.first_bending_hz, measured);
        let experiment_hz = experiment.as_ref().map(|e| e.frequency_hz);
        IdentifyOutput {
            model: model.name.clone(),
            supports: supports(model),
            experiment_hz,
            table: comparison_table(experiment.as_ref(), modal.first_bending_hz, impulse, paper),
            reference_source: if paper {
                Some(reference::source())
            } else {
                model.reference.as_ref().map(|r| r.source.clone())
            },
            measured: measured.map(MeasuredSummary::new),
            impulse: ImpulseOutput::new(&model.name, impulse, experiment_hz),
            calibration: calibration.map(|c| CalibrationOutput::new(&model.name, c)),
            modal,
        }
    }
}
