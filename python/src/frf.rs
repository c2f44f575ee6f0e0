//! `ancf_modal.frf` (hammer records as arrays), `ancf_modal.frf_files`
//! (the command line's `frf`) and their result, `ancf_modal.FrfResult`.
//!
//! A front end over [`ancf::commands::frf`]: keyword arguments → request →
//! `run` → wrap; `to_dict()` is the run's document.

use crate::errors::{compute, Failure};
use crate::model::{choice, PyModel};
use ancf::commands::frf::{run as frf_run, FrfRecords, FrfRequest, FrfRun};
use ancf::measured::analysis::Estimator;
use ancf::measured::Channel;
use ancf::output::frf_report::ResponseQuantity;
use ancf::signal::Window;
use numpy::{Complex64, PyArray1, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// The keyword arguments `frf` and `frf_files` share.
struct Options<'a> {
    window: &'a str,
    estimator: &'a str,
    band: Option<(f64, f64)>,
    max_order: i64,
    response_quantity: Option<&'a str>,
    at: Option<String>,
}

impl Options<'_> {
    /// The request on `records`, the text choices read.
    fn request(self, records: FrfRecords) -> Result<FrfRequest, Failure> {
        let window: Window =
            self.window
                .parse()
                .map_err(|why: ancf::signal::window::WindowError| {
                    Failure::argument("window", self.window, &why.to_string())
                })?;
        let estimator = match choice("estimator", self.estimator, &["h1", "h2"])? {
            "h2" => Estimator::H2,
            _ => Estimator::H1,
        };
        let response_quantity = match self.response_quantity {
            None => None,
            Some(q) => Some(
                match choice(
                    "response_quantity",
                    q,
                    &["displacement", "velocity", "acceleration"],
                )? {
                    "displacement" => ResponseQuantity::Displacement,
                    "acceleration" => ResponseQuantity::Acceleration,
                    _ => ResponseQuantity::Velocity,
                },
            ),
        };
        Ok(FrfRequest {
            records,
            window,
            estimator,
            band: self.band,
            max_order: usize::try_from(self.max_order).map_err(|_| {
                Failure::argument(
                    "max_order",
                    self.max_order,
                    "must be a whole number from 2 to 200",
                )
            })?,
            response_quantity,
            at: self.at,
            ..FrfRequest::default()
        })
    }
}

/// Rows of a 1-D (one hit) or 2-D (one hit per row) float array.
fn rows(name: &str, a: &Bound<'_, PyAny>) -> PyResult<Vec<Vec<f64>>> {
    let py = a.py();
    let kwargs = PyDict::new(py);
    kwargs.set_item("dtype", "float64")?;
    let a = py
        .import("numpy")?
        .call_method("ascontiguousarray", (a,), Some(&kwargs))?;
    let a: PyReadonlyArrayDyn<'_, f64> = a.extract()?;
    let view = a.as_array();
    match a.ndim() {
        1 => Ok(vec![view.iter().copied().collect()]),
        2 => Ok(view
            .outer_iter()
            .map(|r| r.iter().copied().collect())
            .collect()),
        n => Err(Failure::argument(
            name,
            format!("array of {n} dimensions"),
            "must be one hit (1-D) or one hit per row (2-D)",
        )
        .into()),
    }
}

/// Runs the request (with the GIL released) and raises the records' notes
/// as `ModelWarning`s (the command line's `warning:` lines; the model's
/// were raised when it was read).
fn run(py: Python<'_>, model: Option<&PyModel>, request: FrfRequest) -> PyResult<PyFrfResult> {
    let input = model.map(PyModel::input);
    let run = compute(py, move || {
        frf_run(input.as_ref(), &request).map_err(Failure::from)
    })?;
    crate::warn(py, run.document.own_warnings())?;
    Ok(PyFrfResult { run })
}

/// The H1/H2 estimate and modal fit of hammer hits given as arrays: `force`
/// [N] and `response` [m, m/s or m/s² as `response_quantity` says], each
/// 1-D (one hit) or 2-D (one hit per row, averaged), sampled at `fs` [Hz].
/// `window`: rect, hann, force:P, exponential:P; `estimator` for the fit:
/// h1 or h2; `band` (LO, HI) [Hz] of the fit (default: chosen from the
/// force spectrum and the noise floor); `max_order` of the stabilization
/// diagram; `model` and its sensor `at`: the model's FRF beside the
/// measured one.
#[pyfunction]
#[pyo3(signature = (force, response, fs, window = "rect", estimator = "h1", band = None, max_order = 40, response_quantity = None, model = None, at = None))]
#[allow(clippy::too_many_arguments)]
pub fn frf(
    py: Python<'_>,
    force: &Bound<'_, PyAny>,
    response: &Bound<'_, PyAny>,
    fs: f64,
    window: &str,
    estimator: &str,
    band: Option<(f64, f64)>,
    max_order: i64,
    response_quantity: Option<&str>,
    model: Option<PyRef<'_, PyModel>>,
    at: Option<String>,
) -> PyResult<PyFrfResult> {
    let options = Options {
        window,
        estimator,
        band,
        max_order,
        response_quantity,
        at,
    };
    let records = FrfRecords::Arrays {
        force: rows("force", force)?,
        response: rows("response", response)?,
        fs,
    };
    run(py, model.as_deref(), options.request(records)?)
}

/// A channel given as a column name or a 1-based index.
fn channel(name: &str, c: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Channel>> {
    let Some(c) = c else { return Ok(None) };
    let text = c.str()?.to_string();
    text.parse::<Channel>()
        .map(Some)
        .map_err(|why| Failure::argument(name, text, &why).into())
}

/// `frf` on measurement files, as the command line's `frf`: CSV (header
/// row, time [s] in the first column; `force`/`response` a column name or
/// 1-based index; by default the one column whose name holds `force`, else column
/// 2, is the force and the first other column after time the response) or
/// UFF 58 time records or an FRF.
/// Several files are hits, averaged.
#[pyfunction]
#[pyo3(signature = (paths, force = None, response = None, window = "rect", estimator = "h1", band = None, max_order = 40, response_quantity = None, model = None, at = None))]
#[allow(clippy::too_many_arguments)]
pub fn frf_files(
    py: Python<'_>,
    paths: Vec<PathBuf>,
    force: Option<&Bound<'_, PyAny>>,
    response: Option<&Bound<'_, PyAny>>,
    window: &str,
    estimator: &str,
    band: Option<(f64, f64)>,
    max_order: i64,
    response_quantity: Option<&str>,
    model: Option<PyRef<'_, PyModel>>,
    at: Option<String>,
) -> PyResult<PyFrfResult> {
    if paths.is_empty() {
        return Err(Failure::argument("paths", "[]", "give at least one file").into());
    }
    let options = Options {
        window,
        estimator,
        band,
        max_order,
        response_quantity,
        at,
    };
    let request = FrfRequest {
        force: channel("force", force)?,
        response: channel("response", response)?,
        ..options.request(FrfRecords::Files(paths))?
    };
    run(py, model.as_deref(), request)
}

/// Measured FRFs and the modes fitted to them.
#[pyclass(name = "FrfResult", module = "ancf_modal", frozen)]
pub struct PyFrfResult {
    run: FrfRun,
}

impl PyFrfResult {
    /// One key of the document as a Python object.
    fn key<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document()[key])
    }
}

#[pymethods]
impl PyFrfResult {
    /// Frequencies of the spectra [Hz].
    #[getter]
    fn freq<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.analysis.frequency_hz)
    }

    /// H1 = G_fx/G_ff [response unit per N], complex.
    #[getter]
    fn h1<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<Complex64>> {
        PyArray1::from_slice(py, &self.run.analysis.h1)
    }

    /// H2 = G_xx/G_xf [response unit per N], complex; None for a measured FRF.
    #[getter]
    fn h2<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<Complex64>>> {
        let h2 = self.run.analysis.h2.as_ref()?;
        Some(PyArray1::from_slice(py, h2))
    }

    /// Coherence γ² [–]; None for a measured FRF without one.
    #[getter]
    fn coherence<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        let c = self.run.analysis.coherence.as_ref()?;
        Some(PyArray1::from_slice(py, c))
    }

    /// The model's FRF at its sensor on `freq` [response unit per N]
    /// (with `model` and `at`); else None.
    #[getter]
    fn model_frf<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<Complex64>>> {
        let o = self.run.overlay.as_ref()?;
        Some(PyArray1::from_slice(py, &o.h))
    }

    /// The fit band (LO, HI) [Hz].
    #[getter]
    fn band(&self) -> (f64, f64) {
        self.run.analysis.band
    }

    /// The identified modes: dicts with frequency_hz [Hz], damping_ratio
    /// [–], magnitude [|H|] and residue [re, im].
    #[getter]
    fn peaks<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "peaks")
    }

    /// Stable poles not reported as modes, with the reason.
    #[getter]
    fn rejected<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "rejected")
    }

    /// The stabilization diagram: dicts with order, frequency_hz [Hz],
    /// damping_ratio [–], stability.
    #[getter]
    fn stabilization<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "stabilization")
    }

    /// The result as the library's JSON document (`frf --json`) as a dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document())
    }

    /// Writes H1 and the coherence as UFF 58 to `path`, as `frf --uff`.
    fn write_uff(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || {
            ancf::output::files::write_atomic(&path, self.run.uff().as_bytes())
                .map_err(|e| Failure::input(&e))
        })
    }

    /// Writes the spectra and the fitted model as CSV to `path`, as `frf
    /// --csv`.
    fn write_csv(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || {
            ancf::output::files::write_atomic(&path, self.run.csv().as_bytes())
                .map_err(|e| Failure::input(&e))
        })
    }

    /// Draws the FRF, the fit, the coherence and the stabilization diagram
    /// to `path` (.svg or .png), as `frf --plot`.
    fn plot(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || self.run.write_plot(&path).map_err(Failure::from))
    }

    /// The command line's report, then its `warning:` lines (the run's
    /// warnings, as `to_dict()["warnings"]`).
    fn __repr__(&self) -> String {
        crate::with_warnings(self.run.text(), &self.run.document.warnings)
    }
}
