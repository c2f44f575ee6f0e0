//! `Model.identify(...)` (the command line's `identify`, the main job) and
//! its result, `ancf_modal.IdentifyResult`.
//!
//! A front end over [`ancf::commands::identify`]: keyword arguments →
//! request → `run` → wrap; `to_dict()` is the run's document and
//! `write_out_dir` writes the files of `identify --out-dir`.

use crate::errors::{compute, Failure};
use crate::impulse::Experiment;
use crate::model::PyModel;
use ancf::commands::identify::{run as identify, IdentifyRequest, IdentifyRun};
use ancf::commands::report::{of_identified, ReportRequest};
use ancf::commands::ModelInput;
use ancf::signal::Window;
use numpy::PyArray1;
use pyo3::prelude::*;
use std::path::PathBuf;

/// `identify`'s keyword arguments (SI units).
pub struct Request<'a> {
    /// The impulse experiment's, as `Model.impulse`'s.
    pub experiment: Experiment<'a>,
    pub calibrate: bool,
    pub measured: Option<Vec<PathBuf>>,
    pub measured_window: &'a str,
    pub measured_band: Option<(f64, f64)>,
}

/// A window's text, named `name` in the error.
fn window(name: &str, text: &str) -> Result<Window, Failure> {
    text.parse()
        .map_err(|why: ancf::signal::window::WindowError| {
            Failure::argument(name, text, &why.to_string())
        })
}

impl Request<'_> {
    /// The library's request (the windows parsed, each named by its
    /// keyword in an error).
    pub fn into_request(self) -> Result<IdentifyRequest, Failure> {
        Ok(IdentifyRequest {
            experiment: self.experiment.request()?,
            calibrate: self.calibrate,
            measured: self.measured.unwrap_or_default(),
            measured_window: window("measured_window", self.measured_window)?,
            measured_band: self.measured_band,
        })
    }
}

/// `identify` on `model`.
pub fn run(model: &PyModel, py: Python<'_>, r: Request<'_>) -> PyResult<PyIdentifyResult> {
    let request = r.into_request()?;
    let input = model.input();
    let run = compute(py, || identify(&input, &request).map_err(Failure::from))?;
    // The run's own warnings: the analyses' (named by the model's source)
    // and the measured records' notes (named by their files); the model's
    // were raised when it was read.
    crate::warn(py, run.document.own_warnings())?;
    Ok(PyIdentifyResult { input, run })
}

/// The result of `Model.identify`: the comparison of first bending
/// frequencies, the modes, the impulse experiment, the measured records
/// and the calibration.
#[pyclass(name = "IdentifyResult", module = "ancf_modal", frozen)]
pub struct PyIdentifyResult {
    input: ModelInput,
    run: IdentifyRun,
}

#[pymethods]
impl PyIdentifyResult {
    /// The experiment's first bending frequency [Hz] (measured records, or
    /// the model's reference); None without one.
    #[getter]
    fn experiment_hz(&self) -> Option<f64> {
        self.run.document.output.experiment_hz
    }

    /// The comparison, one dict per row: source, first_bending_hz [Hz],
    /// error_percent and paper_error_percent [%] (None where undefined).
    #[getter]
    fn table<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document()["table"])
    }

    /// Whether the comparison is the paper's Table 3.
    #[getter]
    fn paper(&self) -> bool {
        self.run.paper
    }

    /// Natural frequencies of the modes at the reference [Hz].
    #[getter]
    fn frequencies_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let f: Vec<f64> = self
            .run
            .modal
            .modes
            .iter()
            .map(|m| m.frequency_hz)
            .collect();
        PyArray1::from_vec(py, f)
    }

    /// The model with the fitted equivalent height (`calibrate=True`, what
    /// `--out-dir` writes as calibrated.json); else None.
    #[getter]
    fn calibrated_model(&self) -> Option<PyModel> {
        let c = self.run.document.output.calibration.as_ref()?;
        Some(PyModel::made(
            c.result.fitted_model.clone(),
            &self.input.source,
        ))
    }

    /// The result as the library's JSON document (`identify --json`, the
    /// output directory's summary.json) as a dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document())
    }

    /// Writes what `identify --out-dir` writes into `out_dir` (created if
    /// missing): summary.json, modes.csv, signal.csv, spectrum.csv,
    /// calibrated.json (with `calibrate=True`) and the figures modes,
    /// response, spectrum and convergence as .svg and .png.
    fn write_out_dir(&self, py: Python<'_>, out_dir: PathBuf) -> PyResult<()> {
        compute(py, || {
            self.run.write_out_dir(&out_dir).map_err(Failure::from)
        })
    }

    /// Writes what `identify --html` writes: the report (as
    /// `Model.report`) of this run, to `path`.
    fn write_html(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        ancf::commands::report::check_out("path", &path).map_err(Failure::from)?;
        let request = ReportRequest {
            out: path,
            command_line: crate::report::provenance("IdentifyResult.write_html"),
            ..ReportRequest::default()
        };
        compute(py, || {
            let page = of_identified(&self.input, &self.run, &request).map_err(Failure::from)?;
            page.write().map_err(Failure::from)
        })
    }

    /// The command line's report, then its `warning:` lines (the run's
    /// warnings, as `to_dict()["warnings"]`).
    fn __repr__(&self) -> String {
        crate::with_warnings(self.run.text(None), &self.run.document.warnings)
    }
}
