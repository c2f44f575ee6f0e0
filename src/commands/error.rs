//! Why a command failed: the library's typed errors, with the model's
//! name where the analysis of a valid model failed. Messages name request
//! fields (`modes`), never a front end's flags or keywords; a front end
//! that wants its own name in front maps [`CommandError::Argument`].

use crate::analysis::sweep::SweepError;
use crate::error::{AnalysisError, ModelError, SimulationError};
use crate::measured::error::MeasuredError;
use crate::output::files::WriteError;
use crate::output::plot::PlotError;
use std::path::PathBuf;

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
            // `sweep`, `sweep-merge`:
            CommandError::Required { .. }
            | CommandError::SweepParams(_)
            | CommandError::SweepMerge(_)
            | CommandError::ReadFile { .. }
            | CommandError::NoLoadsToScale => true,
            CommandError::PointsFailed { .. } => false,
        }
    }
}
