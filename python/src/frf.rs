//! `ancf_modal.frf` (hammer records as arrays), `ancf_modal.frf_files`
//! (the command line's `frf`) and their result, `ancf_modal.FrfResult`.
//!
//! [`PyFrfResult::document`] is the one place that builds `to_dict()`.

use crate::errors::{compute, Failure};
use crate::model::{choice, finite};
use ancf::measured::analysis::{analyse, AnalysisSettings, Estimator, FrfAnalysis};
use ancf::measured::{
    check_force, read_measurement_noted, Channel, Channels, Measurement, TimeRecord,
};
use ancf::output::frf_report::ResponseQuantity;
use ancf::signal::Window;
use numpy::{Complex64, PyArray1, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// The analysis settings shared by `frf` and `frf_files`.
struct Options {
    settings: AnalysisSettings,
    quantity: ResponseQuantity,
}

fn options(
    window: &str,
    estimator: &str,
    band: Option<(f64, f64)>,
    max_order: i64,
    response_quantity: &str,
) -> Result<Options, Failure> {
    let window: Window = window
        .parse()
        .map_err(|why: ancf::signal::window::WindowError| {
            Failure::argument("window", window, &why.to_string())
        })?;
    let estimator = match choice("estimator", estimator, &["h1", "h2"])? {
        "h2" => Estimator::H2,
        _ => Estimator::H1,
    };
    if let Some((lo, hi)) = band {
        let (lo, hi) = (finite("band", lo)?, finite("band", hi)?);
        if !(lo >= 0.0 && hi > lo) {
            return Err(Failure::argument(
                "band",
                format!("({lo}, {hi})"),
                "the band needs 0 ≤ LO < HI [Hz]",
            ));
        }
    }
    if !(2..=200).contains(&max_order) {
        return Err(Failure::argument(
            "max_order",
            max_order,
            "must be a whole number from 2 to 200",
        ));
    }
    let quantity = match choice(
        "response_quantity",
        response_quantity,
        &["displacement", "velocity", "acceleration"],
    )? {
        "displacement" => ResponseQuantity::Displacement,
        "acceleration" => ResponseQuantity::Acceleration,
        _ => ResponseQuantity::Velocity,
    };
    Ok(Options {
        settings: AnalysisSettings {
            window,
            estimator,
            band,
            max_order: max_order as usize,
        },
        quantity,
    })
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

/// The H1/H2 estimate and modal fit of hammer hits given as arrays: `force`
/// [N] and `response` [m, m/s or m/s² as `response_quantity` says], each
/// 1-D (one hit) or 2-D (one hit per row, averaged), sampled at `fs` [Hz].
/// `window`: rect, hann, force:P, exponential:P; `estimator` for the fit:
/// h1 or h2; `band` (LO, HI) [Hz] of the fit (default: chosen from the
/// force spectrum and the noise floor); `max_order` of the stabilization
/// diagram.
#[pyfunction]
#[pyo3(signature = (force, response, fs, window = "rect", estimator = "h1", band = None, max_order = 40, response_quantity = "velocity"))]
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
    response_quantity: &str,
) -> PyResult<PyFrfResult> {
    let o = options(window, estimator, band, max_order, response_quantity)?;
    if !(fs.is_finite() && fs > 0.0) {
        return Err(Failure::argument("fs", fs, "must be a number > 0").into());
    }
    let (f, x) = (rows("force", force)?, rows("response", response)?);
    if f.len() != x.len() || f.iter().zip(&x).any(|(a, b)| a.len() != b.len()) {
        return Err(Failure::argument(
            "response",
            format!("{} hits of {} samples", x.len(), x[0].len()),
            &format!(
                "must have the force's shape, {} hits of {} samples",
                f.len(),
                f[0].len()
            ),
        )
        .into());
    }
    let min = ancf::measured::MIN_SAMPLES;
    if f[0].len() < min {
        return Err(Failure::argument(
            "force",
            format!("{} samples", f[0].len()),
            &format!("a hit needs at least {min} samples"),
        )
        .into());
    }
    let analysis = compute(py, move || {
        let single = f.len() == 1;
        let mut measurements = Vec::with_capacity(f.len());
        for (i, (force, response)) in f.into_iter().zip(x).enumerate() {
            let name = if single {
                String::from("<array>")
            } else {
                format!("<array row {i}>")
            };
            let n = force.len();
            let r = TimeRecord {
                file: PathBuf::from(name),
                sample_rate_hz: fs,
                force,
                response,
                force_label: String::from("force"),
                response_label: String::from("response"),
                lines: (1..=n).collect(),
            };
            check_force(&r).map_err(|e| Failure::input(&e))?;
            measurements.push(Measurement::Time(r));
        }
        analyse(measurements, o.settings).map_err(|e| Failure::input(&e))
    })?;
    let notes = analysis.warnings();
    crate::warn_all(py, &notes)?;
    Ok(PyFrfResult {
        analysis,
        quantity: o.quantity,
        notes,
    })
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
#[pyo3(signature = (paths, force = None, response = None, window = "rect", estimator = "h1", band = None, max_order = 40, response_quantity = "velocity"))]
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
    response_quantity: &str,
) -> PyResult<PyFrfResult> {
    let o = options(window, estimator, band, max_order, response_quantity)?;
    if paths.is_empty() {
        return Err(Failure::argument("paths", "[]", "give at least one file").into());
    }
    let channels = Channels {
        force: channel("force", force)?,
        response: channel("response", response)?,
    };
    let (analysis, notes) = compute(py, move || {
        let mut notes = Vec::new();
        let mut measurements = Vec::with_capacity(paths.len());
        for p in &paths {
            let (m, n) = read_measurement_noted(p, &channels).map_err(|e| Failure::input(&e))?;
            measurements.push(m);
            notes.extend(n);
        }
        let analysis = analyse(measurements, o.settings).map_err(|e| Failure::input(&e))?;
        notes.extend(analysis.warnings());
        Ok((analysis, notes))
    })?;
    // The UFF datasets skipped: Python warnings and the document's `warnings`.
    crate::warn_all(py, &notes)?;
    Ok(PyFrfResult {
        analysis,
        quantity: o.quantity,
        notes,
    })
}

/// Measured FRFs and the modes fitted to them.
#[pyclass(name = "FrfResult", module = "ancf_modal", frozen)]
pub struct PyFrfResult {
    analysis: FrfAnalysis,
    quantity: ResponseQuantity,
    /// What reading the files left for the user (UFF datasets skipped).
    notes: Vec<String>,
}

impl PyFrfResult {
    /// The document `frf --json` prints without `--model`: the typed
    /// result ([`ancf::results::FrfOutput`]) with the provenance block, the
    /// notes of the reading as its `warnings`.
    fn document(&self) -> serde_json::Value {
        ancf::results::document(
            &ancf::results::FrfOutput::new(&self.analysis, self.quantity, None),
            None,
            &self.notes,
        )
        .expect("results serialize")
    }

    /// One key of the document as a Python object.
    fn key<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.document()[key])
    }
}

#[pymethods]
impl PyFrfResult {
    /// Frequencies of the spectra [Hz].
    #[getter]
    fn freq<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.analysis.frequency_hz)
    }

    /// H1 = G_fx/G_ff [response unit per N], complex.
    #[getter]
    fn h1<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<Complex64>> {
        PyArray1::from_vec(
            py,
            self.analysis
                .h1
                .iter()
                .map(|c| Complex64::new(c.re, c.im))
                .collect(),
        )
    }

    /// H2 = G_xx/G_xf [response unit per N], complex; None for a measured FRF.
    #[getter]
    fn h2<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<Complex64>>> {
        self.analysis
            .h2
            .as_ref()
            .map(|h| PyArray1::from_vec(py, h.iter().map(|c| Complex64::new(c.re, c.im)).collect()))
    }

    /// Coherence γ² [–]; None for a measured FRF without one.
    #[getter]
    fn coherence<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.analysis
            .coherence
            .as_ref()
            .map(|c| PyArray1::from_slice(py, c))
    }

    /// The fit band (LO, HI) [Hz].
    #[getter]
    fn band(&self) -> (f64, f64) {
        self.analysis.band
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
        crate::json_to_python(py, &self.document())
    }

    fn __repr__(&self) -> String {
        ancf::output::frf_report::frf_table(&self.analysis, self.quantity)
    }
}
