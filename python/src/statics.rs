//! `Model.static(...)` (the command line's `static`) and its result,
//! `ancf_modal.StaticResult`.
//!
//! A front end over [`ancf::commands::statics`].

use crate::errors::{compute, Failure};
use crate::model::PyModel;
use ancf::commands::statics::{run as statics, StaticRequest, StaticRun};
use numpy::PyArray1;
use pyo3::prelude::*;

/// The static equilibrium and its report.
#[pyclass(name = "StaticResult", module = "ancf_modal", frozen)]
pub struct PyStaticResult {
    run: StaticRun,
}

/// The static equilibrium of `model` under its loads × `load_scale`.
pub fn run(model: &PyModel, py: Python<'_>, load_scale: f64) -> PyResult<PyStaticResult> {
    let input = model.input();
    let request = StaticRequest { load_scale };
    let run = compute(py, move || statics(&input, &request).map_err(Failure::from))?;
    crate::warn(py, run.document.own_warnings())?;
    Ok(PyStaticResult { run })
}

#[pymethods]
impl PyStaticResult {
    /// The equilibrium's coordinates q, as `Model.coordinates()` names them
    /// [m, –, rad], positions about the model's centre of mass (the
    /// system's origin; `to_dict()` gives node positions in the model's
    /// frame).
    #[getter]
    fn q<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.equilibrium.q)
    }

    /// The constraint multipliers λ (C_qᵀλ is the joints' generalized
    /// force) [N, N m].
    #[getter]
    fn multipliers<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.equilibrium.lambda)
    }

    /// Final unbalanced force ‖Q_int − Q_ext + C_qᵀλ‖∞ [N, N m].
    #[getter]
    fn residual(&self) -> f64 {
        self.run.equilibrium.residual
    }

    /// The applied-load factor [–].
    #[getter]
    fn load_scale(&self) -> f64 {
        self.run.equilibrium.load_scale
    }

    /// The report as the library's JSON document (`static --json`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document())
    }

    /// The command line's report, then its `warning:` lines (the run's
    /// warnings, as `to_dict()["warnings"]`).
    fn __repr__(&self) -> String {
        crate::with_warnings(self.run.text(), &self.run.document.warnings)
    }
}
