//! The paper's time-domain frequency test (Section 2.2, Eq. 14): a
//! half-sine force F(t) = F₀ sin(πt/t_F), t ≤ t_F, on the free assembly,
//! integrated to the end time; a vibrometer-like sensor sampled on a uniform
//! grid (51.2 kHz by default, the paper's acquisition rate); its spectrum;
//! the first bending peak, matched to the eigenvalue result.
//!
//! The FFT sees the integrator's numerical frequency, not the continuous
//! one: generalized-α lengthens periods by ≈ (ωh)²/12 (7e-5 at 4.6 kHz and
//! h = 1 µs). The identified peak is corrected by inverting the scheme's
//! exact numerical frequency of a linear oscillator
//! ([`super::dispersion::GenAlpha::true_frequency_from_observed`]); both
//! the raw and the corrected values are reported.
//!
//! **The hammer** is the model's half-sine loads (all of them; the force
//! record is the sum of their magnitudes, and `amplitude`/`duration`
//! override theirs). A model without one is excited by its step loads, and
//! the result says so ([`Excitation::Step`]); a model with neither is an
//! error that names its other time-varying loads: a released preload is
//! not a hammer blow. Every load still acts as the model says (constant,
//! stepped or released); only the force record is the excitation's.
//!
//! **Pre-stress.** The blow strikes the assembly at rest in the static
//! equilibrium under the loads at t = 0⁻ (a string's tension, a spring's
//! preload, gravity: [`crate::analysis::statics::start`]), and the
//! eigenvalues it is compared with are the linearization there, as
//! `modal --prestress` computes them; at the reference only when it
//! balances those loads or [`Start::Reference`] asks for it.
//!
//! The sensor is read at every step and, with a sample rate, resampled
//! behind an anti-aliasing low-pass (band-limited interpolation,
//! [`crate::signal::resample`]), as an acquisition system filters before
//! it samples: the modes above the Nyquist frequency (29.3 and 30.6 kHz of
//! the paper's assembly at 51.2 kHz) do not fold into the spectrum.

pub mod damping;
pub mod sensor;
pub mod sight;

use super::modal::{modal_at_reference, ModalResult, ModalSettings};
use super::statics::prestress::modal_at_equilibrium;
use super::statics::start::{starting_equilibrium, Start};
use super::transient::dispersion::{DispersionError, GenAlpha};
use super::transient::{rayleigh, Integrator, RunStats, State, TransientSettings};
use crate::error::{AnalysisError, InvalidModel, TransientError};
use crate::model::{Model, SensorQuantity, TimeFunction, ValidModel};
use crate::signal::frf::{frf_h1, Frf};
use crate::signal::resample::{pre_trigger, resample_from_rest, AntiAlias};
use crate::signal::spectrum::{
    self, Peak, PeakSettings, Spectrum, SpectrumError, SpectrumSettings,
};
use crate::system::System;
use damping::{identify_damping, DampingBand, DampingCheck};
use sensor::SensorProbe;
use sight::Sight;
use std::f64::consts::PI;

/// Why the impulse experiment failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ImpulseError {
    #[error(transparent)]
    Transient(#[from] TransientError),
    #[error(transparent)]
    Analysis(#[from] AnalysisError),
    #[error("spectrum")]
    Spectrum(#[from] SpectrumError),
    #[error("integrator correction")]
    Dispersion(#[from] DispersionError),
    #[error("the model has no sensor to record (add one under `sensors`)")]
    NoSensor,
    #[error("the model has no sensor `{id}` (its sensors: {available})")]
    UnknownSensor {
        id: String,
        available: crate::error::Ids,
    },
    #[error(
        "the model has no time-varying load to excite it (add a `half_sine` load: the hammer)"
    )]
    NoExcitation,
    #[error("the model has no half-sine load to act as the hammer (nor a step load); its time-varying loads ({others}) are releases, not a hammer blow (add a load with \"time\": {{\"half_sine\": {{\"duration\": …}}}}, or simulate the release as a transient)")]
    NoHammer { others: crate::error::Ids },
    #[error("a pulse amplitude or duration applies to half-sine loads, and the model has none (it is excited by its step loads {loads})")]
    NoPulseToOverride { loads: crate::error::Ids },
    #[error("the pulse amplitude must be finite and non-zero, got {value} N")]
    InvalidAmplitude { value: f64 },
    #[error("sample rate {rate} Hz must be positive and at most 1/step = {} Hz", 1.0 / .step)]
    SampleRateTooHigh { rate: f64, step: f64 },
    #[error(
        "the pulse lasts {duration} s, shorter than two steps of {step} s: it cannot be resolved"
    )]
    PulseTooShort { duration: f64, step: f64 },
    /// The model with the pulse amplitude and duration of the settings
    /// fails validation.
    #[error("the model with the pulse overrides")]
    Overrides(#[source] Box<InvalidModel>),
}

/// Which loads excite the experiment (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Excitation {
    /// The half-sine loads: the hammer.
    HalfSine,
    /// The step loads, for a model without a half-sine load.
    Step,
}

impl Excitation {
    fn matches(self, time: &TimeFunction) -> bool {
        match self {
            Excitation::HalfSine => matches!(time, TimeFunction::HalfSine { .. }),
            Excitation::Step => matches!(time, TimeFunction::Step { .. }),
        }
    }
}

/// The excitation of `model` and its loads' names (id, or `loads[i]`).
pub fn excitation(model: &Model) -> Result<(Excitation, Vec<String>), ImpulseError> {
    let name = |i: usize| {
        model.loads[i]
            .id
            .clone()
            .unwrap_or_else(|| format!("loads[{i}]"))
    };
    let of = |kind: Excitation| -> Vec<String> {
        (0..model.loads.len())
            .filter(|&i| kind.matches(&model.loads[i].time))
            .map(name)
            .collect()
    };
    for kind in [Excitation::HalfSine, Excitation::Step] {
        let loads = of(kind);
        if !loads.is_empty() {
            return Ok((kind, loads));
        }
    }
    let others: Vec<String> = (0..model.loads.len())
        .filter(|&i| !matches!(model.loads[i].time, TimeFunction::Constant))
        .map(name)
        .collect();
    if others.is_empty() {
        Err(ImpulseError::NoExcitation)
    } else {
        Err(ImpulseError::NoHammer {
            others: crate::error::Ids(others),
        })
    }
}

/// The paper's acquisition rate [SI: Hz]: the sensor's default sampling
/// rate here and `transient`'s default output rate.
pub const ACQUISITION_RATE_HZ: f64 = 51_200.0;

/// Settings of the impulse experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct ImpulseSettings {
    pub transient: TransientSettings,
    /// The state struck at rest: the static equilibrium under the loads at
    /// t = 0⁻ (the reference when it balances them) or the reference
    /// ([`crate::analysis::statics::start`]).
    pub start: Start,
    /// Override of the pulse amplitude F₀ [SI: N] (all half-sine loads).
    pub amplitude: Option<f64>,
    /// Override of the pulse duration t_F [SI: s] (all half-sine loads).
    pub duration: Option<f64>,
    /// Sampling rate [SI: Hz]; `None` records every step.
    pub sample_rate: Option<f64>,
    /// Sensor id; `None` = the model's first sensor.
    pub sensor: Option<String>,
    pub spectrum: SpectrumSettings,
    pub peaks: PeakSettings,
}

impl Default for ImpulseSettings {
    fn default() -> Self {
        ImpulseSettings {
            transient: TransientSettings::default(),
            start: Start::default(),
            amplitude: None,
            duration: None,
            sample_rate: Some(ACQUISITION_RATE_HZ),
            sensor: None,
            spectrum: SpectrumSettings::default(),
            peaks: PeakSettings::default(),
        }
    }
}

/// The first bending frequency, three ways.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FirstBending {
    /// Interpolated FFT peak [SI: Hz].
    pub raw_hz: f64,
    /// Peak corrected for the integrator's frequency error [SI: Hz].
    pub corrected_hz: f64,
    /// Eigenvalue result at the state struck (the reference, or the
    /// static equilibrium the run started from) [SI: Hz].
    pub eigen_hz: f64,
}

impl FirstBending {
    /// (raw − eigen)/eigen.
    pub fn raw_error(&self) -> f64 {
        (self.raw_hz - self.eigen_hz) / self.eigen_hz
    }
    /// (corrected − eigen)/eigen.
    pub fn corrected_error(&self) -> f64 {
        (self.corrected_hz - self.eigen_hz) / self.eigen_hz
    }
}

/// Everything the experiment produced.
#[derive(Debug, Clone)]
pub struct ImpulseResult {
    /// What excited the model, and the loads (the hammer: half-sine).
    pub excitation: Excitation,
    pub excitation_loads: Vec<String>,
    pub sensor: String,
    pub quantity: SensorQuantity,
    /// Sample times [SI: s] and sensor values [SI: m, m/s or m/s²].
    pub time: Vec<f64>,
    pub signal: Vec<f64>,
    /// Magnitude of the applied pulse at the sample times [SI: N].
    pub force: Vec<f64>,
    pub sample_rate_hz: f64,
    pub spectrum: Spectrum,
    pub peaks: Vec<Peak>,
    pub first_bending: Option<FirstBending>,
    /// The first bending mode's damping fitted from the records against
    /// the model's (see [`damping`]).
    pub damping: Option<DampingCheck>,
    pub frf: Option<Frf>,
    /// The modes at the state struck.
    pub modal: ModalResult,
    /// The sensor's sight of the first bending mode ([`sight`]); `None`
    /// without a bending mode. A blind sensor identifies no first bending
    /// frequency.
    pub sight: Option<Sight>,
    /// Static iterations of the equilibrium the run started from; `None`
    /// when it started at the reference.
    pub equilibrium_iterations: Option<usize>,
    /// The integrator's counters; no energy books (the dissipations are 0:
    /// the experiment reports no energy balance, `transient` does).
    pub stats: RunStats,
    pub settings: ImpulseSettings,
}

impl ImpulseResult {
    /// When the record cannot show the first bending mode ([`sight`]):
    /// the sentence that says so (the sensor does not see it, or the
    /// hammer does not excite it), and where a sensor or a blow would.
    pub fn blind_sentence(&self) -> Option<String> {
        let sight = self.sight.as_ref().filter(|s| s.blind())?;
        let mode = self.modal.first_bending()?;
        let [dx, dy] = sight.best_direction;
        let (what, fraction, place) = if sight.sensor_blind() {
            (
                format!("the sensor `{}` does not see", self.sensor),
                format!("it reads {:.1e} of the mode's largest motion", sight.ratio),
                "a sensor there would see it",
            )
        } else {
            (
                format!(
                    "the hammer (load {}) does not excite",
                    (self.excitation_loads.iter())
                        .map(|l| format!("`{l}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                format!(
                    "its force does {:.1e} of its work on the mode's largest motion",
                    sight.reach
                ),
                "a blow there would excite it",
            )
        };
        Some(format!(
            "{what} the first bending mode ({:.3} Hz): {fraction}, so no first bending frequency is identified; {} moves most, along ({dx:.3}, {dy:.3}): {place}",
            mode.frequency_hz, sight.best_point
        ))
    }
}

/// Apply the command-line overrides to the model's pulse loads.
fn with_overrides(model: &Model, s: &ImpulseSettings) -> Result<Model, ImpulseError> {
    let mut m = model.clone();
    for load in m.loads.iter_mut() {
        if let TimeFunction::HalfSine { duration } = &mut load.time {
            if let Some(d) = s.duration {
                *duration = d;
            }
            if let Some(f0) = s.amplitude {
                let norm = load.force[0].hypot(load.force[1]);
                load.force = if norm > 0.0 {
                    [load.force[0] * f0 / norm, load.force[1] * f0 / norm]
                } else {
                    [0.0, f0]
                };
            }
        }
    }
    if let Some(f0) = s.amplitude {
        if !(f0.is_finite() && f0 != 0.0) {
            return Err(ImpulseError::InvalidAmplitude { value: f0 });
        }
    }
    let (kind, loads) = excitation(&m)?;
    if (s.amplitude.is_some() || s.duration.is_some()) && kind != Excitation::HalfSine {
        return Err(ImpulseError::NoPulseToOverride {
            loads: crate::error::Ids(loads),
        });
    }
    Ok(m)
}

fn check_settings(model: &Model, s: &ImpulseSettings) -> Result<(), ImpulseError> {
    s.transient.validate()?;
    let h = s.transient.step;
    if let Some(rate) = s.sample_rate {
        if !(rate > 0.0 && rate.is_finite()) || rate > 1.0 / h * (1.0 + 1e-12) {
            return Err(ImpulseError::SampleRateTooHigh { rate, step: h });
        }
    }
    for l in &model.loads {
        if let TimeFunction::HalfSine { duration } = l.time {
            if duration < 2.0 * h {
                return Err(ImpulseError::PulseTooShort { duration, step: h });
            }
        }
    }
    Ok(())
}

/// Run the experiment; `progress` receives the fraction of steps done.
pub fn run_impulse(
    model: &ValidModel,
    settings: &ImpulseSettings,
    progress: &mut dyn FnMut(f64),
) -> Result<ImpulseResult, ImpulseError> {
    let changed = with_overrides(model, settings)?;
    check_settings(&changed, settings)?;
    // Validated again only when the overrides changed it.
    let overridden;
    let model = if changed == **model {
        model
    } else {
        overridden = (changed.validated()).map_err(|e| ImpulseError::Overrides(Box::new(e)))?;
        &overridden
    };
    let unreleased = System::new(model);
    let equilibrium = starting_equilibrium(&unreleased, settings.start)?;
    // The modes of the state struck: where the run starts, with the
    // supports it released still holding (the linearization `modal
    // --prestress` takes).
    let modal = match &equilibrium {
        Some(eq) => modal_at_equilibrium(&unreleased, eq, &ModalSettings::default())?,
        None => modal_at_reference(&unreleased, &ModalSettings::default())?,
    };
    let system = match &equilibrium {
        Some(eq) => unreleased.release_supports(&eq.q, &eq.lambda),
        None => unreleased,
    };
    let point = match &settings.sensor {
        Some(id) => system.sensors.iter().find(|s| &s.id == id).ok_or_else(|| {
            ImpulseError::UnknownSensor {
                id: id.clone(),
                available: crate::error::Ids::of(system.sensors.iter().map(|s| &s.id)),
            }
        })?,
        None => system.sensors.first().ok_or(ImpulseError::NoSensor)?,
    };
    let probe = SensorProbe::new(&system, point);
    let struck = equilibrium.as_ref().map_or(&system.q0, |eq| &eq.q);
    let (kind, excitation_loads) = excitation(model)?;
    let hammer: Vec<&crate::mechanics::load::PointLoad> = (system.loads.iter())
        .filter(|l| kind.matches(&l.time))
        .collect();
    let sight = modal
        .first_bending()
        .map(|m| sight::sight(&system, &probe, &hammer, struck, &m.shape));
    let h = settings.transient.step;
    let transient = TransientSettings {
        damping: settings.transient.damping.or(model.damping),
        ..settings.transient
    };
    // The experiment reports no energy balance.
    let mut integrator = Integrator::new(&system, transient)?.without_energy_books();
    let mut state = match &equilibrium {
        Some(eq) => integrator.state_after_release(eq.q.clone(), vec![0.0; system.ndof()])?,
        None => integrator.initial_state()?,
    };
    let total = settings.transient.steps();
    let mut recorder = Recorder::new(&probe, settings.sample_rate, &settings.transient);
    let mut done = 0usize;
    let stats = integrator.run(&mut state, |st| {
        recorder.record(st);
        done += 1;
        if done.is_multiple_of((total / 100).max(1)) {
            progress(done as f64 / total as f64);
        }
    })?;
    let (time, signal, force) = recorder.finish(|t| pulse_magnitude(&system, kind, t));
    let sample_rate_hz = settings.sample_rate.unwrap_or(1.0 / h);
    let spectrum = spectrum::amplitude_spectrum(&signal, sample_rate_hz, &settings.spectrum)?;
    let peaks = spectrum::find_peaks(&spectrum, &peak_settings(&modal, &settings.peaks));
    let first_bending = match &sight {
        Some(s) if s.blind() => None,
        _ => identify_first_bending(&modal, &spectrum, settings)?,
    };
    let damping = damping_band(&system, &modal, &transient)?
        .and_then(|band| identify_damping(&force, &signal, sample_rate_hz, &band));
    let frf = frf_h1(&force, &signal, sample_rate_hz, &settings.spectrum).ok();
    Ok(ImpulseResult {
        excitation: kind,
        excitation_loads,
        sensor: probe.id().to_string(),
        quantity: probe.point.quantity,
        time,
        signal,
        force,
        sample_rate_hz,
        spectrum,
        peaks,
        first_bending,
        damping,
        frf,
        modal,
        sight,
        equilibrium_iterations: equilibrium.map(|eq| eq.iterations),
        stats,
        settings: settings.clone(),
    })
}

/// Sum of the magnitudes of the excitation's loads at t [SI: N].
fn pulse_magnitude(system: &System, kind: Excitation, t: f64) -> f64 {
    system
        .loads
        .iter()
        .filter(|l| kind.matches(&l.time))
        .map(|l| l.force_at(t).norm())
        .sum()
}

/// `settings` with the search starting no lower than half the lowest
/// elastic eigenfrequency [SI: Hz]: below it a record holds only the rigid
/// motion's leakage, whatever the structure's scale (a 2 Hz diving board
/// and a 4.6 kHz contact alike), and the threshold is relative to the
/// largest magnitude above it.
fn peak_settings(modal: &ModalResult, settings: &PeakSettings) -> PeakSettings {
    let lowest = modal
        .modes
        .iter()
        .filter(|m| !m.kind.is_zero())
        .map(|m| m.frequency_hz)
        .fold(f64::INFINITY, f64::min);
    let from_modes = if lowest.is_finite() {
        0.5 * lowest
    } else {
        0.0
    };
    PeakSettings {
        min_frequency_hz: settings.min_frequency_hz.max(from_modes),
        ..*settings
    }
}

/// The first bending eigenfrequency and its band, half-way to its elastic
/// neighbours [SI: Hz].
pub fn first_bending_band(modal: &ModalResult) -> Option<(f64, f64, f64)> {
    let elastic: Vec<f64> = modal
        .modes
        .iter()
        .filter(|m| !m.kind.is_zero())
        .map(|m| m.frequency_hz)
        .collect();
    let eigen = modal.first_bending()?.frequency_hz;
    let k = elastic.iter().position(|&f| f == eigen).unwrap_or(0);
    let lo = if k == 0 {
        0.5 * eigen
    } else {
        0.5 * (elastic[k - 1] + eigen)
    };
    let hi = elastic
        .get(k + 1)
        .map_or(1.5 * eigen, |f| 0.5 * (f + eigen));
    Some((eigen, lo, hi))
}

/// The band and the expected ratios of the damping check.
fn damping_band(
    system: &System,
    modal: &ModalResult,
    transient: &TransientSettings,
) -> Result<Option<DampingBand>, ImpulseError> {
    let Some((eigen_hz, lo_hz, hi_hz)) = first_bending_band(modal) else {
        return Ok(None);
    };
    let omega = 2.0 * PI * eigen_hz;
    // The run damps with C = αM + βK₀, K₀ the reference's stiffness.
    let modal_ratio = match (transient.damping, modal.first_bending()) {
        (Some(d), Some(m)) => {
            rayleigh::mode_ratio(d, &rayleigh::reference_stiffness(system), &m.shape, omega)
        }
        _ => 0.0,
    };
    let numerical = GenAlpha::from_spectral_radius(transient.spectral_radius)?
        .numerical_frequency(omega, transient.step)?;
    let w = damping::BAND_HALF_WIDTH;
    Ok(Some(DampingBand {
        eigen_hz,
        lo_hz: lo_hz.max(eigen_hz * (1.0 - w)),
        hi_hz: hi_hz.min(eigen_hz * (1.0 + w)),
        modal_ratio,
        numerical_ratio: numerical.damping_ratio,
    }))
}

/// The FFT peak in the band of the first bending eigenfrequency (half-way
/// to its elastic neighbours), corrected for the integrator.
fn identify_first_bending(
    modal: &ModalResult,
    spec: &Spectrum,
    s: &ImpulseSettings,
) -> Result<Option<FirstBending>, ImpulseError> {
    let Some((eigen_hz, lo, hi)) = first_bending_band(modal) else {
        return Ok(None);
    };
    let Some(peak) = spectrum::dominant_peak_in(spec, lo, hi) else {
        return Ok(None);
    };
    let coef = GenAlpha::from_spectral_radius(s.transient.spectral_radius)?;
    let corrected = coef
        .true_frequency_from_observed(2.0 * PI * peak.frequency_hz, s.transient.step)?
        / (2.0 * PI);
    Ok(Some(FirstBending {
        raw_hz: peak.frequency_hz,
        corrected_hz: corrected,
        eigen_hz,
    }))
}

/// The sensor read at every integrator step; with a sample rate, resampled
/// at the end behind the anti-aliasing low-pass of
/// [`crate::signal::resample`] (pass band to 0.4 f_s, −90 dB from the
/// new Nyquist frequency f_s/2), as acquisition hardware filters before it
/// samples: modes above f_s/2 leave no folded peak below it. The force
/// passes the same filter, and the record starts a pre-trigger ahead of
/// the blow ([`crate::signal::resample::resample_from_rest`]: 29 samples,
/// t < 0), so the low-pass's ringing ahead of the blow is recorded in
/// both channels and their spectra's ratio is the structure's FRF (cut at
/// t = 0 it had taken 5.7 % off the force's integral at 51.2 kHz and
/// biased a fitted 925 Hz mode's damping by 8 %).
struct Recorder<'p> {
    probe: &'p SensorProbe,
    rate: Option<f64>,
    /// Integrator time step [SI: s].
    step: f64,
    time: Vec<f64>,
    signal: Vec<f64>,
}

impl<'p> Recorder<'p> {
    fn new(probe: &'p SensorProbe, rate: Option<f64>, transient: &TransientSettings) -> Self {
        let capacity = (transient.end_time / transient.step) as usize + 2;
        Recorder {
            probe,
            rate,
            step: transient.step,
            time: Vec::with_capacity(capacity),
            signal: Vec::with_capacity(capacity),
        }
    }

    fn record(&mut self, st: &State) {
        self.time.push(st.t);
        self.signal.push(self.probe.read(st));
    }

    /// Sample times, the (filtered, resampled) sensor signal and force.
    fn finish(self, force: impl Fn(f64) -> f64 + Sync) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let raw_force = || -> Vec<f64> { self.time.iter().map(|&t| force(t)).collect() };
        let Some(rate) = self.rate else {
            let raw_force = raw_force();
            return (self.time, self.signal, raw_force);
        };
        let design = AntiAlias::default();
        let f_in = 1.0 / self.step;
        let t0 = self.time.first().copied().unwrap_or(0.0);
        // At rest before the blow: the sensor holds its first value, the
        // excitation is zero. The two records are filtered side by side.
        let rest = self.signal.first().copied().unwrap_or(0.0);
        let (signal, force) = rayon::join(
            || resample_from_rest(&self.signal, rest, f_in, rate, &design),
            || resample_from_rest(&raw_force(), 0.0, f_in, rate, &design),
        );
        let lead = pre_trigger(&design, rate) as f64;
        let time = (0..signal.len())
            .map(|m| t0 + (m as f64 - lead) / rate)
            .collect();
        (time, signal, force)
    }
}
