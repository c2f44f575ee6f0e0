//! `Model.switch_off(...)` (the command line's `switch-off`) and its
//! result, `ancf_modal.SwitchOffResult`.
//!
//! [`PySwitchOffResult::document`] is the one place that builds
//! `to_dict()`.

use crate::errors::{compute, Failure};
use crate::model::PyModel;
use ancf::analysis::switch_off::{
    run_switch_off, SwitchOffResult, SwitchOffRun, SwitchOffSettings,
};
use ancf::model::PointSpec;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `BEAM:S` (arc length [m]) or `BODY`, as the command line's `--point`.
fn point(text: &str) -> Result<PointSpec, Failure> {
    match text.split_once(':') {
        Some((beam, arc)) => {
            let s = arc
                .trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    Failure::argument("point", text, &format!("`{arc}` is not an arc length in m"))
                })?;
            Ok(PointSpec {
                beam: Some(beam.to_string()),
                s: Some(s),
                ..PointSpec::default()
            })
        }
        None => Ok(PointSpec {
            body: Some(text.to_string()),
            ..PointSpec::default()
        }),
    }
}

/// The experiment's keyword arguments.
pub struct Request<'a> {
    pub end_time: f64,
    pub step: f64,
    pub distance: f64,
    pub direction: (f64, f64),
    pub point: Option<&'a str>,
    pub sample_rate: f64,
    pub compare_rigid: bool,
    pub no_step_check: bool,
}

/// The switch-off of `model`.
pub fn run(model: &PyModel, py: Python<'_>, r: Request<'_>) -> PyResult<PySwitchOffResult> {
    for (name, v) in [
        ("end_time", r.end_time),
        ("step", r.step),
        ("distance", r.distance),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(Failure::argument(name, v, "must be a number > 0").into());
        }
    }
    if !(r.sample_rate.is_finite() && r.sample_rate >= 0.0) {
        return Err(Failure::argument("sample_rate", r.sample_rate, "must be a number ≥ 0").into());
    }
    let (dx, dy) = r.direction;
    if !(dx.is_finite() && dy.is_finite()) {
        return Err(
            Failure::argument("direction", format!("({dx}, {dy})"), "must be finite").into(),
        );
    }
    let settings = SwitchOffSettings {
        step: r.step,
        end_time: r.end_time,
        sample_rate: r.sample_rate,
        distance: r.distance,
        direction: [dx, dy],
        point: r.point.map(point).transpose()?,
        compare_rigid: r.compare_rigid,
        halve_step: !r.no_step_check,
        ..SwitchOffSettings::default()
    };
    let shared = model.model.clone();
    let label = model.label();
    let result = compute(py, move || {
        run_switch_off(&shared, &settings).map_err(|e| crate::errors::simulation(&label, &e))
    })?;
    Ok(PySwitchOffResult {
        sha256: model.sha256.clone(),
        result,
    })
}

/// The result of `Model.switch_off`: the tracked point's motion, the time
/// to the distance, contacts, released loads and the energy balance.
#[pyclass(name = "SwitchOffResult", module = "ancf_modal", frozen)]
pub struct PySwitchOffResult {
    sha256: String,
    result: SwitchOffResult,
}

impl PySwitchOffResult {
    /// The document `switch-off --json` prints: the typed result
    /// ([`ancf::results::SwitchOffOutput`]) with the provenance block.
    fn document(&self) -> serde_json::Value {
        crate::document(
            &ancf::results::SwitchOffOutput::new(&self.result),
            None,
            Some(&self.sha256),
        )
    }

    fn rigid_run(&self) -> Option<&SwitchOffRun> {
        self.result.rigid.as_ref()
    }
}

#[pymethods]
impl PySwitchOffResult {
    /// Time for the tracked point to travel `distance` along `direction`
    /// [s]; None when it does not within the end time.
    #[getter]
    fn time_to_distance_s(&self) -> Option<f64> {
        self.result.flexible.time_to_distance_s
    }

    /// Sample times [s].
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.flexible.time_s)
    }

    /// The tracked point's x [m] in the model's frame.
    #[getter]
    fn x<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.flexible.x_m)
    }

    /// The tracked point's y [m] in the model's frame.
    #[getter]
    fn y<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.flexible.y_m)
    }

    /// Each released load's magnitude at the sample times [N], by label.
    #[getter]
    fn released_loads<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (label, f) in &self.result.flexible.released_loads {
            d.set_item(label, PyArray1::from_slice(py, f))?;
        }
        Ok(d)
    }

    /// The same model with every beam rigid: its time to the distance [s]
    /// (`compare_rigid=True`; else None).
    #[getter]
    fn rigid_time_to_distance_s(&self) -> Option<f64> {
        self.rigid_run().and_then(|r| r.time_to_distance_s)
    }

    /// The time to the distance at half the step [s] (the discretization
    /// check; None with `no_step_check=True`).
    #[getter]
    fn half_step_time_to_distance_s(&self) -> Option<f64> {
        self.result.half_step_time_s
    }

    /// Things the reader must know (a run that ended early).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.result.warnings.clone()
    }

    /// The result as the library's JSON document (`switch-off --json`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.document())
    }

    fn __repr__(&self) -> String {
        ancf::output::switch_off_report::switch_off_table(&self.result)
    }
}
