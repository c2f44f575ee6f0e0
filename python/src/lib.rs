//! The Python package `ancf_modal`: its extension module `ancf_modal._native`
//! over the library (convert → call → wrap). Every computation runs with the
//! GIL released ([`errors::compute`]); library errors arrive as
//! `ancf_modal.ModelError` / `ancf_modal.AnalysisError` with the command
//! line's one-line message, warnings as `ancf_modal.ModelWarning`.

mod builtin;
mod calibrate;
mod calibrate_transient;
mod convergence;
mod errors;
mod frf;
mod identify;
mod impulse;
mod matrices;
mod modal;
mod model;
mod reduce;
mod report;
mod statics;
mod sweep;
mod sweep_dask;
mod switch_off;
mod transient;

use pyo3::prelude::*;

/// Raises each of `texts` as `ancf_modal.ModelWarning` (a `UserWarning`):
/// the command line's `warning:` lines, the model's when it is read and a
/// run's own when the call that ran it returns. Stack level 1 is the
/// Python frame that called the extension (the methods are native): the
/// warning points at the user's call.
pub(crate) fn warn(py: Python<'_>, texts: &[String]) -> PyResult<()> {
    let category = py.get_type::<errors::ModelWarning>();
    for t in texts {
        // A C string ends at a NUL: one inside the text (an id may hold
        // `\u0000`) is written out.
        let message = std::ffi::CString::new(t.replace('\0', "\\0"))
            .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
        PyErr::warn(py, &category, &message, 1)?;
    }
    Ok(())
}

/// A result's `repr`: `text` (the command line's report) followed by one
/// `warning: …` line per warning of the run, as the command line's
/// terminal shows them after the report; `text` alone without warnings.
pub(crate) fn with_warnings(text: String, warnings: &[String]) -> String {
    use std::fmt::Write;
    let mut s = text;
    if !warnings.is_empty() && !s.is_empty() && !s.ends_with('\n') {
        s.push('\n');
    }
    for w in warnings {
        let _ = writeln!(s, "warning: {w}");
    }
    s
}

/// A JSON document as Python objects (dicts, lists, floats …): what every
/// result's `to_dict()` returns.
pub(crate) fn json_to_python<'py>(
    py: Python<'py>,
    doc: &serde_json::Value,
) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (doc.to_string(),))
}

/// Panics inside [`errors::compute`] (for the test suite: a panic in the
/// library must arrive as `AnalysisError`).
#[pyfunction]
fn _panic(py: Python<'_>, message: String) -> PyResult<()> {
    errors::compute(py, move || -> Result<(), errors::Failure> {
        panic!("{message}")
    })
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", ancf::results::provenance::tool_version())?;
    m.add("ModelError", py.get_type::<errors::ModelError>())?;
    m.add("AnalysisError", py.get_type::<errors::AnalysisError>())?;
    m.add("ModelWarning", py.get_type::<errors::ModelWarning>())?;
    m.add_class::<model::PyModel>()?;
    m.add_class::<modal::PyModalResult>()?;
    m.add_class::<frf::PyFrfResult>()?;
    m.add_class::<impulse::PyImpulseResult>()?;
    m.add_class::<statics::PyStaticResult>()?;
    m.add_class::<calibrate::PyCalibrationResult>()?;
    m.add_class::<calibrate_transient::PyTransientCalibrationResult>()?;
    m.add_class::<convergence::PyConvergenceResult>()?;
    m.add_class::<sweep::PySweepResult>()?;
    m.add_class::<switch_off::PySwitchOffResult>()?;
    m.add_class::<transient::PyTransientResult>()?;
    m.add_class::<identify::PyIdentifyResult>()?;
    m.add_class::<reduce::PyReducedBody>()?;
    m.add_function(wrap_pyfunction!(sweep::sweep_function, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_merge_function, m)?)?;
    m.add_function(wrap_pyfunction!(frf::frf, m)?)?;
    m.add_function(wrap_pyfunction!(_panic, m)?)?;
    m.add_function(wrap_pyfunction!(frf::frf_files, m)?)?;
    Ok(())
}
