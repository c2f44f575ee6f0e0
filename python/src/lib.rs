//! The Python package `ancf_modal`: its extension module `ancf_modal._native`
//! over the library (convert → call → wrap). Every computation runs with the
//! GIL released ([`errors::compute`]); library errors arrive as
//! `ancf_modal.ModelError` / `ancf_modal.AnalysisError` with the command
//! line's one-line message.

mod builtin;
mod errors;
mod frf;
mod matrices;
mod modal;
mod model;

use pyo3::prelude::*;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", ancf::output::provenance::tool_version())?;
    m.add("ModelError", py.get_type::<errors::ModelError>())?;
    m.add("AnalysisError", py.get_type::<errors::AnalysisError>())?;
    m.add_class::<model::PyModel>()?;
    m.add_class::<modal::PyModalResult>()?;
    m.add_class::<frf::PyFrfResult>()?;
    m.add_function(wrap_pyfunction!(frf::frf, m)?)?;
    m.add_function(wrap_pyfunction!(frf::frf_files, m)?)?;
    Ok(())
}
