//! `Model.calibrate(...)` (the command line's `calibrate`, eigenvalue
//! method) and its result, `ancf_modal.CalibrationResult`.
//!
//! [`PyCalibrationResult::document`] is the one place that builds
//! `to_dict()`.

use crate::errors::{compute, Failure};
use crate::model::{choice, PyModel};
use ancf::analysis::calibrate::{
    calibrate, CalibrationError, CalibrationRequest, CalibrationResult, CalibrationSettings,
    ModeSelection, ParameterSpec,
};
use ancf::analysis::ModeKind;
use ancf::model::ValidModel;
use ancf::results::provenance::sha256_hex;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use std::sync::Arc;

/// `params`: a name, a list of names, or {name: (lower, upper) or None}.
fn parameter_specs(params: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<ParameterSpec>> {
    let Some(params) = params else {
        return Ok(vec![ParameterSpec::named("height")]);
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

/// `target_hz`: one frequency or a sequence of them.
fn targets(target_hz: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Vec<f64>>> {
    match target_hz {
        None => Ok(None),
        Some(t) => match t.extract::<f64>() {
            Ok(f) => Ok(Some(vec![f])),
            Err(_) => Ok(Some(t.extract::<Vec<f64>>()?)),
        },
    }
}

/// The calibration's keyword arguments.
pub struct Request<'py, 'a> {
    pub target_hz: Option<&'a Bound<'py, PyAny>>,
    pub params: Option<&'a Bound<'py, PyAny>>,
    pub mode_kind: &'a str,
    pub mode: Option<Vec<i64>>,
    pub keep_mass: bool,
    pub tolerance: Option<f64>,
    pub max_evaluations: i64,
}

/// Fits the model's parameters to measured frequencies.
pub fn run(model: &PyModel, py: Python<'_>, r: Request<'_, '_>) -> PyResult<PyCalibrationResult> {
    let kind = match choice("mode_kind", r.mode_kind, &["bending", "axial", "spring"])? {
        "axial" => ModeKind::Axial,
        "spring" => ModeKind::Spring,
        _ => ModeKind::Bending,
    };
    let mut numbers = Vec::new();
    for n in r.mode.unwrap_or_default() {
        if n < 1 {
            return Err(Failure::argument("mode", n, "must be a whole number ≥ 1").into());
        }
        numbers.push(n as usize);
    }
    if let Some(t) = r.tolerance {
        if !(t.is_finite() && t > 0.0) {
            return Err(Failure::argument("tolerance", t, "must be a number > 0").into());
        }
    }
    if !(2..=10_000).contains(&r.max_evaluations) {
        return Err(Failure::argument(
            "max_evaluations",
            r.max_evaluations,
            "must be a whole number from 2 to 10000",
        )
        .into());
    }
    let parameters = parameter_specs(r.params)?;
    let targets_hz = match targets(r.target_hz)? {
        Some(t) => t,
        None => match &model.model.reference {
            Some(reference) => vec![reference.first_bending_hz],
            None => {
                return Err(
                    Failure::Input(crate::errors::one_line(&CalibrationError::NoTargets)).into(),
                )
            }
        },
    };
    let request = CalibrationRequest {
        parameters,
        targets_hz,
        modes: ModeSelection { kind, numbers },
        keep_mass: r.keep_mass,
    };
    let settings = CalibrationSettings {
        tolerance_hz: r.tolerance,
        max_evaluations: r.max_evaluations as usize,
        ..CalibrationSettings::default()
    };
    let shared = Arc::clone(&model.model);
    let label = model.label();
    let result = compute(py, move || {
        calibrate(&shared, &request, &settings).map_err(|e| match e {
            CalibrationError::Analysis { .. }
            | CalibrationError::Impulse { .. }
            | CalibrationError::NotConverged { .. } => Failure::analysis(&label, &e),
            _ => match keyword(&e) {
                Some(k) => Failure::Input(format!("{k}: {}", crate::errors::one_line(&e))),
                None => Failure::input(&e),
            },
        })
    })?;
    Ok(PyCalibrationResult {
        model: Arc::clone(&model.model),
        source: model.source.clone(),
        sha256: model.sha256.clone(),
        result,
    })
}

/// The keyword argument a calibration error concerns, named in front of
/// the message as the command line names its flag (`--param: …`); the
/// library names quantities, not arguments.
fn keyword(e: &CalibrationError) -> Option<&'static str> {
    use CalibrationError as E;
    Some(match e {
        E::NoParameters
        | E::Parameter(_)
        | E::DuplicateParameter { .. }
        | E::InvalidBounds { .. }
        | E::Unreachable { .. } => "params",
        E::NoTargets | E::TargetNotPositive { .. } => "target_hz",
        E::DensityWithKeepMass { .. } => "keep_mass",
        E::ModeCount { .. } | E::ModeNotFound { .. } => "mode",
        _ => return None,
    })
}

/// The result of `Model.calibrate`: the fitted parameters and model.
#[pyclass(name = "CalibrationResult", module = "ancf_modal", frozen)]
pub struct PyCalibrationResult {
    model: Arc<ValidModel>,
    source: ancf::error::Source,
    sha256: String,
    result: CalibrationResult,
}

impl PyCalibrationResult {
    /// The document `calibrate --json` prints: the typed result
    /// ([`ancf::results::CalibrationOutput`]) with the provenance block.
    fn document(&self) -> serde_json::Value {
        let label = self.source.to_string();
        crate::document(
            &ancf::results::CalibrationOutput::new(&self.model.name, &self.result),
            Some((&self.model, &label)),
            Some(&self.sha256),
        )
    }
}

#[pymethods]
impl PyCalibrationResult {
    /// The fitted values by parameter name [SI units of each parameter].
    #[getter]
    fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for p in &self.result.parameters {
            d.set_item(&p.name, p.fitted)?;
        }
        Ok(d)
    }

    /// The targets [Hz].
    #[getter]
    fn targets_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.targets_hz)
    }

    /// The tracked modes' frequencies before the fit [Hz].
    #[getter]
    fn initial_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.initial_hz)
    }

    /// The tracked modes' frequencies of the fitted model [Hz].
    #[getter]
    fn achieved_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.achieved_hz)
    }

    /// Model evaluations, the start included.
    #[getter]
    fn evaluations(&self) -> usize {
        self.result.evaluations
    }

    /// The calibrated model (what `calibrate --out` writes).
    #[getter]
    fn fitted_model(&self) -> PyModel {
        let model = self.result.fitted_model.clone();
        PyModel {
            sha256: sha256_hex(model.to_json().as_bytes()),
            model: Arc::new(model),
            source: self.source.clone(),
        }
    }

    /// The result as the library's JSON document (`calibrate --json`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.document())
    }

    fn __repr__(&self) -> String {
        ancf::output::calibrate_report::calibrate_table(&self.model.name, &self.result)
    }
}
