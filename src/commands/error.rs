//! Why a command failed: the library's typed errors, with the model's
//! name where the analysis of a valid model failed. Messages name request
//! fields (`modes`), never a front end's flags or keywords; a front end
//! that wants its own name in front maps [`CommandError::Argument`].

use crate::error::{AnalysisError, ModelError, SimulationError};
use crate::measured::error::MeasuredError;
use crate::output::files::WriteError;
use crate::output::plot::PlotError;
use std::path::PathBuf;
// --- `frf` and `identify` ---
use crate::analysis::calibrate::CalibrationError;
use crate::analysis::impulse::ImpulseError;
use crate::error::TransientError;
use crate::results::fit::OverlayError;

/// A command's error.
#[derive(Debug, thiserror::Error)]
pub enum CommandError {
    /// The model (file) is bad.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// A request field out of its range: its name, the value and what is
    /// allowed.
    #[error("{name} `{value}`: {allowed}")]
    Argument {
        name: &'static str,
        value: String,
        allowed: String,
    },
    /// The analysis of a valid model failed.
    #[error("{model}")]
    Analysis {
        model: String,
        #[source]
        source: AnalysisError,
    },
    /// A simulation of a valid model failed (or its settings are bad).
    #[error("{model}")]
    Simulation {
        model: String,
        #[source]
        source: SimulationError,
    },
    /// A measurement or mode-set file is bad.
    #[error(transparent)]
    Measured(#[from] MeasuredError),
    /// Another mode set does not fit this model's (`other` is its file).
    #[error("{}: {why}", other.display())]
    OtherModes { other: PathBuf, why: String },
    /// An output file could not be written.
    #[error(transparent)]
    Write(#[from] WriteError),
    /// A figure could not be drawn or written.
    #[error(transparent)]
    Plot(#[from] PlotError),
    // --- `frf` and `identify` ---
    /// The model's FRF beside the measured one could not be computed
    /// (`model` names the model).
    #[error("{model}")]
    Overlay {
        model: String,
        #[source]
        source: OverlayError,
    },
    /// The time-integration settings are bad, or the integration failed.
    #[error(transparent)]
    Transient(#[from] TransientError),
    /// The impulse experiment on the model named `model` failed.
    #[error("{model}")]
    Impulse {
        model: String,
        #[source]
        source: ImpulseError,
    },
    /// A calibration failed.
    #[error(transparent)]
    Calibration(#[from] CalibrationError),
    /// `calibrate` was asked for without an experiment to fit to.
    #[error("calibrate needs an experiment: the model has no `reference` and no measured records were given")]
    NoExperiment,
    /// The output directory could not be created.
    #[error("{}: cannot create the output directory", dir.display())]
    OutputDir {
        dir: PathBuf,
        #[source]
        io: std::io::Error,
    },
}

impl CommandError {
    /// `e`, an analysis error of the model named `model`.
    pub fn analysis(model: impl Into<String>, e: AnalysisError) -> Self {
        CommandError::Analysis {
            model: model.into(),
            source: e,
        }
    }

    /// A request field out of range.
    pub fn argument(
        name: &'static str,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        CommandError::Argument {
            name,
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }

    /// Whether the error is the input's (bad model, file or argument) rather
    /// than a failed analysis of good input: Python's `ModelError` against
    /// `AnalysisError`.
    pub fn is_input(&self) -> bool {
        match self {
            CommandError::Model(_)
            | CommandError::Argument { .. }
            | CommandError::Measured(_)
            | CommandError::OtherModes { .. }
            | CommandError::Write(_)
            | CommandError::Plot(_) => true,
            CommandError::Simulation { source, .. } => matches!(
                source,
                SimulationError::InvalidPoint { .. }
                    | SimulationError::InvalidSetting { .. }
                    | SimulationError::ReleaseNeedsEquilibrium { .. }
            ),
            CommandError::Analysis { .. } => false,
            // --- `frf` and `identify` ---
            CommandError::Overlay { source, .. } => matches!(source, OverlayError::Frf(_)),
            CommandError::Transient(e) => transient_input(e),
            CommandError::Impulse { source, .. } => match source {
                ImpulseError::Transient(e) => transient_input(e),
                ImpulseError::Analysis(_)
                | ImpulseError::Spectrum(_)
                | ImpulseError::Dispersion(_) => false,
                _ => true,
            },
            CommandError::Calibration(e) => !matches!(
                e,
                CalibrationError::Analysis { .. }
                    | CalibrationError::Impulse { .. }
                    | CalibrationError::NotConverged { .. }
            ),
            CommandError::NoExperiment | CommandError::OutputDir { .. } => true,
        }
    }
}

// --- `frf` and `identify` ---
/// Whether a time integration's error is its settings' (bad input) rather
/// than a failed run.
fn transient_input(e: &TransientError) -> bool {
    matches!(
        e,
        TransientError::InvalidStep { .. }
            | TransientError::InvalidEndTime { .. }
            | TransientError::InvalidSpectralRadius { .. }
    )
}
