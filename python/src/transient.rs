//! `Model.transient(...)` (the command line's `transient`) and its result,
//! `ancf_modal.TransientResult`.
//!
//! A front end over [`ancf::commands::transient`]: keyword arguments →
//! request → `run` → wrap; `to_dict()` is the run's document.

use crate::errors::{compute, Failure};
use crate::model::PyModel;
use ancf::commands::transient::{run as transient, TransientRequest, TransientRun};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// The transient of `model`.
pub fn run(
    model: &PyModel,
    py: Python<'_>,
    request: TransientRequest,
) -> PyResult<PyTransientResult> {
    let input = model.input();
    let run = compute(py, move || {
        transient(&input, &request).map_err(Failure::from)
    })?;
    crate::warn(py, run.document.own_warnings())?;
    Ok(PyTransientResult { run })
}

/// The result of `Model.transient`: the sensors' records, the contacts and
/// the energy balance.
#[pyclass(name = "TransientResult", module = "ancf_modal", frozen)]
pub struct PyTransientResult {
    run: TransientRun,
}

#[pymethods]
impl PyTransientResult {
    /// Sample times [s].
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.simulation.time)
    }

    /// Each sensor's samples by id [m, m/s or m/s², as the sensor measures].
    #[getter]
    fn sensors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (id, v) in &self.run.simulation.sensors {
            d.set_item(id, PyArray1::from_slice(py, v))?;
        }
        Ok(d)
    }

    /// The result as the library's JSON document (`transient --json`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document())
    }

    /// Writes the samples (time [s], each sensor, each contact's force
    /// [N]) as CSV to `path`, as `transient --csv`.
    fn write_csv(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || {
            ancf::output::files::write_atomic(&path, self.run.csv().as_bytes())
                .map_err(|e| Failure::input(&e))
        })
    }

    /// Writes the loads' and sensors' records as UFF 58 to `path`, as
    /// `transient --uff` (a run with `sample_rate` above 0: UFF 58 time
    /// data are evenly sampled).
    fn write_uff(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || {
            let text = self.run.uff().map_err(Failure::from)?;
            ancf::output::files::write_atomic(&path, text.as_bytes())
                .map_err(|e| Failure::input(&e))
        })
    }

    /// Draws each sensor against time to `path` (.svg or .png), as
    /// `transient --plot`.
    fn plot(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || self.run.write_plot(&path).map_err(Failure::from))
    }

    /// The command line's report, then its `warning:` lines (the run's
    /// warnings, as `to_dict()["warnings"]`).
    fn __repr__(&self) -> String {
        crate::with_warnings(self.run.text(), &self.run.document.warnings)
    }
}
