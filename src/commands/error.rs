//! Why a command failed: the library's typed errors, with the model's
//! name where the analysis of a valid model failed. Messages name request
//! fields (`modes`), never a front end's flags or keywords; a front end
//! that wants its own name in front maps [`CommandError::Argument`].

use crate::analysis::calibrate::CalibrationError;
use crate::analysis::impulse::ImpulseError;
use crate::analysis::sweep::SweepError;
use crate::error::{AnalysisError, ModelError, SimulationError, TransientError};
use crate::measured::error::MeasuredError;
use crate::output::files::WriteError;
use crate::output::plot::PlotError;
use std::path::PathBuf;
// --- `frf` and `identify` ---
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
    /// The reduction of a valid model failed.
    #[error("{model}")]
    Reduce {
        model: String,
        #[source]
        source: crate::analysis::reduce::ReduceError,
    },
    /// A simulation of a valid model failed (or its settings are bad).
    #[error("{model}")]
    Simulation {
        model: String,
        #[source]
        source: SimulationError,
    },
    /// The paper's Fig. 10 study does not apply to the model.
    #[error("{model}")]
    Study {
        model: String,
        #[source]
        source: Box<crate::analysis::switch_off_study::StudyError>,
    },
    /// A measurement or mode-set file is bad.
    #[error(transparent)]
    Measured(#[from] MeasuredError),
    /// Another mode set does not fit this model's (`other` is its file).
    #[error("{}: {why}", other.display())]
    OtherModes { other: PathBuf, why: String },
    /// A calibration to a transient failed.
    #[error("{model}")]
    TransientCalibration {
        model: String,
        #[source]
        source: Box<crate::analysis::calibrate::transient::TransientFitError>,
    },
    /// The model with every beam made rigid is not a valid model.
    #[error("{model}: the model with every beam rigid")]
    RigidBeams {
        model: String,
        #[source]
        source: crate::error::InvalidModel,
    },
    /// An output file could not be written.
    #[error(transparent)]
    Write(#[from] WriteError),
    /// A figure could not be drawn or written.
    #[error(transparent)]
    Plot(#[from] PlotError),
    // --- impulse, transient, switch-off, calibrate ---
    /// The time integration's settings do not fit together (an end time
    /// within one step), or the integration failed.
    #[error(transparent)]
    Integration(#[from] TransientError),
    /// The impulse experiment on the model named `model` failed, or the
    /// model cannot run it (no sensor, no hammer, a pulse too short for
    /// the step).
    #[error("{model}")]
    Impulse {
        model: String,
        #[source]
        source: ImpulseError,
    },
    /// The calibration of the model named `model` failed, or what it asks
    /// for is not there (a parameter, a mode, a target).
    #[error("{model}")]
    Calibration {
        model: String,
        #[source]
        source: CalibrationError,
    },
    // --- `frf` and `identify` ---
    /// The model's FRF beside the measured one could not be computed
    /// (`model` names the model).
    #[error("{model}")]
    Overlay {
        model: String,
        #[source]
        source: OverlayError,
    },
    /// `calibrate` was asked for without an experiment to fit to.
    #[error("calibrate needs an experiment: the model has no `reference` and no measured records were given")]
    NoExperiment,
    /// `calibrate` or `measured` asked of `report` for a model (named
    /// `model`) without the impulse experiment they need.
    #[error("{model}: calibrate and measured need the impulse experiment, and the model has no half-sine or step load")]
    NeedsImpulse { model: String },
    /// The output directory could not be created.
    #[error("{}: cannot create the output directory", dir.display())]
    OutputDir {
        dir: PathBuf,
        #[source]
        io: std::io::Error,
    },

    // `sweep`, `sweep-merge` (and `modal --sweep-load`):
    /// A request field that has no default was not given (`quantity`).
    #[error("{name} is required (one of: {one_of})")]
    Required { name: &'static str, one_of: String },
    /// The sweep's `params` (or its other settings) define no sweep.
    #[error("params")]
    SweepParams(#[source] SweepError),
    /// Shard documents that do not join into one sweep, or a document that
    /// is not a sweep's.
    #[error(transparent)]
    SweepMerge(#[from] SweepError),
    /// A file (a shard document) could not be read.
    #[error("{}: cannot read the file", file.display())]
    ReadFile {
        file: PathBuf,
        #[source]
        io: std::io::Error,
    },
    /// `calibrate`'s targets could not be taken from the `frf` document
    /// `file`.
    #[error("{}", file.display())]
    TargetsFrom {
        file: PathBuf,
        #[source]
        source: super::calibrate::TargetsFromError,
    },
    /// Points of a sweep failed (each is recorded in the document; the
    /// command line exits with an error after writing everything).
    #[error("{failed} of {total} points failed (first: point {index}: {message})")]
    PointsFailed {
        failed: usize,
        total: usize,
        index: usize,
        message: String,
    },
    /// A load sweep of a model without loads.
    #[error("the model has no loads to scale")]
    NoLoadsToScale,
}

impl CommandError {
    /// `e`, an analysis error of the model named `model`.
    pub fn analysis(model: impl Into<String>, e: AnalysisError) -> Self {
        CommandError::Analysis {
            model: model.into(),
            source: e,
        }
    }

    // --- impulse, transient, switch-off, calibrate ---
    /// `e`, a simulation error of the model named `model`.
    pub fn simulation(model: impl Into<String>, e: SimulationError) -> Self {
        CommandError::Simulation {
            model: model.into(),
            source: e,
        }
    }

    /// `e`, an impulse experiment's error on the model named `model`.
    pub fn impulse(model: impl Into<String>, e: ImpulseError) -> Self {
        CommandError::Impulse {
            model: model.into(),
            source: e,
        }
    }

    /// `e`, a calibration error of the model named `model`.
    pub fn calibration(model: impl Into<String>, e: CalibrationError) -> Self {
        CommandError::Calibration {
            model: model.into(),
            source: e,
        }
    }
    // --- end impulse, transient, switch-off, calibrate ---

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
            | CommandError::RigidBeams { .. }
            | CommandError::Study { .. }
            | CommandError::Plot(_) => true,
            CommandError::Simulation { source, .. } => matches!(
                source,
                SimulationError::InvalidPoint { .. }
                    | SimulationError::InvalidSetting { .. }
                    | SimulationError::ReleaseNeedsEquilibrium { .. }
            ),
            CommandError::Analysis { .. } => false,
            CommandError::Reduce { source, .. } => matches!(
                source,
                crate::analysis::reduce::ReduceError::InterfaceNotFree { .. }
                    | crate::analysis::reduce::ReduceError::NotHeld
            ),
            // --- impulse, transient, switch-off, calibrate ---
            CommandError::Integration(e) => transient_input(e),
            CommandError::Impulse { source, .. } => super::impulse::is_input(source),
            CommandError::Calibration { source, .. } => !matches!(
                source,
                CalibrationError::Analysis { .. }
                    | CalibrationError::Impulse { .. }
                    | CalibrationError::NotConverged { .. }
            ),
            CommandError::TransientCalibration { source, .. } => {
                use crate::analysis::calibrate::transient::TransientFitError as T;
                !matches!(
                    **source,
                    T::Point { .. }
                        | T::Unreachable { .. }
                        | T::Exhausted { .. }
                        | T::TrajectoryExhausted { .. }
                        | T::Jump { .. }
                )
            }
            // --- `frf` and `identify` ---
            CommandError::Overlay { source, .. } => matches!(source, OverlayError::Frf(_)),
            CommandError::NoExperiment
            | CommandError::NeedsImpulse { .. }
            | CommandError::OutputDir { .. } => true,
            // `sweep`, `sweep-merge`:
            CommandError::Required { .. }
            | CommandError::SweepParams(_)
            | CommandError::SweepMerge(_)
            | CommandError::ReadFile { .. }
            | CommandError::TargetsFrom { .. }
            | CommandError::NoLoadsToScale => true,
            CommandError::PointsFailed { .. } => false,
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
