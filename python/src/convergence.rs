//! `Model.convergence(...)` (the command line's `convergence`) and its
//! result, `ancf_modal.ConvergenceResult`: a front end over
//! [`ancf::commands::convergence`].

use crate::errors::{compute, Failure};
use crate::model::PyModel;
use ancf::commands::convergence::{run as convergence, ConvergenceRequest, ConvergenceRun};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use std::path::PathBuf;

/// The mesh convergence of the first bending frequencies.
#[pyclass(name = "ConvergenceResult", module = "ancf_modal", frozen)]
pub struct PyConvergenceResult {
    run: ConvergenceRun,
}

/// The convergence study of `model` (the command line's `convergence`).
pub fn run(
    model: &PyModel,
    py: Python<'_>,
    max_elements: i64,
    modes: i64,
) -> PyResult<PyConvergenceResult> {
    let whole = |name: &'static str, v: i64, lo: i64, hi: i64| {
        if (lo..=hi).contains(&v) {
            Ok(v as usize)
        } else {
            Err(Failure::argument(
                name,
                v,
                &format!("must be a whole number from {lo} to {hi}"),
            ))
        }
    };
    let request = ConvergenceRequest {
        max_elements: whole("max_elements", max_elements, 2, 256)?,
        modes: whole("modes", modes, 1, 10)?,
    };
    let input = model.input();
    let run = compute(py, move || {
        convergence(&input, &request).map_err(Failure::from)
    })?;
    crate::warn(py, run.document.own_warnings())?;
    Ok(PyConvergenceResult { run })
}

/// Rows of equal length as a 2-D array (modes × meshes).
fn matrix<'py>(
    py: Python<'py>,
    rows: &[Vec<f64>],
    columns: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    if rows.is_empty() {
        return Ok(PyArray2::zeros(py, [0, columns], false));
    }
    PyArray2::from_vec2(py, rows).map_err(|e| Failure::Analysis(e.to_string()).into())
}

#[pymethods]
impl PyConvergenceResult {
    /// Elements per beam of each mesh, ascending.
    #[getter]
    fn elements(&self) -> Vec<usize> {
        self.run.data.elements.clone()
    }

    /// Number of coordinates of each mesh.
    #[getter]
    fn coordinates(&self) -> Vec<usize> {
        self.run.data.coordinates.clone()
    }

    /// Reference frequency of each bending mode [Hz] (Euler–Bernoulli for a
    /// single free beam, else the finest mesh).
    #[getter]
    fn reference_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.data.reference_hz)
    }

    /// `frequencies_hz[k, i]`: bending mode k+1 at mesh i [Hz]; NaN when
    /// that mesh has fewer bending modes.
    #[getter]
    fn frequencies_hz<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        matrix(
            py,
            &self.run.data.frequencies_hz,
            self.run.data.elements.len(),
        )
    }

    /// `relative_errors[k, i] = |f_k(n_i) − f_k| / f_k` [–]; NaN where
    /// undefined (at the finest mesh when it is the reference).
    #[getter]
    fn relative_errors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        matrix(py, &self.run.data.errors, self.run.data.elements.len())
    }

    /// The result as the library's JSON document (`convergence --json`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document())
    }

    /// Draws the errors against the element count to `path` (.svg or
    /// .png), as `convergence --plot`.
    fn plot(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || self.run.write_plot(&path).map_err(Failure::from))
    }

    /// The command line's report, then its `warning:` lines (the run's
    /// warnings, as `to_dict()["warnings"]`).
    fn __repr__(&self) -> String {
        crate::with_warnings(self.run.text(), &self.run.document.warnings)
    }
}
