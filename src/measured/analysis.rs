//! The `frf` pipeline as one call: measurement files → averaged H1, H2 and
//! coherence (or an FRF read as such) → the band the hammer excited → the
//! modal fit ([`super::fit`]) of the chosen estimator.
//!
//! Default band: from the second bin to the lower of 0.8 × Nyquist (where
//! acquisition anti-aliasing filters start to act) and the highest
//! frequency at which the mean force spectrum is within 20 dB of its
//! maximum (beyond it the hammer puts no energy in and H is noise).

use std::path::PathBuf;

use realfft::num_complex::Complex64;

use super::fit::{fit, FitSettings, ModalFit};
use super::frf::{estimate, FrfEstimate};
use super::window::Window;
use super::{MeasuredError, Measurement};

/// Which estimator the fit uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Estimator {
    /// G_fx/G_ff: unbiased by response noise (the usual choice).
    #[default]
    H1,
    /// G_xx/G_xf: unbiased by force noise, better at resonances when
    /// leakage or force noise dominates.
    H2,
}

impl Estimator {
    pub fn name(self) -> &'static str {
        match self {
            Estimator::H1 => "h1",
            Estimator::H2 => "h2",
        }
    }
}

/// Settings of [`analyse`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnalysisSettings {
    pub window: Window,
    pub estimator: Estimator,
    /// Fit band, Hz; `None` picks it (module doc).
    pub band: Option<(f64, f64)>,
    /// Highest LSCF order.
    pub max_order: usize,
}

impl Default for AnalysisSettings {
    fn default() -> Self {
        AnalysisSettings {
            window: Window::Rectangular,
            estimator: Estimator::H1,
            band: None,
            max_order: 40,
        }
    }
}

/// Force level (dB below its maximum) that bounds the default band.
pub const FORCE_BAND_DB: f64 = 20.0;

/// The result of [`analyse`].
#[derive(Debug, Clone)]
pub struct FrfAnalysis {
    pub files: Vec<PathBuf>,
    pub frequency_hz: Vec<f64>,
    pub h1: Vec<Complex64>,
    /// H2 and the coherence exist for time records (and the coherence for
    /// a UFF FRF that carries one).
    pub h2: Option<Vec<Complex64>>,
    pub coherence: Option<Vec<f64>>,
    /// The spectral estimate (time records only).
    pub estimate: Option<FrfEstimate>,
    pub settings: AnalysisSettings,
    pub band: (f64, f64),
    pub fit: ModalFit,
}

impl FrfAnalysis {
    /// The estimator the fit used.
    pub fn fitted_frf(&self) -> &[Complex64] {
        match (self.settings.estimator, &self.h2) {
            (Estimator::H2, Some(h2)) => h2,
            _ => &self.h1,
        }
    }
}

fn default_band(frequency_hz: &[f64], force_power: Option<&[f64]>) -> (f64, f64) {
    let n = frequency_hz.len();
    let lo = frequency_hz.get(1).copied().unwrap_or(0.0);
    let top = frequency_hz[n - 1];
    let mut hi = 0.8 * top;
    if let Some(g) = force_power {
        let max = g.iter().cloned().fold(0.0, f64::max);
        let floor = max * 10f64.powf(-FORCE_BAND_DB / 10.0);
        if let Some(k) = g.iter().rposition(|v| *v >= floor) {
            hi = hi.min(frequency_hz[k]);
        }
    }
    (lo, hi.max(lo))
}

/// Runs the pipeline on the measurements of one test (several hits, or
/// one FRF).
///
/// # Panics
/// If `measurements` is empty.
pub fn analyse(
    measurements: Vec<Measurement>,
    settings: AnalysisSettings,
) -> Result<FrfAnalysis, MeasuredError> {
    assert!(!measurements.is_empty(), "analyse needs a measurement");
    let files: Vec<PathBuf> = measurements
        .iter()
        .map(|m| match m {
            Measurement::Time(r) => r.file.clone(),
            Measurement::Frf(f) => f.file.clone(),
        })
        .collect();
    let (frequency_hz, h1, h2, coherence, est) =
        if measurements.len() == 1 && matches!(measurements[0], Measurement::Frf(_)) {
            let Some(Measurement::Frf(f)) = measurements.into_iter().next() else {
                unreachable!("checked above")
            };
            (f.frequency_hz, f.h, None, f.coherence, None)
        } else {
            let mut records = Vec::with_capacity(measurements.len());
            for m in measurements {
                match m {
                    Measurement::Time(r) => records.push(r),
                    Measurement::Frf(f) => return Err(MeasuredError::MixedKinds { file: f.file }),
                }
            }
            let e = estimate(&records, settings.window)?;
            (
                e.frequency_hz.clone(),
                e.h1.clone(),
                Some(e.h2.clone()),
                Some(e.coherence.clone()),
                Some(e),
            )
        };
    let band = settings.band.unwrap_or_else(|| {
        default_band(
            &frequency_hz,
            est.as_ref().map(|e| e.force_power.as_slice()),
        )
    });
    let h = match (settings.estimator, &h2) {
        (Estimator::H2, Some(h2)) => h2,
        _ => &h1,
    };
    let fit = fit(
        &frequency_hz,
        h,
        &FitSettings {
            f_lo: band.0,
            f_hi: band.1,
            max_order: settings.max_order,
            window_decay_rate: est.as_ref().map_or(0.0, |e| e.window_decay_rate),
        },
    );
    Ok(FrfAnalysis {
        files,
        frequency_hz,
        h1,
        h2,
        coherence,
        estimate: est,
        settings,
        band,
        fit,
    })
}
