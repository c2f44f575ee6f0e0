//! `Model.calibrate(quantity="time_to_distance_s", target=…)` and
//! `Model.calibrate(trajectory=…)` (the command line's `calibrate
//! --quantity` / `--trajectory`) and their result,
//! `ancf_modal.TransientCalibrationResult`.
//!
//! A front end over [`ancf::commands::calibrate_transient`]: keyword
//! arguments → request → `run` → wrap; `to_dict()` is the run's document.

use crate::calibrate::by_name;
use crate::errors::{compute, Failure};
use crate::model::PyModel;
use ancf::analysis::calibrate::transient::Trajectory;
use ancf::commands::calibrate_transient::{
    run as calibrate, CalibrateTransientRequest, CalibrateTransientRun, TrajectoryInput,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// The transient calibration's keyword arguments.
pub struct Request<'py, 'a> {
    pub quantity: Option<String>,
    pub target: Option<f64>,
    pub trajectory: Option<&'a Bound<'py, PyAny>>,
    pub params: Option<&'a Bound<'py, PyAny>>,
    pub balance: Option<String>,
    pub tolerance: Option<f64>,
    pub max_evaluations: i64,
}

/// `trajectory`: a CSV file's path, or (t, x, y) sequences [s, m, m].
fn trajectory(t: &Bound<'_, PyAny>) -> PyResult<TrajectoryInput> {
    if let Ok(path) = t.extract::<PathBuf>() {
        return Ok(TrajectoryInput::File(path));
    }
    let (time_s, x_m, y_m) = t.extract::<(Vec<f64>, Vec<f64>, Vec<f64>)>().map_err(|_| {
        Failure::argument(
            "trajectory",
            t.get_type()
                .name()
                .map_or_else(|_| String::from("?"), |n| n.to_string()),
            "must be a CSV file's path or (t, x, y) sequences of numbers [s, m, m]",
        )
    })?;
    Ok(TrajectoryInput::Samples(Trajectory {
        label: String::from("(the samples given)"),
        time_s,
        x_m,
        y_m,
    }))
}

/// Fits the model's parameters to a switch-off time or trajectory.
pub fn run(
    model: &PyModel,
    py: Python<'_>,
    r: Request<'_, '_>,
) -> PyResult<PyTransientCalibrationResult> {
    let max_evaluations = crate::calibrate::max_evaluations(r.max_evaluations)?;
    let request = CalibrateTransientRequest {
        quantity: r.quantity,
        target_s: r.target,
        trajectory: r.trajectory.map(trajectory).transpose()?,
        params: crate::calibrate::parameter_specs(r.params)?,
        balance: r.balance,
        tolerance_s: r.tolerance,
        max_evaluations,
        ..CalibrateTransientRequest::default()
    };
    let input = model.input();
    let run = compute(py, move || {
        calibrate(&input, &request).map_err(Failure::from)
    })?;
    crate::warn(py, run.document.own_warnings())?;
    Ok(PyTransientCalibrationResult {
        source: model.source.clone(),
        run,
    })
}

/// The result of a transient `Model.calibrate`: the fitted parameters,
/// their standard errors (a trajectory fit), and the fitted model.
#[pyclass(name = "TransientCalibrationResult", module = "ancf_modal", frozen)]
pub struct PyTransientCalibrationResult {
    source: ancf::error::Source,
    run: CalibrateTransientRun,
}

#[pymethods]
impl PyTransientCalibrationResult {
    /// `time_to_distance_s` or `trajectory`.
    #[getter]
    fn quantity(&self) -> &'static str {
        self.run.result.quantity
    }

    /// The fitted values by parameter name [SI units of each parameter].
    #[getter]
    fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let p = &self.run.result.parameters;
        by_name(py, p.iter().map(|p| (p.name.as_str(), p.fitted)))
    }

    /// Each parameter's standard error [SI], from the least-squares
    /// Jacobian and residual (a trajectory fit); None for a time fit.
    #[getter]
    fn standard_errors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let c = &self.run.result.calibrated;
        by_name(py, c.iter().map(|c| (c.name.as_str(), c.standard_error)))
    }

    /// The time to distance of the starting and of the fitted model [s]
    /// (None: not reached), at the fit's fixed step.
    #[getter]
    fn initial_time_s(&self) -> Option<f64> {
        self.run.result.initial_time_s
    }

    #[getter]
    fn achieved_time_s(&self) -> Option<f64> {
        self.run.result.achieved_time_s
    }

    /// The rms misfit of a trajectory fit at the fit [m] (None: a time fit).
    #[getter]
    fn rms_m(&self) -> Option<f64> {
        self.run.result.rms_m
    }

    /// Switch-off experiments run.
    #[getter]
    fn evaluations(&self) -> usize {
        self.run.result.history.len()
    }

    /// The calibrated model (what `calibrate --out` writes).
    #[getter]
    fn fitted_model(&self) -> PyModel {
        PyModel::made(self.run.result.fitted_model.clone(), &self.source)
    }

    /// The result as the library's JSON document (`calibrate --quantity …
    /// --json`): `calibrated [{name, value, target, achieved,
    /// standard_error}]` says what was fitted, to what, and how well.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document())
    }

    /// The command line's report, then its `warning:` lines.
    fn __repr__(&self) -> String {
        crate::with_warnings(self.run.text(), &self.run.document.warnings)
    }
}
