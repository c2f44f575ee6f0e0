//! The command layer: one request and one `run` per command, under every
//! front end.
//!
//! Each command is a plain request struct with [`Default`] (the defaults
//! live there and nowhere else) and a function
//! `run(&ModelInput, &Request) -> Result<Output, CommandError>`. The output
//! is typed and carries the run's warnings, each named by the model's
//! source; [`Run::document`] gives the `--json` document with its
//! provenance block. The command line (clap) and the Python package (pyo3)
//! only map their arguments to a request and render or wrap the output:
//! what a command computes is written once, here.
//!
//! | command | request | output |
//! |---|---|---|
//! | `modal` | [`modal::ModalRequest`] | [`modal::ModalRun`] |
//! | `static` | [`statics::StaticRequest`] | [`statics::StaticRun`] |
//! | `convergence` | [`convergence::ConvergenceRequest`] | [`convergence::ConvergenceRun`] |
//! | `impulse` | [`impulse::ImpulseRequest`] | [`impulse::ImpulseRun`] |
//! | `transient` | [`transient::TransientRequest`] | [`transient::TransientRun`] |
//! | `switch-off` | [`switch_off::SwitchOffRequest`] | [`switch_off::SwitchOffRun`] |
//! | `calibrate` | [`calibrate::CalibrateRequest`] | [`calibrate::CalibrateRun`] |
//! | `frf` | [`frf::FrfRequest`] | [`frf::FrfRun`] |
//! | `identify` | [`identify::IdentifyRequest`] | [`identify::IdentifyRun`] |
//! | `sweep` | [`sweep::SweepRequest`] | [`sweep::SweepRun`] |
//! | `reduce` | [`reduce::ReduceRequest`] | [`reduce::ReduceRun`] |
//! | `sweep-merge` | [`sweep_merge::SweepMergeRequest`] | [`sweep::SweepRun`] |

pub mod convergence;
pub mod error;
pub mod frf;
pub mod identify;
pub mod input;
pub mod modal;
pub mod reduce;
pub mod report;
pub mod statics;
// impulse, transient, switch-off, calibrate
pub mod calibrate;
pub mod calibrate_transient;
pub mod checks;
pub mod impulse;
pub mod switch_off;
pub mod transient;
// sweep, sweep-merge:
pub mod sweep;
pub mod sweep_merge;

pub use error::CommandError;
pub use input::ModelInput;

use serde::Serialize;

/// A command's typed document with the warnings of its run and the hash of
/// the model it ran on: what `--json` prints and `to_dict()` returns.
#[derive(Debug, Clone)]
pub struct Run<T> {
    /// The typed document ([`crate::results`]).
    pub output: T,
    /// The run's warnings, one sentence each, named by the model's source:
    /// the model's unit warnings first, then the analysis's own.
    pub warnings: Vec<String>,
    /// SHA-256 of the model's bytes, for the provenance; `None` where no
    /// model is involved.
    pub model_sha256: Option<String>,
    /// How many of the first `warnings` are about the model itself (its
    /// units), given when it was read; the rest are the analysis's own.
    pub model_warnings: usize,
}

impl<T: Serialize> Run<T> {
    /// The document: the typed output with the provenance block
    /// (`tool_version`, `model_sha256`, `warnings`).
    pub fn document(&self) -> serde_json::Value {
        crate::results::document(&self.output, self.model_sha256.as_deref(), &self.warnings)
            .unwrap_or_else(|e| serde_json::Value::String(format!("unserializable result: {e}")))
    }
}

impl<T> Run<T> {
    /// The analysis's own warnings (those about the model aside).
    pub fn own_warnings(&self) -> &[String] {
        &self.warnings[self.model_warnings.min(self.warnings.len())..]
    }

    /// A run of `input`'s model with its unit warnings, before the
    /// analysis adds its own ([`Run::warn`]).
    pub fn of(input: &ModelInput, output: T) -> Self {
        let warnings = input.unit_warnings();
        Run {
            output,
            model_warnings: warnings.len(),
            warnings,
            model_sha256: Some(input.sha256.clone()),
        }
    }

    /// Adds the analysis's own warnings, each named by `input`'s source.
    pub fn warn(mut self, input: &ModelInput, texts: impl IntoIterator<Item = String>) -> Self {
        let label = input.label();
        self.warnings
            .extend(texts.into_iter().map(|w| format!("{label}: {w}")));
        self
    }
}
