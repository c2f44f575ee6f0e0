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

/// The measured mode nearest the model's first bending frequency, and
/// whether it is that mode's measurement ([`measured_mode`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Pairing {
    /// The fit has no mode.
    Nothing,
    /// `fit.modes[index]` is the experiment.
    FirstBending(usize),
    /// `fit.modes[index]` lies nearer the model's mode at `model_hz` than
    /// its first bending frequency `first_hz`: it measures that mode.
    OtherMode {
        index: usize,
        model_hz: f64,
        first_hz: f64,
    },
}

impl Pairing {
    /// The experiment's index in the fit's modes.
    pub fn experiment(self) -> Option<usize> {
        match self {
            Pairing::FirstBending(j) => Some(j),
            _ => None,
        }
    }
}

/// The model's elastic frequencies [Hz]: the modes a measured one may be.
pub fn model_frequencies(modal: &ModalOutput) -> Vec<f64> {
    (modal.modes.iter())
        .filter(|m| !m.mode.kind.is_zero() && m.mode.frequency_hz > 0.0)
        .map(|m| m.mode.frequency_hz)
        .collect()
}

/// The mode of `measured`'s fit taken as the experiment: a peak of the
/// fitted spectrum nearest the model's eigenvalue first bending frequency
/// ([`crate::measured::experiment::choose`]), unless it lies nearer
/// another of `modal`'s modes than that one. A fit band that leaves the
/// first bending peak out (20–60 Hz on a board whose modes are 6.17 and
/// 42.6 Hz) has its nearest peak at the second mode, 39 Hz: it was printed
/// as the first bending, 84 % off the model.
pub fn measured_mode(measured: &FrfAnalysis, modal: &ModalOutput) -> Pairing {
    let eigen_hz = modal.first_bending_hz;
    let Some(index) = crate::measured::experiment::choose(&measured.fit, eigen_hz.unwrap_or(0.0))
    else {
        return Pairing::Nothing;
    };
    let Some(first_hz) = eigen_hz else {
        return Pairing::FirstBending(index);
    };
    let f = measured.fit.modes[index].frequency_hz;
    let nearest = (model_frequencies(modal).into_iter())
        .min_by(|a, b| (a - f).abs().total_cmp(&(b - f).abs()));
    match nearest {
        Some(model_hz) if (model_hz - f).abs() < (first_hz - f).abs() => Pairing::OtherMode {
            index,
            model_hz,
            first_hz,
        },
        _ => Pairing::FirstBending(index),
    }
}

/// The experiment (module doc) for a model whose modal analysis is
/// `modal`; `paper` says whether it is the paper's Table 3.
pub fn choose_experiment(
    model: &Model,
    modal: &ModalOutput,
    measured: Option<&FrfAnalysis>,
) -> (Option<Experiment>, bool) {
    let paper = names_the_paper(model) && measured.is_none();
    let experiment = match (measured, &model.reference) {
        (Some(a), _) => measured_mode(a, modal).experiment().map(|j| {
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
        let (experiment, paper) = choose_experiment(model, &modal, measured);
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
