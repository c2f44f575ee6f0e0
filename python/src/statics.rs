//! `Model.static(...)` (the command line's `static`) and its result,
//! `ancf_modal.StaticResult`.
//!
//! [`PyStaticResult::document`] is the one place that builds `to_dict()`.

use crate::errors::{compute, Failure};
use crate::model::{equilibrium, finite, PyModel};
use ancf::analysis::statics::Equilibrium;
use ancf::output::static_report::{static_report, static_table, StaticReport};
use ancf::System;
use numpy::PyArray1;
use pyo3::prelude::*;

/// The static equilibrium and its report.
#[pyclass(name = "StaticResult", module = "ancf_modal", frozen)]
pub struct PyStaticResult {
    sha256: String,
    equilibrium: Equilibrium,
    report: StaticReport,
}

/// The static equilibrium of `model` under its loads × `load_scale`.
pub fn run(model: &PyModel, py: Python<'_>, load_scale: f64) -> PyResult<PyStaticResult> {
    let load_scale = finite("load_scale", load_scale)?;
    let shared = model.model.clone();
    let label = model.label();
    let (equilibrium, report) = compute(py, move || {
        let system = System::new(&shared);
        let eq = equilibrium(&label, &system, load_scale)?;
        let report = static_report(&shared, &system, &eq);
        Ok::<_, Failure>((eq, report))
    })?;
    Ok(PyStaticResult {
        sha256: model.sha256.clone(),
        equilibrium,
        report,
    })
}

impl PyStaticResult {
    /// The document `static --json` prints: the typed report
    /// ([`ancf::results::StaticReport`]) with the provenance block.
    fn document(&self) -> serde_json::Value {
        crate::document(&self.report, None, Some(&self.sha256))
    }
}

#[pymethods]
impl PyStaticResult {
    /// The equilibrium's coordinates q, as `Model.coordinates()` names them
    /// [m, –, rad], positions about the model's centre of mass (the
    /// system's origin; `to_dict()` gives node positions in the model's
    /// frame).
    #[getter]
    fn q<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.equilibrium.q)
    }

    /// The constraint multipliers λ (C_qᵀλ is the joints' generalized
    /// force) [N, N m].
    #[getter]
    fn multipliers<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.equilibrium.lambda)
    }

    /// Final unbalanced force ‖Q_int − Q_ext + C_qᵀλ‖∞ [N, N m].
    #[getter]
    fn residual(&self) -> f64 {
        self.equilibrium.residual
    }

    /// The applied-load factor [–].
    #[getter]
    fn load_scale(&self) -> f64 {
        self.equilibrium.load_scale
    }

    /// The report as the library's JSON document (`static --json`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.document())
    }

    fn __repr__(&self) -> String {
        static_table(&self.report)
    }
}
