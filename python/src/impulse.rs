//! `Model.impulse(...)` (the command line's `impulse`) and its result,
//! `ancf_modal.ImpulseResult`.
//!
//! [`PyImpulseResult::document`] is the one place that builds `to_dict()`.

use crate::errors::{compute, Failure};
use crate::model::PyModel;
use ancf::analysis::impulse::{run_impulse, ImpulseError, ImpulseResult, ImpulseSettings};
use ancf::model::ValidModel;
use ancf::signal::Window;
use numpy::PyArray1;
use pyo3::prelude::*;
use std::sync::Arc;

/// The experiment's keyword arguments, checked as the command line checks
/// its flags.
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
}

impl Experiment<'_> {
    fn settings(&self) -> Result<ImpulseSettings, Failure> {
        let finite = |name: &str, v: f64, ok: bool, why: &str| {
            if v.is_finite() && ok {
                Ok(v)
            } else {
                Err(Failure::argument(name, v, why))
            }
        };
        if let Some(a) = self.amplitude {
            finite("amplitude", a, a != 0.0, "must be a non-zero number")?;
        }
        if let Some(d) = self.duration {
            finite("duration", d, d > 0.0, "must be a number > 0")?;
        }
        let positive = "must be a number > 0";
        let mut s = ImpulseSettings::default();
        s.transient.end_time = finite("end_time", self.end_time, self.end_time > 0.0, positive)?;
        s.transient.step = finite("step", self.step, self.step > 0.0, positive)?;
        let r = self.spectral_radius;
        s.transient.spectral_radius = finite(
            "spectral_radius",
            r,
            (0.0..=1.0).contains(&r),
            "must be a number from 0 to 1",
        )?;
        let rate = self.sample_rate;
        finite("sample_rate", rate, rate >= 0.0, "must be a number ≥ 0")?;
        s.sample_rate = (rate != 0.0).then_some(rate);
        s.amplitude = self.amplitude;
        s.duration = self.duration;
        s.sensor = self.sensor.map(str::to_string);
        s.spectrum.window = self
            .window
            .parse::<Window>()
            .map_err(|e| Failure::argument("window", self.window, &e.to_string()))?;
        s.transient
            .validate()
            .map_err(|e| Failure::Input(crate::errors::one_line(&e)))?;
        Ok(s)
    }
}

/// The result of `Model.impulse`: the simulated records, their spectrum and
/// the peaks.
#[pyclass(name = "ImpulseResult", module = "ancf_modal", frozen)]
pub struct PyImpulseResult {
    model: Arc<ValidModel>,
    sha256: String,
    result: ImpulseResult,
}

/// The impulse experiment on `model`.
pub fn run(model: &PyModel, py: Python<'_>, e: Experiment<'_>) -> PyResult<PyImpulseResult> {
    let settings = e.settings()?;
    let shared = Arc::clone(&model.model);
    let label = model.label();
    let result = compute(py, move || {
        run_impulse(&shared, &settings, &mut |_| {}).map_err(|e| match e {
            // Failures of the run; the rest is what the model or the
            // arguments ask for that cannot be done.
            ImpulseError::Transient(_)
            | ImpulseError::Analysis(_)
            | ImpulseError::Spectrum(_)
            | ImpulseError::Dispersion(_) => Failure::analysis(&label, &e),
            _ => Failure::Input(format!("{label}: {}", crate::errors::one_line(&e))),
        })
    })?;
    Ok(PyImpulseResult {
        model: Arc::clone(&model.model),
        sha256: model.sha256.clone(),
        result,
    })
}

impl PyImpulseResult {
    fn reference_hz(&self) -> Option<f64> {
        self.model.reference.as_ref().map(|r| r.first_bending_hz)
    }

    /// The document `impulse --json` prints: the typed result
    /// ([`ancf::results::ImpulseOutput`]) with the provenance block.
    fn document(&self) -> serde_json::Value {
        crate::document(
            &ancf::results::ImpulseOutput::new(&self.model.name, &self.result, self.reference_hz()),
            None,
            Some(&self.sha256),
        )
    }
}

#[pymethods]
impl PyImpulseResult {
    /// Sample times [s].
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.time)
    }

    /// The sensor's record [m, m/s or m/s², as `quantity`].
    #[getter]
    fn signal<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.signal)
    }

    /// The hammer force at the sample times [N].
    #[getter]
    fn force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.force)
    }

    /// The sensor's id.
    #[getter]
    fn sensor(&self) -> String {
        self.result.sensor.clone()
    }

    /// Sampling rate of the records [Hz].
    #[getter]
    fn sample_rate_hz(&self) -> f64 {
        self.result.sample_rate_hz
    }

    /// Frequencies of the spectrum [Hz].
    #[getter]
    fn spectrum_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.spectrum.frequency_hz)
    }

    /// Window-corrected amplitude spectrum of the signal [signal unit].
    #[getter]
    fn spectrum<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.spectrum.magnitude)
    }

    /// Interpolated spectrum peaks [Hz], by frequency.
    #[getter]
    fn peaks_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let f: Vec<f64> = self.result.peaks.iter().map(|p| p.frequency_hz).collect();
        PyArray1::from_vec(py, f)
    }

    /// The first bending peak as (raw_hz, corrected_hz, eigen_hz) [Hz]: the
    /// FFT peak, the same with the integrator's period error removed, and
    /// the eigenvalue result; None when it was not found.
    #[getter]
    fn first_bending(&self) -> Option<(f64, f64, f64)> {
        self.result
            .first_bending
            .map(|f| (f.raw_hz, f.corrected_hz, f.eigen_hz))
    }

    /// The result as the library's JSON document (`impulse --json`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.document())
    }

    fn __repr__(&self) -> String {
        ancf::output::impulse_report::impulse_table(
            &self.model.name,
            &self.result,
            self.reference_hz(),
        )
    }
}
