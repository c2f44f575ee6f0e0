//! `Model.transient(...)` (the command line's `transient`) and its result,
//! `ancf_modal.TransientResult`.
//!
//! The document and the table are built once, where the run ends
//! ([`run`]): the one place for `to_dict()`.

use crate::errors::{compute, Failure};
use crate::model::PyModel;
use ancf::analysis::simulate::{simulate, SimulationSettings};
use ancf::analysis::transient::TransientSettings;
use ancf::System;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The integration's keyword arguments.
pub struct Request {
    pub end_time: f64,
    pub step: f64,
    pub spectral_radius: f64,
    pub from_equilibrium: bool,
    pub sample_rate: f64,
    pub rigid_beams: bool,
}

/// The transient of `model`.
pub fn run(model: &PyModel, py: Python<'_>, r: Request) -> PyResult<PyTransientResult> {
    for (name, v) in [("end_time", r.end_time), ("step", r.step)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(Failure::argument(name, v, "must be a number > 0").into());
        }
    }
    let rho = r.spectral_radius;
    if !(0.0..=1.0).contains(&rho) {
        return Err(
            Failure::argument("spectral_radius", rho, "must be a number from 0 to 1").into(),
        );
    }
    if !(r.sample_rate.is_finite() && r.sample_rate >= 0.0) {
        return Err(Failure::argument("sample_rate", r.sample_rate, "must be a number ≥ 0").into());
    }
    let shared = model.model.clone();
    let label = model.label();
    let sha256 = model.sha256.clone();
    compute(py, move || {
        let model = match r.rigid_beams {
            true => shared.all_beams_rigid().validated().map_err(|e| {
                Failure::Input(format!("{label}: the model with every beam rigid: {e}"))
            })?,
            false => (*shared).clone(),
        };
        let settings = SimulationSettings {
            transient: TransientSettings {
                step: r.step,
                end_time: r.end_time,
                spectral_radius: rho,
                damping: model.damping,
                ..TransientSettings::default()
            },
            from_equilibrium: r.from_equilibrium,
            sample_rate: r.sample_rate,
            keep_partial: false,
        };
        settings
            .transient
            .validate()
            .map_err(|e| Failure::Input(crate::errors::one_line(&e)))?;
        let sim = simulate(System::new(&model), &[], &settings)
            .map_err(|e| crate::errors::simulation(&label, &e))?;
        let document = crate::document(
            &ancf::results::TransientOutput::new(&model.name, &settings, &sim),
            None,
            Some(&sha256),
        );
        Ok(PyTransientResult {
            table: ancf::output::transient_report::transient_table(&model.name, &settings, &sim),
            document,
            time: sim.time,
            sensors: sim.sensors,
        })
    })
}

/// The result of `Model.transient`: the sensors' records, the contacts and
/// the energy balance.
#[pyclass(name = "TransientResult", module = "ancf_modal", frozen)]
pub struct PyTransientResult {
    time: Vec<f64>,
    sensors: Vec<(String, Vec<f64>)>,
    document: serde_json::Value,
    table: String,
}

#[pymethods]
impl PyTransientResult {
    /// Sample times [s].
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.time)
    }

    /// Each sensor's samples by id [m, m/s or m/s², as the sensor measures].
    #[getter]
    fn sensors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (id, v) in &self.sensors {
            d.set_item(id, PyArray1::from_slice(py, v))?;
        }
        Ok(d)
    }

    /// The result as the library's JSON document (`transient --json`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.document)
    }

    fn __repr__(&self) -> String {
        self.table.clone()
    }
}
