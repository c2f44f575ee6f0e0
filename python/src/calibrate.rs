//! `Model.calibrate(...)` (the command line's `calibrate`, by the
//! eigenvalue or the impulse method) and its result,
//! `ancf_modal.CalibrationResult`.
//!
//! A front end over [`ancf::commands::calibrate`]: keyword arguments →
//! request → `run` → wrap; `to_dict()` is the run's document.

use crate::errors::{compute, one_line, Failure};
use crate::impulse::Experiment;
use crate::model::{choice, PyModel};
use ancf::analysis::calibrate::{CalibrationError, ParameterSpec};
use ancf::commands::calibrate::{
    run as calibrate, CalibrateRequest, CalibrateRun, Method, TargetKind,
};
use ancf::commands::CommandError;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use std::path::PathBuf;

/// `params`: a name, a list of names, or {name: (lower, upper) or None};
/// none: the command's default.
pub(crate) fn parameter_specs(params: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<ParameterSpec>> {
    let Some(params) = params else {
        return Ok(Vec::new());
    };
    if let Ok(name) = params.cast::<PyString>() {
        return Ok(vec![ParameterSpec::named(name.to_cow()?.into_owned())]);
    }
    if let Ok(d) = params.cast::<PyDict>() {
        return d
            .iter()
            .map(|(k, v)| {
                Ok(ParameterSpec {
                    name: k.extract()?,
                    bounds: v.extract::<Option<(f64, f64)>>()?,
                })
            })
            .collect();
    }
    let names: Vec<String> = params.extract()?;
    Ok(names.into_iter().map(ParameterSpec::named).collect())
}

/// `target_hz`: one frequency or a sequence of them; none: the model's
/// reference.
fn targets(target_hz: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<f64>> {
    match target_hz {
        None => Ok(Vec::new()),
        Some(t) => match t.extract::<f64>() {
            Ok(f) => Ok(vec![f]),
            Err(_) => t.extract::<Vec<f64>>(),
        },
    }
}

/// `max_evaluations` as a count (the command checks its range).
pub(crate) fn max_evaluations(n: i64) -> Result<usize, Failure> {
    usize::try_from(n).map_err(|_| {
        Failure::argument(
            "max_evaluations",
            n,
            "must be a whole number from 2 to 10000",
        )
    })
}

/// {name: value} of a fit's parameters, in their order.
pub(crate) fn by_name<'py, 'a, V: IntoPyObject<'py>>(
    py: Python<'py>,
    items: impl Iterator<Item = (&'a str, V)>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, value) in items {
        d.set_item(name, value)?;
    }
    Ok(d)
}

/// The calibration's keyword arguments.
pub struct Request<'py, 'a> {
    pub target_hz: Option<&'a Bound<'py, PyAny>>,
    pub params: Option<&'a Bound<'py, PyAny>>,
    pub mode_kind: &'a str,
    pub mode: Option<Vec<i64>>,
    pub keep_mass: bool,
    pub prestress: bool,
    pub tolerance: Option<f64>,
    pub max_evaluations: i64,
    pub method: &'a str,
    pub experiment: Experiment<'a>,
    pub target_from: Option<PathBuf>,
}

/// Fits the model's parameters to measured frequencies.
pub fn run(model: &PyModel, py: Python<'_>, r: Request<'_, '_>) -> PyResult<PyCalibrationResult> {
    let mode_kind = match choice("mode_kind", r.mode_kind, &["bending", "axial", "spring"])? {
        "axial" => TargetKind::Axial,
        "spring" => TargetKind::Spring,
        _ => TargetKind::Bending,
    };
    let method = match choice("method", r.method, &["eigen", "impulse"])? {
        "impulse" => Method::Impulse,
        _ => Method::Eigen,
    };
    let mut modes = Vec::new();
    for n in r.mode.unwrap_or_default() {
        match usize::try_from(n) {
            Ok(n) if n >= 1 => modes.push(n),
            _ => return Err(Failure::argument("mode", n, "must be a whole number ≥ 1").into()),
        }
    }
    let max_evaluations = max_evaluations(r.max_evaluations)?;
    let request = CalibrateRequest {
        targets_hz: targets(r.target_hz)?,
        target_from: r.target_from,
        params: parameter_specs(r.params)?,
        keep_mass: r.keep_mass,
        mode_kind,
        modes,
        method,
        tolerance: r.tolerance,
        max_evaluations,
        experiment: r.experiment.request()?,
        prestress: r.prestress,
    };
    let input = model.input();
    let run = compute(py, move || calibrate(&input, &request).map_err(failure))?;
    crate::warn(py, run.document.own_warnings())?;
    Ok(PyCalibrationResult {
        source: model.source.clone(),
        run,
    })
}

/// A calibration's error: a failed analysis after the model's name, an
/// input error after the keyword argument it concerns, as the command
/// line names its flag (`--param: …`); the library names quantities, not
/// arguments.
fn failure(e: CommandError) -> Failure {
    use CalibrationError as E;
    let CommandError::Calibration { model, source } = e else {
        return Failure::from(e);
    };
    let keyword = match &source {
        E::Analysis { .. } | E::Impulse { .. } | E::NotConverged { .. } => {
            return Failure::analysis(&model, &source)
        }
        E::NoParameters
        | E::Parameter(_)
        | E::DuplicateParameter { .. }
        | E::InvalidBounds { .. }
        | E::Unreachable { .. } => "params",
        E::NoTargets | E::TargetNotPositive { .. } => "target_hz",
        E::DensityWithKeepMass { .. } => "keep_mass",
        E::ModeCount { .. } | E::ModeNotFound { .. } => "mode",
        E::ImpulseMode { .. } | E::NeedsSensitivities { .. } => "method",
        _ => return Failure::input(&source),
    };
    Failure::Input(format!("{keyword}: {}", one_line(&source)))
}

/// The result of `Model.calibrate`: the fitted parameters and model.
#[pyclass(name = "CalibrationResult", module = "ancf_modal", frozen)]
pub struct PyCalibrationResult {
    source: ancf::error::Source,
    run: CalibrateRun,
}

#[pymethods]
impl PyCalibrationResult {
    /// The fitted values by parameter name [SI units of each parameter].
    #[getter]
    fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let p = &self.run.result.parameters;
        by_name(py, p.iter().map(|p| (p.name.as_str(), p.fitted)))
    }

    /// The targets [Hz].
    #[getter]
    fn targets_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.result.targets_hz)
    }

    /// The tracked modes' frequencies before the fit [Hz].
    #[getter]
    fn initial_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.result.initial_hz)
    }

    /// The tracked modes' frequencies of the fitted model [Hz].
    #[getter]
    fn achieved_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.result.achieved_hz)
    }

    /// Model evaluations, the start included.
    #[getter]
    fn evaluations(&self) -> usize {
        self.run.result.evaluations
    }

    /// The calibrated model (what `calibrate --out` writes).
    #[getter]
    fn fitted_model(&self) -> PyModel {
        PyModel::made(self.run.result.fitted_model.clone(), &self.source)
    }

    /// The result as the library's JSON document (`calibrate --json`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document())
    }

    /// Draws the fit to `path` (.svg or .png): the first target's
    /// frequency over the first parameter, the evaluations and the fit, as
    /// `calibrate --plot`.
    fn plot(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || self.run.write_plot(&path).map_err(Failure::from))
    }

    /// The command line's report, then its `warning:` lines (the run's
    /// warnings, as `to_dict()["warnings"]`).
    fn __repr__(&self) -> String {
        crate::with_warnings(self.run.text(), &self.run.document.warnings)
    }
}
