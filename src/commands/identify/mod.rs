//! `identify`, the main job: the modal analysis at the reference (the
//! natural frequencies [Hz] of [`IDENTIFY_MODES`] modes), the paper's
//! impulse experiment (a half-sine hammer pulse [N, s], generalized-α
//! integration [s], the sensor's spectrum and its first bending peak
//! [Hz], raw and corrected for the integrator's period error), and the
//! first bending frequency of both beside the experiment's: the paper's
//! Table 3 for the paper's model ([`crate::results::identify`]).
//!
//! The experiment is the fitted mode of measured hammer records nearest
//! the model's first bending frequency among those that are a peak of the
//! fitted spectrum (`measured`, analysed as `frf` does; checked against
//! the records, a poor fit warned of: [`crate::measured::experiment`]),
//! else the model's `reference`. With `calibrate`, the first beam's
//! equivalent height [m] whose eigenvalue first bending frequency meets the
//! experiment's.

mod files;

use super::frf::{FrfRecords, FrfRequest};
use super::impulse::ImpulseRequest;
use super::{CommandError, ModelInput, Run};
use crate::analysis::impulse::{run_impulse, ImpulseResult, ImpulseSettings};
use crate::analysis::{ModalResult, ModalSettings};
use crate::measured::analysis::FrfAnalysis;
use crate::results::identify::{choose_experiment, measured_mode, Pairing, IDENTIFY_MODES};
use crate::results::IdentifyOutput;
use crate::signal::Window;
use crate::System;
use std::path::PathBuf;
use std::sync::Arc;

pub use files::FIGURES;

/// What `identify` computes: the impulse experiment's settings (as
/// `impulse`'s), and what the model is compared with and fitted to.
#[derive(Debug, Clone, PartialEq)]
pub struct IdentifyRequest {
    /// The impulse experiment, as `impulse` runs it.
    pub experiment: ImpulseRequest,
    /// Also fit the first beam's equivalent height to the experiment's
    /// first bending frequency (eigenvalue-based `calibrate`).
    pub calibrate: bool,
    /// Measured hammer records (CSV or UFF 58, as for `frf`): their fitted
    /// mode nearest the model's first bending frequency, of those that are
    /// a peak of the fitted spectrum, is the experiment
    /// ([`crate::measured::experiment`]).
    pub measured: Vec<PathBuf>,
    /// The window of the measured records.
    pub measured_window: Window,
    /// Fit band (LO, HI) [Hz] of the measured records; `None`: chosen as
    /// `frf` chooses it.
    pub measured_band: Option<(f64, f64)>,
}

impl Default for IdentifyRequest {
    fn default() -> Self {
        let measured = FrfRequest::default();
        IdentifyRequest {
            experiment: ImpulseRequest::default(),
            calibrate: false,
            measured: Vec::new(),
            measured_window: measured.window,
            measured_band: measured.band,
        }
    }
}

impl IdentifyRequest {
    /// The impulse experiment's settings, the request's ranges checked
    /// ([`ImpulseRequest::check`]).
    pub fn impulse_settings(&self) -> Result<ImpulseSettings, CommandError> {
        self.experiment.check()?;
        Ok(self.experiment.settings())
    }
}

/// `identify`'s output: the parts it computed and the document.
#[derive(Debug)]
pub struct IdentifyRun {
    /// The model.
    pub model: Arc<crate::model::ValidModel>,
    /// Its assembled system.
    pub system: System,
    /// The modes at the reference.
    pub modal: ModalResult,
    /// The impulse experiment.
    pub impulse: ImpulseResult,
    /// The measured records' analysis (`measured`).
    pub measured: Option<FrfAnalysis>,
    /// Whether the comparison is the paper's Table 3.
    pub paper: bool,
    /// The document (`--json`, `summary.json`) with the run's warnings.
    pub document: Run<IdentifyOutput>,
}

/// Runs `identify` on `input`.
pub fn run(input: &ModelInput, request: &IdentifyRequest) -> Result<IdentifyRun, CommandError> {
    run_with_progress(input, request, &mut |_| {})
}

/// [`run`], telling `progress` the fraction of the integration's steps
/// done.
pub fn run_with_progress(
    input: &ModelInput,
    request: &IdentifyRequest,
    progress: &mut dyn FnMut(f64),
) -> Result<IdentifyRun, CommandError> {
    let settings = request.impulse_settings()?;
    let model = &input.model;
    let system = System::new(model);
    let modal_settings = ModalSettings {
        modes: Some(IDENTIFY_MODES),
        ..ModalSettings::default()
    };
    let (modal, modal_output) = crate::results::modal::modal(model, &system, &modal_settings)
        .map_err(|e| CommandError::analysis(input.label(), e))?;
    // The modal analysis's and the impulse's own warnings, as `modal` and
    // `impulse` give them.
    let mut own = super::modal::reference_modal_warnings(model, &system, &modal);
    let impulse =
        run_impulse(model, &settings, progress).map_err(|source| CommandError::Impulse {
            model: input.label(),
            source,
        })?;
    own.extend(super::impulse::impulse_warnings(&impulse));
    let (measured, notes) = if request.measured.is_empty() {
        (None, Vec::new())
    } else {
        let frf = super::frf::run(
            None,
            &FrfRequest {
                records: FrfRecords::Files(request.measured.clone()),
                window: request.measured_window,
                band: request.measured_band,
                ..FrfRequest::default()
            },
        )?;
        (Some(frf.analysis), frf.document.warnings)
    };
    let (experiment, paper) = choose_experiment(model, &modal_output, measured.as_ref());
    // The mode taken as the experiment, checked against its records: a
    // poor fit is said, not printed as a frequency alone.
    let mut notes = notes;
    if let Some(a) = &measured {
        match measured_mode(a, &modal_output) {
            Pairing::FirstBending(j) => {
                notes.extend(crate::measured::experiment::check(a, j).warnings());
            }
            Pairing::OtherMode {
                index,
                model_hz,
                first_hz,
            } => notes.push(format!(
                "the measured mode nearest the model's first bending frequency ({first_hz:.3} Hz), {:.3} Hz, lies nearer the model's mode at {model_hz:.3} Hz: it measures that mode, and is not compared as the first bending; a fit band that holds the first bending peak measures it",
                a.fit.modes[index].frequency_hz
            )),
            Pairing::Nothing => notes.push(format!(
                "the fit of the measured records found no mode over {:.0}–{:.0} Hz: there is no measured first bending to compare with; a fit band that holds its peak measures it",
                a.band.0, a.band.1
            )),
        }
    }
    let calibration = match (request.calibrate, &experiment) {
        (true, Some(e)) => Some(
            super::calibrate::equivalent_height(model, e.frequency_hz).map_err(|source| {
                CommandError::Calibration {
                    model: input.label(),
                    source,
                }
            })?,
        ),
        (true, None) => return Err(CommandError::NoExperiment),
        _ => None,
    };
    let output = IdentifyOutput::new(
        model,
        modal_output,
        &impulse,
        measured.as_ref(),
        calibration.as_ref(),
    );
    // The records' notes name their files, not the model.
    let mut document = Run::of(input, output).warn(input, own);
    document.warnings.extend(notes);
    Ok(IdentifyRun {
        model: Arc::clone(model),
        system,
        modal,
        impulse,
        measured,
        paper,
        document,
    })
}
