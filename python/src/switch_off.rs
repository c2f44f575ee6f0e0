//! `Model.switch_off(...)` (the command line's `switch-off`) and its
//! result, `ancf_modal.SwitchOffResult`.
//!
//! A front end over [`ancf::commands::switch_off`]: keyword arguments →
//! request → `run` → wrap; `to_dict()` is the run's document.

use crate::errors::{compute, Failure};
use crate::model::PyModel;
use ancf::analysis::switch_off::SwitchOffRun as Motion;
use ancf::commands::switch_off::{parse_point, run as switch_off, SwitchOffRequest, SwitchOffRun};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

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
    pub fig10: bool,
}

/// The switch-off of `model`.
pub fn run(model: &PyModel, py: Python<'_>, r: Request<'_>) -> PyResult<PySwitchOffResult> {
    let point = r
        .point
        .map(|text| parse_point(text).map_err(|why| Failure::argument("point", text, &why)))
        .transpose()?;
    let request = SwitchOffRequest {
        end_time: r.end_time,
        step: r.step,
        distance: r.distance,
        direction: [r.direction.0, r.direction.1],
        point,
        sample_rate: r.sample_rate,
        compare_rigid: r.compare_rigid,
        no_step_check: r.no_step_check,
        fig10: r.fig10,
    };
    let input = model.input();
    let label = model.label();
    let run = compute(py, move || {
        switch_off(&input, &request).map_err(Failure::from)
    })?;
    // The analysis's own warnings (a run that ended early) as Python
    // warnings; `to_dict()["warnings"]` and `warnings` hold them too.
    let own: Vec<String> = run
        .result
        .warnings
        .iter()
        .map(|w| format!("{label}: {w}"))
        .collect();
    crate::warn(py, &own)?;
    Ok(PySwitchOffResult { run })
}

/// The result of `Model.switch_off`: the tracked point's motion, the time
/// to the distance, contacts, released loads and the energy balance.
#[pyclass(name = "SwitchOffResult", module = "ancf_modal", frozen)]
pub struct PySwitchOffResult {
    run: SwitchOffRun,
}

impl PySwitchOffResult {
    fn flexible(&self) -> &Motion {
        &self.run.result.flexible
    }
}

#[pymethods]
impl PySwitchOffResult {
    /// Time for the tracked point to travel `distance` along `direction`
    /// [s]; None when it does not within the end time.
    #[getter]
    fn time_to_distance_s(&self) -> Option<f64> {
        self.flexible().time_to_distance_s
    }

    /// Sample times [s].
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.flexible().time_s)
    }

    /// The tracked point's x [m] in the model's frame.
    #[getter]
    fn x<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.flexible().x_m)
    }

    /// The tracked point's y [m] in the model's frame.
    #[getter]
    fn y<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.flexible().y_m)
    }

    /// Each released load's magnitude at the sample times [N], by label.
    #[getter]
    fn released_loads<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (label, f) in &self.flexible().released_loads {
            d.set_item(label, PyArray1::from_slice(py, f))?;
        }
        Ok(d)
    }

    /// The same model with every beam rigid: its time to the distance [s]
    /// (`compare_rigid=True`; else None).
    #[getter]
    fn rigid_time_to_distance_s(&self) -> Option<f64> {
        self.run
            .result
            .rigid
            .as_ref()
            .and_then(|r| r.time_to_distance_s)
    }

    /// The time to the distance at half the step [s] (the discretization
    /// check; None with `no_step_check=True`).
    #[getter]
    fn half_step_time_to_distance_s(&self) -> Option<f64> {
        self.run.result.half_step_time_s
    }

    /// The paper's Fig. 10 study (`fig10=True`) as a dict: `rows` (each
    /// change's `time_to_distance_s`, `ratio_to_reference`, `paper`),
    /// `combined_ratio` beside `paper_combined_ratio`, `calibrated`; every
    /// time a prediction. None without it.
    #[getter]
    fn fig10<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.run
            .study
            .as_ref()
            .map(|s| {
                let value = serde_json::to_value(s).expect("the study serializes");
                crate::json_to_python(py, &value)
            })
            .transpose()
    }

    /// Things the reader must know (a run that ended early).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.run.result.warnings.clone()
    }

    /// The result as the library's JSON document (`switch-off --json`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document())
    }

    /// Writes the tracked point's samples as CSV to `path`, as
    /// `switch-off --csv`.
    fn write_csv(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || {
            ancf::output::files::write_atomic(&path, self.run.csv().as_bytes())
                .map_err(|e| Failure::input(&e))
        })
    }

    /// Draws the travel against time to `path` (.svg or .png) and the
    /// trajectory beside it as `path`'s stem + `.trajectory.<ext>`, as
    /// `switch-off --plot`.
    fn plot(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || self.run.write_plot(&path).map_err(Failure::from))
    }

    /// The command line's report (its own warnings among its lines), then
    /// its `warning:` lines (the model's).
    fn __repr__(&self) -> String {
        crate::with_warnings(self.run.text(), &self.run.document.warnings)
    }
}
