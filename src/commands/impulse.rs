//! `impulse`: the paper's time-domain frequency test (Section 2.2). The
//! model's half-sine loads (the hammer, F(t) = F₀ sin(πt/t_F) for
//! t ≤ t_F; `amplitude` F₀ [N] and `duration` t_F [s] override theirs)
//! strike the assembly at rest in its static equilibrium under the loads
//! at t = 0⁻ (the reference when it balances them, or when `start` asks
//! for it); generalized-α (spectral radius ρ∞ [–])
//! integrates `end_time` [s] in steps of `step` [s]; a sensor [m, m/s or
//! m/s²] is recorded at `sample_rate` [Hz] behind an anti-aliasing
//! low-pass, and its windowed amplitude spectrum gives the peaks [Hz] and
//! the first bending frequency, corrected for the integrator's period
//! error and set beside the eigenvalue's ([`crate::analysis::impulse`]).

use super::{CommandError, ModelInput, Run};
use crate::analysis::impulse::{run_impulse, ImpulseError, ImpulseResult, ImpulseSettings};
use crate::analysis::statics::start::Start;
use crate::model::Model;
use crate::output::figures::{response_path, write_impulse_figures};
use crate::output::impulse_report::{impulse_table, signal_csv, spectrum_csv};
use crate::output::plot::PlotSize;
use crate::output::records_uff::time_records_uff;
use crate::results::ImpulseOutput;
use crate::signal::resample::AntiAlias;
use crate::signal::Window;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// What `impulse` computes (also the experiment of `calibrate`'s impulse
/// method). The defaults are the experiment's ([`ImpulseSettings`]): the
/// paper's 51.2 kHz acquisition, 1 µs steps over 0.1 s, ρ∞ = 0.9, Hann.
#[derive(Debug, Clone, PartialEq)]
pub struct ImpulseRequest {
    /// Pulse amplitude F₀ [N] (non-zero, either sign); `None`: the model's.
    pub amplitude: Option<f64>,
    /// Pulse duration t_F [s] (> 0); `None`: the model's.
    pub duration: Option<f64>,
    /// End time [s] (> 0, longer than one step).
    pub end_time: f64,
    /// Time step [s] (> 0).
    pub step: f64,
    /// Spectral radius at infinity of generalized-α [–] (0 to 1; 1: no
    /// numerical damping).
    pub spectral_radius: f64,
    /// Sensor sampling rate [Hz] (≥ 0, at most 1/step); 0 records every
    /// step.
    pub sample_rate: f64,
    /// The sensor's id; `None`: the model's first sensor.
    pub sensor: Option<String>,
    /// The spectrum's data window.
    pub window: Window,
    /// The state struck at rest: the static equilibrium under the loads at
    /// t = 0⁻ (the default; the reference when it balances them) or the
    /// reference.
    pub start: Start,
}

impl Default for ImpulseRequest {
    fn default() -> Self {
        let s = ImpulseSettings::default();
        ImpulseRequest {
            amplitude: s.amplitude,
            duration: s.duration,
            end_time: s.transient.end_time,
            step: s.transient.step,
            spectral_radius: s.transient.spectral_radius,
            sample_rate: s.sample_rate.unwrap_or(0.0),
            sensor: s.sensor,
            window: s.spectrum.window,
            start: s.start,
        }
    }
}

impl ImpulseRequest {
    /// Checks each field's range (named as the request names it), then the
    /// integration's settings against each other.
    pub fn check(&self) -> Result<(), CommandError> {
        let range = |name: &'static str, v: f64, ok: bool, allowed: &str| {
            if v.is_finite() && ok {
                Ok(())
            } else {
                Err(CommandError::argument(name, v, allowed))
            }
        };
        if let Some(a) = self.amplitude {
            range("amplitude", a, a != 0.0, "must be a non-zero number")?;
        }
        if let Some(d) = self.duration {
            range("duration", d, d > 0.0, "must be a number > 0")?;
        }
        super::checks::time_span(self.end_time, self.step)?;
        super::checks::spectral_radius(self.spectral_radius)?;
        super::checks::sample_rate_for_step(self.sample_rate, self.step)?;
        self.settings().transient.validate()?;
        Ok(())
    }

    /// The experiment's settings.
    pub fn settings(&self) -> ImpulseSettings {
        let mut s = ImpulseSettings::default();
        s.transient.step = self.step;
        s.transient.end_time = self.end_time;
        s.transient.spectral_radius = self.spectral_radius;
        s.amplitude = self.amplitude;
        s.duration = self.duration;
        s.sample_rate = (self.sample_rate != 0.0).then_some(self.sample_rate);
        s.sensor = self.sensor.clone();
        s.spectrum.window = self.window;
        s.start = self.start;
        s
    }
}

/// `impulse`'s output: the records, their spectrum, the peaks and the
/// document.
#[derive(Debug)]
pub struct ImpulseRun {
    /// The model struck (its own loads; the overrides act in the run).
    pub model: Arc<crate::model::ValidModel>,
    /// The experiment's records, spectrum and peaks.
    pub result: ImpulseResult,
    /// The document with the run's warnings.
    pub document: Run<ImpulseOutput>,
}

/// Runs `impulse` on `input`.
pub fn run(input: &ModelInput, request: &ImpulseRequest) -> Result<ImpulseRun, CommandError> {
    run_with_progress(input, request, &mut |_| {})
}

/// [`run`], telling `progress` the fraction of the steps done.
pub fn run_with_progress(
    input: &ModelInput,
    request: &ImpulseRequest,
    progress: &mut dyn FnMut(f64),
) -> Result<ImpulseRun, CommandError> {
    request.check()?;
    let result = run_impulse(&input.model, &request.settings(), progress)
        .map_err(|e| CommandError::impulse(input.label(), e))?;
    let reference = reference_hz(&input.model);
    let output = ImpulseOutput::new(&input.model.name, &result, reference);
    let own = impulse_warnings(&result);
    Ok(ImpulseRun {
        model: input.model.clone(),
        document: Run::of(input, output).warn(input, own),
        result,
    })
}

/// The impulse run's own warnings (`impulse`'s and those it adds to
/// `identify` and `report`): a sensor blind to the first bending mode,
/// settings that do not fit the model's scale.
pub fn impulse_warnings(result: &ImpulseResult) -> Vec<String> {
    let mut own: Vec<String> = result.blind_sentence().into_iter().collect();
    own.extend(scale_warnings(result));
    own
}

/// Fewer steps per period of the first bending mode than this is a warning.
pub const MIN_STEPS_PER_PERIOD: f64 = 20.0;

/// Fewer periods of the first bending mode in the record than this is a
/// warning.
pub const MIN_PERIODS: f64 = 20.0;

/// The warnings of settings that do not fit the model's scale (the
/// defaults are the paper's 4.6 kHz contact's): a first bending mode above
/// the acquisition's pass band, a step that barely resolves its period, a
/// record that holds few of its periods. Each names a setting that fits.
pub fn scale_warnings(r: &ImpulseResult) -> Vec<String> {
    let Some(f1) = r.modal.first_bending().map(|m| m.frequency_hz) else {
        return Vec::new();
    };
    let settings = &r.settings;
    let mut w = Vec::new();
    let pass = AntiAlias::default().pass;
    if let Some(rate) = settings.sample_rate {
        if f1 > pass * rate {
            w.push(format!(
                "the first bending mode ({f1:.4e} Hz) lies above the acquisition's pass band ({pass} × the sample rate {rate} Hz): the anti-aliasing low-pass takes it out of the record; a sample rate of {:e} Hz or more records it",
                nice_up(1.25 * f1 / pass)
            ));
        }
    }
    let period = 1.0 / f1;
    let h = settings.transient.step;
    if h * MIN_STEPS_PER_PERIOD > period {
        w.push(format!(
            "the step {h:e} s takes {:.1} steps per period of the first bending mode ({f1:.4e} Hz), fewer than {MIN_STEPS_PER_PERIOD}: the integrator's numerical damping takes the mode; a step of {:e} s (100 per period) resolves it",
            period / h,
            nice_down(period / 100.0)
        ));
    }
    let end = settings.transient.end_time;
    if end < MIN_PERIODS * period {
        w.push(format!(
            "the record lasts {end:e} s, {:.1} periods of the first bending mode ({f1:.4e} Hz), fewer than {MIN_PERIODS}: its spectral lines are {:.3e} Hz apart; an end time of {:e} s ({} periods) resolves the mode's peak",
            end / period,
            1.0 / end,
            nice_up(100.0 * period),
            100
        ));
    }
    w
}

/// The smallest of 1, 2, 5 × 10ᵏ at or above `x` (> 0).
fn nice_up(x: f64) -> f64 {
    let decade = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * decade)
        .find(|&v| v >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * decade)
}

/// The largest of 1, 2, 5 × 10ᵏ at or below `x` (> 0).
fn nice_down(x: f64) -> f64 {
    let decade = 10f64.powf(x.log10().floor());
    [5.0, 2.0, 1.0]
        .iter()
        .map(|m| m * decade)
        .find(|&v| v <= x * (1.0 + 1e-12))
        .unwrap_or(decade)
}

/// The experiment's first bending frequency in the model's `reference`
/// [Hz].
fn reference_hz(model: &Model) -> Option<f64> {
    model.reference.as_ref().map(|r| r.first_bending_hz)
}

/// Whether an error of the experiment is its input's (a model without a
/// sensor or hammer, settings it cannot run with) rather than a failed
/// run.
pub fn is_input(e: &ImpulseError) -> bool {
    !matches!(
        e,
        ImpulseError::Transient(_)
            | ImpulseError::Analysis(_)
            | ImpulseError::Spectrum(_)
            | ImpulseError::Dispersion(_)
    )
}

impl ImpulseRun {
    /// The command line's report.
    pub fn text(&self) -> String {
        impulse_table(&self.model.name, &self.result, reference_hz(&self.model))
    }

    /// The records as CSV (`--csv`): time [s], the sensor, the force [N].
    pub fn signal_csv(&self) -> String {
        signal_csv(&self.result)
    }

    /// The amplitude spectrum as CSV (beside `--csv`'s file): frequency
    /// [Hz], magnitude, dB.
    pub fn spectrum_csv(&self) -> String {
        spectrum_csv(&self.result)
    }

    /// The records as UFF 58 (`--uff`), stamped with the model's hash.
    pub fn uff(&self) -> String {
        let sha = self.document.model_sha256.as_deref().unwrap_or_default();
        let provenance = crate::results::provenance::header_lines(sha);
        let r = &self.result;
        time_records_uff(
            &r.time,
            &r.force,
            &r.signal,
            &r.sensor,
            r.quantity,
            &provenance,
        )
    }

    /// Writes the records to `path` and the spectrum beside it
    /// ([`spectrum_path`]), as `--csv`.
    pub fn write_csv(&self, path: &Path) -> Result<(), CommandError> {
        crate::output::files::write_atomic(path, self.signal_csv().as_bytes())?;
        crate::output::files::write_atomic(&spectrum_path(path), self.spectrum_csv().as_bytes())?;
        Ok(())
    }

    /// Draws the spectrum to `path` (.svg or .png) and the response beside
    /// it ([`response_path`]), as `--plot`.
    pub fn write_plot(&self, path: &Path) -> Result<(), CommandError> {
        write_impulse_figures(
            &self.model,
            &self.result,
            path,
            &response_path(path),
            PlotSize::default(),
        )?;
        Ok(())
    }
}

/// `--csv F` → the spectrum's file beside it, `F`'s stem +
/// `.spectrum.csv`.
pub fn spectrum_path(csv: &Path) -> PathBuf {
    let stem = csv
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    csv.with_file_name(format!("{stem}.spectrum.csv"))
}
