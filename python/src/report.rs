//! `Model.report(...)` (the command line's `report`): one self-contained
//! HTML file. A front end over [`ancf::commands::report`]: keyword
//! arguments → request → `run` → write.

use crate::errors::{compute, Failure};
use crate::model::PyModel;
use ancf::commands::report::{run as report, ReportRequest};
use pyo3::prelude::*;
use std::path::PathBuf;

/// The provenance's "command line" of a report asked for from Python:
/// the call and the package's version.
pub fn provenance(call: &str) -> String {
    format!(
        "{call} (Python package ancf_modal {})",
        ancf::results::provenance::tool_version()
    )
}

/// Writes the report of `model` to `out`; `identify` holds the impulse
/// experiment's and the comparison's keyword arguments.
pub fn run(
    model: &PyModel,
    py: Python<'_>,
    out: PathBuf,
    prestress: bool,
    identify: crate::identify::Request<'_>,
) -> PyResult<()> {
    let request = ReportRequest {
        out,
        prestress,
        identify: identify.into_request()?,
        command_line: provenance("Model.report"),
    };
    let input = model.input();
    let page = compute(py, || {
        let page = report(&input, &request).map_err(Failure::from)?;
        page.write().map_err(Failure::from)?;
        Ok(page)
    })?;
    crate::identify::warn_own(py, model, page.own_warnings())
}
