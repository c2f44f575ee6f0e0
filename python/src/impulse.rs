//! `Model.impulse(...)` (the command line's `impulse`) and its result,
//! `ancf_modal.ImpulseResult`.
//!
//! A front end over [`ancf::commands::impulse`]: keyword arguments →
//! request → `run` → wrap; `to_dict()` is the run's document.

use crate::errors::{compute, Failure};
use crate::model::PyModel;
use ancf::commands::impulse::{run as impulse, ImpulseRequest, ImpulseRun};
use ancf::signal::Window;
use numpy::PyArray1;
use pyo3::prelude::*;
use std::path::PathBuf;

/// The experiment's keyword arguments (also `Model.calibrate`'s for its
/// impulse method).
#[derive(Clone, Copy)]
pub struct Experiment<'a> {
    pub amplitude: Option<f64>,
    pub duration: Option<f64>,
    pub end_time: f64,
    pub step: f64,
    pub spectral_radius: f64,
    pub sample_rate: f64,
    pub sensor: Option<&'a str>,
    pub window: &'a str,
    /// Strike the reference instead of the static equilibrium.
    pub from_reference: bool,
}

impl Experiment<'_> {
    /// The request; the command checks the numbers' ranges.
    pub fn request(&self) -> Result<ImpulseRequest, Failure> {
        let window = self
            .window
            .parse::<Window>()
            .map_err(|e| Failure::argument("window", self.window, &e.to_string()))?;
        Ok(ImpulseRequest {
            amplitude: self.amplitude,
            duration: self.duration,
            end_time: self.end_time,
            step: self.step,
            spectral_radius: self.spectral_radius,
            sample_rate: self.sample_rate,
            sensor: self.sensor.map(str::to_string),
            window,
            start: ancf::analysis::statics::start::Start::from_reference(self.from_reference),
        })
    }
}

/// The result of `Model.impulse`: the simulated records, their spectrum and
/// the peaks.
#[pyclass(name = "ImpulseResult", module = "ancf_modal", frozen)]
pub struct PyImpulseResult {
    run: ImpulseRun,
}

/// The impulse experiment on `model`.
pub fn run(model: &PyModel, py: Python<'_>, e: Experiment<'_>) -> PyResult<PyImpulseResult> {
    let request = e.request()?;
    let input = model.input();
    let run = compute(py, move || impulse(&input, &request).map_err(Failure::from))?;
    crate::warn(py, run.document.own_warnings())?;
    Ok(PyImpulseResult { run })
}

#[pymethods]
impl PyImpulseResult {
    /// Sample times [s].
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.result.time)
    }

    /// The sensor's record [m, m/s or m/s², as `quantity`].
    #[getter]
    fn signal<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.result.signal)
    }

    /// The hammer force at the sample times [N].
    #[getter]
    fn force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.result.force)
    }

    /// The sensor's id.
    #[getter]
    fn sensor(&self) -> String {
        self.run.result.sensor.clone()
    }

    /// Sampling rate of the records [Hz].
    #[getter]
    fn sample_rate_hz(&self) -> f64 {
        self.run.result.sample_rate_hz
    }

    /// Frequencies of the spectrum [Hz].
    #[getter]
    fn spectrum_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.result.spectrum.frequency_hz)
    }

    /// Window-corrected amplitude spectrum of the signal [signal unit].
    #[getter]
    fn spectrum<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.run.result.spectrum.magnitude)
    }

    /// Interpolated spectrum peaks [Hz], by frequency.
    #[getter]
    fn peaks_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let f: Vec<f64> = self
            .run
            .result
            .peaks
            .iter()
            .map(|p| p.frequency_hz)
            .collect();
        PyArray1::from_vec(py, f)
    }

    /// The first bending peak as (raw_hz, corrected_hz, eigen_hz) [Hz]: the
    /// FFT peak, the same with the integrator's period error removed, and
    /// the eigenvalue result; None when it was not found.
    #[getter]
    fn first_bending(&self) -> Option<(f64, f64, f64)> {
        self.run
            .result
            .first_bending
            .map(|f| (f.raw_hz, f.corrected_hz, f.eigen_hz))
    }

    /// The result as the library's JSON document (`impulse --json`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document())
    }

    /// Writes the records (time [s], sensor, force [N]) as CSV to `path`
    /// and the spectrum beside it as `path`'s stem + `.spectrum.csv`, as
    /// `impulse --csv`.
    fn write_csv(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || self.run.write_csv(&path).map_err(Failure::from))
    }

    /// Writes the force and the sensor's records as UFF 58 to `path`, as
    /// `impulse --uff`.
    fn write_uff(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || {
            ancf::output::files::write_atomic(&path, self.run.uff().as_bytes())
                .map_err(|e| Failure::input(&e))
        })
    }

    /// Draws the spectrum to `path` (.svg or .png) and the response beside
    /// it as `path`'s stem + `.response.<ext>`, as `impulse --plot`.
    fn plot(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || self.run.write_plot(&path).map_err(Failure::from))
    }

    /// The command line's report, then its `warning:` lines (the run's
    /// warnings, as `to_dict()["warnings"]`).
    fn __repr__(&self) -> String {
        crate::with_warnings(self.run.text(), &self.run.document.warnings)
    }
}
