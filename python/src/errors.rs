//! Library errors as Python exceptions with the command line's one-line
//! message, its warnings' category, and the GIL-free, panic-safe way every
//! computation runs.

use pyo3::exceptions::{PyRuntimeError, PyUserWarning, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    ancf_modal,
    ModelError,
    PyValueError,
    "A bad model file, model parameter or argument value (the command line's `Error:` line)."
);
pyo3::create_exception!(
    ancf_modal,
    AnalysisError,
    PyRuntimeError,
    "An analysis that failed on a valid model: a solver failure, a loss of stability, an internal error."
);
pyo3::create_exception!(
    ancf_modal,
    ModelWarning,
    PyUserWarning,
    "A warning of the model or of a run (the command line's `warning:` lines): sizes that look like other units, a state that is not an equilibrium, beyond beam theory, a run that ended early, a note on measured records."
);

/// Why a computation failed, decided without the GIL and turned into a
/// Python exception after it.
#[derive(Debug)]
pub enum Failure {
    /// Bad input: model, parameter, argument, measurement file.
    Input(String),
    /// The analysis failed.
    Analysis(String),
}

impl Failure {
    /// A bad input, with its causes on one line.
    pub fn input(e: &(dyn std::error::Error + 'static)) -> Self {
        Failure::Input(one_line(e))
    }

    /// A failed analysis of the model `source` (the command line's
    /// `<file>: <message>`).
    pub fn analysis(source: &str, e: &(dyn std::error::Error + 'static)) -> Self {
        Failure::Analysis(format!("{source}: {}", one_line(e)))
    }

    /// A keyword argument's value out of its range, as the command line
    /// states a flag's: ``modes `0`: must be a whole number ≥ 1``.
    pub fn argument(name: &str, value: impl std::fmt::Display, why: &str) -> Self {
        Failure::Input(format!("{name} `{value}`: {why}"))
    }
}

impl From<ancf::commands::CommandError> for Failure {
    /// A command's error: bad input as `ModelError`, a failed analysis as
    /// `AnalysisError`, with the command line's one-line message.
    fn from(e: ancf::commands::CommandError) -> Self {
        // A simulation's setting names its keyword argument (`step: …`).
        if let ancf::commands::CommandError::Simulation { model, source } = &e {
            return simulation(model, source);
        }
        if e.is_input() {
            Failure::Input(one_line(&e))
        } else {
            Failure::Analysis(one_line(&e))
        }
    }
}

impl From<Failure> for PyErr {
    fn from(f: Failure) -> PyErr {
        match f {
            Failure::Input(m) => ModelError::new_err(m),
            Failure::Analysis(m) => AnalysisError::new_err(m),
        }
    }
}

/// The error and its causes on one line, `a: b: c`, leaving out a cause
/// whose text the line already holds (as the command line prints them).
pub fn one_line(e: &(dyn std::error::Error + 'static)) -> String {
    let mut line = String::new();
    let mut cause = Some(e);
    while let Some(c) = cause {
        let text = c.to_string();
        if !line.contains(&text) {
            if !line.is_empty() {
                line.push_str(": ");
            }
            line.push_str(&text);
        }
        cause = c.source();
    }
    line
}

/// Runs `f` with the GIL released, so other Python threads run meanwhile;
/// a panic in the library becomes an [`AnalysisError`], never pyo3's
/// `PanicException`.
pub fn compute<T, F>(py: Python<'_>, f: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce() -> Result<T, Failure> + Send,
{
    let result = py.detach(|| std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)));
    match result {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(failure)) => Err(failure.into()),
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| String::from("unknown cause"));
            Err(AnalysisError::new_err(format!(
                "internal error (a bug of ancf-modal, please report it): {what}"
            )))
        }
    }
}

/// A simulation's error: a setting or the tracked point names the keyword
/// argument (as the command line names its flag), a model that cannot be
/// released from the reference is a bad input, the rest failed runs; each
/// after the model's name `label`.
pub fn simulation(label: &str, e: &ancf::error::SimulationError) -> Failure {
    use ancf::error::{Setting, SimulationError};
    let argument = match e {
        SimulationError::InvalidPoint { .. } => Some("point"),
        SimulationError::InvalidSetting { setting, .. } => Some(match setting {
            Setting::Step => "step",
            Setting::EndTime => "end_time",
            Setting::Distance => "distance",
            Setting::Direction => "direction",
            Setting::SampleRate => "sample_rate",
        }),
        _ => None,
    };
    match (argument, e) {
        (Some(name), _) => Failure::Input(format!("{label}: {name}: {}", one_line(e))),
        (None, SimulationError::ReleaseNeedsEquilibrium { .. }) => {
            Failure::Input(format!("{label}: {}", one_line(e)))
        }
        _ => Failure::analysis(label, e),
    }
}
